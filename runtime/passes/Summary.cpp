#include "passes/Summary.h"

#include <fmt/format.h>

#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

// A number in its display unit to ten significant digits (12000 rpm, not 12000.000000000002);
// a service life in hours, as ratings state it.
std::string quantity(const units::Number& v, const units::Dim& d, cat::Q key) {
  units::DisplayUnit u = key == cat::Q::RatingLife ? units::DisplayUnit{"h", 3600} : units::displayUnitFor(d);
  std::string n = fmt::format("{:.10g}", u.shown(v.toDouble()));
  return u.name.empty() ? n : n + " " + u.name;
}

// A fixed value as the summary shows it: a number in its display unit, a word as written.
std::string shown(const ir::Attribute& a) {
  if (!a.symbol.empty()) return a.symbol;
  if (a.role != ir::Attribute::Fixed || !a.value || a.value->op != ir::Op::Const) return "";
  return quantity(a.value->value, a.dim, a.key);
}

// `rating.lubricant.viscosity_40` reads as `viscosity_40` beside its stage.
std::string_view shortName(cat::Q key) {
  std::string_view n = cat::keyName(key);
  size_t dot = n.rfind('.');
  return dot == std::string_view::npos ? n : n.substr(dot + 1);
}

// The stage inputs the summary names, in this order (the rest is in the tables).
// The fixed geometry first (a pinned design's module and face width identify it), then what
// the rating is given.
constexpr cat::Q kStageInputs[] = {cat::Q::NormalModule, cat::Q::Module, cat::Q::HelixAngle, cat::Q::FaceWidth,
                                   cat::Q::OuterConeDistance, cat::Q::Material, cat::Q::Accuracy, cat::Q::RatingApplicationFactor,
                                   cat::Q::RatingLife, cat::Q::RatingViscosity40, cat::Q::RatingOilTemperature};

} // namespace

std::vector<GearboxReport::Input> decisiveInputs(const ir::Gearbox& gearbox) {
  std::vector<GearboxReport::Input> inputs;
  for (const auto& s : gearbox.operating) {
    if (!s.value) continue;
    inputs.push_back({s.name, s.symbol.empty() ? quantity(*s.value, s.dim, s.key) : s.symbol});
  }
  for (const auto& st : gearbox.stages) {
    std::vector<std::string> parts = {ir::stageKindName(st.kind)};
    for (cat::Q key : kStageInputs) {
      // The stage's value, or each gear's where the gears differ (`pinion.material = …`).
      std::vector<std::string> gears;
      for (const auto& a : st.attributes) {
        if (a.key != key) continue;
        std::string v = shown(a);
        if (v.empty()) continue;
        if (a.gear < 0) parts.push_back(fmt::format("{} {}", shortName(key), v));
        else if (static_cast<size_t>(a.gear) < st.gears.size()) gears.push_back(st.gears[static_cast<size_t>(a.gear)] + " " + v);
      }
      if (!gears.empty()) parts.push_back(fmt::format("{} {}", shortName(key), fmt::join(gears, " / ")));
    }
    if (parts.size() == 1) continue;  // nothing beyond its kind: the tables say it
    inputs.push_back({"stage " + st.name, fmt::format("{}", fmt::join(parts, ", ")), true});
  }
  return inputs;
}

} // namespace gbx::rt::passes
