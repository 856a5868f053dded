#pragma once
// Deciding a design's continuous freedoms (docs/language.md): the point of the freedoms'
// box where every rule holds that ranks best by the objectives (with none, the feasible
// point nearest the middle of the box), or the rule that no point satisfies.
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "model/Evaluator.h"

namespace gbx::rt {

struct DecidedPoint {
  bool feasible = false;
  std::vector<double> freedoms;   // SI, in model.freedoms order; the printed values when they hold
  std::vector<double> keys;       // the ranking keys there (sort by, then objectives; minimised)
  std::vector<double> objectives; // the objectives there (minimised), which chose the point
  std::string rule;               // infeasible: the rule that fails nearest to feasibility
  long evaluations = 0;
};

// The ranking keys of a design at an assignment whose freedoms are points: `sort by` first
// (unless `withSortBy` is false), then each objective, maximised ones negated. NaN where a
// key has no value.
std::vector<double> rankingKeys(const Evaluator& ev, const Assignment& a, bool withSortBy = true);

// Lexicographic order of ranking keys, each compared to 12 significant digits (the search's
// rule: a formula's rounding does not rank two designs).
int compareKeys(const std::vector<double>& x, const std::vector<double>& y);

// The freedoms decided together: all of them, or one stage's where every rule reads the
// freedoms of one stage at most and the objective is a sum of terms that each do.
// One part of a rule (a conjunct of its `and` or `forall`): what a group decides by, so that
// `forall s in stages: …` decides each stage on its own.
struct RulePart {
  const ir::Expr* expr = nullptr;
  std::string text;
};

struct FreedomGroup {
  int stage = -1;                                        // -1: every freedom of the design
  std::vector<int> freedoms;                             // indices in model.freedoms
  std::vector<RulePart> rules;                           // the rules' parts that read them
  bool allObjectives = false;                            // chosen by every objective; else by `terms`
  std::vector<std::pair<const ir::Expr*, double>> terms; // the objective's terms that read them, signed
  bool cacheable = false; // reads nothing but its own stage: the same for the same choices of it
};

// How a model's freedoms are decided, made once per gearbox; its cache of per-stage decisions
// is shared by the threads that decide.
class FreedomPlan {
public:
  explicit FreedomPlan(const Model& m);
  DecidedPoint decide(const Evaluator& ev, const std::vector<int>& choice) const;
  std::vector<FreedomGroup> groups;

private:
  const Model& m_;
  // One objective, every group read only its own stage: a design's objective is the sum of its
  // groups' decided terms and the terms on no freedom.
  bool separable_ = false;
  std::vector<std::pair<const ir::Expr*, double>> freeTerms_;
  std::vector<RulePart> parts_;       // every rule's parts (`and`, `forall`), in order
  std::vector<RulePart> rest_;        // the parts that read no group's freedoms
  mutable std::mutex mutex_;
  mutable std::map<std::vector<int>, DecidedPoint> cache_;
};

} // namespace gbx::rt
