#include "dynamics/Ode.h"
#include "model/Deadline.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

namespace gbx::rt::dyn {

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Integrator::Impl {
  const System* sys = nullptr;
  Stats* stats = nullptr;
  gsl_odeiv2_system gsys{};
  const gsl_odeiv2_step_type* type = nullptr;
  // GSL drivers own a stepper, a control and an evolve, and link them (msbdf needs the link).
  gsl_odeiv2_driver* main = nullptr;   // the integration
  gsl_odeiv2_driver* probe = nullptr;  // single steps for samples and events
  gsl_odeiv2_step* step = nullptr;
  gsl_odeiv2_control* control = nullptr;
  gsl_odeiv2_evolve* evolve = nullptr;
  double h = 0;
  bool implicit = false;

  static int func(double t, const double y[], double dydt[], void* p) {
    auto* self = static_cast<Impl*>(p);
    ++self->stats->rhsEvaluations;
    self->sys->rhs(t, y, dydt);
    for (size_t i = 0; i < self->sys->dim; ++i)
      if (!std::isfinite(dydt[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
  }
  static int jac(double t, const double y[], double* dfdy, double dfdt[], void* p) {
    auto* self = static_cast<Impl*>(p);
    ++self->stats->jacobianEvaluations;
    self->sys->jacobian(t, y, dfdy, dfdt);
    return GSL_SUCCESS;
  }

  // One step of exactly h from (t0, y0), for samples and event location.
  bool stepTo(double t0, const std::vector<double>& y0, double h1, std::vector<double>& out) {
    out = y0;
    std::vector<double> err(sys->dim);
    if (h1 == 0) return true;
    gsl_odeiv2_driver_reset(probe);
    if (implicit) {
      // msbdf is a multistep method: a lone step needs its own small integration.
      double t = t0, hh = h1;
      int status = GSL_SUCCESS;
      while (t < t0 + h1 && status == GSL_SUCCESS)
        status = gsl_odeiv2_evolve_apply(probe->e, probe->c, probe->s, &gsys, &t, t0 + h1, &hh, out.data());
      return status == GSL_SUCCESS;
    }
    return gsl_odeiv2_step_apply(probe->s, t0, h1, out.data(), err.data(), nullptr, nullptr, &gsys) == GSL_SUCCESS;
  }
};

namespace {
// The runtime side of the method registry (compiler/catalogue/Methods.h): GSL's stepper.
// A function-local table: ready whenever it is first asked for.
const std::vector<MethodRow>& kMethodRowsTable() {
  static const std::vector<MethodRow> rows = {
    {cat::Method::Rk8pd, gsl_odeiv2_step_rk8pd}, {cat::Method::Rkf45, gsl_odeiv2_step_rkf45},
    {cat::Method::Rkck, gsl_odeiv2_step_rkck},   {cat::Method::Rk4, gsl_odeiv2_step_rk4},
    {cat::Method::Msbdf, gsl_odeiv2_step_msbdf},
  };
  return rows;
}
} // namespace

const std::vector<MethodRow>& methodRows() { return kMethodRowsTable(); }

const gsl_odeiv2_step_type* stepType(cat::Method m) {
  for (const auto& r : kMethodRowsTable())
    if (r.id == m) return r.stepper;
  return nullptr;
}

Integrator::Integrator(const System& sys, const Accuracy& acc) : impl_(new Impl) {
  gsl_set_error_handler_off();  // errors come back as statuses, never as an abort
  impl_->sys = &sys;
  impl_->stats = &stats_;
  impl_->gsys = {&Impl::func, sys.jacobian ? &Impl::jac : nullptr, sys.dim, impl_};
  impl_->type = stepType(acc.method);
  impl_->implicit = cat::methodSpec(acc.method).implicit;
  std::vector<double> scale = sys.scale;
  scale.resize(sys.dim, 1.0);
  double atol = acc.atol > 0 ? acc.atol : acc.rtol;
  impl_->main = gsl_odeiv2_driver_alloc_scaled_new(&impl_->gsys, impl_->type, 1e-6, atol, acc.rtol, 1.0, 0.0, scale.data());
  impl_->probe = gsl_odeiv2_driver_alloc_scaled_new(&impl_->gsys, impl_->type, 1e-6, atol, acc.rtol, 1.0, 0.0, scale.data());
  impl_->step = impl_->main->s;
  impl_->control = impl_->main->c;
  impl_->evolve = impl_->main->e;
  acc_ = acc;
}

Integrator::~Integrator() {
  gsl_odeiv2_driver_free(impl_->probe);
  gsl_odeiv2_driver_free(impl_->main);
  delete impl_;
}

bool Integrator::advance(double& t, std::vector<double>& y, double t1, const std::vector<double>& samples,
                         const std::function<void(double, const double*)>& onSample) {
  double cpu0 = threadCpuSeconds();
  auto& I = *impl_;
  if (I.implicit && !I.sys->jacobian) {
    error_ = fmt::format("method {} needs the model's Jacobian, which this model does not give; use an explicit method (rk8pd)",
                         cat::methodSpec(acc_.method).name);
    return false;
  }
  const System& sys = *I.sys;
  double span = std::max(t1 - t, 1e-300);
  if (I.h <= 0) I.h = acc_.maxStep > 0 ? std::min(acc_.maxStep, span / 100) : span / 100;
  size_t next = static_cast<size_t>(std::lower_bound(samples.begin(), samples.end(), t) - samples.begin());
  // A sample at the start (a periodic orbit's first point) is the state as given.
  while (next < samples.size() && samples[next] == t) onSample(samples[next++], y.data());
  std::vector<double> y0, ys;
  std::vector<double> ev0(sys.events.size());
  for (size_t k = 0; k < sys.events.size(); ++k) ev0[k] = sys.events[k](t, y.data());
  bool ok = true;
  while (t < t1) {
    if (stats_.steps >= acc_.maxSteps) {
      error_ = fmt::format("step limit of {} reached at t = {:.6g} s", acc_.maxSteps, t);
      ok = false;
      break;
    }
    if ((stats_.steps & 255) == 0 && Deadline::expired()) {
      error_ = fmt::format("time limit of {:g} s (--time-limit) reached at t = {:.6g} s of {:.6g} s", Deadline::seconds(), t, t1);
      ok = false;
      break;
    }
    double t0 = t;
    y0 = y;
    double stop = t1;
    if (acc_.maxStep > 0) {
      I.h = std::min(I.h, acc_.maxStep);
      stop = std::min(t1, t0 + acc_.maxStep);
    }
    size_t failedBefore = I.evolve->failed_steps;
    int status = gsl_odeiv2_evolve_apply(I.evolve, I.control, I.step, &I.gsys, &t, stop, &I.h, y.data());
    stats_.rejected += static_cast<long>(I.evolve->failed_steps - failedBefore);
    if (status != GSL_SUCCESS) {
      error_ = fmt::format("the integrator failed at t = {:.6g} s ({})", t0, gsl_strerror(status));
      ok = false;
      break;
    }
    ++stats_.steps;
    // A step that no longer moves t in floating point, or is below the scene's
    // `min_step`, is a failure, not a loop.
    double hmin = std::max(acc_.minStep, 8.0 * std::numeric_limits<double>::epsilon() * std::fabs(t0));
    if (t - t0 <= hmin && t < t1 && t < stop) {
      error_ = fmt::format("step size fell to {:.3g} s at t = {:.6g} s", t - t0, t0);
      ok = false;
      break;
    }
    // An event inside the step: locate its time, cut the step there, restart from it.
    double tEvent = t;
    bool cut = false;
    for (size_t k = 0; k < sys.events.size(); ++k) {
      double g1 = sys.events[k](t, y.data());
      if ((ev0[k] < 0) == (g1 < 0) || ev0[k] == 0) continue;
      double a = t0, b = t, ga = ev0[k];
      for (int it = 0; it < 60 && b - a > 1e-15 * std::max(1.0, std::fabs(b)); ++it) {
        double mid = 0.5 * (a + b);
        if (!I.stepTo(t0, y0, mid - t0, ys)) break;
        double gm = sys.events[k](mid, ys.data());
        if ((gm < 0) == (ga < 0)) {
          a = mid;
          ga = gm;
        } else {
          b = mid;
        }
      }
      if (b < tEvent) {
        tEvent = b;
        cut = true;
      }
    }
    if (cut) {
      I.stepTo(t0, y0, tEvent - t0, y);
      t = tEvent;
      ++stats_.events;
      gsl_odeiv2_evolve_reset(I.evolve);
      gsl_odeiv2_step_reset(I.step);
    }
    // Samples inside (t0, t]: one exact step from the step's start to each of them.
    while (next < samples.size() && samples[next] <= t) {
      double ts = samples[next++];
      if (ts == t) {
        onSample(ts, y.data());
        continue;
      }
      if (!I.stepTo(t0, y0, ts - t0, ys)) {
        error_ = fmt::format("a sample step failed at t = {:.6g} s", ts);
        ok = false;
        break;
      }
      onSample(ts, ys.data());
    }
    if (!ok) break;
    for (size_t k = 0; k < sys.events.size(); ++k) ev0[k] = sys.events[k](t, y.data());
  }
  stats_.cpuSeconds += threadCpuSeconds() - cpu0;
  return ok;
}

} // namespace gbx::rt::dyn
