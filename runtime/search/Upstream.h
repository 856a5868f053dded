#pragma once
// Rules of a downstream stage that read only its own choices and its operating point. The
// rest of a design reaches them through the ratio upstream of the stage alone (its speed is
// the input speed over it, its torque the input torque times it), so for each of the
// stage's candidates they are asked once over the upstream ratios its designs can have, not
// once per design: a safety falls as the upstream ratio raises the stage's torque, and where
// it crosses its limit is found by bisection. The join then compares a design's upstream
// ratio with the candidate's bracket and asks the design itself only inside it.
#include <functional>
#include <utility>
#include <vector>

#include "search/Conjuncts.h"
#include "search/StageFilter.h"

namespace gbx::rt {

// What a rule says of one candidate over the upstream ratio U: `below` at U <= lo, `above`
// at U >= hi; between them (within 1e-7 of U) the design is asked.
struct Bracket {
  double lo = -INFINITY, hi = INFINITY;
  bool below = false, above = false;
  // 1: holds, 0: fails, -1: ask the design.
  int at(double u) const {
    if (u <= lo * (1 - 1e-12)) return below ? 1 : 0;
    if (u >= hi * (1 + 1e-12)) return above ? 1 : 0;
    return -1;
  }
};

struct UpstreamStage {
  int stage = -1;
  std::vector<const Conjunct*> rules;         // in the search's order of cross rules
  std::vector<std::vector<Bracket>> brackets; // per candidate, per rule
};

// Brackets of `rules` for each candidate of stage s whose upstream range (`range`, per
// candidate; empty where no design reaches it) is not empty; first each candidate's
// freedoms narrowed (search/Narrow.h) by them and by its own rules over freedoms (`own`)
// at the least upstream ratio of its range, where they are easiest to meet. `place` puts a
// candidate into an assignment.
UpstreamStage bracketStage(const Evaluator& ev, int s, std::vector<Candidate>& candidates,
                           const std::vector<const Conjunct*>& rules, const std::vector<const Conjunct*>& own,
                           const std::vector<std::pair<double, double>>& range,
                           const std::function<void(Assignment&, size_t)>& place, int jobs);

} // namespace gbx::rt
