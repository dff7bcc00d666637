# Made by `smcbench simulate --plot`; remake S9-hypomonotone-explicit.png and S9-hypomonotone-explicit.svg with `gnuplot S9-hypomonotone-explicit.gp` in this folder.
# Data: S9-hypomonotone-explicit.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1200,1000 noenhanced font ',10' } else { set terminal png size 1200,1000 noenhanced }
set output 'S9-hypomonotone-explicit.png'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 3,1 title 'S9 hypomonotone, explicit Euler'
set xlabel 't'
set title 'state x'
plot for [i=0:0] 'S9-hypomonotone-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=1:1] 'S9-hypomonotone-explicit.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-0)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=2:2] 'S9-hypomonotone-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-1)
unset multiplot
unset output
set terminal svg size 1200,1000 dynamic noenhanced font 'sans,11'
set output 'S9-hypomonotone-explicit.svg'
set grid
set key outside right top
set format x '%g'
set format y '%g'
set multiplot layout 3,1 title 'S9 hypomonotone, explicit Euler'
set xlabel 't'
set title 'state x'
plot for [i=0:0] 'S9-hypomonotone-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)
set title 'multiplier s (s_k acts on (t_k-1, t_k])'
set yrange [-1.1:1.1]
plot for [i=1:1] 'S9-hypomonotone-explicit.dat' index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-0)
set autoscale y
set title 'sliding variable y = Cx + D'
plot for [i=2:2] 'S9-hypomonotone-explicit.dat' index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-1)
unset multiplot
unset output
