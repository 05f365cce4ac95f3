// The equation listing: a scene's flattened equations in the paper's notation,
// one line per vector or scalar equation, numbered as the paper numbers them:
// component equations in scene order, then connection equations by set.
// Frames are numbered as the paper numbers them (by first appearance in the
// connections) and listed with their component and connector names.
#pragma once
#include <ostream>
#include <string>

#include <boost/hana/for_each.hpp>

#include "flange/equations/residual.hpp"

namespace flange {

namespace detail {
template <class S, int CI>
struct print_context {
  [[nodiscard]] std::string slot_label(int slot) const {
    using C = typename S::template component_type<CI>;
    constexpr int nf = int(C::frames.size());
    if (slot < 4 * nf) {
      static constexpr const char* letters[] = {"r", "R", "F", "M"};
      // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive)
      // on const char* + std::string here.
      std::string label(letters[slot % 4]);
      label.append(std::to_string(S::topology.number[S::table.frame_base[CI] + slot / 4]));
      return label;
    }
    return std::string(C::internals[slot - 4 * nf].name);
  }
};
}  // namespace detail

/// Prints the scene's equations, then "equations: N, unknowns: M".
template <class S>
void print_equations(const S& scene, std::ostream& os) {
  constexpr auto& topo = S::topology;
  constexpr auto& tab = S::table;
  os << "frames:";
  for (int i = 0; i < S::n_frames; ++i) {
    const int f = topo.by_number[i];
    int c = 0;
    while (c + 1 < S::n_components && tab.frame_base[c + 1] <= f) ++c;
    os << (i ? ", " : " ") << i + 1 << " = " << tab.names[c] << '.' << tab.frame_names[c][f - tab.frame_base[c]];
  }
  os << '\n';
  int n = 0;
  [&]<int... I>(std::integer_sequence<int, I...>) {
    (
        [&] {
          using C = typename S::template component_type<I>;
          os << C::name.view() << " (" << C::type_name << ")\n";
          const detail::print_context<S, I> p;
          boost::hana::for_each(scene.template component<I>().equations(), [&](const auto& e) {
            os << "  (" << ++n << ")  ";
            e.print(os, p);
            os << '\n';
          });
        }(),
        ...);
  }(std::make_integer_sequence<int, S::n_components>{});
  os << "connections\n";
  for (int s = 0; s < topo.n_sets; ++s) {
    int members[S::n_frames], k = 0;
    for (int i = 0; i < S::n_frames; ++i)
      if (topo.set_of[topo.by_number[i]] == s) members[k++] = i + 1;
    for (const char* v : {"r", "R"})
      for (int j = 1; j < k; ++j) os << "  (" << ++n << ")  " << v << members[0] << " = " << v << members[j] << '\n';
    for (const char* v : {"F", "M"}) {
      os << "  (" << ++n << ")  ";
      for (int j = 0; j < k; ++j) os << (j ? " + " : "") << v << members[j];
      os << " = 0\n";
    }
  }
  os << "equations: " << S::n_equations << ", unknowns: " << S::n_unknowns << '\n';
}

}  // namespace flange
