#pragma once
// One catalogue row for a named number or word: a stage or gear attribute, a gearbox
// quantity, a setting or an effect parameter. Sema checks against these rows; lowering
// turns the names into their `Q` ids.
#include <optional>
#include <string>
#include <vector>

#include "catalogue/Keys.h"
#include "units/Dim.h"
#include "units/Number.h"

namespace gbx::cat {

using units::Dim;

enum class AttrRole {
  Input,    // fixed or made a decision by the spec
  Derived,  // computed; cannot be set
  Either,   // derived unless the spec fixes it (center_distance)
};

enum class ValueKind { Number, Material, Symbol, Stage, List }; // List: `{a, b, …}` of numbers

struct AttrSpec {
  std::string name;
  Q key = Q::None;
  Dim dim;
  bool integer = false;
  AttrRole role = AttrRole::Input;
  std::string meaning;
  ValueKind value = ValueKind::Number;
  std::optional<Dim> altDim;           // a second accepted dimension (Hz for deg/s)
  std::optional<units::Number> dflt;   // default when absent (SI)
  bool required = false;
  bool positive = false;               // must be > 0
  std::optional<units::Number> atLeast, atMost;  // inclusive bounds (SI), where the standard sets them
  std::string unitHint;                // the unit to suggest for a bare number, when not the display unit
  bool meshPeriods = false;            // may be given in mesh periods
  bool budget = false;                 // atMost is a size budget (E0411), not a physical bound
  std::vector<std::string> symbols;    // accepted words for ValueKind::Symbol; for a Number, words it takes instead of one
  bool sceneRef = false;               // a Number that may instead name a scene (`dynamic_factor = scene vib`)
  std::string example;                 // a typical value as a spec writes it, for the reference (else from the bounds)
  std::string exampleGear;             // the gear a gear row's example names (else the kind's first)
};

// Row builders shared by the catalogue files.
namespace rows {
// A table of rows moved into place (an initializer list would copy each row).
template <class... A> std::vector<AttrSpec> attrs(A&&... a) {
  std::vector<AttrSpec> v;
  v.reserve(sizeof...(a));
  (v.push_back(std::forward<A>(a)), ...);
  return v;
}
AttrSpec in(std::string n, Dim d, std::string meaning);
AttrSpec pos(std::string n, Dim d, std::string meaning);
AttrSpec count(std::string n, std::string meaning);
// A list of constant numbers of one dimension (`{1 um, -2 um, 0 um}`).
AttrSpec list(std::string n, Dim d, std::string meaning);
// A whole number of any sign (its range set by `bounded`).
AttrSpec whole(std::string n, std::string meaning);
AttrSpec derived(std::string n, Dim d, std::string meaning, bool integer = false);
AttrSpec withDefault(AttrSpec a, units::Number v);
AttrSpec required(AttrSpec a);
AttrSpec symbol(std::string n, std::vector<std::string> words, std::string meaning);
AttrSpec keyed(AttrSpec a, Q key);
AttrSpec bounded(AttrSpec a, std::optional<units::Number> lo, std::optional<units::Number> hi);
// The unit a bare number is suggested in, where the display unit would not fit its size
// (`clearance = 100` means 100 um, not 100 mm).
AttrSpec hinted(AttrSpec a, std::string unit);
// A count no larger than `most` (catalogue/Budgets.h).
AttrSpec budgeted(AttrSpec a, std::int64_t most);
units::Number deg(std::int64_t d);
units::Number num(std::int64_t n, std::int64_t d = 1);
} // namespace rows

} // namespace gbx::cat
