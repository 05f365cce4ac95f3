// The scene header for a checked URDF robot (urdf_model.hpp):
//
//   namespace <ns> {
//   inline auto make_scene() { return flange::scene(World, bodies, joints, joint origins, connections); }
//   }
//
// Conventions (docs/urdf.md):
// - a URDF link is a connection set: the World's frame_b for the root, else
//   its parent joint's frame_b; its <inertial> is a Body<link, cm::offset>
//   at that frame, r_CM = the inertial's xyz and J = Pᵀ·I·P, P the
//   inertial's rpy as flange's orientation (URDF gives I in the turned frame);
// - a joint's <origin> is a FixedTranslation (xyz only) or a FixedRotation
//   (rpy, URDF's fixed-axis roll–pitch–yaw) named "<joint>_origin", between
//   the parent link and the joint's frame_a; none when it is zero;
// - revolute and continuous are Revolute, prismatic Prismatic, floating
//   FreeMotion, planar Planar (normal = the axis), fixed merges the child
//   into the parent through its origin; an axis along +x, +y or +z is a
//   compile-time axis (2-D arithmetic), any other a run-time one;
// - <dynamics damping> is axis_law::spring_damper with c = 0; with friction,
//   axis_law::friction (regularised Coulomb); gravity is −9.81 m/s² along z;
// - a revolute or prismatic joint's <limit lower upper> (lower < upper) is a
//   compliant stop at each bound, axis_law::limited<…> (joints/axis_law.hpp),
//   with the stiffness and dissipation of generate_options; effort and
//   velocity limits are not modelled.
#pragma once
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include <flange/math/rotation.hpp>

#include "urdf_model.hpp"

namespace flange_urdf {

namespace detail {

inline std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}
inline std::string vec(const vec3& v) {
  std::string s = "{";  // appended, not concatenated: GCC 12 warns wrongly on "{" + … (bug 105329)
  s.append(num(v[0])).append(", ").append(num(v[1])).append(", ").append(num(v[2])).append("}");
  return s;
}

/// "axis::x" for +x, +y, +z exactly; empty for any other axis.
inline std::string typed_axis(const vec3& a) {
  if (a == vec3{1, 0, 0}) return "axis::x";
  if (a == vec3{0, 1, 0}) return "axis::y";
  if (a == vec3{0, 0, 1}) return "axis::z";
  return "";
}

struct writer {
  const urdf_robot& r;
  std::string file;
  bool driven = false;  ///< one-coordinate joints take a drive: shared_drive<"name", Drive>
  std::vector<std::string> components, connections;
  std::set<std::string> names{"world"};
  std::vector<std::string> link_frame;
  std::vector<std::string> renamed;  ///< names with characters made '_'
  /// Each floating joint's component name and its <origin>: the pose home_state() sets.
  std::vector<std::pair<std::string, origin>> homes;
  /// Joint limits as stops: on, and their stiffness and dissipation.
  bool stops = true;
  double stop_stiffness = 0, stop_dissipation = 0;

  /// Whether joint j's position limits become stops.
  bool has_stops(const joint& j) const {
    return stops && j.has_limit && j.lower < j.upper &&
           (j.kind == joint_kind::revolute || j.kind == joint_kind::prismatic);
  }
  /// The axis law with its stops, if any: "axis_law::limited<axis_law::friction>".
  std::string law(const joint& j, const std::string& inner) const {
    if (!has_stops(j)) return inner;
    return "axis_law::limited<" + (inner == "axis_law::none" ? std::string() : inner) + ">";
  }
  /// The stops' initialiser, last in the joint's parameters: ".stop = {…}".
  std::string stop_init(const joint& j) const {
    if (!has_stops(j)) return "";
    return ".stop = {.lower = " + num(j.lower) + ", .upper = " + num(j.upper) + ", .stiffness = " +
           num(stop_stiffness) + ", .dissipation = " + num(stop_dissipation) + "}";
  }

  /// A component name not yet used: `wanted` with every character flange's
  /// names cannot hold as is ('.', which separates a component from its frame,
  /// a space, …) made '_', or with a suffix if taken (noted).
  std::string unique(const std::string& wanted, const std::string& suffix, std::vector<std::string>& notes) {
    std::string base = wanted;
    for (char& c : base)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
            static_cast<unsigned char>(c) >= 0x80))
        c = '_';
    std::string n = base;
    for (int k = 2; names.count(n); ++k) n = base + suffix + (k > 2 ? std::to_string(k) : "");
    if (n != base) notes.push_back("the component for \"" + wanted + "\" is named \"" + n + "\" (the name is taken)");
    else if (n != wanted) renamed.push_back("\"" + wanted + "\" -> \"" + n + "\"");
    names.insert(n);
    return n;
  }


  /// Mass in the subtree of link l (through every joint).
  double subtree_mass(int l) const {
    double m = r.links[l].has_inertial ? r.links[l].in.mass : 0;
    for (int j : r.links[l].child_joints) m += subtree_mass(r.joints[j].child_link);
    return m;
  }

  void body(int l, std::vector<std::string>& notes) {
    const link& k = r.links[l];
    if (!k.has_inertial) return;
    const std::string n = unique(k.name, "_link", notes);
    const Eigen::Matrix3d P = flange::orientation::rpy(k.in.at.rpy[0], k.in.at.rpy[1], k.in.at.rpy[2]).R;
    Eigen::Matrix3d I;
    I << k.in.ixx, k.in.ixy, k.in.ixz, k.in.ixy, k.in.iyy, k.in.iyz, k.in.ixz, k.in.iyz, k.in.izz;
    const Eigen::Matrix3d PIP = P.transpose() * I * P;
    const Eigen::Matrix3d J = (PIP + PIP.transpose()) / 2;  // exactly symmetric
    std::string Js = "(flange::Mat3d() << ";
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Js += num(J(i, j)) + (i == 2 && j == 2 ? "" : ", ");
    Js += ").finished()";
    components.push_back("Body<\"" + n + "\", cm::offset>({.m = " + num(k.in.mass) + ", .J = " + Js +
                         ", .r_cm = " + vec(k.in.at.xyz) + "})");
    connections.push_back("connect<\"" + link_frame[l] + "\", \"" + n + ".frame_a\">");
  }

  void joint_of(int ji, std::vector<std::string>& notes) {
    const joint& j = r.joints[ji];
    std::string at = link_frame[j.parent_link];
    // A floating joint's state is its child's pose in the parent link's frame
    // (the world's, for a base), as MuJoCo's qpos: its <origin> is not a
    // component but the pose home_state() sets.
    if (j.kind != joint_kind::floating && (j.at.translates() || j.at.rotates())) {
      const std::string o = unique(j.name + "_origin", "_", notes);
      if (j.at.rotates())
        components.push_back("FixedRotation<\"" + o + "\">({.r = " + vec(j.at.xyz) + ", .R = orientation::rpy(" +
                             num(j.at.rpy[0]) + ", " + num(j.at.rpy[1]) + ", " + num(j.at.rpy[2]) + ")})");
      else components.push_back("FixedTranslation<\"" + o + "\">({.d = " + vec(j.at.xyz) + "})");
      connections.push_back("connect<\"" + at + "\", \"" + o + ".frame_a\">");
      at = o + ".frame_b";
    }
    if (j.kind == joint_kind::fixed) {
      link_frame[j.child_link] = at;
      return;
    }
    const std::string n = unique(j.name, "_joint", notes);
    const std::string typed = typed_axis(j.axis);
    const std::string axis = typed.empty() ? "axis::any" : typed;
    const std::string n_param = typed.empty() ? ".n = " + vec(j.axis) + ", " : "";
    std::string c;
    // A driven joint: its drive type and the .tau / .f initialiser (after .n).
    const std::string drive_type = "shared_drive<\"" + n + "\", Drive>";
    const std::string drive_init = driven ? ".tau = drive_for<\"" + n + "\">(drive), " : "";
    const std::string force_init = driven ? ".f = drive_for<\"" + n + "\">(drive), " : "";
    switch (j.kind) {
      case joint_kind::revolute:
      case joint_kind::continuous: {
        const std::string tau = driven ? ", " + drive_type : "";
        const std::string stop = stop_init(j), stop_more = stop.empty() ? "" : ", " + stop;
        if (j.friction > 0)
          c = "Revolute<\"" + n + "\", " + axis + ", " + law(j, "axis_law::friction") + tau + ">({" + n_param +
              drive_init + ".d = " + num(j.damping) + ", .f_c = " + num(j.friction) + ", .v_s = 1e-3" + stop_more + "})";
        else if (j.damping > 0)
          c = "Revolute<\"" + n + "\", " + axis + ", " + law(j, "axis_law::spring_damper") + tau + ">({" + n_param +
              drive_init + ".c = 0, .d = " + num(j.damping) + stop_more + "})";
        else if (driven || !stop.empty())
          c = "Revolute<\"" + n + "\", " + axis + ", " + law(j, "axis_law::none") + tau + ">({" + n_param + drive_init +
              stop + "})";
        else c = "Revolute<\"" + n + "\", " + axis + ">" + (typed.empty() ? "({.n = " + vec(j.axis) + "})" : "{}");
        break;
      }
      case joint_kind::prismatic: {
        const std::string force = driven ? drive_type : "double";
        const std::string stop = stop_init(j), stop_more = stop.empty() ? "" : ", " + stop;
        if (j.friction > 0)
          c = "Prismatic<\"" + n + "\", " + axis + ", " + force + ", " + law(j, "axis_law::friction") + ">({" +
              n_param + force_init + ".d = " + num(j.damping) + ", .f_c = " + num(j.friction) + ", .v_s = 1e-3" +
              stop_more + "})";
        else if (j.damping > 0)
          c = "Prismatic<\"" + n + "\", " + axis + ", " + force + ", " + law(j, "axis_law::spring_damper") + ">({" +
              n_param + force_init + ".c = 0, .d = " + num(j.damping) + stop_more + "})";
        else if (!stop.empty())
          c = "Prismatic<\"" + n + "\", " + axis + ", " + force + ", " + law(j, "axis_law::none") + ">({" + n_param +
              force_init + stop + "})";
        else c = "Prismatic<\"" + n + "\", " + axis + ", " + force + ">({" + n_param + force_init + "})";
        break;
      }
      case joint_kind::floating:
        c = "FreeMotion<\"" + n + "\">{}";
        homes.emplace_back(n, j.at);
        break;
      case joint_kind::planar: {
        // The plane's first direction: a coordinate axis not along the normal.
        const vec3 first = std::abs(j.axis[0]) < 0.9 * std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] +
                                                                 j.axis[2] * j.axis[2])
                               ? vec3{1, 0, 0}
                               : vec3{0, 1, 0};
        c = "Planar<\"" + n + "\">({.n = " + vec(j.axis) + ", .n_x = " + vec(first) + "})";
        notes.push_back(file + ':' + std::to_string(j.line) + ": <joint name=\"" + j.name +
                        "\">: a planar joint; its in-plane coordinates are along " + vec(first) +
                        " projected on the plane, and the normal");
        break;
      }
      case joint_kind::fixed: break;
    }
    components.push_back(c);
    connections.push_back("connect<\"" + at + "\", \"" + n + ".frame_a\">");
    link_frame[j.child_link] = n + ".frame_b";
  }

  void walk(int l, std::vector<std::string>& notes) {
    body(l, notes);
    for (int ji : r.links[l].child_joints) {
      const joint& j = r.joints[ji];
      if (j.kind != joint_kind::fixed && !(subtree_mass(j.child_link) > 0))
        throw urdf_error(file + ':' + std::to_string(r.links[j.child_link].line) + ": <link name=\"" +
                         r.links[j.child_link].name + "\">: joint \"" + j.name +
                         "\" moves it, but neither it nor anything attached to it has an <inertial> with mass; "
                         "give it one");
      joint_of(ji, notes);
      walk(j.child_link, notes);
    }
  }
};

}  // namespace detail

/// How a robot is imported.
struct generate_options {
  /// The root link moves freely (a FreeMotion "floating_base" from the World)
  /// where the URDF welds it to the World (no floating joint at the root).
  bool floating_base = false;
  /// Revolute and prismatic <limit lower upper> become compliant stops
  /// (axis_law::limited) of this stiffness [N m/rad, N/m] and dissipation
  /// [s/rad, s/m] (Simbody's MobilityLinearStop); off, limits are a note.
  bool stops = true;
  double stop_stiffness = 1e4, stop_dissipation = 1.0;
};

/// Writes the scene header for robot r (read from `file`) into out, in
/// namespace ns. Returns the notes (also written into the header).
inline std::vector<std::string> generate(const urdf_robot& r, const std::string& file, const std::string& ns,
                                         std::ostream& out, const generate_options& o = {}) {
  std::vector<std::string> notes = r.notes, driven_notes;
  detail::writer w{r, file, false, {}, {}, {}, std::vector<std::string>(r.links.size()), {}, {}};
  detail::writer wd{r, file, true, {}, {}, {}, std::vector<std::string>(r.links.size()), {}, {}};
  w.link_frame[r.root] = wd.link_frame[r.root] = "world.frame_b";
  if (!(o.stop_stiffness >= 0 && o.stop_dissipation >= 0 && std::isfinite(o.stop_stiffness) &&
        std::isfinite(o.stop_dissipation)))
    throw urdf_error("--stop-stiffness " + detail::num(o.stop_stiffness) + ", --stop-dissipation " +
                     detail::num(o.stop_dissipation) + ": a stop's stiffness and dissipation are finite and not negative");
  for (auto* x : {&w, &wd}) {
    x->stops = o.stops;
    x->stop_stiffness = o.stop_stiffness;
    x->stop_dissipation = o.stop_dissipation;
  }
  {
    // Limits: one note for all.
    std::string limited;
    int n_limited = 0, n_equal = 0;
    for (const auto& j : r.joints)
      if (j.has_limit && (j.kind == joint_kind::revolute || j.kind == joint_kind::prismatic)) {
        if (j.lower < j.upper) limited += std::string(n_limited++ ? ", " : "") + "\"" + j.name + "\" (line " + std::to_string(j.line) + ")";
        else ++n_equal;
      }
    if (n_limited > 0 && o.stops)
      notes.push_back(file + ": " + std::to_string(n_limited) + " joint(s) have position limits, modelled as compliant "
                      "stops (stiffness " + detail::num(o.stop_stiffness) + ", dissipation " +
                      detail::num(o.stop_dissipation) + "; --stop-stiffness, --stop-dissipation; effort and velocity "
                      "limits are not modelled): " + limited);
    else if (n_limited > 0)
      notes.push_back(file + ": " + std::to_string(n_limited) + " joint(s) have position, effort and velocity limits, "
                      "not modelled (--no-limits): " + limited);
    if (n_equal > 0)
      notes.push_back(file + ": " + std::to_string(n_equal) + " joint(s) have <limit> with lower >= upper (URDF's "
                      "default 0, 0): no stops");
  }
  const std::string root = "\"" + r.links[r.root].name + "\"";
  const bool root_has_mass = r.links[r.root].has_inertial && r.links[r.root].in.mass > 0;
  if (o.floating_base) {
    if (!(w.subtree_mass(r.root) > 0))
      throw urdf_error(file + ": --floating-base: the robot has no mass to float");
    for (auto* x : {&w, &wd}) {
      const std::string n = x->unique("floating_base", "_", driven_notes);
      x->components.push_back("FreeMotion<\"" + n + "\">{}");
      x->connections.push_back("connect<\"world.frame_b\", \"" + n + ".frame_a\">");
      x->link_frame[r.root] = n + ".frame_b";
      x->homes.emplace_back(n, origin{});
    }
    notes.push_back("--floating-base: the root link " + root + " moves freely (FreeMotion \"floating_base\"; its state "
                    "is the link's pose and velocity in the world)");
  } else if (r.links[r.root].name == "world" && r.links[r.root].has_inertial) {
    notes.push_back("the root link is named \"world\" but has an inertial: it is welded to the World");
  } else if (root_has_mass) {
    notes.push_back("the root link " + root + " has mass and no floating joint: it is welded to the World (a fixed "
                    "base); --floating-base lets it move freely");
  }
  w.walk(r.root, notes);
  wd.walk(r.root, driven_notes);
  if (!w.renamed.empty()) {
    std::string list;
    for (std::size_t k = 0; k < w.renamed.size(); ++k) list += (k ? ", " : "") + w.renamed[k];
    notes.push_back(std::to_string(w.renamed.size()) + " name(s) hold characters a flange name cannot ('.' separates "
                    "a component from its frame): " + list);
  }
  int moving = 0;
  for (const auto& j : r.joints) moving += j.kind != joint_kind::fixed;
  out << "// Generated by flange-urdf from " << file << "; do not edit.\n"
      << "// Robot \"" << r.name << "\": " << r.links.size() << " links, " << r.joints.size() << " joints ("
      << moving << " moving). docs/urdf.md has the conventions.\n";
  if (!notes.empty()) {
    out << "//\n// Not modelled, or modelled differently (also printed by flange-urdf):\n";
    for (const auto& n : notes) out << "//   " << n << '\n';
  }
  out << "#pragma once\n// The scene and its equations; integrating it needs <flange/flange.hpp> as well.\n"
      << "#include <flange/equations_of_motion.hpp>\n\nnamespace " << ns << " {\n\n"
      << "/// The robot \"" << r.name << "\" as a flange scene (gravity −9.81 m/s² along z).\n"
      << "inline auto make_scene() {\n  using namespace flange;\n  return flange::scene(\n"
      << "      World<\"world\">({.g = {0, 0, -9.81}})";
  for (const auto& c : w.components) out << ",\n      " << c;
  for (const auto& c : w.connections) out << ",\n      " << c;
  out << ");\n}\n\n"
      << "/// The same robot with every revolute and prismatic joint driven: joint \"j\"'s\n"
      << "/// torque or force is drive(joint_tag<\"j\">{}, t, x), resolved at compile time.\n"
      << "template <class Drive>\ninline auto make_scene(Drive drive) {\n  using namespace flange;\n"
      << "  return flange::scene(\n      World<\"world\">({.g = {0, 0, -9.81}})";
  for (const auto& c : wd.components) out << ",\n      " << c;
  for (const auto& c : wd.connections) out << ",\n      " << c;
  out << ");\n}\n\n/// The type of the undriven scene.\nusing scene_type = decltype(make_scene());\n\n"
      << "/// The state the URDF draws: every joint at zero and at rest, each floating\n"
      << "/// joint at its <origin> (its state is its child's pose in the parent link's frame).\n"
      << "template <class S>\ninline typename S::state_type home_state(const S& scene) {\n"
      << "  auto x = flange::neutral_state(scene);\n";
  for (const auto& [n, at] : w.homes)
    out << "  flange::set_joint<\"" << n << "\">(scene, x, {.r = " << detail::vec(at.xyz)
        << ", .v = {}, .R = flange::orientation::rpy(" << detail::num(at.rpy[0]) << ", " << detail::num(at.rpy[1])
        << ", " << detail::num(at.rpy[2]) << "), .w = {}});\n";
  out << "  return x;\n}\n\n}  // namespace " << ns << '\n';
  return notes;
}

}  // namespace flange_urdf
