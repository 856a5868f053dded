#pragma once
// One gear mesh along its line of action (DOMAIN.md §3): m x'' + c x' + k(t) x = F0 + F(t),
// built from the scene's effects only. Each listed effect contributes its terms once,
// when the model is composed; an effect that is not listed has no state, no term and no
// test in the right-hand side.
#include <functional>
#include <string>
#include <vector>

#include "dynamics/Drive.h"
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
};

// Quantities of one instant, for outputs.
struct MeshSignals {
  double displacement, velocity, acceleration, meshForce, contactForce, stiffness, transmissionError, inputSpeed,
      outputSpeed;
};

class MeshModel {
public:
  MeshModel(const MeshParameters& p, const MeshEffects& e);

  const System& system() const { return sys_; }
  std::vector<double> initialState() const;
  MeshSignals signals(double t, const double* y) const;
  double meshPeriod() const;      // at the nominal drive speed, s
  double naturalPeriod() const;   // of the mean linearised mesh, s
  double dampingCoefficient() const { return c_; }
  const Fourier& series() const { return fourier_; }

private:
  // What one instant needs from the drive: the mesh phase and the relative stiffness,
  // computed once per right-hand side.
  struct Instant {
    double tau, rel;
  };
  Instant instant(double t, const double* y) const;
  double phase(double t, const double* y) const;
  double elastic(const double* y, const Instant& at, double* slope) const;
  double excitation(const Instant& at) const;  // transmission error as a displacement
  void rhs(double t, const double* y, double* dydt) const;
  void jacobian(double t, const double* y, double* dfdy, double* dfdt) const;

  MeshParameters p_;
  MeshEffects e_;
  Fourier fourier_;
  double c_ = 0;
  System sys_;
  // Terms composed from the listed effects.
  std::vector<std::function<double(double t, const Instant& at)>> loads_;  // forces along the line of action
};

} // namespace gbx::rt::dyn
