# Made by `smcbench report`; remake work-precision-lyapunov.png and work-precision-lyapunov.svg with `gnuplot work-precision-lyapunov.gp` in this folder.
# Data: work-precision-lyapunov.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'work-precision-lyapunov.png'
set logscale xy
set grid
set key outside right top
set xlabel 'trajectory error of x against a finer reference run (max)'
set ylabel 'run time [s]'
set title 'Work-precision (trajectory error of x), lyapunov'
plot 'work-precision-lyapunov.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 7 title 'explicit Euler', 'work-precision-lyapunov.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'implicit, auto', 'work-precision-lyapunov.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 5 title 'implicit, enum', 'work-precision-lyapunov.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'implicit, ipopt', 'work-precision-lyapunov.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, lemke', 'work-precision-lyapunov.dat' index 5 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-lyapunov.dat' index 6 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'implicit, newton-min', 'work-precision-lyapunov.dat' index 7 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'implicit, psor'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'work-precision-lyapunov.svg'
set logscale xy
set grid
set key outside right top
set xlabel 'trajectory error of x against a finer reference run (max)'
set ylabel 'run time [s]'
set title 'Work-precision (trajectory error of x), lyapunov'
plot 'work-precision-lyapunov.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 7 title 'explicit Euler', 'work-precision-lyapunov.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'implicit, auto', 'work-precision-lyapunov.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#CC79A7' dt 1 pt 5 title 'implicit, enum', 'work-precision-lyapunov.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'implicit, ipopt', 'work-precision-lyapunov.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'implicit, lemke', 'work-precision-lyapunov.dat' index 5 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'implicit, newton', 'work-precision-lyapunov.dat' index 6 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'implicit, newton-min', 'work-precision-lyapunov.dat' index 7 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'implicit, psor'
unset output
