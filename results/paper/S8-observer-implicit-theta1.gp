# Made by `smcbench simulate --plot`; remake S8-observer-implicit-theta1.png and S8-observer-implicit-theta1.svg with `gnuplot S8-observer-implicit-theta1.gp` in this folder.
# Data: S8-observer-implicit-theta1.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1200,900 noenhanced font ',10' } else { set terminal png size 1200,900 noenhanced }
set output 'S8-observer-implicit-theta1.png'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 2,2 title 'S8 observer, tau = 0.001, h = 0.1, theta = 1'
set xlabel 't'
set title 'state x'
plot for [i=0:3] 'S8-observer-implicit-theta1.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=4:4] 'S8-observer-implicit-theta1.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-3)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=5:5] 'S8-observer-implicit-theta1.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-4)
set title 'phase portrait'
set xlabel 'x1'
set ylabel 'x2'
plot 'S8-observer-implicit-theta1.dat' index 6 using 1:2 with linespoints pt 7 ps 0.4 lw 1 title 'x_k', 'S8-observer-implicit-theta1.dat' index 6 every ::0::0 using 1:2 with points pt 6 ps 2.5 lw 2 title 'x0'
unset multiplot
unset output
set terminal svg size 1200,900 dynamic noenhanced font 'sans,11'
set output 'S8-observer-implicit-theta1.svg'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 2,2 title 'S8 observer, tau = 0.001, h = 0.1, theta = 1'
set xlabel 't'
set title 'state x'
plot for [i=0:3] 'S8-observer-implicit-theta1.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=4:4] 'S8-observer-implicit-theta1.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-3)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=5:5] 'S8-observer-implicit-theta1.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-4)
set title 'phase portrait'
set xlabel 'x1'
set ylabel 'x2'
plot 'S8-observer-implicit-theta1.dat' index 6 using 1:2 with linespoints pt 7 ps 0.4 lw 1 title 'x_k', 'S8-observer-implicit-theta1.dat' index 6 every ::0::0 using 1:2 with points pt 6 ps 2.5 lw 2 title 'x0'
unset multiplot
unset output
