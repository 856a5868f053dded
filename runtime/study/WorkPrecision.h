#pragma once
#include <functional>
// `study … { work_precision of SCENE; rtol in {…}; harmonics in a..b; methods in {…}; }`:
// reruns the scene at each setting and reports the error of its first numeric output
// against a reference (itself checked against a still tighter run) with the CPU time.
#include "ir/Ir.h"
#include "model/Model.h"
#include "study/Study.h"

namespace gbx::rt {

WorkPrecisionStudy workPrecision(const Model& m, const Assignment& design, const ir::Study& study, const ScenePlan& scene,
                                 const std::function<void(double)>& progress = {});

} // namespace gbx::rt
