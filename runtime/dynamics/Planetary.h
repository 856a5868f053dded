#pragma once
// An NGW planetary stage as a lumped torsional model (sun driven, ring fixed, carrier
// out): the carrier and each planet's spin are degrees of freedom; every sun-planet and
// ring-planet mesh is a contact along its line of action (docs/dynamics.md).
#include <map>
#include <string>
#include <vector>

#include "dynamics/Ode.h"
#include "dynamics/SceneSupport.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

struct PlanetaryRun {
  std::vector<std::string> provenance;
  Stats stats;
  double meshFrequency = 0;
  TimePlan plan;
  std::vector<double> t;
  SignalSeries signals;
  double staticLoad = 0;      // the mean sun-planet mesh force, for the dynamic factor
  std::vector<double> modes;  // natural frequencies of the linearised model, Hz
  std::string failure;
  // With `periodic`: the periodic steady state found directly (dynamics/Periodic.h).
  bool periodic = false;
  double stability = 0;                             // largest Floquet multiplier modulus
  int newtonIterations = 0;
  double newtonResidual = 0;                        // scaled, at the converged orbit
  std::vector<double> orbit;                        // the orbit's initial state (a sweep's next guess)
  std::string stepRule;                             // the maximum step and its rule
  double period = 0;                                // of the excitation, s
  int harmonics = 0;                                // of the stiffness series, 0 without varying_stiffness
  std::vector<std::string> warnings;                // results to read with care (a balance short of its target)
  int balanceHarmonics = 0;                         // the orbit's harmonics when harmonic balance found it
};

PlanetaryRun runPlanetary(const Evaluator& ev, const Assignment& a, int stage, const ScenePlan& scene,
                          Accuracy acc, const SceneOverrides& ov, double upstream, double downstream, double speed, double E,
                          double nu, double density, bool materialAssumed, bool periodic = false);

} // namespace gbx::rt::dyn
