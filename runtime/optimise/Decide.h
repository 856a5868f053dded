#pragma once
// Deciding a design's continuous freedoms (LANGUAGE.md §15): the point of the freedoms'
// box where every rule holds that ranks best by the objectives (with none, the feasible
// point nearest the middle of the box), or the rule that no point satisfies.
#include <string>
#include <vector>

#include "model/Evaluator.h"

namespace gbx::rt {

struct DecidedPoint {
  bool feasible = false;
  std::vector<double> freedoms; // SI, in model.freedoms order; the printed values when they hold
  std::vector<double> keys;     // the ranking keys there (sort by, then objectives; minimised)
  std::string rule;             // infeasible: the rule that fails nearest to feasibility
  long evaluations = 0;
};

// The ranking keys of a design at an assignment whose freedoms are points: `sort by` first,
// then each objective, maximised ones negated. NaN where a key has no value.
std::vector<double> rankingKeys(const Evaluator& ev, const Assignment& a);

// Lexicographic order of ranking keys, each compared to 12 significant digits (the search's
// rule: a formula's rounding does not rank two designs).
int compareKeys(const std::vector<double>& x, const std::vector<double>& y);

// The freedoms of the design `choice` decided. The decided values are rounded to the digits
// a report prints (4 decimals in the display unit) where the rounded point still satisfies
// every rule, so that the design written with those values reproduces every number.
DecidedPoint decideFreedoms(const Evaluator& ev, const std::vector<int>& choice);

} // namespace gbx::rt
