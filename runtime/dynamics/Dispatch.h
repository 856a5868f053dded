#pragma once
// Runtime choices turned into compile-time constants once, when a model composes its
// right-hand side: each listed effect's term is then present or absent in the compiled code.
#include <type_traits>

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

} // namespace gbx::rt::dyn
