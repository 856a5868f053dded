#pragma once
// The mismatch a cylindrical stage's two shafts give its mesh: both shafts solved with the
// mesh force spread across the face as the contact analysis carries it, their bending and
// twist (with the bearings' deflections) projected on the line of action, slice by slice.
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"

namespace gbx::rt {

class Evaluator;
struct Assignment;

// The shafts that carry a stage's pinion and wheel (their indices among the gearbox's shafts).
struct MeshShafts {
  int pinion = -1, wheel = -1;
};
std::optional<MeshShafts> meshShafts(const ir::Gearbox& g, int stage);

// The separation across the face at `points` equally spaced points from y = 0 (the face's
// end nearer the shafts' left ends, whose axes run the same way) to y = b, from the forces at
// the operating point with the face's load shared as `share` (per slice, summing to 1). The
// least is 0. Empty with `error` said when a shaft cannot be solved.
std::vector<double> shaftSeparation(const Evaluator& ev, const Assignment& a, int stage, const MeshShafts& ms,
                                    const std::vector<double>& share, int points, std::string* error);

} // namespace gbx::rt
