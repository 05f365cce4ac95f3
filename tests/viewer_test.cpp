// The trajectory page's content without a browser: what is recorded (one
// pose per frame and sample, the plotted series) and what is drawn (each
// component's kind), and the error when three.js is missing. The browser
// test (viewer.spatial_arm_in_chromium) plays a real page.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <flange/flange.hpp>
#include <flange/viewer/recording.hpp>

using namespace flange;

namespace {
std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST_CASE("a recording writes every frame's pose at every sample, the plots, and one item per drawn part") {
  const auto arm = scene(World<"world">({.g = {0, 0, -9.81}}), Revolute<"shoulder", axis::z>(),
                         Revolute<"elbow", axis::y>(), BodyBox<"upper">({.r = {0.5, 0, 0}}),
                         FixedTranslation<"rod">({.d = {0.3, 0, 0}}), Body<"tip">({.m = 1, .J = Mat3d::Identity() * 0.01}),
                         connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
                         connect<"upper.frame_b", "elbow.frame_a">, connect<"elbow.frame_b", "rod.frame_a">,
                         connect<"rod.frame_b", "tip.frame_a">);
  using A = decltype(arm);
  viewer::recording page(arm);
  page.plot("energy", [](const auto& s) { return s.energy(); });
  A::state_type x{0.2, 0.5, 1.0, 0.0};
  page.reserve(11);
  odeint::integrate_const(odeint::runge_kutta4<A::state_type>(), arm, x, 0.0, 1.0, 0.1, record(arm, page.observer()));
  REQUIRE(page.samples() == 11);
  const std::string three = "three_stub.js", html = "viewer_test.html";
  std::ofstream(three) << "/* three.js stand-in */";
  page.write_html(html, three, "test");
  const std::string text = read(html);
  CHECK(count(text, "/* three.js stand-in */") == 1);  // inlined, not linked
  CHECK(text.find("src=") == std::string::npos);       // nothing to fetch: it works offline
  // The poses: 7 numbers per frame per sample.
  const auto poses = text.substr(text.find("\"poses\":[") + 9);
  CHECK(count(poses.substr(0, poses.find(']')), ",") + 1 == 11 * 7 * A::n_frames);
  CHECK(count(text, "\"name\":\"energy\"") == 1);
  CHECK(count(text, "\"kind\":\"box\"") == 1);      // the BodyBox, with its rod
  CHECK(count(text, "\"kind\":\"sphere\"") == 1);   // the Body
  CHECK(count(text, "\"kind\":\"rod\"") == 2);      // BodyBox's frame_a → frame_b, the FixedTranslation
  CHECK(count(text, "\"kind\":\"joint\"") == 2);
  CHECK(count(text, "\"kind\":\"world\"") == 1);
  std::remove(three.c_str());
  std::remove(html.c_str());
  CHECK_THROWS_WITH(page.write_html(html, "/nonexistent/three.min.js"), Catch::Contains("install-deps.sh --viewer"));
}
