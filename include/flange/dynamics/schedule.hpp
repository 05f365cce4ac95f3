// How a pass over the kinematic tree is run: its plan and the executor that
// runs its steps over the plan.
//
// A pass says what it computes per link, as steps: the articulated body's
// start, up and down steps (articulated_body.hpp), a walk's at, down, gather
// and leave (Newton–Euler, the mass matrix, the pose and loop passes). How the
// steps are compiled and in which order is decided here, from the scene's
// type and the measured constants of costs.hpp, and nowhere else:
//
//   units   the links a pass visits together: one link each, or links in a
//           row of one kind whose steps hand each other their results in
//           registers (a block: the articulated body's shared steps in a
//           plane, up to costs.hpp's aba_block_links);
//   split   in a scene of more than split_links_above links, each unit (each
//           child's subtree in a walk) is a function of its own: one
//           function of a hundred unrolled links takes the optimiser
//           superlinear time and gigabytes, a call per link a few nanoseconds;
//   shared  a step compiled once per kind of link and called by every link
//           of that kind, rather than unrolled into the pass for each link:
//           beyond a few thousand unrolled instructions the pass outgrows
//           the processor's caches of decoded instructions (costs.hpp);
//   early   the form of the articulated body's step down (costs.hpp,
//           aba_down_early).
//
// The executor: for_units runs a step over the plan's units, parents first
// or children first; walk runs a walk's steps depth first; run_step calls a
// step inline or through its one shared copy; unit_links hands a unit's
// links to its step (a link alone, or a block's in a row). A step is always compiled into
// the unit that runs it (FLANGE_INLINE); a unit is compiled into the pass or
// split off, and a step shared, only here.
#pragma once
#include <array>
#include <tuple>
#include <type_traits>
#include <utility>

#include "flange/detail/inline.hpp"
#include "flange/dynamics/costs.hpp"
#include "flange/dynamics/links.hpp"

namespace flange {

/// How the articulated body's per-link steps are compiled: unrolled into one
/// function, as functions shared by links of one kind, or as the plan decides
/// from the scene's size (detail::aba_plan). The tests run both on one scene;
/// users keep the default.
enum class aba_steps { automatic, unrolled, shared };

namespace detail {

/// Scenes with more links than this compile each unit of a pass as a
/// function of its own (see above).
inline constexpr int split_links_above = 16;
/// Whether scene S's passes call a function per unit (or per subtree).
template <class S>
inline constexpr bool split_links = S::tree.n_links - 1 > split_links_above;

/// The most links from the World to a leaf.
template <class S>
constexpr int tree_depth() {
  constexpr int NL = S::tree.n_links;
  std::array<int, NL> d{};
  int most = 0;
  for (int L = 1; L < NL; ++L) {  // parents come first
    d[L] = d[S::tree.link_parent[L]] + 1;
    most = d[L] > most ? d[L] : most;
  }
  return most;
}

/// Whether scene S's articulated body takes the early step down (costs.hpp,
/// aba_down_early): the plan's choice, which the links' records are shaped by.
template <class A, class S>
inline constexpr bool aba_early = aba_down_early(A::planar, tree_depth<S>(), S::tree.n_links - 1);

/// A pass's units: unit u is the links first[u] … first[u] + len[u] − 1.
template <int NL>
struct unit_table {
  std::array<int, NL> first{}, len{};
  int n = 0;
};
/// Units of at most max_len links, link L joining the unit of L − 1 where joins[L].
template <int NL>
constexpr unit_table<NL> make_units(const std::array<bool, NL>& joins, int max_len) {
  unit_table<NL> t{};
  for (int L = 1; L < NL;) {
    int len = 1;
    while (L + len < NL && len < max_len && joins[L + len]) ++len;
    t.first[t.n] = L;
    t.len[t.n] = len;
    ++t.n;
    L += len;
  }
  return t;
}

/// The articulated body's plan for scene S in algebra A. Kinds says which
/// links are of one kind (Kinds::joins(max_len): may link L run in a block
/// after L − 1) and what its steps cost unrolled (Kinds::instructions()).
template <class A, class S, aba_steps Steps, class Kinds>
struct aba_plan {
  static constexpr int NL = S::tree.n_links;
  static constexpr bool split = split_links<S>;
  /// Steps shared when the unrolled pass would pass the threshold of
  /// costs.hpp (in space from 6 links, in a plane from 18).
  static constexpr bool shared =
      Steps == aba_steps::shared ||
      (Steps == aba_steps::automatic &&
       Kinds::instructions() > (A::planar ? aba_shared_steps_above.planar : aba_shared_steps_above.spatial));
  /// A link alone shares its first step only in space: in a plane that step
  /// is a few dozen instructions, less than its call costs.
  static constexpr bool shared_start = shared && !A::planar;
  static constexpr int block = !shared ? 1 : A::planar ? aba_block_links.planar : aba_block_links.spatial;
  static constexpr bool early = aba_early<A, S>;
  static constexpr unit_table<NL> units = make_units<NL>(Kinds::template joins<block>(), block);
};

// ------------------------------------------------------------ the executor

template <int U, class F>
[[gnu::noinline]] void unit_call(F& f) {
  f(std::integral_constant<int, U>{});
}
/// f(integral_constant<U>) for the units U = 0 … N − 1 (Reverse: N − 1 … 0),
/// each a function of its own when Split.
template <bool Split, int N, bool Reverse = false, class F>
FLANGE_INLINE void for_units(F&& f) {
  [&]<int... U>(std::integer_sequence<int, U...>) FLANGE_INLINE_LAMBDA {
    if constexpr (!Split) {
      if constexpr (Reverse) (f(std::integral_constant<int, N - 1 - U>{}), ...);
      else (f(std::integral_constant<int, U>{}), ...);
    } else {
      if constexpr (Reverse) (unit_call<N - 1 - U>(f), ...);
      else (unit_call<U>(f), ...);
    }
  }(std::make_integer_sequence<int, N>{});
}

/// How a shared step takes an argument: a pointer or a number by value,
/// anything else by reference, as the step itself takes it.
template <class A>
using step_param = std::conditional_t<
    std::is_pointer_v<std::remove_cvref_t<A>> || std::is_arithmetic_v<std::remove_cvref_t<A>>,
    std::remove_cvref_t<A>, std::conditional_t<std::is_lvalue_reference_v<A>, A, const std::remove_reference_t<A>&>>;
/// A step as a function of its own, one per step type and argument types:
/// links of one kind run the same instructions, which stay in the cache.
template <class Step, class... P>
[[gnu::noinline]] decltype(auto) shared_step(P... p) {
  return Step::run(static_cast<P>(p)...);
}
/// Step::run(args…), compiled into the caller or, when Shared, through its
/// one shared copy.
template <bool Shared, class Step, class... Args>
FLANGE_INLINE decltype(auto) run_step(Args&&... args) {
  if constexpr (Shared) return shared_step<Step, step_param<Args&&>...>(std::forward<Args>(args)...);
  else return Step::run(std::forward<Args>(args)...);
}

/// A unit's step as the executor runs it: the link's own step on a link
/// alone, its block form on R links in a row.
template <class Step, int R>
using unit_step = std::conditional_t<R == 1, Step, typename Step::template block<R>>;
/// A unit's links L0 … L0 + R − 1 as its step takes them, from a pass's
/// records and motions (K::records, K::motions: tuples, link L at L − 1;
/// K::element<X, I> their types): a link alone by reference (its record, its
/// motion), a block as pointers, first to last.
template <class K, int L0, int R>
struct unit_links {
  using W = typename K::template element<typename K::records, L0 - 1>;
  using Mo = typename K::template element<typename K::motions, L0 - 1>;
  std::array<W*, R> w;
  std::array<const Mo*, R> m;
  FLANGE_INLINE unit_links(typename K::records& ws, const typename K::motions& motions)
      : unit_links(ws, motions, std::make_integer_sequence<int, R>{}) {}
  template <int... J>
  FLANGE_INLINE unit_links(typename K::records& ws, const typename K::motions& motions, std::integer_sequence<int, J...>)
      : w{&std::get<L0 - 1 + J>(ws)...}, m{&std::get<L0 - 1 + J>(motions)...} {}
  FLANGE_INLINE decltype(auto) records() const {
    if constexpr (R == 1) return static_cast<W&>(*w[0]);
    else return w.data();
  }
  FLANGE_INLINE decltype(auto) motions() const {
    if constexpr (R == 1) return static_cast<const Mo&>(*m[0]);
    else return m.data();
  }
  /// A per-link value of the first link: by reference alone, its address in a block.
  template <class X>
  FLANGE_INLINE static decltype(auto) first(const X& x) {
    if constexpr (R == 1) return (x);
    else return &x;
  }
};

// ------------------------------------------------------------ the walk
//
// walk<L>(ctx, d) visits link L with the value d passed down from its parent
// (ctx.at<L>(d) starts what it will return), then each child C with
// ctx.down<L, C>(d), gathers what each child returns with ctx.gather<L, C>,
// and returns ctx.leave<L>(d, …) to its parent. The walk is unrolled at
// compile time, so each link is a straight-line block and every value has
// its own type (math/sparse.hpp); in a split scene each child's subtree is
// a function of its own.

template <class S, int L, class Ctx, class D>
auto walk(Ctx& ctx, const D& down);

template <class S, int L, class Ctx, class D>
[[gnu::noinline]] auto walk_call(Ctx& ctx, const D& down) {
  return walk<S, L>(ctx, down);
}
template <class S, int L, class Ctx, class D>
FLANGE_INLINE auto walk_subtree(Ctx& ctx, const D& down) {
  if constexpr (split_links<S>) return walk_call<S, L>(ctx, down);
  else return walk<S, L>(ctx, down);
}

template <class S, int L, std::size_t I, class Ctx, class D, class Acc>
FLANGE_INLINE auto walk_children(Ctx& ctx, const D& down, Acc acc) {
  constexpr auto cs = children<S, L>();
  if constexpr (I == cs.size()) {
    return acc;
  } else {
    constexpr int C = cs[I];
    auto r = walk_subtree<S, C>(ctx, ctx.template down<L, C>(down));
    return walk_children<S, L, I + 1>(ctx, down, ctx.template gather<L, C>(std::move(acc), std::move(r)));
  }
}

template <class S, int L, class Ctx, class D>
FLANGE_INLINE auto walk(Ctx& ctx, const D& down) {
  return ctx.template leave<L>(down, walk_children<S, L, 0>(ctx, down, ctx.template at<L>(down)));
}

/// Nothing to pass up.
struct nothing {};
/// The gather and leave of a walk that only passes values down.
struct down_only_walk {
  template <int, int>
  nothing gather(nothing, nothing) {
    return {};
  }
  template <int, class D>
  nothing leave(const D&, nothing) {
    return {};
  }
};

}  // namespace detail

}  // namespace flange
