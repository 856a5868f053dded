#pragma once
// Unit atoms (docs/language.md) and unit expressions built from them.
#include <optional>
#include <string>
#include <vector>

#include "units/Dim.h"
#include "units/Number.h"

namespace gbx::units {

struct Unit {
  Number scale = Number::exact(Rational(1));  // SI value of one unit
  Dim dim;
  // `mesh_period(s)`: a time measured in the scene's own mesh period, resolved at run time.
  bool meshPeriods = false;
  // SI value of the unit's zero: 273.15 K for `degC`. It applies to a literal in that unit
  // alone (`80 degC`); a compound unit (`degC/s`) measures differences and drops it.
  Number offset = Number::exact(Rational(0));
};

// An atom by its spelling (`mm`, `µm`, `°`, `rpm`, `%`, `mesh_periods`); nullopt if unknown.
std::optional<Unit> lookupAtom(const std::string& name);
// Every atom's spelling, for "did you mean" hints.
const std::vector<std::string>& atomNames();

Unit multiply(const Unit& a, const Unit& b);
Unit divide(const Unit& a, const Unit& b);
Unit powerOf(const Unit& a, int e);

// Preferred engineering unit in reports for a dimension ("mm", "rpm", "kN*m"), with its
// SI scale; SI itself where there is no better one.
struct DisplayUnit {
  std::string name;
  double scale;
  double offset = 0;  // SI value of the unit's zero (degC)
  double shown(double si) const { return (si - offset) / scale; }
  double si(double shownValue) const { return shownValue * scale + offset; }
};
DisplayUnit displayUnitFor(const Dim& d);
// The SI unit of a dimension as an engineer writes it (`N`, `N*m`, `W`, `Pa`, `rad/s`), else
// its base units (`Dim::siUnit`); `1` for a plain number. JSON's `si_unit` fields.
std::string siUnitName(const Dim& d);
// Transmission errors, deviations and the other micrometre-scale lengths (docs/reports.md).
inline DisplayUnit micrometres() { return {"um", 1e-6}; }
// The display unit of a difference of this dimension: a temperature difference reads in K
// (degC's zero does not apply to it). Reports show an expression that is not an absolute
// temperature quantity this way.
DisplayUnit differenceUnitFor(const Dim& d);
// A value in its display unit, for messages: "3000 kW", "-3 mm", "0.29".
std::string showQuantity(const Number& v, const Dim& d);

} // namespace gbx::units
