#include "dynamics/Effects.h"

#include <fmt/format.h>

namespace gbx::rt::dyn {

namespace {

using cat::Effect;

// A function-local table: ready whenever it is first asked for.
const std::vector<EffectRow>& kRowsTable() {
  static const std::vector<EffectRow> rows = {
    {Effect::VaryingStiffness,
     [](const SceneEffects& e, const SceneOverrides& ov, MeshParameters& p, MeshEffects& fx, std::vector<std::string>&) {
       fx.varyingStiffness = true;
       fx.harmonics = ov.harmonics ? *ov.harmonics : e.varying->harmonics;
       if (e.varying->stiffness) p.meanStiffness = *e.varying->stiffness;
     },
     false, true, true},
    {Effect::Damping,
     [](const SceneEffects& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.damping = true;
       fx.dampingRatio = e.damping->ratio;
       fx.dampingCoefficient = e.damping->coefficient.value_or(-1);
     },
     false, true, true},
    {Effect::TransmissionError,
     [](const SceneEffects& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.transmissionError = true;
       fx.teMean = e.transmissionError->mean;
       fx.teAmplitude = e.transmissionError->amplitude;
       fx.tePhase = e.transmissionError->phase;
     },
     false, true, false},
    {Effect::Backlash,
     [](const SceneEffects& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.backlash = true;
       fx.clearance = e.backlash->clearance;
     },
     false, true, true},
    {Effect::HertzContact,
     [](const SceneEffects& e, const SceneOverrides&, MeshParameters& p, MeshEffects& fx, std::vector<std::string>& prov) {
       fx.hertz = true;
       fx.hertzExponent = e.hertz->exponent;
       fx.penetrationRamp = e.hertz->penetrationRamp;
       // The damping may be written over the contact stiffness (`0.01 * stiffness`).
       fx.hertzDamping = e.hertz->damping({adamsStiffness(p.hertzStiffness, fx.hertzExponent)});
       prov.push_back(fmt::format("Hertz stiffness {:.6g} N/m^{} = 4/3 sqrt(R) E*, R = {:.4g} mm", p.hertzStiffness, fx.hertzExponent,
                                  p.hertzRadius * 1e3));
     },
     false, true, true},
    {Effect::SpeedFluctuation, nullptr, true, true, true},
    {Effect::TorqueFluctuation,
     [](const SceneEffects& e, const SceneOverrides&, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.torqueFluctuation = true;
       fx.torqueMean = e.torque->mean;
       fx.torqueAmplitude = e.torque->amplitude;
       fx.torqueOmega = e.torque->omega;
     },
     false, true, true},
    // The tables need the flank geometry: the scene computes them once the effects are read.
    {Effect::LoadedMesh,
     [](const SceneEffects& e, const SceneOverrides& ov, MeshParameters&, MeshEffects& fx, std::vector<std::string>&) {
       fx.loadedMesh = true;
       fx.slices = e.loaded->slices * ov.loadedRefine;
       fx.positions = e.loaded->positions * ov.loadedRefine;
       fx.loadedHarmonics = ov.harmonics ? *ov.harmonics : e.loaded->tableHarmonics();
       fx.loadedCorner = e.loaded->corner;
       fx.pitchSeed = e.loaded->pitchSeed;
       for (int g = 0; g < 2; ++g)
         fx.pitchListed[g] = e.loaded->pitch[g].empty() ? nullptr : &e.loaded->pitch[g];
     },
     false, false, true},
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
