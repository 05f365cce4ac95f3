// The DAE residual F(t, y, ẏ) = 0 of a scene, over every flattened variable.
//
// Rows: each component's equations in scene order, then for each connection
// set (in paper order) the potentials equal (r and R, k−1 times each) and the
// flows summed to zero (F and M). A frame connected to nothing is a set of
// one: F = 0, M = 0. Vector equations give 3 rows, scalar equations 1, and an
// orientation equation 3 (Modelica's equalityConstraint).
#pragma once
#include <Eigen/Core>
#include <boost/hana/for_each.hpp>

#include "flange/scene/named_state.hpp"
#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/scene/scene.hpp"

namespace flange {

template <class S, class T>
using dae_vector = Eigen::Matrix<T, S::n_storage, 1>;
template <class S, class T>
using residual_vector = Eigen::Matrix<T, S::n_equations, 1>;

namespace detail {

/// How expression leaves of component CI find their numbers in y and ẏ.
template <class S, int CI, class T>
struct eval_context {
  using scalar = T;
  const T* y;
  const T* yd;
  T t;
  Vec3<T> g;
  named_joint_state<T, S> x;

  template <int Slot, expr::var_kind K>
  auto slot(bool derivative) const {
    constexpr int off = S::template slot_offset<CI>(Slot);
    const T* p = (derivative ? yd : y) + off;
    if constexpr (K == expr::var_kind::scalar) return p[0];
    else if constexpr (K == expr::var_kind::vec) return Vec3<T>(p[0], p[1], p[2]);
    else return Mat3<T>(Eigen::Map<const Mat3<T>>(p));
  }
  [[nodiscard]] const Vec3<T>& gravity() const { return g; }
  template <class In>
  auto input(const In& in) const {
    return eval_input(in, t, x);
  }
};

/// The joints' coordinates q and rates v read back from their internals in y
/// and ẏ (each joint's read_state), for inputs written as f(t, x).
template <class S, class T, class Vy, class Vyd>
void joint_state_from(const S& scene, const Vy& y, const Vyd& yd, T* q, T* v) {
  [&]<int... I>(std::integer_sequence<int, I...>) {
    (
        [&] {
          using C = typename S::template component_type<I>;
          if constexpr (C::kind == role::joint && S::tree.cut_of[I] < 0) {  // a cut joint is not in the state
            constexpr int nf = int(C::frames.size());
            auto get = [&](int k, bool rate) -> const T* {
              const int o = S::template slot_offset<I>(4 * nf + k);
              return rate ? yd.data() + o : y.data() + o;
            };
            read_joint_state(scene.template component<I>(), get, q + S::tree.q_offset[I], v + S::tree.v_offset[I]);
          }
        }(),
        ...);
  }(std::make_integer_sequence<int, S::n_components>{});
}

}  // namespace detail

/// F(t, y, ẏ): one row per scalar equation, zero on a consistent solution.
template <class S, class T, class Vy, class Vyd>
[[nodiscard]] residual_vector<S, T> residual(const S& scene, const T& t, const Vy& y, const Vyd& yd) {
  static_assert(Vy::SizeAtCompileTime == S::n_storage && Vyd::SizeAtCompileTime == S::n_storage,
                "flange: residual() takes y and ẏ of length Scene::n_storage (see dae_vector<Scene, T>)");
  residual_vector<S, T> out;
  std::array<T, (S::n_q > 0 ? S::n_q : 1)> q{};
  std::array<T, (S::n_v > 0 ? S::n_v : 1)> v{};
  detail::joint_state_from(scene, y, yd, q.data(), v.data());
  const auto x = state_view(scene, q.data(), v.data());
  const Vec3<T> g = scene.gravity().template cast<T>();
  int row = 0;
  [&]<int... I>(std::integer_sequence<int, I...>) {
    (
        [&] {
          const detail::eval_context<S, I, T> ctx{y.data(), yd.data(), t, g, x};
          boost::hana::for_each(scene.template component<I>().equations(), [&](const auto& e) {
            e.residue(ctx, [&](int i) -> T& { return out(row + i); });
            row += std::remove_cvref_t<decltype(e)>::size;
          });
        }(),
        ...);
  }(std::make_integer_sequence<int, S::n_components>{});
  constexpr auto& topo = S::topology;
  for (int s = 0; s < topo.n_sets; ++s) {
    // Members in paper order; the potentials of the first equal those of the
    // others (all r equations, then all R equations), the flows sum to zero.
    int members[S::n_frames], k = 0;
    for (int i = 0; i < S::n_frames; ++i)
      if (topo.set_of[topo.by_number[i]] == s) members[k++] = topo.by_number[i];
    for (int j = 1; j < k; ++j, row += 3)
      out.template segment<3>(row) =
          y.template segment<3>(S::frame_offset(members[0], 0)) - y.template segment<3>(S::frame_offset(members[j], 0));
    const Eigen::Map<const Mat3<T>> R1(y.data() + S::frame_offset(members[0], 1));
    for (int j = 1; j < k; ++j, row += 3)
      out.template segment<3>(row) =
          orientation_residue<T>(R1, Eigen::Map<const Mat3<T>>(y.data() + S::frame_offset(members[j], 1)));
    Vec3<T> Fsum = Vec3<T>::Zero(), Msum = Vec3<T>::Zero();
    for (int j = 0; j < k; ++j) {
      Fsum += y.template segment<3>(S::frame_offset(members[j], 2));
      Msum += y.template segment<3>(S::frame_offset(members[j], 3));
    }
    out.template segment<3>(row) = Fsum;
    out.template segment<3>(row + 3) = Msum;
    row += 6;
  }
  return out;
}

}  // namespace flange
