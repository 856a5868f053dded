#include "modification/Modify.h"

#include <functional>
#include <set>

#include <fmt/format.h>

#include "search/Evaluator.h"

namespace gbx::rt {

std::vector<ModOutcome> evaluateModify(const Model& m, const Assignment& a, const ir::Modify& mod) {
  Evaluator ev(m);
  std::vector<ModOutcome> out;
  int st = m.stageIndex(mod.stage);
  for (const auto& rule : mod.rules) {
    ModOutcome o;
    o.target = rule.target;
    o.text = rule.text;
    // The inputs: every quantity the rule (and its condition) reads, per gear where it differs.
    std::set<std::string> seen;
    std::function<void(const ir::Expr&)> collect = [&](const ir::Expr& e) {
      if (e.op == ir::Op::Quantity) {
        std::vector<std::string> names;
        if (e.type.kind == ir::Type::PerGear) {
          auto dot = e.name.find('.');
          for (const auto& g : m.stages[static_cast<size_t>(st)].ir->gears) names.push_back(e.name.substr(0, dot) + "." + g + e.name.substr(dot));
        } else {
          names.push_back(e.name);
        }
        for (const auto& n : names) {
          if (!seen.insert(n).second) continue;
          Value v = ev.quantity(n, a);
          auto dot = n.find('.');
          std::string attr = dot == std::string::npos ? n : n.substr(dot + 1);
          const ir::Attribute* given = st >= 0 ? m.attribute(st, attr) : nullptr;
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
