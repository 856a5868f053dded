#include "dynamics/SteadyOrbit.h"

#include <cmath>

#include <fmt/format.h>

#include "dynamics/Periodic.h"
#include "dynamics/SceneBalance.h"

namespace gbx::rt::dyn {

namespace {

void describeOrbit(SceneResult& r, double Tz);

// The orbit by harmonic balance (`steady_state = harmonic_balance`): with the scene's
// harmonics, or doubled from 2 until the orbit moves less than rtol of its scale. False, with
// a model line saying why, where it is not found (shooting then takes over).
bool balanceOrbit(const MeshModel& model, const ScenePlan& scene, const SceneOverrides& ov, const Accuracy& acc,
                  double T, double Tz, SceneResult& r, std::vector<double>& y, std::optional<BalanceOrbit>& out) {
  BalanceOptions bo;
  bo.period = T;
  bo.linear = model.linear();
  bo.floquet = acc;
  SceneBalance b = sceneBalance(model.system(), bo, scene, ov, acc.rtol, y, 1024, std::lround(T / Tz));
  r.stats += b.stats;
  r.model.push_back(b.line);
  if (!b.warning.empty()) r.warnings.push_back(b.warning);
  if (!b.orbit) return false;
  const BalanceOrbit& o = *b.orbit;
  y = o.state(0);
  r.orbit = y;
  r.period = T;
  r.stability = o.stability;
  r.unstable = o.stability >= 1.0;
  r.newtonIterations = o.iterations;
  r.newtonResidual = o.gapResidual;
  r.balanceHarmonics = o.harmonics;
  r.balanceTruncation = o.truncation;
  r.orbitMethod = fmt::format("harmonic balance with {} harmonics at {} instants", o.harmonics, o.timePoints);
  r.method = "harmonic_balance";
  r.stepRule = fmt::format("{} harmonics at {} instants{}", o.harmonics, o.timePoints,
                           b.chosen ? " (doubled from 2 until the orbit moves less than rtol of its scale)" : "");
  out = std::move(b.orbit);
  return true;
}

// A shooting orbit of period T, as the scene reports it.
void takeShot(const PeriodicOrbit& orbit, double T, SceneResult& r) {
  r.orbit = orbit.y0;
  r.period = T;
  r.stability = orbit.stability;
  r.unstable = orbit.stability >= 1.0;
  r.newtonIterations = orbit.iterations;
  r.newtonResidual = orbit.residual;
}

// Shooting in fixed steps that land on the samples (a smooth model): false where it does not
// serve (too many steps per sample, or Newton fails), and adaptive shooting then follows.
bool fixedOrbit(const MeshModel& model, const PeriodicOptions& po, const Accuracy& acc, const SceneOverrides& ov,
                const TimePlan& tp, double Tz, const std::vector<double>& guess, SceneResult& r,
                std::optional<SampledOrbit>& sampled) {
  SampledOrbit so = sampledOrbit(model.system(), acc, po, guess, tp.dt, ov.stepsPerSample);
  r.stats += so.orbit.stats;
  if (!so.orbit.converged) return false;
  takeShot(so.orbit, po.period, r);
  r.stepsPerSample = so.stepsPerSample;
  r.orbitMethod = fmt::format("{} by variational equations in fixed steps, {} per sample",
                              po.linear ? "linear: the monodromy matrix" : "shooting with Newton", so.stepsPerSample);
  r.stepRule = fmt::format("fixed steps of {:.4g} ms, {} per sample (each step's error within rtol)",
                           tp.dt / so.stepsPerSample * 1e3, so.stepsPerSample);
  describeOrbit(r, Tz);
  sampled = std::move(so);
  return true;
}

} // namespace

// The periodic orbit of a single-mesh scene, from the model's initial state or the caller's
// guess; false (with r.failure) where it is not found.
bool steadyOrbit(const MeshModel& model, const MeshScene& ms, TimePlan& tp, const ScenePlan& scene,
                 const SceneOverrides& ov, const Accuracy& acc, SceneResult& r, std::vector<double>& y,
                 std::optional<BalanceOrbit>& balance, std::optional<SampledOrbit>& sampled) {
  double Tz = 1.0 / ms.meshFrequency, T = model.excitationPeriod();
  if (T <= 0)
    throw SceneFailure{fmt::format(
        "the excitation is not periodic (a start-up ramp, or a fluctuation whose period holds no whole number of "
        "mesh periods), so there is no periodic steady state{}; write `settle = N mesh_periods` to settle a "
        "transient, or `duration` for a run from rest",
        tp.periodicWritten ? "" : " (the default when a scene neither settles nor runs from rest)")};
  if (ov.harmonicBalance.value_or(scene.harmonicBalance) && balanceOrbit(model, scene, ov, acc, T, Tz, r, y, balance)) {
    if (widenToPeriod(tp, T))
      r.model.push_back(
          fmt::format("record window widened to the orbit's period, {} mesh periods", std::lround(T / Tz)));
    return true;
  }
  PeriodicOptions po;
  po.period = T;
  po.linear = model.linear();
  po.confirmLinear = false; // the record run below integrates the period and measures the residual
  std::vector<double> guess = ov.guess && ov.guess->size() == y.size() ? *ov.guess : y;
  if (widenToPeriod(tp, T))
    r.model.push_back(fmt::format("record window widened to the orbit's period, {} mesh periods", std::lround(T / Tz)));
  if (!ov.adaptiveShooting && fixedStepsServe(model.system(), acc) &&
      fixedOrbit(model, po, acc, ov, tp, Tz, guess, r, sampled)) {
    y = r.orbit;
    return true;
  }
  PeriodicOrbit orbit = periodicOrbit(model.system(), acc, po, guess);
  r.stats += orbit.stats;
  if (!orbit.converged) {
    r.failure = fmt::format("scene `{}`: the periodic steady state was not found: {}", scene.name, orbit.failure);
    return false;
  }
  y = orbit.y0;
  takeShot(orbit, T, r);
  r.orbitMethod = fmt::format("{} by {}", po.linear ? "linear: the monodromy matrix" : "shooting with Newton",
                              orbit.variational ? "variational equations" : "differences");
  r.orbitUnconfirmed = orbit.unconfirmed;
  if (!orbit.unconfirmed) describeOrbit(r, Tz);
  return true;
}

namespace {

// The orbit's line in the model, once its residual is known.
void describeOrbit(SceneResult& r, double Tz) {
  double T = r.period;
  r.model.push_back(
      fmt::format("periodic steady state: period {:.6g} ms ({} mesh period{}), {}, {} Newton iteration{}, residual "
                  "{:.2e} of the state scale{}, largest Floquet multiplier {:.6f}",
                  T * 1e3, std::lround(T / Tz), std::lround(T / Tz) == 1 ? "" : "s", r.orbitMethod, r.newtonIterations,
                  r.newtonIterations == 1 ? "" : "s", r.newtonResidual,
                  r.orbitUnconfirmed ? " (one period of the record run from the orbit's start)" : "", r.stability));
}

} // namespace

// A linear orbit found in one Newton step: the record run, carried on to the end of the
// orbit's first period (or read there), comes back to its start to within the residual.
// Where the run is past that end without a sample on it, or cannot be carried on, a period
// from the orbit's start on its own. The failure, or "".
std::string confirmOrbit(Integrator& integ, double t, std::vector<double> y, const std::vector<double>* atPeriod,
                         const System& sys, const Accuracy& acc, SceneResult& r, double Tz) {
  if (!r.orbitUnconfirmed) return "";
  auto none = [](double, const double*) {};
  if (atPeriod) {
    y = *atPeriod;
  } else if (!(t < r.period && integ.advance(t, y, r.period, {}, none))) {
    Integrator fresh(sys, acc);
    double t0 = 0;
    y = r.orbit;
    bool ok = fresh.advance(t0, y, r.period, {}, none);
    r.stats += fresh.stats();
    if (!ok) return "confirming the periodic orbit over its period: " + fresh.error();
  }
  std::vector<double> d(y.size());
  for (size_t i = 0; i < d.size(); ++i)
    d[i] = y[i] - r.orbit[i];
  r.newtonResidual = scaledNorm(d, sys.scale);
  describeOrbit(r, Tz);
  return "";
}

// `settle = N` integrates exactly N periods; whether the transient has died out there is
// measured: one more excitation period from the settled state must come back to it.
void checkSettled(const MeshModel& model, const TimePlan& tp, const Accuracy& acc, SceneResult& r) {
  if (tp.steady == SteadyMethod::Settle && r.orbit.size() == model.system().dim) {
    double T = model.excitationPeriod();
    if (T > 0) {
      Integrator check(model.system(), acc);
      std::vector<double> y1 = r.orbit;
      double t0 = tp.statsFrom; // the settled state's own time: the excitation's phase there
      if (check.advance(t0, y1, tp.statsFrom + T, {}, [](double, const double*) {})) {
        std::vector<double> d(y1.size());
        for (size_t i = 0; i < d.size(); ++i)
          d[i] = y1[i] - r.orbit[i];
        double settleResidual = scaledNorm(d, model.system().scale);
        r.stats += check.stats();
        if (settleResidual > std::max(1e-6, 1e3 * acc.rtol))
          r.warnings.push_back(
              fmt::format("the transient has not died out after the settled periods: one more period moves the state "
                          "by {:.2e} of its scale; settle longer, or write `steady_state = periodic`",
                          settleResidual));
      }
    }
  }
}

} // namespace gbx::rt::dyn
