#include "passes/Designs.h"

#include "model/Sampling.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"
#include "optimise/Optimise.h"
#include "catalogue/Settings.h"
#include "search/FastKey.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

// The table's rows, one at a time: the materialised table and the CSV listing's rows made
// on demand come from the same code.
class DesignRows : public RowSource {
public:
  DesignRows(const Model& m, const std::vector<Design>* designs, const std::vector<const ir::Expr*>& columnExprs,
             const std::vector<Column>& columns, const std::vector<std::vector<double>>& freedoms,
             const Model* baseline, const Assignment* baseDesign)
      : m_(m), designs_(designs), exprs_(columnExprs), columns_(columns), freedoms_(freedoms), ev_(m), blank_(m), a_(m),
        b_(m), ranges_(m.gearbox.report && m.gearbox.report->ranges) {
    if (!freedoms.empty() || baseline) {
      // Optimised designs, or `relative(x)` columns: scene results and relative values at the
      // scenes' own accuracy.
      installHooks(ev_, m, baseline, baseDesign, ownSceneRtol(m));
    }
    // Rules `q in a..b` with constant bounds: the part of q's interval a design may use.
    std::function<void(const ir::Expr&)> collect = [&](const ir::Expr& e) {
      if (e.op == ir::Op::And || e.op == ir::Op::Forall) {
        for (const auto& x : e.args)
          collect(*x);
        return;
      }
      if (e.op == ir::Op::Within && e.args[0]->op == ir::Op::Quantity && e.args[1]->isConst() && e.args[2]->isConst())
        bounds_[e.args[0]->name] = {e.args[1]->value.toDouble(), e.args[2]->value.toDouble()};
    };
    for (const auto& rule : m.gearbox.rules)
      if (rule.expr) collect(*rule.expr);
    // What every row repeats, made once: tooth-count names, the shown values of the slots.
    toothNames_.resize(m.stages.size());
    for (size_t s = 0; s < m.stages.size(); ++s)
      for (const auto& gear : m.stages[s].ir->gears)
        toothNames_[s].push_back(m.stages[s].ir->name + "." + gear + ".z");
    slotShown_.resize(m.slots.size());
    for (size_t sl = 0; sl < m.slots.size(); ++sl) {
      const Slot& slot = m.slots[sl];
      auto du = units::displayUnitFor(slot.dim);
      // A set's member reads as it was written (`0.2 rad`), its value in the display unit.
      bool written = !du.name.empty() && slot.texts.size() == slot.values.size();
      for (size_t vi = 0; vi < slot.values.size(); ++vi) {
        const Value& v = slot.values[vi];
        // A member of a named set (`iso54_series1`) to twelve digits, as a literal would read: `3 mm`, `1.125 mm`.
        std::string text =
            written ? slot.texts[vi] : fmt::format("{:.12g}", v.lo / du.scale) + (du.name.empty() ? "" : " " + du.name);
        slotShown_[sl].push_back({text, {v.lo / du.scale, du.name, v.lo, du.scale, units::siUnitName(slot.dim)}});
      }
    }
    // Columns that read only the gearbox ratio: from the design's exact ratio directly.
    for (const auto* e : columnExprs)
      direct_.push_back(RatioFn::compile(*e));
  }

  // The designs themselves, when the rows outlive the search's result (a listing).
  void own(std::vector<Design> designs) {
    owned_ = std::move(designs);
    designs_ = &owned_;
    remember(owned_.size());
  }
  // A compact listing: each design made when its row is.
  void own(std::shared_ptr<const DesignList> list) {
    list_ = std::move(list);
    remember(list_->size());
  }

  size_t size() const override { return list_ ? list_->size() : designs_->size(); }

  void row(size_t i, DesignRow& row, bool text) const override {
    const Design& d = design(i);
    const Model& m = m_;
    size_t tooth = 0; // row.teeth's entries are reused: their names repeat from row to row
    row.choices.clear();
    row.choiceValues.clear();
    row.cells.clear();
    row.rank = static_cast<int>(i) + 1;
    row.ratio = d.ratio;
    row.undecided = d.undecided;
    const Assignment& a = assign(i);
    if (i < freedoms_.size())
      for (size_t f = 0; f < freedoms_[i].size(); ++f) {
        const Freedom& fr = m.freedoms[f];
        auto u = units::displayUnitFor(fr.dim);
        row.choices.emplace_back(m.freedoms[f].path,
                                 formatNumber(freedoms_[i][f] / u.scale) + (u.name.empty() ? "" : " " + u.name));
        row.choiceValues.push_back(
            {freedoms_[i][f] / u.scale, u.name, freedoms_[i][f], u.scale, units::siUnitName(fr.dim)});
      }
    row.choice = a.choice;
    row.box = a.box;
    for (size_t s = 0; s < m.stages.size(); ++s) {
      const ir::Stage& st = *m.stages[s].ir;
      for (size_t g = 0; g < st.gears.size(); ++g) {
        // A chosen tooth count is read from its slot; a given one may be a formula.
        int slot = m.info(static_cast<int>(s)).entry(static_cast<int>(g), Q::Z).slot;
        const Value& z =
            slot >= 0
                ? m.slots[static_cast<size_t>(slot)].values[static_cast<size_t>(d.choice[static_cast<size_t>(slot)])]
                : (zScratch_ = ev_.attribute(static_cast<int>(s), static_cast<int>(g), Q::Z, a));
        if (z.exact && z.exact->isInteger())
          setTooth(row, tooth++, toothNames_[s][g], static_cast<long long>(z.exact->num()));
      }
      for (int sl : m.stages[s].slots) {
        const Slot& slot = m.slots[static_cast<size_t>(sl)];
        if (slot.key == Q::Z && slot.gear >= 0) continue;
        size_t vi = static_cast<size_t>(d.choice[static_cast<size_t>(sl)]);
        const Value& v = slot.values[vi];
        if (v.exact && v.exact->isInteger() && slot.dim.dimensionless() && !slot.shaft.setting)
          setTooth(row, tooth++, slot.path, static_cast<long long>(v.exact->num()));
        else {
          const Shown& shown = slotShown_[static_cast<size_t>(sl)][vi];
          row.choices.emplace_back(slot.path, shown.text);
          row.choiceValues.push_back(shown.value);
        }
      }
    }
    row.teeth.resize(tooth);
    for (size_t c = 0; c < exprs_.size(); ++c) {
      Value v = value(i, c, a);
      Cell cell;
      if (v.isNumber()) {
        cell.valid = true;
        cell.lo = v.lo;
        cell.hi = v.hi;
        double sc = columns_[c].scale;
        auto shown = [&](double si) { return formatNumber((si - columns_[c].offset) / sc); };
        if (!text) {
          row.cells.push_back(std::move(cell));
          continue;
        }
        cell.text = v.lo == v.hi ? shown(v.lo) : "[" + shown(v.lo) + ", " + shown(v.hi) + "]";
        // `report { ranges; }`: the column over the design's whole box of freedoms beside it,
        // and the part of that a rule on the quantity allows.
        Value w = ranges_ ? ev_.eval(*exprs_[c], wholeBox(i)) : Value::invalid();
        if (w.isNumber() && w.lo != w.hi) {
          cell.ranged = true;
          cell.rlo = w.lo;
          cell.rhi = w.hi;
          cell.text += " in [" + shown(w.lo) + ", " + shown(w.hi) + "]";
          auto b = exprs_[c]->op == ir::Op::Quantity ? bounds_.find(exprs_[c]->name) : bounds_.end();
          if (b != bounds_.end()) {
            cell.feasible = true;
            cell.flo = std::max(w.lo, b->second.first);
            cell.fhi = std::min(w.hi, b->second.second);
            cell.text += " feasible [" + shown(cell.flo) + ", " + shown(cell.fhi) + "]";
          }
        }
      } else {
        cell.text = "n/a";
      }
      row.cells.push_back(std::move(cell));
    }
  }

  bool valid(size_t i, size_t c) const override { return value(i, c, assign(i)).isNumber(); }

private:
  static void setTooth(DesignRow& row, size_t at, const std::string& name, long long z) {
    if (at == row.teeth.size()) {
      row.teeth.emplace_back(name, z);
      return;
    }
    if (row.teeth[at].first != name) row.teeth[at].first = name;
    row.teeth[at].second = z;
  }

  const Design& design(size_t i) const {
    if (!list_) return (*designs_)[i];
    if (made_ != i) {
      list_->get(i, made_design_);
      made_ = i;
    }
    return made_design_;
  }

  // Design i as the evaluator reads it: its choices, its freedoms at their optimum.
  const Assignment& assign(size_t i) const {
    a_.box = blank_.box;
    a_.choice = design(i).choice;
    if (i < freedoms_.size())
      for (size_t f = 0; f < freedoms_[i].size(); ++f)
        a_.box[f] = {freedoms_[i][f], freedoms_[i][f]};
    return a_;
  }

  const Assignment& wholeBox(size_t i) const {
    b_.box = blank_.box;
    b_.choice = design(i).choice;
    return b_;
  }

  // Column c of design i at its assignment. A listing's rows are made more than once
  // (checked, then written): their values are found once.
  Value value(size_t i, size_t c, const Assignment& a) const {
    const size_t at = i * exprs_.size() + c;
    const bool kept = !knownState_.empty();
    if (kept && knownState_[at] == kPoint) return Value::range(knownValue_[at], knownValue_[at]);
    if (kept && knownState_[at] == kNone) return Value::invalid();
    const Design& d = design(i);
    std::optional<Rational> q =
        direct_[c] && !d.undecided && a.box.empty() ? direct_[c]->exactAt(d.ratio) : std::nullopt;
    Value v = q ? Value::rational(*q) : ev_.eval(*exprs_[c], a);
    if (kept && !v.isNumber()) knownState_[at] = kNone;
    if (kept && v.isNumber() && v.lo == v.hi) {
      knownState_[at] = kPoint;
      knownValue_[at] = v.lo;
    }
    return v;
  }

  struct Shown {
    std::string text;
    DesignRow::Value value;
  };
  const Model& m_;
  const std::vector<Design>* designs_;
  std::vector<Design> owned_;
  std::shared_ptr<const DesignList> list_;
  mutable Design made_design_; // design made_ of list_, the last one made
  mutable size_t made_ = SIZE_MAX;
  std::vector<const ir::Expr*> exprs_;
  std::vector<Column> columns_;
  std::vector<std::vector<double>> freedoms_;
  Evaluator ev_;
  Assignment blank_;
  mutable Assignment a_, b_;
  bool ranges_ = false;
  mutable Value zScratch_;
  // A listing's column values, by row and column, found once: a point's value, or that
  // there is none (an interval is found again).
  enum : std::uint8_t { kUnknown, kPoint, kNone };
  mutable std::vector<std::uint8_t> knownState_;
  mutable std::unique_ptr<double[]> knownValue_; // left unset until found
  void remember(size_t rows) {
    knownState_.assign(rows * exprs_.size(), kUnknown);
    knownValue_.reset(new double[rows * exprs_.size()]);
  }
  std::map<std::string, std::pair<double, double>> bounds_;
  std::vector<std::vector<std::string>> toothNames_;
  std::vector<std::vector<Shown>> slotShown_;
  std::vector<std::optional<RatioFn>> direct_;
};

// lazy: the rows are left to be made as the CSV listing is written (the designs move into
// the table); only for designs without freedoms or baselines, whose values are points.
GearboxReport reportOf(const Model& m, SearchResult& r, const std::vector<const ir::Expr*>& columnExprs,
                       const std::vector<std::string>& columnNames,
                       const std::vector<std::vector<double>>& freedoms = {}, const Model* baseline = nullptr,
                       const Assignment* baseDesign = nullptr, bool lazy = false) {
  GearboxReport g;
  g.name = m.gearbox.name;
  g.count = r.count;
  g.undecided = r.undecided;
  g.window = r.window;
  g.funnel = r.funnel;
  for (size_t i = 0; i < columnExprs.size(); ++i) {
    Column c;
    c.name = columnNames[i];
    // A catalogue quantity is monotone in each freedom: its corners give its exact image.
    // So are both ends of a `worst` over the tolerance corners.
    c.exact =
        columnExprs[i]->op == ir::Op::Quantity || columnExprs[i]->isConst() || columnExprs[i]->op == ir::Op::Scatter;
    auto u = displayUnitOf(*columnExprs[i]);
    c.unit = u.name;
    c.scale = u.scale;
    c.offset = u.offset;
    c.siUnit = units::siUnitName(columnExprs[i]->type.dim);
    g.columns.push_back(c);
  }
  auto rows = std::make_shared<DesignRows>(m, &r.designs, columnExprs, g.columns, freedoms, baseline, baseDesign);
  bool points = freedoms.empty() && !baseline && m.freedoms.empty() &&
                std::none_of(columnExprs.begin(), columnExprs.end(), [](const ir::Expr* e) {
                  return ir::uses(e, {ir::Op::SceneOutput, ir::Op::Relative, ir::Op::Scatter});
                });
  const bool listed = lazy && points && r.listing && r.listing->size() > 0;
  if (r.listing && !listed) { // rows that are not points are held whole
    r.designs = r.listing->all();
    r.listing.reset();
  }
  if (listed || (lazy && points && !r.designs.empty())) {
    if (listed)
      rows->own(std::move(r.listing));
    else
      rows->own(std::move(r.designs));
    r.designs.clear();
    g.rows.resize(1);
    rows->row(0, g.rows[0], true);
    g.source = rows;
    for (auto& c : g.columns)
      c.exact = true; // points: no column shows an interval
    return g;
  }
  g.rows.resize(rows->size());
  for (size_t i = 0; i < rows->size(); ++i)
    rows->row(i, g.rows[i], true);
  // Only a column that shows intervals can show enclosures.
  for (size_t i = 0; i < g.columns.size(); ++i) {
    bool interval = false;
    for (const auto& row : g.rows)
      interval = interval || (row.cells[i].valid && row.cells[i].lo != row.cells[i].hi);
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
  struct Check {
    const ir::Expr* e;
    std::string what;
    int column = -1; // a report column has its value in every row already
    std::optional<std::string> error;
  };
  std::vector<Check> checks;
  auto add = [&](const ir::Expr* e, const std::string& what) {
    if (!e || dynamic(*e)) return;
    Check c{e, what, -1, std::nullopt};
    for (size_t i = 0; i < columns.exprs.size() && i < table.columns.size(); ++i)
      if (columns.exprs[i] == e) c.column = static_cast<int>(i);
    checks.push_back(std::move(c));
  };
  for (const auto& o : m.gearbox.objectives)
    add(o.expr.get(), "objective");
  for (const auto* c : columns.exprs) {
    bool objective = false;
    for (const auto& o : m.gearbox.objectives)
      objective = objective || o.expr.get() == c;
    if (!objective) add(c, "report column");
  }
  Evaluator ev(m);
  Assignment a(m);
  if (table.source) {
    // Made rows: a column's values are asked for alone; a row is made only to report it.
    bool columnsOnly = std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.column >= 0; });
    size_t bad = SIZE_MAX;
    for (size_t i = 0; columnsOnly && i < table.source->size() && bad == SIZE_MAX; ++i)
      for (const auto& c : checks)
        if (!table.source->valid(i, static_cast<size_t>(c.column))) bad = i;
    if (columnsOnly && bad == SIZE_MAX) return errors;
  }
  // One pass over the rows (they may be made on demand), each expression reported once.
  forEachRow(table, [&](const DesignRow& row) {
    for (auto& c : checks) {
      if (c.error) continue;
      if (c.column >= 0 && static_cast<size_t>(c.column) < row.cells.size() &&
          row.cells[static_cast<size_t>(c.column)].valid)
        continue;
      a.choice = row.choice;
      a.box = row.box;
      if (ev.eval(*c.e, a).isNumber()) continue;
      // The first quantity inside that has no value says what is missing.
      // A definition that needs itself (through a computed quantity; sema refuses the rest)
      // is said as such: it is given, and giving it again would not help.
      std::string missing;
      bool cyclic = false;
      const ir::Expr* missingExpr = nullptr;
      std::function<void(const ir::Expr&)> find = [&](const ir::Expr& x) {
        if (!missing.empty()) return;
        (void)Evaluator::tookCycle();
        if (x.op == ir::Op::Quantity && x.type.isNumber() && !ev.eval(x, a).isNumber()) {
          missing = x.name;
          missingExpr = &x;
          cyclic = Evaluator::tookCycle();
        }
        for (const auto& y : x.args)
          if (y) find(*y);
      };
      find(*c.e);
      std::string teeth;
      for (const auto& [n, z] : row.teeth)
        teeth += fmt::format("{}{} = {}", teeth.empty() ? "" : ", ", n, z);
      // A rating result has no value where the rating refused the design; its own message
      // says why, and nothing the user could give would change it.
      const auto& ref = missingExpr ? missingExpr->ref : ir::QuantityRef{};
      bool rated = ref.owner == ir::QuantityRef::Stage && cat::isRatingQuantity(ref.key) && ref.index >= 0 &&
                   static_cast<size_t>(ref.index) < m.gearbox.stages.size();
      // A shaft's quantity has none where the shaft cannot stand at this design: say why.
      std::string shaftWhy;
      if (ref.owner == ir::QuantityRef::Shaft && ref.index >= 0 && static_cast<size_t>(ref.index) < m.gearbox.shafts.size())
        if (!computeShaft(ev, ref.index, a, &shaftWhy, false)) shaftWhy = ": " + shaftWhy;
      c.error = fmt::format(
          "{} `{}` has no value for design {} ({}){}", c.what, ir::print(*c.e), row.rank, teeth,
          missing.empty() ? std::string()
          : cyclic ? fmt::format(": `{}` is defined in terms of itself, through what it is computed from", missing)
          : rated  ? fmt::format(": `{}` comes from the rating of stage `{}`, which cannot rate this design (see its message)",
                                 missing, m.gearbox.stages[static_cast<size_t>(ref.index)].name)
          : !shaftWhy.empty() && shaftWhy[0] == ':' ? shaftWhy
                   : fmt::format(": `{}` cannot be computed; give it, or what it is computed from", missing));
    }
  });
  for (const auto& c : checks)
    if (c.error) errors.push_back(*c.error);
  return errors;
}

Columns reportColumns(const ir::Gearbox& gb) {
  Columns c;
  // A decision's own value is listed with the design (teeth, choices, decided freedoms): a
  // column naming it again would repeat it, under the same header in CSV.
  auto decision = [&](const std::string& text) {
    for (const auto& st : gb.stages)
      for (const auto& at : st.attributes)
        if ((at.role == ir::Attribute::Decision || at.role == ir::Attribute::Freedom) && text == st.name + "." + at.name) return true;
    return false;
  };
  if (gb.report && !gb.report->columns.empty()) {
    for (size_t i = 0; i < gb.report->columns.size(); ++i) {
      if (gb.report->ratioColumn[i] || decision(gb.report->columnTexts[i])) continue; // always shown
      c.exprs.push_back(gb.report->columns[i].get());
      c.names.push_back(gb.report->columnTexts[i]);
    }
  }
  // Every objective's value is listed for every design: after the spec's own columns,
  // unless one of them is the objective already.
  for (const auto& ob : gb.objectives) {
    if (std::find(c.names.begin(), c.names.end(), ob.text) != c.names.end()) continue;
    c.exprs.push_back(ob.expr.get());
    c.names.push_back(ob.text);
  }
  return c;
}

std::string deviationsText(const Model& m, const std::vector<double>& deviations, bool sample) {
  const auto& tol = m.gearbox.tolerances;
  std::string at;
  for (size_t i = 0; i < tol.size() && i < deviations.size(); ++i) {
    double d = deviations[i];
    if (d == 0) continue;
    auto u = units::differenceUnitFor(tol[i].dim);  // an offset from the nominal value
    // A sample's deviation to four figures; a corner's is the amount as written.
    std::string amount = sample ? fmt::format("{:+.4g}", d / u.scale) : fmt::format("{:+g}", d / u.scale);
    at += fmt::format("{}{} {}{}", at.empty() ? "" : ", ", tol[i].target, amount, u.name.empty() ? "" : " " + u.name);
  }
  return at;
}

std::optional<std::string> cornerNote(const Model& m, const Evaluator& ev, const ir::Expr& column,
                                      const std::string& name, const Assignment& a) {
  auto where = ev.worstCorner(column, a);
  if (!where) return std::nullopt;
  std::string at = deviationsText(m, where->deviations, where->sample >= 0);
  if (where->sample >= 0)
    return fmt::format("`{}` of design 1 is found at sample {} of {} ({})", name, where->sample + 1,
                       Sampling::of(m.gearbox).samples, at);
  return fmt::format("`{}` of design 1 is found {}", name, at.empty() ? "at the nominal design" : "at " + at);
}

// A freedom of design 1 decided at an end of its range while objectives rank the designs:
// the optimum may lie beyond the range, which the spec then cuts short.
void boundWarnings(const Model& m, const Optimised& o, GearboxReport& g) {
  if (o.freedoms.empty() || m.gearbox.objectives.empty()) return;
  for (size_t f = 0; f < o.freedoms[0].size() && f < m.freedoms.size(); ++f) {
    const Freedom& fr = m.freedoms[f];
    double v = o.freedoms[0][f], tol = 1e-9 * std::max(std::fabs(fr.hi - fr.lo), 1e-300);
    bool low = std::fabs(v - fr.lo) <= tol, high = std::fabs(v - fr.hi) <= tol;
    if (fr.solved || !(low || high) || fr.hi <= fr.lo) continue;
    auto u = units::displayUnitFor(fr.dim);
    g.warnings.push_back(fmt::format("design 1's `{}` is decided at the {} end of its range ({}{}): the objectives may be better "
                                     "beyond it; widen the range to see",
                                     fr.path, low ? "lower" : "upper", formatNumber(v / u.scale), u.name.empty() ? "" : " " + u.name));
  }
}

GearboxReport designTable(const Model& m, Optimised& o, const Columns& columns, bool lazy) {
  GearboxReport g =
      reportOf(m, o.designs, columns.exprs, columns.names, o.freedoms, o.baseline.get(), o.baselineDesign.get(), lazy);
  // Where each `worst(…)` column finds its value for design 1 (docs/language.md).
  if (!g.rows.empty() && !g.source) {
    Evaluator ev(m);
    Assignment a(m);
    a.choice = g.rows[0].choice;
    a.box = g.rows[0].box;
    for (size_t c = 0; c < columns.exprs.size(); ++c)
      if (auto note = cornerNote(m, ev, *columns.exprs[c], columns.names[c], a)) g.notes.push_back(*note);
    // A pair whose transverse contact ratio is below 1 loses contact between one tooth pair
    // and the next: said even where no rule or rating reads eps_alpha.
    for (size_t st = 0; st < m.gearbox.stages.size(); ++st) {
      Value eps = ev.quantity(ir::QuantityRef{ir::QuantityRef::Stage, static_cast<std::int16_t>(st), -1, false, Q::EpsAlpha}, a);
      if (eps.isNumber() && eps.lo <= 0)
        g.warnings.push_back(fmt::format("stage `{}` of design 1 does not mesh: at its centre distance the tip circles do not "
                                         "reach the line of action (eps_alpha {:.4f}); its other numbers describe no real pair",
                                         m.gearbox.stages[st].name, eps.lo));
      else if (eps.isNumber() && eps.lo < 1)
        g.warnings.push_back(fmt::format("stage `{}` of design 1 has eps_alpha {:.4f}, below 1: in a transverse "
                                      "section no tooth pair is in contact for part of each mesh cycle, and the ISO 6336 "
                                      "rating refuses such a pair",
                                      m.gearbox.stages[st].name, eps.lo));
    }
    boundWarnings(m, o, g);
  }
  return g;
}

std::optional<Assignment> bestDesign(const Model& m, const Optimised& o) {
  Assignment best(m);
  if (!o.designs.designs.empty()) {
    best.choice = o.designs.designs[0].choice;
  } else if (o.designs.listing && o.designs.listing->size() > 0) {
    Design d;
    o.designs.listing->get(0, d);
    best.choice = d.choice;
  } else {
    return std::nullopt;
  }
  if (!o.freedoms.empty())
    for (size_t f = 0; f < o.freedoms[0].size(); ++f)
      best.box[f] = {o.freedoms[0][f], o.freedoms[0][f]};
  return best;
}

void setSceneColumns(GearboxReport& table, const std::vector<SceneColumn>& values) {
  for (const auto& v : values) {
    if (table.rows.empty()) break;
    Cell& c = table.rows[0].cells[v.column];
    c.valid = true;
    c.lo = c.hi = v.value;
    c.text = formatNumber((v.value - table.columns[v.column].offset) / table.columns[v.column].scale);
  }
}

} // namespace gbx::rt::passes
