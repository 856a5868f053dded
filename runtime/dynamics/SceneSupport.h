#pragma once
// Pieces shared by the scene models: the time plan, the drive, effect settings.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <array>
#include <optional>

#include "dynamics/Drive.h"
#include "ir/Ir.h"
#include "model/Value.h"

namespace gbx::rt::dyn {

using cat::Q;

// What a study changes in a scene: harmonics, method, tolerance; whether to estimate the
// error and keep the series.
struct SceneOverrides {
  std::optional<int> harmonics;
  std::optional<cat::Method> method;
  std::optional<double> rtol;
  bool estimateError = true;
  bool keepSeries = true;
};

// Recorded samples of every signal of a scene, by signal.
inline constexpr size_t kSignalCount = static_cast<size_t>(cat::Signal::Modes) + 1;
using SignalSeries = std::array<std::vector<double>, kSignalCount>;
inline std::vector<double>& series(SignalSeries& s, cat::Signal id) { return s[static_cast<size_t>(id)]; }

struct SceneFailure {
  std::string what;
};

struct TimePlan {
  double end = 0, statsFrom = 0, dt = 0;
  std::vector<double> samples;  // exactly `samples` per mesh period
};

// A number the model needs: its value, or a SceneFailure naming what is missing.
double needNumber(const Value& v, const std::string& what);

TimePlan timePlan(const ir::Scene& scene, double meshPeriod);
Drive sceneDrive(const ir::Scene& scene, double nominal, double upstream, double meshPeriod);
// A setting's SI value; `locals` are the values of the effect's own words (`stiffness`).
double settingValue(const ir::Setting& s, const std::vector<double>& locals = {});
const ir::Setting* effectParam(const ir::Effect* e, Q key);
// `damping = 0.01 * stiffness` in hertz_contact follows the multibody code of the source
// paper (ADAMS, model units mm-kg-s): K read in N/mm^e gives C in N*s/mm. This returns the
// value of the word `stiffness` such that the expression comes out in N*s/m.
inline double adamsStiffness(double K, double exponent) { return K * std::pow(1e-3, exponent) * 1e3; }
// A fluctuation's angular frequency in rad/s (given as an angular speed or in Hz).
double angularFrequency(const ir::Setting& s);

} // namespace gbx::rt::dyn
