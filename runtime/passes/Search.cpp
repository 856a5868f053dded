#include "passes/Search.h"

#include <algorithm>
#include <atomic>
#include <map>

#include <fmt/format.h>

#include "catalogue/Budgets.h"
#include "model/Deadline.h"
#include "optimise/Decide.h"
#include "parallel/Ranks.h"
#include "passes/Designs.h"

namespace gbx::rt::passes {

namespace {
constexpr long long kDefaultTop = 50;

// Decides the freedoms of the designs not decided yet, `jobs` at a time.
void decideAll(const Model& m, const FreedomPlan& plan, const Design* first, const Design* last,
               std::map<std::vector<int>, DecidedPoint>& decided, int jobs) {
  std::vector<const Design*> open;
  for (const Design* d = first; d != last; ++d)
    if (!decided.count(d->choice)) open.push_back(d);
  std::vector<DecidedPoint> out(open.size());
  Evaluator ev(m);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next++; i < open.size(); i = next++) {
      if (Deadline::expired()) break;
      out[i] = plan.decide(ev, open[i]->choice);
    }
  };
  par::onThreads(std::max(1, std::min<int>(jobs, static_cast<int>(open.size()))), work);
  for (size_t i = 0; i < open.size(); ++i)
    decided.emplace(open[i]->choice, std::move(out[i]));
}

// Designs counted but not decided are decided too, for an exact count, when some design was
// removed by deciding and there are at most this many.
constexpr unsigned long long kDecideForCount = 2000;

// The time limit stopped the deciding: the designs decided so far, ranked, marked partial,
// with how far it got and an estimate of the whole.
SearchResult partialDecided(SearchResult r, const std::map<std::vector<int>, DecidedPoint>& decided,
                            long long want) {
  std::vector<Design> kept;
  for (auto& d : r.designs) {
    auto it = decided.find(d.choice);
    if (it == decided.end() || !it->second.feasible) continue;
    d.undecided = false;
    d.keys = it->second.keys;
    d.freedoms = it->second.freedoms;
    kept.push_back(std::move(d));
  }
  std::stable_sort(kept.begin(), kept.end(), [](const Design& x, const Design& y) { return compareKeys(x.keys, y.keys) < 0; });
  if (want >= 0 && kept.size() > static_cast<size_t>(want)) kept.resize(static_cast<size_t>(want));
  const double done = static_cast<double>(decided.size()), all = static_cast<double>(r.designs.size());
  std::string estimate =
      done > 0 ? fmt::format("; deciding all {:.0f} would take about {:.3g} s", all, Deadline::seconds() * all / done) : "";
  r.partial = fmt::format("time limit of {:g} s (--time-limit) reached while deciding the freedoms: {:.0f} of the {:.0f} "
                          "designs kept were decided{}; the best of those decided are listed, and a design not decided may "
                          "be better; raise --time-limit or narrow the ranges",
                          Deadline::seconds(), done, all, estimate);
  r.designs = std::move(kept);
  return r;
}

// docs/language.md: each design the search keeps gets its continuous freedoms decided, and
// is ranked by the objectives at that point. The search ranks by the best value over the
// whole box, a lower bound of the decided value (a design whose bound has no value comes
// first). Designs are decided in the search's order until the kth decided one ranks before
// the next one's bound: no design from there on can pass it. While that never happens
// within the designs the search kept, it keeps four times as many.
SearchResult decideFreedoms(const Model& m, SearchOptions so, SearchResult r, long long want,
                            const std::function<void(double)>& progress) {
  // The search ranked by lower bounds unless it deferred the rules it cannot bound (`worst`):
  // then every design it lists is decided.
  const bool bounded = !so.deferDynamics;
  std::map<std::vector<int>, DecidedPoint> decided;
  const FreedomPlan plan(m);
  const size_t batch = static_cast<size_t>(std::max(8, 4 * so.jobs));
  size_t examined = 0;
  auto decideInOrder = [&](bool all) {
    std::vector<const DecidedPoint*> ranked;
    size_t i = 0;
    while (i < r.designs.size()) {
      if (!all && bounded && want >= 0 && ranked.size() >= static_cast<size_t>(want) &&
          compareKeys(ranked[static_cast<size_t>(want) - 1]->keys, r.designs[i].keys) <= 0)
        return std::pair<size_t, bool>{i, true};
      size_t end = std::min(r.designs.size(), i + batch);
      decideAll(m, plan, r.designs.data() + i, r.designs.data() + end, decided, so.jobs);
      if (progress) progress(0.99 * static_cast<double>(end) / static_cast<double>(r.designs.size()));
      if (Deadline::expired()) return std::pair<size_t, bool>{end, true};
      // The best `want` decided so far, in order (a short sorted list).
      for (; i < end; ++i) {
        const auto& p = decided.at(r.designs[i].choice);
        if (!p.feasible || all || want < 0) continue;
        auto at = std::upper_bound(ranked.begin(), ranked.end(), &p, [](const DecidedPoint* x, const DecidedPoint* y) {
          return compareKeys(x->keys, y->keys) < 0;
        });
        if (ranked.size() < static_cast<size_t>(want) || at != ranked.end()) {
          ranked.insert(at, &p);
          if (ranked.size() > static_cast<size_t>(want)) ranked.pop_back();
        }
      }
    }
    return std::pair<size_t, bool>{i, false};
  };
  auto widen = [&](unsigned long long to) {
    so.top = static_cast<long long>(std::min<unsigned long long>(to, so.maxKept));
    SearchResult again = rt::search(m, so);
    if (!again.errors.empty()) return false;
    r = std::move(again);
    return true;
  };
  for (;;) {
    auto [upTo, settled] = decideInOrder(false);
    examined = upTo;
    if (Deadline::expired()) return partialDecided(std::move(r), decided, want);
    if (settled || r.designs.size() >= r.count || want < 0) break;
    unsigned long long more = std::min<unsigned long long>(r.designs.size() * 4ULL, so.maxKept);
    if (more <= r.designs.size() || !widen(more)) {
      r.notes.push_back(
          fmt::format("the best {} designs are ranked among the {} whose freedoms were decided; more would "
                      "exceed the designs a search may keep",
                      want, r.designs.size()));
      break;
    }
  }
  // A count that includes designs not decided is exact only if deciding removes none of them.
  size_t removed = 0;
  for (size_t i = 0; i < examined; ++i)
    removed += decided.at(r.designs[i].choice).feasible ? 0 : 1;
  bool uncertain = removed > 0 || r.undecided > 0;
  if (uncertain && examined < r.count) {
    if (r.count <= kDecideForCount && (r.designs.size() >= r.count || widen(r.count))) {
      examined = decideInOrder(true).first;
    } else {
      r.notes.push_back(
          fmt::format("{} of the {} designs counted had their freedoms decided; deciding removed {} of them, so the "
                      "count is an upper bound",
                      examined, r.count, removed));
    }
  }
  // Each design at its decided point; those with none are eliminated, by the rule that fails
  // nearest to feasibility. Designs past the bound are counted, not listed.
  std::vector<Design> kept;
  std::map<std::string, double> removedBy;
  std::vector<std::string> order;
  unsigned long long examinedUndecided = 0;
  for (size_t i = 0; i < examined; ++i) {
    Design& d = r.designs[i];
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
  double before = static_cast<double>(examined);
  for (const auto& rule : order) {
    FunnelStep step;
    step.rule = rule;
    step.scope = m.freedoms.empty() ? "tolerances" : "freedoms";
    step.before = before;
    step.removed = removedBy[rule];
    before -= step.removed;
    r.funnel.push_back(step);
  }
  r.count -= static_cast<unsigned long long>(examined - kept.size());
  r.undecided -= std::min(r.undecided, examinedUndecided);
  if (want >= 0 && kept.size() > static_cast<size_t>(want)) kept.resize(static_cast<size_t>(want));
  r.designs = std::move(kept);
  return r;
}

// Whether the design table's rows are points made one at a time (no column, sort key or
// study output reads a scene, a baseline or the scatter), as a compact listing's must be.
bool pointRows(const ir::Gearbox& gb) {
  auto dynamic = [](const ir::Expr* e) {
    return ir::uses(e, {ir::Op::SceneOutput, ir::Op::Relative, ir::Op::Scatter});
  };
  for (const auto* e : reportColumns(gb).exprs)
    if (dynamic(e)) return false;
  if (gb.report && dynamic(gb.report->sortBy.get())) return false;
  for (const auto& st : gb.studies)
    for (const auto& o : st.outputs)
      if (ir::uses(o.get(), {ir::Op::Relative})) return false;
  return true;
}

} // namespace

SearchResult search(const Model& m, int jobs, double maxDesigns, std::function<void(double)> progress,
                    std::function<void(double)> deciding, bool compact) {
  const ir::Gearbox& gb = m.gearbox;
  SearchOptions so;
  so.compact = compact && m.freedoms.empty() && !needsOptimiser(gb) && pointRows(gb);
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
  // Over freedoms the search ranks by bounds, and deciding the best designs usually reaches
  // past the first `top` of them: four times as many are kept at once (one search, not two).
  if (!m.freedoms.empty() && so.top && *so.top > 0)
    so.top = std::min<long long>(*so.top * 4, static_cast<long long>(so.maxKept));
  SearchResult r = rt::search(m, so);
  // Stopped part way through the join: the designs of the part walked are exact points
  // without freedoms; with freedoms none was decided, so none is listed.
  if (!r.partial.empty()) {
    if (!m.freedoms.empty() || needsOptimiser(gb)) r.designs.clear();
    return r;
  }
  // A rule over tolerance corners (`worst`) without freedoms is checked the same way, at the
  // design's one point.
  if ((m.freedoms.empty() && !needsOptimiser(gb)) || !r.errors.empty() || needsScenes(gb)) return r;
  long long keep = gb.report && gb.report->top ? *gb.report->top : kDefaultTop;
  SearchResult decided = decideFreedoms(m, so, std::move(r), keep, deciding);
  if (deciding) deciding(1.0);
  return decided;
}

} // namespace gbx::rt::passes
