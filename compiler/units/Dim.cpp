#include "units/Dim.h"

#include <utility>
#include <vector>

namespace gbx::units {

Dim Dim::operator*(const Dim& o) const {
  Dim d;
  for (int i = 0; i < Count; ++i) d.e_[i] = static_cast<int8_t>(e_[i] + o.e_[i]);
  return d;
}

Dim Dim::operator/(const Dim& o) const {
  Dim d;
  for (int i = 0; i < Count; ++i) d.e_[i] = static_cast<int8_t>(e_[i] - o.e_[i]);
  return d;
}

Dim Dim::pow(int k) const {
  Dim d;
  for (int i = 0; i < Count; ++i) d.e_[i] = static_cast<int8_t>(e_[i] * k);
  return d;
}

bool Dim::sqrt(Dim& out) const {
  for (int i = 0; i < Count; ++i) {
    if (e_[i] % 2 != 0) return false;
    out.e_[i] = static_cast<int8_t>(e_[i] / 2);
  }
  return true;
}

std::string Dim::siUnit() const {
  if (dimensionless()) return "1";
  static const char* names[Count] = {"m", "kg", "s", "rad", "K"};
  static const int order[Count] = {Mass, Length, Angle, Temperature, Time};
  std::string num, den;
  for (int b : order) {
    int e = e_[b];
    if (e == 0) continue;
    std::string& side = e > 0 ? num : den;
    int a = e > 0 ? e : -e;
    if (!side.empty()) side += "*";
    side += names[b];
    if (a != 1) side += "^" + std::to_string(a);
  }
  if (num.empty()) num = "1";
  if (den.empty()) return num;
  bool compound = den.find('*') != std::string::npos;
  return num + "/" + (compound ? "(" + den + ")" : den);
}

std::string Dim::describe() const {
  static const std::vector<std::pair<Dim, const char*>> named = {
      {dims::none, "a plain number"},
      {dims::length, "a length"},
      {dims::mass, "a mass"},
      {dims::time, "a time"},
      {dims::angle, "an angle"},
      {dims::frequency, "a frequency"},
      {dims::angularSpeed, "an angular speed"},
      {dims::velocity, "a velocity"},
      {dims::acceleration, "an acceleration"},
      {dims::force, "a force"},
      {dims::torque, "a torque"},
      {dims::power, "a power"},
      {dims::pressure, "a pressure (or stiffness per face width)"},
      {dims::density, "a density"},
      {dims::stiffness, "a stiffness"},
      {dims::dampingCoeff, "a damping coefficient"},
      {dims::inertia, "a moment of inertia"},
      {dims::area, "an area"},
      {dims::temperature, "a temperature"},
      {dims::kinematicViscosity, "a kinematic viscosity"},
  };
  for (const auto& [d, n] : named)
    if (d == *this) return n;
  return "a quantity in " + siUnit();
}

} // namespace gbx::units
