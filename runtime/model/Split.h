#pragma once
// Load sharing of a two-branch (or n-branch) power split with torsion shafts
// (docs/dynamics.md): shaft twist, circumferential displacement at the stage-I wheel, and
// the imbalance a backlash difference leaves, for free and preloaded installation.
#include <optional>
#include <string>

#include "ir/Ir.h"
#include "model/Value.h"

namespace gbx::rt {

class Evaluator;
struct Assignment;

struct SplitResult {
  double branchTorque = 0;         // torque in one torsion shaft, N*m
  double twist = 0;                // Psi = Mkp L / (G Jp), rad
  double displacement = 0;         // l = Psi dI / 2, m
  double preloadDisplacement = 0;  // l0 = Psi0 dI / 2 under the installation torque, m
  double imbalance = 0;            // Omega, a fraction (free: dl / 2l; preloaded: max(dl - l0, 0) / 2l)
};

// nullopt (and `error`) when an input is missing.
std::optional<SplitResult> computeSplit(const Evaluator& ev, int split, const Assignment& a, std::string* error = nullptr);

} // namespace gbx::rt
