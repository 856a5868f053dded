#pragma once
// The loaded mesh of a design's spur or helical stage: its flank geometry, the single-pair
// stiffness, and the separations its `modify` rules (or a sweep's value of a modification)
// and its deviations give.
#include <string>
#include <vector>

#include "dynamics/LoadedMesh.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

// `load` is the transverse force along the line of action, N. Every choice is said in `prov`.
LoadedMeshInput loadedMeshInput(const Evaluator& ev, const Assignment& a, int stage, double load, int slices, int positions,
                                std::vector<std::string>& prov);

} // namespace gbx::rt::dyn
