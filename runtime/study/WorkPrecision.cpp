#include "study/WorkPrecision.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include <fmt/format.h>

#include "dynamics/Scene.h"
#include "model/StageKind.h"

namespace gbx::rt {

namespace {

struct Steady {
  std::string name;
  bool periodic;
  bool balance = false; // harmonic balance, its harmonics doubled until the orbit moves less than rtol
};

// The ways to the steady state a study draws: shooting, harmonic balance beside it where a
// stage's scene has a periodic steady state, and settling (or the run from rest).
std::vector<Steady> steadiesOf(const Model& m, const ScenePlan& scene, bool fromRest, long settle) {
  std::vector<Steady> steadies;
  if (!fromRest) steadies.push_back({"periodic", true});
  if (!fromRest && scene.stage >= 0 && m.info(scene.stage).kind->scene != SceneModel::None)
    steadies.push_back({"harmonic_balance", true, true});
  if (fromRest)
    steadies.push_back({"from rest", false});
  else if (!scene.settle || scene.settle.meshPeriods)
    steadies.push_back({fmt::format("settle {}", settle), false});
  return steadies;
}

} // namespace

WorkPrecisionStudy workPrecision(const Model& m, const Assignment& design, const ir::Study& study, const ScenePlan& scene,
                                 const std::function<void(double)>& progress) {
  WorkPrecisionStudy r;
  r.name = study.name;
  r.scene = scene.name;
  std::vector<double> rtols;
  std::vector<int> harmonics;
  std::vector<cat::Method> methods;
  for (const auto& s : study.settings) {
    if (s.key == Q::Rtol)
      for (const auto& v : s.members) rtols.push_back(v.toDouble());
    if (s.key == Q::Harmonics && s.lo && s.hi)
      for (long h = static_cast<long>(s.lo->toDouble()); h <= static_cast<long>(s.hi->toDouble()); ++h) harmonics.push_back(static_cast<int>(h));
    if (s.key == Q::Harmonics)
      for (const auto& v : s.members) harmonics.push_back(static_cast<int>(v.toDouble()));
    if (s.key == Q::Methods)
      for (int c : s.choices) methods.push_back(cat::kMethods[static_cast<size_t>(c)].id);
  }
  if (rtols.empty()) rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::sort(rtols.begin(), rtols.end(), std::greater<>());
  bool varying = scene.fx.varying.has_value();
  if (harmonics.empty() || !varying) harmonics = {0};
  if (methods.empty()) methods = {scene.method};
  double tightest = rtols.back();
  // The periodic steady state against settling a transient, both drawn: the scene's own
  // `settle = N`, or 200 periods when the scene is periodic by default.
  bool fromRest = scene.duration && !scene.record;
  long settle = scene.settle.value && scene.settle.meshPeriods ? std::lround(*scene.settle.value) : 200;
  std::vector<Steady> steadies = steadiesOf(m, scene, fromRest, settle);
  auto steadyOv = [&](dyn::SceneOverrides ov, const Steady& s) {
    ov.harmonicBalance = s.balance;
    if (s.balance) ov.balanceHarmonics = 0; // its harmonics follow rtol
    if (s.periodic)
      ov.forcePeriodic = true;
    else if (!fromRest)
      ov.settlePeriods = settle;
    return ov;
  };
  // Runs in all: a reference and its check per harmonics setting, then every method at every tolerance.
  size_t curves = 0;
  for (const Steady& s : steadies)
    curves += s.balance ? 1 : methods.size();
  double total = static_cast<double>(harmonics.size() * (2 + curves * rtols.size())), done = 0;
  auto tick = [&](double n) {
    done += n;
    if (progress) progress(done / total);
  };
  for (int h : harmonics) {
    dyn::SceneOverrides base;
    base.estimateError = false;
    base.keepSeries = false;
    if (h > 0) base.harmonics = h;
    // The reference, and a still tighter run that says how far it can be trusted.
    auto refOv = steadyOv(base, steadies.front());
    refOv.method = cat::Method::Rk8pd;
    refOv.adaptiveShooting = true; // its error control set by rtol, unlike fixed steps on the samples
    refOv.rtol = tightest / 100;
    auto ref = dyn::runScene(m, design, scene, refOv);
    refOv.rtol = tightest / 1000;
    auto check = dyn::runScene(m, design, scene, refOv);
    tick(2);
    WorkPrecisionStudy::Reference rf;
    rf.harmonics = h;
    if (!ref.failure.empty() || ref.numbers.empty() || !check.failure.empty()) {
      rf.failure = ref.failure.empty() ? check.failure : ref.failure;
      r.references.push_back(rf);
      tick(static_cast<double>(curves * rtols.size()));
      continue;
    }
    // The first steady output (not the stability, a property of the method).
    size_t o = 0;
    while (o < ref.numbers.size() && (ref.numbers[o].signal == cat::Signal::Stability || !std::isfinite(ref.numbers[o].value))) ++o;
    if (o == ref.numbers.size() || o >= check.numbers.size()) {
      rf.failure = "the scene has no steady output to compare (unstable, or only its stability)";
      r.references.push_back(rf);
      tick(static_cast<double>(curves * rtols.size()));
      continue;
    }
    double refValue = ref.numbers[o].value;
    rf.ok = true;
    rf.output = ref.numbers[o].key;
    rf.rtol = tightest / 100;
    rf.steady = steadies.front().name;
    rf.value = refValue;
    rf.checkRtol = tightest / 1000;
    rf.difference = std::fabs(refValue - check.numbers[o].value) / std::max(std::fabs(check.numbers[o].value), 1e-300);
    r.references.push_back(rf);
    for (const Steady& steady : steadies)
    for (cat::Method method : methods) {
      if (steady.balance && method != methods.front()) continue; // no integrator: one curve
      WorkPrecisionStudy::Curve curve{
          h, steady.balance ? "harmonic_balance" : std::string(cat::methodSpec(method).name), steady.name, {}};
      for (double rtol : rtols) {
        auto ov = steadyOv(base, steady);
        ov.method = method;
        ov.rtol = rtol;
        auto run = dyn::runScene(m, design, scene, ov);
        tick(1);
        WorkPrecisionStudy::Run w;
        w.rtol = rtol;
        // A balance that fell back to shooting is no point of its curve.
        if (run.failure.empty() && o < run.numbers.size() && std::isfinite(run.numbers[o].value) &&
            (!steady.balance || run.balanceHarmonics > 0)) {
          w.ok = true;
          w.error = std::fabs(run.numbers[o].value - refValue) / std::max(std::fabs(refValue), 1e-300);
          w.steps = run.stats.steps;
          w.rhsEvaluations = run.stats.rhsEvaluations;
          w.cpuSeconds = run.stats.cpuSeconds;
        }
        curve.runs.push_back(w);
      }
      r.curves.push_back(std::move(curve));
    }
  }
  return r;
}

} // namespace gbx::rt
