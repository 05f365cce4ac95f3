# The four-bar and the slider-crank (examples/fourbar.cpp, examples/slider_crank.cpp):
#   build/examples/fourbar --csv /tmp/fourbar.csv && build/examples/slider_crank --csv /tmp/slider_crank.csv
#   gnuplot -e "fb='/tmp/fourbar.csv'; sc='/tmp/slider_crank.csv'" docs/plot_loops.gp
if (!exists("fb")) fb = "fourbar.csv"
if (!exists("sc")) sc = "slider_crank.csv"
set terminal pngcairo size 1500,460 font "sans,11" noenhanced
set output "docs/loops.png"
set datafile separator ","
set multiplot layout 1,3 title "Closed loops: a motor-driven four-bar (with the force in its cut joint) and a free slider-crank, against their closed forms"
set xlabel "t [s]"
set grid
set ylabel "rocker angle θ4 [rad]"
set key bottom right
plot [0:2] fb using 1:3 with lines lw 2 title "flange", fb using 1:4 every 25 with points pt 6 title "Freudenstein"
set ylabel "motor torque [N m], pivot force [N]"
set key top right
plot [0:2] fb using 1:5 with lines lw 2 title "motor torque", fb using 1:6 with lines lw 2 title "force in the rocker's pivot (cut joint)"
set ylabel "piston x [m]"
set key bottom right
plot [0:0.5] sc using 1:3 with lines lw 2 title "flange", sc using 1:6 every 20 with points pt 6 title "closed form"
