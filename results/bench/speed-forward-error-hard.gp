# Made by `smcbench report`; remake speed-forward-error-hard.png and speed-forward-error-hard.svg with `gnuplot speed-forward-error-hard.gp` in this folder.
# Data: speed-forward-error-hard.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'speed-forward-error-hard.png'
set logscale xy
set grid
set key outside right top
set xlabel 'forward error |z - z*|inf (median; problems with a unique certified z*)'
set ylabel 'time per solve [s]'
set title 'Speed against forward error, suite hard'
plot 'speed-forward-error-hard.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'auto', 'speed-forward-error-hard.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'speed-forward-error-hard.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-forward-error-hard.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'newton-min', 'speed-forward-error-hard.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'speed-forward-error-hard.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'speed-forward-error-hard.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'speed-forward-error-hard.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-mcp-newton-fb', 'speed-forward-error-hard.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-mcp-newton-min', 'speed-forward-error-hard.dat' index 9 using 1:2 with linespoints lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'speed-forward-error-hard.dat' index 10 using 1:2 with linespoints lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'speed-forward-error-hard.dat' index 11 using 1:2 with linespoints lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'speed-forward-error-hard.svg'
set logscale xy
set grid
set key outside right top
set xlabel 'forward error |z - z*|inf (median; problems with a unique certified z*)'
set ylabel 'time per solve [s]'
set title 'Speed against forward error, suite hard'
plot 'speed-forward-error-hard.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'auto', 'speed-forward-error-hard.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'speed-forward-error-hard.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-forward-error-hard.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'newton-min', 'speed-forward-error-hard.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'speed-forward-error-hard.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'speed-forward-error-hard.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'speed-forward-error-hard.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-mcp-newton-fb', 'speed-forward-error-hard.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-mcp-newton-min', 'speed-forward-error-hard.dat' index 9 using 1:2 with linespoints lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'speed-forward-error-hard.dat' index 10 using 1:2 with linespoints lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'speed-forward-error-hard.dat' index 11 using 1:2 with linespoints lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs'
unset output
