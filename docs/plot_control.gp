# Plots the LQR balance example for docs/control.md.
#   build/examples/lqr_balance --csv docs/lqr_balance.csv
#   gnuplot docs/plot_control.gp         (from the repository root)
set datafile separator ","
set terminal pngcairo size 900,560 font "DejaVu Sans,10" noenhanced
set key autotitle columnhead
set grid
set output "docs/lqr_balance.png"
set multiplot layout 2,1 title "flange LQR balance: a double inverted pendulum on a cart, caught from 10° off"
set ylabel "angle [deg], position [cm]"
plot "docs/lqr_balance.csv" using 1:($3*180/pi) with lines lw 2 title "lower link φ1 (from upright)", \
     "" using 1:(($3+$4)*180/pi) with lines lw 2 title "upper link φ1 + φ2 (from upright)", \
     "" using 1:($2*100) with lines lw 2 title "cart s [cm]"
set ylabel "force [N]"
set xlabel "t [s]"
plot "docs/lqr_balance.csv" using 1:5 with steps lw 2 title "cart force u = −K·(x − x*), held over 10 ms"
unset multiplot
