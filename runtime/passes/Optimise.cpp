#include "passes/Optimise.h"

#include <chrono>

#include "optimise/Optimise.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

Optimised optimise(const ir::Program& program, const Model& m, SearchResult found, int jobs, std::function<void(double)> progress) {
  const ir::Gearbox& gb = m.gearbox;
  Optimised out;
  out.designs = std::move(found);
  if (!needsOptimiser(gb)) return out;
  for (const auto& other : program.gearboxes)
    if (other.name == gb.baseline) {
      out.baseline = std::make_unique<Model>(program, other);
      SearchOptions bo;
      bo.top = 1;
      bo.deferDynamics = true;
      auto br = rt::search(*out.baseline, bo);
      if (!br.designs.empty()) {
        out.baselineDesign = std::make_unique<Assignment>(*out.baseline);
        out.baselineDesign->choice = br.designs[0].choice;
      }
    }
  OptimiseOptions oo;
  oo.jobs = jobs;
  oo.progress = std::move(progress);
  auto wall0 = std::chrono::steady_clock::now();
  OptimiseResult opt = rt::optimise(m, out.baseline.get(), out.baselineDesign.get(), out.designs.designs, oo);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  // The ranked optima become the design list.
  SearchResult& r = out.designs;
  size_t keep = gb.report && gb.report->top ? static_cast<size_t>(*gb.report->top) : 10;
  r.count = opt.ranked.size();
  r.designs.clear();
  for (size_t i = 0; i < opt.ranked.size() && i < keep; ++i) {
    Design d;
    d.choice = opt.ranked[i].choice;
    d.ratio = opt.ranked[i].ratio;
    d.keys = {opt.ranked[i].objective};
    r.designs.push_back(d);
    out.freedoms.push_back(opt.ranked[i].freedoms);
  }
  OptimisationSummary& s = out.summary.emplace();
  s.candidates = opt.ranked.size() + opt.infeasible;
  s.infeasible = opt.infeasible;
  s.evaluations = opt.evaluations;
  s.sceneRtol = oo.sceneRtol;
  s.baseline = gb.baseline;
  s.termNames = opt.termNames;
  s.baselineTerms = opt.baselineTerms;
  if (!opt.ranked.empty()) {
    const auto& best = opt.ranked[0];
    OptimisationSummary::Optimum& b = s.best.emplace();
    b.ratio = best.ratio;
    for (size_t f = 0; f < m.freedoms.size() && f < best.freedoms.size(); ++f) {
      const ir::Attribute* at = m.attribute(m.freedoms[f].stage, m.freedoms[f].gear, m.freedoms[f].key);
      b.freedoms.push_back({m.freedoms[f].path, best.freedoms[f], units::displayUnitFor(at ? at->dim : units::Dim{})});
    }
    b.objective = best.objective;
    b.terms = best.terms;
  }
  s.rankCheck = opt.rankCheck;
  s.cloud = opt.cloud;
  s.pareto = opt.pareto;
  s.wallSeconds = wall;
  s.jobs = jobs;
  return out;
}

} // namespace gbx::rt::passes
