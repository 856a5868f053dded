#include "optimise/Decide.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "catalogue/Settings.h"
#include "optimise/Decider.h"
#include "search/Conjuncts.h"
#include "search/Search.h"

namespace gbx::rt {

namespace {

// A ranking key's value at a point: the expression's, negated where maximised; NaN if none.
double keyAt(const Evaluator& ev, const ir::Expr* e, bool minimize, const Assignment& a) {
  Value v = e ? ev.eval(*e, a) : Value::invalid();
  return v.isNumber() ? (minimize ? v.mid() : -v.mid()) : NAN;
}

// The keys a design ranks by: `sort by` (where the report has one) before the objectives.
std::vector<double> withSortKey(const Evaluator& ev, const Assignment& a, const std::vector<double>& objectives) {
  const auto& report = ev.model().gearbox.report;
  if (!report || !report->sortBy) return objectives;
  std::vector<double> keys = {keyAt(ev, report->sortBy.get(), true, a)};
  keys.insert(keys.end(), objectives.begin(), objectives.end());
  return keys;
}

} // namespace

std::vector<double> rankingKeys(const Evaluator& ev, const Assignment& a, bool withSortBy) {
  std::vector<double> objectives;
  for (const auto& o : ev.model().gearbox.objectives)
    objectives.push_back(keyAt(ev, o.expr.get(), o.minimize, a));
  return withSortBy ? withSortKey(ev, a, objectives) : objectives;
}

int compareKeys(const std::vector<double>& x, const std::vector<double>& y) {
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    bool xn = std::isnan(x[i]), yn = std::isnan(y[i]);
    if (xn || yn) {
      if (xn != yn) return xn ? 1 : -1; // no value ranks last
      continue;
    }
    double a = rankingKey(x[i]), b = rankingKey(y[i]);
    if (a != b) return a < b ? -1 : 1;
  }
  return 0;
}

namespace {

// Which stages' freedoms an expression reads (following lets), and whether it reads nothing
// but stage `own`'s own attributes and geometry: no other stage, no gearbox quantity, nothing
// of the operating point, no tolerance corners.
void reads(const Model& m, const ir::Expr& e, int own, std::set<int>& stages, bool& ownOnly, int depth = 0) {
  if (depth > 64) {
    ownOnly = false;
    return;
  }
  switch (e.op) {
  case ir::Op::Quantity:
    if (e.ref.owner == ir::QuantityRef::Stage) {
      if (m.hasStage(e.ref.index) && !m.info(e.ref.index).freedoms.empty()) stages.insert(e.ref.index);
      if (e.ref.index != own || cat::dependsOnOperatingPoint(e.ref.key)) ownOnly = false;
    } else if (e.ref.owner != ir::QuantityRef::Material) {
      ownOnly = false;
    }
    break;
  case ir::Op::Let:
    if (e.let >= 0 && static_cast<size_t>(e.let) < m.gearbox.lets.size() &&
        m.gearbox.lets[static_cast<size_t>(e.let)].expr)
      reads(m, *m.gearbox.lets[static_cast<size_t>(e.let)].expr, own, stages, ownOnly, depth + 1);
    break;
  case ir::Op::Scatter:
  case ir::Op::SceneOutput:
  case ir::Op::Relative:
    ownOnly = false;
    // Corners move freedoms of any stage the tolerances name.
    for (const auto& t : m.gearbox.tolerances)
      if (t.ref.owner == ir::QuantityRef::Stage && m.hasStage(t.ref.index) && !m.info(t.ref.index).freedoms.empty())
        stages.insert(t.ref.index);
    break;
  default: break;
  }
  for (const auto& x : e.args)
    if (x) reads(m, *x, own, stages, ownOnly, depth + 1);
}

// The terms of a sum, with their signs (`a.mass + b.mass`, `x - y`).
void terms(const ir::Expr& e, double sign, std::vector<std::pair<const ir::Expr*, double>>& out) {
  if (e.op == ir::Op::Add && e.args.size() == 2) {
    terms(*e.args[0], sign, out);
    terms(*e.args[1], sign, out);
  } else if (e.op == ir::Op::Sub && e.args.size() == 2) {
    terms(*e.args[0], sign, out);
    terms(*e.args[1], -sign, out);
  } else if (e.op == ir::Op::Neg && e.args.size() == 1) {
    terms(*e.args[0], -sign, out);
  } else {
    out.emplace_back(&e, sign);
  }
}

} // namespace

FreedomPlan::FreedomPlan(const Model& m) : m_(m) {
  for (const auto& r : m.gearbox.rules) {
    if (!r.expr) continue;
    std::vector<const ir::Expr*> parts;
    split(*r.expr, parts);
    for (const auto* e : parts)
      parts_.push_back({e, parts.size() == 1 ? r.text : ruleText(*e)});
  }
  // No freedoms: the design's one point, where every rule is checked (`worst` over the
  // tolerances, which the search defers).
  if (m.freedoms.empty()) {
    rest_ = parts_;
    return;
  }
  auto whole = [&] {
    groups.clear();
    FreedomGroup g;
    for (size_t f = 0; f < m.freedoms.size(); ++f)
      if (!m.freedoms[f].solved) g.freedoms.push_back(static_cast<int>(f));
    g.rules = parts_;
    g.allObjectives = true;
    groups.push_back(std::move(g));
  };
  // A shaft's freedom moves what its stages' ratings read: every freedom decided together.
  if (m.shaftFreedoms) {
    whole();
    return;
  }
  // Separable when every rule reads the freedoms of one stage at most and the one objective
  // is a sum of terms that each do: then each stage's freedoms are decided on their own.
  std::vector<std::set<int>> ruleStages;
  for (const auto& r : parts_) {
    std::set<int> st;
    bool own = true;
    reads(m, *r.expr, -1, st, own);
    if (st.size() > 1) {
      whole();
      return;
    }
    ruleStages.push_back(st);
  }
  std::vector<std::pair<const ir::Expr*, double>> objectiveTerms;
  if (m.gearbox.objectives.size() > 1) {
    whole();
    return;
  }
  if (m.gearbox.objectives.size() == 1) {
    const auto& o = m.gearbox.objectives[0];
    if (!o.expr) {
      whole();
      return;
    }
    terms(*o.expr, o.minimize ? 1.0 : -1.0, objectiveTerms);
  }
  std::vector<std::set<int>> termStages;
  for (const auto& [e, sign] : objectiveTerms) {
    std::set<int> st;
    bool own = true;
    reads(m, *e, -1, st, own);
    if (st.size() > 1) {
      whole();
      return;
    }
    termStages.push_back(st);
  }
  for (size_t s = 0; s < m.stages.size(); ++s) {
    const auto& fs = m.stages[s].freedoms;
    if (fs.empty()) continue;
    FreedomGroup g;
    g.stage = static_cast<int>(s);
    g.freedoms = fs;
    bool own = true;
    std::set<int> ignored;
    for (size_t r = 0; r < parts_.size(); ++r)
      if (ruleStages[r].count(g.stage)) {
        g.rules.push_back(parts_[r]);
        reads(m, *parts_[r].expr, g.stage, ignored, own);
      }
    for (size_t t = 0; t < objectiveTerms.size(); ++t)
      if (termStages[t].count(g.stage)) {
        g.terms.push_back(objectiveTerms[t]);
        reads(m, *objectiveTerms[t].first, g.stage, ignored, own);
      }
    // A stage attribute given by a formula may read another stage.
    for (const auto& at : m.stages[s].ir->attributes)
      if (at.value) reads(m, *at.value, g.stage, ignored, own);
    g.cacheable = own;
    groups.push_back(std::move(g));
  }
  // Rules on no freedom are checked on the whole design at its decided point.
  for (size_t r = 0; r < parts_.size(); ++r)
    if (ruleStages[r].empty()) rest_.push_back(parts_[r]);
  separable_ = !m.gearbox.objectives.empty();
  for (const auto& g : groups)
    separable_ = separable_ && g.cacheable;
  for (size_t t = 0; t < objectiveTerms.size(); ++t)
    if (termStages[t].empty()) freeTerms_.push_back(objectiveTerms[t]);
}

DecidedPoint FreedomPlan::decide(const Evaluator& ev, const std::vector<int>& choice) const {
  DecidedPoint out;
  out.freedoms.assign(m_.freedoms.size(), NAN);
  double sum = 0; // the objective's terms over freedoms, as the groups decided them
  auto add = [&](const DecidedPoint& part) {
    if (!part.objectives.empty()) sum += part.objectives[0];
  };
  for (const auto& g : groups) {
    // A group that reads only its own stage is the same in every design with the same choices
    // of that stage: decided once.
    std::vector<int> key;
    if (g.cacheable) {
      key.push_back(g.stage);
      for (int sl : m_.stages[static_cast<size_t>(g.stage)].slots)
        key.push_back(choice[static_cast<size_t>(sl)]);
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = cache_.find(key); it != cache_.end()) {
        if (!it->second.feasible) return it->second;
        add(it->second);
        for (size_t i = 0; i < g.freedoms.size(); ++i)
          out.freedoms[static_cast<size_t>(g.freedoms[i])] = it->second.freedoms[i];
        continue;
      }
    }
    DecidedPoint part = Decider(ev, choice, g).run();
    out.evaluations += part.evaluations;
    if (g.cacheable) {
      std::lock_guard<std::mutex> lock(mutex_);
      cache_.emplace(key, part);
    }
    if (!part.feasible) return part;
    add(part);
    for (size_t i = 0; i < g.freedoms.size(); ++i)
      out.freedoms[static_cast<size_t>(g.freedoms[i])] = part.freedoms[i];
  }
  // The whole design at the decided point: every rule (those on no freedom included), and its
  // ranking keys.
  Assignment a(m_);
  a.choice = choice;
  for (size_t f = 0; f < out.freedoms.size(); ++f)
    a.box[f] = {out.freedoms[f], out.freedoms[f]};
  ev.solveFreedoms(a, out.freedoms);
  // The groups decided the rules on their freedoms; the rules on none (a `worst` over a stage
  // without freedoms, which the search defers) are checked here.
  for (const auto& r : rest_) {
    Value v = ev.eval(*r.expr, a);
    if (!(v.kind == Value::Bool && v.truth == Truth::True)) {
      DecidedPoint failed;
      failed.rule = r.text;
      return failed;
    }
  }
  out.feasible = true;
  if (separable_) {
    // Every group read only its own stage: the objective is the groups' decided terms and
    // those on no freedom.
    for (const auto& [e, sign] : freeTerms_) {
      Value v = ev.eval(*e, a);
      sum += v.isNumber() ? sign * v.mid() : NAN;
    }
    out.objectives = {sum};
  } else {
    out.objectives = rankingKeys(ev, a, false);
  }
  out.keys = withSortKey(ev, a, out.objectives);
  return out;
}

} // namespace gbx::rt
