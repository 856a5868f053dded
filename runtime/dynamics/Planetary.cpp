#include "dynamics/Planetary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <type_traits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "catalogue/StageKinds.h"
#include "dynamics/Dispatch.h"
#include "dynamics/Effects.h"
#include "dynamics/Lumped.h"
#include "dynamics/Periodic.h"
#include "dynamics/Scene.h"
#include "dynamics/SceneBalance.h"
#include "dynamics/Stiffness.h"

namespace gbx::rt::dyn {

namespace {

double need(const Value& v, const std::string& what) { return needNumber(v, what); }

struct Mesh {
  double K = 0;        // Hertz stiffness, or linear stiffness without hertz_contact
  double phase0 = 0;   // planet phasing, mesh periods
  bool ring = false;
  int planet = 0;
};

// What the right-hand side reads; effects the scene does not list keep their zeros.
struct Params {
  int N = 0;
  size_t nq = 0;
  double rbs = 0, rbp = 0, rbr = 0, zr = 0, JcEff = 0, Jp = 0;
  std::vector<Mesh> meshes;
  Fourier fourier;
  double e = 1.5, ramp = 0, hertzDampingSp = 0, hertzDampingRp = 0, halfClearance = 0;
  double teMean = 0, teAmp = 0, tePhase = 0, cSp = 0, cRp = 0;
  double tMean = 0, tAmp = 0, tOmega = 0;
  Drive drive;
};

// The right-hand side is compiled per combination of listed effects (as in MeshModel.cpp):
// an effect the scene does not list is absent from it, not tested for.
namespace contact {
inline constexpr int Linear = 0, Backlash = 1, Hertz = 2;
}
namespace drivephase {
inline constexpr int Constant = 0, ClosedForm = 1, State = 2;
}

template <bool Varying, bool Damped, int Contact, bool Te, bool TorqueFl, int Phase>
struct Kernel {
  // Transmission error: F = dk(t) e(t) on a mesh always in contact (docs/dynamics.md); with
  // contact loss a displacement inside the contact law, so the force stays continuous.
  static constexpr bool teDisplacement = Te && Contact != contact::Linear;
  static constexpr bool teForce = Te && Contact == contact::Linear && Varying;
  static constexpr bool needsPhase = Varying || teDisplacement || teForce;

  static double sunAngle(const Params& p, double t, const double* y) {
    if constexpr (Phase == drivephase::Constant) return p.drive.speed0 * t;
    else if constexpr (Phase == drivephase::ClosedForm) return p.drive.angle(t);
    else return y[2 * p.nq];
  }
  static double sunSpeed(const Params& p, double t) {
    if constexpr (Phase == drivephase::Constant) return p.drive.speed0;
    else return p.drive.speed(t);
  }
  // Mesh deflection and its rate: sun-planet rbs(ts - tc) + rbp phi; ring-planet -rbp phi - rbr tc.
  static double deflection(const Params& p, const Mesh& me, double ts, double ws, const double* y, double& rate) {
    size_t ip = 1 + static_cast<size_t>(me.planet);
    if (me.ring) {
      rate = -p.rbp * y[p.nq + ip] - p.rbr * y[p.nq];
      return -p.rbp * y[ip] - p.rbr * y[0];
    }
    rate = p.rbs * (ws - y[p.nq]) + p.rbp * y[p.nq + ip];
    return p.rbs * (ts - y[0]) + p.rbp * y[ip];
  }
  // The mesh force at deflection d and rate; with Slopes also its partial derivatives in
  // d, the rate and the mesh phase tau (for the state Jacobian).
  template <bool Slopes>
  static double force(const Params& p, const Mesh& me, double carrierPhase, double d, double rate, double* fd, double* fv,
                      double* ft) {
    [[maybe_unused]] double tau = 0, rel = 1.0, drel = 0, err = 0, derr = 0;
    if constexpr (needsPhase) tau = carrierPhase + me.phase0;
    if constexpr (Varying) {
      rel = relativeStiffness(p.fourier, tau);
      if constexpr (Slopes) drel = relativeStiffnessSlope(p.fourier, tau);
    }
    if constexpr (teDisplacement || teForce) {
      err = p.teMean + p.teAmp * std::sin(2.0 * M_PI * tau + p.tePhase);
      if constexpr (Slopes) derr = 2.0 * M_PI * p.teAmp * std::cos(2.0 * M_PI * tau + p.tePhase);
    }
    double K = me.K;
    if constexpr (Varying) K *= rel;
    [[maybe_unused]] double c = 0;
    if constexpr (Damped) c = me.ring ? p.cRp : p.cSp;
    if constexpr (teDisplacement) d -= err;
    if constexpr (Slopes) *fd = *fv = *ft = 0;
    if constexpr (Contact == contact::Backlash) {
      // Dead zone: both flanks, contact lost inside the clearance.
      double hc = p.halfClearance;
      double e2 = d > hc ? d - hc : d < -hc ? d + hc : 0.0;
      if (e2 == 0) return 0.0;  // no contact, no force
      if constexpr (Slopes) {
        *fd = K;
        *fv = c;
        *ft = me.K * drel * e2 - K * derr;
      }
      if constexpr (Damped) return K * e2 + c * rate;
      else return K * e2;
    } else if constexpr (Contact == contact::Hertz) {
      if (d <= 0) return 0.0;
      double s = p.ramp > 0 ? std::min(1.0, d / p.ramp) : 1.0;
      double hd = me.ring ? p.hertzDampingRp : p.hertzDampingSp;
      double C = hd * s * s * (3.0 - 2.0 * s);
      if constexpr (Damped) C += c;
      double de = p.e == 1.5 ? d * std::sqrt(d) : std::pow(d, p.e);
      double f = K * de + C * rate;
      if (f <= 0) return 0.0;  // a contact pushes, never pulls
      if constexpr (Slopes) {
        double dstep = p.ramp > 0 && s < 1.0 ? 6.0 * s * (1.0 - s) / p.ramp : 0.0;
        *fd = p.e * K * de / d + hd * dstep * rate;
        *fv = C;
        *ft = me.K * drel * de - *fd * derr;
      }
      return f;
    } else {
      double f = K * d;
      if constexpr (Damped) f += c * rate;
      if constexpr (teForce) f += me.K * (rel - 1.0) * err;
      if constexpr (Slopes) {
        *fd = K;
        *fv = c;
        *ft = me.K * drel * d;
        if constexpr (teForce) *ft += me.K * (drel * err + (rel - 1.0) * derr);
      }
      return f;
    }
  }
  static double carrierPhase(const Params& p, const double* y) {
    if constexpr (needsPhase) return p.zr * y[0] / (2.0 * M_PI);
    else return 0.0;
  }
  static double meshForce(const Params& p, const Mesh& me, double t, const double* y) {
    double rate;
    double d = deflection(p, me, sunAngle(p, t, y), sunSpeed(p, t), y, rate);
    return force<false>(p, me, carrierPhase(p, y), d, rate, nullptr, nullptr, nullptr);
  }
  static void rhs(const Params& p, double t, const double* y, double* dy) {
    size_t nq = p.nq;
    for (size_t i = 0; i < nq; ++i) dy[i] = y[nq + i];
    double torqueC;
    if constexpr (TorqueFl) torqueC = -(p.tMean + p.tAmp * std::sin(p.tOmega * t));
    else torqueC = -p.tMean;
    double ts = sunAngle(p, t, y), ws = sunSpeed(p, t), cp = carrierPhase(p, y);
    std::array<double, 32> spin{};  // planets (at most 32, checked)
    for (const auto& me : p.meshes) {
      double rate;
      double d = deflection(p, me, ts, ws, y, rate);
      double f = force<false>(p, me, cp, d, rate, nullptr, nullptr, nullptr);
      torqueC += f * (me.ring ? p.rbr : p.rbs);
      spin[static_cast<size_t>(me.planet)] += me.ring ? f * p.rbp : -f * p.rbp;
    }
    dy[nq] = torqueC / p.JcEff;
    for (int i = 0; i < p.N; ++i) dy[nq + 1 + static_cast<size_t>(i)] = spin[static_cast<size_t>(i)] / p.Jp;
    if constexpr (Phase == drivephase::State) dy[2 * nq] = p.drive.speed(t);
  }
  // The state Jacobian, row-major: each mesh force depends on the carrier angle (deflection
  // and mesh phase), its planet's angle, their speeds, and the drive angle when it is a state.
  static void dfdy(const Params& p, double t, const double* y, double* J) {
    size_t nq = p.nq, n = 2 * nq + (Phase == drivephase::State ? 1 : 0);
    std::fill(J, J + n * n, 0.0);
    for (size_t i = 0; i < nq; ++i) J[i * n + nq + i] = 1.0;
    double ts = sunAngle(p, t, y), ws = sunSpeed(p, t), cp = carrierPhase(p, y);
    double dtau = needsPhase ? p.zr / (2.0 * M_PI) : 0.0;
    for (const auto& me : p.meshes) {
      double rate, fd, fv, ft;
      double d = deflection(p, me, ts, ws, y, rate);
      force<true>(p, me, cp, d, rate, &fd, &fv, &ft);
      size_t ip = 1 + static_cast<size_t>(me.planet);
      double gc = me.ring ? -p.rbr : -p.rbs, gp = me.ring ? -p.rbp : p.rbp;  // d(deflection)/d(theta_c, phi)
      double df[4] = {fd * gc + ft * dtau, fd * gp, fv * gc, fv * gp};
      size_t col[4] = {0, ip, nq, nq + ip};
      double toC = (me.ring ? p.rbr : p.rbs) / p.JcEff, toP = (me.ring ? p.rbp : -p.rbp) / p.Jp;
      double* rowC = J + nq * n;
      double* rowP = J + (nq + ip) * n;
      for (int k = 0; k < 4; ++k) {
        rowC[col[k]] += toC * df[k];
        rowP[col[k]] += toP * df[k];
      }
      if constexpr (Phase == drivephase::State)
        if (!me.ring) {
          rowC[2 * nq] += toC * fd * p.rbs;
          rowP[2 * nq] += toP * fd * p.rbs;
        }
    }
  }
};

struct Compiled {
  std::function<void(double, const double*, double*)> rhs;
  std::function<void(double, const double*, double*)> dfdy;
  std::function<double(const Mesh&, double, const double*)> force;
  std::function<double(const Mesh&, double, const double*, double&)> deflection;  // events and signals
};

Compiled compile(const Params& p, bool varying, bool damped, int contactKind, bool te, bool torqueFl, int phase) {
  Compiled c;
  withBool(varying, [&](auto V) {
    withBool(damped, [&](auto D) {
      withInt3(contactKind, [&](auto C) {
        withBool(te, [&](auto TE) {
          withBool(torqueFl, [&](auto Q) {
            withInt3(phase, [&](auto P) {
              using K = Kernel<decltype(V)::value, decltype(D)::value, decltype(C)::value, decltype(TE)::value, decltype(Q)::value,
                               decltype(P)::value>;
              const Params* pp = &p;
              c.rhs = [pp](double t, const double* y, double* dy) { K::rhs(*pp, t, y, dy); };
              c.dfdy = [pp](double t, const double* y, double* J) { K::dfdy(*pp, t, y, J); };
              c.force = [pp](const Mesh& me, double t, const double* y) { return K::meshForce(*pp, me, t, y); };
              c.deflection = [pp](const Mesh& me, double t, const double* y, double& rate) {
                return K::deflection(*pp, me, K::sunAngle(*pp, t, y), K::sunSpeed(*pp, t), y, rate);
              };
            });
          });
        });
      });
    });
  });
  return c;
}

// A planetary stage's scene set up and run, step by step: its geometry and inertias, the
// effects it lists and the contact law, the load and the drive, the stiffness variation, the
// meshes and their parameters, the modes and the time plan, the initial state, and the run
// (a transient, or the periodic steady state).
class PlanetaryAssembly {
public:
  struct Inputs {
    const Evaluator& ev;
    const Assignment& a;
    int st;
    const ScenePlan& scene;
    Accuracy acc;
    const SceneOverrides& ov;
    double upstream, downstream, speed, E, nu, density;
    bool materialAssumed, periodic;
  };
  explicit PlanetaryAssembly(const Inputs& in)
      : in_(in), ev(in.ev), a(in.a), st(in.st), scene(in.scene), acc(in.acc), prov(run.provenance) {}

  PlanetaryRun build() {
    geometry();
    contact();
    loadAndDrive();
    variation();
    parameters();
    system();
    modes();
    initialState();
    if (!in_.periodic) {
      transient();
      return std::move(run);
    }
    steadyState();
    return std::move(run);
  }

private:
  const Inputs& in_;
  const Evaluator& ev;
  const Assignment& a;
  const int st;
  const ScenePlan& scene;
  Accuracy acc;  // its maximum step is set from the modes
  PlanetaryRun run;
  std::vector<std::string>& prov;
  // Geometry and inertias.
  double zs = 0, zp = 0, zr = 0, mod = 0, alpha = 0, rbs = 0, rbp = 0, rbr = 0, rc = 0, rp = 0, b = 0;
  int N = 0;
  double Jp = 0, JcEff = 0;
  // Contact.
  double Ksp = 0, Krp = 0, e = 1.5, ramp = 0, hertzDampingSp = 0, hertzDampingRp = 0, kLinSp = 0, kLinRp = 0;
  // The listed effects, each empty where the scene does not list it.
  const std::optional<SceneEffects::Hertz>& hertz = scene.fx.hertz;
  const std::optional<SceneEffects::Varying>& varying = scene.fx.varying;
  const std::optional<SceneEffects::Damping>& damping = scene.fx.damping;
  const std::optional<SceneEffects::Fluctuation>& torqueFx = scene.fx.torque;
  const std::optional<SceneEffects::TransmissionError>& te = scene.fx.transmissionError;
  const std::optional<SceneEffects::Backlash>& backlash = scene.fx.backlash;
  // Load, drive, time scales.
  double tMean = 0, tAmp = 0, tOmega = 0, ratio = 1, Tz = 0, Tn = 0, F0 = 0;
  Drive drive;
  Fourier fourier;
  std::vector<Mesh> meshes;
  double halfClearance = 0, teMean = 0, teAmp = 0, tePhase = 0;
  // The model.
  size_t nq = 0, dim = 0;
  Params P;
  Compiled model;
  System sys;
  std::vector<double> y;

  void geometry() {
    using namespace cat::gear;
    zs = need(ev.attribute(st, Sun, Q::Z, a), "sun.z");
    zp = need(ev.attribute(st, Planet, Q::Z, a), "planet.z");
    zr = need(ev.attribute(st, Ring, Q::Z, a), "ring.z");
    N = static_cast<int>(need(ev.attribute(st, Q::Planets, a), "planets"));
    if (N < 1 || N > 32) throw SceneFailure{fmt::format("a planetary scene models 1 to 32 planets, not {}", N)};
    mod = need(ev.attribute(st, Q::Module, a), "`module`");
    alpha = need(ev.attribute(st, Q::PressureAngle, a), "the pressure angle");
    rbs = 0.5 * zs * mod * std::cos(alpha);
    rbp = 0.5 * zp * mod * std::cos(alpha);
    rbr = 0.5 * zr * mod * std::cos(alpha);
    rc = 0.5 * (zs + zp) * mod;
    rp = 0.5 * zp * mod;
    Value bw = ev.attribute(st, Q::FaceWidth, a);
    b = bw.isNumber() ? bw.mid() : 10.0 * mod;
    if (!bw.isNumber()) prov.push_back(fmt::format("face width {:.2f} mm assumed (10 x module): not given", b * 1e3));
    if (in_.materialAssumed) prov.push_back("density 7850 kg/m^3, E = 206 GPa, nu = 0.3 (steel assumed: no material given)");
    double mp = in_.density * M_PI * rp * rp * b;
    Value jpGiven = ev.attribute(st, Planet, Q::Inertia, a);
    Jp = jpGiven.isNumber() ? jpGiven.mid() : 0.5 * mp * rp * rp;
    Value jcGiven = ev.attribute(st, Q::CarrierInertia, a);
    double Rcar = rc + rp;
    double Jc = jcGiven.isNumber() ? jcGiven.mid() : 0.5 * in_.density * M_PI * Rcar * Rcar * b * Rcar * Rcar;
    JcEff = Jc + N * mp * rc * rc;
    prov.push_back(fmt::format("planet inertia {:.4g} kg*m^2 ({}), carrier {:.4g} kg*m^2 ({}) + {} planets at r = {:.2f} mm",
                               Jp, jpGiven.isNumber() ? "given" : "solid disc", Jc, jcGiven.isNumber() ? "given" : "disc of radius rc + rp",
                               N, rc * 1e3));
  }

  // Hertz stiffness K = 4/3 sqrt(R) E*; the ring-planet mesh is internal, so the curvatures
  // subtract (the source paper adds them; docs/dynamics.md). Every listed effect must be one the
  // planetary model implements (its registry row says).
  void contact() {
    double Estar = in_.E / (2.0 * (1.0 - in_.nu * in_.nu));
    double rhoS = rbs * std::tan(alpha), rhoP = rbp * std::tan(alpha), rhoR = rbr * std::tan(alpha);
    double Rsp = 1.0 / (1.0 / rhoS + 1.0 / rhoP), Rrp = 1.0 / (1.0 / rhoP - 1.0 / rhoR);
    Ksp = 4.0 / 3.0 * std::sqrt(Rsp) * Estar;
    Krp = 4.0 / 3.0 * std::sqrt(Rrp) * Estar;
    for (const auto& fx : scene.listed)
      if (const EffectRow* row = effectRow(fx.kind); !row || !row->planetary)
        throw SceneFailure{fmt::format("effect `{}` is not modelled on planetary stages", fx.name)};
    if (backlash && hertz) throw SceneFailure{"`backlash` and `hertz_contact` both describe the contact: list one"};
    if (hertz) {
      e = hertz->exponent;
      ramp = hertz->penetrationRamp;
      hertzDampingSp = hertz->damping({adamsStiffness(Ksp, e)});
      hertzDampingRp = hertz->damping({adamsStiffness(Krp, e)});
      prov.push_back(fmt::format("Hertz stiffness sun-planet {:.4g}, ring-planet {:.4g} N/m^{} (R = {:.3f} / {:.3f} mm, internal curvature subtracted)",
                                 Ksp, Krp, e, Rsp * 1e3, Rrp * 1e3));
    }
  }

  // Load on the carrier: the gearbox output torque brought back through the stages after it;
  // the drive; the static mesh force and the linearised stiffness there.
  void loadAndDrive() {
    double outTorque = need(ev.gearboxQuantity(Q::OutputTorque, a), "an output torque (`operating`)");
    tMean = outTorque / in_.downstream;
    if (torqueFx) {
      tMean = torqueFx->mean / in_.downstream;
      tAmp = torqueFx->amplitude / in_.downstream;
      tOmega = torqueFx->omega;
      prov.push_back("load torque mean + amplitude sin(frequency t) at the gearbox output, brought to the carrier");
    }
    ratio = 1.0 + zr / zs;
    Tz = 2.0 * M_PI / (in_.speed / ratio * zr);
    run.meshFrequency = 1.0 / Tz;
    drive = sceneDrive(scene, in_.speed, in_.upstream, Tz);
    F0 = std::fabs(tMean) / (N * (rbs + rbr));
    auto linear = [&](double K) { return hertz ? e * K * std::pow(std::max(F0, 1e-9) / K, (e - 1.0) / e) : K; };
    kLinSp = linear(Ksp);
    kLinRp = linear(Krp);
    if (!hertz) {
      // Without a contact law the meshes are linear springs of the ISO mesh stiffness.
      Value cg = ev.attribute(st, Q::MeshStiffness, a);
      double k = (cg.isNumber() ? cg.mid() : 16e9) * b;
      Ksp = Krp = kLinSp = kLinRp = k;
      prov.push_back(fmt::format("linear mesh stiffness {:.4g} N/m ({})", k, cg.isNumber() ? "c_gamma given x b" : "c_gamma 16 N/(mm*um) x b assumed"));
    }
  }


  void variation() {
    if (!varying) return;
    int harmonics = in_.ov.harmonics ? *in_.ov.harmonics : varying->harmonics;
    run.harmonics = harmonics;
    double eSp = epsAlphaStandard(zs, zp, mod, alpha, false);
    fourier = contactLineSeries(eSp, 0.0, harmonics);
    prov.push_back(fmt::format("contact-line stiffness variation, {} harmonics, eps_alpha {:.4f} (sun-planet)", harmonics, eSp));
  }

  // Meshes: sun-planet i and ring-planet i, phased by the planets' positions psi_i = 2 pi i/N:
  // zs psi_i / 2 pi on the sun, -zr psi_i / 2 pi on the ring (Parker and Lin's mesh phasing),
  // equal modulo one by the assembly condition, so every planet meets the same mesh cycle.
  // Then the transmission error, the damping and the kernel's parameters.
  void parameters() {
    for (int i = 0; i < N; ++i) {
      meshes.push_back({Ksp, std::fmod(zs * i / static_cast<double>(N), 1.0), false, i});
      meshes.push_back({Krp, 1.0 - std::fmod(zr * i / static_cast<double>(N), 1.0), true, i});
    }
    halfClearance = backlash ? 0.5 * backlash->clearance : 0.0;
    if (te) {
      teMean = te->mean;
      teAmp = te->amplitude;
      tePhase = te->phase;
      prov.push_back("transmission error on every mesh, F = dk(t) e(t), phased with the mesh");
    }
    double cSp = 0, cRp = 0;
    if (damping) {
      double mEq = Jp / (rbp * rbp);
      if (damping->coefficient) cSp = cRp = *damping->coefficient;
      else {
        double z = damping->ratio;
        cSp = 2 * z * std::sqrt(kLinSp * mEq);
        cRp = 2 * z * std::sqrt(kLinRp * mEq);
      }
    }
    // Degrees of freedom: q = [theta_c, phi_1..phi_N]; state = [q, q'] (+ drive angle).
    nq = static_cast<size_t>(N) + 1;
    dim = 2 * nq + (drive.needsState() ? 1 : 0);
    P.N = N;
    P.nq = nq;
    P.rbs = rbs;
    P.rbp = rbp;
    P.rbr = rbr;
    P.zr = zr;
    P.JcEff = JcEff;
    P.Jp = Jp;
    P.meshes = meshes;
    P.fourier = fourier;
    P.e = e;
    P.ramp = ramp;
    P.hertzDampingSp = hertzDampingSp;
    P.hertzDampingRp = hertzDampingRp;
    P.halfClearance = halfClearance;
    P.teMean = teMean;
    P.teAmp = teAmp;
    P.tePhase = tePhase;
    P.cSp = cSp;
    P.cRp = cRp;
    P.tMean = tMean;
    P.tAmp = tAmp;
    P.tOmega = tOmega;
    P.drive = drive;
  }

  // The transmission error of a mesh at the carrier angle y[0].
  double error(const Mesh& me, const double* ys) const {
    double tau = zr * ys[0] / (2.0 * M_PI) + me.phase0;
    return te ? teMean + teAmp * std::sin(2.0 * M_PI * tau + tePhase) : 0.0;
  }

  // The kernel the effects select, and its contact events.
  void system() {
    int contactKind = backlash ? contact::Backlash : hertz ? contact::Hertz : contact::Linear;
    int phaseKind = drive.needsState()                   ? drivephase::State
                    : drive.fluctuates || drive.ramp > 0 ? drivephase::ClosedForm
                                                         : drivephase::Constant;
    model = compile(P, varying.has_value(), damping.has_value(), contactKind, te.has_value(), torqueFx.has_value(), phaseKind);
    sys.dim = dim;
    sys.rhs = model.rhs;
    sys.dfdy = model.dfdy;
    if (hertz)
      for (const auto& me : meshes)
        sys.events.push_back([this, me](double t, const double* ys) {
          double rate;
          return model.deflection(me, t, ys, rate) - error(me, ys);
        });
    if (backlash)
      for (const auto& me : meshes)
        for (double side : {1.0, -1.0})
          sys.events.push_back([this, me, side](double t, const double* ys) {
            double rate;
            return model.deflection(me, t, ys, rate) - error(me, ys) - side * halfClearance;
          });
  }

  // Linearised model: stiffness K = sum k g g^T with g = d(deflection)/dq; modes from the
  // generalised eigenproblem K v = w^2 M v; the step rule and the time plan.
  void modes() {
    Eigen::MatrixXd Km = Eigen::MatrixXd::Zero(static_cast<long>(nq), static_cast<long>(nq)), M = Km;
    M(0, 0) = JcEff;
    for (int i = 0; i < N; ++i) M(1 + i, 1 + i) = Jp;
    for (const auto& me : meshes) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<long>(nq));
      g(0) = me.ring ? -rbr : -rbs;
      g(1 + me.planet) = me.ring ? -rbp : rbp;
      Km += (me.ring ? kLinRp : kLinSp) * g * g.transpose();
    }
    run.modes = naturalFrequencies(Km, M);
    double fmax = 0;
    for (double f : run.modes) {
      fmax = std::max(fmax, f);
      for (int k = 1; k <= 10 && f > 0; ++k)
        if (std::fabs(k * run.meshFrequency - f) <= 0.1 * f)
          prov.push_back(fmt::format("warning: mesh harmonic {} x {:.2f} Hz lies within 10 % of the mode at {:.2f} Hz", k, run.meshFrequency, f));
    }
    prov.push_back(fmt::format("mesh frequency {:.4f} Hz; linearised modes {} Hz", run.meshFrequency, frequencyList(run.modes)));
    Tn = fmax > 0 ? 1.0 / fmax : Tz;
    run.stepRule = lumpedMaxStep(acc.maxStep, Tz, fmax, in_.ov.maxStepFactor, "Tz/20");
    // With `periodic` the record window starts at t = 0 on the orbit.
    run.plan = in_.periodic ? periodicPlan(scene, Tz) : timePlan(scene, Tz, in_.ov.settlePeriods);
  }

  // The static deflection on every mesh, at the kinematic speeds; the state's scales.
  void initialState() {
    double d0 = hertz ? std::pow(F0 / Ksp, 1.0 / e) : F0 / Ksp + halfClearance;
    y.assign(dim, 0.0);
    y[0] = -2.0 * d0 / (rbs + rbr);
    for (int i = 0; i < N; ++i) y[1 + static_cast<size_t>(i)] = (d0 - rbs * (drive.angle(0.0) - y[0])) / rbp;
    double ws0 = drive.speed(0);
    y[nq] = ws0 / ratio;
    for (int i = 0; i < N; ++i) y[nq + 1 + static_cast<size_t>(i)] = -rbs * (ws0 - y[nq]) / rbp;
    sys.scale.assign(dim, 1.0);
    for (size_t i = 0; i < nq; ++i) {
      sys.scale[i] = d0 / rbp;
      sys.scale[nq + i] = std::max(in_.speed, d0 / rbp / Tn);
    }
    run.staticLoad = F0;
  }

  // The signals of the first planet's sun mesh at one sample.
  void sample(double ts, const double* ys) {
    std::vector<double> dy(dim);
    sys.rhs(ts, ys, dy.data());
    double rate;
    double d = model.deflection(meshes[0], ts, ys, rate);
    double f = model.force(meshes[0], ts, ys);
    run.t.push_back(ts);
    using cat::Signal;
    series(run.signals, Signal::Displacement).push_back(d);
    series(run.signals, Signal::Velocity).push_back(rate);
    series(run.signals, Signal::Acceleration).push_back(rbs * (drive.acceleration(ts) - dy[nq]) + rbp * dy[nq + 1]);
    series(run.signals, Signal::MeshForce).push_back(f);
    series(run.signals, Signal::ContactForce).push_back(f);
    series(run.signals, Signal::Stiffness).push_back(varying ? meshes[0].K * relativeStiffness(fourier, zr * ys[0] / (2.0 * M_PI)) : meshes[0].K);
    if (te) series(run.signals, Signal::TransmissionError).push_back(error(meshes[0], ys));
    series(run.signals, Signal::InputSpeed).push_back(drive.speed(ts) * in_.upstream);
    series(run.signals, Signal::OutputSpeed).push_back(ys[nq] / in_.downstream);
  }

  // From `y` over the time plan, sampled; whether it got there.
  bool record() {
    Integrator integ(sys, acc);
    double t = 0;
    bool ok = integ.advance(t, y, run.plan.end, run.plan.samples, [this](double ts, const double* ys) { sample(ts, ys); });
    run.stats += integ.stats();
    if (!ok) run.failure = integ.error();
    return ok;
  }

  void transient() { record(); }

  void notPeriodic(const std::string& why) {
    run.failure = fmt::format("the excitation is not periodic ({}), so there is no periodic steady state: write `settle = N "
                              "mesh_periods` to settle a transient, or `duration` for a run from rest",
                              why);
  }

  // The orbit by harmonic balance (dynamics/HarmonicBalance.h), the samples from its series;
  // false, with a line saying why, where it is not found (shooting then takes over).
  bool balance(const PeriodicOptions& opt, int q) {
    BalanceOptions bo;
    bo.period = opt.period;
    bo.drift = opt.drift;
    bo.linear = opt.linear;
    bo.floquet = acc;
    SceneBalance b = sceneBalance(sys, bo, scene, in_.ov, acc.rtol, y, 2048, q);
    run.stats += b.stats;
    prov.push_back(b.line);
    if (!b.warning.empty()) run.warnings.push_back(b.warning);
    if (!b.orbit) return false;
    const BalanceOrbit& o = *b.orbit;
    run.newtonIterations = o.iterations;
    run.newtonResidual = o.gapResidual;
    run.stability = o.stability;
    run.balanceHarmonics = o.harmonics;
    y = o.state(0);
    run.orbit = y;
    run.period = opt.period;
    double cpu = threadCpuSeconds();
    std::vector<double> ys(dim);
    for (double ts : run.plan.samples) {
      o.state(ts, ys.data());
      sample(ts, ys.data());
    }
    run.stats.cpuSeconds += threadCpuSeconds() - cpu;
    return true;
  }

  // The periodic steady state (dynamics/Periodic.h). The excitation repeats after whole mean
  // mesh periods that also hold whole periods of every fluctuation.
  void steadyState() {
    run.periodic = true;
    if (drive.ramp > 0) return notPeriodic("a `ramp` start-up");
    double sunMean = drive.fluctuates ? drive.mean : drive.speed0;
    std::vector<double> periods;
    if (drive.fluctuates && drive.amplitude != 0) periods.push_back(drive.omega > 0 ? 2.0 * M_PI / drive.omega : INFINITY);
    if (torqueFx && tAmp != 0) periods.push_back(tOmega > 0 ? 2.0 * M_PI / tOmega : INFINITY);
    double Tm = !drive.fluctuates ? Tz : sunMean > 0 ? 2.0 * M_PI * ratio / (sunMean * zr) : INFINITY;
    int q = std::isfinite(Tm) ? wholeMeshPeriods(Tm, periods) : 0;
    if (q == 0) return notPeriodic("no whole number of mesh periods, up to 1000, holds whole periods of the fluctuations");
    double period = q * Tm;
    // Outputs over a whole orbit: a record window shorter than its period is widened to it.
    if (widenToPeriod(run.plan, period)) prov.push_back(fmt::format("record window widened to the orbit's period, {} mesh periods", q));
    // Drift over a period: the carrier turns q ring-tooth pitches; the sun-planet deflection
    // rbs (theta_s - theta_c) + rbp phi repeats, so phi advances -rbs (d theta_s - d theta_c) / rbp.
    double carrierAdvance = q * 2.0 * M_PI / zr, sunAdvance = ratio * carrierAdvance;
    PeriodicOptions opt;
    opt.period = period;
    opt.drift.assign(dim, 0.0);
    opt.drift[0] = carrierAdvance;
    for (size_t i = 1; i < nq; ++i) opt.drift[i] = -rbs * (sunAdvance - carrierAdvance) / rbp;
    opt.linear = !hertz && !backlash && !varying;  // the phase (carrier angle) makes varying stiffness nonlinear
    const SceneOverrides& ov = in_.ov;
    if (ov.harmonicBalance.value_or(scene.harmonicBalance) && balance(opt, q)) return;
    PeriodicOrbit orbit = periodicOrbit(sys, acc, opt, ov.guess && ov.guess->size() == dim ? *ov.guess : y);
    run.stats = orbit.stats;
    run.newtonIterations = orbit.iterations;
    run.newtonResidual = orbit.residual;
    if (!orbit.converged) {
      run.failure = "the periodic steady state was not found: " + orbit.failure;
      return;
    }
    run.stability = orbit.stability;
    prov.push_back(fmt::format("periodic steady state: period {:.6g} ms ({} mesh period{}), Newton {} iteration{} (monodromy by {}), "
                               "residual {:.2e} of the state scale, largest Floquet multiplier {:.6f}",
                               period * 1e3, q, q == 1 ? "" : "s", orbit.iterations, orbit.iterations == 1 ? "" : "s",
                               orbit.variational ? "variational equations" : "differences", orbit.residual, orbit.stability));
    y = orbit.y0;
    run.orbit = orbit.y0;
    run.period = period;
    record();
  }
};

} // namespace

PlanetaryRun runPlanetary(const Evaluator& ev, const Assignment& a, int st, const ScenePlan& scene, Accuracy acc,
                          const SceneOverrides& ov, double upstream, double downstream, double speed, double E, double nu,
                          double density, bool materialAssumed, bool periodic) {
  return PlanetaryAssembly({ev, a, st, scene, acc, ov, upstream, downstream, speed, E, nu, density, materialAssumed, periodic}).build();
}

} // namespace gbx::rt::dyn
