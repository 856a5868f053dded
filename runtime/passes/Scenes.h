#pragma once
// Pass 4, scenes: every `scene` of the gearbox run on the best design.
#include <string>
#include <vector>

#include "passes/Designs.h"
#include "report/Report.h"

namespace gbx::rt::passes {

struct SceneRuns {
  std::vector<SceneReport> scenes;
  std::vector<SceneColumn> columns;  // report columns that are scene results
  std::vector<std::string> errors;
  std::vector<std::string> notes;    // where each `worst(…)` of a scene result is found
};

SceneRuns scenes(const Model& m, const Assignment& best, const Columns& columns);

} // namespace gbx::rt::passes
