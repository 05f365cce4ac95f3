# Plots the example trajectories for the README and docs/.
#   build/examples/robot_arm --csv docs/robot_arm.csv
#   build/examples/gantry_crane --csv docs/gantry_crane.csv
#   build/examples/buffered_crane --csv docs/buffered_crane.csv
#   build/examples/spinning_top --csv docs/spinning_top.csv
#   build/examples/tumbling_body --csv docs/tumbling_body.csv
#   build/examples/bouncing_ball --csv docs/bouncing_ball.csv
#   build/examples/quadruped_stand --csv docs/quadruped_stand.csv
#   gnuplot docs/plot_examples.gp        (from the repository root)
set datafile separator ","
set terminal pngcairo size 900,640 font "DejaVu Sans,10" noenhanced
set key autotitle columnhead
set grid

set output "docs/robot_arm.png"
set multiplot layout 3,1 title "flange robot arm: PD swing-up from hanging to 45° above horizontal"
set ylabel "θ [deg]"
plot "docs/robot_arm.csv" using 1:($2*180/pi) with lines lw 2 title "θ (from the downward vertical)", \
     135 with lines dt 2 title "target"
set ylabel "torque [N m]"
plot "docs/robot_arm.csv" using 1:4 with lines lw 2 title "motor M_z", \
     "" using 1:6 with lines lw 1 title "cut torque at rod.frame_a, z (equals M_z: the joint passes no torque about its axis)"
set ylabel "energy [J]"
set xlabel "t [s]"
plot "docs/robot_arm.csv" using 1:5 with lines lw 2 title "kinetic + potential energy"
unset multiplot

set output "docs/gantry_crane.png"
unset xlabel
set multiplot layout 3,1 title "flange gantry crane: cart pushed for 1 s, braked for 1 s, then coasting"
set ylabel "s [m]"
plot "docs/gantry_crane.csv" using 1:2 with lines lw 2 title "cart position s"
set ylabel "θ [deg]"
plot "docs/gantry_crane.csv" using 1:($3*180/pi) with lines lw 2 title "load angle θ"
set ylabel "force [N]"
set xlabel "t [s]"
plot "docs/gantry_crane.csv" using 1:6 with lines lw 2 title "push f", \
     "" using 1:8 with lines lw 1 title "rope tension"
unset multiplot

# build/examples/buffered_crane --csv docs/buffered_crane.csv
set output "docs/buffered_crane.png"
unset xlabel
set multiplot layout 3,1 title "flange buffered crane: a gust on the load, rail friction, a spring-damper buffer"
set ylabel "s [m]"
plot "docs/buffered_crane.csv" using 1:2 with lines lw 2 title "cart position s"
set ylabel "θ [deg]"
plot "docs/buffered_crane.csv" using 1:($3*180/pi) with lines lw 2 title "load angle θ"
set ylabel "force [N]"
set xlabel "t [s]"
plot "docs/buffered_crane.csv" using 1:7 with lines lw 2 title "buffer tension f"
unset multiplot

set output "docs/spinning_top.png"
unset xlabel
set multiplot layout 3,1 title "flange spinning top: released tilted, spinning at 120 rad/s (Spherical joint)"
set ylabel "tilt [deg]"
plot "docs/spinning_top.csv" using 1:($2*180/pi) with lines lw 2 title "tilt of the symmetry axis from the vertical (nutation)"
set ylabel "azimuth [deg]"
plot "docs/spinning_top.csv" using 1:($3*180/pi) with lines lw 2 title "azimuth of the axis (precession)"
set ylabel "change since t = 0"
set xlabel "t [s]"
plot "docs/spinning_top.csv" using 1:($8*1e12) with lines lw 2 title "energy [pJ]", \
     "" using 1:($9*1e14) with lines lw 1 title "angular momentum about the vertical [1e-14 kg m²/s]"
unset multiplot

set output "docs/tumbling_body.png"
unset xlabel
set multiplot layout 2,1 title "flange tumbling body: spun about its intermediate axis, it flips (FreeMotion)"
set ylabel "ω, body axes [rad/s]"
plot "docs/tumbling_body.csv" using 1:2 with lines lw 1 title "ω1 (smallest inertia)", \
     "" using 1:3 with lines lw 2 title "ω2 (intermediate)", \
     "" using 1:4 with lines lw 1 title "ω3 (largest)"
set ylabel "relative change × 1e12"
set xlabel "t [s]"
plot "docs/tumbling_body.csv" using 1:($7*1e12) with lines lw 2 title "kinetic energy", \
     "" using 1:($8*1e12) with lines lw 1 title "angular momentum in the world, |L − L(0)| / |L(0)|"
unset multiplot

set output "docs/bouncing_ball.png"
unset xlabel
set multiplot layout 3,1 title "flange bouncing ball: thrown with backspin onto the ground (Contact: Hunt–Crossley, Stribeck friction)"
set ylabel "height [m]"
plot "docs/bouncing_ball.csv" using 1:3 with lines lw 2 title "centre height y", \
     0.05 with lines dt 2 title "radius (touching)"
set ylabel "[m/s]"
plot "docs/bouncing_ball.csv" using 1:4 with lines lw 2 title "forward speed v_x", \
     "" using 1:(-$6*0.05) with lines lw 1 title "rolling speed −ω_z·r (equal once it rolls)"
set ylabel "energy [J]"
set xlabel "t [s]"
plot "docs/bouncing_ball.csv" using 1:11 with lines lw 2 title "kinetic + potential + contact elastic energy"
unset multiplot

set output "docs/quadruped_stand.png"
unset xlabel
set multiplot layout 2,1 title "flange quadruped: dropped 4 cm in a crouch, stands under one PD law read by joint name"
set ylabel "trunk height [m]"
plot "docs/quadruped_stand.csv" using 1:2 with lines lw 2 title "trunk centre y"
set ylabel "normal force [N]"
set xlabel "t [s]"
plot "docs/quadruped_stand.csv" using 1:3 with lines lw 1 title "foot0 (hip at +x, +z)", \
     "" using 1:4 with lines lw 1 title "foot1 (−x, +z)", \
     "" using 1:5 with lines lw 1 title "foot2 (+x, −z)", \
     "" using 1:6 with lines lw 1 title "foot3 (−x, −z)", \
     "" using 1:($7*42.183) with lines lw 2 dt 2 title "their sum / 4"
unset multiplot
