#include "passes/Scenes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

SceneReport sceneReport(const dyn::SceneResult& r, const ScenePlan& scene) {
  SceneReport s;
  s.name = r.name.empty() ? scene.name : r.name;
  s.target = scene.target;
  s.failure = r.failure;
  if (!r.failure.empty()) return s;
  s.method = r.method;
  s.eigen = r.eigen;
  s.rtol = r.rtol;
  s.atol = r.atol;
  s.steps = r.stats.steps;
  s.rejected = r.stats.rejected;
  s.rhs = r.stats.rhsEvaluations;
  s.jacobians = r.stats.jacobianEvaluations;
  s.events = r.stats.events;
  s.cpu = r.stats.cpuSeconds;
  s.referenceCpu = r.referenceStats.cpuSeconds;
  s.errorEstimate = r.errorEstimate;
  s.errorMethod = r.errorMethod;
  for (const auto& p : r.errorParts) s.errorParts.emplace_back(p.name, p.value);
  s.stepRule = r.stepRule;
  s.steady = r.balanceHarmonics > 0                    ? "harmonic_balance"
             : r.steady == dyn::SteadyMethod::Periodic ? "periodic"
             : r.steady == dyn::SteadyMethod::Settle   ? "settle"
             : r.steady == dyn::SteadyMethod::Static   ? "static"
                                                       : "from rest";
  s.integrated = r.steady != dyn::SteadyMethod::Static;
  s.model = r.model;
  s.warnings = r.warnings;
  for (const auto& n : r.numbers) {
    auto u = cat::signalFnSpec(n.fn).decibels ? units::DisplayUnit{"dB", 1}
             : n.dim == units::dims::length   ? cat::signalUnit(n.signal)
                                              : units::displayUnitFor(n.dim);
    s.outputs.push_back({n.key, u.name, n.value, n.value / u.scale, n.error});
  }
  for (const auto& ser : r.series) {
    auto u = ser.dim == units::dims::length ? units::micrometres() : units::displayUnitFor(ser.dim);
    if (ser.isSpectrum) {
      SceneReport::SpectrumRow row{ser.key, u.name, u.scale, {}};
      for (const auto& p : ser.spectrum.peaks) row.peaks.push_back({p.frequency, p.amplitude, p.harmonic});
      s.spectra.push_back(row);
    }
    SceneReport::Plot line;
    line.key = ser.key;
    line.signal = ser.signal;
    line.unit = u.name;
    line.spectrum = ser.isSpectrum;
    line.meshFrequency = ser.meshFrequency > 0 ? ser.meshFrequency : r.meshFrequency;
    if (ser.isSpectrum) {
      // Up to the tenth mesh order, or further where a listed peak lies beyond it.
      double fmax = line.meshFrequency > 0 ? 10.5 * line.meshFrequency : INFINITY;
      for (const auto& p : ser.spectrum.peaks) fmax = std::max(fmax, 1.05 * p.frequency);
      for (size_t i = 0; i < ser.spectrum.frequency.size() && ser.spectrum.frequency[i] <= fmax; ++i) {
        line.x.push_back(ser.spectrum.frequency[i]);
        line.y.push_back(ser.spectrum.amplitude[i] / u.scale);
      }
    } else {
      // At most 4000 points: every k-th sample, so the file stays small and faithful.
      size_t step = std::max<size_t>(1, ser.t.size() / 4000);
      for (size_t i = 0; i < ser.t.size(); i += step) {
        line.x.push_back(ser.t[i]);
        line.y.push_back(ser.v[i] / u.scale);
      }
    }
    s.plots.push_back(std::move(line));
  }
  return s;
}

} // namespace

SceneRuns scenes(const Model& m, const Assignment& best, const Columns& columns, int jobs) {
  SceneRuns out;
  std::vector<dyn::SceneResult>& results = out.results;
  for (const auto& sc : m.scenes) {
    auto res = dyn::runScene(m, best, sc);
    if (!res.failure.empty()) out.errors.push_back(res.failure);
    out.scenes.push_back(sceneReport(res, sc));
    results.push_back(std::move(res));
  }
  // Columns over scene results: read from the runs above; at a corner of the tolerance box
  // (`worst(…)`, `mean(…)`) the scene runs again with that corner's deviations.
  std::map<std::pair<int, std::vector<double>>, dyn::SceneResult> corners;
  std::mutex cornersMutex;
  // Monte Carlo: every sample's scenes first, shared over the threads and ranks.
  out.samples = std::make_shared<SampleScenes>(m, best, sampledExpressions(m.gearbox, columns), results, jobs);
  Evaluator ev(m);
  ev.sceneOutput = [&](const ir::Expr& e, const Assignment& a, const Evaluator& asking) -> Value {
    int sc = e.output.scene;
    if (sc < 0 || static_cast<size_t>(sc) >= results.size()) return Value::invalid();
    const dyn::SceneResult* r = &results[static_cast<size_t>(sc)];
    if (!asking.offsets().empty()) {
      if (const auto* at = out.samples->find(sc, asking)) r = at;
    }
    if (!asking.offsets().empty() && r == &results[static_cast<size_t>(sc)]) {
      // Samples may ask from several threads (a scene the sample runs above left out).
      std::lock_guard<std::mutex> lock(cornersMutex);
      std::vector<double> key = asking.offsetKey();
      auto it = corners.find({sc, key});
      if (it == corners.end()) {
        dyn::SceneOverrides ov;
        ov.evaluator = &asking;
        ov.estimateError = false;
        ov.keepSeries = false;
        it = corners.emplace(std::make_pair(sc, key), dyn::runScene(m, a, m.scenes[static_cast<size_t>(sc)], ov)).first;
      }
      r = &it->second;
    }
    const auto* n = r->find(e.output.fn, e.output.signal, e.output.order);
    return n && std::isfinite(n->value) ? Value::number(n->value) : Value::invalid();
  };
  for (size_t i = 0; i < columns.exprs.size(); ++i) {
    const ir::Expr& c = *columns.exprs[i];
    if (c.op == ir::Op::SceneOutput) {
      if (c.output.scene < 0) continue;
      if (const auto* n =
              results[static_cast<size_t>(c.output.scene)].find(c.output.fn, c.output.signal, c.output.order))
        out.columns.push_back({i, n->value});
      continue;
    }
    // `relative(…)` columns: the optimiser's pass.
    if (!ir::uses(&c, {ir::Op::SceneOutput}) || ir::uses(&c, {ir::Op::Relative})) continue;
    Value v = ev.eval(c, best);
    if (v.isNumber()) out.columns.push_back({i, v.mid()});
    // The corners ran for the value above: the note reads them from the same runs.
    if (auto note = cornerNote(m, ev, c, columns.names[i], best)) out.notes.push_back(*note);
  }
  return out;
}

} // namespace gbx::rt::passes
