// A URDF robot read with tinyxml2, checked, as plain data: what flange-urdf
// turns into a scene header (generate.hpp). Every error names the element,
// its name and its line; nothing is guessed and nothing is dropped without a
// note (urdf_robot::notes).
#pragma once
#include <tinyxml2.h>

#include <flange/core/component.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace flange_urdf {

struct urdf_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using vec3 = std::array<double, 3>;

struct origin {
  vec3 xyz{0, 0, 0};
  vec3 rpy{0, 0, 0};
  [[nodiscard]] bool translates() const { return xyz != vec3{0, 0, 0}; }
  [[nodiscard]] bool rotates() const { return rpy != vec3{0, 0, 0}; }
};

struct inertial {
  origin at;
  double mass = 0;
  double ixx = 0, ixy = 0, ixz = 0, iyy = 0, iyz = 0, izz = 0;
};

struct link {
  std::string name;
  int line = 0;
  bool has_inertial = false;
  inertial in;
  int parent_joint = -1;
  std::vector<int> child_joints;
};

enum class joint_kind { revolute, continuous, prismatic, fixed, floating, planar };

struct joint {
  std::string name;
  int line = 0;
  joint_kind kind{};
  std::string parent, child;
  int parent_link = -1, child_link = -1;
  origin at;
  vec3 axis{1, 0, 0};
  double damping = 0, friction = 0;
  bool has_limit = false;
  double lower = 0, upper = 0, effort = 0, velocity = 0;
};

struct urdf_robot {
  std::string name;
  std::vector<link> links;
  std::vector<joint> joints;
  int root = -1;                   ///< the link with no parent
  std::vector<std::string> notes;  ///< what flange does not model, each with its element and line
};

namespace detail {

inline std::string where(const std::string& file, const tinyxml2::XMLElement* e) {
  std::ostringstream s;
  s << file << ':' << e->GetLineNum() << ": <" << e->Name();
  if (const char* n = e->Attribute("name")) s << " name=\"" << n << '"';
  s << '>';
  return s.str();
}

[[noreturn]] inline void fail(const std::string& file, const tinyxml2::XMLElement* e, const std::string& what) {
  throw urdf_error(where(file, e) + ": " + what);
}

/// A finite number from attribute `attr` of e (default if absent and allowed).
inline double number(const std::string& file, const tinyxml2::XMLElement* e, const char* attr, const double* fallback) {
  const char* text = e->Attribute(attr);
  if (!text) {
    if (fallback) return *fallback;
    fail(file, e, std::string("the attribute ") + attr + " is missing");
  }
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  while (end && (*end == ' ' || *end == '\t' || *end == '\n')) ++end;
  if (end == text || (end && *end != '\0'))
    fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" is not a number");
  if (!std::isfinite(v)) fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" is not finite");
  return v;
}

/// Three finite numbers from attribute `attr` of e (default if absent).
inline vec3 triple(const std::string& file, const tinyxml2::XMLElement* e, const char* attr, vec3 fallback) {
  const char* text = e->Attribute(attr);
  if (!text) return fallback;
  std::istringstream in(text);
  vec3 v{};
  std::string word;
  for (auto& x : v) {
    if (!(in >> word)) fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" needs three numbers");
    char* end = nullptr;
    x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" has \"" + word + "\", not a number");
    if (!std::isfinite(x)) fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" is not finite");
  }
  if (in >> word) fail(file, e, std::string("the attribute ") + attr + "=\"" + text + "\" has more than three numbers");
  return v;
}

inline origin read_origin(const std::string& file, const tinyxml2::XMLElement* parent) {
  origin o;
  if (const auto* e = parent->FirstChildElement("origin")) {
    o.xyz = triple(file, e, "xyz", {0, 0, 0});
    o.rpy = triple(file, e, "rpy", {0, 0, 0});
  }
  return o;
}

inline std::string required_name(const std::string& file, const tinyxml2::XMLElement* e) {
  const char* n = e->Attribute("name");
  if (!n || !*n) fail(file, e, "it has no name");
  const std::string s(n);
  for (char c : s)
    if (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20)
      fail(file, e, "its name has a character a C++ string literal cannot hold as is (a quote, backslash or control)");
  return s;
}

}  // namespace detail

/// Reads and checks the URDF file `file` (its text in `xml`).
inline urdf_robot parse(const std::string& file, const std::string& xml) {
  using namespace detail;
  // A xacro file (macros, ${…} expressions) is not a URDF yet.
  for (const char* mark : {"${", "xacro:"})
    if (const auto at = xml.find(mark); at != std::string::npos) {
      const auto line = 1 + std::count(xml.begin(), xml.begin() + static_cast<std::ptrdiff_t>(at), '\n');
      throw urdf_error(file + ':' + std::to_string(line) + ": \"" + mark +
                       "\": this is a xacro file, not a URDF; run xacro first (xacro robot.urdf.xacro > robot.urdf) "
                       "and import the URDF it writes");
    }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    std::ostringstream s;
    s << file << ':' << doc.ErrorLineNum() << ": not well-formed XML: " << doc.ErrorStr();
    throw urdf_error(s.str());
  }
  const auto* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot")
    throw urdf_error(file + ":1: the root element is not <robot>");
  urdf_robot r;
  r.name = required_name(file, robot);
  std::map<std::string, int> link_index;
  for (const auto* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
    link l;
    l.name = required_name(file, e);
    l.line = e->GetLineNum();
    if (link_index.count(l.name)) fail(file, e, "a second link of this name");
    if (const auto* in = e->FirstChildElement("inertial")) {
      l.has_inertial = true;
      l.in.at = read_origin(file, in);
      const auto* m = in->FirstChildElement("mass");
      if (!m) fail(file, in, "it has no <mass value=...>");
      l.in.mass = number(file, m, "value", nullptr);
      if (l.in.mass < 0) fail(file, m, "a negative mass");
      const auto* i = in->FirstChildElement("inertia");
      if (!i) fail(file, in, "it has no <inertia ixx=... />");
      const double zero = 0;
      l.in.ixx = number(file, i, "ixx", &zero);
      l.in.ixy = number(file, i, "ixy", &zero);
      l.in.ixz = number(file, i, "ixz", &zero);
      l.in.iyy = number(file, i, "iyy", &zero);
      l.in.iyz = number(file, i, "iyz", &zero);
      l.in.izz = number(file, i, "izz", &zero);
      // Refused here, with the file and line, as MuJoCo refuses it at load
      // (the scene would refuse it only when made).
      flange::Mat3d I;
      I << l.in.ixx, l.in.ixy, l.in.ixz, l.in.ixy, l.in.iyy, l.in.iyz, l.in.ixz, l.in.iyz, l.in.izz;
      try {
        flange::detail::require_inertia(l.name, "link", I);
      } catch (const flange::parameter_error& err) {
        fail(file, i, err.what());
      }
    }
    link_index[l.name] = int(r.links.size());
    r.links.push_back(std::move(l));
  }
  if (r.links.empty()) fail(file, robot, "the robot has no <link>");
  std::set<std::string> joint_names;
  for (const auto* e = robot->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
    joint j;
    j.name = required_name(file, e);
    j.line = e->GetLineNum();
    if (!joint_names.insert(j.name).second) fail(file, e, "a second joint of this name");
    const char* type = e->Attribute("type");
    const std::string t = type ? type : "";
    if (t == "revolute") j.kind = joint_kind::revolute;
    else if (t == "continuous") j.kind = joint_kind::continuous;
    else if (t == "prismatic") j.kind = joint_kind::prismatic;
    else if (t == "fixed") j.kind = joint_kind::fixed;
    else if (t == "floating") j.kind = joint_kind::floating;
    else if (t == "planar") j.kind = joint_kind::planar;
    else
      fail(file, e, "unknown joint type \"" + t +
                        "\" (URDF has revolute, continuous, prismatic, fixed, floating and planar)");
    const auto* p = e->FirstChildElement("parent");
    const auto* c = e->FirstChildElement("child");
    if (!p || !p->Attribute("link")) fail(file, e, "it has no <parent link=...>");
    if (!c || !c->Attribute("link")) fail(file, e, "it has no <child link=...>");
    j.parent = p->Attribute("link");
    j.child = c->Attribute("link");
    if (!link_index.count(j.parent)) fail(file, p, "no link is named \"" + j.parent + "\"");
    if (!link_index.count(j.child)) fail(file, c, "no link is named \"" + j.child + "\"");
    j.parent_link = link_index[j.parent];
    j.child_link = link_index[j.child];
    if (j.parent_link == j.child_link) fail(file, e, "its parent and child are the same link");
    j.at = read_origin(file, e);
    if (const auto* a = e->FirstChildElement("axis")) {
      j.axis = triple(file, a, "xyz", {1, 0, 0});
      const double n = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
      if (!(n > 0) && j.kind != joint_kind::fixed && j.kind != joint_kind::floating) fail(file, a, "a zero axis");
    }
    if (const auto* d = e->FirstChildElement("dynamics")) {
      const double zero = 0;
      j.damping = number(file, d, "damping", &zero);
      j.friction = number(file, d, "friction", &zero);
      if (j.damping < 0 || j.friction < 0) fail(file, d, "negative damping or friction");
    }
    if (const auto* l = e->FirstChildElement("limit")) {
      const double zero = 0;
      j.has_limit = true;
      j.lower = number(file, l, "lower", &zero);
      j.upper = number(file, l, "upper", &zero);
      j.effort = number(file, l, "effort", &zero);
      j.velocity = number(file, l, "velocity", &zero);
    }
    if (const auto* m = e->FirstChildElement("mimic"))
      r.notes.push_back(where(file, m) + ": a mimic joint; flange simulates joint \"" + j.name +
                        "\" as an independent joint (no mimic constraint)");
    for (const char* other : {"calibration", "safety_controller"})
      if (const auto* x = e->FirstChildElement(other))
        r.notes.push_back(where(file, x) + ": not modelled by flange (joint \"" + j.name + "\")");
    link& child = r.links[j.child_link];
    if (child.parent_joint >= 0)
      fail(file, e, "link \"" + j.child + "\" already has a parent joint, \"" + r.joints[child.parent_joint].name +
                        "\"; a URDF is a tree: a link has at most one parent");
    child.parent_joint = int(r.joints.size());
    r.links[j.parent_link].child_joints.push_back(int(r.joints.size()));
    r.joints.push_back(std::move(j));
  }
  for (const auto* e = robot->FirstChildElement("transmission"); e; e = e->NextSiblingElement("transmission"))
    r.notes.push_back(where(file, e) + ": a transmission; flange does not model actuators, give joint drives instead");
  for (const auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "link" && tag != "joint" && tag != "transmission" && tag != "material")
      r.notes.push_back(where(file, e) + ": ignored (flange reads links, joints and their inertials)");
  }
  // One root; every link reached from it (a cycle leaves links unreached).
  for (int i = 0; i < int(r.links.size()); ++i)
    if (r.links[i].parent_joint < 0) {
      if (r.root >= 0)
        throw urdf_error(file + ':' + std::to_string(r.links[i].line) + ": <link name=\"" + r.links[i].name +
                         "\">: a second root link (the first is \"" + r.links[r.root].name +
                         "\"); connect it with a joint, a URDF has one root");
      r.root = i;
    }
  if (r.root < 0)
    throw urdf_error(file + ':' + std::to_string(r.joints.front().line) + ": <joint name=\"" +
                     r.joints.front().name +
                     "\">: every link has a parent joint, so the joints form a cycle; a URDF is a tree");
  std::vector<bool> seen(r.links.size(), false);
  std::vector<int> stack{r.root};
  while (!stack.empty()) {
    const int l = stack.back();
    stack.pop_back();
    seen[l] = true;
    for (int j : r.links[l].child_joints) stack.push_back(r.joints[j].child_link);
  }
  for (int i = 0; i < int(r.links.size()); ++i)
    if (!seen[i])
      throw urdf_error(file + ':' + std::to_string(r.joints[r.links[i].parent_joint].line) + ": <joint name=\"" +
                       r.joints[r.links[i].parent_joint].name + "\">: link \"" + r.links[i].name +
                       "\" is on a cycle of joints, not reached from the root \"" + r.links[r.root].name + "\"");
  // Friction (regularised in flange) is a note: never silent. Limits are
  // noted where they become stops (generate.hpp).
  for (const auto& j : r.joints) {
    if (j.friction > 0)
      r.notes.push_back(file + ':' + std::to_string(j.line) + ": <joint name=\"" + j.name +
                        "\">: its Coulomb friction " + std::to_string(j.friction) +
                        " becomes axis_law::friction, regularised as f_c·tanh(q̇ / v_s) with v_s = 1e-3");
    if ((j.damping > 0 || j.friction > 0) &&
        (j.kind == joint_kind::fixed || j.kind == joint_kind::floating || j.kind == joint_kind::planar))
      r.notes.push_back(file + ':' + std::to_string(j.line) + ": <joint name=\"" + j.name +
                        "\">: damping and friction on a " +
                        (j.kind == joint_kind::planar ? "planar" : j.kind == joint_kind::floating ? "floating" : "fixed") +
                        " joint are not modelled");
  }
  return r;
}

}  // namespace flange_urdf
