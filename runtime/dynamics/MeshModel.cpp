#include "dynamics/MeshModel.h"

#include <algorithm>
#include <cmath>

namespace gbx::rt::dyn {

MeshModel::MeshModel(const MeshParameters& p, const MeshEffects& e) : p_(p), e_(e) {
  if (e.varyingStiffness) fourier_ = contactLineSeries(p.epsAlpha, p.epsBeta, e.harmonics);
  if (e.damping) c_ = e.dampingCoefficient >= 0 ? e.dampingCoefficient : 2.0 * e.dampingRatio * std::sqrt(p.meanStiffness * p.mass);
  // The static load, or the fluctuating load torque carried by the driven member.
  if (e.torqueFluctuation) {
    double r = p.outputRadius * p.downstream;
    loads_.push_back([this, r](double t, const Instant&) {
      return (e_.torqueMean + e_.torqueAmplitude * std::sin(e_.torqueOmega * t)) / r;
    });
  } else {
    loads_.push_back([this](double, const Instant&) { return p_.staticLoad; });
  }
  // Transmission error: for a mesh always in contact the paper's force F = dk(t) e(t); with
  // contact loss (backlash, Hertz) a displacement inside the contact law, so that the
  // force stays continuous where contact begins and ends.
  if (e.transmissionError && e.varyingStiffness && !e.backlash && !e.hertz)
    loads_.push_back([this](double, const Instant& at) {
      double dk = p_.meanStiffness * (at.rel - 1.0);
      return dk * (e_.teMean + e_.teAmplitude * std::sin(2.0 * M_PI * at.tau + e_.tePhase));
    });
  sys_.dim = p.drive.needsState() ? 3 : 2;
  sys_.rhs = [this](double t, const double* y, double* dydt) { rhs(t, y, dydt); };
  sys_.jacobian = [this](double t, const double* y, double* dfdy, double* dfdt) { jacobian(t, y, dfdy, dfdt); };
  double xs = p.staticLoad / p.meanStiffness;
  double wn = 2.0 * M_PI / naturalPeriod();
  sys_.scale = {xs, xs * wn, 1.0};
  sys_.scale.resize(sys_.dim);
  // Contact onset and loss are events: no step may carry the solution across them.
  if (e.backlash) {
    double b = 0.5 * e.clearance;
    sys_.events.push_back([this, b](double t, const double* y) { return y[0] - excitation(instant(t, y)) - b; });
    sys_.events.push_back([this, b](double t, const double* y) { return y[0] - excitation(instant(t, y)) + b; });
  } else if (e.hertz) {
    sys_.events.push_back([this](double t, const double* y) { return y[0] - excitation(instant(t, y)); });
  }
}

double MeshModel::meshPeriod() const { return 2.0 * M_PI / (p_.drive.speed0 * p_.teethDriver); }

double MeshModel::naturalPeriod() const { return 2.0 * M_PI * std::sqrt(p_.mass / p_.meanStiffness); }

double MeshModel::phase(double t, const double* y) const {
  double angle = p_.drive.needsState() ? y[2] : p_.drive.angle(t);
  return p_.teethDriver * angle / (2.0 * M_PI);
}

std::vector<double> MeshModel::initialState() const {
  // At rest on the mean mesh under the static load.
  double x0 = e_.hertz ? std::pow(p_.staticLoad / p_.hertzStiffness, 1.0 / e_.hertzExponent)
                       : p_.staticLoad / p_.meanStiffness + (e_.backlash ? 0.5 * e_.clearance : 0.0);
  std::vector<double> y = {x0, 0.0};
  if (p_.drive.needsState()) y.push_back(0.0);
  return y;
}

MeshModel::Instant MeshModel::instant(double t, const double* y) const {
  double tau = phase(t, y);
  return {tau, e_.varyingStiffness ? relativeStiffness(fourier_, tau) : 1.0};
}

double MeshModel::excitation(const Instant& at) const {
  if (!e_.transmissionError || !(e_.backlash || e_.hertz)) return 0.0;
  return e_.teMean + e_.teAmplitude * std::sin(2.0 * M_PI * at.tau + e_.tePhase);
}

// Elastic mesh force and its slope in x.
double MeshModel::elastic(const double* y, const Instant& at, double* slope) const {
  double rel = at.rel;
  double x = y[0] - excitation(at);
  if (e_.hertz) {
    if (x <= 0) {
      *slope = 0;
      return 0;
    }
    double K = p_.hertzStiffness * rel;
    double f = K * (e_.hertzExponent == 1.5 ? x * std::sqrt(x) : std::pow(x, e_.hertzExponent));
    *slope = e_.hertzExponent * f / x;
    // Damping ramps in over the first `penetrationRamp` of penetration (a cubic step).
    double s = e_.penetrationRamp > 0 ? std::min(1.0, x / e_.penetrationRamp) : 1.0;
    double step = s * s * (3.0 - 2.0 * s);
    double damped = f + e_.hertzDamping * step * y[1];
    return std::max(0.0, damped);  // a contact pushes, never pulls
  }
  double k = p_.meanStiffness * rel;
  if (e_.backlash) {
    double b = 0.5 * e_.clearance;
    if (x > b) {
      *slope = k;
      return k * (x - b);
    }
    if (x < -b) {
      *slope = k;
      return k * (x + b);
    }
    *slope = 0;
    return 0;
  }
  *slope = k;
  return k * x;
}

void MeshModel::rhs(double t, const double* y, double* dydt) const {
  double slope;
  Instant at = instant(t, y);
  double f = -elastic(y, at, &slope) - c_ * y[1];
  for (const auto& l : loads_) f += l(t, at);
  dydt[0] = y[1];
  dydt[1] = f / p_.mass;
  if (p_.drive.needsState()) dydt[2] = p_.drive.speed(t);
}

void MeshModel::jacobian(double t, const double* y, double* dfdy, double* dfdt) const {
  size_t n = sys_.dim;
  for (size_t i = 0; i < n * n; ++i) dfdy[i] = 0;
  double slope;
  elastic(y, instant(t, y), &slope);
  dfdy[0 * n + 1] = 1.0;
  dfdy[1 * n + 0] = -slope / p_.mass;
  double dampingSlope = c_;
  if (e_.hertz && y[0] > 0) {
    double s = e_.penetrationRamp > 0 ? std::min(1.0, y[0] / e_.penetrationRamp) : 1.0;
    dampingSlope += e_.hertzDamping * s * s * (3.0 - 2.0 * s);
  }
  dfdy[1 * n + 1] = -dampingSlope / p_.mass;
  // Time derivatives by a central difference: the terms depend on t only through the
  // drive's phase and the load, both smooth.
  double h = 1e-7 * std::max(1e-3, meshPeriod());
  std::vector<double> a(n), b(n);
  rhs(t + h, y, a.data());
  rhs(t - h, y, b.data());
  for (size_t i = 0; i < n; ++i) dfdt[i] = (a[i] - b[i]) / (2 * h);
}

MeshSignals MeshModel::signals(double t, const double* y) const {
  MeshSignals s{};
  double d[3];
  rhs(t, y, d);
  double slope;
  Instant at = instant(t, y);
  double contact = elastic(y, at, &slope);
  s.displacement = y[0];
  s.velocity = y[1];
  s.acceleration = d[1];
  s.contactForce = contact;
  s.meshForce = contact + c_ * y[1];
  s.stiffness = p_.meanStiffness * at.rel;
  s.transmissionError = e_.transmissionError ? e_.teMean + e_.teAmplitude * std::sin(2.0 * M_PI * at.tau + e_.tePhase) : 0.0;
  s.inputSpeed = p_.drive.speed(t);
  s.outputSpeed = (s.inputSpeed / p_.ratio + y[1] / p_.outputRadius) / p_.downstream;
  return s;
}

} // namespace gbx::rt::dyn
