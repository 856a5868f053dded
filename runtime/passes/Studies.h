#pragma once
// Pass 6, studies: every `study` of the gearbox (sweeps, work-precision) on the best design.
#include <functional>
#include <vector>

#include "report/Report.h"
#include "model/Model.h"

namespace gbx::rt::passes {

// `progress`, when set, hears the fraction of the work-precision runs done.
// `baseline` and its design: for `relative(…)` in a sweep's outputs.
std::vector<StudyReport> studies(const Model& m, const Assignment& best, std::function<void(double)> progress = {},
                                 const Model* baseline = nullptr, const Assignment* baseDesign = nullptr);

} // namespace gbx::rt::passes
