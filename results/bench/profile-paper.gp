# Made by `smcbench report`; remake profile-paper.png and profile-paper.svg with `gnuplot profile-paper.gp` in this folder.
# Data: profile-paper.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'profile-paper.png'
set logscale x 2
set grid
set key outside right top
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:282038]
set title 'Performance profile, suite paper'
plot 'profile-paper.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'lemke', 'profile-paper.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'profile-paper.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-paper.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#CC79A7' dt 1 pt 5 title 'enum', 'profile-paper.dat' index 4 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'profile-paper.dat' index 5 using 1:2 with steps lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'auto', 'profile-paper.dat' index 6 using 1:2 with steps lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-relay-avi', 'profile-paper.dat' index 7 using 1:2 with steps lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-relay-lemke', 'profile-paper.dat' index 8 using 1:2 with steps lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs', 'profile-paper.dat' index 9 using 1:2 with steps lw 2 lc rgb '#E7298A' dt 5 pt 10 title 'siconos-relay-enum', 'profile-paper.dat' index 10 using 1:2 with steps lw 2 lc rgb '#66A61E' dt 2 pt 4 title 'siconos-lcp-lemke', 'profile-paper.dat' index 11 using 1:2 with steps lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'profile-paper.dat' index 12 using 1:2 with steps lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'profile-paper.dat' index 13 using 1:2 with steps lw 2 lc rgb '#666666' dt 5 pt 10 title 'siconos-mlcp-enum', 'profile-paper.dat' index 14 using 1:2 with steps lw 2 lc rgb '#17BECF' dt 2 pt 4 title 'siconos-mlcp-lemke', 'profile-paper.dat' index 15 using 1:2 with steps lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'profile-paper.dat' index 16 using 1:2 with steps lw 2 lc rgb '#9467BD' dt 4 pt 8 title 'siconos-mlcp-direct-enum', 'profile-paper.dat' index 17 using 1:2 with steps lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'profile-paper.dat' index 18 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'newton-sparse-path'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'profile-paper.svg'
set logscale x 2
set grid
set key outside right top
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:282038]
set title 'Performance profile, suite paper'
plot 'profile-paper.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'lemke', 'profile-paper.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'profile-paper.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-paper.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#CC79A7' dt 1 pt 5 title 'enum', 'profile-paper.dat' index 4 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'profile-paper.dat' index 5 using 1:2 with steps lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'auto', 'profile-paper.dat' index 6 using 1:2 with steps lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-relay-avi', 'profile-paper.dat' index 7 using 1:2 with steps lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-relay-lemke', 'profile-paper.dat' index 8 using 1:2 with steps lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs', 'profile-paper.dat' index 9 using 1:2 with steps lw 2 lc rgb '#E7298A' dt 5 pt 10 title 'siconos-relay-enum', 'profile-paper.dat' index 10 using 1:2 with steps lw 2 lc rgb '#66A61E' dt 2 pt 4 title 'siconos-lcp-lemke', 'profile-paper.dat' index 11 using 1:2 with steps lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'profile-paper.dat' index 12 using 1:2 with steps lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'profile-paper.dat' index 13 using 1:2 with steps lw 2 lc rgb '#666666' dt 5 pt 10 title 'siconos-mlcp-enum', 'profile-paper.dat' index 14 using 1:2 with steps lw 2 lc rgb '#17BECF' dt 2 pt 4 title 'siconos-mlcp-lemke', 'profile-paper.dat' index 15 using 1:2 with steps lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'profile-paper.dat' index 16 using 1:2 with steps lw 2 lc rgb '#9467BD' dt 4 pt 8 title 'siconos-mlcp-direct-enum', 'profile-paper.dat' index 17 using 1:2 with steps lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'profile-paper.dat' index 18 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'newton-sparse-path'
unset output
