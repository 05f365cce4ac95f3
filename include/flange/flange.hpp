// flange: multibody scenes composed at compile time. The umbrella header.
#pragma once
#include "flange/math/rotation.hpp"
#include "flange/components/world.hpp"
#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/forces/torque.hpp"
#include "flange/scene/scene.hpp"
#include "flange/equations/residual.hpp"
#include "flange/equations/listing.hpp"
#include "flange/dynamics/newton_euler.hpp"
#include "flange/dynamics/articulated_body.hpp"
