# Made by `smcbench report`; remake work-precision-s-sign.png and work-precision-s-sign.svg with `gnuplot work-precision-s-sign.gp` in this folder.
# Data: work-precision-s-sign.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'work-precision-s-sign.png'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'per-step forward error of s against certified solutions (max; 1e-17 = exact)'
set ylabel 'run time [s]'
set title 'Work-precision (per-step forward error of s), sign'
plot 'work-precision-s-sign.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, auto', 'work-precision-s-sign.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'implicit, bpp', 'work-precision-s-sign.dat' index 2 using 1:2 with linespoints lw 2 lc rgb '#D55E00' dt 4 pt 4 title 'implicit, bullet-dantzig', 'work-precision-s-sign.dat' index 3 using 1:2 with linespoints lw 2 lc rgb '#CC79A7' dt 4 pt 5 title 'implicit, bullet-lemke', 'work-precision-s-sign.dat' index 4 using 1:2 with linespoints lw 2 lc rgb '#009E73' dt 4 pt 7 title 'implicit, bullet-pgs', 'work-precision-s-sign.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E69F00' dt 4 pt 9 title 'implicit, dart-dantzig', 'work-precision-s-sign.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#000000' dt 4 pt 13 title 'implicit, dart-lemke', 'work-precision-s-sign.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#56B4E9' dt 4 pt 11 title 'implicit, dart-pgs', 'work-precision-s-sign.dat' index 8 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 11 title 'implicit, enum', 'work-precision-s-sign.dat' index 9 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'implicit, ipopt', 'work-precision-s-sign.dat' index 10 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'implicit, lemke', 'work-precision-s-sign.dat' index 11 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-s-sign.dat' index 12 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'implicit, newton-min', 'work-precision-s-sign.dat' index 13 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 5 title 'implicit, psor'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'work-precision-s-sign.svg'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'per-step forward error of s against certified solutions (max; 1e-17 = exact)'
set ylabel 'run time [s]'
set title 'Work-precision (per-step forward error of s), sign'
plot 'work-precision-s-sign.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, auto', 'work-precision-s-sign.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'implicit, bpp', 'work-precision-s-sign.dat' index 2 using 1:2 with linespoints lw 2 lc rgb '#D55E00' dt 4 pt 4 title 'implicit, bullet-dantzig', 'work-precision-s-sign.dat' index 3 using 1:2 with linespoints lw 2 lc rgb '#CC79A7' dt 4 pt 5 title 'implicit, bullet-lemke', 'work-precision-s-sign.dat' index 4 using 1:2 with linespoints lw 2 lc rgb '#009E73' dt 4 pt 7 title 'implicit, bullet-pgs', 'work-precision-s-sign.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E69F00' dt 4 pt 9 title 'implicit, dart-dantzig', 'work-precision-s-sign.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#000000' dt 4 pt 13 title 'implicit, dart-lemke', 'work-precision-s-sign.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#56B4E9' dt 4 pt 11 title 'implicit, dart-pgs', 'work-precision-s-sign.dat' index 8 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 11 title 'implicit, enum', 'work-precision-s-sign.dat' index 9 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'implicit, ipopt', 'work-precision-s-sign.dat' index 10 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'implicit, lemke', 'work-precision-s-sign.dat' index 11 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-s-sign.dat' index 12 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'implicit, newton-min', 'work-precision-s-sign.dat' index 13 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 5 title 'implicit, psor'
unset output
