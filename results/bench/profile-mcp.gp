# Made by `smcbench report`; remake profile-mcp.png and profile-mcp.svg with `gnuplot profile-mcp.gp` in this folder.
# Data: profile-mcp.dat (one block per curve, in the order of the plot command).
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,600 noenhanced font ',10' } else { set terminal png size 1100,600 noenhanced }
set output 'profile-mcp.png'
set logscale x 2
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:35696.2]
set title 'Performance profile, suite mcp'
plot 'profile-mcp.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, 'profile-mcp.dat' index 0 using 1:2 every 8 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, keyentry with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-mcp.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, 'profile-mcp.dat' index 1 using 1:2 every 7 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, keyentry with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'profile-mcp.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, 'profile-mcp.dat' index 2 using 1:2 every 7 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, keyentry with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'profile-mcp.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, 'profile-mcp.dat' index 3 using 1:2 every 8 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto', 'profile-mcp.dat' index 4 using 1:2 with steps lw 2 lc rgb '#000000' dt 3 pt 11 notitle, 'profile-mcp.dat' index 4 using 1:2 every 6 with points lw 2 lc rgb '#000000' dt 3 pt 11 notitle, keyentry with linespoints lw 2 lc rgb '#000000' dt 3 pt 11 title 'siconos-mcp-newton-fb', 'profile-mcp.dat' index 5 using 1:2 with steps lw 2 lc rgb '#0072B2' dt 4 pt 6 notitle, 'profile-mcp.dat' index 5 using 1:2 every 6 with points lw 2 lc rgb '#0072B2' dt 4 pt 6 notitle, keyentry with linespoints lw 2 lc rgb '#0072B2' dt 4 pt 6 title 'siconos-mcp-newton-min'
unset output
set terminal svg size 1100,600 dynamic noenhanced font 'sans,11'
set output 'profile-mcp.svg'
set logscale x 2
set grid
set key outside right top
set format x '%g'
set format y '%g'
set xlabel 'tau (time / best time)'
set ylabel 'fraction of problems'
set yrange [0:1.02]
set xrange [1:35696.2]
set title 'Performance profile, suite mcp'
plot 'profile-mcp.dat' index 0 using 1:2 with steps lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, 'profile-mcp.dat' index 0 using 1:2 every 8 with points lw 2.5 lc rgb '#009E73' dt 1 pt 9 notitle, keyentry with linespoints lw 2.5 lc rgb '#009E73' dt 1 pt 9 title 'newton', 'profile-mcp.dat' index 1 using 1:2 with steps lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, 'profile-mcp.dat' index 1 using 1:2 every 7 with points lw 2.5 lc rgb '#E69F00' dt 1 pt 13 notitle, keyentry with linespoints lw 2.5 lc rgb '#E69F00' dt 1 pt 13 title 'ipopt', 'profile-mcp.dat' index 2 using 1:2 with steps lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, 'profile-mcp.dat' index 2 using 1:2 every 7 with points lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 notitle, keyentry with linespoints lw 2.5 lc rgb '#56B4E9' dt 1 pt 6 title 'newton-min', 'profile-mcp.dat' index 3 using 1:2 with steps lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, 'profile-mcp.dat' index 3 using 1:2 every 8 with points lw 2.5 lc rgb '#0072B2' dt 1 pt 5 notitle, keyentry with linespoints lw 2.5 lc rgb '#0072B2' dt 1 pt 5 title 'auto', 'profile-mcp.dat' index 4 using 1:2 with steps lw 2 lc rgb '#000000' dt 3 pt 11 notitle, 'profile-mcp.dat' index 4 using 1:2 every 6 with points lw 2 lc rgb '#000000' dt 3 pt 11 notitle, keyentry with linespoints lw 2 lc rgb '#000000' dt 3 pt 11 title 'siconos-mcp-newton-fb', 'profile-mcp.dat' index 5 using 1:2 with steps lw 2 lc rgb '#0072B2' dt 4 pt 6 notitle, 'profile-mcp.dat' index 5 using 1:2 every 6 with points lw 2 lc rgb '#0072B2' dt 4 pt 6 notitle, keyentry with linespoints lw 2 lc rgb '#0072B2' dt 4 pt 6 title 'siconos-mcp-newton-min'
unset output
