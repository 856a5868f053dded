#include "units/Unit.h"

#include <cmath>
#include <map>

namespace gbx::units {

namespace {

Number dec(std::int64_t num, std::int64_t den = 1, int pi = 0) {
  return Number::exact(Rational::make(num, den), pi);
}

struct AtomEntry {
  const char* name;
  Number scale;
  Dim dim;
  bool mesh = false;
  Number offset = Number::exact(Rational(0));
};

const std::vector<AtomEntry>& table() {
  using namespace dims;
  static const std::vector<AtomEntry> t = {
      {"m", dec(1), length},
      {"cm", dec(1, 100), length},
      {"mm", dec(1, 1000), length},
      {"um", dec(1, 1000000), length},
      {"\u00B5m", dec(1, 1000000), length},
      {"\u03BCm", dec(1, 1000000), length},
      {"nm", dec(1, 1000000000), length},
      {"km", dec(1000), length},
      {"s", dec(1), time},
      {"ms", dec(1, 1000), time},
      {"us", dec(1, 1000000), time},
      {"min", dec(60), time},
      {"h", dec(3600), time},
      {"Hz", dec(1), frequency},
      {"kHz", dec(1000), frequency},
      {"rad", dec(1), angle},
      {"mrad", dec(1, 1000), angle}, // a shaft's slope at a gear is reported in it
      {"deg", dec(1, 180, 1), angle},
      {"\u00B0", dec(1, 180, 1), angle},
      {"r", dec(2, 1, 1), angle}, // one revolution, so that r/min reads as rpm
      {"rev", dec(2, 1, 1), angle},
      {"rpm", dec(1, 30, 1), angularSpeed},
      {"N", dec(1), force},
      {"kN", dec(1000), force},
      {"MN", dec(1000000), force},
      {"J", dec(1), torque},
      {"W", dec(1), power},
      {"kW", dec(1000), power},
      {"MW", dec(1000000), power},
      {"Pa", dec(1), pressure},
      {"kPa", dec(1000), pressure},
      {"MPa", dec(1000000), pressure},
      {"GPa", dec(1000000000), pressure},
      {"kg", dec(1), mass},
      {"g", dec(1, 1000), mass},
      {"t", dec(1000), mass},
      {"%", dec(1, 100), none},
      {"K", dec(1), temperature},
      {"degC", dec(1), temperature, false, dec(27315, 100)},
      {"mesh_period", dec(1), time, true},
      {"mesh_periods", dec(1), time, true},
  };
  return t;
}

} // namespace

std::optional<Unit> lookupAtom(const std::string& name) {
  for (const auto& a : table())
    if (name == a.name) return Unit{a.scale, a.dim, a.mesh, a.offset};
  return std::nullopt;
}

const std::vector<std::string>& atomNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& a : table()) n.push_back(a.name);
    return n;
  }();
  return names;
}

Unit multiply(const Unit& a, const Unit& b) {
  return Unit{a.scale.mul(b.scale), a.dim * b.dim, a.meshPeriods || b.meshPeriods};
}

Unit divide(const Unit& a, const Unit& b) {
  return Unit{a.scale.div(b.scale), a.dim / b.dim, a.meshPeriods || b.meshPeriods};
}

Unit powerOf(const Unit& a, int e) { return Unit{a.scale.pow(e), a.dim.pow(e), a.meshPeriods}; }

DisplayUnit displayUnitFor(const Dim& d) {
  using namespace dims;
  static const std::vector<std::pair<Dim, DisplayUnit>> prefs = {
      {length, {"mm", 1e-3}},
      {mass, {"kg", 1.0}},
      {time, {"s", 1.0}},
      {angle, {"deg", 3.14159265358979323846 / 180.0}},
      {frequency, {"Hz", 1.0}},
      {angularSpeed, {"rpm", 3.14159265358979323846 / 30.0}},
      {velocity, {"m/s", 1.0}},
      {acceleration, {"m/s^2", 1.0}},
      {force, {"N", 1.0}},
      {torque, {"N*m", 1.0}},
      {power, {"kW", 1e3}},
      {pressure, {"MPa", 1e6}},
      {density, {"kg/m^3", 1.0}},
      {stiffness, {"N/m", 1.0}},
      {dampingCoeff, {"N*s/m", 1.0}},
      {inertia, {"kg*m^2", 1.0}},
      {temperature, {"degC", 1.0, 273.15}},
      {kinematicViscosity, {"mm^2/s", 1e-6}},
      {none, {"", 1.0}},
  };
  for (const auto& [dim, u] : prefs)
    if (dim == d) return u;
  return {d.siUnit(), 1.0};
}

DisplayUnit differenceUnitFor(const Dim& d) {
  DisplayUnit u = displayUnitFor(d);
  if (u.offset != 0) return {d.siUnit(), 1.0};
  return u;
}

std::string showQuantity(const Number& v, const Dim& d) {
  if (d.dimensionless()) return v.str();
  DisplayUnit u = displayUnitFor(d);
  return formatDouble(u.shown(v.toDouble())) + " " + u.name;
}

std::string siUnitName(const Dim& d) {
  static const std::vector<std::pair<Dim, const char*>> named = {
      {dims::force, "N"},           {dims::torque, "N*m"},       {dims::power, "W"},
      {dims::pressure, "Pa"},       {dims::frequency, "Hz"},     {dims::stiffness, "N/m"},
      {dims::dampingCoeff, "N*s/m"}, {dims::angularSpeed, "rad/s"}, {dims::inertia, "kg*m^2"},
  };
  for (const auto& [dim, name] : named)
    if (dim == d) return name;
  return d.siUnit();
}

} // namespace gbx::units
