#include "passes/Optimise.h"

#include <chrono>
#include <functional>

#include <algorithm>
#include <cmath>

#include "model/Evaluator.h"
#include "optimise/Optimise.h"
#include "passes/Search.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

// The search budget of a baseline solved for `relative(…)`: that of a solve.
constexpr double kBaselineDesigns = 1e9;

// How far each inequality rule `q >= c` / `q <= c` stands from its bound at the optimum:
// the rule with no margin is the one that binds.
std::vector<OptimisationSummary::Optimum::Margin> margins(const Model& m, const std::vector<int>& choice,
                                                          const std::vector<double>& freedoms) {
  std::vector<OptimisationSummary::Optimum::Margin> out;
  Evaluator ev(m);
  Assignment a(m);
  a.choice = choice;
  for (size_t f = 0; f < freedoms.size() && f < a.box.size(); ++f)
    a.box[f] = {freedoms[f], freedoms[f]};
  std::function<void(const ir::Expr&, const std::string&)> visit = [&](const ir::Expr& e, const std::string& text) {
    if (e.op == ir::Op::And) {
      for (const auto& x : e.args)
        visit(*x, ir::print(*x));
      return;
    }
    bool ge = e.op == ir::Op::Ge || e.op == ir::Op::Gt, le = e.op == ir::Op::Le || e.op == ir::Op::Lt;
    if (!(ge || le) || e.args.size() != 2 || !e.args[1]->isConst()) return;
    Value q = ev.eval(*e.args[0], a);
    if (!q.isNumber()) return;
    double bound = e.args[1]->value.toDouble();
    if (bound == 0) return;
    auto u = valueUnitOf(*e.args[0]);  // a temperature difference reads in K, without degC's zero
    OptimisationSummary::Optimum::Margin mg;
    mg.rule = text;
    mg.value = u.shown(q.mid());
    mg.bound = u.shown(bound);
    mg.unit = u.name;
    mg.margin = (ge ? q.mid() - bound : bound - q.mid()) / std::fabs(bound);
    out.push_back(mg);
  };
  for (const auto& r : m.gearbox.rules)
    if (r.expr) visit(*r.expr, r.text);
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.margin < y.margin; });
  return out;
}

// Each objective at the optimum with every tolerance at -amount and +amount alone, and over
// the corners of the tolerance box: how much manufacturing scatter moves the optimum's merit.
std::vector<OptimisationSummary::Optimum::Sensitivity> sensitivity(const Model& m, const Model* baseline,
                                                                   const Assignment* baseDesign,
                                                                   const std::vector<int>& choice,
                                                                   const std::vector<double>& freedoms, double rtol) {
  std::vector<OptimisationSummary::Optimum::Sensitivity> out;
  const auto& tol = m.gearbox.tolerances;
  if (tol.empty()) return out;
  Evaluator ev(m);
  installHooks(ev, m, baseline, baseDesign, rtol);
  ev.nominalOnly = true;
  Assignment a(m);
  a.choice = choice;
  for (size_t f = 0; f < freedoms.size() && f < a.box.size(); ++f)
    a.box[f] = {freedoms[f], freedoms[f]};
  auto atSI = [&](const ir::Expr& e, const std::vector<double>& deltas) {
    Evaluator x(ev);
    for (size_t i = 0; i < tol.size(); ++i)
      if (deltas[i] != 0) x.addOffset(tol[i].ref, deltas[i]);
    Value v = x.eval(e, a);
    return v.isNumber() ? v.mid() : NAN;
  };
  // Each objective, and each quantity it compares with the baseline: a term near zero (a
  // vibration that vanishes) may swing far more than the sum it sits in.
  std::vector<std::pair<std::string, const ir::Expr*>> items;
  std::function<void(const ir::Expr&)> terms = [&](const ir::Expr& e) {
    if (e.op == ir::Op::Relative && e.args[0]) items.emplace_back(ir::print(*e.args[0]), e.args[0].get());
    for (const auto& x : e.args)
      if (x) terms(*x);
  };
  for (const auto& o : m.gearbox.objectives)
    if (o.expr) {
      items.emplace_back(o.text, o.expr.get());
      terms(*o.expr);
    }
  for (const auto& [text, expr] : items) {
    const ir::Expr& e = *expr;
    OptimisationSummary::Optimum::Sensitivity s;
    s.objective = text;
    auto du = valueUnitOf(e);
    s.unit = du.name;
    auto at = [&](const std::vector<double>& deltas) {
      double v = du.shown(atSI(e, deltas));
      if (!std::isfinite(v)) ++s.failed;
      return v;
    };
    std::vector<double> zero(tol.size(), 0.0);
    s.nominal = s.lo = s.hi = at(zero);
    for (size_t i = 0; i < tol.size(); ++i) {
      auto u = units::differenceUnitFor(tol[i].dim);  // a tolerance is a difference
      OptimisationSummary::Optimum::Sensitivity::Line line{tol[i].target, tol[i].amount / u.scale, u.name, 0, 0};
      std::vector<double> d = zero;
      d[i] = -tol[i].amount;
      line.minus = at(d);
      d[i] = tol[i].amount;
      line.plus = at(d);
      s.lines.push_back(line);
    }
    for (unsigned corner = 0; corner < (1u << tol.size()); ++corner) {
      std::vector<double> d(tol.size());
      for (size_t i = 0; i < tol.size(); ++i)
        d[i] = (corner >> i) & 1u ? tol[i].amount : -tol[i].amount;
      double f = at(d);
      if (!std::isfinite(f)) continue;
      s.lo = std::isfinite(s.lo) ? std::min(s.lo, f) : f;
      s.hi = std::isfinite(s.hi) ? std::max(s.hi, f) : f;
    }
    out.push_back(std::move(s));
  }
  return out;
}

} // namespace

Optimised optimise(const ir::Program& program, const Model& m, SearchResult found, int jobs,
                   std::function<void(double)> progress, int maxIterations) {
  const ir::Gearbox& gb = m.gearbox;
  Optimised out;
  out.designs = std::move(found);
  // `relative(x)` in the report needs the baseline's design even when nothing is optimised.
  auto relative = [](const ir::Expr* e) { return ir::uses(e, {ir::Op::Relative}); };
  bool reportsRelative = false;
  if (gb.report) {
    reportsRelative = relative(gb.report->sortBy.get());
    for (const auto& c : gb.report->columns)
      reportsRelative = reportsRelative || relative(c.get());
  }
  // A sweep's `relative(…)` reads the baseline at each of its points.
  for (const auto& st : gb.studies)
    for (const auto& o : st.outputs)
      reportsRelative = reportsRelative || relative(o.get());
  // `worst(…)` over catalogue quantities: decided by the search pass.
  bool optimised = needsOptimiser(gb) && needsScenes(gb);
  // Freedoms the search pass decided: the design table, scenes and ratings read them.
  if (!optimised && !out.designs.designs.empty() && !out.designs.designs[0].freedoms.empty())
    for (const auto& d : out.designs.designs)
      out.freedoms.push_back(d.freedoms);
  if (!optimised && !reportsRelative) return out;
  // The baseline's design is its design 1, as solving the baseline alone reports it: ranked
  // by its own objectives, its freedoms decided or optimised.
  for (const auto& other : program.gearboxes)
    if (other.name == gb.baseline) {
      out.baseline = std::make_unique<Model>(program, other);
      SearchResult br = passes::search(*out.baseline, jobs, kBaselineDesigns, nullptr);
      std::vector<double> freedoms;
      if (needsOptimiser(other) && br.errors.empty()) {
        Optimised bo = optimise(program, *out.baseline, std::move(br), jobs, nullptr, maxIterations);
        br = std::move(bo.designs);
        if (!bo.freedoms.empty()) freedoms = bo.freedoms[0];
      } else if (!br.designs.empty()) {
        freedoms = br.designs[0].freedoms;
      }
      if (!br.designs.empty()) {
        out.baselineDesign = std::make_unique<Assignment>(*out.baseline);
        out.baselineDesign->choice = br.designs[0].choice;
        for (size_t f = 0; f < freedoms.size() && f < out.baselineDesign->box.size(); ++f)
          out.baselineDesign->box[f] = {freedoms[f], freedoms[f]};
      }
    }
  if (!optimised) return out;
  OptimiseOptions oo;
  oo.jobs = jobs;
  if (maxIterations > 0) oo.maxIterations = maxIterations;
  oo.progress = std::move(progress);
  auto wall0 = std::chrono::steady_clock::now();
  OptimiseResult opt = rt::optimise(m, out.baseline.get(), out.baselineDesign.get(), out.designs.designs, oo);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  // The ranked optima become the design list.
  SearchResult& r = out.designs;
  size_t keep = gb.report && gb.report->top ? static_cast<size_t>(*gb.report->top) : 10;
  r.count = opt.ranked.size();
  r.designs.clear();
  for (size_t i = 0; i < opt.ranked.size() && i < keep; ++i) {
    Design d;
    d.choice = opt.ranked[i].choice;
    d.ratio = opt.ranked[i].ratio;
    d.keys = {opt.ranked[i].objective};
    r.designs.push_back(d);
    out.freedoms.push_back(opt.ranked[i].freedoms);
  }
  OptimisationSummary& s = out.summary.emplace();
  s.candidates = opt.ranked.size() + opt.infeasible;
  s.infeasible = opt.infeasible;
  s.evaluations = opt.evaluations;
  s.sceneRtol = oo.sceneRtol;
  s.baseline = gb.baseline;
  s.termNames = opt.termNames;
  s.baselineTerms = opt.baselineTerms;
  if (!opt.ranked.empty()) {
    const auto& best = opt.ranked[0];
    OptimisationSummary::Optimum& b = s.best.emplace();
    b.ratio = best.ratio;
    for (size_t f = 0; f < m.freedoms.size() && f < best.freedoms.size(); ++f) {
      b.freedoms.push_back({m.freedoms[f].path, best.freedoms[f], units::displayUnitFor(m.freedoms[f].dim)});
    }
    b.objective = best.objective;
    b.terms = best.terms;
    b.margins = margins(m, best.choice, best.freedoms);
    b.sensitivity =
        sensitivity(m, out.baseline.get(), out.baselineDesign.get(), best.choice, best.freedoms, oo.sceneRtol);
  }
  s.rankCheck = opt.rankCheck;
  s.cloud = opt.cloud;
  s.pareto = opt.pareto;
  s.wallSeconds = wall;
  s.jobs = jobs;
  return out;
}

} // namespace gbx::rt::passes
