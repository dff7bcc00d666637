# Made by `smcbench simulate --plot`; remake S1-sign-explicit-h0.2.png and S1-sign-explicit-h0.2.svg with `gnuplot S1-sign-explicit-h0.2.gp` in this folder.
# Data: S1-sign-explicit-h0.2.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1200,1000 noenhanced font ',10' } else { set terminal png size 1200,1000 noenhanced }
set output 'S1-sign-explicit-h0.2.png'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 3,1 title 'S1 sign, explicit Euler, h = 0.2'
set xlabel 't'
set title 'state x'
plot for [i=0:0] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=1:1] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-0)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=2:2] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-1)
unset multiplot
unset output
set terminal svg size 1200,1000 dynamic noenhanced font 'sans,11'
set output 'S1-sign-explicit-h0.2.svg'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 3,1 title 'S1 sign, explicit Euler, h = 0.2'
set xlabel 't'
set title 'state x'
plot for [i=0:0] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=1:1] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-0)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=2:2] 'S1-sign-explicit-h0.2.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-1)
unset multiplot
unset output
