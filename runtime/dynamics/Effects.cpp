#include "dynamics/Effects.h"

#include <fmt/format.h>

namespace gbx::rt::dyn {

namespace {

using cat::Effect;

double param(const ir::Effect& e, Q key, double dflt, const std::vector<double>& locals = {}) {
  const ir::Setting* s = effectParam(&e, key);
  return s ? settingValue(*s, locals) : dflt;
}

// A function-local table: ready whenever it is first asked for.
const std::vector<EffectRow>& kRowsTable() {
  static const std::vector<EffectRow> rows = {
    {Effect::VaryingStiffness,
     [](const ir::Effect& e, const SceneOverrides& ov, MeshParameters& p, MeshEffects& fx, std::vector<std::string>&) {
       fx.varyingStiffness = true;
       fx.harmonics = ov.harmonics ? *ov.harmonics : static_cast<int>(param(e, Q::Harmonics, 5));
       if (effectParam(&e, Q::Stiffness)) p.meanStiffness = param(e, Q::Stiffness, p.meanStiffness);
     },
     false, true},
    {Effect::Damping,
     [](const ir::Effect& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.damping = true;
       fx.dampingRatio = param(e, Q::DampingRatio, 0);
       fx.dampingCoefficient = effectParam(&e, Q::Coefficient) ? param(e, Q::Coefficient, 0) : -1;
     },
     false, true},
    {Effect::TransmissionError,
     [](const ir::Effect& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.transmissionError = true;
       fx.teMean = param(e, Q::Mean, 0);
       fx.teAmplitude = param(e, Q::Amplitude, 0);
       fx.tePhase = param(e, Q::Phase, 0);
     },
     false, true},
    {Effect::Backlash,
     [](const ir::Effect& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.backlash = true;
       fx.clearance = param(e, Q::Clearance, 0);
     },
     false, true},
    {Effect::HertzContact,
     [](const ir::Effect& e, const SceneOverrides&, MeshParameters& p, MeshEffects& fx, std::vector<std::string>& prov) {
       fx.hertz = true;
       fx.hertzExponent = param(e, Q::Exponent, 1.5);
       fx.penetrationRamp = param(e, Q::PenetrationRamp, 0);
       // The damping may be written over the contact stiffness (`0.01 * stiffness`).
       fx.hertzDamping = param(e, Q::Damping, 0, {adamsStiffness(p.hertzStiffness, fx.hertzExponent)});
       prov.push_back(fmt::format("Hertz stiffness {:.6g} N/m^{} = 4/3 sqrt(R) E*, R = {:.4g} mm", p.hertzStiffness, fx.hertzExponent,
                                  p.hertzRadius * 1e3));
     },
     false, true},
    {Effect::SpeedFluctuation, nullptr, true, true},
    {Effect::TorqueFluctuation,
     [](const ir::Effect& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.torqueFluctuation = true;
       fx.torqueMean = param(e, Q::Mean, 0);
       fx.torqueAmplitude = param(e, Q::Amplitude, 0);
       fx.torqueOmega = angularFrequency(*effectParam(&e, Q::Frequency));
     },
     false, true},
    // The tables need the flank geometry: the scene computes them once the effects are read.
    {Effect::LoadedMesh,
     [](const ir::Effect& e, const SceneOverrides& ov, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.loadedMesh = true;
       fx.slices = static_cast<int>(param(e, Q::Slices, 40)) * ov.loadedRefine;
       fx.positions = static_cast<int>(param(e, Q::Positions, 64)) * ov.loadedRefine;
       int h = effectParam(&e, Q::Harmonics) ? static_cast<int>(param(e, Q::Harmonics, 16)) : static_cast<int>(param(e, Q::Positions, 64)) / 4;
       fx.loadedHarmonics = ov.harmonics ? *ov.harmonics : h;
     },
     false, false},
  };
  return rows;
}

} // namespace

const std::vector<EffectRow>& effectRows() { return kRowsTable(); }

const EffectRow* effectRow(cat::Effect id) {
  for (const auto& r : kRowsTable())
    if (r.id == id) return &r;
  return nullptr;
}

} // namespace gbx::rt::dyn
