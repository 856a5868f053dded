#include "dynamics/SceneBalance.h"

#include <cmath>

#include <fmt/format.h>

namespace gbx::rt::dyn {

SceneBalance sceneBalance(const System& sys, BalanceOptions options, const ScenePlan& scene, const SceneOverrides& ov,
                          double rtol, const std::vector<double>& state, long maxUnknowns, long meshPeriods) {
  SceneBalance b;
  // An override of 0: chosen for the target whatever the scene writes (a work-precision curve).
  const int N = ov.balanceHarmonics ? *ov.balanceHarmonics : scene.balanceHarmonics.value_or(0);
  const std::vector<double>& guess = ov.guess && ov.guess->size() == state.size() ? *ov.guess : state;
  const Eigen::MatrixXd* start =
      ov.balanceStart && ov.balanceStart->cols() == static_cast<long>(state.size()) ? ov.balanceStart : nullptr;
  BalanceOrbit o;
  b.chosen = N <= 0;
  if (N > 0) {
    options.harmonics = N;
    o = harmonicBalance(sys, options, guess, start);
  } else {
    o = harmonicBalanceTo(sys, options, rtol, guess, 2, maxUnknowns, start);
  }
  b.stats = o.stats;
  if (o.converged && !std::isfinite(o.stability)) {
    o.converged = false;
    o.failure = "its stability " + o.stabilityMethod;
  }
  if (!o.converged) {
    b.line = fmt::format("harmonic balance with {} harmonics did not find the orbit ({}): shooting instead",
                         o.harmonics, o.failure);
    return b;
  }
  if (N <= 0 && !(o.truncation <= rtol))
    b.warning =
        fmt::format("scene `{}`: harmonic balance stopped at {} harmonics (the Newton system's size), where the orbit "
                    "still moves by {:.2e} of its scale against half as many; write `harmonics` or loosen rtol",
                    scene.name, o.harmonics, o.truncation);
  b.line = fmt::format(
      "periodic steady state: period {:.6g} ms ({} mesh period{}), harmonic balance with {} harmonics at {} instants, "
      "{} Newton "
      "iteration{}, residual between the instants {:.2e} of the state's rate{}, largest Floquet multiplier {:.6f} ({})",
      options.period * 1e3, meshPeriods, meshPeriods == 1 ? "" : "s", o.harmonics, o.timePoints, o.iterations,
      o.iterations == 1 ? "" : "s", o.gapResidual,
      !std::isfinite(o.truncation) ? ""
      : o.truncation <= rtol       ? fmt::format(", {:.2e} of the state scale from twice the harmonics", o.truncation)
                                   : fmt::format(", {:.2e} of the state scale from half the harmonics", o.truncation),
      o.stability, o.stabilityMethod);
  b.orbit = std::move(o);
  return b;
}

} // namespace gbx::rt::dyn
