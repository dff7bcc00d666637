# Made by `smcbench report`; remake profile-siconos-m65-1024.png and profile-siconos-m65-1024.svg with `gnuplot profile-siconos-m65-1024.gp` in this folder.
# Data: profile-siconos-m65-1024.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'profile-siconos-m65-1024.png'
set logscale x 2
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:1301.59]
set title 'Performance profile, suite siconos m65-1024'
plot 'profile-siconos-m65-1024.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 7 notitle, 'profile-siconos-m65-1024.dat' index 0 using 1:2 every 1 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 7 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'lemke', 'profile-siconos-m65-1024.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, 'profile-siconos-m65-1024.dat' index 1 using 1:2 every 1 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, keyentry with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-siconos-m65-1024.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, 'profile-siconos-m65-1024.dat' index 2 using 1:2 every 1 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, keyentry with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'profile-siconos-m65-1024.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, 'profile-siconos-m65-1024.dat' index 3 using 1:2 every 1 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, keyentry with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'profile-siconos-m65-1024.dat' index 4 using 1:2 with steps lw 2.5 lc rgb '#000000' dt 1 pt 4 notitle, 'profile-siconos-m65-1024.dat' index 4 using 1:2 every 1 with points lw 2.5 lc rgb '#000000' dt 1 pt 4 notitle, keyentry with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'bpp', 'profile-siconos-m65-1024.dat' index 5 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, 'profile-siconos-m65-1024.dat' index 5 using 1:2 every 1 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'profile-siconos-m65-1024.svg'
set logscale x 2
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:1301.59]
set title 'Performance profile, suite siconos m65-1024'
plot 'profile-siconos-m65-1024.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 7 notitle, 'profile-siconos-m65-1024.dat' index 0 using 1:2 every 1 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 7 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'lemke', 'profile-siconos-m65-1024.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, 'profile-siconos-m65-1024.dat' index 1 using 1:2 every 1 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, keyentry with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-siconos-m65-1024.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, 'profile-siconos-m65-1024.dat' index 2 using 1:2 every 1 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, keyentry with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'profile-siconos-m65-1024.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, 'profile-siconos-m65-1024.dat' index 3 using 1:2 every 1 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, keyentry with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'profile-siconos-m65-1024.dat' index 4 using 1:2 with steps lw 2.5 lc rgb '#000000' dt 1 pt 4 notitle, 'profile-siconos-m65-1024.dat' index 4 using 1:2 every 1 with points lw 2.5 lc rgb '#000000' dt 1 pt 4 notitle, keyentry with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'bpp', 'profile-siconos-m65-1024.dat' index 5 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, 'profile-siconos-m65-1024.dat' index 5 using 1:2 every 1 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto'
unset output
