// Connections by name become pairs of frame numbers, once, before the scene's
// type is made.
//
// connect<"j3.frame_b", "r3.frame_a"> is a type holding two strings, and a
// string template argument is mangled character by character: in a chain,
// the connections were three quarters of the scene type's mangled name,
// which every instantiated function of the scene carries (at 32 links,
// 15 of a symbol's 19 KB). The compiler's time at a hundred links went
// into mangling those names. So the names are resolved here, their
// mistakes reported here, and the scene's type holds only
// wiring<a₀, b₀, a₁, b₁, …>: each connection's two frames as global frame
// numbers (a component's frames numbered after those of the components
// before it), −1 where a name names no frame.
#pragma once
#include <array>
#include <string_view>
#include <utility>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/closest_name.hpp"
#include "flange/detail/fixed_string.hpp"
#include "flange/detail/type_list.hpp"
#include "flange/scene/connect.hpp"
#include "flange/scene/diagnostics.hpp"
#include "flange/scene/topology.hpp"

namespace flange::detail {

/// The scene table of components Cs, with room for NK connections (not
/// filled in).
template <int NK, class... Cs>
constexpr auto component_table() {
  constexpr int nf = (0 + ... + int(Cs::frames.size()));
  scene_table<int(sizeof...(Cs)), nf, NK> t{};
  int c = 0, base = 0;
  (
      [&] {
        t.names[c] = Cs::name.view();
        if constexpr (requires { Cs::type_name; }) t.type_names[c] = Cs::type_name;
        t.kinds[c] = Cs::kind;
        t.nframes[c] = int(Cs::frames.size());
        t.frame_base[c] = base;
        for (int k = 0; k < int(Cs::frames.size()); ++k) t.frame_names[c][k] = Cs::frames[k];
        base += int(Cs::frames.size());
        t.massive[c] = carries_body<Cs>;
        if constexpr (Cs::kind == role::joint) {
          t.can_cut[c] = cuttable<Cs>;
          if constexpr (joint_requirements::sizes<Cs>) {
            t.nq[c] = Cs::nq;
            t.nv[c] = Cs::nv;
          }
        }
        if constexpr (Cs::kind == role::rigid) {
          if constexpr (requires { Cs::rotation_axis; }) t.rigid_rotation[c] = Cs::rotation_axis;
        }
        ++c;
      }(),
      ...);
  return t;
}

/// The component table and its name index, once per scene: the connections'
/// resolution and the Scene read the same constants (a variable template is
/// evaluated once per program; a function call in each was evaluated twice).
template <int NK, class... Cs>
inline constexpr auto component_table_v = component_table<NK, Cs...>();
template <int NK, class... Cs>
inline constexpr auto name_index_v = index_names(component_table_v<NK, Cs...>);

/// "component.frame" of global frame f, as a constant (names up to 127
/// characters).
struct frame_name_buffer {
  char data[128]{};
  std::size_t size = 0;
  [[nodiscard]] constexpr std::string_view view() const { return {data, size}; }
};
template <int NC, int NF, int NK>
constexpr frame_name_buffer frame_name(const scene_table<NC, NF, NK>& t, int f) {
  frame_name_buffer b;
  for (int c = 0; c < NC; ++c)
    if (f >= t.frame_base[c] && f < t.frame_base[c] + t.nframes[c]) {
      auto put = [&](std::string_view s) {
        for (char ch : s)
          if (b.size < sizeof b.data - 1) b.data[b.size++] = ch;
      };
      put(t.names[c]);
      put(".");
      put(t.frame_names[c][f - t.frame_base[c]]);
    }
  return b;
}

/// The connections, resolved: frames[2k] and frames[2k + 1] are connection
/// k's two frames.
template <int... F>
struct wiring {
  static constexpr int n_connections = int(sizeof...(F)) / 2;
  static constexpr std::array<int, sizeof...(F)> frames{F...};
};

/// connect<"a", "b"> again, from frame numbers (for the messages of mistakes
/// found after resolution: the same type the user wrote).
template <const auto& Table, int A, int B>
using connection_of = connection<fixed_string<frame_name(Table, A).size + 1>(frame_name(Table, A).view()),
                                 fixed_string<frame_name(Table, B).size + 1>(frame_name(Table, B).view())>;

template <const auto& Frames, class Seq>
struct make_wiring;
template <const auto& Frames, std::size_t... I>
struct make_wiring<Frames, std::index_sequence<I...>> {
  using type = wiring<Frames[I]...>;
};

template <class Components, class Connections>
struct resolve_connections;

/// ::type is the wiring of connections Ks among components Cs. A connection
/// naming no frame is reported here, with the frame name closest to the one
/// it misspells; other mistakes are the scene's to report.
template <class... Cs, class... Ks>
struct resolve_connections<type_list<Cs...>, type_list<Ks...>> {
  static constexpr int nk = int(sizeof...(Ks));
  static constexpr auto& table = component_table_v<nk, Cs...>;
  static constexpr auto& index = name_index_v<nk, Cs...>;
  static constexpr std::array<int, 2 * sizeof...(Ks)> frames = [] {
    const std::array<std::string_view, sizeof...(Ks)> a{Ks::a...}, b{Ks::b...};
    std::array<int, 2 * sizeof...(Ks)> r{};
    for (int k = 0; k < nk; ++k) {
      r[2 * k] = find_frame(table, a[k], index);
      r[2 * k + 1] = find_frame(table, b[k], index);
    }
    return r;
  }();
  /// The first connection naming no frame, −1 if none.
  static constexpr int bad = first_unresolved(frames);

 private:
  static constexpr int closest_frame(std::string_view name) {
    int best = 0, best_d = -1;
    for (int f = 0; f < (0 + ... + int(Cs::frames.size())); ++f) {
      const int d = edit_distance(name, frame_name(table, f).view());
      if (best_d < 0 || d < best_d) best = f, best_d = d;
    }
    return best;
  }
  template <int K>
  static constexpr frame_name_buffer suggestion =
      frame_name(table, closest_frame(frames[2 * K] < 0 ? nth_t<K, Ks...>::a : nth_t<K, Ks...>::b));
  template <int K>
  static constexpr bool report_bad_name() {
    if constexpr (K >= 0) {
      constexpr auto& b = suggestion<K>;
      (void)sizeof(diagnostic::connection_names_no_frame<nth_t<K, Ks...>,
                                                         diagnostic::did_you_mean<fixed_string<b.size + 1>(b.view())>>);
    }
    return true;
  }

 public:
  // A name given twice is the scene's to report, first and alone:
  // connections naming it reach only the first component of that name, so
  // a connection that then names no frame is its symptom, not a mistake.
  static_assert(report_bad_name<index.duplicate < 0 ? bad : -1>());

  using type = typename make_wiring<frames, std::make_index_sequence<2 * sizeof...(Ks)>>::type;
};

}  // namespace flange::detail
