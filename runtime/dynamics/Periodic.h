#pragma once
// The periodic steady state of a periodically forced system, found directly instead of by
// settling a transient (docs/dynamics.md): shooting, Newton on the initial state x0 so that one
// period of the flow returns to x0 (plus a known drift of angle coordinates). Its Jacobian
// is the monodromy matrix, from the variational equations when the system gives dfdy,
// else by differences. For a linear system the first Newton step is exact; the eigenvalues
// of the monodromy matrix (Floquet multipliers) give the orbit's stability.
#include <algorithm>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "dynamics/Ode.h"

namespace gbx::rt::dyn {

struct PeriodicOptions {
  double period = 0;          // s
  std::vector<double> drift;  // y(T) - y(0) on the orbit (angles that advance), 0 if empty
  int maxIterations = 40;
  bool linear = false;        // one Newton step is exact; the second only confirms it
  // For a linear system, leave that confirming period to the caller, who integrates the
  // orbit's period anyway to record it: the orbit comes back with one iteration and
  // residual NaN, to be measured over that run (PeriodicOrbit::unconfirmed).
  bool confirmLinear = true;
};

struct PeriodicOrbit {
  bool converged = false;
  std::vector<double> y0;
  Eigen::MatrixXd monodromy;
  std::vector<std::complex<double>> multipliers;
  double stability = 0;   // largest multiplier modulus
  double residual = 0;    // |phi_T(y0) - y0 - drift| over the state scale, at the last check
  int iterations = 0;
  bool unconfirmed = false;  // a linear orbit whose residual the caller measures (confirmLinear false)
  bool variational = false;  // monodromy from the variational equations (else differences)
  long settledPeriods = 0;   // periods settled before Newton converged (0: Newton from the guess)
  Stats stats;               // every right-hand side, variational ones included
  std::string failure;
};

// One period of the flow from y and its monodromy matrix.
struct FlowResult {
  bool ok = false;
  std::vector<double> y;  // phi_T(y0)
  Eigen::MatrixXd phi;    // d phi_T / d y0
  std::string failure;
};
FlowResult flowWithMonodromy(const System& sys, const Accuracy& acc, double t0, double period, const std::vector<double>& y0,
                             Stats& stats);

// The system with its variational equations: [y, Phi] with Phi' = J(t, y) Phi (it reads sys,
// which must outlive it).
System variationalSystem(const System& sys);

// Newton on R = phi_T(y0) - y0 - drift stops when its correction is at the level the
// integration can resolve: this, of the state scale.
inline double newtonTolerance(const Accuracy& acc) { return std::max(10.0 * acc.rtol, 1e-13); }
// Newton's correction d from (Phi(T) - I) d = -R; none, with the failure said, where Phi has a
// multiplier at 1 (the orbit is not isolated).
std::optional<Eigen::VectorXd> newtonCorrection(const Eigen::MatrixXd& phi, const Eigen::VectorXd& R,
                                                std::string& failure);
// y0 moved by d, damped to at most ten state scales; the scaled size of the move, and
// whether d was taken whole.
double dampedStep(std::vector<double>& y0, const Eigen::VectorXd& d, const std::vector<double>& scale, bool& whole);

// Largest modulus of the eigenvalues of M, and the eigenvalues.
double spectralRadius(const Eigen::MatrixXd& M, std::vector<std::complex<double>>* eigenvalues = nullptr);

// The system's state scale, one per state (1 where it gives none).
std::vector<double> stateScale(const System& sys);

// Scaled max norm: max |v_i| / scale_i.
double scaledNorm(const std::vector<double>& v, const std::vector<double>& scale);

PeriodicOrbit periodicOrbit(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess);

} // namespace gbx::rt::dyn
