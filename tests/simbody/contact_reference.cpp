// Simbody's HuntCrossleyForce on the scenes that contact_test.cpp and
// contact_shapes_test.cpp build in flange with the same numbers
// (contact_scenes.hpp): a ball, then a box (its corners' spheres), each on a
// Free mobilizer thrown onto a HalfSpace on Ground. Writes to the file named
// by its argument, for each scene in turn, "t x y z Qx Qy Qz Qw vx vy vz wx
// wy wz" (flange's FreeMotion state: ω in body axes, the quaternion scalar
// last) every 0.01 s over 1.5 s, integrated with Runge–Kutta–Merson at
// accuracy 1e-12.
//
// Its own C++17 program with no flange header (cmake/flange_simbody.cmake).
#include <Simbody.h>

#include <cstdio>
#include <vector>

#include "contact_scenes.hpp"

using namespace SimTK;
namespace s = contact_scenes;

namespace {

/// One free body with the given spheres (centre in body axes, radius) on
/// the ground y ≤ 0, thrown from (R, r, v, ω in body axes); its trajectory
/// appended to out.
bool run(std::FILE* out, double m, const Vec3& J, const std::vector<std::pair<Vec3, double>>& spheres,
         const Rotation& R0, const Vec3& r0, const Vec3& v0, const Vec3& w0_body) {
  MultibodySystem system;
  SimbodyMatterSubsystem matter(system);
  GeneralForceSubsystem forces(system);
  GeneralContactSubsystem contact(system);
  Force::UniformGravity gravity(forces, matter, Vec3(0, -s::g, 0));
  const Body::Rigid body(MassProperties(m, Vec3(0), Inertia(J)));
  MobilizedBody::Free free(matter.Ground(), Transform(), body, Transform());
  const ContactSetIndex set = contact.createContactSet();
  for (const auto& [c, r] : spheres) contact.addBody(set, free, ContactGeometry::Sphere(r), Transform(c));
  // Simbody's half-space is x > 0 of its frame: turned so that its outward normal is +y.
  contact.addBody(set, matter.updGround(), ContactGeometry::HalfSpace(), Transform(Rotation(-0.5 * Pi, ZAxis), Vec3(0)));
  HuntCrossleyForce hc(forces, contact, set);
  for (int k = 0; k <= int(spheres.size()); ++k)
    hc.setBodyParameters(ContactSurfaceIndex(k), s::stiffness, s::dissipation, s::static_friction, s::dynamic_friction,
                         s::viscous_friction);
  hc.setTransitionVelocity(s::transition_velocity);
  system.realizeTopology();
  State state = system.getDefaultState();
  free.setQToFitTransform(state, Transform(R0, r0));
  free.setUToFitVelocity(state, SpatialVec(R0 * w0_body, v0));
  RungeKuttaMersonIntegrator integ(system);
  integ.setAccuracy(1e-12);
  TimeStepper ts(system, integ);
  ts.initialize(state);
  for (int k = 0; k <= s::samples; ++k) {
    const double t = k * s::dt;
    if (k > 0) ts.stepTo(t);
    const State& now = integ.getState();
    const Vec7 q = free.getQ(now);  // (Qw, Qx, Qy, Qz, x, y, z)
    const Vec6 u = free.getU(now);  // (ω, v) in Ground
    const Rotation R = free.getBodyRotation(now);
    const Vec3 w_body = ~R * Vec3(u[0], u[1], u[2]);
    std::fprintf(out, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", t, q[4],
                 q[5], q[6], q[1], q[2], q[3], q[0], u[3], u[4], u[5], w_body[0], w_body[1], w_body[2]);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: simbody_contact <output file>\n");
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  // The ball.
  run(out, s::m, Vec3(s::J[0], s::J[1], s::J[2]), {{Vec3(0), s::radius}}, Rotation(), Vec3(0, s::y0, 0),
      Vec3(s::vx0, s::vy0, s::vz0), Vec3(s::wx0, 0, s::wz0));
  // The box: its corners' spheres, each corner_radius inside the box's corner.
  std::vector<std::pair<Vec3, double>> corners;
  for (int i = 0; i < 8; ++i) {
    Vec3 c;
    for (int k = 0; k < 3; ++k) c[k] = ((i >> k) & 1 ? 1 : -1) * (s::box_h[k] - s::corner_radius);
    corners.emplace_back(c, s::corner_radius);
  }
  const Rotation R0(s::box_angle, UnitVec3(s::box_axis[0], s::box_axis[1], s::box_axis[2]));
  run(out, s::box_m, Vec3(s::box_J[0], s::box_J[1], s::box_J[2]), corners, R0, Vec3(0, s::box_y0, 0),
      Vec3(s::box_v0[0], s::box_v0[1], s::box_v0[2]), Vec3(s::box_w0[0], s::box_w0[1], s::box_w0[2]));
  return std::fclose(out) == 0 ? 0 : 1;
}
