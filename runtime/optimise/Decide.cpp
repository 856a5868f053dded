#include "optimise/Decide.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "catalogue/Settings.h"
#include "optimise/Violation.h"
#include "search/Search.h"
#include "units/Unit.h"

namespace gbx::rt {

namespace {

// One evaluated point of the freedoms' box, in coordinates normalised to [0, 1] per freedom.
struct Point {
  std::vector<double> t, x;
  bool feasible = false;
  double violation = INFINITY;
  std::vector<double> keys;
  double offCentre = 0; // squared distance from the middle of the box, normalised
};

// Feasible before infeasible; among feasible points the better keys, then the nearer the
// middle; among infeasible ones the smaller violation.
bool better(const Point& p, const Point& q) {
  if (p.feasible != q.feasible) return p.feasible;
  if (!p.feasible) return p.violation < q.violation;
  int c = compareKeys(p.keys, q.keys);
  if (c != 0) return c < 0;
  return p.offCentre < q.offCentre - 1e-15;
}

class Decider {
public:
  Decider(const Evaluator& ev, const std::vector<int>& choice, const FreedomGroup& g)
      : ev_(ev), m_(ev.model()), a_(m_), g_(g) {
    a_.choice = choice;
    for (int f : g.freedoms) {
      lo_.push_back(m_.freedoms[static_cast<size_t>(f)].lo);
      hi_.push_back(m_.freedoms[static_cast<size_t>(f)].hi);
    }
  }

  DecidedPoint run() {
    const size_t n = lo_.size();
    // A grid over the box: its best points start the refinement, and a feasible region
    // narrower than the box is found where a single start would miss it.
    size_t k = std::clamp<size_t>(
        static_cast<size_t>(std::floor(std::pow(128.0, 1.0 / static_cast<double>(std::max<size_t>(n, 1))))), 3, 17);
    size_t total = 1;
    for (size_t i = 0; i < n && total < 4096; ++i)
      total *= k;
    std::vector<Point> grid;
    grid.reserve(total + 1);
    grid.push_back(at(std::vector<double>(n, 0.5)));
    for (size_t g = 0; g < total; ++g) {
      std::vector<double> t(n);
      size_t rest = g;
      for (size_t i = 0; i < n; ++i) {
        t[i] = static_cast<double>(rest % k) / static_cast<double>(k - 1);
        rest /= k;
      }
      grid.push_back(at(t));
    }
    std::stable_sort(grid.begin(), grid.end(), better);
    // Refine the three best distinct starts by a compass search.
    Point best = grid.front();
    size_t starts = 0;
    for (size_t g = 0; g < grid.size() && starts < 3; ++g) {
      if (g > 0 && grid[g].t == grid[g - 1].t) continue;
      Point p = compass(grid[g], 1.0 / static_cast<double>(k - 1));
      if (better(p, best)) best = p;
      ++starts;
    }
    DecidedPoint out;
    out.evaluations = evaluations_;
    if (!best.feasible) {
      out.rule = failing(best);
      return out;
    }
    best = printed(best);
    out.feasible = true;
    out.freedoms = best.x;
    out.objectives = best.keys;
    out.evaluations = evaluations_;
    return out;
  }

private:
  Point at(const std::vector<double>& t) {
    Point p;
    p.t = t;
    p.x.resize(t.size());
    for (size_t i = 0; i < t.size(); ++i)
      p.x[i] = t[i] >= 1 ? hi_[i] : lo_[i] + (hi_[i] - lo_[i]) * t[i];
    return atSI(std::move(p));
  }

  Point atSI(Point p) {
    ++evaluations_;
    for (size_t i = 0; i < p.x.size(); ++i) {
      a_.box[static_cast<size_t>(g_.freedoms[i])] = {p.x[i], p.x[i]};
      double d = p.t[i] - 0.5;
      p.offCentre += d * d;
    }
    p.violation = 0;
    bool all = true;
    for (const auto* r : g_.rules) {
      Value v = ev_.eval(*r->expr, a_);
      bool holds = v.kind == Value::Bool && v.truth == Truth::True;
      all = all && holds;
      if (!holds) p.violation += std::max(violation(ev_, *r->expr, a_), 1e-12);
    }
    p.feasible = all;
    // The point is chosen by the objectives alone; `sort by` only orders the decided designs.
    if (all) {
      if (g_.allObjectives) {
        p.keys = rankingKeys(ev_, a_, false);
      } else if (!g_.terms.empty()) {
        double sum = 0;
        for (const auto& [e, sign] : g_.terms) {
          Value v = ev_.eval(*e, a_);
          sum += v.isNumber() ? sign * v.mid() : NAN;
        }
        p.keys = {sum};
      }
    }
    return p;
  }

  // The moves of the pattern search: along each freedom, and (up to four freedoms) along
  // every combination of them, with half-steps for one or two; a rule whose boundary bends
  // across the box is followed by the combined moves where single ones all leave it.
  static std::vector<std::vector<double>> directions(size_t n) {
    std::vector<double> levels = n <= 2   ? std::vector<double>{-1, -0.5, 0, 0.5, 1}
                                 : n <= 4 ? std::vector<double>{-1, 0, 1}
                                          : std::vector<double>{};
    std::vector<std::vector<double>> out;
    if (levels.empty()) {
      for (size_t i = 0; i < n; ++i)
        for (double s : {-1.0, 1.0}) {
          std::vector<double> d(n, 0.0);
          d[i] = s;
          out.push_back(d);
        }
      return out;
    }
    size_t total = 1;
    for (size_t i = 0; i < n; ++i)
      total *= levels.size();
    for (size_t c = 0; c < total; ++c) {
      std::vector<double> d(n);
      size_t rest = c;
      double largest = 0;
      for (size_t i = 0; i < n; ++i) {
        d[i] = levels[rest % levels.size()];
        rest /= levels.size();
        largest = std::max(largest, std::fabs(d[i]));
      }
      if (largest == 1) out.push_back(d); // a half-step only beside a whole one
    }
    // Single-freedom moves first: the cheap ones, and the ones that reach a bound exactly.
    auto moved = [](const std::vector<double>& d) {
      return std::count_if(d.begin(), d.end(), [](double v) { return v != 0; });
    };
    std::stable_sort(out.begin(), out.end(), [&](const auto& x, const auto& y) { return moved(x) < moved(y); });
    return out;
  }

  // Moves by h along the pattern's directions while that improves, halving h when no move
  // does; a move past a bound stops at the bound, so a best point at the end of a range is
  // reached exactly. It stops at 1e-7 of each range, far below the printed digits.
  Point compass(Point p, double h) {
    const size_t n = p.t.size();
    const auto dirs = directions(n);
    while (h > 1e-7 && evaluations_ < kBudget) {
      bool moved = false;
      for (const auto& d : dirs) {
        std::vector<double> t = p.t;
        bool changed = false;
        for (size_t i = 0; i < n; ++i) {
          t[i] = std::clamp(t[i] + d[i] * h, 0.0, 1.0);
          changed = changed || t[i] != p.t[i];
        }
        if (!changed) continue;
        Point q = at(t);
        if (better(q, p)) {
          p = std::move(q);
          moved = true;
          break;
        }
      }
      if (!moved) h *= 0.5;
    }
    return p;
  }

  // The rule that fails by the most at the point nearest to feasibility.
  std::string failing(const Point& p) {
    for (size_t i = 0; i < p.x.size(); ++i)
      a_.box[static_cast<size_t>(g_.freedoms[i])] = {p.x[i], p.x[i]};
    std::string worst;
    double most = -1;
    for (const auto* r : g_.rules) {
      Value v = ev_.eval(*r->expr, a_);
      if (v.kind == Value::Bool && v.truth == Truth::True) continue;
      double d = violation(ev_, *r->expr, a_);
      if (d > most) {
        most = d;
        worst = r->text;
      }
    }
    return worst;
  }

  // The point as a report prints it (4 decimals in the display unit): of the roundings down
  // and up of each freedom, the best that still satisfies every rule. Written into the spec,
  // those values give the same doubles, so every number is reproduced.
  Point printed(const Point& p) {
    const size_t n = p.x.size();
    std::vector<std::vector<double>> options(n);
    for (size_t i = 0; i < n; ++i) {
      const Freedom& f = m_.freedoms[static_cast<size_t>(g_.freedoms[i])];
      const ir::Attribute* attr = m_.attribute(f.stage, f.gear, f.key);
      units::Dim dim = attr ? attr->dim : units::Dim{};
      auto du = units::displayUnitFor(dim);
      double shown = p.x[i] / du.scale;
      double mag = std::fabs(shown);
      std::optional<units::Number> unit;
      if (du.name.empty())
        unit = units::Number::exact(units::Rational(1));
      else if (auto atom = units::lookupAtom(du.name))
        unit = atom->scale;
      // formatNumber's digits: 4 decimals, or 5 significant ones below 1e-3 (`1.2345e-04`).
      int exponent = mag != 0 && mag < 1e-3 ? static_cast<int>(std::floor(std::log10(mag))) : 0;
      if (!unit || mag >= 1e7 || exponent < -14 || n > 6) {
        options[i].push_back(p.x[i]);
        continue;
      }
      std::int64_t denominator = 10000;
      for (int e = exponent; e < 0; ++e)
        denominator *= 10;
      double scaled = shown * static_cast<double>(denominator);
      for (double q : {std::floor(scaled), std::ceil(scaled)}) {
        double v = units::Number::exact(units::Rational::make(static_cast<std::int64_t>(q), denominator))
                       .mul(*unit)
                       .toDouble();
        if (v < lo_[i] || v > hi_[i]) continue;
        if (std::find(options[i].begin(), options[i].end(), v) == options[i].end()) options[i].push_back(v);
      }
      if (options[i].empty()) options[i].push_back(p.x[i]);
    }
    Point best;
    bool found = false;
    size_t combos = 1;
    for (const auto& o : options)
      combos *= o.size();
    for (size_t c = 0; c < combos; ++c) {
      Point q;
      q.x.resize(n);
      q.t.resize(n);
      size_t rest = c;
      for (size_t i = 0; i < n; ++i) {
        q.x[i] = options[i][rest % options[i].size()];
        rest /= options[i].size();
        q.t[i] = hi_[i] > lo_[i] ? (q.x[i] - lo_[i]) / (hi_[i] - lo_[i]) : 0.5;
      }
      q = atSI(std::move(q));
      if (q.feasible && (!found || better(q, best))) {
        best = std::move(q);
        found = true;
      }
    }
    return found ? best : p;
  }

  static constexpr long kBudget = 20000;
  const Evaluator& ev_;
  const Model& m_;
  Assignment a_;
  const FreedomGroup& g_;
  std::vector<double> lo_, hi_;
  long evaluations_ = 0;
};

} // namespace

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
  // No freedoms: the design's one point, where every rule is checked (`worst` over the
  // tolerances, which the search defers).
  if (m.freedoms.empty()) {
    for (const auto& r : m.gearbox.rules)
      if (r.expr) rest_.push_back(&r);
    return;
  }
  auto whole = [&] {
    groups.clear();
    FreedomGroup g;
    for (size_t f = 0; f < m.freedoms.size(); ++f)
      g.freedoms.push_back(static_cast<int>(f));
    for (const auto& r : m.gearbox.rules)
      if (r.expr) g.rules.push_back(&r);
    g.allObjectives = true;
    groups.push_back(std::move(g));
  };
  // Separable when every rule reads the freedoms of one stage at most and the one objective
  // is a sum of terms that each do: then each stage's freedoms are decided on their own.
  std::vector<std::set<int>> ruleStages;
  for (const auto& r : m.gearbox.rules) {
    std::set<int> st;
    bool own = true;
    if (r.expr) reads(m, *r.expr, -1, st, own);
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
    for (size_t r = 0; r < m.gearbox.rules.size(); ++r)
      if (ruleStages[r].count(g.stage)) {
        g.rules.push_back(&m.gearbox.rules[r]);
        reads(m, *m.gearbox.rules[r].expr, g.stage, ignored, own);
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
  for (size_t r = 0; r < m.gearbox.rules.size(); ++r)
    if (ruleStages[r].empty() && m.gearbox.rules[r].expr) rest_.push_back(&m.gearbox.rules[r]);
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
  // The groups decided the rules on their freedoms; the rules on none (a `worst` over a stage
  // without freedoms, which the search defers) are checked here.
  for (const auto* r : rest_) {
    Value v = ev.eval(*r->expr, a);
    if (!(v.kind == Value::Bool && v.truth == Truth::True)) {
      DecidedPoint failed;
      failed.rule = r->text;
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
