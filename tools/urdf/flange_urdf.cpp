// flange-urdf: a URDF robot as a flange scene header.
//
//   flange-urdf robot.urdf [--namespace NAME] [--floating-base] [--stop-stiffness K]
//               [--stop-dissipation D] [--no-limits] [-o robot_scene.hpp]
//
// --floating-base lets the root link move freely (a FreeMotion from the
// World) where the URDF has no floating joint; without it such a root is
// welded to the World, and a note says so.
//
// A revolute or prismatic joint's <limit lower upper> becomes a compliant
// stop at each bound (axis_law::limited, Simbody's MobilityLinearStop) of
// stiffness K (default 1e4 N m/rad or N/m) and dissipation D (default 1 s/rad
// or s/m); --no-limits leaves them out (a note lists them).
//
// Writes the header (to stdout without -o); prints what flange does not model
// (limits, mimic joints, transmissions, …) to stderr. A bad URDF (an unknown
// joint type, a link with two parents, a cycle, a missing mass, a number
// that is not finite, …) is an error naming the element and its line, and
// nothing is written. docs/urdf.md has the conventions.
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>

#include "generate.hpp"

namespace {
constexpr const char* usage =
    "usage: flange-urdf robot.urdf [--namespace NAME] [--floating-base] [--stop-stiffness K] "
    "[--stop-dissipation D] [--no-limits] [-o FILE]\n";
}

int main(int argc, char** argv) {
  std::string in, out, ns;
  flange_urdf::generate_options options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o" && i + 1 < argc) out = argv[++i];
    else if (a == "--floating-base") options.floating_base = true;
    else if (a == "--namespace" && i + 1 < argc) ns = argv[++i];
    else if (a == "--no-limits") options.stops = false;
    else if ((a == "--stop-stiffness" || a == "--stop-dissipation") && i + 1 < argc) {
      const std::string v = argv[++i];
      std::size_t used = 0;
      double x = 0;
      try {
        x = std::stod(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != v.size()) {
        std::cerr << "flange-urdf: " << a << " " << v << ": not a number\n";
        return 2;
      }
      (a == "--stop-stiffness" ? options.stop_stiffness : options.stop_dissipation) = x;
    }
    else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
    else {
      std::cerr << usage;
      return 2;
    }
  }
  if (in.empty()) {
    std::cerr << usage;
    return 2;
  }
  std::ifstream f(in);
  if (!f) {
    std::cerr << "flange-urdf: cannot read " << in << '\n';
    return 1;
  }
  std::stringstream text;
  text << f.rdbuf();
  try {
    const auto robot = flange_urdf::parse(in, text.str());
    if (ns.empty()) {
      ns = robot.name;
      for (char& c : ns)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      if (ns.empty() || std::isdigit(static_cast<unsigned char>(ns[0]))) ns = "robot_" + ns;
    }
    std::ostringstream header;
    const auto notes = flange_urdf::generate(robot, in, ns, header, options);
    for (const auto& n : notes) std::cerr << "flange-urdf: note: " << n << '\n';
    if (out.empty()) {
      std::cout << header.str();
    } else {
      std::ofstream o(out);
      o << header.str();
      if (!o) {
        std::cerr << "flange-urdf: cannot write " << out << '\n';
        return 1;
      }
    }
  } catch (const flange_urdf::urdf_error& e) {
    std::cerr << "flange-urdf: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "flange-urdf: error: " << in << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}
