// The buffered crane with a PD-controlled cart (flange/models/controlled_crane.hpp)
// for Python: its parameters adapted to Boost.Hana, so that a module built from
// this header (examples/python/CMakeLists.txt) has them as named numbers
// ("controller.kp", "m_load", …) settable per call and per ensemble case.
#pragma once
#include <boost/hana/adapt_struct.hpp>
#include <flange/models/controlled_crane.hpp>

BOOST_HANA_ADAPT_STRUCT(flange::models::cart_pd, kp, kd, target);
BOOST_HANA_ADAPT_STRUCT(flange::models::controlled_crane_params, controller, m_cart, m_load, rope, rail_d, rail_f_c,
                        buffer_c, buffer_d, buffer_s0);
