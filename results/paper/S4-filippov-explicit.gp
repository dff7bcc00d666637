# Made by `smcbench simulate --plot`; remake S4-filippov-explicit.png and S4-filippov-explicit.svg with `gnuplot S4-filippov-explicit.gp` in this folder.
# Data: S4-filippov-explicit.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1200,900 noenhanced font ',10' } else { set terminal png size 1200,900 noenhanced }
set output 'S4-filippov-explicit.png'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 2,2 title 'S4 filippov, explicit Euler, h = 0.002'
set xlabel 't'
set title 'state x'
plot for [i=0:1] 'S4-filippov-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=2:3] 'S4-filippov-explicit.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-1)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=4:5] 'S4-filippov-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-3)
set title 'phase portrait'
set xlabel 'x1'
set ylabel 'x2'
plot 'S4-filippov-explicit.dat' index 6 using 1:2 with linespoints pt 7 ps 0.4 lw 1 title 'x_k', 'S4-filippov-explicit.dat' index 6 every ::0::0 using 1:2 with points pt 6 ps 2.5 lw 2 title 'x0'
unset multiplot
unset output
set terminal svg size 1200,900 dynamic noenhanced font 'sans,11'
set output 'S4-filippov-explicit.svg'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 2,2 title 'S4 filippov, explicit Euler, h = 0.002'
set xlabel 't'
set title 'state x'
plot for [i=0:1] 'S4-filippov-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=2:3] 'S4-filippov-explicit.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-1)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=4:5] 'S4-filippov-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-3)
set title 'phase portrait'
set xlabel 'x1'
set ylabel 'x2'
plot 'S4-filippov-explicit.dat' index 6 using 1:2 with linespoints pt 7 ps 0.4 lw 1 title 'x_k', 'S4-filippov-explicit.dat' index 6 every ::0::0 using 1:2 with points pt 6 ps 2.5 lw 2 title 'x0'
unset multiplot
unset output
