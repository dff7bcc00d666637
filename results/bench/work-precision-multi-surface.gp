# Made by `smcbench report`; remake work-precision-multi-surface.png and work-precision-multi-surface.svg with `gnuplot work-precision-multi-surface.gp` in this folder.
# Data: work-precision-multi-surface.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'work-precision-multi-surface.png'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'trajectory error of x against a finer reference run (max)'
set ylabel 'run time [s]'
set title 'Work-precision (trajectory error of x), multi-surface'
plot 'work-precision-multi-surface.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 4 title 'explicit Euler', 'work-precision-multi-surface.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, auto', 'work-precision-multi-surface.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'implicit, bpp', 'work-precision-multi-surface.dat' index 3 using 1:2 with linespoints lw 2 lc rgb '#D55E00' dt 4 pt 4 title 'implicit, bullet-dantzig', 'work-precision-multi-surface.dat' index 4 using 1:2 with linespoints lw 2 lc rgb '#CC79A7' dt 4 pt 5 title 'implicit, bullet-lemke', 'work-precision-multi-surface.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#009E73' dt 4 pt 7 title 'implicit, bullet-pgs', 'work-precision-multi-surface.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#E69F00' dt 4 pt 9 title 'implicit, dart-dantzig', 'work-precision-multi-surface.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#000000' dt 4 pt 13 title 'implicit, dart-lemke', 'work-precision-multi-surface.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#56B4E9' dt 4 pt 11 title 'implicit, dart-pgs', 'work-precision-multi-surface.dat' index 9 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 11 title 'implicit, enum', 'work-precision-multi-surface.dat' index 10 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'implicit, ipopt', 'work-precision-multi-surface.dat' index 11 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'implicit, lemke', 'work-precision-multi-surface.dat' index 12 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-multi-surface.dat' index 13 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'implicit, newton-min', 'work-precision-multi-surface.dat' index 14 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 5 title 'implicit, psor'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'work-precision-multi-surface.svg'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'trajectory error of x against a finer reference run (max)'
set ylabel 'run time [s]'
set title 'Work-precision (trajectory error of x), multi-surface'
plot 'work-precision-multi-surface.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 4 title 'explicit Euler', 'work-precision-multi-surface.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, auto', 'work-precision-multi-surface.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 4 title 'implicit, bpp', 'work-precision-multi-surface.dat' index 3 using 1:2 with linespoints lw 2 lc rgb '#D55E00' dt 4 pt 4 title 'implicit, bullet-dantzig', 'work-precision-multi-surface.dat' index 4 using 1:2 with linespoints lw 2 lc rgb '#CC79A7' dt 4 pt 5 title 'implicit, bullet-lemke', 'work-precision-multi-surface.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#009E73' dt 4 pt 7 title 'implicit, bullet-pgs', 'work-precision-multi-surface.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#E69F00' dt 4 pt 9 title 'implicit, dart-dantzig', 'work-precision-multi-surface.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#000000' dt 4 pt 13 title 'implicit, dart-lemke', 'work-precision-multi-surface.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#56B4E9' dt 4 pt 11 title 'implicit, dart-pgs', 'work-precision-multi-surface.dat' index 9 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 11 title 'implicit, enum', 'work-precision-multi-surface.dat' index 10 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'implicit, ipopt', 'work-precision-multi-surface.dat' index 11 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 7 title 'implicit, lemke', 'work-precision-multi-surface.dat' index 12 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-multi-surface.dat' index 13 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'implicit, newton-min', 'work-precision-multi-surface.dat' index 14 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 5 title 'implicit, psor'
unset output
