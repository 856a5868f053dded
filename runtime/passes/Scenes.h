#pragma once
// Pass 4, scenes: every `scene` of the gearbox run on the best design.
#include <memory>
#include <string>
#include <vector>

#include "passes/Designs.h"
#include "passes/Samples.h"
#include "report/Report.h"

namespace gbx::rt::passes {

struct SceneRuns {
  std::vector<SceneReport> scenes;
  std::vector<SceneColumn> columns;  // report columns that are scene results
  std::vector<std::string> errors;
  std::vector<std::string> notes;    // where each `worst(…)` of a scene result is found
  std::vector<dyn::SceneResult> results;  // each scene's run at the nominal design
  std::shared_ptr<const SampleScenes> samples;  // their runs at the Monte Carlo samples
};

// jobs: the threads the Monte Carlo samples' scenes share (with the ranks under mpirun).
SceneRuns scenes(const Model& m, const Assignment& best, const Columns& columns, int jobs = 1);

} // namespace gbx::rt::passes
