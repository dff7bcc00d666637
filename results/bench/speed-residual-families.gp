# Made by `smcbench report`; remake speed-residual-families.png and speed-residual-families.svg with `gnuplot speed-residual-families.gp` in this folder.
# Data: speed-residual-families.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'speed-residual-families.png'
set logscale xy
set grid
set key outside right top
set xlabel 'achieved relative natural residual (median)'
set ylabel 'time per solve [s]'
set title 'Speed against residual, suite families'
plot 'speed-residual-families.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'auto', 'speed-residual-families.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'speed-residual-families.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-residual-families.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'newton-min', 'speed-residual-families.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'speed-residual-families.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'speed-residual-families.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'speed-residual-families.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-mcp-newton-fb', 'speed-residual-families.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-mcp-newton-min', 'speed-residual-families.dat' index 9 using 1:2 with linespoints lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'speed-residual-families.dat' index 10 using 1:2 with linespoints lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'speed-residual-families.dat' index 11 using 1:2 with linespoints lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'speed-residual-families.svg'
set logscale xy
set grid
set key outside right top
set xlabel 'achieved relative natural residual (median)'
set ylabel 'time per solve [s]'
set title 'Speed against residual, suite families'
plot 'speed-residual-families.dat' index 0 using 1:2 with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 5 title 'auto', 'speed-residual-families.dat' index 1 using 1:2 with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 7 title 'ipopt', 'speed-residual-families.dat' index 2 using 1:2 with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-residual-families.dat' index 3 using 1:2 with linespoints lw 2.5 lc rgb '#000000' dt 1 pt 9 title 'newton-min', 'speed-residual-families.dat' index 4 using 1:2 with linespoints lw 2.5 lc rgb '#D55E00' dt 1 pt 7 title 'psor', 'speed-residual-families.dat' index 5 using 1:2 with linespoints lw 2 lc rgb '#E6AB02' dt 3 pt 6 title 'siconos-lcp-newton-fb', 'speed-residual-families.dat' index 6 using 1:2 with linespoints lw 2 lc rgb '#A6761D' dt 4 pt 8 title 'siconos-lcp-newton-min', 'speed-residual-families.dat' index 7 using 1:2 with linespoints lw 2 lc rgb '#1B9E77' dt 2 pt 4 title 'siconos-mcp-newton-fb', 'speed-residual-families.dat' index 8 using 1:2 with linespoints lw 2 lc rgb '#D95F02' dt 3 pt 6 title 'siconos-mcp-newton-min', 'speed-residual-families.dat' index 9 using 1:2 with linespoints lw 2 lc rgb '#FF7F0E' dt 5 pt 10 title 'siconos-mlcp-direct-fb', 'speed-residual-families.dat' index 10 using 1:2 with linespoints lw 2 lc rgb '#BCBD22' dt 3 pt 6 title 'siconos-mlcp-fb', 'speed-residual-families.dat' index 11 using 1:2 with linespoints lw 2 lc rgb '#7570B3' dt 4 pt 8 title 'siconos-relay-pgs'
unset output
