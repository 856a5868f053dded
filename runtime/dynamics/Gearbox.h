#pragma once
// A whole gearbox in time (docs/dynamics.md): every shaft, carrier, planet spin and idler a
// rotation, the gearbox input driven, the output loaded, every mesh of every stage a contact
// along its line of action with the scene's effects. The lumped model of the modes
// (dynamics/Lumped.h) with contact laws instead of linear springs.
#include <string>
#include <vector>

#include "dynamics/Ode.h"
#include "dynamics/SceneSupport.h"
#include "model/Evaluator.h"

namespace gbx::rt::dyn {

struct GearboxRun {
  std::vector<std::string> provenance;
  Stats stats;
  TimePlan plan;
  std::string stepRule;
  int harmonics = 0;         // of the stiffness series, 0 without varying_stiffness
  double meshFrequency = 0;  // of the fastest mesh: `samples` and `mesh_period` count its periods
  std::vector<double> t;
  struct MeshSeries {
    std::string name;          // "planet_stage.sun_planet" (a planetary stage: the first planet's)
    double meshFrequency = 0;  // its stage's, for naming spectral peaks
    std::vector<double> meshForce, contactForce;  // N, along the line of action and normal to the flank
  };
  std::vector<MeshSeries> meshes;
  std::vector<double> inputSpeed, outputSpeed;  // rad/s, the output positive in its kinematic sense
  std::vector<std::string> members;             // the degrees of freedom, the driven input first
  std::vector<double> kinematic;                // each member's speed per unit input speed
  std::vector<double> modes;                    // of the model linearised at the static load, Hz
  // Energy over the run (SceneOverrides::energyAudit): the drive's work, the work the load
  // takes, the work the contact damping dissipates, and the kinetic and elastic energy gained.
  double driveWork = 0, loadWork = 0, dissipated = 0, energyGained = 0;
  // The periodic steady state (`steady_state`): the orbit's start, its period (whole periods
  // of every mesh), how it was found and its largest Floquet multiplier.
  bool periodic = false;
  std::vector<double> orbit;
  double period = 0, stability = NAN, newtonResidual = 0;
  int newtonIterations = 0, balanceHarmonics = 0;
  std::string failure;
};

GearboxRun runGearbox(const Model& m, const Evaluator& ev, const Assignment& a, const ScenePlan& scene, Accuracy acc,
                      const SceneOverrides& ov);

} // namespace gbx::rt::dyn
