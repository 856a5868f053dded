#pragma once
// Pass 6, studies: every `study` of the gearbox (sweeps, work-precision) on the best design.
#include <vector>

#include "report/Report.h"
#include "model/Model.h"

namespace gbx::rt::passes {

std::vector<StudyReport> studies(const Model& m, const Assignment& best);

} // namespace gbx::rt::passes
