// One stage's candidates: every combination of its decisions' values that its own rules
// (and its kind's) do not remove, sorted by exact ratio, with the funnel of what removed the rest.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "search/Conjuncts.h"
#include "search/Search.h"

namespace gbx::rt {

struct Candidate {
  std::vector<int> idx; // value index per slot of the stage
  Rational ratio;
  double r = 0;
  bool undecided = false;
  // Per freedom of the stage (its order): the range where its rules can hold; empty for the
  // whole box.
  std::vector<std::pair<double, double>> box;
};

struct StageResult {
  std::vector<Candidate> candidates;
  std::vector<FunnelStep> funnel;
  std::vector<std::string> notes;
  double timedOutAt = -1;  // the fraction visited when the time limit stopped the filter
};

// `s1.pinion.z` 1..1000000 (1000000 values) × …: the ranges that make a stage's domain.
std::string stageRanges(const Model& m, int s);

// The candidates of stage s before its rules: the product of its decisions' value counts.
double stageDomain(const Model& m, int s);

std::string timeLimitMessage(const std::string& doing, double done, double limit, double space);

// With `narrow`, each candidate's freedoms are narrowed to where its rules can hold
// (search/Narrow.h).
StageResult filterStage(const Evaluator& ev, int s, const std::vector<const Conjunct*>& local, int jobs, bool narrow);

} // namespace gbx::rt
