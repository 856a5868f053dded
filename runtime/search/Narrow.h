#pragma once
// A candidate's continuous freedom narrowed to where its rules can hold. The search ranks a
// design with freedoms by the best value its objectives reach over the box (a lower bound of
// the value at its decided point); over the part of the range where the rules can hold,
// that bound is the decided value itself wherever the objective is monotone in the freedom
// and one rule binds, as a face width sized by its safeties is.
#include <utility>
#include <vector>

#include "search/Conjuncts.h"

namespace gbx::rt {

// The range of freedom f (a.box[f] on entry, restored on return) with its ends moved inward
// past the parts where some rule fails at every point. The rules are asked at points of f
// (the other freedoms over their box): samples (either side of each point where a tolerance
// table jumps among them, model/ToleranceEdges.h), then bisection to 1e-4 of the range between
// a failing and a passing one, then probes at halving distances below (above) the edge for a
// passing island left by a factor read from a table, whose own edge is found in turn. The
// ends returned fail (or are the range's own): the narrowed range holds every passing point
// the probes can see. The whole range where no sample passes.
std::pair<double, double> feasibleSpan(const Evaluator& ev, Assignment& a, const std::vector<const Conjunct*>& rules,
                                       int f);

} // namespace gbx::rt
