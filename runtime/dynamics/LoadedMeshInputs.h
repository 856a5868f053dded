#pragma once
#include <optional>
// The loaded mesh of a design's spur or helical stage: its flank geometry, the single-pair
// stiffness, and the separations its `modify` rules (or a sweep's value of a modification)
// and its deviations give.
#include <string>
#include <vector>

#include "dynamics/LoadedMesh.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

// What a caller other than a scene asks of the loaded mesh: the rating's contact analysis
// adds the lead deviation f_Hbeta (m) across the face in the adverse sense and keeps the lead
// alone (no tip relief, pitch or profile deviation: those load the pairs along the path).
struct LoadedMeshUse {
  double leadDeviation = 0;
  bool leadOnly = false;
  double deflectionScale = 1;  // the pinion's deflections at the operating torque times this (F_m / F_t)
  // The shafts' separation across the face (ShaftMesh), already at the load: it takes the
  // place of the pinion's bending and torsion deflections.
  std::vector<double> shaftProfile;
  // The sense the lead deviation adds in and a correction opposes, when decided once (the
  // shafts' fixed point: a tilt near zero must not flip it from one step to the next).
  double sense = 0;
};

// `load` is the transverse force along the line of action, N. Every choice is said in `prov`.
LoadedMeshInput loadedMeshInput(const Evaluator& ev, const Assignment& a, int stage, double load, int slices, int positions,
                                std::vector<std::string>& prov, const LoadedMeshUse& use = {});

// The teeth's single pitch deviations (each tooth's pitch from the one before it, minus the
// nominal, on the reference circle) as the teeth's lateness along the line of action: summed
// tooth by tooth, the sum closed over the circumference (the last tooth is the reference),
// times cos(alpha_t).
std::vector<double> toothLateness(const std::vector<double>& singlePitch, double cosAlphaT);

// Per-tooth pitch deviations for the loaded mesh: a gear's list as written, or, with a seed,
// each tooth's drawn from a normal distribution with the gear's `pitch_deviation` (f_pt, given
// or from its accuracy grade) as three standard deviations. Fills in.toothLateness.
struct ToothErrors {
  const std::vector<double>* listed[2] = {nullptr, nullptr};
  std::optional<double> seed;
  bool any() const { return seed || (listed[0] && !listed[0]->empty()) || (listed[1] && !listed[1]->empty()); }
};
void toothErrors(const Evaluator& ev, const Assignment& a, int stage, const ToothErrors& errors, LoadedMeshInput& in,
                 std::vector<std::string>& prov);

} // namespace gbx::rt::dyn
