#pragma once
// The whole gearbox as a lumped torsional model: one rotation per shaft (a stage's wheel
// and the next stage's pinion share one), idlers, planets and carriers their own; meshes
// as linear springs along their lines of action; split branches with their torsion
// shafts. Its natural frequencies and mode shapes come from K v = w^2 M v.
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

struct LumpedModes {
  std::vector<double> frequencies;   // Hz, the rigid-body mode left out
  std::vector<std::string> shapes;   // per mode, the members that move most
  std::vector<std::string> provenance;
};

LumpedModes gearboxModes(const Model& m, const Assignment& a);

} // namespace gbx::rt::dyn
