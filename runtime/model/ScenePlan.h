#pragma once
// A scene resolved once (docs/language.md, docs/dynamics.md): its accuracy, time plan, steady-state
// method, drive and effects with their parameters in SI, and its outputs. The Model plans
// every scene of its gearbox when it is built; the scene models, the passes and the studies
// read the plan, never the scene's settings in the IR.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"

namespace gbx::rt {

using cat::Q;

// A scene that cannot run: what it lacks, in a sentence (the scene's result says it).
struct SceneFailure {
  std::string what;
};

// How a scene reaches its steady state (docs/dynamics.md).
enum class SteadyMethod {
  FromRest, // `duration`: a run from rest, start-up included
  Settle,   // `settle = N mesh_periods`: exactly N periods, then record
  Periodic, // `steady_state = periodic`, or the default where the excitation is periodic
  Static,   // no dynamics: every output reads the loaded mesh's static table
};

// A time written in seconds or in the scene's mesh periods (`settle = 200 mesh_periods`).
// Written is what decides the steady state; the value is what the time plan uses.
struct SceneTime {
  bool written = false;
  std::optional<double> value;  // s, or mesh periods
  bool meshPeriods = false;
  explicit operator bool() const { return written; }
  // In seconds for the given mesh period; none where the scene gives no value.
  std::optional<double> at(double meshPeriod) const {
    if (!value) return std::nullopt;
    return *value * (meshPeriods ? meshPeriod : 1.0);
  }
};

// An effect parameter in SI (a frequency in rad/s), or an expression over the effect's own
// words (`damping = 0.01 * stiffness`), bound when the model knows them.
class EffectValue {
public:
  using Locals = std::vector<double>;
  EffectValue() = default;
  explicit EffectValue(double v) : value_(v) {}
  explicit EffectValue(const ir::Expr& e);
  double operator()(const Locals& locals = {}) const { return fn_ ? fn_(locals) : value_; }

private:
  double value_ = 0;
  std::function<double(const Locals&)> fn_;
};

// An effect as the scene lists it: its kind and its parameters by key.
struct ListedEffect {
  cat::Effect kind = cat::Effect::VaryingStiffness;
  std::string name;
  std::vector<std::pair<Q, EffectValue>> params;
  std::vector<std::pair<Q, std::vector<double>>> lists; // list parameters, SI
  const EffectValue* param(Q key) const;
  const std::vector<double>* list(Q key) const;
  // Sets one parameter from a value in the unit `dim` (a sweep of `scene.effect.parameter`).
  void set(Q key, double si, units::Dim dim);
};

// The loaded mesh's settings (outside SceneEffects so that std::optional of it can be default
// constructed while SceneEffects is still being defined: its member initialisers are not
// parsed until then, and clang refuses the emplace()).
struct LoadedMeshPlan {
  int slices = 40, positions = 64;
  std::optional<int> harmonics; // the tables' Fourier harmonics; default positions / 4
  int tableHarmonics() const { return harmonics.value_or(positions / 4); }
  bool corner = false;             // contact outside the path
  std::optional<double> pitchSeed; // draw the teeth's pitch deviations with this seed
  std::vector<double> pitch[2];    // the teeth's single pitch deviations as listed, SI
};

// The listed effects by kind, each with its parameters and their defaults (the catalogue's,
// which sema writes in where the scene leaves one out). What the scene does not list is empty.
struct SceneEffects {
  struct Varying {
    int harmonics = 5;
    std::optional<double> stiffness;  // the mean mesh stiffness, when given
  };
  struct Damping {
    double ratio = 0;
    std::optional<double> coefficient;  // given: it, not the ratio
  };
  struct TransmissionError {
    double mean = 0, amplitude = 0, phase = 0;
  };
  struct Backlash {
    double clearance = 0;  // total, along the line of action
  };
  struct Hertz {
    double exponent = 1.5, penetrationRamp = 0;
    EffectValue damping;  // over the word `stiffness` (the contact's, in the source paper's units)
  };
  struct Fluctuation {
    double mean = 0, amplitude = 0, omega = 0;  // omega in rad/s
  };
  using Loaded = LoadedMeshPlan;
  std::optional<Varying> varying;
  std::optional<Damping> damping;
  std::optional<TransmissionError> transmissionError;
  std::optional<Backlash> backlash;
  std::optional<Hertz> hertz;
  std::optional<Fluctuation> speed, torque;
  std::optional<Loaded> loaded;
};

struct ScenePlan {
  std::string name;
  std::string target;  // the stage's name, "" for the whole gearbox
  int stage = -1;      // the target's index, -1 the whole gearbox
  // Accuracy: what the scene writes; the integrator's defaults where it does not.
  cat::Method method = cat::Method::Rk8pd;
  std::optional<double> rtol, atol;
  std::optional<long> maxSteps;
  SceneTime maxStep, minStep;
  // The time plan.
  int samplesPerPeriod = 160;
  SceneTime settle, record, duration, ramp;
  bool periodicWritten = false;        // `steady_state = periodic` or `harmonic_balance`
  bool harmonicBalance = false;        // `steady_state = harmonic_balance`
  std::optional<int> balanceHarmonics; // its `harmonics`, when written
  // The effects, as listed and by kind.
  std::vector<ListedEffect> listed;
  SceneEffects fx;
  std::vector<ir::SceneOutput> outputs;
  bool timeDomain = false;  // an output other than `modes`
  // A parameter the runtime cannot evaluate (an expression over other quantities): the
  // scene fails with this when it runs, as every scene failure does, and the model is
  // built all the same.
  std::string failure;

  // How the scene reaches its steady state; `settlePeriods` is a study's forced settle.
  SteadyMethod steady(std::optional<long> settlePeriods = std::nullopt) const;
  // The same scene with one effect parameter set (a sweep of `scene.effect.parameter`).
  ScenePlan withEffectParam(int effect, Q key, double si, units::Dim dim) const;
};

ScenePlan planScene(const ir::Scene& scene);

} // namespace gbx::rt
