#pragma once
// The registry of integration methods a scene's `accuracy { method = … }` may name. Each
// has one runtime row in runtime/dynamics/Ode.cpp (its GSL stepper).
#include <cstdint>
#include <string_view>
#include <vector>

namespace gbx::cat {

enum class Method : std::uint8_t { Rk8pd, Rkf45, Rkck, Rk4, Msbdf };

struct MethodSpec {
  Method id;
  std::string_view name;
  bool implicit;  // needs the Jacobian
};

inline constexpr MethodSpec kMethods[] = {
    {Method::Rk8pd, "rk8pd", false}, {Method::Rkf45, "rkf45", false}, {Method::Rkck, "rkck", false},
    {Method::Rk4, "rk4", false},     {Method::Msbdf, "msbdf", true},
};

inline const MethodSpec& methodSpec(Method m) { return kMethods[static_cast<size_t>(m)]; }

inline const MethodSpec* findMethod(std::string_view name) {
  for (const auto& m : kMethods)
    if (m.name == name) return &m;
  return nullptr;
}

inline std::vector<std::string> methodNames() {
  std::vector<std::string> v;
  for (const auto& m : kMethods) v.emplace_back(m.name);
  return v;
}

} // namespace gbx::cat
