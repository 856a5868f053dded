#pragma once
// Runtime choices turned into compile-time constants once, when a model composes its
// right-hand side: each listed effect's term is then present or absent in the compiled code.
#include <type_traits>
#include <utility>

namespace gbx::rt::dyn {

template <class F>
void withBool(bool b, F&& f) {
  if (b) f(std::true_type{});
  else f(std::false_type{});
}

template <class F>
void withInt3(int v, F&& f) {
  if (v == 0) f(std::integral_constant<int, 0>{});
  else if (v == 1) f(std::integral_constant<int, 1>{});
  else f(std::integral_constant<int, 2>{});
}

template <class F>
void withInt4(int v, F&& f) {
  if (v == 3) f(std::integral_constant<int, 3>{});
  else withInt3(v, std::forward<F>(f));
}

} // namespace gbx::rt::dyn
