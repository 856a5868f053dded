#pragma once
// Exhaustive tooth-count synthesis (docs/language.md): every design that satisfies every
// rule, none invented, ranked by the objectives. Per-stage candidate lists are filtered
// by the rules that concern one stage; stages are joined by meet-in-the-middle over
// their exact ratios; `interchangeable` designs are counted once per orbit.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/Evaluator.h"
#include "model/Model.h"

namespace gbx::rt {

struct FunnelStep {
  std::string rule;    // the rule's source text or a named implicit rule
  std::string scope;   // stage name, or "" for the gearbox
  double before = 0;   // candidates (or combinations) that reached this rule
  double removed = 0;  // how many it removed
  bool domain = false; // the stage's candidate count before any rule (rule "domain")
};

struct Design {
  std::vector<int> choice;  // value index per slot
  Rational ratio;
  bool undecided = false;   // freedoms: neither a witness nor a refutation within the budget
  std::vector<double> keys; // objective values, minimised (maximised ones negated)
  // The continuous freedoms as decided (SI, model order): where every rule holds, best by
  // the objectives. Empty before deciding, or without freedoms.
  std::vector<double> freedoms;
};

// The ranked designs of a listing kept compact (SearchOptions::compact): each made when read.
class DesignList {
public:
  virtual ~DesignList() = default;
  virtual size_t size() const = 0;
  // Design i of the ranking into `out`, its vectors reused.
  virtual void get(size_t i, Design& out) const = 0;
  // Every design, made whole, in ranking order.
  std::vector<Design> all() const;
};

struct SearchOptions {
  int jobs = 1;
  std::optional<long long> top;  // how many designs to keep, ranked; nullopt: all
  // Called now and then with the fraction of the join done, from one thread, when the
  // join is large (over a million left entries or rows × columns).
  std::function<void(double)> progress;
  const ir::Expr* sortBy = nullptr;  // `report { sort by … }`: ranks before the objectives
  // Rules and objectives that need scenes or a baseline are left to the optimiser: the
  // search then lists every design that satisfies the others, unranked.
  bool deferDynamics = false;
  // Every design visited and keyed by the evaluator: no counting by arithmetic, no screen,
  // no bounds (what the pruned search is tested and benchmarked against).
  bool exhaustive = false;
  // The search budget (`--max-designs`): each stage's domain, and the product of the
  // stages' candidate lists the join would walk, counted before the work starts.
  double maxDesigns = 1e9;
  // Designs a search may keep for its report, with or without `top`; finding more is a
  // failure (a `top` beyond it is cut to it, so memory stays bounded).
  size_t maxKept = SIZE_MAX;
  // The ranked designs as a compact `listing` instead of `designs` (a long CSV listing
  // without freedoms: its rows are made one at a time as they are written).
  bool compact = false;
};

struct SearchResult {
  unsigned long long count = 0;      // feasible designs (orbits under `interchangeable`)
  unsigned long long undecided = 0;  // of which undecided
  std::vector<Design> designs;       // ranked, at most `top`
  std::shared_ptr<const DesignList> listing; // the same, compact, in their place (SearchOptions::compact)
  std::vector<FunnelStep> funnel;
  std::string window;                // the exact ratio window used, if any ("[579/100, 581/100]")
  std::vector<std::string> errors;   // rules or objectives the search cannot evaluate
  std::vector<std::string> deferred; // rules left to the optimiser (deferDynamics)
  std::vector<std::string> notes;    // candidates removed because a rule could not be evaluated for them
  // Set when the time limit stopped the work part way: how far it got and an estimate of the
  // whole. The count and the designs are then those of the part done (marked partial).
  std::string partial;
};

// An objective's value as the ranking compares it: to 12 significant digits, so values
// equal but for the rounding of their formulas tie.
double rankingKey(double v);

// True when a rule or objective of the gearbox needs a scene result or `relative(…)`.
bool needsOptimiser(const ir::Gearbox& g);
// True when one of them needs a scene result or `relative(…)` (the rest, `worst(…)` and
// `mean(…)` of catalogue quantities, are cheap at a point: the freedoms are decided instead).
bool needsScenes(const ir::Gearbox& g);
// Whether a rule or an objective reads a scene's result.
bool readsScenes(const ir::Gearbox& g);

SearchResult search(const Model& m, const SearchOptions& options);

} // namespace gbx::rt
