#pragma once
// Runs a `scene` of a solved design: builds the model from the stage and the listed
// effects, integrates it to the scene's accuracy, and returns its outputs with their
// cost and an error estimate.
#include <optional>
#include <string>
#include <vector>

#include "dynamics/MeshModel.h"
#include "dynamics/Ode.h"
#include "dynamics/SceneSupport.h"
#include "dynamics/Spectrum.h"
#include "ir/Ir.h"
#include "model/Evaluator.h"
#include "model/Model.h"

namespace gbx::rt::dyn {

struct SceneNumber {
  std::string key;  // "rms(acceleration)"
  double value = 0; // SI
  units::Dim dim;
  cat::SignalFn fn = cat::SignalFn::Rms;  // what it is, for `scene.fn(signal)` in objectives
  cat::Signal signal = cat::Signal::Modes;
  // The size an error of this output is measured against (docs/language.md): the RMS of its
  // signal over the recorded window, a force at least the static load; 0: the value itself.
  double scale = 0;
  double error = NAN;  // its own error estimate, relative to that scale
  int order = 0;       // `harmonic(x, k)`, `level(x, k)`: k
};

struct SceneSeries {
  std::string key;     // "plot(acceleration)" or "spectrum(mesh_force)"
  std::string signal;
  units::Dim dim;
  std::vector<double> t, v;
  bool isSpectrum = false;
  Spectrum spectrum;
  double meshFrequency = 0;  // a spectrum: the mesh whose orders its harmonics count, Hz
};

struct SceneResult {
  std::string name, target, method;  // method as reported: an integrator's name, or "eigen"
  bool eigen = false;                // modes of a lumped model: no integration, no error estimate
  double rtol = 0, atol = 0;
  Stats stats;
  double errorEstimate = -1;  // relative, over the numeric outputs; < 0 when not estimated
  std::string errorMethod;
  // The estimate's parts: the integration, the stiffness series' truncation, Newton's residual.
  struct ErrorPart {
    std::string name;
    double value = 0;
    std::string detail;
  };
  std::vector<ErrorPart> errorParts;
  std::string stepRule;  // the maximum step and where it comes from
  // Periodic steady state: how it was found and whether it is stable.
  SteadyMethod steady = SteadyMethod::Settle;
  double period = 0;      // of the excitation, s
  double stability = NAN; // largest Floquet multiplier modulus (periodic only)
  bool unstable = false;  // stability >= 1: no steady outputs
  int newtonIterations = 0;
  double newtonResidual = 0;
  std::string orbitMethod;        // how the orbit was found, for the model's line
  bool orbitUnconfirmed = false;  // a linear orbit whose residual the record run measures
  std::vector<double> orbit;  // the orbit's initial state, for a neighbouring sweep point
  int harmonics = 0;          // of the stiffness series, 0 without varying_stiffness
  int balanceHarmonics = 0;   // the orbit's harmonics when harmonic balance found it, else 0
  int stepsPerSample = 0;     // the fixed steps between two samples when shooting took them, else 0
  double balanceTruncation = NAN; // its change from half the harmonics, of the state scale (N chosen for a target)
  Stats referenceStats;
  double meshFrequency = 0;
  double naturalFrequency = 0;  // of the mean linearised mesh (single-mesh scenes), Hz
  std::vector<SceneNumber> numbers;
  std::vector<SceneSeries> series;
  std::vector<std::string> model;  // how the model was built, parameter by parameter
  std::string failure;             // set when the run failed (exit 3)
  std::vector<std::string> warnings;  // results to read with care (teeth that would separate)
  const SceneNumber* find(cat::SignalFn fn, cat::Signal signal, int order = 0) const;
  const SceneNumber* find(const std::string& key) const;  // by the report's key, for tests
  const SceneNumber* find(const ir::SceneOutputRef& ref) const;
  SceneNumber stabilityNumber;  // `scene.stability` read where the scene does not list it
  // A whole-gearbox scene's members, their kinematic speeds per unit input speed, and its
  // energy balance when SceneOverrides::energyAudit asks for it (dynamics/Gearbox.h).
  struct WholeGearbox {
    std::vector<std::string> members;
    std::vector<double> kinematic;
    double driveWork = 0, loadWork = 0, dissipated = 0, energyGained = 0;
  } gearbox;
};

// The single-mesh model of a scene on a spur or helical stage, as runScene builds it.
struct MeshScene {
  MeshParameters params;
  MeshEffects effects;
  Accuracy accuracy;
  TimePlan plan;
  double meshFrequency = 0;
  std::vector<std::string> provenance;
  std::string stepRule;
  int harmonics = 0;  // of the stiffness series, 0 without varying_stiffness
};
MeshScene meshScene(const Model& m, const Assignment& design, const ScenePlan& scene, const SceneOverrides& ov = {});

// Runs one of the model's planned scenes (Model::scenes).
SceneResult runScene(const Model& m, const Assignment& design, const ScenePlan& scene, const SceneOverrides& ov = {});

// Plans a scene first: one outside the model's own (a test's, a modified copy).
MeshScene meshScene(const Model& m, const Assignment& design, const ir::Scene& scene, const SceneOverrides& ov = {});
SceneResult runScene(const Model& m, const Assignment& design, const ir::Scene& scene, const SceneOverrides& ov = {});

} // namespace gbx::rt::dyn
