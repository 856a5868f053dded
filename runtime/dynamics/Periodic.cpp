#include "dynamics/Periodic.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace gbx::rt::dyn {

namespace {

// The system with its variational equations: [y, Phi] with Phi' = J(t, y) Phi, Phi(0) = I.
// Events and tolerances act on y; Phi_ij is scaled by scale_i / scale_j.
System variational(const System& sys) {
  size_t n = sys.dim;
  System v;
  v.dim = n + n * n;
  v.rhs = [&sys, n](double t, const double* y, double* dy) {
    double J[64];
    std::vector<double> big;
    double* jac = J;
    if (n * n > 64) {
      big.resize(n * n);
      jac = big.data();
    }
    if (sys.rhsDfdy) {
      sys.rhsDfdy(t, y, dy, jac);
    } else {
      sys.rhs(t, y, dy);
      sys.dfdy(t, y, jac);
    }
    const double* P = y + n;
    double* dP = dy + n;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) {
        double s = 0;
        for (size_t k = 0; k < n; ++k) s += jac[i * n + k] * P[k * n + j];
        dP[i * n + j] = s;
      }
  };
  // For the implicit method: the block Jacobian [[J, 0], [., I (x) J]], leaving out the
  // second derivatives of f (it only steers the method's own Newton iteration).
  if (sys.jacobian)
    v.jacobian = [&sys, n](double t, const double* y, double* dfdy, double* dfdt) {
      size_t N = n + n * n;
      for (size_t i = 0; i < N * N; ++i) dfdy[i] = 0;
      for (size_t i = 0; i < N; ++i) dfdt[i] = 0;
      std::vector<double> J(n * n);
      sys.jacobian(t, y, J.data(), dfdt);
      for (size_t i = 0; i < n; ++i)
        for (size_t k = 0; k < n; ++k) dfdy[i * N + k] = J[i * n + k];
      // d(Phi'_ij)/d(Phi_kj) = J_ik
      for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i)
          for (size_t k = 0; k < n; ++k) dfdy[(n + i * n + j) * N + (n + k * n + j)] = J[i * n + k];
    };
  v.events = sys.events;  // they read y's first n components only
  std::vector<double> sc = stateScale(sys);
  v.scale = sc;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) v.scale.push_back(sc[i] / sc[j]);
  return v;
}

bool integrate(const System& sys, const Accuracy& acc, double t0, double period, std::vector<double>& y, Stats& stats,
               std::string& failure) {
  Integrator integ(sys, acc);
  double t = t0;
  bool ok = integ.advance(t, y, t0 + period, {}, [](double, const double*) {});
  stats += integ.stats();
  if (!ok) failure = integ.error();
  return ok;
}

} // namespace

System variationalSystem(const System& sys) { return variational(sys); }

std::optional<Eigen::VectorXd> newtonCorrection(const Eigen::MatrixXd& phi, const Eigen::VectorXd& R,
                                                std::string& failure) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(phi - Eigen::MatrixXd::Identity(phi.rows(), phi.cols()));
  if (!lu.isInvertible()) {
    failure =
        "the monodromy matrix has a multiplier at 1: the periodic orbit is not isolated (a resonance without damping?)";
    return std::nullopt;
  }
  return Eigen::VectorXd(lu.solve(-R));
}

double dampedStep(std::vector<double>& y0, const Eigen::VectorXd& d, const std::vector<double>& scale, bool& whole) {
  std::vector<double> step(y0.size());
  for (size_t i = 0; i < step.size(); ++i)
    step[i] = d(static_cast<long>(i));
  double sn = scaledNorm(step, scale);
  double damp = sn > 10.0 ? 10.0 / sn : 1.0;
  for (size_t i = 0; i < step.size(); ++i)
    y0[i] += damp * step[i];
  whole = damp == 1.0 && std::isfinite(sn);
  return damp * sn;
}

double scaledNorm(const std::vector<double>& v, const std::vector<double>& scale) {
  double m = 0;
  for (size_t i = 0; i < v.size(); ++i) m = std::max(m, std::fabs(v[i]) / (i < scale.size() && scale[i] > 0 ? scale[i] : 1.0));
  return m;
}

double spectralRadius(const Eigen::MatrixXd& M, std::vector<std::complex<double>>* eigenvalues) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(M, false);
  double r = 0;
  if (eigenvalues) eigenvalues->clear();
  for (long i = 0; i < es.eigenvalues().size(); ++i) {
    r = std::max(r, std::abs(es.eigenvalues()(i)));
    if (eigenvalues) eigenvalues->push_back(es.eigenvalues()(i));
  }
  // Sorted by modulus, largest first, so reports and tests read them in a fixed order.
  if (eigenvalues)
    std::stable_sort(eigenvalues->begin(), eigenvalues->end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  return r;
}

FlowResult flowWithMonodromy(const System& sys, const Accuracy& acc, double t0, double period, const std::vector<double>& y0,
                             Stats& stats) {
  FlowResult r;
  size_t n = sys.dim;
  r.phi = Eigen::MatrixXd::Identity(static_cast<long>(n), static_cast<long>(n));
  if (sys.dfdy) {
    System v = variational(sys);
    std::vector<double> y = y0;
    y.resize(n + n * n, 0.0);
    for (size_t i = 0; i < n; ++i) y[n + i * n + i] = 1.0;
    if (!integrate(v, acc, t0, period, y, stats, r.failure)) return r;
    r.y.assign(y.begin(), y.begin() + static_cast<long>(n));
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) r.phi(static_cast<long>(i), static_cast<long>(j)) = y[n + i * n + j];
    r.ok = true;
    return r;
  }
  // Central differences, each column its own pair of runs; the step balances truncation
  // (h^2) against the integration error (rtol / h).
  std::vector<double> y = y0;
  if (!integrate(sys, acc, t0, period, y, stats, r.failure)) return r;
  r.y = y;
  std::vector<double> sc = stateScale(sys);
  double rel = std::cbrt(std::max(acc.rtol, 1e-15));
  for (size_t j = 0; j < n; ++j) {
    double h = rel * sc[j];
    std::vector<double> yp = y0, ym = y0;
    yp[j] += h;
    ym[j] -= h;
    if (!integrate(sys, acc, t0, period, yp, stats, r.failure) || !integrate(sys, acc, t0, period, ym, stats, r.failure)) return r;
    for (size_t i = 0; i < n; ++i) r.phi(static_cast<long>(i), static_cast<long>(j)) = (yp[i] - ym[i]) / (2 * h);
  }
  r.ok = true;
  return r;
}

namespace {

PeriodicOrbit newton(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess, Stats& stats) {
  PeriodicOrbit o;
  size_t n = sys.dim;
  o.variational = static_cast<bool>(sys.dfdy);
  std::vector<double> sc = stateScale(sys);
  std::vector<double> drift = opt.drift;
  drift.resize(n, 0.0);
  double tol = newtonTolerance(acc);
  std::vector<double> y0 = std::move(guess);
  double lastStep = INFINITY;
  for (int it = 0; it < opt.maxIterations; ++it) {
    FlowResult f = flowWithMonodromy(sys, acc, 0.0, opt.period, y0, stats);
    ++o.iterations;
    if (!f.ok) {
      o.failure = f.failure;
      return o;
    }
    Eigen::VectorXd R(static_cast<long>(n));
    std::vector<double> res(n);
    for (size_t i = 0; i < n; ++i) res[i] = R(static_cast<long>(i)) = f.y[i] - y0[i] - drift[i];
    o.residual = scaledNorm(res, sc);
    o.monodromy = f.phi;
    o.y0 = y0;
    // Converged: the last correction was negligible (or, for a linear system, exact).
    if (o.residual <= tol || lastStep <= tol || (opt.linear && it >= 1)) {
      // A linear orbit is exact after one step: what remains is the integration error
      // carried through the monodromy matrix (large inside an instability region), and it
      // is reported as the Newton residual, not taken for a failure.
      o.converged = (opt.linear && std::isfinite(o.residual)) || o.residual <= std::max(tol, 1e3 * acc.rtol);
      if (!o.converged)
        o.failure = fmt::format("Newton stalled: the orbit's residual is {:.3g} of the state scale after {} iterations", o.residual,
                                o.iterations);
      break;
    }
    std::optional<Eigen::VectorXd> d = newtonCorrection(f.phi, R, o.failure);
    if (!d) return o;
    bool whole = false;
    lastStep = dampedStep(y0, *d, sc, whole);
    if (opt.linear && !opt.confirmLinear && whole) {
      o.y0 = y0;
      o.converged = true;
      o.unconfirmed = true;
      o.residual = NAN;
      break;
    }
    if (it + 1 == opt.maxIterations) o.failure = fmt::format("Newton did not converge in {} iterations (residual {:.3g} of the state scale)",
                                                             opt.maxIterations, o.residual);
  }
  if (!o.failure.empty()) return o;
  o.stability = spectralRadius(o.monodromy, &o.multipliers);
  return o;
}

} // namespace

std::vector<double> stateScale(const System& sys) {
  std::vector<double> s = sys.scale;
  s.resize(sys.dim, 1.0);
  for (double& x : s)
    if (!(x > 0)) x = 1.0;
  return s;
}

PeriodicOrbit periodicOrbit(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess) {
  // Newton from the guess; when it fails (a guess outside the orbit's basin: contact lost
  // for a whole period, a wrong branch), settle the transient for a growing number of
  // periods from the guess and start Newton again from there.
  Stats stats;
  std::vector<double> start = guess;
  long settled = 0;
  PeriodicOrbit o;
  for (int attempt = 0; attempt < 5; ++attempt) {
    o = newton(sys, acc, opt, start, stats);
    // Settling helps a guess outside the basin, not an orbit that is not isolated.
    if (o.converged || attempt == 4 || o.failure.find("not isolated") != std::string::npos) break;
    long periods = 25L << attempt;
    std::string failure;
    bool ok = true;
    for (long k = 0; k < periods && ok; ++k) ok = integrate(sys, acc, 0.0, opt.period, start, stats, failure);
    if (!ok) {
      o.failure += "; settling from it failed: " + failure;
      break;
    }
    for (size_t i = 0; i < start.size() && i < opt.drift.size(); ++i) start[i] -= static_cast<double>(periods) * opt.drift[i];
    settled += periods;
  }
  o.stats = stats;
  o.settledPeriods = settled;
  return o;
}

} // namespace gbx::rt::dyn
