// The scenes fuzz target's random trees (fuzz/scenes_fuzz.hpp): a spatial
// tree with every joint kind and force element, and a planar one, with
// stops (axis_law::limited) on some of their revolute and prismatic joints.
#include "scenes_fuzz.hpp"

namespace flange::fuzz {

constexpr auto spatial_tree = models::random_tree_shape(7, 6, false, true, true);
constexpr auto planar_tree = models::random_tree_shape(3, 6, true, true, true);

void fuzz_trees(bytes& b, int which) {
  if (which == 0) run(b, true, [&] { return models::tree<spatial_tree>(tree_numbers<spatial_tree.n>(b)); });
  else run(b, true, [&] { return models::tree<planar_tree>(tree_numbers<planar_tree.n>(b)); });
}

}  // namespace flange::fuzz
