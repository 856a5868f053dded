#pragma once
// The orbit of a stage's scene by harmonic balance (`steady_state = harmonic_balance`), as the
// single-mesh and the planetary scenes take it: with the scene's `harmonics`, or doubled from 2
// until the orbit's truncation is below rtol. An orbit that is not found, or whose stability is
// not, is not taken: the scene then finds it by shooting, and the model's line says why.
#include <optional>
#include <string>
#include <vector>

#include "dynamics/HarmonicBalance.h"
#include "dynamics/SceneSupport.h"

namespace gbx::rt::dyn {

struct SceneBalance {
  std::optional<BalanceOrbit> orbit; // empty: not found
  std::string line;                  // for the model: the orbit found, or why not
  std::string warning;               // the target not met within the Newton system's size
  Stats stats;                       // every attempt's
  bool chosen = false;               // N chosen for rtol (the scene writes no `harmonics`)
};

// `options` gives the period, the drift, linearity and the stability's accuracy; `state` is
// the model's initial state (the guess unless the caller gives one); `meshPeriods` the orbit's
// period in mesh periods, for the line.
SceneBalance sceneBalance(const System& sys, BalanceOptions options, const ScenePlan& scene, const SceneOverrides& ov,
                          double rtol, const std::vector<double>& state, long maxUnknowns, long meshPeriods);

} // namespace gbx::rt::dyn
