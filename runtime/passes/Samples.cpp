#include "passes/Samples.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Deadline.h"
#include "model/Sampling.h"
#include "parallel/Ranks.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

// Every `worst`, `mean` and `quantile` node under e, through the gearbox's lets.
void scatters(const ir::Gearbox& g, const ir::Expr& e, std::vector<const ir::Expr*>& out, int depth = 0) {
  if (depth > 64) return;
  if (e.op == ir::Op::Scatter) out.push_back(&e);
  if (e.op == ir::Op::Let && e.let >= 0 && static_cast<size_t>(e.let) < g.lets.size() && g.lets[static_cast<size_t>(e.let)].expr)
    scatters(g, *g.lets[static_cast<size_t>(e.let)].expr, out, depth + 1);
  for (const auto& a : e.args)
    if (a) scatters(g, *a, out, depth + 1);
}

// The scenes a quantity reads, through the lets.
void scenesOf(const ir::Gearbox& g, const ir::Expr& e, std::set<int>& out, int depth = 0) {
  if (depth > 64) return;
  if (e.op == ir::Op::SceneOutput && e.output.scene >= 0) out.insert(e.output.scene);
  if (e.op == ir::Op::Let && e.let >= 0 && static_cast<size_t>(e.let) < g.lets.size() && g.lets[static_cast<size_t>(e.let)].expr)
    scenesOf(g, *g.lets[static_cast<size_t>(e.let)].expr, out, depth + 1);
  for (const auto& a : e.args)
    if (a) scenesOf(g, *a, out, depth + 1);
}

std::vector<const ir::Expr*> sampledNodes(const Model& m, const std::vector<const ir::Expr*>& exprs) {
  std::vector<const ir::Expr*> nodes;
  for (const auto* e : exprs)
    if (e) scatters(m.gearbox, *e, nodes);
  return nodes;
}

// Bins by the Freedman-Diaconis rule, between 10 and 60 of them, over [min, max].
void histogram(MonteCarloReport::Output& o, const std::vector<double>& sorted) {
  double lo = sorted.front(), hi = sorted.back();
  if (!(hi > lo)) {
    o.edges = {lo, lo};
    o.counts = {static_cast<long>(sorted.size())};
    return;
  }
  double iqr = sortedQuantile(sorted, 0.75) - sortedQuantile(sorted, 0.25);
  double width = 2 * iqr / std::cbrt(static_cast<double>(sorted.size()));
  long bins = width > 0 ? static_cast<long>(std::ceil((hi - lo) / width)) : 10;
  bins = std::clamp(bins, 10L, 60L);
  o.edges.resize(static_cast<size_t>(bins) + 1);
  for (long b = 0; b <= bins; ++b) o.edges[static_cast<size_t>(b)] = lo + (hi - lo) * static_cast<double>(b) / static_cast<double>(bins);
  o.counts.assign(static_cast<size_t>(bins), 0);
  for (double x : sorted) {
    long b = std::min(bins - 1, static_cast<long>((x - lo) / (hi - lo) * static_cast<double>(bins)));
    ++o.counts[static_cast<size_t>(b)];
  }
}

// Why q has no value over the samples: the first sample where it has none, and its deviations.
std::string failureAt(const Model& m, const Evaluator& ev, const ir::Expr& node, const Assignment& best, const Sampling& s) {
  const auto& tol = m.gearbox.tolerances;
  for (long k = 0; k < s.samples; ++k) {
    Evaluator at(ev);
    std::vector<double> d = s.deviations(tol, k);
    for (size_t i = 0; i < tol.size(); ++i) at.addOffset(tol[i].ref, d[i]);
    if (at.eval(*node.args[0], best).isNumber()) continue;
    return fmt::format("`{}` has no value at Monte Carlo sample {} of {} ({}); its statistics are left out", node.name, k + 1,
                       s.samples, deviationsText(m, d, true));
  }
  return fmt::format("`{}` has no value at some Monte Carlo sample; its statistics are left out", node.name);
}

// Samples that put an attribute beyond the range its catalogue row allows (a helix angle
// below zero): said, since such a sample describes no real pair.
std::vector<std::string> rangeWarnings(const Model& m, const Evaluator& ev, const Assignment& best, const MonteCarloReport& r) {
  std::vector<std::string> out;
  const auto& tol = m.gearbox.tolerances;
  for (size_t i = 0; i < tol.size(); ++i) {
    const ir::Tolerance& t = tol[i];
    if (t.ref.owner != ir::QuantityRef::Stage || t.ref.index < 0 || static_cast<size_t>(t.ref.index) >= m.gearbox.stages.size()) continue;
    const ir::Stage& st = m.gearbox.stages[static_cast<size_t>(t.ref.index)];
    const cat::AttrSpec* spec = cat::findAttr(cat::kindSpec(st.kind), t.target.substr(st.name.size() + 1));
    Value v = ev.quantity(t.ref, best);
    if (!spec || !v.isNumber()) continue;
    auto u = units::displayUnitFor(t.dim);
    double lo = spec->atLeast ? spec->atLeast->toDouble() : -INFINITY, hi = spec->atMost ? spec->atMost->toDouble() : INFINITY;
    long below = 0, above = 0;
    double least = INFINITY, most = -INFINITY;
    for (const auto& d : r.deviations) {
      double x = v.mid() + d[i];
      least = std::min(least, x);
      most = std::max(most, x);
      below += x < lo || (spec->positive && x <= 0);
      above += x > hi;
    }
    if (below + above == 0) continue;
    std::string range = spec->atLeast && spec->atMost ? fmt::format("{:g} to {:g} {}", u.shown(lo), u.shown(hi), u.name)
                        : spec->atLeast                 ? fmt::format("at least {:g} {}", u.shown(lo), u.name)
                        : spec->atMost                  ? fmt::format("at most {:g} {}", u.shown(hi), u.name)
                                                        : std::string("above zero");
    out.push_back(fmt::format("{} of {} samples put `{}` outside its range, {} (the samples reach {:.4g} to {:.4g} {}): they "
                              "describe no real pair; narrow the tolerance",
                              below + above, r.samples, t.target, range, u.shown(least), u.shown(most), u.name));
  }
  return out;
}

} // namespace

std::vector<const ir::Expr*> sampledExpressions(const ir::Gearbox& g, const Columns& columns) {
  std::vector<const ir::Expr*> exprs = columns.exprs;
  for (const auto& rule : g.rules) exprs.push_back(rule.expr.get());
  for (const auto& ob : g.objectives) exprs.push_back(ob.expr.get());
  return exprs;
}

SampleScenes::SampleScenes(const Model& m, const Assignment& best, const std::vector<const ir::Expr*>& exprs,
                           const std::vector<dyn::SceneResult>& nominal, int jobs) {
  Sampling s = Sampling::of(m.gearbox);
  const auto& tol = m.gearbox.tolerances;
  if (!s.on() || tol.empty()) return;
  std::set<int> used;
  for (const auto* n : sampledNodes(m, exprs))
    if (!n->args.empty() && n->args[0]) scenesOf(m.gearbox, *n->args[0], used);
  if (used.empty()) return;
  auto offsetsAt = [&](size_t k, Evaluator& at) {
    std::vector<double> d = s.deviations(tol, static_cast<long>(k));
    for (size_t i = 0; i < tol.size(); ++i) at.addOffset(tol[i].ref, d[i]);
  };
  for (long k = 0; k < s.samples; ++k) {
    Evaluator at(m);
    offsetsAt(static_cast<size_t>(k), at);
    sampleOf_.emplace(at.offsetKey(), k);
  }
  for (int sc : used) {
    if (sc < 0 || static_cast<size_t>(sc) >= nominal.size() || static_cast<size_t>(sc) >= m.scenes.size()) continue;
    const dyn::SceneResult& base = nominal[static_cast<size_t>(sc)];
    // Each sample's numbers in the nominal run's order; none where the run failed.
    auto values = par::map(static_cast<size_t>(s.samples), jobs, [&](size_t k) {
      if (Deadline::expired()) return std::vector<double>{};  // past the time limit: the run fails
      Evaluator at(m);
      offsetsAt(k, at);
      dyn::SceneOverrides ov;
      ov.evaluator = &at;
      ov.estimateError = false;
      ov.keepSeries = false;
      dyn::SceneResult r = dyn::runScene(m, best, m.scenes[static_cast<size_t>(sc)], ov);
      std::vector<double> v;
      if (!r.failure.empty() || r.numbers.size() != base.numbers.size()) return v;
      for (const auto& n : r.numbers) v.push_back(n.value);
      return v;
    }, true);
    auto& runs = runs_[sc];
    runs.reserve(values.size());
    for (size_t k = 0; k < values.size(); ++k) {
      dyn::SceneResult r;
      r.name = base.name;
      if (values[k].size() != base.numbers.size()) {
        r.failure = fmt::format("scene `{}` failed at Monte Carlo sample {}", base.name, k + 1);
      } else {
        r.numbers = base.numbers;
        for (size_t j = 0; j < values[k].size(); ++j) r.numbers[j].value = values[k][j];
      }
      runs.push_back(std::move(r));
    }
  }
}

const dyn::SceneResult* SampleScenes::find(int scene, const Evaluator& asking) const {
  auto r = runs_.find(scene);
  if (r == runs_.end()) return nullptr;
  auto k = sampleOf_.find(asking.offsetKey());
  if (k == sampleOf_.end() || static_cast<size_t>(k->second) >= r->second.size()) return nullptr;
  return &r->second[static_cast<size_t>(k->second)];
}

std::optional<MonteCarloReport> monteCarlo(const Model& m, const Assignment& best, const Columns& columns,
                                           const SampleScenes* scenes, const std::vector<dyn::SceneResult>& nominal) {
  Sampling s = Sampling::of(m.gearbox);
  if (!s.on() || m.gearbox.tolerances.empty()) return std::nullopt;
  MonteCarloReport r;
  r.samples = s.samples;
  r.distribution = s.distributionName();
  r.uniform = s.distribution == cat::distribution::Uniform;
  r.seed = s.seed;
  for (const auto& t : m.gearbox.tolerances) {
    auto u = units::differenceUnitFor(t.dim);
    r.tolerances.push_back({t.target, t.amount / u.scale, u.name, t.amount, u.scale});
  }
  for (long k = 0; k < s.samples; ++k) r.deviations.push_back(s.deviations(m.gearbox.tolerances, k));
  const std::vector<const ir::Expr*> exprs = sampledExpressions(m.gearbox, columns);
  Evaluator ev(m);
  ev.sceneOutput = [&](const ir::Expr& e, const Assignment&, const Evaluator& asking) -> Value {
    int sc = e.output.scene;
    const dyn::SceneResult* run = nullptr;
    if (asking.offsets().empty()) run = sc >= 0 && static_cast<size_t>(sc) < nominal.size() ? &nominal[static_cast<size_t>(sc)] : nullptr;
    else if (scenes) run = scenes->find(sc, asking);
    const auto* n = run ? run->find(e.output) : nullptr;
    return n && std::isfinite(n->value) ? Value::number(n->value) : Value::invalid();
  };
  // One output per quantity as written; a `quantile` adds its p to that quantity's.
  std::map<std::string, size_t> index;
  for (const ir::Expr* n : sampledNodes(m, exprs)) {
    if (n->args.empty() || !n->args[0]) continue;
    auto [it, added] = index.emplace(n->name, r.outputs.size());
    if (added) {
      MonteCarloReport::Output o;
      o.quantity = n->name;
      o.unit = displayUnitOf(*n->args[0]);
      auto xs = ev.overSamples(*n->args[0], best, true);
      if (!xs) {
        r.failure += (r.failure.empty() ? "" : "; ") + failureAt(m, ev, *n, best, s);
        index.erase(it);
        continue;
      }
      o.values = std::move(*xs);
      Value at = ev.eval(*n->args[0], best);
      o.nominal = at.isNumber() ? at.mid() : NAN;
      for (double p : {0.05, 0.5, 0.95}) o.quantiles.push_back({p, 0, 0});
      r.outputs.push_back(std::move(o));
    }
    auto& o = r.outputs[it->second];
    // The worse end: where a rule or an objective reads it, else the quantity's own.
    if (n->fn == cat::Fn::Worst && n->sense != 0) o.sense = n->sense;
    else if (o.sense == 0) o.sense = betterSense(*n->args[0]);
    if (n->fn == cat::Fn::Quantile && n->args.size() > 1 && n->args[1]->isConst()) {
      double p = n->args[1]->value.toDouble();
      if (std::none_of(o.quantiles.begin(), o.quantiles.end(), [&](const auto& q) { return q.p == p; })) o.quantiles.push_back({p, 0, 0});
    }
  }
  for (auto& o : r.outputs) {
    std::vector<double> sorted = o.values;
    std::sort(sorted.begin(), sorted.end());
    o.mean = sampleMean(o.values);
    o.stdDev = sampleStdDev(o.values);
    o.meanError = o.stdDev / std::sqrt(static_cast<double>(o.values.size()));
    o.min = sorted.front();
    o.max = sorted.back();
    std::sort(o.quantiles.begin(), o.quantiles.end(), [](const auto& a, const auto& b) { return a.p < b.p; });
    for (auto& q : o.quantiles) {
      q.value = sortedQuantile(sorted, q.p);
      q.error = quantileStandardError(sorted, q.p);
    }
    if (o.sense != 0) o.worstSample = static_cast<long>(worstIndex(o.values, o.sense));
    histogram(o, sorted);
  }
  // Quantities read over the samples only in studies: no part of its own (each sweep point
  // reads them there).
  if (r.outputs.empty() && r.failure.empty()) return std::nullopt;
  r.warnings = rangeWarnings(m, ev, best, r);
  return r;
}

} // namespace gbx::rt::passes
