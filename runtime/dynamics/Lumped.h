#pragma once
// The whole gearbox as a lumped torsional model: one rotation per shaft (a stage's wheel
// and the next stage's pinion share one), idlers, planets and carriers their own; meshes
// as linear springs along their lines of action; split branches with their torsion
// shafts. Its natural frequencies and mode shapes come from K v = w^2 M v.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "ir/Ir.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

struct LumpedModes {
  std::vector<double> frequencies;   // Hz, the rigid-body mode left out
  std::vector<std::string> shapes;   // per mode, the members that move most
  std::vector<std::string> provenance;
};

LumpedModes gearboxModes(const Model& m, const Assignment& a);

// The natural frequencies, Hz, of K v = w^2 M v (a rigid-body or unstable mode as 0).
std::vector<double> naturalFrequencies(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M);
// "4628.1, 14181.4 Hz"-style list, one decimal.
std::string frequencyList(const std::vector<double>& f);
// The maximum step of a lumped model: a twentieth of the shorter of the mesh period Tz and
// the period of its highest mode (times a rerun's factor); returns the rule as reported.
std::string lumpedMaxStep(double& maxStep, double Tz, double fmax, std::optional<double> factor, const char* meshRule);

} // namespace gbx::rt::dyn
