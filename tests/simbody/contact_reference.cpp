// Simbody's HuntCrossleyForce on the scene that contact_test.cpp builds in
// flange with the same numbers (contact_scenes.hpp): a ball on a Free
// mobilizer thrown onto a HalfSpace on Ground. Writes to the file named by
// its argument "t x y z Qx Qy Qz Qw vx vy vz wx wy wz" (flange's FreeMotion
// state: ω in body axes, the quaternion scalar last) every 0.01 s over
// 1.5 s, integrated with Runge–Kutta–Merson at accuracy 1e-12.
//
// Its own C++17 program with no flange header (cmake/flange_simbody.cmake).
#include <Simbody.h>

#include <cstdio>

#include "contact_scenes.hpp"

using namespace SimTK;

int main(int argc, char** argv) {
  namespace s = contact_scenes;
  if (argc != 2) {
    std::fprintf(stderr, "usage: simbody_contact <output file>\n");
    return 2;
  }
  MultibodySystem system;
  SimbodyMatterSubsystem matter(system);
  GeneralForceSubsystem forces(system);
  GeneralContactSubsystem contact(system);
  Force::UniformGravity gravity(forces, matter, Vec3(0, -s::g, 0));
  const Body::Rigid body(MassProperties(s::m, Vec3(0), Inertia(Vec3(s::J[0], s::J[1], s::J[2]))));
  MobilizedBody::Free ball(matter.Ground(), Transform(), body, Transform());
  const ContactSetIndex set = contact.createContactSet();
  contact.addBody(set, ball, ContactGeometry::Sphere(s::radius), Transform());
  // Simbody's half-space is x > 0 of its frame: turned so that its outward normal is +y.
  contact.addBody(set, matter.updGround(), ContactGeometry::HalfSpace(), Transform(Rotation(-0.5 * Pi, ZAxis), Vec3(0)));
  HuntCrossleyForce hc(forces, contact, set);
  for (int k = 0; k < 2; ++k)
    hc.setBodyParameters(ContactSurfaceIndex(k), s::stiffness, s::dissipation, s::static_friction, s::dynamic_friction,
                         s::viscous_friction);
  hc.setTransitionVelocity(s::transition_velocity);
  system.realizeTopology();
  State state = system.getDefaultState();
  ball.setQToFitTranslation(state, Vec3(0, s::y0, 0));
  ball.setUToFitVelocity(state, SpatialVec(Vec3(s::wx0, 0, s::wz0), Vec3(s::vx0, s::vy0, s::vz0)));
  RungeKuttaMersonIntegrator integ(system);
  integ.setAccuracy(1e-12);
  TimeStepper ts(system, integ);
  ts.initialize(state);
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  for (int k = 0; k <= s::samples; ++k) {
    const double t = k * s::dt;
    if (k > 0) ts.stepTo(t);
    const State& now = integ.getState();
    const Vec7 q = ball.getQ(now);  // (Qw, Qx, Qy, Qz, x, y, z)
    const Vec6 u = ball.getU(now);  // (ω, v) in Ground
    const Rotation R = ball.getBodyRotation(now);
    const Vec3 w_body = ~R * Vec3(u[0], u[1], u[2]);
    std::fprintf(out, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", t, q[4],
                 q[5], q[6], q[1], q[2], q[3], q[0], u[3], u[4], u[5], w_body[0], w_body[1], w_body[2]);
  }
  return std::fclose(out) == 0 ? 0 : 1;
}
