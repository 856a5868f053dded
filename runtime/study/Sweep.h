#pragma once
// `study … { sweep X in a..b step s; output …; plot; }`: the outputs at every value of X,
// with every other input as the design has it.
#include "ir/Ir.h"
#include "model/Model.h"
#include "study/Study.h"

namespace gbx::rt {

SweepStudy sweep(const Model& m, const Assignment& design, const ir::Study& study);

} // namespace gbx::rt
