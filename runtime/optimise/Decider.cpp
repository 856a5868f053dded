#include "optimise/Decider.h"

#include <algorithm>
#include <cmath>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <nlopt.h>

#include "model/ToleranceEdges.h"
#include "optimise/Violation.h"
#include "units/Unit.h"

namespace gbx::rt {

namespace {
// Evaluations one group may spend: far above what either method needs (tens), a bound on a
// rule whose margin misleads them.
constexpr long kBudget = 4000;
// Samples of a single freedom's range: the rules' boundaries and the objective's minima are
// bracketed between them.
constexpr int kSamples = 5;
// The normalised step of the optimiser's forward differences.
constexpr double kStep = 1e-7;

double minimum(const std::vector<double>& v) { return v.empty() ? 1.0 : *std::min_element(v.begin(), v.end()); }

} // namespace

bool better(const Decider::Point& p, const Decider::Point& q) {
  if (p.feasible != q.feasible) return p.feasible;
  if (!p.feasible) return p.violation < q.violation;
  int c = compareKeys(p.keys, q.keys);
  if (c != 0) return c < 0;
  return p.offCentre < q.offCentre - 1e-15;
}

Decider::Decider(const Evaluator& ev, const std::vector<int>& choice, const FreedomGroup& g)
    : ev_(ev), m_(ev.model()), a_(m_), g_(g) {
  a_.choice = choice;
  for (int f : g.freedoms) {
    lo_.push_back(m_.freedoms[static_cast<size_t>(f)].lo);
    hi_.push_back(m_.freedoms[static_cast<size_t>(f)].hi);
  }
}

DecidedPoint Decider::run() {
  gsl_set_error_handler_off(); // a failed bracket comes back as a status, never as an abort
  Point p = lo_.size() == 1 ? alone() : severally();
  DecidedPoint out;
  if (!p.feasible) {
    out.rule = failing(p);
    out.evaluations = evaluations_;
    return out;
  }
  if (lo_.size() > 1 && !flat_) p = towardMiddle(p);
  p = printed(p);
  // An optimiser's end point on a rule's boundary may miss it by a rounding (a margin of
  // -1e-16): its printed neighbours that satisfy every rule compete too.
  for (const Point& q : nearlyFeasible_) {
    Point r = printed(q);
    if (r.feasible && better(r, p)) p = std::move(r);
  }
  out.feasible = true;
  out.freedoms = p.x;
  out.objectives = p.keys;
  out.evaluations = evaluations_;
  return out;
}

Decider::Point Decider::at(const std::vector<double>& t) {
  Point p;
  p.t = t;
  p.x.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i)
    p.x[i] = t[i] >= 1 ? hi_[i] : t[i] <= 0 ? lo_[i] : lo_[i] + (hi_[i] - lo_[i]) * t[i];
  return atSI(std::move(p));
}

Decider::Point Decider::atSI(Point p) {
  ++evaluations_;
  for (size_t i = 0; i < p.x.size(); ++i) {
    a_.box[static_cast<size_t>(g_.freedoms[i])] = {p.x[i], p.x[i]};
    double d = p.t[i] - 0.5;
    p.offCentre += d * d;
  }
  p.violation = 0;
  p.feasible = true;
  for (const auto& r : g_.rules) {
    Value v = ev_.eval(*r.expr, a_);
    bool holds = v.kind == Value::Bool && v.truth == Truth::True;
    p.feasible = p.feasible && holds;
    if (!holds) p.violation += std::max(violation(ev_, *r.expr, a_), 1e-12);
    margins(ev_, *r.expr, a_, p.margins);
  }
  // The point is chosen by the objectives alone; `sort by` only orders the decided designs.
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
  p.objective = p.keys.empty() || flat_ ? p.offCentre : std::isnan(p.keys[0]) ? 1e300 : p.keys[0];
  consider(p);
  return p;
}

// A freedom the objectives do not read (a face width under a centre-distance objective) is
// left by the optimiser wherever it stopped; the documented tie-break is the feasible point
// nearer the middle. Each such freedom moves toward the middle as far as the point stays
// feasible with the same objectives (bisection, 30 steps); one probe tells such a freedom.
Decider::Point Decider::towardMiddle(Point p) {
  // The point's coordinates over the whole box (a cell's search left them over the cell).
  for (size_t i = 0; i < p.t.size(); ++i)
    p.t[i] = hi_[i] > lo_[i] ? (p.x[i] - lo_[i]) / (hi_[i] - lo_[i]) : 0.5;
  for (size_t i = 0; i < p.t.size(); ++i) {
    auto moved = [&](double ti) {
      std::vector<double> t = p.t;
      t[i] = ti;
      return at(t);
    };
    auto same = [&](const Point& q) { return q.feasible && compareKeys(q.keys, p.keys) == 0; };
    const double from = p.t[i], step = from < 0.5 ? 1e-3 : -1e-3;
    if (std::fabs(from - 0.5) < 1e-3 || !same(moved(from + step))) continue;
    Point mid = moved(0.5);
    if (same(mid)) {
      p = mid;
      continue;
    }
    double good = from + step, bad = 0.5;
    for (int it = 0; it < 30; ++it) {
      double t = 0.5 * (good + bad);
      (same(moved(t)) ? good : bad) = t;
    }
    p = moved(good);
  }
  return p;
}

void Decider::consider(const Point& p) {
  if (best_.t.empty() || better(p, best_)) best_ = p;
}

// One freedom: samples over its range; between two samples on either side of a rule's
// boundary, the boundary; about a sample better than both neighbours, the interior minimum.
// Every point evaluated competes, so the best of samples, boundaries and minima is kept.
Decider::Point Decider::alone() {
  std::vector<Point> s;
  for (int k = 0; k < kSamples; ++k)
    s.push_back(at({static_cast<double>(k) / (kSamples - 1)}));
  // Either side of each point where a tolerance table jumps: between samples, then, the
  // rules are smooth, and a range that meets them below such a point is not missed.
  Assignment whole = a_;
  const int f = g_.freedoms[0];
  whole.box[static_cast<size_t>(f)] = {lo_[0], hi_[0]};
  const auto pieces = cutAt(lo_[0], hi_[0], toleranceEdges(ev_, whole, f));
  for (size_t k = 0; k + 1 < pieces.size(); ++k)
    for (double x : {pieces[k].second, pieces[k + 1].first}) {
      Point p;
      p.t = {(x - lo_[0]) / (hi_[0] - lo_[0])};
      p.x = {x};
      s.push_back(atSI(std::move(p)));
    }
  std::sort(s.begin(), s.end(), [](const Point& x, const Point& y) { return x.t[0] < y.t[0]; });
  for (size_t k = 0; k + 1 < s.size(); ++k)
    if (s[k].feasible != s[k + 1].feasible) boundary(s[k].feasible ? s[k] : s[k + 1], s[k].feasible ? s[k + 1] : s[k]);
  for (size_t k = 1; k + 1 < s.size(); ++k)
    if (s[k].feasible && s[k - 1].feasible && s[k + 1].feasible && s[k].objective < s[k - 1].objective &&
        s[k].objective < s[k + 1].objective)
      interiorMinimum(s[k - 1], s[k], s[k + 1]);
  return best_;
}

// The rules' boundary between a feasible and an infeasible point of one freedom: the root of
// the least margin by Brent's method, to 1e-13 of the range (far below the printed digits).
// Where the margins do not change sign across the bracket (a rule with no margin), bisection
// on feasibility itself. A factor read from a table (a tolerance by face width range) can
// jump, leaving feasible islands beside the root the bracket converged to: points between it
// and the infeasible end, at halving distances, look for one, and its boundary is found too.
Decider::Point Decider::boundary(const Point& in, const Point& out, int depth) {
  // The points the root finder evaluated, the bracket's ends first: its start and its result
  // are among them, and are not evaluated again.
  struct Seen {
    Decider* d;
    std::vector<Point> points;
    const Point& at(double t) {
      for (const auto& p : points)
        if (p.t[0] == t) return p;
      points.push_back(d->at({t}));
      return points.back();
    }
  } seen{this, {in, out}};
  gsl_function f;
  f.function = [](double t, void* c) { return minimum(static_cast<Seen*>(c)->at(t).margins); };
  f.params = &seen;
  const bool up = in.t[0] < out.t[0];
  double a = up ? in.t[0] : out.t[0], b = up ? out.t[0] : in.t[0];
  double fa = minimum(up ? in.margins : out.margins), fb = minimum(up ? out.margins : in.margins);
  Point p = in, q = out; // the feasible and the infeasible end of the bracket
  if (fa * fb < 0 && (fa >= 0) == up) {
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &f, a, b);
    for (int it = 0; it < 100 && evaluations_ < kBudget; ++it) {
      if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
      double lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
      if (gsl_root_test_interval(lo, hi, 1e-13, 0) == GSL_SUCCESS) break;
    }
    Point lo = seen.at(gsl_root_fsolver_x_lower(s)), hi = seen.at(gsl_root_fsolver_x_upper(s));
    gsl_root_fsolver_free(s);
    Point& feasibleEnd = up ? lo : hi;
    Point& otherEnd = up ? hi : lo;
    if (feasibleEnd.feasible && !otherEnd.feasible) {
      p = feasibleEnd;
      q = otherEnd;
    }
  }
  // Bisection on feasibility where the root's bracket does not settle it.
  while (std::fabs(p.t[0] - q.t[0]) > 1e-13 && evaluations_ < kBudget) {
    Point c = at({0.5 * (p.t[0] + q.t[0])});
    (c.feasible ? p : q) = std::move(c);
  }
  if (depth < 3)
    for (int j = 1; j <= 5 && evaluations_ < kBudget; ++j) {
      Point c = at({p.t[0] + (out.t[0] - p.t[0]) * std::ldexp(1.0, -j)});
      if (c.feasible) return boundary(c, out, depth + 1);
    }
  return p;
}

// The objective's minimum between two feasible neighbours of a better feasible sample, by
// Brent's minimiser (to 1e-9 of the range: a smooth minimum is flat to 1e-18 there).
void Decider::interiorMinimum(const Point& left, const Point& middle, const Point& right) {
  gsl_function f;
  f.function = [](double t, void* c) { return static_cast<Decider*>(c)->at({t}).objective; };
  f.params = this;
  gsl_min_fminimizer* s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (gsl_min_fminimizer_set_with_values(s, &f, middle.t[0], middle.objective, left.t[0], left.objective, right.t[0],
                                         right.objective) == GSL_SUCCESS) {
    for (int it = 0; it < 100 && evaluations_ < kBudget; ++it) {
      if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) break;
      if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), 1e-9, 0) == GSL_SUCCESS)
        break;
    }
  }
  gsl_min_fminimizer_free(s);
}

// Several freedoms: a sample of the box (a grid, the middle and the corners included), then
// SLSQP from its three best distinct points.
// Several freedoms: the box cut into cells where a tolerance table jumps (model/
// ToleranceEdges.h), each cell searched on its own, so that no optimiser step crosses a jump
// and a feasible pocket below one (a face width under 40 mm, a helix angle that keeps a
// wheel under 280 mm) is searched as a box of its own. At most 16 cells; beyond, the whole.
Decider::Point Decider::severally() {
  const std::vector<double> lo = lo_, hi = hi_;
  Assignment whole = a_;
  for (size_t i = 0; i < lo.size(); ++i)
    whole.box[static_cast<size_t>(g_.freedoms[i])] = {lo[i], hi[i]};
  std::vector<std::vector<std::pair<double, double>>> pieces(lo.size());
  size_t cells = 1;
  for (size_t i = 0; i < lo.size(); ++i) {
    pieces[i] = cutAt(lo[i], hi[i], toleranceEdges(ev_, whole, g_.freedoms[i]));
    cells *= pieces[i].size();
  }
  if (cells > 16) return cell();
  for (size_t c = 0; c < cells; ++c) {
    size_t rest = c;
    for (size_t i = 0; i < lo.size(); ++i) {
      std::tie(lo_[i], hi_[i]) = pieces[i][rest % pieces[i].size()];
      rest /= pieces[i].size();
    }
    cell();
  }
  lo_ = lo;
  hi_ = hi;
  return best_;
}

// One box of several freedoms: a grid, then SLSQP from its three best points.
Decider::Point Decider::cell() {
  const size_t n = lo_.size();
  size_t k =
      std::clamp<size_t>(static_cast<size_t>(std::floor(std::pow(64.0, 1.0 / static_cast<double>(n)) + 1e-9)), 2, 9);
  size_t total = 1;
  for (size_t i = 0; i < n && total <= 256; ++i)
    total *= k;
  std::vector<Point> sample;
  sample.push_back(at(std::vector<double>(n, 0.5)));
  for (size_t g = 0; g < total && g < 4096; ++g) {
    std::vector<double> t(n);
    size_t rest = g;
    for (size_t i = 0; i < n; ++i) {
      t[i] = static_cast<double>(rest % k) / static_cast<double>(k - 1);
      rest /= k;
    }
    sample.push_back(at(t));
  }
  // Objectives that do not move over the box (a ratio, with freedoms of the geometry alone)
  // leave the tie-break to choose: the feasible point nearest the middle.
  flat_ = std::all_of(sample.begin(), sample.end(),
                      [&](const Point& p) { return compareKeys(p.keys, sample[0].keys) == 0; });
  if (flat_)
    for (auto& p : sample)
      p.objective = p.offCentre;
  std::stable_sort(sample.begin(), sample.end(), better);
  size_t starts = 0;
  for (size_t g = 0; g < sample.size() && starts < 3 && evaluations_ < kBudget; ++g) {
    if (g > 0 && sample[g].t == sample[g - 1].t) continue;
    slsqp(sample[g]);
    ++starts;
  }
  return best_;
}

namespace {

// NLopt's view of a Decider: the objective and the constraints at one x come from one
// evaluation and its forward differences, kept for the calls that ask again at the same x.
struct Problem {
  Decider* d;
  size_t m = 0; // margins
  double scale; // the objective's, at the start
  std::vector<double> x;
  Decider::Point at;
  std::vector<std::vector<double>> probes; // per freedom: the margins and objective a step on
  std::vector<double> steps;

  void ensure(const double* t, size_t n, bool gradient) {
    bool same = x.size() == n && std::equal(x.begin(), x.end(), t);
    if (!same) {
      x.assign(t, t + n);
      at = d->at(x);
      at.margins.resize(m, -1.0);
      probes.clear();
    }
    if (!gradient || !probes.empty()) return;
    steps.assign(n, kStep);
    for (size_t i = 0; i < n; ++i) {
      std::vector<double> u = x;
      if (u[i] + kStep > 1) steps[i] = -kStep;
      u[i] += steps[i];
      Decider::Point p = d->at(u);
      p.margins.resize(m, -1.0);
      p.margins.push_back(p.objective);
      probes.push_back(std::move(p.margins));
    }
  }
};

double objective(unsigned n, const double* t, double* grad, void* data) {
  auto* p = static_cast<Problem*>(data);
  p->ensure(t, n, grad != nullptr);
  if (grad)
    for (unsigned i = 0; i < n; ++i)
      grad[i] = (p->probes[i][p->m] - p->at.objective) / p->steps[i] / p->scale;
  return p->at.objective / p->scale;
}

// NLopt's constraints are c(x) <= 0: the negated margins.
void constraints(unsigned m, double* c, unsigned n, const double* t, double* grad, void* data) {
  auto* p = static_cast<Problem*>(data);
  p->ensure(t, n, grad != nullptr);
  for (unsigned j = 0; j < m; ++j) {
    c[j] = -p->at.margins[j];
    if (grad)
      for (unsigned i = 0; i < n; ++i)
        grad[j * n + i] = -(p->probes[i][j] - p->at.margins[j]) / p->steps[i];
  }
}

} // namespace

// SLSQP from a start, the rules' margins as inequality constraints and the box as bounds.
void Decider::slsqp(const Point& start) {
  const unsigned n = static_cast<unsigned>(start.t.size());
  Problem pr{this, start.margins.size(), std::max(std::fabs(start.objective), 1e-300), {}, {}, {}, {}};
  nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, n);
  std::vector<double> lo(n, 0.0), hi(n, 1.0), tol(pr.m, 0.0);
  nlopt_set_lower_bounds(opt, lo.data());
  nlopt_set_upper_bounds(opt, hi.data());
  nlopt_set_min_objective(opt, objective, &pr);
  if (pr.m) nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(pr.m), constraints, &pr, tol.data());
  nlopt_set_xtol_abs1(opt, 1e-13);
  nlopt_set_ftol_rel(opt, 1e-15);
  nlopt_set_maxeval(opt, 200);
  std::vector<double> t = start.t;
  double f = 0;
  nlopt_optimize(opt, t.data(), &f);
  nlopt_destroy(opt);
  Point end = at(t);
  if (!end.feasible && minimum(end.margins) > -1e-9) nearlyFeasible_.push_back(std::move(end));
}

// The rule that fails by the most at the point nearest to feasibility.
std::string Decider::failing(const Point& p) {
  for (size_t i = 0; i < p.x.size(); ++i)
    a_.box[static_cast<size_t>(g_.freedoms[i])] = {p.x[i], p.x[i]};
  std::string worst;
  double most = -1;
  for (const auto& r : g_.rules) {
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

namespace {

// A freedom's value as the report prints it: 4 decimals in its display unit, or 5
// significant digits below 1e-3 (formatNumber), `steps` printed digits from the value's floor
// (negative: below it). The unit's scale is exact where the unit is, so a value written with
// those digits reads back as the same double.
struct Printed {
  std::optional<units::Number> unit;
  std::int64_t denominator = 0;
  double scaled = 0;
  double at(double steps) const {
    double q = std::floor(scaled) + steps;
    return units::Number::exact(units::Rational::make(static_cast<std::int64_t>(q), denominator)).mul(*unit).toDouble();
  }
};

std::optional<Printed> printedDigits(const Freedom& f, double x) {
  units::Dim dim = f.dim;
  auto du = units::displayUnitFor(dim);
  double shown = x / du.scale;
  double mag = std::fabs(shown);
  Printed p;
  if (du.name.empty())
    p.unit = units::Number::exact(units::Rational(1));
  else if (auto atom = units::lookupAtom(du.name))
    p.unit = atom->scale;
  int exponent = mag != 0 && mag < 1e-3 ? static_cast<int>(std::floor(std::log10(mag))) : 0;
  if (!p.unit || mag >= 1e7 || exponent < -14) return std::nullopt;
  p.denominator = 10000;
  for (int e = exponent; e < 0; ++e)
    p.denominator *= 10;
  p.scaled = shown * static_cast<double>(p.denominator);
  return p;
}

} // namespace

// The point as the report prints it: of the values a printed digit or two either side of
// each freedom, the best combination that satisfies every rule. Written into the spec, those
// values give the same doubles, so every number is reproduced, every rule included.
Decider::Point Decider::printed(const Point& p) {
  const size_t n = p.x.size();
  if (n > 6) return p;
  std::vector<std::optional<Printed>> digits(n);
  for (size_t i = 0; i < n; ++i)
    digits[i] = printedDigits(m_.freedoms[static_cast<size_t>(g_.freedoms[i])], p.x[i]);
  // The nearest roundings first (floor, ceil); then a digit further either way, for a rule
  // whose boundary the two nearest both miss.
  for (int reach = 1; reach <= 3; ++reach) {
    std::vector<std::vector<double>> options(n);
    for (size_t i = 0; i < n; ++i) {
      if (!digits[i]) {
        options[i] = {p.x[i]};
        continue;
      }
      for (int s = 1 - reach; s <= reach; ++s) {
        double v = digits[i]->at(s);
        if (v >= lo_[i] && v <= hi_[i] && std::find(options[i].begin(), options[i].end(), v) == options[i].end())
          options[i].push_back(v);
      }
      if (options[i].empty()) options[i] = {p.x[i]};
    }
    size_t combos = 1;
    for (const auto& o : options)
      combos *= o.size();
    Point best;
    bool found = false;
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
    if (found) return best;
  }
  return p;
}

} // namespace gbx::rt
