#pragma once
// Pieces shared by the scene models: the time plan, the drive, effect settings.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <array>
#include <optional>

#include <Eigen/Core>

#include "dynamics/Drive.h"
#include "model/ScenePlan.h"
#include "model/Value.h"

namespace gbx::rt {
class Evaluator;
class Model;
struct Elastic;
}

namespace gbx::rt::dyn {

using cat::Q;

// What a study changes in a scene: harmonics, method, tolerance; whether to estimate the
// error and keep the series.
struct SceneOverrides {
  std::optional<int> harmonics;
  // Harmonic balance: on or off whatever the scene says (a work-precision curve), and its
  // number of harmonics (an error-estimate rerun at twice the scene's).
  std::optional<bool> harmonicBalance;
  std::optional<int> balanceHarmonics; // 0: chosen for rtol whatever the scene writes
  int stepsPerSample = 0;              // fixed-step shooting: the steps between two samples (0: chosen for rtol)
  bool adaptiveShooting = false;       // shooting by the adaptive integrator on any model (an independent reference)
  std::optional<cat::Method> method;
  std::optional<double> rtol;
  bool estimateError = true;
  bool keepSeries = true;
  // A sweep's evaluator, whose overrides (an operating value, a stage attribute) the scene
  // is built with; nullptr: the design as it is.
  const Evaluator* evaluator = nullptr;
  // The periodic orbit's initial state from a neighbouring sweep point: Newton's first guess;
  // for a transient, the state it starts from.
  std::optional<std::vector<double>> guess;
  // Harmonic balance's first guess: a neighbouring orbit's coefficients (a continuation's point).
  const Eigen::MatrixXd* balanceStart = nullptr;
  // Settle exactly this many mesh periods instead (a work-precision study's settled curve).
  std::optional<long> settlePeriods;
  bool forcePeriodic = false;  // the periodic steady state whatever the scene says (a study's periodic curve)
  std::optional<double> maxStepFactor;  // times the scene's maximum step (an error-estimate rerun)
  bool keepUnstable = false;  // values on an unstable orbit too (a continuation's middle branch)
  int loadedRefine = 1;       // the loaded mesh's slices and positions times this (an error-estimate rerun)
  bool energyAudit = false;   // a whole-gearbox scene also integrates its energy balance (tests)
  bool dynamicFactor = false; // also the dynamic factor where the scene does not list it (K_v by method A)
};

using SteadyMethod = rt::SteadyMethod;
using SceneFailure = rt::SceneFailure;

// Recorded samples of every signal of a scene, by signal.
inline constexpr size_t kSignalCount = static_cast<size_t>(cat::Signal::Modes) + 1;
using SignalSeries = std::array<std::vector<double>, kSignalCount>;
inline std::vector<double>& series(SignalSeries& s, cat::Signal id) { return s[static_cast<size_t>(id)]; }
inline const std::vector<double>& series(const SignalSeries& s, cat::Signal id) { return s[static_cast<size_t>(id)]; }

using Elastic = rt::Elastic;
// A stage's elastic constants and density, as the model read them from its material.
const Elastic& materialOf(const Model& m, int stage);

struct TimePlan {
  double end = 0, statsFrom = 0, dt = 0;
  std::vector<double> samples;  // exactly `samples` per mesh period
  SteadyMethod steady = SteadyMethod::Settle;
  bool periodicWritten = false;  // `steady_state = periodic` in the scene
};

// A number the model needs: its value, or a SceneFailure naming what is missing.
double needNumber(const Value& v, const std::string& what);

TimePlan timePlan(const ScenePlan& scene, double meshPeriod, std::optional<long> settlePeriods = std::nullopt);
// The plan of a periodic steady state: the record window from t = 0 on the orbit.
TimePlan periodicPlan(const ScenePlan& scene, double meshPeriod);
// The fewest whole periods Tm (at most 1000) that hold whole periods of every one given; 0 when
// there is none.
int wholeMeshPeriods(double Tm, const std::vector<double>& periods);
// Widens a periodic plan's record window to a whole orbit of the given period; true when it did.
bool widenToPeriod(TimePlan& plan, double period);
Drive sceneDrive(const ScenePlan& scene, double nominal, double upstream, double meshPeriod);
// `damping = 0.01 * stiffness` in hertz_contact follows the multibody code of the source
// paper (ADAMS, model units mm-kg-s): K read in N/mm^e gives C in N*s/mm. This returns the
// value of the word `stiffness` such that the expression comes out in N*s/m.
inline double adamsStiffness(double K, double exponent) { return K * std::pow(1e-3, exponent) * 1e3; }

} // namespace gbx::rt::dyn
