#pragma once
// `continuation = arclength`: a scene's periodic response followed through its turning
// points (the jump-up and jump-down speeds of a mesh with backlash), by pseudo-arclength
// continuation of the shooting or harmonic balance equations in (orbit, swept quantity). Every point of
// every branch is reported in the order followed, with its stability.
#include "ir/Ir.h"
#include "model/Model.h"
#include "study/Study.h"

namespace gbx::rt {

// Returns false, doing nothing, for a linear scene: its response has no turning points (only
// poles where a Floquet multiplier passes 1), so the sweep follows it point by point.
bool continuation(const Model& m, const Assignment& design, const ir::Study& study, const ScenePlan& scene, SweepStudy& out);

} // namespace gbx::rt
