// What the scenes fuzz target (fuzz/scenes_fuzz.cpp) does with each scene:
// bytes → parameters and a state, then the derivative, a short checked
// simulation and recovery, with the invariants every scene must keep:
//
//   * no crash, no hang, no undefined behaviour (built with ASan + UBSan);
//   * every failure is a flange::error (parameter_error at construction,
//     simulation_error or parameter_error while simulating) whose message
//     names what went wrong; anything else thrown is a finding;
//   * the checked path (flange::simulate) either throws or returns a finite
//     state, whatever the input (no silent NaN);
//   * on tame inputs (physical ranges, as the law tests draw them) the raw
//     derivative is finite, the residual of the components' equations on the
//     recovered variables is ≈ 0, and, on trees whose mass matrix is well
//     conditioned (cond(M) < 1e6, M from the kinetic energy:
//     dynamics/energy_mass_matrix.hpp),
//     the articulated-body algorithm agrees with Newton–Euler + mass matrix.
//
// The first byte picks the scene, the second whether the numbers are tame
// or wild (raw doubles, NaN, infinities, zeros, negatives, 1e±300).
// docs/fuzzing.md says how to build and run it; fuzz/corpus/scenes holds the
// seed corpus CI starts from.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <numbers>

#include <flange/dynamics/other_algorithm.hpp>
#include <flange/flange.hpp>
#include <flange/dynamics/energy_mass_matrix.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/linkages.hpp>
#include <flange/models/tree.hpp>

namespace flange::fuzz {
using namespace flange;


[[noreturn]] inline void finding(const char* what, const char* detail = "") {
  std::fprintf(stderr, "scenes_fuzz: %s %s\n", what, detail);
  std::abort();
}

/// Numbers from the fuzzer's bytes; zeros once they run out.
struct bytes {
  const std::uint8_t* p;
  std::size_t n;
  bool wild = false;
  std::uint8_t byte() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  double unit() { return (byte() * 256.0 + byte()) / 65535.0; }
  double in(double a, double b) { return a + (b - a) * unit(); }
  /// A number in [a, b] when tame; when wild, sometimes that, sometimes anything.
  double num(double a, double b) {
    if (!wild) return in(a, b);
    switch (byte() % 12) {
      case 0: return std::numeric_limits<double>::quiet_NaN();
      case 1: return std::numeric_limits<double>::infinity();
      case 2: return 0.0;
      case 3: return -in(a, b);
      case 4: return in(a, b) * 1e300;
      case 5: return in(a, b) * 1e-300;
      case 6: {
        double d = 0;
        for (std::size_t k = 0; k < sizeof d; ++k) reinterpret_cast<std::uint8_t*>(&d)[k] = byte();
        return d;
      }
      case 7: return in(a, b) * std::pow(10.0, in(-12, 12));
      default: return in(a, b);
    }
  }
  Vec3d vec(double a, double b) { return Vec3d(num(a, b), num(a, b), num(a, b)); }
  Vec3d direction() {
    Vec3d u(in(-1, 1), in(-1, 1), in(-1, 1) + 1e-3);
    return wild && byte() % 4 == 0 ? vec(-1, 1) : Vec3d(u.normalized());
  }
  /// A physical inertia (principal moments obeying the triangle inequality,
  /// turned), or, when wild, sometimes any matrix.
  Mat3d inertia() {
    if (wild && byte() % 3 == 0) {
      Mat3d J;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J(i, j) = num(0.01, 0.1);
      return J;
    }
    const double a = in(0.02, 0.1), b = in(0.02, 0.1), c = in(std::abs(a - b), a + b);
    const Mat3d Q = axis_rotation<double>(Vec3d(in(-1, 1), in(-1, 1), 1).normalized(), in(-3, 3));
    return Q * Vec3d(a, b, c).asDiagonal() * Q.transpose();
  }
};

template <int N>
models::tree_params<N> tree_numbers(bytes& b) {
  models::tree_params<N> p;
  for (int i = 0; i < N; ++i) {
    p.offset[i] = b.direction() * b.num(0.2, 1);
    p.axis[i] = b.direction();
    p.axis2[i] = b.direction();
    p.m[i] = b.num(0.2, 2);
    p.J[i] = b.inertia();
    p.r_cm[i] = b.vec(-0.2, 0.2);
    p.c[i] = b.num(1, 20);
    p.d[i] = b.num(0.1, 1);
    p.q0[i] = b.num(-0.5, 0.5);
    p.f_c[i] = b.num(0.1, 1);
    p.f[i] = b.num(-2, 2);
    p.torque[i] = b.vec(-1, 1);
    p.line_c[i] = b.num(1, 20);
    p.line_s0[i] = b.num(0.1, 0.5);
    p.line_d[i] = b.num(0.1, 1);
    p.load[i] = b.vec(-2, 2);
  }
  p.g = Vec3d(b.num(-1, 1), b.num(-10, -9), b.num(-1, 1));
  // Stops last, so that the corpus's bytes for the numbers above keep their meaning.
  for (int i = 0; i < N; ++i) {
    p.lower[i] = b.num(-1.2, -0.2);
    p.upper[i] = b.num(0.2, 1.2);
    p.k_stop[i] = b.num(10, 200);
    p.d_stop[i] = b.num(0, 1);
  }
  return p;
}

template <class S>
typename S::state_type state_from(const S& s, bytes& b) {
  typename S::state_type x;
  for (int i = 0; i < S::n_q; ++i) x[i] = b.num(-1.5, 1.5);
  for (int i = S::n_q; i < S::n_state; ++i) x[i] = b.num(-2, 2);
  if (!b.wild) normalize(s, x);  // valid coordinates (unit quaternions, closed loops)
  return x;
}


/// The derivative, recovery, the second algorithm and a checked run.
template <class S>
void exercise(const S& s, bytes& b, bool tree) {
  using X = typename S::state_type;
  X x = state_from(s, b);
  const double t = b.in(0, 1);
  bool closed = true;  // a loop scene's state closes its loops (tame states are projected; it may fail)
  try {
    check_loops(s, x);
  } catch (const parameter_error&) {
    closed = false;
  }
  if (!b.wild && detail::finite(x) && closed) {
    X dx;
    bool singular = false;
    try {
      s(x, dx, t);
    } catch (const simulation_error&) {
      singular = true;  // a singular mass matrix, named; tame shapes may have one at some q
    }
    if (!singular) {
      if (!detail::finite(dx)) finding("tame input, raw derivative not finite");
      const auto sol = recover(s, t, x);
      if (!std::isfinite(sol.energy())) finding("tame input, recovered energy not finite");
      const double r = scaled_residual(s, sol);
      if (!(r <= 1e-9)) {
        char m[64];
        std::snprintf(m, sizeof m, "%g", r);
        finding("tame input, residual on recovered values", m);
      }
      if constexpr (!flange::detail::has_loops<S>) if (tree) {
        // The second algorithm. cond(M) (n_v²/4 recoveries) is computed only
        // when the two disagree beyond round-off, to judge whether they may.
        std::array<double, S::n_v> aba;
        double err = 0;
        try {
          accelerations_other(s, t, x.data(), x.data() + S::n_q, aba.data());
          double scale = 1;
          for (int i = 0; i < S::n_v; ++i) scale = std::max(scale, std::abs(dx[S::n_q + i]));
          for (int i = 0; i < S::n_v; ++i) err = std::max(err, std::abs(aba[i] - dx[S::n_q + i]) / scale);
        } catch (const simulation_error&) {
          err = std::numeric_limits<double>::infinity();  // refused a state the default accepted
        }
        if (!(err <= 1e-12)) {
          // Round-off amplified by the conditioning: ε·cond(M) and a margin
          // for the length of the sums; checked where cond(M) < 1e6.
          const double cond = mass_matrix_condition(s, x);
          if (cond < 1e6 && !(err <= 1e-13 * cond)) {
            char m[96];
            std::snprintf(m, sizeof m, "error %g at cond(M) %g", err, cond);
            finding("articulated body disagrees with Newton-Euler + mass matrix:", m);
          }
        }
      }
    }
  } else {
    X dx;
    try {
      s(x, dx, t);  // unchecked: any value, but no crash and no UB
    } catch (const error&) {
    }
  }
  // The checked path: a finite state or a flange::error, whatever the input.
  try {
    const X x1 = simulate(s, x, 0.0, 0.05, {.tolerance = 1e-8, .max_rhs_evals = 1000});
    if (!detail::finite(x1)) finding("simulate returned a non-finite state");
    const auto sol = recover(s, 0.05, x1);
    if (!b.wild && !std::isfinite(sol.energy())) finding("tame input, energy after simulate not finite");
  } catch (const parameter_error& e) {
    // A state no scene can have (a quaternion far from unit length), refused
    // before the first step as a wrong parameter is: naming the component.
    if (std::strstr(e.what(), "\"") == nullptr) finding("a parameter error that names no component:", e.what());
  } catch (const error& e) {
    if (std::strstr(e.what(), "flange") == nullptr) finding("an error that does not say where it comes from:", e.what());
  }
}

template <class Make>
void run(bytes& b, bool tree, Make make) {
  try {
    const auto s = make();
    exercise(s, b, tree);
  } catch (const parameter_error& e) {
    // Refused at construction: the message must name the component.
    if (std::strstr(e.what(), "\"") == nullptr) finding("a parameter error that names no component:", e.what());
  }
}

/// A contact surface's material from the bytes.
inline contact_material material(bytes& b) {
  return {.stiffness = b.num(1e4, 1e7), .dissipation = b.num(0, 1), .static_friction = b.num(0, 1),
          .dynamic_friction = b.num(0, 1), .viscous_friction = b.num(0, 0.2)};
}

/// The eight scenes, in five translation units so that they build in parallel.
void fuzz_trees(bytes& b, int which);
void fuzz_chain_and_crane(bytes& b, int which);
void fuzz_loops(bytes& b, int which);
void fuzz_contacts(bytes& b, int which);
void fuzz_legged_contact(bytes& b);

}  // namespace flange::fuzz
