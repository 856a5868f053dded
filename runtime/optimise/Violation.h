#pragma once
// How far a rule stands from holding at a point of the freedoms: 0 when it holds, else its
// excess relative to the scale of the compared values. Both the optimiser's penalty and the
// deciding of continuous freedoms steer by it.
#include "ir/Ir.h"
#include "model/Evaluator.h"

namespace gbx::rt {

// `and`/`forall` sum their parts' violations, `or` takes the least; an inequality its
// relative excess; any other rule 1 unless it is true.
double violation(const Evaluator& ev, const ir::Expr& e, const Assignment& a);

} // namespace gbx::rt
