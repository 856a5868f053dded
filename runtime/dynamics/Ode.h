#pragma once
// Integration of a first-order system with GSL odeiv2, with what GSL lacks: samples at
// exact times without shortening the integrator's steps, events located inside a step
// (contact onset and loss), a step limit, a smallest step, and a full account of cost.
#include <functional>
#include <string>
#include <vector>

#include <gsl/gsl_odeiv2.h>

#include "catalogue/Methods.h"

namespace gbx::rt::dyn {

struct System {
  size_t dim = 0;
  std::function<void(double t, const double* y, double* dydt)> rhs;
  // Analytic Jacobian (required by msbdf): dfdy row-major dim x dim, dfdt.
  std::function<void(double t, const double* y, double* dfdy, double* dfdt)> jacobian;
  // The state Jacobian alone (row-major dim x dim), for the variational equations of the
  // periodic steady state; empty: the monodromy matrix is found by differences.
  std::function<void(double t, const double* y, double* dfdy)> dfdy;
  // Optional: rhs and dfdy from one evaluation, where they share their work.
  std::function<void(double t, const double* y, double* dydt, double* dfdy)> rhsDfdy;
  // Events: the integrator stops at every sign change of each function and restarts there.
  std::vector<std::function<double(double t, const double* y)>> events;
  std::vector<double> scale;  // absolute tolerance per component = atol * scale[i]
};

// One row per integration method: its GSL stepper.
struct MethodRow {
  cat::Method id;
  const gsl_odeiv2_step_type* stepper;
};
const std::vector<MethodRow>& methodRows();
const gsl_odeiv2_step_type* stepType(cat::Method m);

struct Accuracy {
  cat::Method method = cat::Method::Rk8pd;
  double rtol = 1e-6;
  double atol = 0;      // 0: the same as rtol, on the scaled components
  double maxStep = 0;   // 0: none
  double minStep = 0;   // 0: 1e-14 of the time span
  long maxSteps = 5000000;  // a runaway (chattering contact) fails in seconds
};

struct Stats {
  long steps = 0, rejected = 0, rhsEvaluations = 0, jacobianEvaluations = 0, events = 0;
  double cpuSeconds = 0;
  Stats& operator+=(const Stats& s) {
    steps += s.steps;
    rejected += s.rejected;
    rhsEvaluations += s.rhsEvaluations;
    jacobianEvaluations += s.jacobianEvaluations;
    events += s.events;
    cpuSeconds += s.cpuSeconds;
    return *this;
  }
};

class Integrator {
public:
  Integrator(const System& sys, const Accuracy& acc);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  // Advances y from t to t1. `onSample` is called at each time of `samples` (ascending,
  // within (t, t1]) with the state there. Returns false on failure (see error()).
  bool advance(double& t, std::vector<double>& y, double t1, const std::vector<double>& samples,
               const std::function<void(double, const double*)>& onSample);

  const Stats& stats() const { return stats_; }
  const std::string& error() const { return error_; }

private:
  struct Impl;
  Impl* impl_;
  Accuracy acc_;
  Stats stats_;
  std::string error_;
};

// CPU time of the calling thread, seconds.
double threadCpuSeconds();

} // namespace gbx::rt::dyn
