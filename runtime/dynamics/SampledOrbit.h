#pragma once
// Shooting with fixed steps that land on the samples (docs/dynamics.md). For a smooth model
// (no contact events) and an explicit method, each Newton run integrates one period of the
// flow and its variational equations in equal steps, a whole number of them between two
// samples, and keeps the state (and the variational matrix) at every sample. The orbit's
// samples then come out of the Newton run itself: for a linear model by superposition,
// y(t_k) = y_k + Phi(t_k) d with d the one Newton correction; for a nonlinear one from the
// run of the last iteration. No record run follows, and no extra step reaches a sample.
// The steps per sample start at one (or at what the maximum step needs) and are doubled
// until every step's own error estimate is within the tolerance.
#include <string>
#include <vector>

#include "dynamics/Ode.h"
#include "dynamics/Periodic.h"

namespace gbx::rt::dyn {

struct SampledOrbit {
  PeriodicOrbit orbit;
  double dt = 0;                           // between two samples
  std::vector<std::vector<double>> states; // at k dt, k = 0 .. M-1: one period
  int stepsPerSample = 0;
  // The state at a sample time t = k dt (k any whole number: the orbit repeats).
  const std::vector<double>& at(double t) const;
};

// Whether the fixed steps serve this system and accuracy: no events, the variational
// equations, an explicit method.
bool fixedStepsServe(const System& sys, const Accuracy& acc);

// The orbit with samples every dt (the period a whole number of them). stepsPerSample > 0
// fixes the steps between two samples (an error estimate's rerun); 0 chooses them. Returns
// an orbit with converged false where Newton fails, or where more than 64 steps per sample
// would be needed (the adaptive integrator then serves).
SampledOrbit sampledOrbit(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess,
                          double dt, int stepsPerSample = 0);

} // namespace gbx::rt::dyn
