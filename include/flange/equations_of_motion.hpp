// flange without the integrators: every component, joint and force element,
// scenes and their checks, the residual and its listing, the forward dynamics
// (Newton–Euler + mass matrix, articulated body), recovery, energies, the
// checked derivative and the example models. It does not include
// Boost.Odeint, which is half of <flange/flange.hpp>'s compile time: include
// this header where a unit evaluates derivatives or residuals without
// integrating (an embedded controller, another integrator, a test of the
// equations). <flange/flange.hpp> is this plus simulate/ (Odeint's steppers,
// simulate(), projection). The exact Jacobian, jacobian(scene, t, x), is
// <flange/simulate/jacobian.hpp> (its derivative passes cost every unit that
// parses them about 0.8 s of g++'s time, so only units that ask pay); the
// stiff stepper, linearize and equilibrium include it.
#pragma once
#include "flange/math/rotation.hpp"
#include "flange/components/world.hpp"
#include "flange/components/body.hpp"
#include "flange/components/body_shape.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/fixed_rotation.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/joints/spherical.hpp"
#include "flange/joints/universal.hpp"
#include "flange/joints/cylindrical.hpp"
#include "flange/joints/planar.hpp"
#include "flange/joints/free_motion.hpp"
#include "flange/forces/torque.hpp"
#include "flange/forces/line_force.hpp"
#include "flange/forces/world_force.hpp"
#include "flange/forces/contact.hpp"
#include "flange/scene/scene.hpp"
#include "flange/equations/residual.hpp"
#include "flange/equations/listing.hpp"
#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/articulated_body.hpp"
#include "flange/dynamics/algorithm.hpp"
#include "flange/dynamics/recover.hpp"
#include "flange/dynamics/momentum.hpp"
#include "flange/simulate/system.hpp"
#include "flange/models/paper.hpp"
#include "flange/models/chain.hpp"
#include "flange/models/gimbal.hpp"
#include "flange/models/legged.hpp"
#include "flange/models/tree.hpp"
#include "flange/models/linkages.hpp"
#include "flange/simulate/checked.hpp"
