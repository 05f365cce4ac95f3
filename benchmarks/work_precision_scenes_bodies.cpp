// The work-precision study's scenes: a free body, the four-bar loop and
// the falling legged robot.
#include <array>
#include <cmath>

#include <flange/models/legged.hpp>
#include <flange/models/linkages.hpp>

#include "work_precision_study.hpp"

namespace work_precision {

void study_bodies(const options& o, std::vector<study::point>& points, std::ostream& refs) {
  {
    // An asymmetric body thrown under gravity on a FreeMotion, its centre of
    // mass off its frame, spinning near its intermediate axis (it flips).
    const auto free_body =
        scene(World<"world">{}, FreeMotion<"fly">{},
              Body<"body", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.1, 0, 0}}),
              connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "body.frame_a">);
    auto x0 = neutral_state(free_body);
    set_joint<"fly">(free_body, x0,
                     {.r = Vec3d::Zero(), .v = Vec3d(1, 2, 0), .R = orientation{}, .w = Vec3d(0.3, 4, 0.2)});
    study_scene("free_body", free_body, x0, 5.0, false, o, points, refs);
  }
  {
    // A closed loop: the crank-rocker four-bar (models/linkages.hpp), free
    // under gravity from θ2 = 1 rad at 3 rad/s, its loop closed. The plain
    // ODE form (no projection between steps) for every stepper.
    const models::fourbar_params p{};
    const auto fb = models::fourbar(p);
    const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
    std::array<double, 6> x0{q[0], q[1], q[2], 3.0, 0, 0};
    close_loops<"crank_pivot">(fb, x0);
    study_scene("fourbar", fb, x0, 5.0, false, o, points, refs);
  }
  {
    // A floating-base robot falling freely: a trunk on a FreeMotion with four
    // legs of three revolute joints (models/legged.hpp), every coordinate and
    // rate moved off neutral.
    const auto legged = models::legged<4, 3>();
    auto x0 = neutral_state(legged);
    for (std::size_t i = 0; i < x0.size(); ++i) x0[i] += 0.3 * std::sin(1.3 * i + 0.4);
    normalize(legged, x0);
    study_scene("legged", legged, x0, 2.0, false, o, points, refs);
  }
}

}  // namespace work_precision
