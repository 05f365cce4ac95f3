// flange::renamed<Named>(scene) (simulate/system.hpp): the same scene under a
// short type name. The numbers must not change (the derivative, the
// projection and named access give the same bits as the scene they came
// from), and the name must be short: the type's mangled name, which every
// function of its dynamics carries, no longer holds the list of components.
// models::window_row names its scene so (window_row_scene).
#include <catch2/catch.hpp>
#include <cstring>
#include <typeinfo>

#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

using namespace flange;

namespace {
struct fourbar_scene : decltype(models::fourbar(models::fourbar_params{}))::scene_type {};
}  // namespace

TEST_CASE("a renamed scene gives the same numbers as the scene it came from, under a short name",
          "[renamed][loops]") {
  models::fourbar_params p{};
  p.m_coupler = 2.7;  // not the default: the parameters must move in with the components
  const auto plain = models::fourbar(p);
  const auto named = renamed<fourbar_scene>(models::fourbar(p));
  using P = std::remove_cvref_t<decltype(plain)>;
  using N = std::remove_cvref_t<decltype(named)>;
  static_assert(std::is_same_v<N, System<fourbar_scene>> && std::is_same_v<N::scene_type, fourbar_scene>);
  static_assert(N::n_q == P::n_q && N::n_v == P::n_v && N::q_offset("rocker_pin") == P::q_offset("rocker_pin"));

  // The derivative, the projection and a cut joint read by name, bit for bit.
  typename P::state_type x{}, xn{};
  x[P::q_offset("crank_pivot")] = xn[N::q_offset("crank_pivot")] = 1.1;
  x[P::n_q + P::q_offset("crank_pivot")] = xn[N::n_q + N::q_offset("crank_pivot")] = -2.3;
  close_loops<"crank_pivot">(plain, x);
  close_loops<"crank_pivot">(named, xn);
  REQUIRE(std::memcmp(x.data(), xn.data(), sizeof(double) * x.size()) == 0);
  typename P::state_type dx{}, dxn{};
  plain(x, dx, 0.0);
  named(xn, dxn, 0.0);
  CHECK(std::memcmp(dx.data(), dxn.data(), sizeof(double) * dx.size()) == 0);
  auto y = x, yn = xn;
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = yn[i] = x[i] + 1e-7 * double(int(i % 5) - 2);
  normalize(plain, y);
  normalize(named, yn);
  CHECK(std::memcmp(y.data(), yn.data(), sizeof(double) * y.size()) == 0);
  CHECK(get_joint<"rocker_pivot">(named, xn).q == get_joint<"rocker_pivot">(plain, x).q);

  // The names: the plain type's mangled name spells out every component
  // (tens of characters each), the renamed one names fourbar_scene; so does
  // the window row's, whatever its size.
  const std::size_t plain_name = std::strlen(typeid(P).name()), short_name = std::strlen(typeid(N).name());
  const std::size_t row_name = std::strlen(typeid(decltype(models::window_row<40>(models::window_row_params{}))).name());
  INFO("mangled names: " << plain_name << ", " << short_name << " and " << row_name << " characters");
  CHECK(plain_name > 500);
  CHECK(short_name < 64);
  CHECK(row_name < 200);
}
