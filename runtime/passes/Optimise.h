#pragma once
// Pass 2, optimisation: when objectives or rules need scenes or a baseline, the optimum of
// the continuous freedoms inside every candidate; the ranked optima become the design list.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "report/Report.h"
#include "search/Search.h"

namespace gbx::rt::passes {

struct Optimised {
  SearchResult designs;                       // the search's, or the ranked optima
  std::vector<std::vector<double>> freedoms;  // each design's optimum freedoms, SI; empty when not optimised
  std::unique_ptr<Model> baseline;            // the gearbox `relative(…)` compares with
  std::unique_ptr<Assignment> baselineDesign;
  std::optional<OptimisationSummary> summary;
};

// `maxIterations` > 0 caps the optimiser's iterations per candidate (a test setting).
Optimised optimise(const ir::Program& program, const Model& m, SearchResult found, int jobs, std::function<void(double)> progress,
                   int maxIterations = 0);

} // namespace gbx::rt::passes
