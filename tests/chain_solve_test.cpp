// The articulated-body solve of a chain's mass matrix (math/chain_solve.hpp),
// both kernels (Eigen's rows of up to eight columns, and AVX2 with fused multiply-adds
// where the processor has them) and the dispatcher, against a dense solve in
// long double of M_ij = s_iᵀ·(A_max(i,j) + … + A_N)·s_j built from the same
// columns and inertias: chains of 1, 5, 13 and 30 nodes, in space (six
// numbers a node) and in the plane (three), with as many columns as the
// Jacobian's 2N + 1 and with one (chain_solve_column); and a pivot that
// fails, in the whole factor and a node at a time.
#include <catch2/catch.hpp>
#include <flange/math/chain_solve.hpp>
#include <flange/math/tree_solve.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Cholesky>

using namespace flange;

namespace {

template <int C>
using Mat = Eigen::Matrix<double, C, C>;
using LMat = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

/// A chain's columns and own inertias: symmetric positive definite, every
/// third node massless (as a ball's first rotation nodes are).
template <int N, int C>
struct random_chain {
  std::array<std::array<double, C>, N> s;
  std::array<Mat<C>, N> A;
  explicit random_chain(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < N; ++k) {
      for (int c = 0; c < C; ++c) s[k][c] = u(rng);
      Mat<C> B;
      for (int i = 0; i < C; ++i)
        for (int j = 0; j < C; ++j) B(i, j) = u(rng);
      A[k] = k % 3 == 1 && k + 1 < N ? Mat<C>::Zero() : Mat<C>(B * B.transpose() + 0.5 * Mat<C>::Identity());
    }
  }
  /// M in long double.
  LMat mass_matrix() const {
    std::vector<Eigen::Matrix<long double, C, C>> Ic(N);
    Ic[N - 1] = A[N - 1].template cast<long double>();
    for (int k = N - 2; k >= 0; --k) Ic[k] = A[k].template cast<long double>() + Ic[k + 1];
    LMat M(N, N);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        const Eigen::Matrix<long double, C, 1> si = Eigen::Map<const Eigen::Matrix<double, C, 1>>(s[i].data()).template cast<long double>(),
                                               sj = Eigen::Map<const Eigen::Matrix<double, C, 1>>(s[j].data()).template cast<long double>();
        M(i, j) = si.dot(Ic[std::max(i, j)] * sj);
      }
    return M;
  }
  std::array<double, N> diagonal() const {
    std::array<double, N> d;
    const LMat M = mass_matrix();
    for (int k = 0; k < N; ++k) d[k] = double(M(k, k));
    return d;
  }
};

/// The largest |X − M⁻¹·B| over the first cols columns, relative to the
/// largest |M⁻¹·B|.
double solve_error(const LMat& M, int cols, int ld, const std::vector<double>& B, const std::vector<double>& X) {
  const int N = int(M.rows());
  LMat Bl(N, cols);
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) Bl(r, c) = B[r * ld + c];
  const LMat ref = M.llt().solve(Bl);
  long double worst = 0, scale = ref.cwiseAbs().maxCoeff();
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) worst = std::max(worst, std::abs(X[r * ld + c] - ref(r, c)));
  return double(worst / scale);
}

template <int N, int C>
void check_chain(std::mt19937& rng) {
  constexpr int cols = 2 * N + 1, ld = detail::tree_solve_row(cols);
  const random_chain<N, C> chain(rng);
  const auto diag = chain.diagonal();
  detail::chain_factor<N, C> f;
  REQUIRE(f.factor(chain.s, [&](int k) { return chain.A[k]; }, diag.data(), 1e-12));
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> B(N * ld);
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < ld; ++c) B[r * ld + c] = c < cols ? u(rng) : 0.0;
  const LMat M = chain.mass_matrix();
  // The solve's error is a few ε times M's condition number.
  const double cond = double(M.cast<double>().jacobiSvd().singularValues().maxCoeff() /
                             M.cast<double>().jacobiSvd().singularValues().minCoeff());
  const double tol = 20 * cond * 2.2e-16;
  INFO("N = " << N << ", C = " << C << ", condition " << cond);
  {
    std::vector<double> X = B;
    // A value past the columns: the first kernel leaves it as it was.
    if (ld > cols) X[ld - 1] = 7;
    detail::chain_solve_blocks<N, C, cols>(f, X.data(), ld);
    CHECK(solve_error(M, cols, ld, B, X) < tol);
    if (ld > cols) CHECK(X[ld - 1] == 7);
  }
  {
    std::vector<double> X = B;
    detail::chain_solve<N, C, cols, ld>(f, X.data());
    CHECK(solve_error(M, cols, ld, B, X) < tol);
  }
  {
    // The first 2N columns alone in rows of ld numbers (the Jacobian's
    // solve where ∂/∂t is zero): those solved, the columns past the next
    // multiple of four left as they were.
    constexpr int first = 2 * N;
    std::vector<double> X = B;
    for (int r = 0; r < N; ++r) X[r * ld + ld - 1] = 7;
    detail::chain_solve<N, C, first, ld>(f, X.data());
    CHECK(solve_error(M, first, ld, B, X) < tol);
    for (int r = 0; r < N; ++r)
      if (detail::tree_solve_row(first) < ld) CHECK(X[r * ld + ld - 1] == 7);
  }
  {
    // One column, the scalar sweeps (the Jacobian's v̇).
    std::vector<double> x(N), b(N);
    for (int r = 0; r < N; ++r) x[r] = b[r] = B[r * ld];
    detail::chain_solve_column(f, x.data());
    CHECK(solve_error(M, 1, 1, b, x) < tol);
  }
#ifdef FLANGE_CHAIN_SOLVE_AVX2
  if (detail::cpu_has_avx2_fma) {
    std::vector<double> X = B;
    detail::chain_solve_avx2<N, C, ld, ld>(f, X.data());
    CHECK(solve_error(M, cols, ld, B, X) < tol);
    for (int r = 0; r < N; ++r)
      for (int c = cols; c < ld; ++c) CHECK(X[r * ld + c] == 0);
  }
#endif
}

}  // namespace

TEST_CASE("chain_solve: both kernels solve a chain's M·X = B as a dense solve in long double does") {
  std::mt19937 rng(17);
  for (int round = 0; round < 5; ++round) {
    check_chain<1, 6>(rng);
    check_chain<5, 6>(rng);
    check_chain<13, 6>(rng);
    check_chain<30, 6>(rng);
    check_chain<5, 3>(rng);
    check_chain<30, 3>(rng);
  }
#ifdef FLANGE_CHAIN_SOLVE_AVX2
  if (!detail::cpu_has_avx2_fma) WARN("this processor has no AVX2 and FMA: their kernel was not run");
#endif
}

TEST_CASE("chain_solve: the factor's pivots are the leaves-first LTDL factor's, and one that fails stops it") {
  std::mt19937 rng(3);
  constexpr int N = 9;
  random_chain<N, 6> chain(rng);
  // D_k is the pivot M's leaves-first LTDL factor meets at node k: the
  // Schur complement of the nodes below k, M_kk − M_k,b·M_bb⁻¹·M_b,k.
  {
    const auto diag = chain.diagonal();
    detail::chain_factor<N, 6> f;
    REQUIRE(f.factor(chain.s, [&](int k) { return chain.A[k]; }, diag.data(), 1e-12));
    const LMat M = chain.mass_matrix();
    for (int k = 0; k + 1 < N; ++k) {
      const int b = N - 1 - k;
      const LMat Mbb = M.bottomRightCorner(b, b);
      const long double schur =
          M(k, k) - (M.block(k, k + 1, 1, b) * Mbb.llt().solve(M.block(k + 1, k, b, 1)))(0, 0);
      CHECK(std::abs(1 / f.inv[k] - double(schur)) < 1e-12 * diag[k]);
    }
  }
  // The last node's column moves nothing with its inertia (a massless tip):
  // D = 0 there, the first pivot met.
  chain.A[N - 1].setZero();
  chain.A[N - 2] = Mat<6>::Identity();
  const auto diag = chain.diagonal();
  detail::chain_factor<N, 6> f;
  CHECK_FALSE(f.factor(chain.s, [&](int k) { return chain.A[k]; }, diag.data(), 1e-12));
  CHECK(f.failed == N - 1);
  CHECK(f.failed_d == 0);
  // A node at a time (as the Jacobian's pass carries it), the factor goes
  // on past the pivot that failed in finite numbers and keeps that one.
  detail::chain_factor<N, 6> g;
  g.start();
  for (int k = N - 1; k >= 0; --k) g.node(k, chain.s[k], chain.A[k], diag[k], 1e-12);
  CHECK(g.failed == N - 1);
  CHECK(g.failed_d == 0);
  for (int k = 0; k < N; ++k) CHECK(std::isfinite(g.inv[k]));
}
