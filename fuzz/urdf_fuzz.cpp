// libFuzzer target for flange-urdf's reader and writer (tools/urdf/): bytes
// as a URDF file, parsed and, when accepted, turned into a scene header.
// Invariants: no crash, no hang, no undefined behaviour (ASan + UBSan); a
// file refused is refused with a urdf_error that names the file and a line;
// nothing else is thrown. fuzz/corpus/urdf starts from the test robots.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <sstream>
#include <string>

#include "generate.hpp"
#include "urdf_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    const auto robot = flange_urdf::parse("fuzz.urdf", xml);
    std::ostringstream out;
    (void)flange_urdf::generate(robot, "fuzz.urdf", "robot", out);
  } catch (const flange_urdf::urdf_error& e) {
    if (std::strncmp(e.what(), "fuzz.urdf:", 10) != 0) {
      std::fprintf(stderr, "urdf_fuzz: an error that names no file and line: %s\n", e.what());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "urdf_fuzz: an exception that is not a urdf_error: %s\n", e.what());
    std::abort();
  }
  return 0;
}
