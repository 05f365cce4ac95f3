// Structure of the paper's two scenes: counts, connection sets, the paper's
// frame numbering, and the equation listing. The counts are static_asserts:
// building this file is half the test.
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <flange/equations/listing.hpp>
#include <flange/models/paper.hpp>

using namespace flange;
using Arm = decltype(models::robot_arm());
using Crane = decltype(models::gantry_crane());

// The paper: "35 × 3 + 1 = 106" equations, "8 × 4 × 3 + 3 × 3 + 1 = 106" variables.
static_assert(Arm::n_equations == 106 && Arm::n_unknowns == 106);
static_assert(Arm::n_frames == 8 && Arm::topology.n_sets == 3);

// The crane by the same rules: 9 frames (108 frame variables) + s, φ, R_rel and
// each body's v, ω (5 vectors, 2 scalars) = 125, and 125 equations. The paper
// counts 89 = 6 × 4 × 3 + 5 × 3 + 2: its figure has 6 frames, because each
// connection of exactly two frames is drawn as one frame. Our crane has three
// such sets; each adds a frame (12 unknowns) and 12 equations (r, R equal;
// F, M summing to zero), so 125 − 3 × 12 = 89.
static_assert(Crane::n_equations == 125 && Crane::n_unknowns == 125);
static_assert(Crane::n_frames == 9);
constexpr int two_frame_sets(const auto& topo) {
  int n = 0;
  for (int s = 0; s < topo.n_sets; ++s) n += topo.set_size[s] == 2;
  return n;
}
static_assert(two_frame_sets(Crane::topology) == 3);
static_assert(Crane::n_equations - 12 * two_frame_sets(Crane::topology) == 89);

// The robot arm's frames are numbered as the paper numbers them (Figure 2).
constexpr int number(std::string_view f) { return Arm::topology.number[Arm::frame_index(f)]; }
static_assert(number("world.frame_b") == 1 && number("joint.frame_a") == 2 && number("motor.frame_a") == 3);
static_assert(number("joint.frame_b") == 4 && number("rod.frame_a") == 5 && number("motor.frame_b") == 6);
static_assert(number("rod.frame_b") == 7 && number("mass.frame_a") == 8);

TEST_CASE("the robot arm's listing is the paper's equations (1)-(36)") {
  std::ostringstream os;
  print_equations(models::robot_arm(), os);
  const std::string s = os.str();
  INFO(s);
  // One line per paper equation, in the paper's order and notation.
  for (const char* line : {"(1)  r1 = 0",
                           "(2)  R1 = 1",
                           "(3)  F3 = 0",
                           "(4)  F6 = 0",
                           "(5)  M3 = M_ext",
                           "(6)  M6 = −R6·R3'·M_ext",
                           "(7)  R_rel = n·n' + (1 − n·n')·cos(φ) − tilde(n)·sin(φ)",
                           "(8)  r2 = r4",
                           "(9)  R4 = R_rel·R2",
                           "(10)  F4 = −R_rel·F2",
                           "(11)  M4 = −R_rel·M2",
                           "(12)  0 = M4·n",
                           "(13)  r7 = r5 + R5'·d",
                           "(14)  R7 = R5",
                           "(15)  F7 = −F5",
                           "(16)  M7 = −M5 + d × F5",
                           "(17)  v = der(r8)",
                           "(18)  tilde(ω) = R8·der(R8)'",
                           "(19)  F8 = R8·m·(der(v) − g)",
                           "(20)  M8 = J·der(ω) + ω × (J·ω)",
                           "(21)  r1 = r2",
                           "(22)  r1 = r3",
                           "(23)  R1 = R2",
                           "(24)  R1 = R3",
                           "(25)  F1 + F2 + F3 = 0",
                           "(26)  M1 + M2 + M3 = 0",
                           "(27)  r4 = r5",
                           "(28)  r4 = r6",
                           "(29)  R4 = R5",
                           "(30)  R4 = R6",
                           "(31)  F4 + F5 + F6 = 0",
                           "(32)  M4 + M5 + M6 = 0",
                           "(33)  r7 = r8",
                           "(34)  R7 = R8",
                           "(35)  F7 + F8 = 0",
                           "(36)  M7 + M8 = 0"})
    CHECK(s.find(std::string("  ") + line + "\n") != std::string::npos);
  CHECK(s.find("(37)") == std::string::npos);
  CHECK(s.substr(s.rfind("equations:")) == "equations: 106, unknowns: 106\n");
}

TEST_CASE("the crane's listing ends with its counts") {
  std::ostringstream os;
  print_equations(models::gantry_crane(), os);
  const std::string s = os.str();
  CHECK(s.find("f = −F3·n") != std::string::npos);  // the prismatic's force input
  CHECK(s.substr(s.rfind("equations:")) == "equations: 125, unknowns: 125\n");
}
