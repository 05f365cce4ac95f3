# The spatial arm's joints and tool tip (examples/spatial_arm.cpp):
#   build/examples/spatial_arm --csv /tmp/spatial_arm.csv && gnuplot -e "csv='/tmp/spatial_arm.csv'" docs/plot_spatial_arm.gp
if (!exists("csv")) csv = "spatial_arm.csv"
set terminal pngcairo size 1200,460 font "sans,11" noenhanced
set output "docs/spatial_arm.png"
set datafile separator ","
set multiplot layout 1,2 title "A 3-joint spatial arm: PD drives read by joint name, links from their shapes"
set xlabel "t [s]"
set ylabel "joint angle [rad]"
set key bottom right
set grid
plot csv using 1:2 with lines lw 2 title "shoulder (target 1.0)", \
     csv using 1:3 with lines lw 2 title "elbow (target -0.8)", \
     csv using 1:4 with lines lw 2 title "wrist (target 0.4)"
set xlabel "tip x [m]"
set ylabel "tip z [m]"
set size ratio -1
unset key
set title "tool tip (hand.frame_b), seen from the side (x, z)"
plot csv using 5:7 with lines lw 2
unset multiplot
