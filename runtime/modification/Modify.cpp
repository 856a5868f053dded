#include "modification/Modify.h"

#include <functional>
#include <set>

#include <fmt/format.h>

#include "model/Evaluator.h"

namespace gbx::rt {

std::vector<ModOutcome> evaluateModify(const Model& m, const Assignment& a, const ir::Modify& mod) {
  Evaluator ev(m);
  std::vector<ModOutcome> out;
  int st = mod.stageIndex;
  for (const auto& rule : mod.rules) {
    ModOutcome o;
    o.target = rule.target;
    o.modTarget = rule.modTarget;
    o.text = rule.text;
    // The inputs: every quantity the rule (and its condition) reads, per gear where it differs.
    std::set<std::string> seen;
    std::function<void(const ir::Expr&)> collect = [&](const ir::Expr& e) {
      if (e.op == ir::Op::Quantity) {
        // A per-gear quantity is read for each gear of the stage.
        std::vector<ir::QuantityRef> refs;
        if (e.ref.perGear) {
          for (size_t g = 0; g < m.stages[static_cast<size_t>(st)].ir->gears.size(); ++g) {
            ir::QuantityRef r = e.ref;
            r.gear = static_cast<std::int8_t>(g);
            r.perGear = false;
            refs.push_back(r);
          }
        } else {
          refs.push_back(e.ref);
        }
        for (const auto& r : refs) {
          std::string n = e.name;
          if (r.owner == ir::QuantityRef::Stage) {
            const ir::Stage& stage = *m.stages[static_cast<size_t>(r.index)].ir;
            n = stage.name + "." + (r.gear >= 0 ? stage.gears[static_cast<size_t>(r.gear)] + "." : "") + std::string(cat::keyName(r.key));
          }
          if (!seen.insert(n).second) continue;
          Value v = ev.quantity(r, a);
          const ir::Attribute* given = r.owner == ir::QuantityRef::Stage ? m.attribute(r.index, r.gear, r.key) : nullptr;
          o.inputs.push_back({n, v.isNumber() ? v.mid() : NAN, e.type.dim, given && given->role == ir::Attribute::Fixed});
        }
      }
      for (const auto& x : e.args)
        if (x) collect(*x);
    };
    if (rule.value) collect(*rule.value);
    if (rule.when) collect(*rule.when);
    for (const auto& in : o.inputs)
      if (std::isnan(in.value) && o.error.empty())
        o.error = fmt::format("`{}` cannot be computed for this design: give it, or what it is computed from", in.name);
    if (rule.when) {
      Value w = ev.eval(*rule.when, a);
      o.condition = ir::print(*rule.when);
      if (w.kind != Value::Bool || w.truth == Truth::Unknown) {
        if (o.error.empty()) o.error = "its condition cannot be decided";
      } else {
        o.present = w.truth == Truth::True;
      }
    }
    if (o.present && rule.value) {
      Value v = ev.eval(*rule.value, a);
      if (v.isNumber()) o.value = v.mid();
      else if (o.error.empty()) o.error = "its value cannot be computed";
    }
    out.push_back(std::move(o));
  }
  return out;
}

} // namespace gbx::rt
