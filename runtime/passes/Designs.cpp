#include "passes/Designs.h"

#include <functional>
#include <map>

#include <fmt/format.h>

#include "optimise/Optimise.h"
#include "model/Evaluator.h"
#include "search/FastKey.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

GearboxReport reportOf(const Model& m, const SearchResult& r, const std::vector<const ir::Expr*>& columnExprs,
                       const std::vector<std::string>& columnNames, const std::vector<std::vector<double>>& freedoms = {},
                       const Model* baseline = nullptr, const Assignment* baseDesign = nullptr) {
  Evaluator ev(m);
  if (!freedoms.empty() || baseline) {
    // Optimised designs, or `relative(x)` columns: scene results and relative values at the
    // scenes' own accuracy.
    const ir::Setting* own = m.gearbox.scenes.empty() ? nullptr : ir::findSetting(m.gearbox.scenes[0].accuracy, Q::Rtol);
    installHooks(ev, m, baseline, baseDesign, own && own->value ? own->value->toDouble() : 1e-9);
  }
  GearboxReport g;
  g.name = m.gearbox.name;
  g.count = r.count;
  g.undecided = r.undecided;
  g.window = r.window;
  g.funnel = r.funnel;
  // Rules `q in a..b` with constant bounds: the part of q's interval a design may use.
  std::map<std::string, std::pair<double, double>> bounds;
  std::function<void(const ir::Expr&)> collect = [&](const ir::Expr& e) {
    if (e.op == ir::Op::And || e.op == ir::Op::Forall) {
      for (const auto& x : e.args) collect(*x);
      return;
    }
    if (e.op == ir::Op::Within && e.args[0]->op == ir::Op::Quantity && e.args[1]->isConst() && e.args[2]->isConst())
      bounds[e.args[0]->name] = {e.args[1]->value.toDouble(), e.args[2]->value.toDouble()};
  };
  for (const auto& rule : m.gearbox.rules)
    if (rule.expr) collect(*rule.expr);
  for (size_t i = 0; i < columnExprs.size(); ++i) {
    Column c;
    c.name = columnNames[i];
    // A catalogue quantity is monotone in each freedom: its corners give its exact image.
    c.exact = columnExprs[i]->op == ir::Op::Quantity || columnExprs[i]->isConst();
    auto u = units::displayUnitFor(columnExprs[i]->type.dim);
    // Imbalances read best in percent.
    if (columnExprs[i]->op == ir::Op::Quantity && columnExprs[i]->ref.key == Q::Imbalance) u = {"%", 0.01};
    c.unit = u.name;
    c.scale = u.scale;
    g.columns.push_back(c);
  }
  // What every row repeats, made once: tooth-count names, the shown values of the slots.
  std::vector<std::vector<std::string>> toothNames(m.stages.size());
  for (size_t s = 0; s < m.stages.size(); ++s)
    for (const auto& gear : m.stages[s].ir->gears) toothNames[s].push_back(m.stages[s].ir->name + "." + gear + ".z");
  struct Shown {
    std::string text;
    DesignRow::Value value;
  };
  std::vector<std::vector<Shown>> slotShown(m.slots.size());
  for (size_t sl = 0; sl < m.slots.size(); ++sl) {
    const Slot& slot = m.slots[sl];
    const ir::Stage& st = *m.stages[static_cast<size_t>(slot.stage)].ir;
    auto du = units::displayUnitFor(st.find(slot.attr) ? st.find(slot.attr)->dim : units::Dim{});
    for (const Value& v : slot.values)
      slotShown[sl].push_back({formatNumber(v.lo / du.scale) + (du.name.empty() ? "" : " " + du.name), {v.lo / du.scale, du.name}});
  }
  // Columns that read only the gearbox ratio: from the design's exact ratio directly.
  std::vector<std::optional<RatioFn>> direct;
  for (const auto* e : columnExprs) direct.push_back(RatioFn::compile(*e));
  const Assignment blank(m);
  Assignment a(m);
  int rank = 0;
  for (const auto& d : r.designs) {
    DesignRow row;
    row.rank = ++rank;
    row.ratio = d.ratio;
    row.undecided = d.undecided;
    a.box = blank.box;
    a.choice = d.choice;
    size_t ri = static_cast<size_t>(row.rank - 1);
    if (ri < freedoms.size())
      for (size_t f = 0; f < freedoms[ri].size(); ++f) {
        a.box[f] = {freedoms[ri][f], freedoms[ri][f]};
        const Freedom& fr = m.freedoms[f];
        const ir::Attribute* at = m.attribute(fr.stage, fr.gear, fr.key);
        auto u = units::displayUnitFor(at ? at->dim : units::Dim{});
        row.choices.emplace_back(m.freedoms[f].path, formatNumber(freedoms[ri][f] / u.scale) + (u.name.empty() ? "" : " " + u.name));
        row.choiceValues.push_back({freedoms[ri][f] / u.scale, u.name});
      }
    row.choice = a.choice;
    row.box = a.box;
    for (size_t s = 0; s < m.stages.size(); ++s) {
      const ir::Stage& st = *m.stages[s].ir;
      for (size_t g = 0; g < st.gears.size(); ++g) {
        Value z = ev.attribute(static_cast<int>(s), static_cast<int>(g), Q::Z, a);
        if (z.exact && z.exact->isInteger()) row.teeth.emplace_back(toothNames[s][g], static_cast<long long>(z.exact->num()));
      }
      for (int sl : m.stages[s].slots) {
        const Slot& slot = m.slots[static_cast<size_t>(sl)];
        if (slot.key == Q::Z && slot.gear >= 0) continue;
        size_t vi = static_cast<size_t>(d.choice[static_cast<size_t>(sl)]);
        const Value& v = slot.values[vi];
        if (v.exact && v.exact->isInteger()) row.teeth.emplace_back(slot.path, static_cast<long long>(v.exact->num()));
        else {
          const Shown& shown = slotShown[static_cast<size_t>(sl)][vi];
          row.choices.emplace_back(slot.path, shown.text);
          row.choiceValues.push_back(shown.value);
        }
      }
    }
    for (size_t i = 0; i < columnExprs.size(); ++i) {
      std::optional<Rational> q = direct[i] && !row.undecided && a.box.empty() ? direct[i]->exactAt(d.ratio) : std::nullopt;
      Value v = q ? Value::rational(*q) : ev.eval(*columnExprs[i], a);
      Cell c;
      if (v.isNumber()) {
        c.valid = true;
        c.lo = v.lo;
        c.hi = v.hi;
        double s = g.columns[i].scale;
        c.text = v.lo == v.hi ? formatNumber(v.lo / s) : "[" + formatNumber(v.lo / s) + ", " + formatNumber(v.hi / s) + "]";
        auto b = columnExprs[i]->op == ir::Op::Quantity ? bounds.find(columnExprs[i]->name) : bounds.end();
        if (b != bounds.end() && v.lo != v.hi) {
          c.feasible = true;
          c.flo = std::max(v.lo, b->second.first);
          c.fhi = std::min(v.hi, b->second.second);
          c.text += " feasible [" + formatNumber(c.flo / s) + ", " + formatNumber(c.fhi / s) + "]";
        }
      } else {
        c.text = "n/a";
      }
      row.cells.push_back(c);
    }
    g.rows.push_back(std::move(row));
  }
  // Only a column that shows intervals can show enclosures.
  for (size_t i = 0; i < g.columns.size(); ++i) {
    bool interval = false;
    for (const auto& row : g.rows) interval = interval || (row.cells[i].valid && row.cells[i].lo != row.cells[i].hi);
    if (!interval) g.columns[i].exact = true;
  }
  return g;
}

} // namespace

std::vector<std::string> unevaluated(const Model& m, const GearboxReport& table, const Columns& columns) {
  std::vector<std::string> errors;
  if (table.rows.empty()) return errors;
  // Needs scenes or a baseline: evaluated by the optimiser and the scene pass, not here.
  auto dynamic = [](const ir::Expr& e) { return ir::uses(&e, {ir::Op::SceneOutput, ir::Op::Relative}); };
  Evaluator ev(m);
  auto check = [&](const ir::Expr& e, const std::string& what) {
    if (dynamic(e)) return;
    for (const auto& row : table.rows) {
      Assignment a(m);
      a.choice = row.choice;
      a.box = row.box;
      if (ev.eval(e, a).isNumber()) continue;
      // The first quantity inside that has no value says what is missing.
      std::string missing;
      std::function<void(const ir::Expr&)> find = [&](const ir::Expr& x) {
        if (!missing.empty()) return;
        if (x.op == ir::Op::Quantity && x.type.isNumber() && !ev.eval(x, a).isNumber()) missing = x.name;
        for (const auto& y : x.args)
          if (y) find(*y);
      };
      find(e);
      std::string teeth;
      for (const auto& [n, z] : row.teeth) teeth += fmt::format("{}{} = {}", teeth.empty() ? "" : ", ", n, z);
      errors.push_back(fmt::format("{} `{}` has no value for design {} ({}){}", what, ir::print(e), row.rank, teeth,
                                   missing.empty() ? std::string()
                                                   : fmt::format(": `{}` cannot be computed; give it, or what it is computed from", missing)));
      return;  // once per expression
    }
  };
  for (const auto& o : m.gearbox.objectives)
    if (o.expr) check(*o.expr, "objective");
  for (const auto* c : columns.exprs) {
    bool objective = false;
    for (const auto& o : m.gearbox.objectives) objective = objective || o.expr.get() == c;
    if (c && !objective) check(*c, "report column");
  }
  return errors;
}

Columns reportColumns(const ir::Gearbox& gb) {
  Columns c;
  if (gb.report && !gb.report->columns.empty()) {
    for (size_t i = 0; i < gb.report->columns.size(); ++i) {
      if (gb.report->ratioColumn[i]) continue;  // always shown
      c.exprs.push_back(gb.report->columns[i].get());
      c.names.push_back(gb.report->columnTexts[i]);
    }
  } else {
    for (const auto& ob : gb.objectives) {
      c.exprs.push_back(ob.expr.get());
      c.names.push_back(ob.text);
    }
  }
  return c;
}

GearboxReport designTable(const Model& m, const Optimised& o, const Columns& columns) {
  return reportOf(m, o.designs, columns.exprs, columns.names, o.freedoms, o.baseline.get(), o.baselineDesign.get());
}

std::optional<Assignment> bestDesign(const Model& m, const Optimised& o) {
  if (o.designs.designs.empty()) return std::nullopt;
  Assignment best(m);
  best.choice = o.designs.designs[0].choice;
  if (!o.freedoms.empty())
    for (size_t f = 0; f < o.freedoms[0].size(); ++f) best.box[f] = {o.freedoms[0][f], o.freedoms[0][f]};
  return best;
}

void setSceneColumns(GearboxReport& table, const std::vector<SceneColumn>& values) {
  for (const auto& v : values) {
    if (table.rows.empty()) break;
    Cell& c = table.rows[0].cells[v.column];
    c.valid = true;
    c.lo = c.hi = v.value;
    c.text = formatNumber(v.value / table.columns[v.column].scale);
  }
}

} // namespace gbx::rt::passes
