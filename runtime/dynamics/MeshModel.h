#pragma once
// One gear mesh along its line of action (docs/dynamics.md): m x'' + c x' + k(t) x = F0 + F(t),
// built from the scene's effects only. Each listed effect contributes its terms once,
// when the model is composed; an effect that is not listed has no state, no term and no
// test in the right-hand side.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/Drive.h"
#include "dynamics/LoadedMesh.h"
#include "dynamics/Ode.h"
#include "dynamics/Stiffness.h"

namespace gbx::rt::dyn {

struct MeshParameters {
  double mass = 0;             // equivalent mass, kg
  double meanStiffness = 0;    // N/m
  double staticLoad = 0;       // N, along the line of action
  double teethDriver = 0;      // tooth count of the driving member (mesh phase)
  double outputRadius = 0;     // base radius of the driven member, m
  double ratio = 1;            // stage reduction
  double downstream = 1;       // product of the ratios after this stage
  double epsAlpha = 1.5, epsBeta = 0;
  double hertzStiffness = 0;   // K of F = K d^e, N/m^e
  double hertzRadius = 0;      // equivalent radius of curvature at the pitch point, m
  Drive drive;
  std::vector<std::string> provenance;  // where each parameter came from, for the report
};

// Effect parameters, in SI, as the scene gives them.
struct MeshEffects {
  bool varyingStiffness = false;
  int harmonics = 5;
  bool damping = false;
  double dampingRatio = 0, dampingCoefficient = -1;
  bool transmissionError = false;
  double teMean = 0, teAmplitude = 0, tePhase = 0;
  bool backlash = false;
  double clearance = 0;
  bool hertz = false;
  double hertzExponent = 1.5, penetrationRamp = 0, hertzDamping = 0;
  bool torqueFluctuation = false;
  double torqueMean = 0, torqueAmplitude = 0, torqueOmega = 0;
  // loaded_mesh: the thin-slice tables of one mesh period, as Fourier series (built by the
  // scene from the flank geometry): stiffness k, loaded static transmission error e_s and
  // the effective separation u = e_s - F0/k, so that the mesh force is k (x - u).
  bool loadedMesh = false;
  int slices = 40, positions = 64, loadedHarmonics = 16;
  PeriodicSeries loadedStiffness, loadedTe, loadedSeparation;
  // Contact outside the path, and the teeth's pitch deviations (listed per gear, or drawn with
  // a seed): the table then runs over the hunting period, the dynamics reading its mean period.
  bool loadedCorner = false;
  std::optional<double> pitchSeed;
  const std::vector<double>* pitchListed[2] = {nullptr, nullptr};
  std::vector<double> loadedTable; // the static transmission error over the table's periods
  std::vector<double> loadedStiffnessTable; // the mesh stiffness over the same periods
  int loadedPeriods = 1;
};

// Quantities of one instant, for outputs.
struct MeshSignals {
  double displacement, velocity, acceleration, meshForce, contactForce, stiffness, transmissionError, staticTransmissionError,
      inputSpeed, outputSpeed;
};

class MeshModel {
public:
  MeshModel(const MeshParameters& p, const MeshEffects& e);
  MeshModel(const MeshModel&) = delete;
  MeshModel& operator=(const MeshModel&) = delete;

  const System& system() const { return sys_; }
  std::vector<double> initialState() const;
  MeshSignals signals(double t, const double* y) const;
  double meshPeriod() const;      // at the nominal drive speed, s
  double naturalPeriod() const;   // of the mean linearised mesh, s
  double dampingCoefficient() const { return c_; }
  const Fourier& series() const { return fourier_; }
  // The period of the excitation (the mesh period, or a whole number of them that also
  // holds whole periods of a fluctuation), or 0 when the excitation is not periodic.
  double excitationPeriod() const;
  bool linear() const { return !e_.backlash && !e_.hertz; }

private:
  template <class Terms>
  friend struct MeshKernel;
  double phase(double t, const double* y) const;
  double teDisplacement(double tau) const;
  double teDisplacementAt(double t, const double* y) const;

  MeshParameters p_;
  MeshEffects e_;
  Fourier fourier_;
  double c_ = 0;
  double b_ = 0;  // half the backlash clearance
  System sys_;
};

} // namespace gbx::rt::dyn
