// A user-written body that forgets its torque equation: 9 scalar equations
// where its 18 unknowns less 6 flow variables need 12.
#include <flange/equations_of_motion.hpp>
using namespace flange;

template <fixed_string Name, bool Complete>
struct HalfBody : Body<Name> {
  using Body<Name>::Body;
  using Body<Name>::v;
  using Body<Name>::w;
  auto equations() const {
    using namespace expr;
    const param<double> m{this->m(), "m"};
    if constexpr (Complete) return Body<Name>::equations();
    else
      return boost::hana::make_tuple(eq(v, der(r_<0>)), skew_eq(tilde(w), R_<0> * transpose(der(R_<0>))),
                                     eq(F_<0>, R_<0> * m * (der(v) - gravity{})));
  }
};

#ifdef FLANGE_KO
constexpr bool complete = false;
#else
constexpr bool complete = true;
#endif

auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, HalfBody<"mass", complete>({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "mass.frame_a">);
int main() {}
