#pragma once
// The periodic steady state by harmonic balance (docs/dynamics.md): the orbit is written as a
// truncated Fourier series in every state, y(t) = c_0 + sum_j c_j cos(j w t) + s_j sin(j w t)
// (plus the known drift of angle coordinates), and the coefficients are found so that the
// series satisfies y' = f(t, y) projected on the same harmonics (Galerkin). The right-hand
// side is evaluated at L equally spaced instants of the period and transformed back
// (alternating frequency-time), so contact loss and backlash need nothing of their own.
// Newton's Jacobian comes from the system's dfdy at the same instants; for a linear system
// the first step is exact. The orbit's stability is Hill's: the eigenvalues of the
// linearised operator in the same basis, the n nearest the real axis.
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "dynamics/Ode.h"

namespace gbx::rt::dyn {

struct BalanceOptions {
  double period = 0;         // s
  std::vector<double> drift; // y(T) - y(0) on the orbit (angles that advance), 0 if empty
  int harmonics = 10;        // N
  int timePoints = 0; // L; 0: the smallest power of two >= 3N + 2 (products of two series alias no lower harmonic)
  int maxIterations = 40;
  bool linear = false;   // the first Newton step is exact
  bool stability = true; // Hill's multipliers
  // The residual y' - f(t, y) is checked at this many points per interval between the
  // transform's instants, none of them on an instant: an event the instants step over shows
  // up there.
  int checkRefine = 1;
  double newtonTolerance = 1e-12; // of the state scale
  double gapLimit = 0.05;         // a larger residual between the samples is not an orbit
  // Hill's method up to this many unknowns; beyond, one period of the variational equations
  // from the orbit's start, at this accuracy.
  long hillLimit = 40;
  Accuracy floquet;
};

struct BalanceOrbit {
  bool converged = false;
  int harmonics = 0, timePoints = 0, iterations = 0;
  double period = 0;
  std::vector<double> drift;
  // Rows: mean, cos 1, sin 1, ..., cos N, sin N; one column per state.
  Eigen::MatrixXd coeffs;
  double residual = NAN;    // the Galerkin residual after the last step, over w times the state scale
  double gapResidual = NAN; // largest |y' - f(t, y)| between the samples, over the largest |y'| of that state
  double tail = NAN;        // the amplitude of harmonic N over the largest harmonic amplitude, worst state
  double truncation = NAN;  // the largest scaled change to the orbit with twice the harmonics (harmonicBalanceTo)
  std::vector<std::complex<double>> multipliers;
  double stability = NAN; // largest multiplier modulus (NaN: not computed)
  std::string stabilityMethod;
  bool unresolved = false; // Newton converged, but the residual between the samples is above the limit
  Stats stats;             // right-hand sides and Jacobians, CPU time
  std::string failure;

  // The orbit's state at time t (any t: the drift is carried on).
  void state(double t, double* y) const;
  std::vector<double> state(double t) const;
};

// From a guess: a state (taken as the constant term) or, when `start` has the right number of
// columns, a previous orbit's coefficients (a neighbouring point of a sweep; its harmonics are
// cut or padded to N).
BalanceOrbit harmonicBalance(const System& sys, const BalanceOptions& opt, const std::vector<double>& guess,
                             const Eigen::MatrixXd* start = nullptr);

// The Galerkin residual D c - P f(c) (+ the drift's rate) of coefficients c (K x n, K = 2N + 1,
// rows as BalanceOrbit::coeffs) on opt's period, drift and instants, K x n; with `jacobian`,
// also dR/dc with unknowns and equations ordered h n + a. A continuation's equations.
Eigen::MatrixXd balanceResidual(const System& sys, const BalanceOptions& opt, const Eigen::MatrixXd& coeffs,
                                Eigen::MatrixXd* jacobian, Stats& stats);

// The kinematic equations y_a' = y_b of the system along the series c (the Jacobian's row a is
// b's unit row at every instant), as pairs (a, b): a velocity b follows from its displacement
// a's coefficients, so a solver may leave b's out.
std::vector<std::pair<long, long>> balanceKinematicPairs(const System& sys, const BalanceOptions& opt,
                                                         const Eigen::MatrixXd& coeffs);

// Newton's system without the velocities of the kinematic pairs (a, b): the equations but the
// kinematic rows and the unknowns but the velocities' coefficients, as full indices h n + a in
// that order; the reduction's Jacobian holds dR/dc_a + dR/dc_b D, each velocity's
// coefficients being D (the derivative at frequency w) times its displacement's.
struct KinematicIndices {
  std::vector<long> rows, keep;
};
struct KinematicReduction : KinematicIndices {
  Eigen::MatrixXd jacobian; // rows.size() x keep.size()
};
KinematicIndices keptIndices(const std::vector<std::pair<long, long>>& pairs, long K, long n);
KinematicReduction withoutVelocities(const Eigen::MatrixXd& jacobian, const std::vector<std::pair<long, long>>& pairs,
                                     long K, long n, double w);

// The first N harmonics of an orbit given by M equally spaced states over its period
// (t = k T / M, k = 0 .. M-1) with the drift taken out: a guess from a shooting orbit.
Eigen::MatrixXd seriesOfSamples(const std::vector<std::vector<double>>& samples, const std::vector<double>& drift,
                                int N);

// Chooses N for a target: from `first` harmonics, doubling while the orbit moves by more than
// `target` of the state scale from the one with half the harmonics (and the system stays
// within `maxUnknowns`). Where the target is met, the orbit with half the harmonics of the
// last doubling (the change measures its error), its truncation that change; otherwise the
// last orbit, its truncation the last change.
BalanceOrbit harmonicBalanceTo(const System& sys, BalanceOptions opt, double target, const std::vector<double>& guess,
                               int first = 8, long maxUnknowns = 4096, const Eigen::MatrixXd* start = nullptr);

} // namespace gbx::rt::dyn
