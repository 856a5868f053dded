#pragma once
// Monte Carlo over the tolerances (docs/optimisation.md) at design 1. The scenes that sampled
// quantities read run once per sample, shared over the threads and the ranks; the columns
// and the Monte Carlo report read those runs.
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "passes/Designs.h"
#include "report/Report.h"

namespace gbx::rt::passes {

class SampleScenes {
public:
  // Runs, for every sample, each scene that a sampled quantity of `exprs` reads; `nominal`
  // are the scenes' runs at the nominal design (their outputs' names and order).
  SampleScenes(const Model& m, const Assignment& best, const std::vector<const ir::Expr*>& exprs,
               const std::vector<dyn::SceneResult>& nominal, int jobs);
  // The scene at the sample whose deviations `asking` carries; null where it did not run.
  const dyn::SceneResult* find(int scene, const Evaluator& asking) const;

private:
  std::map<std::vector<double>, long> sampleOf_;
  std::map<int, std::vector<dyn::SceneResult>> runs_;
};

// What a Monte Carlo part reads over the samples: the report's columns, the rules and the
// objectives.
std::vector<const ir::Expr*> sampledExpressions(const ir::Gearbox& g, const Columns& columns);

// The quantities under `worst`, `mean` and `quantile` in the columns, the rules and the
// objectives, each at every sample, with their statistics; nothing without `samples`.
std::optional<MonteCarloReport> monteCarlo(const Model& m, const Assignment& best, const Columns& columns,
                                           const SampleScenes* scenes, const std::vector<dyn::SceneResult>& nominal);

} // namespace gbx::rt::passes
