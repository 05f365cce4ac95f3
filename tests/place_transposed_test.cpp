// A row-major block placed, turned, into a column-major matrix
// (math/place_transposed.hpp): both kernels (a number at a time, and AVX2 by
// 4 × 4 blocks where the processor has it) and the dispatcher, against the
// definition dst(r0 + row_to[r], col_to[c]) = src(r, c) written out, on the
// shapes the Jacobian gives: rows in order (a chain) or permuted (a tree's
// rows in link order), columns in order, or with columns left out (a ball's
// turns) and a jump, and counts of rows and columns that are and are not
// multiples of four. Every other entry of dst must stay as it was.
#include <catch2/catch.hpp>
#include <flange/math/place_transposed.hpp>

#include <array>
#include <vector>

using namespace flange;

namespace {

constexpr int ld = 19, r0 = 5;

/// The columns of a source of R rows: columns 0 … R − 1 to dst columns in
/// order, then R … 2R − 1 to the columns from r0 + 1 on; Gap: columns 1 to 3
/// left out and the first half shifted by one.
template <int R, bool Gap>
constexpr std::array<int, 2 * R> columns() {
  std::array<int, 2 * R> c{};
  for (int k = 0; k < R; ++k) {
    c[k] = Gap ? (k >= 1 && k <= 3 ? -1 : k + 1) : k;
    c[R + k] = r0 + 1 + k;
  }
  return c;
}
/// Rows in order, or turned about by a stride prime to R.
template <int R, bool Permuted>
constexpr std::array<int, R> rows() {
  std::array<int, R> r{};
  for (int k = 0; k < R; ++k) r[k] = Permuted ? (k * 5 + 2) % R : k;
  return r;
}

template <int R, bool Permuted, bool Gap>
void check() {
  static_assert(r0 + R <= ld);
  constexpr int ls = (2 * R + 1 + 3) / 4 * 4;
  static constexpr auto row_to = rows<R, Permuted>();
  static constexpr auto col_to = columns<R, Gap>();
  constexpr int ncols = r0 + 1 + R;
  std::vector<double> src(R * ls);
  for (int i = 0; i < R * ls; ++i) src[i] = 1000.0 + i;
  std::vector<double> want(std::size_t(ld) * ncols, -1.0);
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < 2 * R; ++c)
      if (col_to[c] >= 0) want[std::size_t(col_to[c]) * ld + r0 + row_to[r]] = src[r * ls + c];
  auto run = [&](auto kernel) {
    std::vector<double> dst(std::size_t(ld) * ncols, -1.0);
    kernel(src.data(), dst.data());
    return dst;
  };
  CHECK(run([](const double* s, double* d) { detail::place_transposed_portable<ls, ld, row_to, col_to>(s, d, r0); }) ==
        want);
  CHECK(run([](const double* s, double* d) { detail::place_transposed<ls, ld, row_to, col_to>(s, d, r0); }) == want);
#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
  if (detail::cpu_has_avx2)
    CHECK(run([](const double* s, double* d) { detail::place_transposed_avx2<ls, ld, row_to, col_to>(s, d, r0); }) ==
          want);
#endif
}

}  // namespace

TEST_CASE("place_transposed: a chain's rows, in order, 4 and 7 of them") {
  check<4, false, false>();
  check<7, false, false>();
}

TEST_CASE("place_transposed: rows permuted, columns left out, 8 and 13 of them") {
  check<8, true, true>();
  check<13, true, true>();
  check<13, true, false>();
  check<6, false, true>();
}
