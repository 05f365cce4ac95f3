// A rubber ball thrown onto the ground with backspin: it bounces lower each
// time (the contact's dissipation), skids at every landing while friction
// turns its spin around, and ends rolling. The ball is a free body with a
// Contact between its sphere and the ground (forces/contact.hpp, Hunt–Crossley
// with Stribeck friction).
//
//   bouncing_ball                 simulate 3 s, write bouncing_ball.csv, print a summary
//   bouncing_ball --equations     print the equations
//   bouncing_ball --csv FILE      write the trajectory to FILE
//   bouncing_ball --html FILE     also write a page that plays the motion in 3-D
//
// The CSV has t, the centre's x and y, its velocity, the spin ω_z (world),
// the contact's penetration, normal force, friction force and slip speed,
// and the energy (kinetic + potential + the contact's elastic energy).
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>

#include <flange/flange.hpp>
#include <flange/viewer/recording.hpp>

using namespace flange;

int main(int argc, char** argv) {
  const char* csv = "bouncing_ball.csv";
  const char* html = nullptr;
  bool equations = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--equations")) equations = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--html") && i + 1 < argc) html = argv[++i];
    else return std::cerr << "usage: bouncing_ball [--equations] [--csv FILE] [--html FILE]\n", 2;
  }
  // A 0.2 kg rubber ball of radius 5 cm (a hollow sphere: J = (2/3)·m·r²) on
  // a concrete floor, the ground y ≤ 0.
  const double m = 0.2, r = 0.05, J = 2.0 / 3 * m * r * r;
  const contact_material rubber{.stiffness = 5e6, .dissipation = 0.4, .static_friction = 0.9, .dynamic_friction = 0.7};
  const contact_material concrete{.stiffness = 3e7, .dissipation = 0.2, .static_friction = 0.9, .dynamic_friction = 0.7};
  const auto ball = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"ball">({.m = m, .J = Mat3d::Identity() * J}),
                          Contact<"bounce", contact_shape::sphere, contact_shape::half_space>(
                              {.a = {.radius = r}, .b = {.n = {0, 1, 0}}, .material_a = rubber,
                               .material_b = concrete, .transition_velocity = 0.01}),
                          connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "ball.frame_a">,
                          connect<"fly.frame_b", "bounce.frame_a">, connect<"world.frame_b", "bounce.frame_b">);
  using Ball = decltype(ball);
  if (equations) {
    print_equations(ball, std::cout);
    return 0;
  }
  // Thrown from 1 m up at 2 m/s forward, spinning backward at 25 rad/s.
  auto x0 = neutral_state(ball);
  set_joint<"fly">(ball, x0, {.r = Vec3d(0, 1, 0), .v = Vec3d(2, 0, 0), .R = orientation{}, .w = Vec3d(0, 0, 25)});
  const auto run = simulate(ball, x0, output_times(0.0, 3.0, 0.002), {.tolerance = 1e-9});

  std::ofstream out(csv);
  out << "t,x,y,vx,vy,w_z,depth,f_n,f_t,v_s,energy\n";
  out.precision(10);
  viewer::recording page(ball);
  page.plot("height [m]", [](const auto& s) { return s.frame("ball.frame_a").r.y(); })
      .plot("normal force / 100 [N]", [](const auto& s) { return internal<"bounce", "f_n">(s) / 100; });
  int bounces = 0;
  bool touching = false;
  double e_prev = recover(ball, 0.0, x0).energy(), rise = 0, peak_force = 0;
  for (std::size_t k = 0; k < run.size(); ++k) {
    const auto s = recover(ball, run.t[k], run.x[k]);
    page.add(s);
    const auto& f = s.frame("ball.frame_a");
    const Vec3d w = f.R.transpose() * f.w;  // world coordinates
    const double fn = internal<"bounce", "f_n">(s);
    if (fn > 0 && !touching) ++bounces;
    touching = fn > 0;
    peak_force = std::max(peak_force, fn);
    rise = std::max(rise, s.energy() - e_prev);  // the energy only ever falls
    e_prev = s.energy();
    out << s.t << ',' << f.r.x() << ',' << f.r.y() << ',' << f.v.x() << ',' << f.v.y() << ',' << w.z() << ','
        << internal<"bounce", "δ">(s) << ',' << fn << ',' << internal<"bounce", "f_t">(s) << ','
        << internal<"bounce", "v_s">(s) << ',' << s.energy() << '\n';
  }
  const auto end = recover(ball, 3.0, run.x.back());
  const auto& f = end.frame("ball.frame_a");
  const double slip = internal<"bounce", "v_s">(end), w_end = (f.R.transpose() * f.w).z();
  if (html) {
    page.write_html(html, viewer::three_js(), "flange: a bouncing ball");
    std::cout << "wrote " << html << " (" << page.samples() << " samples)\n";
  }
  std::cout << "flange bouncing ball: " << Ball::n_equations << " equations, " << Ball::n_unknowns
            << " unknowns; a Contact between a sphere and the ground\n"
            << "  thrown from 1 m at 2 m/s with 25 rad/s of backspin, 3 s (dopri5, tol 1e-9, " << run.rhs_evals
            << " evaluations)\n"
            << "  " << bounces << " landings, the hardest " << peak_force << " N; the energy rose by at most " << rise
            << " J between samples\n"
            << "  at the end: rolling at " << f.v.x() << " m/s with ω_z = " << w_end << " rad/s, slipping at " << slip
            << " m/s\n"
            << "  largest scaled residual at the end " << scaled_residual(ball, end) << "\n"
            << "  wrote " << csv << "\n";
  // It bounced, lost energy at every step, and ends rolling forward (backspin turned around).
  return bounces >= 3 && rise < 1e-9 && slip < 0.01 && f.v.x() > 0 ? 0 : 1;
}
