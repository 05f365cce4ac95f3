// A probe for tools/chain_counts.sh: the N-link chain of models/chain.hpp with
// the scale benchmark's random parameters and state (benchmarks/scale/scale.hpp),
// its derivative called K times by one algorithm. Not part of the CMake build.
//
//   chain_derivative K ALGORITHM
//
// ALGORITHM: default (the System's derivative), articulated, other (the
// algorithm the cost model did not pick), articulated_unrolled and
// articulated_shared (the articulated body with its per-link steps forced
// into one form, dynamics/articulated_body.hpp: aba_steps), or jacobian
// (not a derivative: the exact Jacobian, simulate/jacobian.hpp's jacobian()).
//
// Compile-time choices: -DPROBE_N=<links> and -DPROBE_AXES=runtime|typed|planar,
// or tree: the scale benchmark's floating tree, models::legged<4, N / 4>.
#include <flange/dynamics/other_algorithm.hpp>
#include <flange/flange.hpp>
#include <flange/models/legged.hpp>
#ifdef PROBE_JACOBIAN
#include <flange/simulate/jacobian.hpp>
#endif

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#ifndef PROBE_N
#define PROBE_N 16
#endif
#define PROBE_runtime 0
#define PROBE_typed 1
#define PROBE_planar 2
#define PROBE_tree 3
#define PROBE_KIND_(a) PROBE_##a
#define PROBE_KIND(a) PROBE_KIND_(a)
#ifndef PROBE_AXES
#define PROBE_AXES runtime
#endif

template <int I>
struct probe_axes {
#if PROBE_KIND(PROBE_AXES) == PROBE_typed
  using type = flange::axis::coordinate<I % 3>;
#elif PROBE_KIND(PROBE_AXES) == PROBE_planar
  using type = flange::axis::z;
#else
  using type = flange::axis::any;
#endif
};

int main(int argc, char** argv) {
  using namespace flange;
  constexpr int N = PROBE_N;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> s(-1, 1);
#if PROBE_KIND(PROBE_AXES) == PROBE_tree
  const auto c = models::legged<4, N / 4>();
  using S = std::remove_cvref_t<decltype(c)>;
  typename S::state_type x, dx{};
  for (auto& v : x) v = s(rng);
  double nq = 0;  // the base's unit quaternion, as the scale benchmark
  for (int i = 3; i < 7; ++i) nq += x[i] * x[i];
  for (int i = 3; i < 7; ++i) x[i] /= std::sqrt(nq);
#else
  const auto p = models::random_chain_params<N>(rng);
  const auto c = models::chain<N, probe_axes>(p);
  using S = std::remove_cvref_t<decltype(c)>;
  typename S::state_type x, dx{};
  for (auto& v : x) v = s(rng);
#endif
  const long k = argc > 1 ? std::atol(argv[1]) : 1000;
  const char* alg = argc > 2 ? argv[2] : "default";
  const double* q = x.data();
  const double* v = x.data() + S::n_q;
  double* vd = dx.data() + S::n_q;
  double sum = 0;
#ifdef PROBE_JACOBIAN
  jacobian_matrix<S> J = make_jacobian_matrix<S>();
#endif
  for (long i = 0; i < k; ++i) {
    asm volatile("" : : "r"(x.data()) : "memory");
    if (!std::strcmp(alg, "articulated")) accelerations_articulated_body(c, 0.0, q, v, vd);
    else if (!std::strcmp(alg, "articulated_unrolled"))
      accelerations_articulated_body<aba_steps::unrolled>(c, 0.0, q, v, vd);
    else if (!std::strcmp(alg, "articulated_shared"))
      accelerations_articulated_body<aba_steps::shared>(c, 0.0, q, v, vd);
    else if (!std::strcmp(alg, "other")) accelerations_other(c, 0.0, q, v, vd);
#ifdef PROBE_JACOBIAN  // compiled only when asked for: a long chain's Jacobian takes a minute
    else if (!std::strcmp(alg, "jacobian")) {
      jacobian(c, 0.0, x, J);
      dx[S::n_q] = J(S::n_q, 0);
    }
#endif
    else c(x, dx, 0.0);
    asm volatile("" : : "r"(dx.data()) : "memory");
    sum += dx[S::n_q];
  }
  std::printf("%.17g %s\n", sum,
              algorithm_for<S>() == forward_algorithm::articulated_body ? "articulated" : "newton_euler_mass_matrix");
}
