#include "passes/Search.h"

#include <fmt/format.h>

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
  // What is kept is bounded, whatever `top` says: a ranking holds at most one design more
  // than the budget, and finding that many is a clear failure instead of memory spent.
  const auto kept = static_cast<long long>(cat::budget::kKeptDesigns);
  const bool capped = so.top && *so.top > kept;
  if (capped) so.top = kept + 1;
  so.maxKept = static_cast<size_t>(kept);
  SearchResult res = rt::search(m, so);
  if (capped && res.designs.size() > static_cast<size_t>(kept)) {
    res.errors.push_back(fmt::format("{} designs satisfy the rules, more than the {} a report can list (the budget of kept "
                                     "designs); ask for fewer with `report {{ top N; }}`, or narrow the ranges",
                                     res.count, kept));
    std::vector<Design>().swap(res.designs);
  }
  return res;
}

} // namespace gbx::rt::passes
