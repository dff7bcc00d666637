# Made by `smcbench report`; remake speed-forward-error-mcp.png and speed-forward-error-mcp.svg with `gnuplot speed-forward-error-mcp.gp` in this folder.
# Data: speed-forward-error-mcp.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'speed-forward-error-mcp.png'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'forward error |z - z*|inf against the nearest reference (1e-17 = exact)'
set ylabel 'time per solve [s]'
set title 'Speed against forward error, MCP suite mcp'
plot 'speed-forward-error-mcp.dat' index 0 using 1:2 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto', 'speed-forward-error-mcp.dat' index 1 using 1:2 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'speed-forward-error-mcp.dat' index 2 using 1:2 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-forward-error-mcp.dat' index 3 using 1:2 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'speed-forward-error-mcp.dat' index 4 using 1:2 with points lw 2 lc rgb '#000000' dt 3 pt 11 title 'siconos-mcp-newton-fb', 'speed-forward-error-mcp.dat' index 5 using 1:2 with points lw 2 lc rgb '#0072B2' dt 4 pt 6 title 'siconos-mcp-newton-min'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'speed-forward-error-mcp.svg'
set logscale xy
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'forward error |z - z*|inf against the nearest reference (1e-17 = exact)'
set ylabel 'time per solve [s]'
set title 'Speed against forward error, MCP suite mcp'
plot 'speed-forward-error-mcp.dat' index 0 using 1:2 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto', 'speed-forward-error-mcp.dat' index 1 using 1:2 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'speed-forward-error-mcp.dat' index 2 using 1:2 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'speed-forward-error-mcp.dat' index 3 using 1:2 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'speed-forward-error-mcp.dat' index 4 using 1:2 with points lw 2 lc rgb '#000000' dt 3 pt 11 title 'siconos-mcp-newton-fb', 'speed-forward-error-mcp.dat' index 5 using 1:2 with points lw 2 lc rgb '#0072B2' dt 4 pt 6 title 'siconos-mcp-newton-min'
unset output
