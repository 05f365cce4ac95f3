// A list of types, its I-th element, and values of a list of types held side
// by side and reached by position.
//
// Both look an element up as one base among a class's bases, one base per
// element, so that nothing instantiated holds the rest of the list. The
// recursive alternatives (std::tuple_element in GCC 12's libstdc++, which
// steps three elements at a time; a type_list split head from tail) make a
// class per step with the remaining elements: quadratic in the length of
// the list: at 128 links (513 components) the lookup alone cost GCC 1.2 GB
// of its 3.3 GB front end. A lookup is memoised per position and list
// (nth<I, type_list<Ts...>>, two arguments however long the list), so each
// position's base is searched for once.
#pragma once
#include <cstddef>
#include <utility>

namespace flange::detail {

template <class...>
struct type_list {};

template <std::size_t I, class T>
struct indexed_type {
  using type = T;
};
template <class Seq, class... Ts>
struct type_index;
template <std::size_t... I, class... Ts>
struct type_index<std::index_sequence<I...>, Ts...> : indexed_type<I, Ts>... {};
template <std::size_t I, class T>
indexed_type<I, T> select_indexed(const indexed_type<I, T>&);

/// The index of a list, once per list.
template <class List>
struct list_index;
template <class... Ts>
struct list_index<type_list<Ts...>> {
  using type = type_index<std::index_sequence_for<Ts...>, Ts...>;
};
/// Element I of List. It takes the list as one type, not its elements: an
/// instantiation then holds two arguments, where nth<I, Ts...> held all N
/// elements (N lookups of N arguments each).
template <int I, class List>
struct nth {
  using type = typename decltype(select_indexed<std::size_t(I)>(
      std::declval<const typename list_index<List>::type&>()))::type;
};
template <int I, class... Ts>
using nth_t = typename nth<I, type_list<Ts...>>::type;

/// One value of type T at position I of an indexed_values.
template <std::size_t I, class T>
struct indexed_value {
  T value;
};
/// Values of the types Ts (values or references), side by side;
/// value_at<I>(v) is the I-th.
template <class Seq, class... Ts>
struct indexed_values;
template <std::size_t... I, class... Ts>
struct indexed_values<std::index_sequence<I...>, Ts...> : indexed_value<I, Ts>... {
  /// Each value initialised from one argument, forwarded (so references
  /// are held as references, and a value is moved or copied once).
  template <class... A>
  explicit indexed_values(std::in_place_t, A&&... a) : indexed_value<I, Ts>{std::forward<A>(a)}... {}
};
/// The value at position K of an indexed_values: const T& for a value held
/// by a const indexed_values, the referred object for a reference. T is
/// deduced from the one base indexed_value<K, T>, so an instantiation names
/// that value's type alone; a member get<K> would carry the whole list in
/// its mangled name (tens of kilobytes for a scene of a few hundred
/// components, each mangled again by the compiler).
template <std::size_t K, class T>
[[nodiscard]] constexpr auto& value_at(const indexed_value<K, T>& v) {
  return v.value;
}
template <std::size_t K, class T>
[[nodiscard]] constexpr auto& value_at(indexed_value<K, T>& v) {
  return v.value;
}

}  // namespace flange::detail
