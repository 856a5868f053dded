#include "passes/Search.h"

#include "catalogue/Budgets.h"

namespace gbx::rt::passes {

namespace {
constexpr long long kDefaultTop = 50;
}

SearchResult search(const Model& m, int jobs, double maxDesigns, std::function<void(double)> progress) {
  const ir::Gearbox& gb = m.gearbox;
  SearchOptions so;
  so.jobs = jobs;
  so.maxDesigns = maxDesigns;
  so.top = gb.report && gb.report->top ? *gb.report->top : kDefaultTop;
  if (gb.report && gb.report->sortBy) so.sortBy = gb.report->sortBy.get();
  so.progress = std::move(progress);
  if (needsOptimiser(gb)) {
    so.deferDynamics = true;
    so.top = std::nullopt;
  }
  so.maxKept = static_cast<size_t>(cat::budget::kKeptDesigns);
  return rt::search(m, so);
}

} // namespace gbx::rt::passes
