#pragma once
// How far a rule stands from holding at a point of the freedoms: 0 when it holds, else its
// excess relative to the scale of the compared values. Both the optimiser's penalty and the
// deciding of continuous freedoms steer by it.
#include <vector>

#include "ir/Ir.h"
#include "model/Evaluator.h"

namespace gbx::rt {

// `and`/`forall` sum their parts' violations, `or` takes the least; an inequality its
// relative excess; any other rule 1 unless it is true.
double violation(const Evaluator& ev, const ir::Expr& e, const Assignment& a);

// Each conjunct's signed margin at a point: positive where it holds with room, negative
// where it fails, relative to the scale of the compared values, so that a constrained
// optimiser can follow a rule's boundary. `and`/`forall` give one margin per part, `or` the
// largest of its parts', an interval test (`x in a..b`, `x == c +- t`) two; any other rule
// +1 where it is true and -1 where it is not. Where a side has no value the margin is -1.
void margins(const Evaluator& ev, const ir::Expr& e, const Assignment& a, std::vector<double>& out);

} // namespace gbx::rt
