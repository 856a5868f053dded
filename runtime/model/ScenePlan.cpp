#include "model/ScenePlan.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "catalogue/Settings.h"

namespace gbx::rt {

namespace {

using Fn = std::function<double(const EffectValue::Locals&)>;

// An effect parameter's expression as a function of the effect's own words; what it may not
// use fails when the model evaluates it, as the scene's failure.
Fn compile(const ir::Expr& e) {
  using L = EffectValue::Locals;
  auto binary = [&](auto op) -> Fn {
    Fn a = compile(*e.args[0]), b = compile(*e.args[1]);
    return [a, b, op](const L& l) { return op(a(l), b(l)); };
  };
  switch (e.op) {
  case ir::Op::Const: {
    double v = e.value.toDouble();
    return [v](const L&) { return v; };
  }
  case ir::Op::Symbol: {
    int k = e.let;
    std::string name = e.name;
    return [k, name](const L& l) {
      if (k < 0 || static_cast<size_t>(k) >= l.size()) throw SceneFailure{fmt::format("`{}` has no value here", name)};
      return l[static_cast<size_t>(k)];
    };
  }
  case ir::Op::Neg: {
    Fn a = compile(*e.args[0]);
    return [a](const L& l) { return -a(l); };
  }
  case ir::Op::Add: return binary([](double x, double y) { return x + y; });
  case ir::Op::Sub: return binary([](double x, double y) { return x - y; });
  case ir::Op::Mul: return binary([](double x, double y) { return x * y; });
  case ir::Op::Div: return binary([](double x, double y) { return x / y; });
  default:
    return [](const L&) -> double { throw SceneFailure{"a setting's expression can use numbers and the effect's own words only"}; };
  }
}

// A fluctuation's frequency may be written in Hz; the plan keeps rad/s.
double inSi(Q key, double v, units::Dim dim) { return key == Q::Frequency && dim == units::dims::frequency ? v * 2.0 * M_PI : v; }

EffectValue valueOf(const ir::Setting& s) {
  if (s.choice >= 0) return EffectValue(static_cast<double>(s.choice));
  if (s.value) return EffectValue(inSi(s.key, s.value->toDouble(), s.dim));
  if (s.expr) return EffectValue(*s.expr);
  return EffectValue(0.0);
}

SceneTime timeOf(const std::vector<ir::Setting>& settings, Q key) {
  SceneTime t;
  const ir::Setting* s = ir::findSetting(settings, key);
  if (!s) return t;
  t.written = true;
  t.meshPeriods = s->meshPeriods;
  if (s->value) t.value = s->value->toDouble();
  return t;
}

// The typed view of the listed effects; the first of a kind counts, as the models read it.
SceneEffects effectsOf(const std::vector<ListedEffect>& listed) {
  using cat::Effect;
  SceneEffects fx;
  auto get = [](const ListedEffect& e, Q key, double dflt) {
    const EffectValue* v = e.param(key);
    return v ? (*v)() : dflt;
  };
  for (const auto& e : listed) {
    switch (e.kind) {
    case Effect::VaryingStiffness:
      if (fx.varying) break;
      fx.varying = SceneEffects::Varying{static_cast<int>(get(e, Q::Harmonics, 5)), std::nullopt};
      if (e.param(Q::Stiffness)) fx.varying->stiffness = get(e, Q::Stiffness, 0);
      break;
    case Effect::Damping:
      if (fx.damping) break;
      fx.damping = SceneEffects::Damping{get(e, Q::DampingRatio, 0), std::nullopt};
      if (e.param(Q::Coefficient)) fx.damping->coefficient = get(e, Q::Coefficient, 0);
      break;
    case Effect::TransmissionError:
      if (!fx.transmissionError) fx.transmissionError = SceneEffects::TransmissionError{get(e, Q::Mean, 0), get(e, Q::Amplitude, 0), get(e, Q::Phase, 0)};
      break;
    case Effect::Backlash:
      if (!fx.backlash) fx.backlash = SceneEffects::Backlash{get(e, Q::Clearance, 0)};
      break;
    case Effect::HertzContact:
      if (fx.hertz) break;
      fx.hertz = SceneEffects::Hertz{get(e, Q::Exponent, 1.5), get(e, Q::PenetrationRamp, 0), EffectValue(0.0)};
      if (const EffectValue* d = e.param(Q::Damping)) fx.hertz->damping = *d;
      break;
    case Effect::SpeedFluctuation:
    case Effect::TorqueFluctuation: {
      auto& slot = e.kind == Effect::SpeedFluctuation ? fx.speed : fx.torque;
      if (!slot) slot = SceneEffects::Fluctuation{get(e, Q::Mean, 0), get(e, Q::Amplitude, 0), get(e, Q::Frequency, 0)};
      break;
    }
    case Effect::LoadedMesh:
      if (fx.loaded) break;
      fx.loaded.emplace();
      fx.loaded->slices = static_cast<int>(get(e, Q::Slices, 40));
      fx.loaded->positions = static_cast<int>(get(e, Q::Positions, 64));
      if (e.param(Q::Harmonics)) fx.loaded->harmonics = static_cast<int>(get(e, Q::Harmonics, 0));
      fx.loaded->corner = get(e, Q::CornerContact, 0) == 1.0; // `true`, the row's second word
      if (e.param(Q::PitchSeed)) fx.loaded->pitchSeed = get(e, Q::PitchSeed, 0);
      if (const auto* v = e.list(Q::PinionPitchDeviations)) fx.loaded->pitch[0] = *v;
      if (const auto* v = e.list(Q::WheelPitchDeviations)) fx.loaded->pitch[1] = *v;
      break;
    }
  }
  return fx;
}

// The typed effects, or the failure of a parameter that cannot be evaluated (kept for the
// scene's run: planning never throws, so the model is always built).
void resolveEffects(ScenePlan& p) {
  p.failure.clear();
  try {
    p.fx = effectsOf(p.listed);
  } catch (const SceneFailure& f) {
    p.fx = {};
    p.failure = f.what;
  }
}

} // namespace

EffectValue::EffectValue(const ir::Expr& e) : fn_(compile(e)) {}

const std::vector<double>* ListedEffect::list(Q key) const {
  for (const auto& [k, v] : lists)
    if (k == key) return &v;
  return nullptr;
}

const EffectValue* ListedEffect::param(Q key) const {
  for (const auto& [k, v] : params)
    if (k == key) return &v;
  return nullptr;
}

void ListedEffect::set(Q key, double si, units::Dim dim) {
  EffectValue v(inSi(key, si, dim));
  for (auto& [k, x] : params)
    if (k == key) {
      x = v;
      return;
    }
  params.emplace_back(key, v);
}

SteadyMethod ScenePlan::steady(std::optional<long> settlePeriods) const {
  // The periodic steady state when the scene asks for it, and by default when it neither
  // settles nor runs from rest (docs/dynamics.md).
  bool settles = settlePeriods || settle;
  if (!settlePeriods && (periodicWritten || (!settles && !duration))) return SteadyMethod::Periodic;
  return record ? SteadyMethod::Settle : SteadyMethod::FromRest;
}

ScenePlan ScenePlan::withEffectParam(int effect, Q key, double si, units::Dim dim) const {
  ScenePlan p = *this;
  p.listed[static_cast<size_t>(effect)].set(key, si, dim);
  resolveEffects(p);
  return p;
}

ScenePlan planScene(const ir::Scene& scene) {
  ScenePlan p;
  p.name = scene.name;
  p.target = scene.target;
  p.stage = scene.stage;
  p.method = scene.method();
  auto number = [](const std::vector<ir::Setting>& set, Q key) -> std::optional<double> {
    const ir::Setting* s = ir::findSetting(set, key);
    if (s && s->value) return s->value->toDouble();
    return std::nullopt;
  };
  p.rtol = number(scene.accuracy, Q::Rtol);
  p.atol = number(scene.accuracy, Q::Atol);
  if (auto n = number(scene.accuracy, Q::MaxSteps)) p.maxSteps = static_cast<long>(*n);
  p.maxStep = timeOf(scene.accuracy, Q::MaxStep);
  p.minStep = timeOf(scene.accuracy, Q::MinStep);
  if (auto n = number(scene.settings, Q::Samples)) p.samplesPerPeriod = static_cast<int>(*n);
  p.settle = timeOf(scene.settings, Q::Settle);
  p.record = timeOf(scene.settings, Q::Record);
  p.duration = timeOf(scene.settings, Q::Duration);
  p.ramp = timeOf(scene.settings, Q::Ramp);
  const ir::Setting* steady = ir::findSetting(scene.settings, Q::SteadyState);
  p.periodicWritten = steady != nullptr;
  p.harmonicBalance = steady && steady->choice == cat::kSteadyHarmonicBalance;
  if (auto n = number(scene.settings, Q::Harmonics)) p.balanceHarmonics = static_cast<int>(*n);
  for (const auto& e : scene.effects) {
    ListedEffect l{e.kind, e.name, {}, {}};
    for (const auto& s : e.params) {
      if (s.members.empty()) {
        l.params.emplace_back(s.key, valueOf(s));
        continue;
      }
      std::vector<double> v;
      for (const auto& m : s.members)
        v.push_back(m.toDouble());
      l.lists.emplace_back(s.key, std::move(v));
    }
    p.listed.push_back(std::move(l));
  }
  resolveEffects(p);
  p.outputs = scene.outputs;
  p.timeDomain = std::any_of(p.outputs.begin(), p.outputs.end(), [](const ir::SceneOutput& o) { return o.id != cat::Signal::Modes; });
  return p;
}

} // namespace gbx::rt
