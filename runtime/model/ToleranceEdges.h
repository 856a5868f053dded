#pragma once
// Where a continuous freedom makes a rating jump. The deviations a rating reads from a
// stage's accuracy grade are ISO 1328's tables, by ranges of module, reference diameter and
// face width, so a safety is piecewise smooth in a freedom that moves one of them: it drops
// where the face width passes 80 mm, say, and a range of face widths that meets a rule can
// end just below such a point with none beside it. Whoever searches a freedom's range
// samples these points, and then every gap between samples lies within one table range.
#include <utility>
#include <vector>

#include "model/Evaluator.h"

namespace gbx::rt {

// The values of freedom f, inside its box in `a`, where a gear's module, reference
// diameter or face width crosses a bound of ISO 1328's ranges, at the design `a` (its other
// quantities at their middle), sorted. None for a freedom that moves none of them.
std::vector<double> toleranceEdges(const Evaluator& ev, const Assignment& a, int f);

// [lo, hi] cut at sorted `edges` inside it: each piece ends just below an edge (a value on a
// bound is in the range below it) and the next begins just above, so each piece lies within
// one table range. One piece, [lo, hi], without edges.
std::vector<std::pair<double, double>> cutAt(double lo, double hi, const std::vector<double>& edges);

} // namespace gbx::rt
