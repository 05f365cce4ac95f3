// A recorded simulation as a self-contained HTML page that plays it in 3-D
// (three.js, inlined), with a time slider, play/pause and a plot of chosen
// variables under the scene. It works offline, opened from the disk.
//
//   viewer::recording rec(arm);                               // joint coordinates are plotted
//   rec.plot("energy [J]", [](const auto& s) { return s.energy(); });
//   odeint::integrate_const(stepper, arm, x, 0.0, 4.0, 0.01, record(arm, rec.observer()));
//   rec.write_html("arm.html", viewer::three_js());           // three.js from tools/install-deps.sh --viewer
//
// Drawn: every Body as a sphere at its centre of mass (radius from its mass),
// BodyBox and BodyCylinder with their shapes, FixedTranslation and
// FixedRotation as rods, joints as small markers, the World's axes; each
// Contact's shapes (a half-space as a square 4 m across) and, at each
// sample, an arrow per contact point for the force on frame_a's shape
// (0.3 m for the 90th percentile of the forces while touching). Frames
// are recorded as poses (r, and the orientation as a quaternion) at each
// observed time; drawables refer to frames, so the page size grows with
// frames × samples. Not in the umbrella header (it reads a file and uses
// std::function); recording is outside the stepping loop.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "flange/components/body_shape.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/dynamics/recover.hpp"
#include "flange/errors.hpp"
#include "flange/forces/contact.hpp"

namespace flange::viewer {

/// The path of three.js's UMD build: $FLANGE_THREE_JS, else where
/// tools/install-deps.sh --viewer puts it (tools/viewer/node_modules, seen
/// from the source tree given at build time as FLANGE_SOURCE_DIR), else "".
inline std::string three_js() {
  if (const char* p = std::getenv("FLANGE_THREE_JS")) return p;
#ifdef FLANGE_SOURCE_DIR
  return std::string(FLANGE_SOURCE_DIR) + "/tools/viewer/node_modules/three/build/three.min.js";
#else
  return "tools/viewer/node_modules/three/build/three.min.js";
#endif
}

namespace detail {
inline void number(std::ostream& o, double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", std::isfinite(x) ? x : 0.0);
  o << b;
}
inline void numbers(std::ostream& o, std::initializer_list<double> xs) {
  bool first = true;
  for (double x : xs) {
    if (!first) o << ',';
    number(o, x);
    first = false;
  }
}
/// A quaternion (x, y, z, w) of the active rotation M (body → world).
inline Eigen::Quaterniond quat(const Mat3d& M) { return Eigen::Quaterniond(M).normalized(); }
}  // namespace detail

template <class S>
class recording {
 public:
  using solution = dae_solution<S, double>;
  explicit recording(const S& scene) : scene_(scene) {
    // The default plot: every joint coordinate, named by its joint.
    for (int c = 0; c < S::n_components; ++c)
      for (int k = 0; k < S::table.nq[c]; ++k) {
        std::string n(S::table.names[c]);  // appended: GCC 12 warns wrongly on a + b (bug 105329)
        if (S::table.nq[c] > 1) n.append("[").append(std::to_string(k)).append("]");
        const int q = S::tree.q_offset[c] + k;
        series_.push_back({std::move(n), [q](const solution& s) { return s.q[q]; }, {}});
      }
  }

  /// Plots f(solution) under the scene, as `name`. The first call replaces
  /// the default plot of the joint coordinates.
  template <class F>
  recording& plot(std::string name, F f) {
    if (!custom_) series_.clear(), custom_ = true;
    series_.push_back({std::move(name), std::function<double(const solution&)>(std::move(f)), {}});
    return *this;
  }

  /// Reserves room for n samples. Recording stores the trajectory, so it
  /// allocates as it grows unless reserved; the derivative never does.
  void reserve(std::size_t n) {
    times_.reserve(n);
    poses_.reserve(n * 7 * S::n_frames);
    arrows_.reserve(n * 6 * contact_points());
    for (auto& x : series_) x.values.reserve(n);
  }
  /// Records one observed solution (recover's).
  void add(const solution& s) {
    times_.push_back(s.t);
    for (int f = 0; f < S::n_frames; ++f) {
      const auto& k = s.frames[f];
      const Eigen::Quaterniond q = detail::quat(k.R.transpose());
      poses_.insert(poses_.end(), {k.r.x(), k.r.y(), k.r.z(), q.x(), q.y(), q.z(), q.w()});
    }
    for (auto& x : series_) x.values.push_back(x.f(s));
    // Each contact point's force on frame_a's shape, where it acts.
    flange::detail::for_each_component(scene_, [&](auto i, const auto& c) {
      using C = std::remove_cvref_t<decltype(c)>;
      if constexpr (requires { C::pairs_two_bodies; }) {
        constexpr int f = S::table.frame_base[decltype(i)::value];
        for (int k = 0; k < C::points; ++k) {
          const auto cp = c.evaluate(k, s.frames[f], s.frames[f + 1]);
          arrows_.insert(arrows_.end(), {cp.point.x(), cp.point.y(), cp.point.z(), cp.force.x(), cp.force.y(),
                                         cp.force.z()});
        }
      }
    });
  }
  /// An observer for record(scene, …).
  auto observer() {
    return [this](const solution& s) { add(s); };
  }
  [[nodiscard]] std::size_t samples() const { return times_.size(); }
  /// The scene's contact points (an arrow each at every sample).
  static constexpr int contact_points() { return contact_points_from(std::make_integer_sequence<int, S::n_components>{}); }

  /// Writes the page: the recording as JSON, the player, and three.js
  /// (read from three_js_path and inlined, so the page works offline).
  void write_html(const std::string& path, const std::string& three_js_path, const std::string& title = "flange") const {
    std::ifstream lib(three_js_path);
    if (!lib)
      throw error("flange viewer: three.js not found at \"" + three_js_path +
                  "\"; run tools/install-deps.sh --viewer, or set FLANGE_THREE_JS to three.min.js");
    std::stringstream three;
    three << lib.rdbuf();
    std::ofstream out(path);
    if (!out) throw error("flange viewer: cannot write \"" + path + "\"");
    out << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>" << title << "</title>\n" << style
        << "</head><body>\n<div id=\"view\"></div>\n<div id=\"controls\"><button id=\"play\">pause</button>"
        << "<input id=\"time\" type=\"range\" min=\"0\" max=\"" << (times_.empty() ? 0 : times_.size() - 1)
        << "\" value=\"0\"><span id=\"clock\"></span></div>\n<canvas id=\"plot\" width=\"900\" height=\"220\"></canvas>\n"
        << "<div id=\"status\">loading</div>\n<script>" << three.str() << "</script>\n<script>\nconst data = ";
    json(out, title);
    out << ";\n" << player << "</script></body></html>\n";
  }

 private:
  struct series {
    std::string name;
    std::function<double(const solution&)> f;
    std::vector<double> values;
  };

  /// A component's contact points: a Contact's, else none.
  template <class C>
  static constexpr int points_of() {
    if constexpr (requires { C::pairs_two_bodies; }) return C::points;
    else return 0;
  }
  template <int... C>
  static constexpr int contact_points_from(std::integer_sequence<int, C...>) {
    return (0 + ... + points_of<typename S::template component_type<C>>());
  }

  // A Contact's shape at its frame: "shape" items the player draws pale.
  template <class Item>
  static void contact_shape_item(Item& item, std::string_view name, int f, const contact_shape::sphere& s) {
    item("contact_sphere", name, f, {0, 0, 0, s.radius});
  }
  template <class Item>
  static void contact_shape_item(Item& item, std::string_view name, int f, const contact_shape::box& b) {
    const Eigen::Quaterniond q = detail::quat(b.axes.transpose());
    item("contact_box", name, f,
         {b.center.x(), b.center.y(), b.center.z(), q.x(), q.y(), q.z(), q.w(), 2 * b.half_extents.x(),
          2 * b.half_extents.y(), 2 * b.half_extents.z()});
  }
  template <class Item>
  static void contact_shape_item(Item& item, std::string_view name, int f, const contact_shape::capsule& c) {
    // three's capsule runs along y: turned onto the axis.
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Vec3d::UnitY(), c.axis);
    item("contact_capsule", name, f,
         {c.center.x(), c.center.y(), c.center.z(), q.x(), q.y(), q.z(), q.w(), c.radius, 2 * c.half_length});
  }
  template <class Item>
  static void contact_shape_item(Item& item, std::string_view name, int f, const contact_shape::half_space& h) {
    // A square 4 m across on the boundary, its normal along n.
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Vec3d::UnitZ(), h.n);
    const Vec3d c = h.offset * h.n;
    item("contact_plane", name, f, {c.x(), c.y(), c.z(), q.x(), q.y(), q.z(), q.w(), 4.0});
  }

  void json(std::ostream& o, const std::string& title) const {
    o << "{\"title\":\"" << title << "\",\"nframes\":" << S::n_frames << ",\"t\":[";
    for (std::size_t i = 0; i < times_.size(); ++i) o << (i ? "," : ""), detail::number(o, times_[i]);
    o << "],\"poses\":[";
    for (std::size_t i = 0; i < poses_.size(); ++i) o << (i ? "," : ""), detail::number(o, poses_[i]);
    o << "],\"arrows\":[";
    for (std::size_t i = 0; i < arrows_.size(); ++i) o << (i ? "," : ""), detail::number(o, arrows_[i]);
    o << "],\"series\":[";
    for (std::size_t j = 0; j < series_.size(); ++j) {
      o << (j ? "," : "") << "{\"name\":\"" << series_[j].name << "\",\"v\":[";
      for (std::size_t i = 0; i < series_[j].values.size(); ++i) o << (i ? "," : ""), detail::number(o, series_[j].values[i]);
      o << "]}";
    }
    o << "],\"items\":[";
    bool first = true;
    auto item = [&](const std::string& kind, std::string_view name, int frame, std::initializer_list<double> nums) {
      o << (first ? "" : ",") << "{\"kind\":\"" << kind << "\",\"name\":\"" << name << "\",\"frame\":" << frame
        << ",\"p\":[";
      detail::numbers(o, nums);
      o << "]}";
      first = false;
    };
    // A body without a shape: a sphere at its centre of mass, 0.05 m for 1 kg, growing as m^(1/3).
    auto sphere = [&](std::string_view name, int frame, double m, const Vec3d& c) {
      item("sphere", name, frame, {c.x(), c.y(), c.z(), 0.05 * std::cbrt(std::max(m, 1e-3))});
    };
    flange::detail::for_each_component(scene_, [&](auto i, const auto& c) {
      using C = std::remove_cvref_t<decltype(c)>;
      constexpr int f = S::table.frame_base[decltype(i)::value];
      if constexpr (C::kind == role::body) {
        sphere(C::name.view(), f, c.m(), c.r_cm());
      } else if constexpr (carries_body<C>) {
        // A shaped body: its mesh along r, centred at r/2, turned to its axes.
        const Mat3d T = flange::detail::shape_axes(c.r().norm() > 0 ? c.r() : Vec3d::UnitX(), Vec3d(0, 1, 0));
        const Eigen::Quaterniond q = detail::quat(T.transpose());
        const Vec3d m = c.r() / 2, s = c.size();
        if constexpr (std::is_same_v<typename C::shape_type, shape_kind::none>) {
          sphere(C::name.view(), f, c.m(), c.r_cm());
        } else {
          const std::string kind = std::is_same_v<typename C::shape_type, shape_kind::box> ? "box" : "cylinder";
          item(kind, C::name.view(), f, {m.x(), m.y(), m.z(), q.x(), q.y(), q.z(), q.w(), s.x(), s.y(), s.z()});
        }
        item("rod", C::name.view(), f, {double(f + 1)});
      } else if constexpr (C::kind == role::rigid) {
        item("rod", C::name.view(), f, {double(f + 1)});
      } else if constexpr (C::kind == role::joint) {
        item("joint", C::name.view(), f, {});
      } else if constexpr (C::kind == role::world) {
        item("world", C::name.view(), f, {});
      } else if constexpr (requires { C::pairs_two_bodies; }) {
        contact_shape_item(item, C::name.view(), f, c.geometry().a);
        contact_shape_item(item, C::name.view(), f + 1, c.geometry().b);
      }
    });
    o << "]}";
  }

  static constexpr const char* style =
      "<style>body{margin:0;font:13px sans-serif;background:#fafafa}#view{width:900px;height:520px}"
      "#controls{width:900px;display:flex;gap:8px;align-items:center;padding:4px 0}#time{flex:1}"
      "#status{color:#888;font-size:11px}</style>\n";

  // The player: a three.js scene built from data.items, posed from
  // data.poses at the slider's sample; play/pause; a mouse orbit; the plot
  // with a cursor. It reports what it drew into #status (the browser test
  // reads it).
  static constexpr const char* player = R"JS(
const n = data.t.length, F = data.nframes;
const view = document.getElementById('view'), status = document.getElementById('status');
const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
renderer.setSize(900, 520);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xfafafa);
const camera = new THREE.PerspectiveCamera(45, 900 / 520, 0.01, 100);
camera.up.set(0, 0, 1);
scene.add(new THREE.HemisphereLight(0xffffff, 0x888888, 0.9));
const sun = new THREE.DirectionalLight(0xffffff, 0.6); sun.position.set(2, -3, 5); scene.add(sun);
const colors = [0x3b7dd8, 0xd8743b, 0x4caf50, 0x9c27b0, 0xc0392b, 0x16a085];
const frames = [];
for (let f = 0; f < F; ++f) { const g = new THREE.Group(); scene.add(g); frames.push(g); }
const rods = [];
let meshes = 0, ci = 0;
for (const it of data.items) {
  const p = it.p, mat = new THREE.MeshStandardMaterial({color: colors[ci++ % colors.length], roughness: 0.6});
  let m = null;
  if (it.kind === 'sphere') { m = new THREE.Mesh(new THREE.SphereGeometry(p[3], 24, 16), mat); m.position.set(p[0], p[1], p[2]); }
  else if (it.kind === 'box' || it.kind === 'cylinder') {
    m = it.kind === 'box' ? new THREE.Mesh(new THREE.BoxGeometry(p[7], p[8], p[9]), mat)
                          : new THREE.Mesh(new THREE.CylinderGeometry(p[8] / 2, p[8] / 2, p[7], 24), mat);
    if (it.kind === 'cylinder') m.geometry.rotateZ(-Math.PI / 2);  // three's cylinder runs along y; ours along x
    m.position.set(p[0], p[1], p[2]); m.quaternion.set(p[3], p[4], p[5], p[6]);
  }
  else if (it.kind === 'joint') m = new THREE.Mesh(new THREE.SphereGeometry(0.025, 16, 12), new THREE.MeshStandardMaterial({color: 0x555555}));
  else if (it.kind === 'rod') {
    const geo = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]);
    const line = new THREE.Line(geo, new THREE.LineBasicMaterial({color: 0x222222}));
    scene.add(line); rods.push({line: line, a: it.frame, b: p[0]}); continue;
  }
  else if (it.kind === 'world') { frames[it.frame].add(new THREE.AxesHelper(0.3)); continue; }
  else if (it.kind.startsWith('contact_')) {
    // A contact shape: pale and translucent, over the body's own drawing.
    const pale = new THREE.MeshStandardMaterial({color: it.kind === 'contact_plane' ? 0xc8c8c8 : 0x9e9e9e, roughness: 0.8, transparent: true, opacity: it.kind === 'contact_plane' ? 0.3 : 0.45, side: THREE.DoubleSide, depthWrite: it.kind !== 'contact_plane'});
    if (it.kind === 'contact_sphere') m = new THREE.Mesh(new THREE.SphereGeometry(p[3], 24, 16), pale);
    else if (it.kind === 'contact_box') m = new THREE.Mesh(new THREE.BoxGeometry(p[7], p[8], p[9]), pale);
    else if (it.kind === 'contact_capsule') m = new THREE.Mesh(new THREE.CapsuleGeometry(p[7], p[8], 8, 16), pale);
    else if (it.kind === 'contact_plane') m = new THREE.Mesh(new THREE.PlaneGeometry(p[7], p[7]), pale);
    m.position.set(p[0], p[1], p[2]);
    if (it.kind !== 'contact_sphere') m.quaternion.set(p[3], p[4], p[5], p[6]);
  }
  if (m) { frames[it.frame].add(m); ++meshes; }
}
// One arrow per contact point: the force on frame_a's shape at its point,
// 0.3 m for the 90th percentile of the forces while touching (impacts
// longer, up to 0.6 m).
const A = data.arrows.length / (6 * Math.max(n, 1)), arrows = [];
const touching = [];
for (let q = 0; q < data.arrows.length; q += 6) { const f = Math.hypot(data.arrows[q + 3], data.arrows[q + 4], data.arrows[q + 5]); if (f > 0) touching.push(f); }
touching.sort((a, b) => a - b);
const fmax = touching.length ? touching[Math.floor(0.9 * (touching.length - 1))] : 0;
for (let a = 0; a < A; ++a) { const h = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, 0xc0392b); h.visible = false; scene.add(h); arrows.push(h); }
// The camera looks at the middle of everything the recording visits.
const box = new THREE.Box3();
for (let i = 0; i < n; ++i) for (let f = 0; f < F; ++f) { const o = (i * F + f) * 7; box.expandByPoint(new THREE.Vector3(data.poses[o], data.poses[o + 1], data.poses[o + 2])); }
const center = box.getCenter(new THREE.Vector3()), radius = Math.max(box.getSize(new THREE.Vector3()).length(), 0.5);
let az = -0.9, el = 0.45, dist = 1.3 * radius;
// Up is z, or a ground's normal where a contact has one (the camera stays on its open side).
const up = new THREE.Vector3(0, 0, 1);
for (const it of data.items) if (it.kind === 'contact_plane') { up.set(0, 0, 1).applyQuaternion(new THREE.Quaternion(it.p[3], it.p[4], it.p[5], it.p[6])); break; }
const e1 = new THREE.Vector3(1, 0, 0);
if (Math.abs(e1.dot(up)) > 0.9) e1.set(0, 1, 0);
e1.addScaledVector(up, -e1.dot(up)).normalize();
const e2 = new THREE.Vector3().crossVectors(up, e1);
camera.up.copy(up);
function place() {
  camera.position.copy(center).addScaledVector(e1, dist * Math.cos(el) * Math.cos(az))
      .addScaledVector(e2, dist * Math.cos(el) * Math.sin(az)).addScaledVector(up, dist * Math.sin(el));
  camera.lookAt(center);
}
let drag = null;
renderer.domElement.addEventListener('mousedown', e => drag = [e.clientX, e.clientY]);
window.addEventListener('mouseup', () => drag = null);
window.addEventListener('mousemove', e => { if (!drag) return; az -= 0.01 * (e.clientX - drag[0]); el = Math.max(-1.5, Math.min(1.5, el + 0.01 * (e.clientY - drag[1]))); drag = [e.clientX, e.clientY]; show(k); });
renderer.domElement.addEventListener('wheel', e => { e.preventDefault(); dist *= Math.exp(0.001 * e.deltaY); show(k); });
// The plot.
const plot = document.getElementById('plot'), g2 = plot.getContext('2d');
function drawPlot(i) {
  const W = plot.width, H = plot.height, L = 60, B = 22;
  g2.clearRect(0, 0, W, H); g2.font = '11px sans-serif';
  let lo = Infinity, hi = -Infinity;
  for (const s of data.series) for (const v of s.v) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!(hi > lo)) { hi = lo + 1; }
  const t0 = data.t[0], t1 = data.t[n - 1] > t0 ? data.t[n - 1] : t0 + 1;
  const X = t => L + (W - L - 10) * (t - t0) / (t1 - t0), Y = v => H - B - (H - B - 10) * (v - lo) / (hi - lo);
  g2.strokeStyle = '#bbb'; g2.strokeRect(L, 10, W - L - 10, H - B - 10);
  g2.fillStyle = '#444'; g2.fillText(hi.toPrecision(3), 4, 16); g2.fillText(lo.toPrecision(3), 4, H - B);
  g2.fillText('t = ' + t0.toFixed(2) + ' s', L, H - 6); g2.fillText(t1.toFixed(2) + ' s', W - 50, H - 6);
  data.series.forEach((s, j) => {
    g2.strokeStyle = '#' + colors[j % colors.length].toString(16).padStart(6, '0'); g2.beginPath();
    s.v.forEach((v, q) => q ? g2.lineTo(X(data.t[q]), Y(v)) : g2.moveTo(X(data.t[q]), Y(v))); g2.stroke();
    g2.fillStyle = g2.strokeStyle; g2.fillText(s.name, L + 8 + 110 * j, 24);
  });
  g2.strokeStyle = '#000'; g2.beginPath(); g2.moveTo(X(data.t[i]), 10); g2.lineTo(X(data.t[i]), H - B); g2.stroke();
}
const slider = document.getElementById('time'), clock = document.getElementById('clock'), button = document.getElementById('play');
let k = 0, playing = true, shown = 0;
const moved = new THREE.Vector3();
let starts = [];
let travel = 0, arrowsShown = 0;
function show(i) {
  k = i;
  for (let f = 0; f < F; ++f) {
    const o = (i * F + f) * 7, P = data.poses;
    frames[f].position.set(P[o], P[o + 1], P[o + 2]); frames[f].quaternion.set(P[o + 3], P[o + 4], P[o + 5], P[o + 6]);
  }
  for (const r of rods) {
    const a = (i * F + r.a) * 7, b = (i * F + r.b) * 7, P = data.poses, pos = r.line.geometry.attributes.position;
    pos.setXYZ(0, P[a], P[a + 1], P[a + 2]); pos.setXYZ(1, P[b], P[b + 1], P[b + 2]); pos.needsUpdate = true;
  }
  for (let a = 0; a < A; ++a) {
    const o = (i * A + a) * 6, P = data.arrows, f = Math.hypot(P[o + 3], P[o + 4], P[o + 5]);
    arrows[a].visible = f > 0 && fmax > 0;
    if (arrows[a].visible) {
      const len = Math.min(0.6, 0.3 * f / fmax);
      arrows[a].position.set(P[o], P[o + 1], P[o + 2]);
      arrows[a].setDirection(new THREE.Vector3(P[o + 3] / f, P[o + 4] / f, P[o + 5] / f));
      arrows[a].setLength(len, Math.min(0.05, 0.3 * len), Math.min(0.03, 0.2 * len));
    }
  }
  place(); renderer.render(scene, camera); drawPlot(i);
  slider.value = i; clock.textContent = 't = ' + data.t[i].toFixed(3) + ' s';
  // What the browser test reads: how many objects, samples shown, how far the frames moved, drawn pixels.
  if (shown === 0) starts = frames.map(g => g.position.clone());
  frames.forEach((g, f) => { travel = Math.max(travel, moved.subVectors(g.position, starts[f]).length()); });
  ++shown;
  const gl = renderer.getContext(), px = new Uint8Array(4 * 900 * 520);
  let drawn = 0;
  if (shown % 20 === 1 || i === n - 1) {
    gl.readPixels(0, 0, 900, 520, gl.RGBA, gl.UNSIGNED_BYTE, px);
    for (let q = 0; q < px.length; q += 4) if (Math.abs(px[q] - 250) + Math.abs(px[q + 1] - 250) + Math.abs(px[q + 2] - 250) > 30) ++drawn;
    status.dataset.pixels = drawn;
  }
  arrowsShown = Math.max(arrowsShown, arrows.filter(a => a.visible).length);
  status.textContent = 'drew ' + meshes + ' objects; showed ' + shown + ' samples; the frames moved up to ' + travel.toFixed(3) + ' m; ' + (status.dataset.pixels || 0) + ' pixels drawn' + (A ? '; up to ' + arrowsShown + ' of ' + A + ' contact forces drawn at once' : '');
}
slider.addEventListener('input', () => { playing = false; button.textContent = 'play'; show(+slider.value); });
button.addEventListener('click', () => { playing = !playing; button.textContent = playing ? 'pause' : 'play'; if (playing && k >= n - 1) k = 0; });
let last = null;
function tick(now) {
  if (playing && n > 1) {
    if (last === null) last = now;
    // Real time: advance to the sample at the elapsed simulated time.
    let j = k;
    const target = data.t[k] + (now - last) / 1000;
    while (j < n - 1 && data.t[j + 1] <= target) ++j;
    if (j !== k) { last = now; show(j); }
    if (k >= n - 1) { playing = false; button.textContent = 'play'; }
  }
  requestAnimationFrame(tick);
}
show(0);
requestAnimationFrame(tick);
)JS";

  const S& scene_;
  std::vector<series> series_;
  bool custom_ = false;
  std::vector<double> times_, poses_, arrows_;
};

}  // namespace flange::viewer
