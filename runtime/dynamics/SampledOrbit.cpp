#include "dynamics/SampledOrbit.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include "model/Deadline.h"

namespace gbx::rt::dyn {

namespace {

constexpr int kMostStepsPerSample = 64;

// One period in fixed steps of the system with its variational equations (n states, then
// the n x n matrix row by row), from y0 and the identity: the state and the matrix at
// every sample, and the largest step error over its tolerance.
struct FixedRun {
  std::vector<std::vector<double>> y; // at each sample, n states
  std::vector<Eigen::MatrixXd> phi;   // at each sample
  std::vector<double> yT;             // one period on
  Eigen::MatrixXd phiT;
  double worst = 0; // the largest |error| / (atol scale + rtol |y|) of a step
  std::string failure;
};

class FixedStepper {
public:
  FixedStepper(const System& v, const Accuracy& acc, Stats& stats) : v_(v), acc_(acc), stats_(stats) {
    gsl_set_error_handler_off();
    step_.reset(gsl_odeiv2_step_alloc(stepType(acc.method), v.dim));
    gsys_ = {&FixedStepper::func, nullptr, v.dim, this};
  }

  FixedRun run(size_t n, const std::vector<double>& y0, long samples, double dt, int m) {
    FixedRun r;
    const size_t N = v_.dim;
    std::vector<double> y(N, 0.0), err(N);
    std::copy(y0.begin(), y0.end(), y.begin());
    for (size_t i = 0; i < n; ++i)
      y[n + i * n + i] = 1.0;
    const double atol = acc_.atol > 0 ? acc_.atol : acc_.rtol;
    const double h = dt / m;
    auto keep = [&](std::vector<double>& state, Eigen::MatrixXd& P) {
      state.assign(y.begin(), y.begin() + static_cast<long>(n));
      P.resize(static_cast<long>(n), static_cast<long>(n));
      for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < n; ++j)
          P(static_cast<long>(i), static_cast<long>(j)) = y[n + i * n + j];
    };
    r.y.resize(static_cast<size_t>(samples));
    r.phi.resize(static_cast<size_t>(samples));
    for (long k = 0; k < samples; ++k) {
      keep(r.y[static_cast<size_t>(k)], r.phi[static_cast<size_t>(k)]);
      if (Deadline::expired()) {
        r.failure = fmt::format("time limit of {:g} s (--time-limit) reached", Deadline::seconds());
        return r;
      }
      for (int s = 0; s < m; ++s) {
        // Each step's time from its index, so that the steps land on the samples exactly.
        double t = (static_cast<double>(k) * m + s) * h;
        int status = gsl_odeiv2_step_apply(step_.get(), t, h, y.data(), err.data(), nullptr, nullptr, &gsys_);
        ++stats_.steps;
        if (status != GSL_SUCCESS) {
          r.failure = fmt::format("the integrator failed at t = {:.6g} s ({})", t, gsl_strerror(status));
          return r;
        }
        for (size_t i = 0; i < N; ++i)
          r.worst = std::max(r.worst, std::fabs(err[i]) / (atol * v_.scale[i] + acc_.rtol * std::fabs(y[i])));
      }
    }
    keep(r.yT, r.phiT);
    return r;
  }

private:
  struct Free {
    void operator()(gsl_odeiv2_step* s) const { gsl_odeiv2_step_free(s); }
  };
  static int func(double t, const double y[], double dydt[], void* p) {
    auto* self = static_cast<FixedStepper*>(p);
    ++self->stats_.rhsEvaluations;
    self->v_.rhs(t, y, dydt);
    for (size_t i = 0; i < self->v_.dim; ++i)
      if (!std::isfinite(dydt[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
  }
  const System& v_;
  const Accuracy& acc_;
  Stats& stats_;
  std::unique_ptr<gsl_odeiv2_step, Free> step_;
  gsl_odeiv2_system gsys_{};
};

} // namespace

const std::vector<double>& SampledOrbit::at(double t) const {
  const long M = static_cast<long>(states.size());
  long k = std::lround(t / dt) % M;
  return states[static_cast<size_t>(k < 0 ? k + M : k)];
}

bool fixedStepsServe(const System& sys, const Accuracy& acc) {
  return sys.events.empty() && static_cast<bool>(sys.dfdy) && !cat::methodSpec(acc.method).implicit &&
         stepType(acc.method) != nullptr;
}

namespace {

SampledOrbit sampledFrom(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess,
                         double dt, int stepsPerSample, int depth) {
  SampledOrbit out;
  out.dt = dt;
  PeriodicOrbit& o = out.orbit;
  o.variational = true;
  const size_t n = sys.dim;
  const double ratio = opt.period / dt;
  if (!std::isfinite(ratio) || ratio < 0.5 || std::fabs(ratio - std::round(ratio)) > 1e-9 * ratio) {
    o.failure = "the samples do not divide the period";
    return out;
  }
  for (double d : opt.drift)
    if (d != 0) {
      o.failure = "coordinates that drift over a period"; // their samples would need the drift added (none below)
      return out;
    }
  const long M = std::lround(ratio);
  const double spacing = opt.period / static_cast<double>(M); // exactly a part of the period
  const double cpu0 = threadCpuSeconds();
  System v = variationalSystem(sys);
  Stats stats;
  FixedStepper stepper(v, acc, stats);
  const std::vector<double> sc = stateScale(sys);
  const double tol = newtonTolerance(acc);
  // The steps per sample: as given, or the least the maximum step allows, doubled until
  // every step's error is within the tolerance (checked on the first run).
  const double least = std::ceil(spacing / (acc.maxStep > 0 ? acc.maxStep : spacing) - 1e-9);
  int m = stepsPerSample > 0 ? stepsPerSample : static_cast<int>(std::clamp(least, 1.0, 2.0 * kMostStepsPerSample));
  std::vector<double> y0 = std::move(guess);
  FixedRun run;
  // An error estimate's rerun (steps given) may take twice the most.
  const int most = stepsPerSample > 0 ? 2 * kMostStepsPerSample : kMostStepsPerSample;
  for (;; m *= 2) {
    if (m > most) {
      o.failure = fmt::format("more than {} fixed steps per sample would be needed", most);
      stats.cpuSeconds += threadCpuSeconds() - cpu0;
      o.stats = stats;
      return out;
    }
    run = stepper.run(n, y0, M, spacing, m);
    if (!run.failure.empty() || stepsPerSample > 0 || run.worst <= 1.0) break;
  }
  out.stepsPerSample = m;
  double lastStep = INFINITY;
  for (int it = 0; it < opt.maxIterations && run.failure.empty(); ++it) {
    ++o.iterations;
    Eigen::VectorXd R(static_cast<long>(n));
    std::vector<double> res(n);
    for (size_t i = 0; i < n; ++i)
      res[i] = R(static_cast<long>(i)) = run.yT[i] - y0[i];
    o.residual = scaledNorm(res, sc);
    o.monodromy = run.phiT;
    if (!opt.linear && (o.residual <= tol || lastStep <= tol)) {
      o.converged = o.residual <= std::max(tol, 1e3 * acc.rtol);
      if (!o.converged)
        o.failure = fmt::format("Newton stalled: the orbit's residual is {:.3g} of the state scale after {} iterations",
                                o.residual, o.iterations);
      break;
    }
    std::optional<Eigen::VectorXd> correction = newtonCorrection(run.phiT, R, o.failure);
    if (!correction) break;
    const Eigen::VectorXd& d = *correction;
    if (opt.linear) {
      // Exact in one step: the samples by superposition, the residual what rounding leaves.
      for (size_t k = 0; k < run.y.size(); ++k) {
        Eigen::VectorXd yk = run.phi[k] * d;
        for (size_t i = 0; i < n; ++i)
          run.y[k][i] += yk(static_cast<long>(i));
      }
      Eigen::VectorXd end = run.phiT * d;
      for (size_t i = 0; i < n; ++i) {
        y0[i] += d(static_cast<long>(i));
        res[i] = run.yT[i] + end(static_cast<long>(i)) - y0[i];
      }
      o.residual = scaledNorm(res, sc);
      o.converged = std::isfinite(o.residual);
      break;
    }
    bool whole = false;
    lastStep = dampedStep(y0, d, sc, whole);
    run = stepper.run(n, y0, M, spacing, m);
    if (it + 1 == opt.maxIterations)
      o.failure = fmt::format("Newton did not converge in {} iterations (residual {:.3g} of the state scale)",
                              opt.maxIterations, o.residual);
  }
  if (!run.failure.empty()) o.failure = run.failure;
  stats.cpuSeconds += threadCpuSeconds() - cpu0;
  o.stats = stats;
  if (!o.converged) return out;
  // A nonlinear orbit's own run must meet the tolerance too (the steps were chosen on the
  // run from the guess): where it does not, once more from the orbit, the steps chosen there.
  if (!opt.linear && stepsPerSample == 0 && run.worst > 1.0 && depth < 2) {
    SampledOrbit again = sampledFrom(sys, acc, opt, y0, dt, 0, depth + 1);
    again.orbit.stats += o.stats;
    again.orbit.iterations += o.iterations;
    return again;
  }
  o.y0 = y0;
  o.stability = spectralRadius(o.monodromy, &o.multipliers);
  out.states = std::move(run.y);
  return out;
}

} // namespace

SampledOrbit sampledOrbit(const System& sys, const Accuracy& acc, const PeriodicOptions& opt, std::vector<double> guess,
                          double dt, int stepsPerSample) {
  return sampledFrom(sys, acc, opt, std::move(guess), dt, stepsPerSample, 0);
}

} // namespace gbx::rt::dyn
