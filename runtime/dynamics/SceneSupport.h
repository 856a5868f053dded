#pragma once
// Pieces shared by the scene models: the time plan, the drive, effect settings.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "dynamics/Drive.h"
#include "ir/Ir.h"
#include "search/Value.h"

namespace gbx::rt::dyn {

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
double settingValue(const ir::Setting& s, const std::map<std::string, double>& locals);
const ir::Setting* effectParam(const ir::Effect* e, const char* name);
const ir::Effect* findEffect(const ir::Scene& scene, const char* name);
// `damping = 0.01 * stiffness` in hertz_contact follows the multibody code of the source
// paper (ADAMS, model units mm-kg-s): K read in N/mm^e gives C in N*s/mm. This returns the
// value of the word `stiffness` such that the expression comes out in N*s/m.
inline double adamsStiffness(double K, double exponent) { return K * std::pow(1e-3, exponent) * 1e3; }
// A fluctuation's angular frequency in rad/s (given as an angular speed or in Hz).
double angularFrequency(const ir::Setting& s);

} // namespace gbx::rt::dyn
