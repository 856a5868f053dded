#include "passes/Search.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <thread>

#include <fmt/format.h>

#include "catalogue/Budgets.h"
#include "model/Deadline.h"
#include "optimise/Decide.h"

namespace gbx::rt::passes {

namespace {
constexpr long long kDefaultTop = 50;

// Decides the freedoms of the designs not decided yet, `jobs` at a time.
void decideAll(const Model& m, const std::vector<Design>& designs, std::map<std::vector<int>, DecidedPoint>& decided,
               int jobs) {
  std::vector<const Design*> open;
  for (const auto& d : designs)
    if (!decided.count(d.choice)) open.push_back(&d);
  std::vector<DecidedPoint> out(open.size());
  Evaluator ev(m);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next++; i < open.size(); i = next++) {
      if (Deadline::expired()) break;
      out[i] = decideFreedoms(ev, open[i]->choice);
    }
  };
  int threads = std::max(1, std::min<int>(jobs, static_cast<int>(open.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(work);
  work();
  for (auto& th : pool)
    th.join();
  for (size_t i = 0; i < open.size(); ++i)
    decided.emplace(open[i]->choice, std::move(out[i]));
}

// LANGUAGE.md §15: each design the search keeps gets its continuous freedoms decided, and
// is ranked by the objectives at that point. The search ranks by the best value over the
// whole box, a lower bound of the decided value: while the kth decided design could still
// be passed by one the search did not keep, the search keeps more (four times as many).
SearchResult decideFreedoms(const Model& m, SearchOptions so, SearchResult r) {
  const long long want = so.top ? *so.top : -1;
  std::map<std::vector<int>, DecidedPoint> decided;
  for (;;) {
    decideAll(m, r.designs, decided, so.jobs);
    if (Deadline::expired()) return r;
    size_t feasible = 0;
    for (const auto& d : r.designs)
      feasible += decided.at(d.choice).feasible ? 1 : 0;
    bool everyDesign = r.designs.size() >= r.count;
    if (everyDesign || want < 0) break;
    // The decided designs ranked; the kth is settled when no design left out, whose key is
    // at least the last kept one's bound, can rank before it.
    std::vector<const DecidedPoint*> ranked;
    for (const auto& d : r.designs)
      if (const auto& p = decided.at(d.choice); p.feasible) ranked.push_back(&p);
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const DecidedPoint* x, const DecidedPoint* y) { return compareKeys(x->keys, y->keys) < 0; });
    if (feasible >= static_cast<size_t>(want) &&
        compareKeys(ranked[static_cast<size_t>(want) - 1]->keys, r.designs.back().keys) <= 0)
      break;
    long long more =
        std::min<long long>(static_cast<long long>(r.designs.size()) * 4, static_cast<long long>(so.maxKept));
    if (more <= static_cast<long long>(r.designs.size())) {
      r.notes.push_back(
          fmt::format("the best {} designs are ranked among the {} whose freedoms were decided; more would "
                      "exceed the designs a search may keep",
                      want, r.designs.size()));
      break;
    }
    so.top = more;
    SearchResult again = rt::search(m, so);
    if (!again.errors.empty()) return again;
    r = std::move(again);
  }
  // Each design at its decided point; those with none are eliminated, by the rule that fails
  // nearest to feasibility.
  std::vector<Design> kept;
  std::map<std::string, double> removedBy;
  std::vector<std::string> order;
  unsigned long long examinedUndecided = 0;
  for (auto& d : r.designs) {
    const DecidedPoint& p = decided.at(d.choice);
    examinedUndecided += d.undecided ? 1 : 0;
    if (!p.feasible) {
      if (!removedBy.count(p.rule)) order.push_back(p.rule);
      removedBy[p.rule] += 1;
      continue;
    }
    d.undecided = false;
    d.keys = p.keys;
    d.freedoms = p.freedoms;
    kept.push_back(std::move(d));
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Design& x, const Design& y) { return compareKeys(x.keys, y.keys) < 0; });
  const double examined = static_cast<double>(r.designs.size());
  double before = examined;
  for (const auto& rule : order) {
    FunnelStep step;
    step.rule = rule;
    step.scope = "freedoms";
    step.before = before;
    step.removed = removedBy[rule];
    before -= step.removed;
    r.funnel.push_back(step);
  }
  r.count -= static_cast<unsigned long long>(examined - static_cast<double>(kept.size()));
  r.undecided -= std::min(r.undecided, examinedUndecided);
  if (want >= 0 && kept.size() > static_cast<size_t>(want)) kept.resize(static_cast<size_t>(want));
  r.designs = std::move(kept);
  return r;
}
} // namespace

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
  SearchResult r = rt::search(m, so);
  if (so.deferDynamics || m.freedoms.empty() || !r.errors.empty()) return r;
  return decideFreedoms(m, so, std::move(r));
}

} // namespace gbx::rt::passes
