#pragma once
// Design optimisation with continuous freedoms (helix angle, profile shifts) inside every
// integer candidate, objectives over scene results and `relative(…)` to the baseline.
#include <functional>
#include <string>
#include <vector>

#include "model/Model.h"
#include "search/Search.h"

namespace gbx::rt {

struct OptimiseOptions {
  int jobs = 1;
  double sceneRtol = 1e-7;  // scenes inside the objective: ranking-stable, checked afterwards
  size_t rankCheck = 5;     // re-rank the best this many at the scene's own tolerance
  int maxIterations = 160;
  std::function<void(double)> progress;
};

struct OptCandidate {
  std::vector<int> choice;       // integer decisions
  Rational ratio;
  std::vector<double> freedoms;  // optimum, SI, in model.freedoms order
  double objective = 0;
  std::vector<double> terms;     // the quantities under relative(…), absolute
  bool feasible = false;
  long evaluations = 0;
};

struct OptimiseResult {
  std::vector<OptCandidate> ranked;  // feasible first, best first
  size_t infeasible = 0;
  std::vector<std::string> termNames;
  std::vector<double> baselineTerms;
  std::vector<std::pair<double, double>> cloud, pareto;  // relative terms of feasible evaluations; non-dominated ones
  std::string rankCheck;
  long evaluations = 0;
  double cpuSeconds = 0;
  std::string error;
};

// `candidates` from a search with deferDynamics; `baseline` the gearbox this one extends.
OptimiseResult optimise(const Model& m, const Model* baseline, const Assignment* baselineDesign, const std::vector<Design>& candidates,
                        const OptimiseOptions& options);

// Installs scene and baseline hooks on an evaluator (scenes at `rtol`).
void installHooks(class Evaluator& ev, const Model& m, const Model* baseline, const Assignment* baselineDesign, double rtol);
// The scenes' own tolerance (the first scene's rtol), at which chosen designs are reported.
double ownSceneRtol(const Model& m);

} // namespace gbx::rt
