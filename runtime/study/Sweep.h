#pragma once
// `study … { sweep X in a..b step s; output …; plot; }`: the outputs at every value of X,
// with every other input as the design has it.
#include "ir/Ir.h"
#include "model/Model.h"
#include "study/Study.h"

namespace gbx::rt {

// `relative(…)` in an output reads `baseline` (its design `baseDesign`) at the same point.
SweepStudy sweep(const Model& m, const Assignment& design, const ir::Study& study, const Model* baseline = nullptr,
                 const Assignment* baseDesign = nullptr);

// A speed sweep's resonance marks: where the mesh frequency (fm at x) meets the natural
// frequency fn, half of it, or twice it (the principal parametric resonance).
void resonanceMarks(SweepStudy& r, const ir::Study& st, double x, double fm, double fn);

} // namespace gbx::rt
