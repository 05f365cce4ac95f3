# Heat maps of the crane sweep (examples/crane_sweep.cpp):
#   build/examples/crane_sweep --csv docs/crane_sweep.csv && gnuplot docs/plot_crane_sweep.gp
# Columns: case,kp,m_load,ok,max_swing,settling_time,final_s,...; rows run
# kp-major, so a blank line is put between kp values for pm3d.
set terminal pngcairo size 1300,520 font "sans,11"
set output "docs/crane_sweep.png"
set datafile separator ","
set multiplot layout 1,2 title "Buffered crane, PD on the cart: 20 × 20 cases, each the same compiled scene"
set view map
set logscale x
set xlabel "kp [N/m]"
set ylabel "load mass [kg]"
set xrange [2:200]
set yrange [0.1:3]
set pm3d map corners2color c1
set palette rgbformulae 33,13,10
data = "< awk -F, 'NR > 1 { if ($2 != last && NR > 2) print \"\"; last = $2; print }' docs/crane_sweep.csv"
set title "largest swing of the load [deg]"
splot data using 2:3:($5 * 180 / pi) with pm3d notitle
set title "time until the swing stays below 0.01 rad [s] (20 = not within the run)"
splot data using 2:3:6 with pm3d notitle
unset multiplot
