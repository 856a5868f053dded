#include "study/Sweep.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "study/Continuation.h"

namespace gbx::rt {

namespace {

void scenesOf(const ir::Expr& e, std::set<int>& out) {
  if (e.op == ir::Op::SceneOutput && e.output.scene >= 0) out.insert(e.output.scene);
  for (const auto& x : e.args)
    if (x) scenesOf(*x, out);
}

} // namespace

void resonanceMarks(SweepStudy& r, const ir::Study& st, double x, double fm, double fn) {
  if (st.swept.key != Q::InputSpeed || !(fm > 0) || !(fn > 0)) return;
  const std::pair<double, const char*> orders[] = {{2.0, "f_mesh = 2 f_n (parametric)"}, {1.0, "f_mesh = f_n"}, {0.5, "2 f_mesh = f_n"}, {1.0 / 3.0, "3 f_mesh = f_n"}};
  double lo = std::min(st.lo->toDouble(), st.hi->toDouble()), hi = std::max(st.lo->toDouble(), st.hi->toDouble());
  for (const auto& [k, label] : orders)
    if (double at = x * k * fn / fm; at >= lo && at <= hi) r.marks.emplace_back(at, label);
}

namespace {

// Where a sweep stands: the swept value and the series' value (NaN without a series).
struct At {
  double x = 0, series = NAN;
};

// One scene of gearbox m at a sweep's point: the swept or series effect parameter set where
// it is this scene's.
dyn::SceneResult sceneAt(const Model& m, const Assignment& a, int s, const ir::Study::EffectParam& swept,
                         const ir::Study::EffectParam& series, const ir::Study& st, At at, dyn::SceneOverrides ov) {
  ScenePlan plan = m.scenes[static_cast<size_t>(s)];
  if (s == swept.scene) plan = plan.withEffectParam(swept.effect, swept.key, at.x, st.dim.value_or(units::Dim{}));
  if (st.series && s == series.scene) plan = plan.withEffectParam(series.effect, series.key, at.series, st.series->dim);
  return dyn::runScene(m, a, plan, ov);
}

// The overrides of a quantity swept or set by the series.
void overrideAt(Evaluator& ev, const ir::Study& st, const ir::QuantityRef& swept, const ir::Study::EffectParam& sweptFx,
                const ir::QuantityRef& series, const ir::Study::EffectParam& seriesFx, At at) {
  if (sweptFx.scene < 0 && swept.owner != ir::QuantityRef::Unresolved) ev.setOverride(swept, Value::number(at.x));
  if (st.series && seriesFx.scene < 0 && series.owner != ir::QuantityRef::Unresolved)
    ev.setOverride(series, Value::number(at.series));
}

// `relative(…)` in an output: the baseline gearbox at the same point, its scenes run there.
struct BaselineAt {
  const Model* model = nullptr;
  const Assignment* design = nullptr;
  std::set<int> scenes; // the baseline's scenes the outputs' baselines read

  explicit BaselineAt(const ir::Study& st, const Model* m, const Assignment* d) : model(m), design(d) {
    std::function<void(const ir::Expr&)> visit = [&](const ir::Expr& e) {
      if (e.inBaseline) scenesOf(*e.inBaseline, scenes);
      for (const auto& x : e.args)
        if (x) visit(*x);
    };
    for (const auto& o : st.outputs)
      visit(*o);
  }
  bool on() const { return model && design; }
  // Installs the baseline's view of point `at` in ev; its evaluator and scene results live in
  // the holders given.
  void install(Evaluator& ev, const ir::Study& st, At at, std::unique_ptr<Evaluator>& bev,
               std::map<int, dyn::SceneResult>& runs, std::string& failure) const {
    bev = std::make_unique<Evaluator>(*model);
    overrideAt(*bev, st, st.sweptInBaseline, st.sweptEffectInBaseline, st.seriesInBaseline, st.seriesEffectInBaseline,
               at);
    for (int s : scenes) {
      dyn::SceneOverrides ov;
      ov.evaluator = bev.get();
      ov.keepSeries = false;
      ov.estimateError = false;
      dyn::SceneResult r = sceneAt(*model, *design, s, st.sweptEffectInBaseline, st.seriesEffectInBaseline, st, at, ov);
      if (!r.failure.empty() && failure.empty()) failure = "the baseline's " + r.failure;
      runs.emplace(s, std::move(r));
    }
    bev->sceneOutput = [&runs](const ir::Expr& e, const Assignment&, const Evaluator&) {
      auto it = runs.find(e.output.scene);
      const dyn::SceneNumber* n = it == runs.end() ? nullptr : it->second.find(e.output);
      return n && std::isfinite(n->value) ? Value::number(n->value) : Value::invalid();
    };
    const Evaluator* b = bev.get();
    const Assignment* d = design;
    ev.baseline = [b, d](const ir::Expr& e) { return b->eval(e, *d); };
  }
};

// One point of a sweep (`first`: the first of the first line); false, with r.failure, where
// it cannot be solved.
bool sweepPoint(const Model& m, const Assignment& a, const ir::Study& st, At at, bool first, const BaselineAt& base,
                const std::set<int>& scenes, const std::vector<std::set<int>>& outputScenes,
                std::map<int, std::vector<double>>& guesses, SweepStudy& r) {
  const ir::Study::EffectParam seriesFx = st.series ? st.series->effect : ir::Study::EffectParam{};
  Evaluator ev(m);
  overrideAt(ev, st, st.swept, st.sweptEffect, st.series ? st.series->ref : ir::QuantityRef{}, seriesFx, at);
  SweepStudy::Point p;
  p.x = at.x;
  p.series = at.series;
  auto where = [&] {
    std::string line =
        st.series ? fmt::format(", {} = {:.6g} {}", r.seriesTarget, r.seriesUnit.shown(at.series), r.seriesUnit.name)
                  : "";
    return fmt::format("study `{}` at {} = {:.6g} {}{}", st.name, st.target, r.unit.shown(at.x), r.unit.name, line);
  };
  std::map<int, dyn::SceneResult> results;
  for (int s : scenes) {
    dyn::SceneOverrides ov;
    ov.evaluator = &ev;
    ov.keepSeries = false;
    if (guesses.count(s)) ov.guess = guesses[s];
    dyn::SceneResult res = sceneAt(m, a, s, st.sweptEffect, seriesFx, st, at, ov);
    if (!res.failure.empty()) {
      r.failure = fmt::format("{}: {}", where(), res.failure);
      return false;
    }
    if (!res.orbit.empty()) guesses[s] = res.orbit;
    if (s == *scenes.begin()) {
      if (first) resonanceMarks(r, st, at.x, res.meshFrequency, res.naturalFrequency);
      p.stability = res.stability;
      p.error = res.errorEstimate >= 0 ? res.errorEstimate : NAN;
    }
    results.emplace(s, std::move(res));
  }
  std::unique_ptr<Evaluator> bev;
  std::map<int, dyn::SceneResult> baseRuns;
  if (base.on()) {
    std::string failure;
    base.install(ev, st, at, bev, baseRuns, failure);
    if (!failure.empty()) {
      r.failure = fmt::format("{}: {}", where(), failure);
      return false;
    }
  }
  if (r.scene)
    ev.sceneOutput = [&](const ir::Expr& e, const Assignment& aa, const Evaluator& asking) {
      auto it = results.find(e.output.scene);
      const dyn::SceneResult* run = it == results.end() ? nullptr : &it->second;
      // At a corner of the tolerance box (`worst`, `mean`) the scene runs again there.
      dyn::SceneResult corner;
      if (run && !asking.offsets().empty()) {
        dyn::SceneOverrides ov;
        ov.evaluator = &asking;
        ov.keepSeries = false;
        ov.estimateError = false;
        if (guesses.count(e.output.scene)) ov.guess = guesses[e.output.scene];
        corner = sceneAt(m, aa, e.output.scene, st.sweptEffect, seriesFx, st, at, ov);
        run = &corner;
      }
      const dyn::SceneNumber* num = run ? run->find(e.output) : nullptr;
      return num && std::isfinite(num->value) ? Value::number(num->value) : Value::invalid();
    };
  for (size_t i = 0; i < st.outputs.size(); ++i) {
    Value v = ev.eval(*st.outputs[i], a);
    p.y.push_back(v.isNumber() ? v.mid() : NAN);
    bool unstable = false;
    for (int s : outputScenes[i])
      unstable = unstable || results.at(s).unstable;
    p.unstable.push_back(unstable);
  }
  r.points.push_back(std::move(p));
  return true;
}

} // namespace

SweepStudy sweep(const Model& m, const Assignment& a, const ir::Study& st, const Model* baseline,
                 const Assignment* baseDesign) {
  SweepStudy r;
  r.name = st.name;
  // Where the design itself stands on the swept axis, when the axis is one of its quantities.
  if (st.sweptEffect.scene < 0 && st.swept.owner != ir::QuantityRef::Unresolved) {
    Value at = Evaluator(m).quantity(st.swept, a);
    if (at.isNumber() && at.isPoint()) r.nominal = at.mid();
  }
  r.target = st.target;
  r.plot = st.plot;
  double lo = st.lo->toDouble(), hi = st.hi->toDouble(), step = st.step->toDouble();
  // The swept quantity in its one display unit (docs/reports.md): a deviation, a modification
  // or an effect's length (a clearance, an error amplitude) in um.
  units::Dim sweptDim = st.dim.value_or(units::Dim{});
  bool micro = sweptDim == units::dims::length && (st.sweptEffect.scene >= 0 || cat::readsInMicrometres(st.swept.key));
  r.unit = micro ? units::micrometres() : units::displayUnitFor(sweptDim);
  for (size_t i = 0; i < st.outputs.size(); ++i) r.outputs.push_back({st.outputTexts[i], displayUnitOf(*st.outputs[i])});
  long n = static_cast<long>(std::floor(std::fabs(hi - lo) / step * (1 + 1e-12))) + 1;
  if (hi < lo) step = -step;  // a down-sweep
  std::set<int> scenes;
  std::vector<std::set<int>> outputScenes(st.outputs.size());
  for (size_t i = 0; i < st.outputs.size(); ++i) {
    scenesOf(*st.outputs[i], outputScenes[i]);
    scenes.insert(outputScenes[i].begin(), outputScenes[i].end());
  }
  r.scene = !scenes.empty();
  const ir::Setting* cont = ir::findSetting(st.settings, Q::Continuation);
  bool arclength = cont && cont->choice == cat::continuation::Arclength;
  if (r.scene) r.continuation = arclength ? "arclength" : "natural";
  const auto& fxp = st.sweptEffect;
  // The baseline only where an output reads it.
  bool readsBaseline = std::any_of(st.outputs.begin(), st.outputs.end(),
                                   [](const ir::ExprPtr& o) { return ir::uses(o.get(), {ir::Op::Relative}); });
  if (!readsBaseline) baseline = nullptr;
  if (arclength && (st.series || readsBaseline)) {
    r.failure = fmt::format(
        "study `{}`: `continuation = arclength` follows one line without a baseline; leave out `continuation`, "
        "or the set of lines and `relative(…)`",
        st.name);
    return r;
  }
  if (arclength && fxp.scene >= 0) {
    r.failure = fmt::format("study `{}`: `continuation = arclength` follows the operating point or a stage attribute; sweep `{}` "
                            "point by point (leave out `continuation`)",
                            st.name, st.target);
    return r;
  }
  if (fxp.scene >= 0 && !scenes.count(fxp.scene)) scenes.insert(fxp.scene);
  if (!scenes.empty()) r.stabilityScene = m.scenes[static_cast<size_t>(*scenes.begin())].name;
  // The checker made sure an arclength study's outputs read exactly one scene (E0225).
  if (arclength) {
    if (continuation(m, a, st, m.scenes[static_cast<size_t>(*scenes.begin())], r)) {
      return r;
    }
    r.continuation = "natural";
    r.notes.push_back("the scene is linear: its response has no turning points, only poles where a Floquet multiplier passes 1, so it "
                      "is followed point by point");
  }
  if (st.series) {
    r.seriesTarget = st.series->target;
    units::Dim d = st.series->dim;
    bool microSeries =
        d == units::dims::length && (st.series->effect.scene >= 0 || cat::readsInMicrometres(st.series->ref.key));
    r.seriesUnit = microSeries ? units::micrometres() : units::displayUnitFor(d);
  }
  BaselineAt base(st, baseline, baseDesign);
  std::vector<double> lines;
  if (st.series)
    for (const auto& v : st.series->members)
      lines.push_back(v.toDouble());
  else
    lines.push_back(NAN);
  for (size_t l = 0; l < lines.size(); ++l) {
    // Natural continuation along each line: each periodic orbit the next point's first guess.
    std::map<int, std::vector<double>> guesses;
    for (long k = 0; k < n; ++k) {
      At at{lo + static_cast<double>(k) * step, lines[l]};
      if (!sweepPoint(m, a, st, at, k == 0 && l == 0, base, scenes, outputScenes, guesses, r)) return r;
    }
  }
  // Every point's scene estimated its error; the report gives the largest.
  const SweepStudy::Point* worst = nullptr;
  for (const auto& p : r.points)
    if (std::isfinite(p.error) && (!worst || p.error > worst->error)) worst = &p;
  if (worst)
    r.notes.push_back(fmt::format("error estimate of scene `{}` at every point, at most {:.2e} (at {} = {:.6g}{})", r.stabilityScene,
                                  worst->error, st.target, r.unit.shown(worst->x), r.unit.name.empty() ? "" : " " + r.unit.name));
  return r;
}

} // namespace gbx::rt
