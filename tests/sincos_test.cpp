// Many cosines and sines in one call (math/sincos.hpp: glibc's libmvec on
// x86-64, 4 lanes with AVX2 or 2 with SSE2; std::cos and std::sin
// elsewhere), against long double's cosl and sinl: within libmvec's
// documented bound of 4 ulp, for every batch size up to 9 (the padded tails),
// small and large angles, and through the scene: a chain whose links take
// their angles from one batch against the same chain with its cosines and
// sines one at a time (long double, which takes the one-at-a-time path).
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/math/sincos.hpp>

#include <cmath>
#include <limits>
#include <random>

using namespace flange;

namespace {

/// |x − exact| in units in the last place of exact (as a double).
double ulps(double x, long double exact) {
  const double e = static_cast<double>(exact);
  const double ulp = std::nextafter(std::abs(e), std::numeric_limits<double>::infinity()) - std::abs(e);
  return static_cast<double>(std::abs(static_cast<long double>(x) - exact)) / ulp;
}

template <std::size_t N>
double worst_ulps(std::mt19937& rng, double range, int rounds) {
  std::uniform_real_distribution<double> u(-range, range);
  double worst = 0;
  for (int r = 0; r < rounds; ++r) {
    cos_sin_batch<N> b;
    for (std::size_t i = 0; i < N; ++i) b.a[i] = u(rng);
    b.compute();
    for (std::size_t i = 0; i < N; ++i) {
      const long double a = b.a[i];
      worst = std::max({worst, ulps(b[i].c, std::cos(a)), ulps(b[i].s, std::sin(a))});
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("a batch of cosines and sines is within 4 ulp of long double's, every size and range", "[sincos]") {
  std::mt19937 rng(3);
  const auto check = [&]<std::size_t N>(std::integral_constant<std::size_t, N>) {
    for (const double range : {1.0, 4.0, 100.0, 1e6}) {
      const double w = worst_ulps<N>(rng, range, 4000);
      INFO("N = " << N << ", angles in ±" << range << ": worst " << w << " ulp");
      CHECK(w <= 4.0);
    }
  };
  [&]<std::size_t... N>(std::index_sequence<N...>) {
    (check(std::integral_constant<std::size_t, N + 1>{}), ...);
  }(std::make_index_sequence<9>{});
}

TEST_CASE("a batch gives exact values where they are exact, and NaN for what is not finite", "[sincos]") {
  cos_sin_batch<5> b;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  b.a[0] = 0.0, b.a[1] = -0.0, b.a[2] = 1e-300, b.a[3] = nan, b.a[4] = inf;
  b.compute();
  CHECK(b.c[0] == 1.0);
  CHECK(b.s[0] == 0.0);
  CHECK(b.c[1] == 1.0);
  CHECK(b.c[2] == 1.0);
  CHECK(b.s[2] == 1e-300);
  CHECK(std::isnan(b.c[3]));
  CHECK(std::isnan(b.s[3]));
  CHECK(std::isnan(b.c[4]));
  CHECK(std::isnan(b.s[4]));
}

TEST_CASE("a chain's links with their angles from one batch agree with one at a time to round-off", "[sincos]") {
  // double takes the batch (dynamics/links.hpp: link_motions), long double
  // the cosines and sines one at a time; both through the same algorithm.
  std::mt19937 rng(5);
  const auto p = models::random_chain_params<12>(rng);
  const auto chain = models::chain<12, models::runtime_axes>(p);
  using S = std::remove_cvref_t<decltype(chain)>;
  std::uniform_real_distribution<double> u(-3, 3);
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    typename S::state_type x, dx;
    std::array<long double, S::n_q + S::n_v> xl, dxl;
    for (std::size_t i = 0; i < x.size(); ++i) xl[i] = x[i] = u(rng);
    chain(x, dx, 0.0);
    chain(xl, dxl, 0.0L);
    double scale = 0;
    for (std::size_t i = 0; i < x.size(); ++i) scale = std::max(scale, std::abs(static_cast<double>(dxl[i])));
    for (std::size_t i = 0; i < x.size(); ++i)
      worst = std::max(worst, std::abs(dx[i] - static_cast<double>(dxl[i])) / scale);
  }
  INFO("worst relative difference " << worst);
  // Round-off of the double evaluation times cond(M) (planar_test's bound).
  CHECK(worst < 1e-11);
}
