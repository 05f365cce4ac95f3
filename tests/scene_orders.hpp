// A scene's parts (components and connections, as one tuple) written in
// another order: the order decides which joints are cut and which way the
// tree runs, and must not change the motion (docs/loops.md).
#pragma once
#include <array>
#include <cstddef>
#include <tuple>
#include <utility>

#include <flange/flange.hpp>

namespace flange::test {

/// A scene of parts in their order.
template <class Parts>
auto scene_of(const Parts& parts) {
  return std::apply([](const auto&... p) { return scene(p...); }, parts);
}

/// 0, 1, …, N−1 shuffled by a Fisher–Yates shuffle driven by Seed, the first
/// (the World) kept first.
template <unsigned Seed, std::size_t N>
constexpr std::array<std::size_t, N> shuffled_order() {
  std::array<std::size_t, N> order{};
  for (std::size_t i = 0; i < N; ++i) order[i] = i;
  unsigned long long state = Seed;
  for (std::size_t i = N - 1; i > 1; --i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::swap(order[i], order[1 + (state >> 33) % i]);  // a place in [1, i]
  }
  return order;
}

/// 0, 1, …, N−1 with From moved to just after To (To > From).
template <std::size_t N>
constexpr std::array<std::size_t, N> moved_after(std::size_t from, std::size_t to) {
  std::array<std::size_t, N> order{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < N; ++i) {
    if (i != from) order[k++] = i;
    if (i == to) order[k++] = from;
  }
  return order;
}

/// A scene of parts in the given order of their places.
template <auto Order, class Parts>
auto scene_in_order(const Parts& parts) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return scene(std::get<Order[I]>(parts)...);
  }(std::make_index_sequence<Order.size()>{});
}

/// A scene of parts in the order shuffled_order<Seed> gives.
template <unsigned Seed, class Parts>
auto shuffled_scene(const Parts& parts) {
  return scene_in_order<shuffled_order<Seed, std::tuple_size_v<Parts>>()>(parts);
}

}  // namespace flange::test
