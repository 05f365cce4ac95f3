// Expression templates for component equations.
//
// A component writes its equations once, in the paper's notation:
//
//     eq(r_b, r_a + transpose(R_a) * d)
//
// and the resulting tree of node types serves two masters:
//   * eval(ctx)   evaluates the expression to numbers (scalar, 3-vector, 3×3),
//   * print(os,p) prints it, e.g. "r7 = r5 + R5'·d".
// As in Eigen, the node (what) is kept apart from how it is evaluated: a node
// never knows where its variables live; the context passed in does.
#pragma once
#include <ostream>
#include <tuple>
#include <type_traits>
#include <utility>

#include "flange/math/rotation.hpp"
#include "flange/math/types.hpp"

namespace flange::expr {

/// The shape of a value an expression evaluates to.
enum class shape { scalar, vec, row, mat };

/// The kind of a variable slot: its storage size and its count as unknowns.
enum class var_kind { scalar, vec, rot };
constexpr int storage_size(var_kind k) { return k == var_kind::scalar ? 1 : k == var_kind::vec ? 3 : 9; }
constexpr int unknown_count(var_kind k) { return k == var_kind::scalar ? 1 : 3; }
constexpr shape shape_of(var_kind k) {
  return k == var_kind::scalar ? shape::scalar : k == var_kind::vec ? shape::vec : shape::mat;
}

struct node {};  // tag base of every expression node
template <class E>
concept Expr = std::is_base_of_v<node, std::remove_cvref_t<E>>;

/// The value type of a shape for scalar type T.
template <class T, shape S>
using value_t = std::conditional_t<
    S == shape::scalar, T,
    std::conditional_t<S == shape::vec, Vec3<T>, std::conditional_t<S == shape::row, Row3<T>, Mat3<T>>>>;

// Printing precedence: a child printed inside a parent of higher precedence
// gets parentheses.
inline constexpr int prec_add = 1, prec_neg = 2, prec_mul = 3, prec_postfix = 4, prec_atom = 5;

template <class E, class P>
void print_child(std::ostream& os, const E& e, const P& p, int min_prec) {
  if (E::prec < min_prec) {
    os << '(';
    e.print(os, p);
    os << ')';
  } else {
    e.print(os, p);
  }
}

// ---------------------------------------------------------------- leaves

/// A variable of the component: local slot number Slot of kind K. The
/// context maps it to the flattened DAE vector.
template <int Slot, var_kind K>
struct var : node {
  static constexpr int slot = Slot;
  static constexpr var_kind kind = K;
  static constexpr shape sh = shape_of(K);
  static constexpr int prec = prec_atom;
  template <class C>
  auto eval(const C& c) const {
    return c.template slot<Slot, K>(false);
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << p.slot_label(Slot);
  }
};

/// der(x): the time derivative of a variable, read from ẏ.
template <class V>
struct der_node : node {
  static constexpr shape sh = V::sh;
  static constexpr int prec = prec_atom;
  template <class C>
  auto eval(const C& c) const {
    return c.template slot<V::slot, V::kind>(true);
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << "der(" << p.slot_label(V::slot) << ')';
  }
};
template <int Slot, var_kind K>
constexpr der_node<var<Slot, K>> der(var<Slot, K>) {
  return {};
}

namespace detail {
template <class V>
constexpr shape shape_of_value() {
  if constexpr (std::is_arithmetic_v<V>) return shape::scalar;
  else if constexpr (V::RowsAtCompileTime == 3 && V::ColsAtCompileTime == 1) return shape::vec;
  else if constexpr (V::RowsAtCompileTime == 1 && V::ColsAtCompileTime == 3) return shape::row;
  else return shape::mat;
}
template <class T, class V>
auto cast(const V& v) {
  if constexpr (std::is_same_v<V, T>) return v;
  else if constexpr (std::is_arithmetic_v<V>) return T(v);
  else if constexpr (std::is_same_v<typename V::Scalar, T>) return v.eval();
  else return v.template cast<T>().eval();
}
}  // namespace detail

/// A parameter of the component (m, J, d, n…): a value fixed during the
/// simulation, printed by name.
template <class V>
struct param : node {
  static constexpr shape sh = detail::shape_of_value<V>();
  static constexpr int prec = prec_atom;
  V value;
  const char* name;
  param(V v, const char* n) : value(std::move(v)), name(n) {}
  template <class C>
  auto eval(const C&) const {
    return detail::cast<typename C::scalar>(value);
  }
  template <class P>
  void print(std::ostream& os, const P&) const {
    os << name;
  }
};

/// The world's gravity acceleration g, as Modelica's inner/outer world gives it
/// to every Body.
struct gravity : node {
  static constexpr shape sh = shape::vec;
  static constexpr int prec = prec_atom;
  template <class C>
  auto eval(const C& c) const {
    return c.gravity();
  }
  template <class P>
  void print(std::ostream& os, const P&) const {
    os << 'g';
  }
};

/// An input (M_ext(t), f(t)…) of shape S; In is the component's input holder.
template <class In, shape S>
struct input_node : node {
  static constexpr shape sh = S;
  static constexpr int prec = prec_atom;
  const In* in;
  const char* name;
  template <class C>
  auto eval(const C& c) const {
    return c.input(*in);
  }
  template <class P>
  void print(std::ostream& os, const P&) const {
    os << name;
  }
};

/// The constants 1 (identity matrix) and 0.
struct identity : node {
  static constexpr shape sh = shape::mat;
  static constexpr int prec = prec_atom;
  template <class C>
  auto eval(const C&) const {
    return Mat3<typename C::scalar>::Identity().eval();
  }
  template <class P>
  void print(std::ostream& os, const P&) const {
    os << '1';
  }
};
template <shape S>
struct zero : node {
  static constexpr shape sh = S;
  static constexpr int prec = prec_atom;
  template <class C>
  auto eval(const C&) const {
    using T = typename C::scalar;
    if constexpr (S == shape::scalar) return T(0);
    else return value_t<T, S>::Zero().eval();
  }
  template <class P>
  void print(std::ostream& os, const P&) const {
    os << '0';
  }
};

// ---------------------------------------------------------------- operations

namespace detail {
constexpr shape mul_shape(shape a, shape b) {
  if (a == shape::scalar) return b;
  if (b == shape::scalar) return a;
  if (a == shape::mat && b == shape::vec) return shape::vec;
  if (a == shape::mat && b == shape::mat) return shape::mat;
  if (a == shape::vec && b == shape::row) return shape::mat;
  if (a == shape::row && b == shape::vec) return shape::scalar;
  if (a == shape::row && b == shape::mat) return shape::row;
  throw "flange: these shapes cannot be multiplied";  // not a constant expression: compile error
}
}  // namespace detail

/// A binary node: the operation Op says the result's shape, how to compute it
/// and how it prints; the node only holds its operands (Eigen's split of
/// what, op and how).
template <class Op, class A, class B>
struct binary : node {
  static constexpr shape sh = Op::template result<A::sh, B::sh>();
  static constexpr int prec = Op::prec;
  A a;
  B b;
  binary(A x, B y) : a(std::move(x)), b(std::move(y)) {}
  template <class C>
  auto eval(const C& c) const {
    return Op::apply(a.eval(c), b.eval(c));
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    print_child(os, a, p, Op::left_prec);
    os << Op::symbol;
    print_child(os, b, p, Op::right_prec);
  }
};

namespace ops {
template <class X>
auto plain(X&& x) {
  if constexpr (std::is_arithmetic_v<std::remove_cvref_t<X>>) return x;
  else return x.eval();
}
/// a + b (Sign = +1) and a − b (Sign = −1).
template <int Sign>
struct additive {
  template <shape A, shape B>
  static constexpr shape result() {
    static_assert(A == B, "flange: adding or subtracting expressions of different shapes");
    return A;
  }
  static constexpr int prec = prec_add, left_prec = prec_add, right_prec = prec_add + 1;
  static constexpr const char* symbol = Sign > 0 ? " + " : " − ";
  template <class X, class Y>
  static auto apply(const X& x, const Y& y) {
    if constexpr (Sign > 0) return plain(x + y);
    else return plain(x - y);
  }
};
using plus = additive<+1>;
using minus = additive<-1>;
struct times {
  template <shape A, shape B>
  static constexpr shape result() {
    return detail::mul_shape(A, B);
  }
  static constexpr int prec = prec_mul, left_prec = prec_mul, right_prec = prec_mul + 1;
  static constexpr const char* symbol = "·";
  template <class X, class Y>
  static auto apply(const X& x, const Y& y) {
    if constexpr (std::is_arithmetic_v<X> || std::is_arithmetic_v<Y>) {
      return plain(x * y);
    } else {
      if constexpr (X::RowsAtCompileTime == 1 && Y::ColsAtCompileTime == 1) return (x * y)(0, 0);  // row·vector
      else return plain(x * y);
    }
  }
};
struct cross_product {
  template <shape A, shape B>
  static constexpr shape result() {
    static_assert(A == shape::vec && B == shape::vec, "flange: cross() takes two 3-vectors");
    return shape::vec;
  }
  static constexpr int prec = prec_mul, left_prec = prec_mul + 1, right_prec = prec_mul + 1;
  static constexpr const char* symbol = " × ";
  template <class X, class Y>
  static auto apply(const X& x, const Y& y) {
    return x.cross(y).eval();
  }
};
struct dot_product {
  template <shape A, shape B>
  static constexpr shape result() {
    static_assert(A == shape::vec && B == shape::vec, "flange: dot() takes two 3-vectors");
    return shape::scalar;
  }
  static constexpr int prec = prec_mul, left_prec = prec_mul + 1, right_prec = prec_mul + 1;
  static constexpr const char* symbol = "·";
  template <class X, class Y>
  static auto apply(const X& x, const Y& y) {
    return x.dot(y);
  }
};
}  // namespace ops

template <class A>
struct neg : node {
  static constexpr shape sh = A::sh;
  static constexpr int prec = prec_neg;
  A a;
  explicit neg(A x) : a(std::move(x)) {}
  template <class C>
  auto eval(const C& c) const {
    if constexpr (sh == shape::scalar) return -a.eval(c);
    else return (-a.eval(c)).eval();
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << "−";
    print_child(os, a, p, prec_mul);
  }
};


template <class A>
struct transpose_node : node {
  static constexpr shape sh = A::sh == shape::vec ? shape::row : A::sh == shape::row ? shape::vec : A::sh;
  static constexpr int prec = prec_postfix;
  A a;
  explicit transpose_node(A x) : a(std::move(x)) {}
  template <class C>
  auto eval(const C& c) const {
    if constexpr (A::sh == shape::scalar) return a.eval(c);
    else return a.eval(c).transpose().eval();
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    print_child(os, a, p, prec_postfix);
    os << '\'';
  }
};

template <class A>
struct tilde_node : node {
  static_assert(A::sh == shape::vec, "flange: tilde() takes a 3-vector");
  static constexpr shape sh = shape::mat;
  static constexpr int prec = prec_atom;
  A a;
  explicit tilde_node(A x) : a(std::move(x)) {}
  template <class C>
  auto eval(const C& c) const {
    return tilde<typename C::scalar>(a.eval(c));
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << "tilde(";
    a.print(os, p);
    os << ')';
  }
};

enum class function { sin, cos, tanh };

template <class A, function Fn>
struct function_node : node {
  static_assert(A::sh == shape::scalar, "flange: sin(), cos() and tanh() take a scalar");
  static constexpr shape sh = shape::scalar;
  static constexpr int prec = prec_atom;
  A a;
  explicit function_node(A x) : a(std::move(x)) {}
  template <class C>
  auto eval(const C& c) const {
    using std::cos;
    using std::sin;
    using std::tanh;
    if constexpr (Fn == function::sin) return sin(a.eval(c));
    else if constexpr (Fn == function::cos) return cos(a.eval(c));
    else return tanh(a.eval(c));
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << (Fn == function::sin ? "sin(" : Fn == function::cos ? "cos(" : "tanh(");
    a.print(os, p);
    os << ')';
  }
};

/// f(a…) for a function object f with a static `name`, of result shape S
/// (a joint stop's piecewise force, a contact's wrench), printed name(a, …).
/// Each argument reaches f as a value of the scalar type (vectors and
/// matrices evaluated).
template <shape S, class F, class... A>
struct call_node : node {
  static constexpr shape sh = S;
  static constexpr int prec = prec_atom;
  F f;
  std::tuple<A...> args;
  explicit call_node(F fn, A... a) : f(std::move(fn)), args(std::move(a)...) {}
  template <class C>
  auto eval(const C& c) const {
    using T = typename C::scalar;
    return std::apply([&](const auto&... a) { return f(detail::cast<T>(a.eval(c))...); }, args);
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    os << F::name << '(';
    std::apply(
        [&](const auto&... a) {
          int k = 0;
          ((os << (k++ ? ", " : ""), a.print(os, p)), ...);
        },
        args);
    os << ')';
  }
};

template <Expr A, Expr B> auto operator+(A a, B b) { return binary<ops::plus, A, B>(std::move(a), std::move(b)); }
template <Expr A, Expr B> auto operator-(A a, B b) { return binary<ops::minus, A, B>(std::move(a), std::move(b)); }
template <Expr A> auto operator-(A a) { return neg<A>(std::move(a)); }
template <Expr A, Expr B> auto operator*(A a, B b) { return binary<ops::times, A, B>(std::move(a), std::move(b)); }
template <Expr A, Expr B> auto cross(A a, B b) { return binary<ops::cross_product, A, B>(std::move(a), std::move(b)); }
template <Expr A, Expr B> auto dot(A a, B b) { return binary<ops::dot_product, A, B>(std::move(a), std::move(b)); }
template <Expr A> auto transpose(A a) { return transpose_node<A>(std::move(a)); }
template <Expr A> auto tilde(A a) { return tilde_node<A>(std::move(a)); }
template <Expr A> auto sin(A a) { return function_node<A, function::sin>(std::move(a)); }
template <Expr A> auto cos(A a) { return function_node<A, function::cos>(std::move(a)); }
template <Expr A> auto tanh(A a) { return function_node<A, function::tanh>(std::move(a)); }
template <shape S = shape::scalar, class F, Expr... A> auto call(F f, A... a) { return call_node<S, F, A...>(std::move(f), std::move(a)...); }

// ---------------------------------------------------------------- equations

/// How an equation between two values becomes residues.
enum class eq_kind {
  value,        ///< scalar or 3-vector: lhs − rhs
  orientation,  ///< R1 = R2: three angles (Modelica's equalityConstraint)
  skew          ///< ã = B with B skew-symmetric: vex(ã − B), three residues
};

template <class L, class R, eq_kind K>
struct equation {
  static_assert(L::sh == R::sh, "flange: the two sides of an equation have different shapes");
  static_assert(K != eq_kind::value || L::sh == shape::scalar || L::sh == shape::vec,
                "flange: a matrix equation must say whether it is an orientation or a skew equation");
  static constexpr int size = L::sh == shape::scalar ? 1 : 3;
  L lhs;
  R rhs;

  /// Writes the equation's residues to out[0 .. size).
  template <class C, class Out>
  void residue(const C& c, Out&& out) const {
    using T = typename C::scalar;
    if constexpr (K == eq_kind::orientation) {
      const Vec3<T> r = orientation_residue<T>(lhs.eval(c), rhs.eval(c));
      for (int i = 0; i < 3; ++i) out(i) = r(i);
    } else if constexpr (K == eq_kind::skew) {
      const Vec3<T> r = vex<T>((lhs.eval(c) - rhs.eval(c)).eval());
      for (int i = 0; i < 3; ++i) out(i) = r(i);
    } else if constexpr (size == 1) {
      out(0) = lhs.eval(c) - rhs.eval(c);
    } else {
      const Vec3<T> r = lhs.eval(c) - rhs.eval(c);
      for (int i = 0; i < 3; ++i) out(i) = r(i);
    }
  }
  template <class P>
  void print(std::ostream& os, const P& p) const {
    lhs.print(os, p);
    os << " = ";
    rhs.print(os, p);
  }
};

template <Expr L, Expr R>
auto eq(L l, R r) {
  return equation<L, R, eq_kind::value>{std::move(l), std::move(r)};
}
template <Expr L, Expr R>
auto orientation_eq(L l, R r) {
  return equation<L, R, eq_kind::orientation>{std::move(l), std::move(r)};
}
template <Expr L, Expr R>
auto skew_eq(L l, R r) {
  return equation<L, R, eq_kind::skew>{std::move(l), std::move(r)};
}

}  // namespace flange::expr
