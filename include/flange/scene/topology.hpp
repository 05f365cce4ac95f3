// Structural analysis of a scene, done by constexpr functions over plain
// arrays (not by template recursion): connection sets by union–find, the
// paper's frame numbering, reachability from the World, equation and unknown
// counts, and the kinematic tree the dynamics walk.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>

#include "flange/core/component.hpp"

namespace flange::detail {

inline constexpr int max_frames_per_component = 2;

/// What the analysis needs to know of the components and connections.
template <int NC, int NF, int NK>
struct scene_table {
  std::array<std::string_view, NC> names{};
  std::array<std::string_view, NC> type_names{};
  std::array<role, NC> kinds{};
  std::array<int, NC> nframes{};
  std::array<int, NC> frame_base{};
  std::array<std::array<std::string_view, max_frames_per_component>, NC> frame_names{};
  /// Connection k's two frames (global numbers) are conn[2k] and conn[2k + 1],
  /// −1 for a name naming none: the layout of the scene type's wiring.
  std::array<int, 2 * NK> conn{};
  std::array<int, NC> nq{}, nv{};            ///< a joint's configuration and velocity sizes (0 for others)
  std::array<int, NC> rigid_rotation{};      ///< a rigid edge's rotation: −2 none, −1 any, k about axis k
  std::array<bool, NC> massive{};            ///< carries a body (mass at its frames)
  std::array<bool, NC> can_cut{};            ///< a joint that can close a loop (detail::cuttable)
};

template <int NC, int NF, int NK>
struct topology {
  // --- errors (−1: none)
  int bad_name_connection = -1;   ///< a connection naming no existing frame
  int self_connection = -1;       ///< a connection whose two ends are one frame
  int redundant_connection = -1;  ///< joins two frames already in one set
  int duplicate_name = -1;        ///< second component with an existing name
  int n_worlds = 0;
  int world = -1;          ///< index of the (first) World
  int second_world = -1;
  int unreached = -1;      ///< first component with no connection path to the World

  // --- connection sets
  std::array<int, NF> set_of{};    ///< frame → set (sets numbered in paper order)
  std::array<int, NF> number{};    ///< frame → the paper's frame number, 1-based
  std::array<int, NF> by_number{}; ///< paper number − 1 → frame
  int n_sets = 0;
  std::array<int, NF> set_size{};

  [[nodiscard]] constexpr bool ok() const {
    return bad_name_connection < 0 && self_connection < 0 && redundant_connection < 0 && duplicate_name < 0 &&
           n_worlds == 1 && unreached < 0;
  }
};

template <std::size_t M>
constexpr int find_root(std::array<int, M>& p, int i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

/// FNV-1a of a name: the scene analysis finds names by these (name_index).
constexpr std::uint32_t name_hash(std::string_view s) {
  std::uint32_t h = 2166136261u;
  for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h;
}
/// The components by name: an open-addressing hash table, so that finding the
/// frame a connection names costs a few steps, not a sweep of the scene (a
/// sweep per connection made the analysis quadratic in the scene's size,
/// which at a few hundred components cost the compiler hundreds of MB).
template <int NC>
struct name_index {
  static constexpr int size = [] {
    int n = 1;
    while (n < 2 * NC) n *= 2;
    return n;
  }();
  std::array<std::uint32_t, NC> hash{};
  std::array<int, size> slot{};  ///< component + 1, or 0 where empty
  int duplicate = -1;            ///< the first component whose name an earlier one has
};
template <int NC, int NF, int NK>
constexpr name_index<NC> index_names(const scene_table<NC, NF, NK>& t) {
  name_index<NC> r{};
  constexpr int mask = name_index<NC>::size - 1;
  for (int c = 0; c < NC; ++c) {
    r.hash[c] = name_hash(t.names[c]);
    for (int i = int(r.hash[c] & mask);; i = (i + 1) & mask) {
      const int d = r.slot[i] - 1;
      if (d < 0) {
        r.slot[i] = c + 1;
        break;
      }
      if (r.hash[d] == r.hash[c] && t.names[d] == t.names[c]) {
        if (r.duplicate < 0) r.duplicate = c;
        break;
      }
    }
  }
  return r;
}

/// The frame "component.frame" names, or −1.
template <int NC, int NF, int NK>
constexpr int find_frame(const scene_table<NC, NF, NK>& t, std::string_view s, const name_index<NC>& index) {
  // A loop, not find/substr: with g++'s -fsanitize=undefined those carry
  // null-pointer checks that are not constant expressions.
  std::size_t dot = 0;
  while (dot < s.size() && s[dot] != '.') ++dot;
  if (dot == s.size()) return -1;
  const std::string_view comp(s.data(), dot), frame(s.data() + dot + 1, s.size() - dot - 1);
  const std::uint32_t h = name_hash(comp);
  constexpr int mask = name_index<NC>::size - 1;
  for (int i = int(h & mask); index.slot[i] != 0; i = (i + 1) & mask) {
    const int c = index.slot[i] - 1;
    if (index.hash[c] == h && t.names[c] == comp) {
      for (int k = 0; k < t.nframes[c]; ++k)
        if (t.frame_names[c][k] == frame) return t.frame_base[c] + k;
      return -1;
    }
  }
  return -1;
}
/// The first connection of frame pairs f (connection k: f[2k], f[2k + 1])
/// with a name that names no frame (−1), or −1 if every name resolved.
template <std::size_t M>
constexpr int first_unresolved(const std::array<int, M>& f) {
  for (std::size_t i = 0; i < M; ++i)
    if (f[i] < 0) return int(i / 2);
  return -1;
}
/// The analysis of table t. Its names' index, index_names(t), is passed in:
/// the scene evaluates it once, for this and for the connections' resolution.
template <int NC, int NF, int NK>
constexpr topology<NC, NF, NK> analyze(const scene_table<NC, NF, NK>& t, const name_index<NC>& index) {
  topology<NC, NF, NK> r{};
  r.duplicate_name = index.duplicate;
  r.bad_name_connection = first_unresolved(t.conn);
  for (int c = 0; c < NC; ++c) {
    if (t.kinds[c] == role::world) {
      if (++r.n_worlds == 1) r.world = c;
      else if (r.second_world < 0) r.second_world = c;
    }
  }
  std::array<int, NF> parent{};
  for (int f = 0; f < NF; ++f) parent[f] = f;
  for (int k = 0; k < NK; ++k) {
    const int a = t.conn[2 * k], b = t.conn[2 * k + 1];
    if (a < 0 || b < 0) continue;  // first_unresolved above
    if (a == b) {
      if (r.self_connection < 0) r.self_connection = k;
      continue;
    }
    const int ra = find_root(parent, a), rb = find_root(parent, b);
    if (ra == rb) {
      if (r.redundant_connection < 0) r.redundant_connection = k;
      continue;
    }
    parent[rb] = ra;
  }
  // The paper numbers frames in the order the connections first name them;
  // frames connected to nothing come last, in component order.
  int next = 0;
  std::array<bool, NF> numbered{};
  auto give = [&](int f) {
    if (f >= 0 && !numbered[f]) {
      numbered[f] = true;
      r.number[f] = ++next;
      r.by_number[next - 1] = f;
    }
  };
  for (int f : t.conn) give(f);
  for (int f = 0; f < NF; ++f) give(f);
  // Sets in the order of their lowest-numbered frame.
  std::array<int, NF> set_of_root{};
  for (auto& s : set_of_root) s = -1;
  for (int i = 0; i < NF; ++i) {
    const int f = r.by_number[i];
    const int root = find_root(parent, f);
    if (set_of_root[root] < 0) set_of_root[root] = r.n_sets++;
    r.set_of[f] = set_of_root[root];
    ++r.set_size[r.set_of[f]];
  }
  // Reachability from the World: sets joined by connections, and all frames
  // of one component joined through the component.
  // One union–find over the sets, joined through each component's frames:
  // linear in the scene, where a sweep until nothing grows was quadratic.
  if (r.world >= 0) {
    std::array<int, NF> joined{};
    for (int s = 0; s < NF; ++s) joined[s] = s;
    for (int c = 0; c < NC; ++c)
      for (int k = 1; k < t.nframes[c]; ++k) {
        const int a = find_root(joined, r.set_of[t.frame_base[c]]), b = find_root(joined, r.set_of[t.frame_base[c] + k]);
        if (a != b) joined[b] = a;
      }
    const int world = find_root(joined, r.set_of[t.frame_base[r.world]]);
    for (int c = 0; c < NC && r.unreached < 0; ++c)
      if (find_root(joined, r.set_of[t.frame_base[c]]) != world) r.unreached = c;
  }
  return r;
}

// ------------------------------------------------------------ kinematic tree

/// The kinematic tree: links are the World's rigid cluster (link 0) and one
/// link per joint; rigid edges (FixedTranslation) join connection sets within a
/// link. Links are numbered breadth-first, so a parent precedes its children.
template <int NC, int NF>
struct tree {
  int loop = -1;      ///< a loop no joint can close: rigid edges only, or a joint with both frames in one set
  int floating = -1;  ///< a component not tied to the World through joints and rigid edges
  int n_links = 1;
  int n_q = 0;
  std::array<int, NC + 1> link_joint{};       ///< link → its joint component
  std::array<int, NC + 1> link_dir{};         ///< +1: frame_a toward the World; −1: frame_b
  std::array<int, NC + 1> link_parent{};
  std::array<int, NC + 1> link_parent_set{};  ///< set holding the joint's parent-side frame
  std::array<int, NC + 1> link_root_set{};
  std::array<int, NF> set_link{};             ///< −1: not in the tree
  std::array<int, NF> set_parent{};           ///< −1: the set is its link's root
  std::array<int, NF> set_edge{};             ///< rigid component joining set to set_parent
  std::array<int, NF> set_edge_dir{};
  std::array<int, NC> joint_index{};          ///< joint component → its place among the joints (scene order), −1 for others
  std::array<int, NC> q_offset{};             ///< joint component → offset of its coordinates in q
  std::array<int, NC> v_offset{};             ///< joint component → offset of its rates in v
  int n_joints = 0, n_v = 0;
  std::array<int, NC> link_of_joint{};
  std::array<int, NF> set_rotation{};         ///< rotation of a set relative to its link: −2 none, −1 any, k about axis k
  int n_tree_sets = 0;
  std::array<int, NF> set_order{};            ///< sets in breadth-first order from the World's
  // Closed loops (dynamics/loops.hpp): each loop is closed by a cut joint,
  // which stays out of the tree and of the state and becomes constraints.
  int n_cuts = 0;
  std::array<int, NC> cuts{};                 ///< cut k → its joint component
  std::array<int, NC> cut_of{};               ///< component → its cut index, −1 for others
};

/// How bad a choice of cut joints is, 0 when it is good: 4·NC for each cut
/// joint that cannot close a loop (a Universal, or a joint with a drive or
/// an axis law), and 1 for each tree joint that moves no mass (no body
/// beyond it: the tree's mass matrix is singular there, though the
/// constrained system need not be). A choice that leaves a loop in the tree
/// is not a choice (a large number). cluster: each set's rigid cluster.
/// (Called only for a scene with no loop that no joint can close.)
template <int NC, int NF, int NK>
constexpr int cut_score(const scene_table<NC, NF, NK>& t, const topology<NC, NF, NK>& topo,
                        const std::array<int, std::size_t(NF)>& cluster,
                        const std::array<bool, std::size_t(NC)>& is_cut) {
  constexpr int invalid = 1 << 30;
  std::array<int, NF> uf{};
  for (int i = 0; i < NF; ++i) uf[i] = i;
  std::array<int, NF + 1> first{};
  std::array<int, 2 * NC> incident{};
  int score = 0;
  for (int e = 0; e < NC; ++e) {
    if (t.kinds[e] != role::joint) continue;
    if (is_cut[e]) {
      if (!t.can_cut[e]) score += 4 * NC;
      continue;
    }
    const int a = cluster[topo.set_of[t.frame_base[e]]], b = cluster[topo.set_of[t.frame_base[e] + 1]];
    const int ra = find_root(uf, a), rb = find_root(uf, b);
    if (ra == rb) return invalid;
    uf[rb] = ra;
    ++first[a + 1];
    ++first[b + 1];
  }
  for (int i = 0; i < NF; ++i) first[i + 1] += first[i];
  std::array<int, NF> fill{};
  for (int e = 0; e < NC; ++e)
    if (t.kinds[e] == role::joint && !is_cut[e]) {
      const int a = cluster[topo.set_of[t.frame_base[e]]], b = cluster[topo.set_of[t.frame_base[e] + 1]];
      incident[first[a] + fill[a]++] = e;
      incident[first[b] + fill[b]++] = e;
    }
  std::array<bool, NF> mass{};
  for (int c = 0; c < NC; ++c)
    if (t.massive[c]) mass[cluster[topo.set_of[t.frame_base[c]]]] = true;
  // Breadth-first from the World's cluster; then each cluster's mass is
  // added to its parent's, children before parents.
  std::array<int, NF> order{}, parent{};
  std::array<bool, NF> seen{};
  int n = 0;
  const int root = cluster[topo.set_of[t.frame_base[topo.world]]];
  order[n++] = root;
  seen[root] = true;
  parent[root] = -1;
  for (int head = 0; head < n; ++head) {
    const int u = order[head];
    for (int i = first[u]; i < first[u + 1]; ++i) {
      const int e = incident[i];
      const int a = cluster[topo.set_of[t.frame_base[e]]], b = cluster[topo.set_of[t.frame_base[e] + 1]];
      const int other = a == u ? b : a;
      if (seen[other]) continue;
      seen[other] = true;
      parent[other] = u;
      order[n++] = other;
    }
  }
  for (int k = n - 1; k > 0; --k) {
    const int u = order[k];
    if (!mass[u]) ++score;
    else mass[parent[u]] = true;
  }
  return score;
}

/// The cut joints, improved from the writing order's: while the choice
/// scores above 0 (cut_score), the swap of a cut joint for a tree joint that
/// lowers the score most is made, of equal ones the joint written last (a
/// tree joint not on the cut joint's loop would leave a loop, and scores as
/// no choice). A scene whose writing order's cuts are good keeps them.
template <int NC, int NF, int NK>
constexpr void choose_cuts(const scene_table<NC, NF, NK>& t, const topology<NC, NF, NK>& topo,
                           const std::array<int, std::size_t(NF)>& cluster,
                           std::array<bool, std::size_t(NC)>& is_cut) {
  int score = cut_score(t, topo, cluster, is_cut);
  for (int round = 0; score > 0 && round < NC; ++round) {
    int best = score, from = -1, to = -1;
    for (int c = 0; c < NC; ++c) {
      if (!is_cut[c]) continue;
      for (int j = NC - 1; j >= 0; --j) {  // of equal swaps, the joint written last
        if (t.kinds[j] != role::joint || is_cut[j]) continue;
        is_cut[c] = false;
        is_cut[j] = true;
        const int s = cut_score(t, topo, cluster, is_cut);
        is_cut[c] = true;
        is_cut[j] = false;
        if (s < best) {
          best = s;
          from = c;
          to = j;
        }
      }
    }
    if (from < 0) return;
    is_cut[from] = false;
    is_cut[to] = true;
    score = best;
  }
}

template <int NC, int NF, int NK>
constexpr tree<NC, NF> build_tree(const scene_table<NC, NF, NK>& t, const topology<NC, NF, NK>& topo) {
  tree<NC, NF> r{};
  for (auto& s : r.set_link) s = -1;
  for (auto& s : r.set_parent) s = -1;
  for (auto& s : r.set_edge) s = -1;
  for (auto& x : r.set_rotation) x = -2;
  for (auto& x : r.cut_of) x = -1;
  std::array<bool, NC> used{};
  // Loops first, by union–find: rigid edges, then joints, each in scene
  // order. A joint that joins two sets already joined closes a loop and is
  // cut: the last joint written in each loop (docs/loops.md), unless that
  // choice is bad (choose_cuts). A rigid edge that closes a loop closes a
  // loop of rigid edges, which nothing can cut, and so does a joint whose
  // two frames are in one set.
  if (topo.ok()) {
    std::array<int, NF> uf{}, cluster{};
    std::array<bool, NC> is_cut{};
    for (int i = 0; i < NF; ++i) uf[i] = i;
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1)
        for (int i = 0; i < NF; ++i) cluster[i] = find_root(uf, i);  // the rigid clusters
      for (int e = 0; e < NC; ++e) {
        if (t.kinds[e] != (pass == 0 ? role::rigid : role::joint)) continue;
        const int sa = topo.set_of[t.frame_base[e]], sb = topo.set_of[t.frame_base[e] + 1];
        const int a = find_root(uf, sa), b = find_root(uf, sb);
        if (a != b) {
          uf[b] = a;
          continue;
        }
        used[e] = true;  // left out of the tree
        if (pass == 0 || sa == sb) {
          if (r.loop < 0) r.loop = e;
        } else {
          is_cut[e] = true;
          ++r.n_cuts;
        }
      }
    }
    if (r.n_cuts > 0 && r.loop < 0) choose_cuts(t, topo, cluster, is_cut);
    r.n_cuts = 0;
    for (int e = 0; e < NC; ++e)
      if (is_cut[e]) {
        r.cut_of[e] = r.n_cuts;
        r.cuts[r.n_cuts++] = e;
      }
    for (int e = 0; e < NC; ++e)
      if (t.kinds[e] == role::joint && r.loop < 0) used[e] = is_cut[e];
  }
  for (int c = 0; c < NC; ++c) {
    r.joint_index[c] = r.q_offset[c] = r.v_offset[c] = -1;
    r.link_of_joint[c] = -1;
    if (t.kinds[c] == role::joint && r.cut_of[c] < 0) {
      r.joint_index[c] = r.n_joints++;
      r.q_offset[c] = r.n_q;
      r.v_offset[c] = r.n_v;
      r.n_q += t.nq[c];
      r.n_v += t.nv[c];
    }
  }
  if (!topo.ok()) return r;
  // Each set's joints and rigid edges, in scene order (compressed rows):
  // the walk below visits a set's own edges, not every component per set.
  std::array<int, NF + 1> first{};
  std::array<int, 2 * NC> incident{};
  {
    auto each_edge = [&](auto&& f) {
      for (int e = 0; e < NC; ++e) {
        if (t.kinds[e] != role::joint && t.kinds[e] != role::rigid) continue;
        const int sa = topo.set_of[t.frame_base[e]], sb = topo.set_of[t.frame_base[e] + 1];
        f(sa, e);
        if (sb != sa) f(sb, e);
      }
    };
    each_edge([&](int set, int) { ++first[set + 1]; });
    for (int i = 0; i < NF; ++i) first[i + 1] += first[i];
    std::array<int, NF> fill{};
    each_edge([&](int set, int e) { incident[first[set] + fill[set]++] = e; });
  }
  std::array<int, NF> queue{};
  int head = 0, tail = 0;
  const int root = topo.set_of[t.frame_base[topo.world]];
  r.set_link[root] = 0;
  r.link_root_set[0] = root;
  queue[tail++] = root;
  while (head < tail) {
    const int u = queue[head++];
    r.set_order[r.n_tree_sets++] = u;
    for (int i = first[u]; i < first[u + 1]; ++i) {
      const int e = incident[i];
      if (used[e]) continue;
      const int sa = topo.set_of[t.frame_base[e]], sb = topo.set_of[t.frame_base[e] + 1];  // one of them is u
      used[e] = true;
      const int other = sa == u ? sb : sa;
      const int dir = sa == u ? 1 : -1;
      if (sa == sb || r.set_link[other] >= 0) {
        if (r.loop < 0) r.loop = e;
        continue;
      }
      if (t.kinds[e] == role::joint) {
        const int L = r.n_links++;
        r.link_joint[L] = e;
        r.link_dir[L] = dir;
        r.link_parent[L] = r.set_link[u];
        r.link_parent_set[L] = u;
        r.link_root_set[L] = other;
        r.link_of_joint[e] = L;
        r.set_link[other] = L;
      } else {
        r.set_link[other] = r.set_link[u];
        r.set_parent[other] = u;
        r.set_edge[other] = e;
        r.set_edge_dir[other] = dir;
        // Rotations compose: none with k stays k, k with k stays k, else any.
        const int a = r.set_rotation[u], b = t.rigid_rotation[e];
        r.set_rotation[other] = a == -2 ? b : b == -2 ? a : (a == b ? a : -1);
      }
      queue[tail++] = other;
    }
  }
  // Report a body or joint before a force element: the element is usually
  // fine, it is what hangs on it that lacks a joint.
  for (int pass = 0; pass < 2; ++pass)
    for (int c = 0; c < NC && r.floating < 0; ++c) {
      if (t.kinds[c] == role::world || (t.kinds[c] == role::force) != (pass == 1)) continue;
      bool in = true;
      for (int k = 0; k < t.nframes[c]; ++k) in = in && r.set_link[topo.set_of[t.frame_base[c] + k]] >= 0;
      if (!in) r.floating = c;
    }
  return r;
}

}  // namespace flange::detail
