#include "passes/Modifications.h"

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "modification/Modify.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

Modifications modifications(const Model& m, const Assignment& best) {
  Modifications result;
  for (const auto& md : m.gearbox.modifies) {
    ModifyReport mr;
    mr.stage = md.stage;
    for (const auto& out : evaluateModify(m, best, md)) {
      ModRow row;
      row.target = out.target;
      row.text = out.text;
      row.present = out.present;
      row.error = out.error;
      if (out.modTarget >= 0 && cat::modificationReadsInMicrometres(static_cast<cat::Mod>(out.modTarget))) row.unit = units::micrometres();
      if (out.value) {
        row.valid = true;
        row.si = *out.value;
        row.shown = fmt::format("{:.2f} {}", row.unit.shown(*out.value), row.unit.name);
      }
      if (!out.condition.empty()) row.condition = out.condition;
      for (const auto& in : out.inputs) {
        auto u = units::displayUnitFor(in.dim);
        std::string v = in.dim == units::dims::length ? formatLength(in.value)
                                                      : formatNumber(in.value / u.scale) + (u.name.empty() ? "" : " " + u.name);
        row.inputs.push_back(fmt::format("{} = {}{}", in.name, v, in.given ? " (given)" : ""));
        row.inputsSI.emplace_back(in.name, in.value);
      }
      if (!row.error.empty()) result.errors.push_back(fmt::format("modify {}: `{}`: {}", md.stage, row.target, row.error));
      mr.rows.push_back(std::move(row));
    }
    result.modifications.push_back(std::move(mr));
  }
  return result;
}

} // namespace gbx::rt::passes
