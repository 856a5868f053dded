#include "study/Sweep.h"

#include <cmath>
#include <functional>
#include <map>
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

SweepStudy sweep(const Model& m, const Assignment& a, const ir::Study& st) {
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
  // Natural continuation: point by point, each periodic orbit the next point's first guess.
  std::map<int, std::vector<double>> guesses;
  for (long k = 0; k < n; ++k) {
    double x = lo + static_cast<double>(k) * step;
    Evaluator ev(m);
    if (fxp.scene < 0) ev.setOverride(st.swept, Value::number(x));
    SweepStudy::Point p;
    p.x = x;
    std::map<int, dyn::SceneResult> results;
    for (int s : scenes) {
      dyn::SceneOverrides ov;
      ov.evaluator = &ev;
      ov.keepSeries = false;
      if (guesses.count(s)) ov.guess = guesses[s];
      const ScenePlan& declared = m.scenes[static_cast<size_t>(s)];
      dyn::SceneResult res = s == fxp.scene ? dyn::runScene(m, a, declared.withEffectParam(fxp.effect, fxp.key, x, st.dim.value_or(units::Dim{})), ov)
                                            : dyn::runScene(m, a, declared, ov);
      if (!res.failure.empty()) {
        r.failure = fmt::format("study `{}` at {} = {:.6g} {}: {}", st.name, st.target, r.unit.shown(x), r.unit.name, res.failure);
        return r;
      }
      if (!res.orbit.empty()) guesses[s] = res.orbit;
      if (s == *scenes.begin()) {
        if (k == 0) resonanceMarks(r, st, x, res.meshFrequency, res.naturalFrequency);
        p.stability = res.stability;
        p.error = res.errorEstimate >= 0 ? res.errorEstimate : NAN;
      }
      results.emplace(s, std::move(res));
    }
    if (r.scene)
      ev.sceneOutput = [&](const ir::Expr& e, const Assignment& aa, const Evaluator& asking) {
        auto it = results.find(e.output.scene);
        const dyn::SceneResult* r = it == results.end() ? nullptr : &it->second;
        // At a corner of the tolerance box (`worst`, `mean`) the scene runs again there.
        dyn::SceneResult corner;
        if (r && !asking.offsets().empty()) {
          dyn::SceneOverrides ov;
          ov.evaluator = &asking;
          ov.keepSeries = false;
          ov.estimateError = false;
          if (guesses.count(e.output.scene)) ov.guess = guesses[e.output.scene];
          const ScenePlan& declared = m.scenes[static_cast<size_t>(e.output.scene)];
          corner = e.output.scene == fxp.scene ? dyn::runScene(m, aa, declared.withEffectParam(fxp.effect, fxp.key, x, st.dim.value_or(units::Dim{})), ov)
                                               : dyn::runScene(m, aa, declared, ov);
          r = &corner;
        }
        const dyn::SceneNumber* num = r ? r->find(e.output) : nullptr;
        return num && std::isfinite(num->value) ? Value::number(num->value) : Value::invalid();
      };
    for (size_t i = 0; i < st.outputs.size(); ++i) {
      Value v = ev.eval(*st.outputs[i], a);
      p.y.push_back(v.isNumber() ? v.mid() : NAN);
      bool unstable = false;
      for (int s : outputScenes[i]) unstable = unstable || results.at(s).unstable;
      p.unstable.push_back(unstable);
    }
    r.points.push_back(std::move(p));
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
