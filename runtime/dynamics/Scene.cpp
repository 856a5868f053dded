#include "dynamics/Scene.h"


#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "catalogue/Budgets.h"
#include "catalogue/StageKinds.h"
#include "dynamics/Effects.h"
#include "dynamics/Gearbox.h"
#include "dynamics/HarmonicBalance.h"
#include "dynamics/Levels.h"
#include "dynamics/LoadedMesh.h"
#include "dynamics/LoadedMeshInputs.h"
#include "dynamics/Lumped.h"
#include "dynamics/MeshModel.h"
#include "dynamics/OrderOutputs.h"
#include "dynamics/Periodic.h"
#include "dynamics/Planetary.h"
#include "dynamics/SceneSupport.h"
#include "dynamics/Statistics.h"
#include "dynamics/SteadyOrbit.h"
#include "model/Deadline.h"
#include "model/StageKind.h"
#include "model/Standards.h"

namespace gbx::rt::dyn {

const SceneNumber* SceneResult::find(const std::string& key) const {
  for (const auto& n : numbers)
    if (n.key == key) return &n;
  return nullptr;
}

const SceneNumber* SceneResult::find(const ir::SceneOutputRef& ref) const {
  if (!ref.bare) return find(ref.fn, ref.signal, ref.order);
  for (const auto& n : numbers)
    if (n.signal == ref.signal) return &n;
  // Every periodic scene has a stability, listed or not.
  if (ref.signal == cat::Signal::Stability && steady == SteadyMethod::Periodic && std::isfinite(stability)) return &stabilityNumber;
  return nullptr;
}

const SceneNumber* SceneResult::find(cat::SignalFn fn, cat::Signal signal, int order) const {
  // A single result (`dynamic_factor`) is written bare: its signal names it, whatever
  // function a reference carries.
  const bool single = cat::signalSpec(signal).scalar;
  for (const auto& n : numbers)
    if (n.signal == signal && (single || (n.fn == fn && n.order == order))) return &n;
  return nullptr;
}

namespace {

using units::Dim;
namespace dims = units::dims;

using Failure = SceneFailure;

double num(const Value& v, const std::string& what) { return needNumber(v, what); }

using cat::Signal;

// Mass moment of inertia: given, or a solid cylinder of the pitch diameter and face width.
double inertiaOf(const Evaluator& ev, int st, const Assignment& a, int g, double density, std::vector<std::string>& prov) {
  const std::string& gear = ev.model().info(st).ir->gears[static_cast<size_t>(g)];
  Value given = ev.attribute(st, g, Q::Inertia, a);
  if (given.isNumber()) {
    prov.push_back(fmt::format("{} inertia {:.6g} kg*m^2 (given)", gear, given.lo));
    return given.lo;
  }
  double d = num(ev.derived(st, g, Q::D, a), gear + " pitch diameter");
  double b = num(ev.attribute(st, Q::FaceWidth, a), "`face_width` (or the gears' `inertia`)");
  double r = 0.5 * d;
  double J = 0.5 * density * M_PI * b * r * r * r * r;
  prov.push_back(fmt::format("{} inertia {:.6g} kg*m^2 (solid cylinder, d = {:.1f} mm, b = {:.1f} mm)", gear, J, d * 1e3, b * 1e3));
  return J;
}


struct Samples {
  std::vector<double> t;
  SignalSeries signals;
  double staticLoad = NAN;    // the mean mesh force
  // The largest quasi-static mesh force: the static load, or with a fluctuating load torque
  // its mean plus its amplitude. The dynamic factor is the peak mesh force over it, so that a
  // fluctuation the application factor K_A covers is not counted again in K_v.
  double quasiStaticPeak = NAN;
  std::vector<double> modes;  // natural frequencies of a lumped model, Hz
  // The loaded mesh's static transmission error as tabulated, over its periods (one, or the
  // hunting period), and whether the scene's outputs read nothing else.
  std::vector<double> staticTable, staticStiffness;
  int staticPeriods = 1;
  bool staticOnly = false;
  // The table an output of signal s reads in place of a recorded window: the static
  // transmission error's over the hunting period or without dynamics, the stiffness's without
  // dynamics; nullptr for a recorded window.
  const std::vector<double>* table(Signal s) const {
    if (s == Signal::StaticTransmissionError && !staticTable.empty() && (staticOnly || staticPeriods > 1))
      return &staticTable;
    if (s == Signal::Stiffness && staticOnly && !staticStiffness.empty()) return &staticStiffness;
    return nullptr;
  }
  // The table an order of signal s reads: the static transmission error's always (its recorded
  // series holds only the harmonics the dynamics read), else as `table`.
  OrderSource orderTable(Signal s) const {
    if (s == Signal::StaticTransmissionError && !staticTable.empty()) return {&staticTable, staticPeriods};
    return {table(s), staticPeriods};
  }
};

// Every output reads the loaded mesh's tables (its static transmission error, its stiffness):
// the dynamics are not run.
bool readsOnlyTheTable(const ScenePlan& scene) {
  return scene.fx.loaded && !scene.outputs.empty() &&
         std::all_of(scene.outputs.begin(), scene.outputs.end(), [](const ir::SceneOutput& o) {
           return o.id == Signal::StaticTransmissionError || o.id == Signal::Stiffness;
         });
}

// The scene's `accuracy { … }` with a study's overrides.
Accuracy sceneAccuracy(const ScenePlan& scene, const SceneOverrides& ov) {
  Accuracy acc;
  acc.method = scene.method;
  if (scene.rtol) acc.rtol = *scene.rtol;
  if (scene.atol) acc.atol = *scene.atol;
  if (scene.maxSteps) acc.maxSteps = *scene.maxSteps;
  if (ov.method) acc.method = *ov.method;
  if (ov.rtol) acc.rtol = *ov.rtol;
  return acc;
}

// A table over several periods as its mean period, position by position.
std::vector<double> foldedPeriod(const std::vector<double>& table, int periods) {
  size_t P = table.size() / static_cast<size_t>(periods);
  std::vector<double> out(P, 0.0);
  for (size_t i = 0; i < table.size(); ++i)
    out[i % P] += table[i] / periods;
  return out;
}

// The loaded mesh's tables over one mesh period (dynamics/LoadedMesh.h) as the series the
// right-hand side reads; the mean mesh stiffness becomes the tables' mean.
void loadMesh(const Evaluator& ev, const Assignment& a, int st, MeshParameters& p, MeshEffects& fx, std::vector<std::string>& prov) {
  if (fx.hertz) throw Failure{"`loaded_mesh` gives the mesh its stiffness and `hertz_contact` describes it again: list one"};
  LoadedMeshInput in = loadedMeshInput(ev, a, st, p.staticLoad, fx.slices, fx.positions, prov);
  in.cornerContact = fx.loadedCorner;
  ToothErrors errors;
  errors.seed = fx.pitchSeed;
  for (int g = 0; g < 2; ++g)
    errors.listed[g] = fx.pitchListed[g];
  toothErrors(ev, a, st, errors, in, prov);
  LoadedMeshTable tab = loadedMesh(in);
  if (!tab.failure.empty()) throw Failure{"the loaded mesh: " + tab.failure};
  fx.loadedTable = tab.te;
  fx.loadedStiffnessTable = tab.stiffness;
  fx.loadedPeriods = tab.periods;
  if (in.cornerContact)
    prov.push_back(
        tab.cornerPositions > 0
            ? fmt::format(
                  "loaded mesh: contact outside the path at {} of {} positions, a tip corner carrying up to {:.3g} % "
                  "of the load",
                  tab.cornerPositions, tab.te.size(), 100 * tab.cornerShare)
            : std::string("loaded mesh: no tip corner touches outside the path at this load"));
  // Over the hunting period the dynamics read the mean mesh period (every tooth pair's average).
  if (tab.periods > 1) {
    tab.te = foldedPeriod(tab.te, tab.periods);
    tab.stiffness = foldedPeriod(tab.stiffness, tab.periods);
    prov.push_back(
        fmt::format("loaded mesh: the dynamics read the mean of the {} mesh periods; the static transmission error's "
                    "outputs read all of them",
                    tab.periods));
  }
  std::vector<double> u(tab.te.size());
  for (size_t i = 0; i < u.size(); ++i) u[i] = tab.te[i] - p.staticLoad / tab.stiffness[i];
  int H = fx.loadedHarmonics;
  fx.loadedStiffness = periodicSeries(tab.stiffness, H);
  fx.loadedTe = periodicSeries(tab.te, H);
  fx.loadedSeparation = periodicSeries(u, H);
  double b = in.g.faceWidth;
  // The dynamics reads the tables through H harmonics: their swing is what the scene's
  // `static_transmission_error` signal shows, the table's jumps smoothed.
  double sLo = INFINITY, sHi = -INFINITY;
  for (size_t i = 0; i < tab.te.size(); ++i) {
    double v = fx.loadedTe(static_cast<double>(i) / static_cast<double>(tab.te.size()));
    sLo = std::min(sLo, v);
    sHi = std::max(sHi, v);
  }
  prov.push_back(fmt::format("loaded mesh: the {} harmonics the dynamics reads swing the static transmission error by {:.4g} um", H,
                             (sHi - sLo) * 1e6));
  prov.push_back(fmt::format("loaded mesh: static transmission error {:.4g} um mean, {:.4g} um peak to peak (the table); mesh stiffness {:.4g} "
                             "N/(mm*um) per face width mean ({:.4g} with every pair in contact), {:.4g} to {:.4g}, its mean in place of "
                             "the mean mesh stiffness above; {} harmonics of the tables; eps_alpha {:.4f}, eps_beta {:.4f}",
                             tab.meanTe * 1e6, tab.peakToPeakTe * 1e6, tab.meanStiffness / b * 1e-9, tab.lightLoadStiffness / b * 1e-9,
                             *std::min_element(tab.stiffness.begin(), tab.stiffness.end()) / b * 1e-9,
                             *std::max_element(tab.stiffness.begin(), tab.stiffness.end()) / b * 1e-9, H, tab.epsAlpha, tab.epsBeta));
  p.meanStiffness = tab.meanStiffness;
}

MeshScene meshSceneOf(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov, Accuracy acc,
                      std::vector<std::string>& prov) {
  Evaluator ev = ov.evaluator ? *ov.evaluator : Evaluator(m);
  int st = scene.stage;
  const ir::Stage& stage = *m.stages[static_cast<size_t>(st)].ir;
  using cat::gear::Pinion;
  using cat::gear::Wheel;
  double upstream = num(ev.ratioProduct(0, st, a), "the ratios upstream");
  double downstream = num(ev.ratioProduct(st + 1, static_cast<int>(m.stages.size()), a), "the ratios downstream");
  double speed = num(ev.derived(st, Q::InputSpeed, a), "an input speed (`operating`)");
  Elastic mat = materialOf(m, st);
  MeshParameters p;
  double rb1 = num(ev.derived(st, Pinion, Q::BaseRadius, a), "the pinion base radius (`normal_module`)");
  double rb2 = num(ev.derived(st, Wheel, Q::BaseRadius, a), "the wheel base radius");
  double b = num(ev.attribute(st, Q::FaceWidth, a), "`face_width`");
  double J1 = inertiaOf(ev, st, a, Pinion, mat.density, prov), J2 = inertiaOf(ev, st, a, Wheel, mat.density, prov);
  if (mat.assumed) prov.push_back("density 7850 kg/m^3, E = 206 GPa, nu = 0.3 (steel assumed: no material given)");
  p.mass = J1 * J2 / (J2 * rb1 * rb1 + J1 * rb2 * rb2);
  prov.push_back(fmt::format("equivalent mass {:.6g} kg = J1 J2 / (J2 rb1^2 + J1 rb2^2)", p.mass));
  p.epsAlpha = num(ev.derived(st, Q::EpsAlpha, a), "the transverse contact ratio");
  p.epsBeta = stage.kind == ir::StageKind::Helical ? num(ev.derived(st, Q::EpsBeta, a), "the overlap ratio") : 0.0;
  // Given when the stage sets it; the evaluator would otherwise supply ISO 6336's value.
  Value cg = m.attribute(st, Q::MeshStiffness) ? ev.attribute(st, Q::MeshStiffness, a) : Value::invalid();
  if (cg.isNumber()) {
    p.meanStiffness = cg.lo * b;
    prov.push_back(fmt::format("mean mesh stiffness {:.6g} N/m = c_gamma {:.4g} N/(mm*um) x b (given)", p.meanStiffness, cg.lo * 1e-9));
  } else {
    double beta = stage.kind == ir::StageKind::Helical ? num(ev.attribute(st, Q::HelixAngle, a), "the helix angle") : 0.0;
    Value x1 = ev.attribute(st, Pinion, Q::Shift, a), x2 = ev.attribute(st, Wheel, Q::Shift, a);
    double cgam = iso::meshStiffness(num(ev.attribute(st, Pinion, Q::Z, a), "pinion.z"), num(ev.attribute(st, Wheel, Q::Z, a), "wheel.z"),
                                   x1.isNumber() ? x1.mid() : 0.0, x2.isNumber() ? x2.mid() : 0.0, beta, p.epsAlpha);
    p.meanStiffness = cgam * b;
    prov.push_back(fmt::format("mean mesh stiffness {:.6g} N/m = c_gamma {:.4g} N/(mm*um) x b (ISO 6336-1 method B, eps_alpha {:.4f})",
                               p.meanStiffness, cgam * 1e-9, p.epsAlpha));
  }
  double torque = num(ev.derived(st, Q::InputTorque, a), "an input torque (`operating`)");
  p.staticLoad = torque / rb1;
  prov.push_back(fmt::format("static load {:.6g} N = T1 / rb1; eps_alpha {:.4f}, eps_beta {:.4f}", p.staticLoad, p.epsAlpha, p.epsBeta));
  p.teethDriver = num(ev.attribute(st, Pinion, Q::Z, a), "pinion.z");
  p.outputRadius = rb2;
  p.ratio = num(ev.derived(st, Q::Ratio, a), "the stage ratio");
  p.downstream = downstream;
  double Tz = 2.0 * M_PI / (speed * p.teethDriver);
  p.drive = sceneDrive(scene, speed, upstream, Tz);
  // Hertz stiffness K = 4/3 sqrt(R) E* at the pitch point.
  double alphaW = num(ev.derived(st, Q::WorkingPressureAngle, a), "the working pressure angle");
  double rho1 = rb1 * std::tan(alphaW), rho2 = rb2 * std::tan(alphaW);
  double R = 1.0 / (1.0 / rho1 + 1.0 / rho2);
  double Estar = mat.E / (2.0 * (1.0 - mat.nu * mat.nu));
  p.hertzStiffness = 4.0 / 3.0 * std::sqrt(R) * Estar;
  p.hertzRadius = R;

  // Each listed effect adds its own terms; what the scene does not list is never built.
  MeshEffects fx;
  for (const auto& e : scene.listed)
    if (const EffectRow* row = effectRow(e.kind); row && row->mesh) row->mesh(scene.fx, ov, p, fx, prov);
  if (fx.loadedMesh) loadMesh(ev, a, st, p, fx, prov);
  MeshModel model(p, fx);
  if (fx.damping) prov.push_back(fmt::format("damping coefficient {:.6g} N*s/m", model.dampingCoefficient()));
  prov.push_back(fmt::format("mesh frequency {:.4f} Hz, natural frequency {:.4f} Hz", 1.0 / Tz, 1.0 / model.naturalPeriod()));
  // Steps of a smooth model: at most one period of the highest stiffness harmonic, so that
  // no step spans a whole period of its forcing, where an error estimate could miss it;
  // below that the tolerance alone decides (a quarter of it fixed the cost, and the error,
  // of every looser tolerance). With contact (backlash, Hertz) the right-hand side has
  // kinks the error estimate does not see: a quarter of it, and a twentieth of the natural
  // period, a contact's time scale.
  const bool contact = fx.backlash || fx.hertz;
  int harmonics = fx.varyingStiffness ? std::max(1, fx.harmonics) : fx.loadedMesh ? std::max(1, fx.loadedHarmonics) : 1;
  const int per = contact ? 4 : 1;
  acc.maxStep = Tz / (per * harmonics);
  std::string rule = contact ? "Tz/4" : "Tz";
  if (fx.varyingStiffness || fx.loadedMesh)
    rule = contact ? fmt::format("Tz/(4 x {} harmonics)", harmonics) : fmt::format("Tz/{} harmonics", harmonics);
  if (contact && model.naturalPeriod() / 20.0 < acc.maxStep) {
    acc.maxStep = model.naturalPeriod() / 20.0;
    rule = "Tn/20 (natural period, a contact's time scale)";
  }
  if (auto given = scene.maxStep.at(Tz)) {
    acc.maxStep = *given;
    rule = "given";
  }
  if (ov.maxStepFactor) {
    acc.maxStep *= *ov.maxStepFactor;
    rule += fmt::format(" x {:g}", *ov.maxStepFactor);
  }
  if (auto given = scene.minStep.at(Tz)) acc.minStep = *given;
  MeshScene out;
  out.params = p;
  out.effects = fx;
  out.accuracy = acc;
  out.plan = ov.forcePeriodic ? periodicPlan(scene, Tz) : timePlan(scene, Tz, ov.settlePeriods);
  out.meshFrequency = 1.0 / Tz;
  out.provenance = prov;
  out.stepRule = fmt::format("max step {} = {:.4g} ms", rule, acc.maxStep * 1e3);
  out.harmonics = fx.varyingStiffness ? fx.harmonics : fx.loadedMesh ? fx.loadedHarmonics : 0;
  return out;
}

// An output series (`plot`, `spectrum`) over the statistics window from sample `first`;
// a spectrum names its peaks as harmonics of the mesh frequency fz.
SceneSeries recorded(const ir::SceneOutput& o, Dim dim, const std::vector<double>& t, size_t first, std::vector<double> v, double dt,
                     double fz) {
  SceneSeries s;
  s.key = o.key();
  s.signal = o.mesh.empty() ? o.signal : o.signal + "(" + o.mesh + ")";
  s.dim = dim;
  s.t.assign(t.begin() + static_cast<long>(std::min(first, t.size())), t.end());
  s.v = std::move(v);
  if (o.fn == cat::SignalFn::Spectrum) {
    s.isSpectrum = true;
    s.spectrum = spectrum(s.v, dt, fz);
    s.meshFrequency = fz;
  }
  return s;
}

// A planetary or whole-gearbox run's periodic orbit, as the scene reports it.
template <class Run> void takeOrbit(const Run& run, SceneResult& r) {
  r.stability = run.stability;
  r.unstable = run.failure.empty() && run.stability >= 1.0;
  r.newtonIterations = run.newtonIterations;
  r.newtonResidual = run.newtonResidual;
  r.balanceHarmonics = run.balanceHarmonics;
  if (run.balanceHarmonics > 0) r.method = "harmonic_balance";
  r.period = run.period;
  r.orbit = run.orbit;
}

// A whole-gearbox scene in time (docs/dynamics.md): the outputs of its meshes by name.
SceneResult runWholeGearbox(const Model& m, const Evaluator& ev, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov,
                            SceneResult r) {
  Accuracy acc = sceneAccuracy(scene, ov);
  r.method = std::string(cat::methodSpec(acc.method).name);
  r.rtol = acc.rtol;
  r.atol = acc.atol > 0 ? acc.atol : acc.rtol;
  GearboxRun g = runGearbox(m, ev, a, scene, acc, ov);
  r.model = g.provenance;
  r.stats = g.stats;
  r.stepRule = g.stepRule;
  r.harmonics = g.harmonics;
  r.meshFrequency = g.meshFrequency;
  r.steady = g.plan.steady;
  if (!g.failure.empty()) {
    r.failure = fmt::format("scene `{}`: {}", scene.name, g.failure);
    return r;
  }
  if (g.periodic) takeOrbit(g, r);
  r.gearbox.members = g.members;
  r.gearbox.kinematic = g.kinematic;
  r.gearbox.driveWork = g.driveWork;
  r.gearbox.loadWork = g.loadWork;
  r.gearbox.dissipated = g.dissipated;
  r.gearbox.energyGained = g.energyGained;
  size_t first = static_cast<size_t>(std::lower_bound(g.t.begin(), g.t.end(), g.plan.statsFrom - 1e-12) - g.t.begin());
  auto window = [&](const std::vector<double>& v) { return std::vector<double>(v.begin() + static_cast<long>(std::min(first, v.size())), v.end()); };
  for (const auto& o : scene.outputs) {
    Dim dim = cat::signalSpec(o.id).dim;
    if (o.id == Signal::Modes) {
      for (size_t i = 0; i < g.modes.size(); ++i) r.numbers.push_back({fmt::format("mode {}", i + 1), g.modes[i], units::dims::frequency});
      continue;
    }
    const std::vector<double>* v = nullptr;
    double fz = g.meshFrequency;
    if (o.id == Signal::InputSpeed) v = &g.inputSpeed;
    else if (o.id == Signal::OutputSpeed) v = &g.outputSpeed;
    else
      for (const auto& ms : g.meshes)
        if (ms.name == o.mesh) {
          v = o.id == Signal::ContactForce ? &ms.contactForce : &ms.meshForce;
          fz = ms.meshFrequency;
        }
    if (!v) throw Failure{fmt::format("`{}` is not an output of the whole-gearbox model", o.key())};
    std::vector<double> w = window(*v);
    if (!cat::signalFnSpec(o.fn).number) {
      if (!ov.keepSeries) continue;
      r.series.push_back(recorded(o, dim, g.t, first, std::move(w), g.plan.dt, fz));
      continue;
    }
    if (cat::signalFnSpec(o.fn).order != cat::OrderArg::None) {
      r.numbers.push_back(orderNumber(o, {nullptr, 1}, w, g.plan.dt, fz));
      continue;
    }
    r.numbers.push_back({o.key(), w.empty() ? NAN : statistic(o.fn)(w), dim, o.fn, o.id, w.empty() ? 0.0 : statistic(cat::SignalFn::Rms)(w)});
  }
  return r;
}

// The whole gearbox's lumped torsional model, for its modes.
SceneResult wholeGearboxModes(const Model& m, const Assignment& a, SceneResult r) {
  // The whole gearbox: its lumped torsional model, for its modes.
  LumpedModes lm = gearboxModes(m, a);
  r.model = lm.provenance;
  for (size_t i = 0; i < lm.frequencies.size(); ++i) {
    r.numbers.push_back({fmt::format("mode {}", i + 1), lm.frequencies[i], units::dims::frequency});
    r.model.push_back(fmt::format("mode {}: {:.2f} Hz, moving {}", i + 1, lm.frequencies[i], lm.shapes[i]));
  }
  r.eigen = true;
  r.method = "eigen";
  return r;
}

// A scene on a spur or helical stage: its mesh model run, the signals recorded; the failure,
// or "".
std::string runSingleMesh(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov, Accuracy& acc,
                          SceneResult& r, Samples& samples, TimePlan& tp) {
  auto record = [&](Signal k, double v) { series(samples.signals, k).push_back(v); };
  double cpu0 = threadCpuSeconds();
  MeshScene ms = meshSceneOf(m, a, scene, ov, acc, r.model);
  MeshModel model(ms.params, ms.effects);
  const MeshParameters& p = ms.params;
  acc = ms.accuracy;
  tp = ms.plan;
  r.meshFrequency = ms.meshFrequency;
  r.stepRule = ms.stepRule;
  r.harmonics = ms.harmonics;
  r.naturalFrequency = 1.0 / model.naturalPeriod();
  r.steady = tp.steady;
  samples.staticTable = ms.effects.loadedTable;
  samples.staticStiffness = ms.effects.loadedStiffnessTable;
  samples.staticPeriods = ms.effects.loadedPeriods;
  samples.staticLoad = p.staticLoad;
  if (readsOnlyTheTable(scene)) {
    // Its cost is the table's (a table kept from an identical input costs nothing again).
    r.stats.cpuSeconds += threadCpuSeconds() - cpu0;
    samples.staticOnly = true;
    r.steady = SteadyMethod::Static;
    r.model.push_back("the outputs read only the loaded mesh's table: the dynamics are not run");
    return "";
  }
  std::vector<double> y = model.initialState();
  // A transient may start from a given state (a study's run from another initial condition).
  if (tp.steady != SteadyMethod::Periodic && ov.guess && ov.guess->size() == y.size()) y = *ov.guess;
  std::optional<BalanceOrbit> balance;
  std::optional<SampledOrbit> sampled;
  if (tp.steady == SteadyMethod::Periodic && !steadyOrbit(model, ms, tp, scene, ov, acc, r, y, balance, sampled))
    return "";
  std::vector<double> atPeriod;  // the state a whole orbit period on, where the record window reaches it
  auto take = [&](double ts, const double* ys) {
    if (r.orbitUnconfirmed && atPeriod.empty() && std::fabs(ts - r.period) <= 1e-9 * r.period)
      atPeriod.assign(ys, ys + y.size());
    MeshSignals s = model.signals(ts, ys);
    // A settled run's first sample lies on its orbit at phase 0 (a whole number of periods).
    if (samples.t.empty() && tp.steady == SteadyMethod::Settle) r.orbit.assign(ys, ys + model.system().dim);
    samples.t.push_back(ts);
    record(Signal::Displacement, s.displacement);
    record(Signal::Velocity, s.velocity);
    record(Signal::Acceleration, s.acceleration);
    record(Signal::MeshForce, s.meshForce);
    record(Signal::ContactForce, s.contactForce);
    record(Signal::Stiffness, s.stiffness);
    record(Signal::TransmissionError, s.transmissionError);
    record(Signal::StaticTransmissionError, s.staticTransmissionError);
    record(Signal::InputSpeed, s.inputSpeed);
    record(Signal::OutputSpeed, s.outputSpeed);
  };
  if (balance) { // the samples from the series: nothing is integrated
    double cpu = threadCpuSeconds();
    for (double ts : tp.samples) {
      balance->state(ts, y.data());
      take(ts, y.data());
    }
    r.stats.cpuSeconds += threadCpuSeconds() - cpu;
  }
  if (sampled) // the samples the fixed steps landed on: nothing is integrated again
    for (double ts : tp.samples)
      take(ts, sampled->at(ts).data());
  samples.staticLoad = p.staticLoad;
  const MeshEffects& fx = ms.effects;
  samples.quasiStaticPeak = fx.torqueFluctuation ? (std::fabs(fx.torqueMean) + std::fabs(fx.torqueAmplitude)) / std::fabs(p.outputRadius * p.downstream)
                                                 : p.staticLoad;
  if (balance || sampled) return "";
  Integrator integ(model.system(), acc);
  double t = 0;
  bool ok = integ.advance(t, y, tp.end, tp.samples, take);
  std::string confirmFailure;
  if (ok)
    confirmFailure = confirmOrbit(integ, t, y, atPeriod.empty() ? nullptr : &atPeriod, model.system(), acc, r,
                                  1.0 / ms.meshFrequency);
  r.stats += integ.stats();
  if (!ok) return integ.error();
  if (!confirmFailure.empty()) return confirmFailure;
  checkSettled(model, tp, acc, r);
  return "";
}

// A scene on a planetary stage; the failure, or "".
std::string runPlanetaryScene(const Model& m, const Evaluator& ev, const Assignment& a, int st, const ScenePlan& scene,
                              const SceneOverrides& ov, const Accuracy& acc, SceneResult& r, Samples& samples, TimePlan& tp) {
  double upstream = num(ev.ratioProduct(0, st, a), "the ratios upstream");
  double downstream = num(ev.ratioProduct(st + 1, static_cast<int>(m.stages.size()), a), "the ratios downstream");
  double speed = num(ev.derived(st, Q::InputSpeed, a), "an input speed (`operating`)");
  Elastic mat = materialOf(m, st);
  bool periodic = ov.forcePeriodic || scene.steady(ov.settlePeriods) == SteadyMethod::Periodic;
  PlanetaryRun pr = runPlanetary(ev, a, st, scene, acc, ov, upstream, downstream, speed, mat.E, mat.nu, mat.density,
                                 mat.assumed, periodic);
  r.model = pr.provenance;
  r.warnings.insert(r.warnings.end(), pr.warnings.begin(), pr.warnings.end());
  r.stats = pr.stats;
  r.harmonics = pr.harmonics;
  r.stepRule = pr.stepRule;
  if (periodic) {
    r.steady = SteadyMethod::Periodic;
    takeOrbit(pr, r);
  } else {
    r.steady = pr.plan.steady;
  }
  r.meshFrequency = pr.meshFrequency;
  tp = pr.plan;
  samples.t = pr.t;
  samples.signals = pr.signals;
  samples.staticLoad = pr.staticLoad;
  samples.quasiStaticPeak = pr.staticLoad;
  samples.modes = pr.modes;
  return pr.failure;
}

// What the run says about itself: an unstable orbit, a linear mesh in tension.
void runWarnings(const ScenePlan& scene, const SceneOverrides& ov, const Samples& samples, SceneResult& r) {
  r.stabilityNumber = {"stability", r.stability, {}, cat::SignalFn::Max, Signal::Stability};
  if (r.unstable && !ov.keepUnstable)
    r.warnings.push_back(fmt::format("scene `{}` has no steady response: its periodic solution is unstable (largest Floquet multiplier "
                                     "{:.6f} > 1; a parametric resonance or a jump); the response grows by that factor every {:.6g} ms, "
                                     "so no steady value is reported",
                                     scene.name, r.stability, r.period * 1e3));
  // A linear mesh carries tension when the force changes sign: the teeth would separate,
  // which only a contact law (backlash, Hertz contact) models.
  if (!scene.fx.backlash && !scene.fx.hertz) {
    const auto& f = series(samples.signals, Signal::MeshForce);
    auto [lo, hi] = std::minmax_element(f.begin(), f.end());
    if (lo != f.end() && *lo < 0 && *hi > 0)
      r.warnings.push_back(fmt::format(
          "the mesh force changes sign (down to {:.4g} N against a static load of {:.4g} N): the teeth would separate, which this "
          "linear mesh does not allow; list `backlash {{ clearance = …; }}` among the effects to model contact loss",
          *lo, samples.staticLoad));
  }
}

// The loaded mesh's table as a series over its periods (a plot or a spectrum of the static
// transmission error over the hunting period).
SceneSeries tableSeries(const ir::SceneOutput& o, const std::vector<double>& table, const Samples& samples, double fz) {
  size_t n = table.size();
  double dt = static_cast<double>(samples.staticPeriods) / (fz * static_cast<double>(n));
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i)
    t[i] = static_cast<double>(i) * dt;
  return recorded(o, cat::signalSpec(o.id).dim, t, 0, table, dt, fz);
}

// The scene's outputs over the statistics window.
void sceneOutputs(const ScenePlan& scene, const SceneOverrides& ov, const Samples& samples, const TimePlan& tp, SceneResult& r) {
  // Outputs over the statistics window.
  size_t first = static_cast<size_t>(std::lower_bound(samples.t.begin(), samples.t.end(), tp.statsFrom - 1e-12) - samples.t.begin());
  auto window = [&](Signal sig) {
    const auto& v = series(samples.signals, sig);
    return std::vector<double>(v.begin() + static_cast<long>(std::min(first, v.size())), v.end());
  };
  auto over = [](cat::SignalFn fn, const std::vector<double>& v) { return v.empty() ? NAN : statistic(fn)(v); };
  std::map<Signal, OrderSpectrum> spectra;
  for (const auto& o : scene.outputs) {
    Dim dim = cat::signalSpec(o.id).dim;
    if (o.id == Signal::Modes) {
      for (size_t i = 0; i < samples.modes.size(); ++i)
        r.numbers.push_back({fmt::format("mode {}", i + 1), samples.modes[i], units::dims::frequency});
      continue;
    }
    if (o.id == Signal::Stability) {
      // A caller that forces a settled run (a study's settled curve) gets no multiplier.
      if (r.steady != SteadyMethod::Periodic && !ov.settlePeriods)
        throw Failure{"`stability` is a property of the periodic steady state: write `steady_state = periodic`, or leave out `settle`"};
      r.numbers.push_back(r.stabilityNumber);
      continue;
    }
    // An unstable periodic response has no steady value to report (docs/dynamics.md).
    if (r.unstable && !ov.keepUnstable && cat::signalFnSpec(o.fn).number) {
      r.numbers.push_back({o.key(), NAN, o.id == Signal::DynamicFactor ? Dim{} : dim, o.fn, o.id});
      continue;
    }
    if (o.id == Signal::DynamicFactor) {
      double peak = over(cat::SignalFn::Peak, window(Signal::MeshForce));
      r.numbers.push_back({"dynamic_factor", peak / samples.quasiStaticPeak, {}, cat::SignalFn::Peak, Signal::DynamicFactor});
      continue;
    }
    // The static transmission error over the hunting period, or of a scene without dynamics:
    // the table itself, every position.
    const std::vector<double>* table = samples.table(o.id);
    const cat::SignalFnSpec& fn = cat::signalFnSpec(o.fn);
    if (fn.order != cat::OrderArg::None) {
      r.numbers.push_back(orderNumber(o, samples.orderTable(o.id), window(o.id), tp.dt, r.meshFrequency, &spectra));
      continue;
    }
    if (!fn.number) {
      if (!ov.keepSeries) continue;
      if (table)
        r.series.push_back(tableSeries(o, *table, samples, r.meshFrequency));
      else
        r.series.push_back(recorded(o, dim, samples.t, first, window(o.id), tp.dt, r.meshFrequency));
      continue;
    }
    if (table) {
      r.numbers.push_back({o.key(), over(o.fn, *table), dim, o.fn, o.id, over(cat::SignalFn::Rms, *table)});
      continue;
    }
    // An output's error is measured against its signal's size, a force against at least the
    // static load: a minimum near zero does not turn a small error into a large relative one.
    double scale = over(cat::SignalFn::Rms, window(o.id));
    if (dim == units::dims::force && std::isfinite(samples.staticLoad)) scale = std::max(scale, std::fabs(samples.staticLoad));
    r.numbers.push_back({o.key(), over(o.fn, window(o.id)), dim, o.fn, o.id, std::isfinite(scale) ? scale : 0.0});
  }
  // The rating's K_v by method A reads the dynamic factor of a scene that may not list it.
  bool listed = std::any_of(scene.outputs.begin(), scene.outputs.end(), [](const auto& o) { return o.id == Signal::DynamicFactor; });
  if (ov.dynamicFactor && !listed) {
    double peak = r.unstable && !ov.keepUnstable ? NAN : over(cat::SignalFn::Peak, window(Signal::MeshForce));
    r.numbers.push_back({"dynamic_factor", peak / samples.quasiStaticPeak, {}, cat::SignalFn::Peak, Signal::DynamicFactor});
  }
}

SceneResult runOnce(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov) {
  if (!scene.failure.empty()) throw Failure{scene.failure};
  SceneResult r;
  r.name = scene.name;
  r.target = scene.target;
  Evaluator ev = ov.evaluator ? *ov.evaluator : Evaluator(m);
  int st = scene.stage;
  if (st < 0) {
    if (scene.timeDomain) return runWholeGearbox(m, ev, a, scene, ov, std::move(r));
    return wholeGearboxModes(m, a, std::move(r));
  }
  const ir::Stage& stage = *m.stages[static_cast<size_t>(st)].ir;
  Accuracy acc = sceneAccuracy(scene, ov);
  r.method = std::string(cat::methodSpec(acc.method).name);
  r.rtol = acc.rtol;
  r.atol = acc.atol > 0 ? acc.atol : acc.rtol;
  Samples samples;
  TimePlan tp;
  std::string failure;
  switch (m.info(st).kind->scene) {
  case SceneModel::SingleMesh:
    failure = runSingleMesh(m, a, scene, ov, acc, r, samples, tp);
    if (failure.empty() && !r.failure.empty()) return r;  // no periodic orbit
    break;
  case SceneModel::Planetary: failure = runPlanetaryScene(m, ev, a, st, scene, ov, acc, r, samples, tp); break;
  case SceneModel::None: throw Failure{fmt::format("scenes on {} stages are not modelled", ir::stageKindName(stage.kind))};
  }
  if (!failure.empty()) {
    r.failure = fmt::format("scene `{}`: {}", scene.name, failure);
    return r;
  }
  runWarnings(scene, ov, samples, r);
  // An overlap ratio near a whole number: the contact-line length barely varies, so what the
  // loaded mesh excites comes from the deviations and the tip engagement alone and moves
  // steeply with the face width and the helix angle.
  if (scene.fx.loaded && stage.kind == ir::StageKind::Helical) {
    Value eb = ev.derived(st, Q::EpsBeta, a);
    double e = eb.isNumber() ? eb.mid() : NAN, whole = std::round(e);
    if (whole >= 1 && std::fabs(e - whole) < 0.1)
      r.warnings.push_back(fmt::format("the overlap ratio eps_beta = {:.4f} is within 0.1 of {:.0f}: the length of the contact lines "
                                       "barely varies, so the loaded mesh's excitation comes from the deviations and the tip engagement "
                                       "and changes steeply with the face width and the helix angle",
                                       e, whole));
  }
  sceneOutputs(scene, ov, samples, tp, r);
  return r;
}

} // namespace


// ---- shared by the scene models --------------------------------------------------------

const Elastic& materialOf(const Model& m, int st) { return m.info(st).elastic; }


double needNumber(const Value& v, const std::string& what) {
  if (!v.isNumber() || !std::isfinite(v.lo)) throw SceneFailure{fmt::format("the scene needs {}, which this design does not give", what)};
  return v.mid();
}

namespace {

// The number of samples a plan records, checked against its budget before any is made.
long recordedSamples(double n, const char* window) {
  if (!(n <= static_cast<double>(cat::budget::kRecordedSamples)))
    throw SceneFailure{fmt::format("{} is {:.3g} samples, beyond the budget of {} recorded samples per run; record a shorter "
                                   "window or fewer samples per mesh period",
                                   window, n, cat::budget::kRecordedSamples)};
  return std::max<long>(1, std::lround(n));
}

} // namespace

// The fewest whole mean mesh periods Tm (at most 1000) that hold whole periods of every
// fluctuation; 0 when there is none.
int wholeMeshPeriods(double Tm, const std::vector<double>& periods) {
  for (int q = 1; q <= 1000; ++q) {
    bool whole = true;
    for (double P : periods) {
      double r = q * Tm / P;
      if (std::round(r) < 1 || std::fabs(r - std::round(r)) > 1e-9 * std::max(1.0, r)) {
        whole = false;
        break;
      }
    }
    if (whole) return q;
  }
  return 0;
}

bool widenToPeriod(TimePlan& plan, double period) {
  if (static_cast<double>(plan.samples.size()) * plan.dt >= period * (1 - 1e-9)) return false;
  long n = recordedSamples(period / plan.dt, "the orbit's whole period");
  plan.samples.clear();
  for (long i = 0; i < n; ++i) plan.samples.push_back(static_cast<double>(i) * plan.dt);
  plan.end = plan.samples.back();
  return true;
}

TimePlan periodicPlan(const ScenePlan& scene, double Tz) {
  int perPeriod = scene.samplesPerPeriod;
  double window = scene.record.at(Tz).value_or(Tz);
  TimePlan p;
  p.dt = Tz / perPeriod;
  long n = recordedSamples(window / Tz * perPeriod, "the recorded window");
  for (long i = 0; i < n; ++i) p.samples.push_back(static_cast<double>(i) * p.dt);
  p.end = p.samples.back();
  p.statsFrom = 0;
  p.steady = SteadyMethod::Periodic;
  p.periodicWritten = scene.periodicWritten;
  return p;
}

TimePlan timePlan(const ScenePlan& scene, double Tz, std::optional<long> settlePeriods) {
  if (scene.steady(settlePeriods) == SteadyMethod::Periodic) return periodicPlan(scene, Tz);
  int perPeriod = scene.samplesPerPeriod;
  TimePlan p;
  p.dt = Tz / perPeriod;
  double settle = settlePeriods ? static_cast<double>(*settlePeriods) * Tz : scene.settle.at(Tz).value_or(0);
  double ramp = scene.ramp.at(Tz).value_or(0);
  if (auto rec = scene.record.at(Tz)) {
    long n = recordedSamples(*rec / Tz * perPeriod, "the recorded window");
    for (long i = 0; i < n; ++i) p.samples.push_back(settle + static_cast<double>(i) * p.dt);
    p.end = p.samples.back();
    p.statsFrom = settle;
    p.steady = SteadyMethod::Settle;
  } else {
    double duration = scene.duration.at(Tz).value_or(0);
    long n = duration > 0 ? recordedSamples(std::floor(duration / p.dt), "the run from rest") : 0;
    for (long i = 1; i <= n; ++i) p.samples.push_back(static_cast<double>(i) * p.dt);
    p.end = duration;
    // Statistics of a run from rest leave out the start-up.
    p.statsFrom = std::max(settle, ramp);
    p.steady = SteadyMethod::FromRest;
  }
  return p;
}

Drive sceneDrive(const ScenePlan& scene, double nominal, double upstream, double Tz) {
  Drive d;
  d.speed0 = nominal;
  if (auto ramp = scene.ramp.at(Tz)) d.ramp = *ramp;
  if (const auto& f = scene.fx.speed) {
    d.fluctuates = true;
    d.mean = f->mean / upstream;
    d.amplitude = f->amplitude / upstream;
    d.omega = f->omega;
  }
  return d;
}

MeshScene meshScene(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov) {
  if (!scene.failure.empty()) throw Failure{scene.failure};
  std::vector<std::string> prov;
  return meshSceneOf(m, a, scene, ov, sceneAccuracy(scene, ov), prov);
}

MeshScene meshScene(const Model& m, const Assignment& a, const ir::Scene& scene, const SceneOverrides& ov) {
  return meshScene(m, a, planScene(scene), ov);
}

namespace {

// Each steady output's difference between two runs of one scene (the same outputs, so the
// numbers come in the same order), relative to the output's own scale; stability is not an
// output value. NaN where an output has no number in either run.
std::vector<double> outputDifferences(const SceneResult& r, const SceneResult& ref) {
  std::vector<double> d(r.numbers.size(), NAN);
  for (size_t i = 0; i < r.numbers.size() && i < ref.numbers.size(); ++i) {
    const auto &n = r.numbers[i], &x = ref.numbers[i];
    if (n.signal == Signal::Stability || !std::isfinite(n.value) || !std::isfinite(x.value)) continue;
    // A level's difference in dB as the relative difference of the amplitude it stands for.
    if (cat::signalFnSpec(n.fn).decibels) {
      d[i] = std::fabs(n.value - x.value) * std::log(10.0) / 20.0;
      continue;
    }
    double scale = std::max({std::fabs(x.value), x.scale, n.scale, 1e-300});
    d[i] = std::fabs(n.value - x.value) / scale;
  }
  return d;
}

double largest(const std::vector<double>& d) {
  double worst = 0;
  for (double x : d)
    if (std::isfinite(x)) worst = std::max(worst, x);
  return worst;
}

} // namespace

// The error estimate covers the model, not only the integrator: the integration (a rerun at
// a hundredth of the tolerance with half the maximum step, so the two step sequences can
// never coincide), the truncation of the stiffness series (N against 2N harmonics) and,
// for the periodic steady state, Newton's residual. The parts add up.
static void estimateError(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov, SceneResult& r) {
  SceneOverrides tight = ov;
  tight.rtol = r.rtol / 100.0;
  tight.maxStepFactor = 0.5 * ov.maxStepFactor.value_or(1.0);
  tight.keepSeries = false;
  tight.estimateError = false;
  if (r.steady == SteadyMethod::Periodic && !r.orbit.empty()) tight.guess = r.orbit;
  // Harmonic balance: its truncation against twice the harmonics, the other parts at its own.
  const int N = r.balanceHarmonics;
  if (N > 0) tight.balanceHarmonics = 2 * N;
  else
    tight.harmonicBalance = false; // shooting found this orbit: its reference is shooting's too
  // Fixed steps: the reference takes twice as many (a tighter rtol alone would not change them);
  // the other reruns take the scene's own.
  const int ownSteps = r.stepsPerSample > 0 ? r.stepsPerSample : ov.stepsPerSample;
  if (r.stepsPerSample > 0) tight.stepsPerSample = 2 * r.stepsPerSample;
  // A static scene integrates nothing: its estimate is its table's discretisation alone.
  const bool integrated = r.steady != SteadyMethod::Static;
  SceneResult ref;
  if (integrated) {
    ref = runOnce(m, a, scene, tight);
    if (!ref.failure.empty()) return;
    r.referenceStats = ref.stats;
  }
  std::vector<double> perOutput(r.numbers.size(), 0.0);
  auto part = [&](const SceneResult& other) {
    auto d = outputDifferences(r, other);
    for (size_t i = 0; i < d.size(); ++i)
      if (std::isfinite(d[i])) perOutput[i] += d[i];
    return largest(d);
  };
  if (integrated && N > 0 && ref.balanceHarmonics == 2 * N)
    r.errorParts.push_back({"harmonic truncation", part(ref), fmt::format("{} against {} harmonics", N, 2 * N)});
  else if (integrated && N > 0)
    r.errorParts.push_back({"harmonic truncation", part(ref),
                            fmt::format("{} harmonics against shooting at rtol {:.0e}", N, tight.rtol.value())});
  else if (integrated && r.stepsPerSample > 0 && ref.stepsPerSample == 2 * r.stepsPerSample)
    r.errorParts.push_back({"integration", part(ref),
                            fmt::format("against a rerun with {} fixed steps per sample instead of {}",
                                        tight.stepsPerSample, r.stepsPerSample)});
  else if (integrated)
    r.errorParts.push_back(
        {"integration", part(ref),
         fmt::format("against a rerun at rtol {:.0e} with half the maximum step", tight.rtol.value())});
  if (r.harmonics > 0 && integrated) {
    SceneOverrides twice = tight;
    twice.rtol = ov.rtol;
    twice.maxStepFactor = ov.maxStepFactor;
    twice.stepsPerSample = ownSteps;
    twice.harmonics = 2 * r.harmonics;
    if (N > 0) twice.balanceHarmonics = N;
    SceneResult h2 = runOnce(m, a, scene, twice);
    if (h2.failure.empty()) {
      r.referenceStats += h2.stats;
      r.errorParts.push_back({"stiffness series", part(h2), fmt::format("{} against {} harmonics", r.harmonics, 2 * r.harmonics)});
    }
  }
  // The loaded mesh's discretisation: twice the slices and positions.
  if (scene.fx.loaded) {
    SceneOverrides fine = tight;
    fine.rtol = ov.rtol;
    fine.maxStepFactor = ov.maxStepFactor;
    fine.stepsPerSample = ownSteps;
    fine.loadedRefine = 2 * ov.loadedRefine;
    if (N > 0) fine.balanceHarmonics = N;
    SceneResult f2 = runOnce(m, a, scene, fine);
    if (f2.failure.empty()) {
      r.referenceStats += f2.stats;
      r.errorParts.push_back({"loaded mesh", part(f2), "against twice the slices and positions"});
    }
  }
  if (N > 0)
    r.errorParts.push_back(
        {"residual between the instants", r.newtonResidual, "of the state's rate, halfway between the instants"});
  else if (r.steady == SteadyMethod::Periodic)
    r.errorParts.push_back({"Newton residual", r.newtonResidual, fmt::format("of the state scale, after {} iteration{}", r.newtonIterations,
                                                                             r.newtonIterations == 1 ? "" : "s")});
  // Each output's own estimate: the parts that differ per output, and the residual all share.
  double shared = r.steady == SteadyMethod::Periodic ? r.newtonResidual : 0.0;
  for (size_t i = 0; i < r.numbers.size(); ++i)
    if (r.numbers[i].signal != Signal::Stability && std::isfinite(r.numbers[i].value)) r.numbers[i].error = perOutput[i] + shared;
  r.errorEstimate = 0;
  std::string text;
  for (const auto& p : r.errorParts) {
    r.errorEstimate += p.value;
    text += fmt::format("{}{} {:.2e} ({})", text.empty() ? "" : " + ", p.name, p.value, p.detail);
  }
  r.errorMethod = text;
  // A model error larger than the differences a comparison would read: say so where the
  // results are shown (an optimiser ranking by them, a relief study).
  if (r.errorEstimate > 0.1) {
    const SceneResult::ErrorPart* top = &r.errorParts.front();
    for (const auto& p : r.errorParts)
      if (p.value > top->value) top = &p;
    r.warnings.push_back(fmt::format("the error estimate of scene `{}` is {:.0f} % (mostly the {}: {}); results and rankings that "
                                     "differ by less are not resolved — refine what it names",
                                     scene.name, 100 * r.errorEstimate, top->name, top->detail));
  }
}

SceneResult runScene(const Model& m, const Assignment& a, const ScenePlan& scene, const SceneOverrides& ov) {
  SceneResult r;
  if (Deadline::expired()) { // no table and no integration past the time limit
    r.name = scene.name;
    r.failure = fmt::format("scene `{}`: time limit of {:g} s (--time-limit) reached", scene.name, Deadline::seconds());
    return r;
  }
  try {
    r = runOnce(m, a, scene, ov);
    bool steadyNumbers = std::any_of(r.numbers.begin(), r.numbers.end(),
                                     [](const SceneNumber& n) { return n.signal != Signal::Stability && std::isfinite(n.value); });
    if (r.failure.empty() && ov.estimateError && steadyNumbers && !r.eigen) estimateError(m, a, scene, ov, r);
  } catch (const Failure& f) {
    r.name = scene.name;
    r.failure = fmt::format("scene `{}`: {}", scene.name, f.what);
  }
  return r;
}

SceneResult runScene(const Model& m, const Assignment& a, const ir::Scene& scene, const SceneOverrides& ov) {
  return runScene(m, a, planScene(scene), ov);
}

} // namespace gbx::rt::dyn
