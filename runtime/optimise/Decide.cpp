#include "optimise/Decide.h"

#include <algorithm>
#include <cmath>

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
  Decider(const Evaluator& ev, const std::vector<int>& choice) : ev_(ev), m_(ev.model()), a_(m_) {
    a_.choice = choice;
    for (const auto& f : m_.freedoms) {
      lo_.push_back(f.lo);
      hi_.push_back(f.hi);
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
    out.keys = best.keys;
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
      a_.box[i] = {p.x[i], p.x[i]};
      double d = p.t[i] - 0.5;
      p.offCentre += d * d;
    }
    p.violation = 0;
    bool all = true;
    for (const auto& r : m_.gearbox.rules) {
      if (!r.expr) continue;
      Value v = ev_.eval(*r.expr, a_);
      bool holds = v.kind == Value::Bool && v.truth == Truth::True;
      all = all && holds;
      if (!holds) p.violation += std::max(violation(ev_, *r.expr, a_), 1e-12);
    }
    p.feasible = all;
    if (all) p.keys = rankingKeys(ev_, a_);
    return p;
  }

  // Moves along each freedom by ±h while that improves, halving h when no move does; a move
  // past a bound stops at the bound, so a best point at the end of a range is reached exactly.
  Point compass(Point p, double h) {
    const size_t n = p.t.size();
    while (h > 1e-10 && evaluations_ < kBudget) {
      bool moved = false;
      for (size_t i = 0; i < n && !moved; ++i)
        for (double s : {-1.0, 1.0}) {
          std::vector<double> t = p.t;
          t[i] = std::clamp(t[i] + s * h, 0.0, 1.0);
          if (t[i] == p.t[i]) continue;
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
      a_.box[i] = {p.x[i], p.x[i]};
    std::string worst;
    double most = -1;
    for (const auto& r : m_.gearbox.rules) {
      if (!r.expr) continue;
      Value v = ev_.eval(*r.expr, a_);
      if (v.kind == Value::Bool && v.truth == Truth::True) continue;
      double d = violation(ev_, *r.expr, a_);
      if (d > most) {
        most = d;
        worst = r.text;
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
      const Freedom& f = m_.freedoms[i];
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
      if (!unit || (mag != 0 && (mag < 1e-3 || mag >= 1e7)) || n > 6) {
        options[i].push_back(p.x[i]);
        continue;
      }
      double scaled = shown * 1e4;
      for (double q : {std::floor(scaled), std::ceil(scaled)}) {
        double v =
            units::Number::exact(units::Rational::make(static_cast<std::int64_t>(q), 10000)).mul(*unit).toDouble();
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
  std::vector<double> lo_, hi_;
  long evaluations_ = 0;
};

} // namespace

std::vector<double> rankingKeys(const Evaluator& ev, const Assignment& a) {
  const Model& m = ev.model();
  std::vector<double> keys;
  auto add = [&](const ir::Expr* e, bool minimize) {
    Value v = e ? ev.eval(*e, a) : Value::invalid();
    keys.push_back(v.isNumber() ? (minimize ? v.mid() : -v.mid()) : NAN);
  };
  if (m.gearbox.report && m.gearbox.report->sortBy) add(m.gearbox.report->sortBy.get(), true);
  for (const auto& o : m.gearbox.objectives)
    add(o.expr.get(), o.minimize);
  return keys;
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

DecidedPoint decideFreedoms(const Evaluator& ev, const std::vector<int>& choice) { return Decider(ev, choice).run(); }

} // namespace gbx::rt
