// flange: multibody scenes composed at compile time. The umbrella header:
// <flange/equations_of_motion.hpp> (everything but the integrators) and the
// Boost.Odeint boundary, with every Odeint stepper, simulate() and projection.
#pragma once
#include "flange/equations_of_motion.hpp"
#include "flange/simulate/odeint.hpp"
#include "flange/simulate/projected.hpp"
#include "flange/simulate/simulate.hpp"
