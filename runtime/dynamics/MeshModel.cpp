#include "dynamics/MeshModel.h"

#include "dynamics/Dispatch.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace gbx::rt::dyn {

// The right-hand side is compiled per combination of listed effects: each term is present
// or absent at compile time, so a scene pays for exactly the effects it lists — no flag
// tests, no dead terms (bench/dynamics_bench.cpp `rhs` measures it against a hand-written base).
namespace contact {
inline constexpr int Linear = 0, Backlash = 1, Hertz = 2;
}
namespace te {
// F = dk e; e inside the contact law; the loaded mesh's separation u inside the contact law
inline constexpr int None = 0, Force = 1, Displacement = 2, Loaded = 3;
}
namespace drivephase {
inline constexpr int Constant = 0, ClosedForm = 1, State = 2;
}

template <bool Varying, bool Damped, int Contact, int Te, bool TorqueFl, int Phase>
struct Terms {
  static constexpr bool varying = Varying, damped = Damped, torqueFl = TorqueFl;
  static constexpr int contact = Contact, te = Te, phase = Phase;
  static constexpr bool needsPhase = Varying || Te != te::None;
};

template <class T>
struct MeshKernel {
  static double tau(const MeshModel& m, double t, const double* y) {
    if constexpr (T::phase == drivephase::Constant) return m.p_.teethDriver * m.p_.drive.speed0 * t * (0.5 / M_PI);
    else if constexpr (T::phase == drivephase::ClosedForm) return m.p_.teethDriver * m.p_.drive.angle(t) * (0.5 / M_PI);
    else return m.p_.teethDriver * y[2] * (0.5 / M_PI);
  }
  // Elastic (and contact-damping) force along the line of action, its slopes in x and v.
  static double force(const MeshModel& m, double t, const double* y, double* slope, double* vslope) {
    double rel = 1.0, ph = 0.0;
    if constexpr (T::needsPhase) ph = tau(m, t, y);
    double x = y[0];
    if constexpr (T::te == te::Loaded) {
      // The loaded mesh's stiffness and separation share the phase: one pass over both.
      double sk, su;
      seriesPair(m.fourier_, m.e_.loadedSeparation.f, ph, sk, su);
      rel = 1.0 + sk;
      x -= m.e_.loadedSeparation.mean + su;
    } else if constexpr (T::varying) {
      rel = relativeStiffness(m.fourier_, ph);
    }
    if constexpr (T::te == te::Displacement) x -= m.teDisplacement(ph);
    double f = 0, k = 0, kv = 0;
    if constexpr (T::contact == contact::Linear) {
      k = m.p_.meanStiffness * rel;
      f = k * x;
    } else if constexpr (T::contact == contact::Backlash) {
      double kk = m.p_.meanStiffness * rel;
      if (x > m.b_) {
        k = kk;
        f = kk * (x - m.b_);
      } else if (x < -m.b_) {
        k = kk;
        f = kk * (x + m.b_);
      }
    } else {
      if (x > 0) {
        double K = m.p_.hertzStiffness * rel;
        double e = m.e_.hertzExponent;
        double fe = K * (e == 1.5 ? x * std::sqrt(x) : std::pow(x, e));
        // Contact damping ramps in over the first `penetrationRamp` of penetration (a cubic step).
        double r = m.e_.penetrationRamp;
        double s = r > 0 ? std::min(1.0, x / r) : 1.0;
        double step = s * s * (3.0 - 2.0 * s);
        double dstep = r > 0 && s < 1.0 ? 6.0 * s * (1.0 - s) / r : 0.0;
        double damped = fe + m.e_.hertzDamping * step * y[1];
        if (damped > 0) {  // a contact pushes, never pulls
          f = damped;
          k = e * fe / x + m.e_.hertzDamping * dstep * y[1];
          kv = m.e_.hertzDamping * step;
        }
      }
    }
    if constexpr (T::damped) {
      f += m.c_ * y[1];
      kv += m.c_;
    }
    // External loads: the static load or the fluctuating load torque; F = dk e.
    double load;
    if constexpr (T::torqueFl)
      load = (m.e_.torqueMean + m.e_.torqueAmplitude * std::sin(m.e_.torqueOmega * t)) / (m.p_.outputRadius * m.p_.downstream);
    else
      load = m.p_.staticLoad;
    if constexpr (T::te == te::Force) load += m.p_.meanStiffness * (rel - 1.0) * m.teDisplacement(ph);
    if (slope) *slope = k;
    if (vslope) *vslope = kv;
    return load - f;
  }
  static void rhs(const MeshModel& m, double t, const double* y, double* dy) { derivatives(m, t, y, force(m, t, y, nullptr, nullptr), dy); }
  static void derivatives(const MeshModel& m, double t, const double* y, double f, double* dy) {
    dy[0] = y[1];
    dy[1] = f / m.p_.mass;
    if constexpr (T::phase == drivephase::State) dy[2] = m.p_.drive.speed(t);
  }
  static void dfdy(const MeshModel& m, double t, const double* y, double* J) {
    double k, kv;
    force(m, t, y, &k, &kv);
    jacobian(m, k, kv, J);
  }
  static void jacobian(const MeshModel& m, double k, double kv, double* J) {
    constexpr size_t n = T::phase == drivephase::State ? 3 : 2;
    for (size_t i = 0; i < n * n; ++i) J[i] = 0;
    J[1] = 1.0;
    J[n + 0] = -k / m.p_.mass;
    J[n + 1] = -kv / m.p_.mass;
  }
  // Both from one evaluation of the force (the variational equations read both each step).
  static void rhsDfdy(const MeshModel& m, double t, const double* y, double* dy, double* J) {
    double k, kv;
    derivatives(m, t, y, force(m, t, y, &k, &kv), dy);
    jacobian(m, k, kv, J);
  }
};

MeshModel::MeshModel(const MeshParameters& p, const MeshEffects& e) : p_(p), e_(e) {
  if (e.varyingStiffness) fourier_ = contactLineSeries(p.epsAlpha, p.epsBeta, e.harmonics);
  // The loaded mesh's stiffness relative to its mean, the same series form as the contact lines'.
  if (e.loadedMesh)
    for (size_t k = 0; k < e.loadedStiffness.f.a.size(); ++k) {
      fourier_.a.push_back(e.loadedStiffness.f.a[k] / e.loadedStiffness.mean);
      fourier_.b.push_back(e.loadedStiffness.f.b[k] / e.loadedStiffness.mean);
    }
  if (e.damping) c_ = e.dampingCoefficient >= 0 ? e.dampingCoefficient : 2.0 * e.dampingRatio * std::sqrt(p.meanStiffness * p.mass);
  b_ = 0.5 * e.clearance;
  int contactKind = e.backlash ? contact::Backlash : e.hertz ? contact::Hertz : contact::Linear;
  // Transmission error: for a mesh always in contact the paper's force F = dk(t) e(t); with
  // contact loss (backlash, Hertz) a displacement inside the contact law, so that the
  // force stays continuous where contact begins and ends.
  int teKind = e.loadedMesh                                  ? te::Loaded
               : !e.transmissionError                        ? te::None
               : contactKind != contact::Linear              ? te::Displacement
               : e.varyingStiffness                          ? te::Force
                                                             : te::None;
  int phaseKind = p.drive.needsState()                 ? drivephase::State
                  : p.drive.fluctuates || p.drive.ramp > 0 ? drivephase::ClosedForm
                                                           : drivephase::Constant;
  withBool(e.varyingStiffness || e.loadedMesh, [&](auto V) {
    withBool(e.damping, [&](auto D) {
      withInt3(contactKind, [&](auto C) {
        withInt4(teKind, [&](auto TE) {
          withBool(e.torqueFluctuation, [&](auto Q) {
            withInt3(phaseKind, [&](auto P) {
              using K = MeshKernel<Terms<decltype(V)::value, decltype(D)::value, decltype(C)::value, decltype(TE)::value,
                                         decltype(Q)::value, decltype(P)::value>>;
              sys_.rhs = [this](double t, const double* y, double* dy) { K::rhs(*this, t, y, dy); };
              sys_.dfdy = [this](double t, const double* y, double* J) { K::dfdy(*this, t, y, J); };
              sys_.rhsDfdy = [this](double t, const double* y, double* dy, double* J) { K::rhsDfdy(*this, t, y, dy, J); };
            });
          });
        });
      });
    });
  });
  sys_.dim = p.drive.needsState() ? 3 : 2;
  // The implicit method's Jacobian: dfdy as above, dfdt by a central difference (the terms
  // depend on t only through the drive's phase and the load, both smooth).
  sys_.jacobian = [this](double t, const double* y, double* dfdy, double* dfdt) {
    size_t n = sys_.dim;
    sys_.dfdy(t, y, dfdy);
    double h = 1e-7 * std::max(1e-3, meshPeriod());
    double a[3], b[3];
    sys_.rhs(t + h, y, a);
    sys_.rhs(t - h, y, b);
    for (size_t i = 0; i < n; ++i) dfdt[i] = (a[i] - b[i]) / (2 * h);
  };
  double xs = p.staticLoad / p.meanStiffness;
  double wn = 2.0 * M_PI / naturalPeriod();
  sys_.scale = {xs, xs * wn, 1.0};
  sys_.scale.resize(sys_.dim);
  // Contact onset and loss are events: no step may carry the solution across them.
  if (e.backlash) {
    for (double side : {1.0, -1.0})
      sys_.events.push_back([this, side](double t, const double* y) { return y[0] - teDisplacementAt(t, y) - side * b_; });
  } else if (e.hertz) {
    sys_.events.push_back([this](double t, const double* y) { return y[0] - teDisplacementAt(t, y); });
  }
}

double MeshModel::meshPeriod() const { return 2.0 * M_PI / (p_.drive.speed0 * p_.teethDriver); }

double MeshModel::naturalPeriod() const { return 2.0 * M_PI * std::sqrt(p_.mass / p_.meanStiffness); }

double MeshModel::excitationPeriod() const {
  double Tz = meshPeriod();
  if (p_.drive.ramp > 0) return 0;  // a start-up is a transient by definition
  // Whole periods of every fluctuation in a whole number of mesh periods (at most 1000).
  std::vector<double> periods;
  if (e_.torqueFluctuation && e_.torqueOmega > 0 && e_.torqueAmplitude != 0) periods.push_back(2.0 * M_PI / e_.torqueOmega);
  double meshes = 1.0;  // mesh periods per excitation period
  if (p_.drive.fluctuates) {
    // The mesh phase advances by z * mean * T / (2 pi) over a fluctuation period T.
    if (p_.drive.omega <= 0) return 0;
    double T = 2.0 * M_PI / p_.drive.omega;
    double per = p_.teethDriver * p_.drive.mean * T / (2.0 * M_PI);
    for (int q = 1; q <= 1000; ++q) {
      double n = per * q;
      if (std::fabs(n - std::round(n)) <= 1e-9 * std::max(1.0, n)) {
        bool whole = true;
        for (double P : periods) {
          double r = q * T / P;
          whole = whole && std::fabs(r - std::round(r)) <= 1e-9 * std::max(1.0, r);
        }
        if (whole) return q * T;
      }
    }
    return 0;
  }
  for (double P : periods) {
    double r = P / Tz;
    bool found = false;
    for (int q = 1; q <= 1000 && !found; ++q) {
      double n = r * q;
      if (std::fabs(n - std::round(n)) <= 1e-9 * std::max(1.0, n)) {
        meshes = std::max(meshes, std::round(n));
        found = true;
      }
    }
    if (!found) return 0;
  }
  return meshes * Tz;
}

double MeshModel::phase(double t, const double* y) const {
  double angle = p_.drive.needsState() ? y[2] : p_.drive.angle(t);
  return p_.teethDriver * angle / (2.0 * M_PI);
}

double MeshModel::teDisplacement(double tau) const {
  return e_.teMean + e_.teAmplitude * std::sin(2.0 * M_PI * tau + e_.tePhase);
}

double MeshModel::teDisplacementAt(double t, const double* y) const {
  if (e_.loadedMesh) return e_.loadedSeparation(phase(t, y));
  return e_.transmissionError ? teDisplacement(phase(t, y)) : 0.0;
}

std::vector<double> MeshModel::initialState() const {
  // At rest on the mean mesh under the static load.
  double x0 = e_.hertz        ? std::pow(p_.staticLoad / p_.hertzStiffness, 1.0 / e_.hertzExponent)
              : e_.loadedMesh ? e_.loadedTe(0.0) + (e_.backlash ? b_ : 0.0)
                              : p_.staticLoad / p_.meanStiffness + (e_.backlash ? b_ : 0.0);
  std::vector<double> y = {x0, 0.0};
  if (p_.drive.needsState()) y.push_back(0.0);
  return y;
}

MeshSignals MeshModel::signals(double t, const double* y) const {
  MeshSignals s{};
  double d[3];
  sys_.rhs(t, y, d);
  double tau = phase(t, y);
  double rel = e_.varyingStiffness || e_.loadedMesh ? relativeStiffness(fourier_, tau) : 1.0;
  // The load side of the balance m a = load - contact - c v.
  double load = e_.torqueFluctuation
                    ? (e_.torqueMean + e_.torqueAmplitude * std::sin(e_.torqueOmega * t)) / (p_.outputRadius * p_.downstream)
                    : p_.staticLoad;
  if (e_.transmissionError && e_.varyingStiffness && linear()) load += p_.meanStiffness * (rel - 1.0) * teDisplacement(tau);
  double meshForce = load - p_.mass * d[1];  // contact (with its damping) plus the mesh damping
  s.displacement = y[0];
  s.velocity = y[1];
  s.acceleration = d[1];
  s.meshForce = meshForce;
  s.contactForce = meshForce - c_ * y[1];
  s.stiffness = p_.meanStiffness * rel;
  // With the loaded mesh the transmission error is the dynamic one, the displacement itself.
  s.transmissionError = e_.loadedMesh ? y[0] : e_.transmissionError ? teDisplacement(tau) : 0.0;
  s.staticTransmissionError = e_.loadedMesh ? e_.loadedTe(tau) : 0.0;
  s.inputSpeed = p_.drive.speed(t);
  s.outputSpeed = (s.inputSpeed / p_.ratio + y[1] / p_.outputRadius) / p_.downstream;
  return s;
}

} // namespace gbx::rt::dyn
