#include "dynamics/Planetary.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "catalogue/StageKinds.h"
#include "dynamics/Effects.h"
#include "dynamics/Scene.h"
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

} // namespace

PlanetaryRun runPlanetary(const Evaluator& ev, const Assignment& a, int st, const ir::Scene& scene, Accuracy acc,
                          const SceneOverrides& ov, double upstream, double downstream, double speed, double E, double nu,
                          double density, bool materialAssumed) {
  PlanetaryRun run;
  auto& prov = run.provenance;
  using namespace cat::gear;
  using cat::Effect;
  double zs = need(ev.attribute(st, Sun, Q::Z, a), "sun.z"), zp = need(ev.attribute(st, Planet, Q::Z, a), "planet.z"),
         zr = need(ev.attribute(st, Ring, Q::Z, a), "ring.z");
  int N = static_cast<int>(need(ev.attribute(st, Q::Planets, a), "planets"));
  if (N < 1 || N > 32) throw SceneFailure{fmt::format("a planetary scene models 1 to 32 planets, not {}", N)};
  double mod = need(ev.attribute(st, Q::Module, a), "`module`");
  double alpha = need(ev.attribute(st, Q::PressureAngle, a), "the pressure angle");
  double rbs = 0.5 * zs * mod * std::cos(alpha), rbp = 0.5 * zp * mod * std::cos(alpha), rbr = 0.5 * zr * mod * std::cos(alpha);
  double rc = 0.5 * (zs + zp) * mod, rp = 0.5 * zp * mod;
  Value bw = ev.attribute(st, Q::FaceWidth, a);
  double b = bw.isNumber() ? bw.mid() : 10.0 * mod;
  if (!bw.isNumber()) prov.push_back(fmt::format("face width {:.2f} mm assumed (10 x module): not given", b * 1e3));
  if (materialAssumed) prov.push_back("density 7850 kg/m^3, E = 206 GPa, nu = 0.3 (steel assumed: no material given)");
  double mp = density * M_PI * rp * rp * b;
  Value jpGiven = ev.attribute(st, Planet, Q::Inertia, a);
  double Jp = jpGiven.isNumber() ? jpGiven.mid() : 0.5 * mp * rp * rp;
  Value jcGiven = ev.attribute(st, Q::CarrierInertia, a);
  double Rcar = rc + rp;
  double Jc = jcGiven.isNumber() ? jcGiven.mid() : 0.5 * density * M_PI * Rcar * Rcar * b * Rcar * Rcar;
  double JcEff = Jc + N * mp * rc * rc;
  prov.push_back(fmt::format("planet inertia {:.4g} kg*m^2 ({}), carrier {:.4g} kg*m^2 ({}) + {} planets at r = {:.2f} mm",
                             Jp, jpGiven.isNumber() ? "given" : "solid disc", Jc, jcGiven.isNumber() ? "given" : "disc of radius rc + rp",
                             N, rc * 1e3));
  // Hertz stiffness K = 4/3 sqrt(R) E*; the ring-planet mesh is internal, so the
  // curvatures subtract (the source paper adds them; DOMAIN.md §2).
  double Estar = E / (2.0 * (1.0 - nu * nu));
  double rhoS = rbs * std::tan(alpha), rhoP = rbp * std::tan(alpha), rhoR = rbr * std::tan(alpha);
  double Rsp = 1.0 / (1.0 / rhoS + 1.0 / rhoP), Rrp = 1.0 / (1.0 / rhoP - 1.0 / rhoR);
  double Ksp = 4.0 / 3.0 * std::sqrt(Rsp) * Estar, Krp = 4.0 / 3.0 * std::sqrt(Rrp) * Estar;

  // Every listed effect must be one the planetary model implements (its registry row says).
  for (const auto& fx : scene.effects)
    if (const EffectRow* row = effectRow(fx.kind); !row || !row->planetary)
      throw SceneFailure{fmt::format("effect `{}` is not modelled on planetary stages", fx.name)};
  const ir::Effect* hertz = scene.findEffect(Effect::HertzContact);
  const ir::Effect* varying = scene.findEffect(Effect::VaryingStiffness);
  const ir::Effect* damping = scene.findEffect(Effect::Damping);
  const ir::Effect* torqueFx = scene.findEffect(Effect::TorqueFluctuation);
  const ir::Effect* te = scene.findEffect(Effect::TransmissionError);
  const ir::Effect* backlash = scene.findEffect(Effect::Backlash);
  if (backlash && hertz) throw SceneFailure{"`backlash` and `hertz_contact` both describe the contact: list one"};
  double e = 1.5, ramp = 0, hertzDampingSp = 0, hertzDampingRp = 0;
  if (hertz) {
    if (const auto* s = effectParam(hertz, Q::Exponent)) e = settingValue(*s);
    if (const auto* s = effectParam(hertz, Q::PenetrationRamp)) ramp = settingValue(*s);
    if (const auto* s = effectParam(hertz, Q::Damping)) {
      hertzDampingSp = settingValue(*s, {adamsStiffness(Ksp, e)});
      hertzDampingRp = settingValue(*s, {adamsStiffness(Krp, e)});
    }
    prov.push_back(fmt::format("Hertz stiffness sun-planet {:.4g}, ring-planet {:.4g} N/m^{} (R = {:.3f} / {:.3f} mm, internal curvature subtracted)",
                               Ksp, Krp, e, Rsp * 1e3, Rrp * 1e3));
  }
  // Load on the carrier: the gearbox output torque brought back through the stages after it.
  double outTorque = need(ev.gearboxQuantity(Q::OutputTorque, a), "an output torque (`operating`)");
  double tMean = outTorque / downstream, tAmp = 0, tOmega = 0;
  if (torqueFx) {
    tMean = settingValue(*effectParam(torqueFx, Q::Mean)) / downstream;
    tAmp = settingValue(*effectParam(torqueFx, Q::Amplitude)) / downstream;
    tOmega = angularFrequency(*effectParam(torqueFx, Q::Frequency));
    prov.push_back("load torque mean + amplitude sin(frequency t) at the gearbox output, brought to the carrier");
  }
  double ratio = 1.0 + zr / zs;
  double Tz = 2.0 * M_PI / (speed / ratio * zr);
  run.meshFrequency = 1.0 / Tz;
  Drive drive = sceneDrive(scene, speed, upstream, Tz);
  // Static mesh force and the linearised stiffness there.
  double F0 = std::fabs(tMean) / (N * (rbs + rbr));
  auto linear = [&](double K) { return hertz ? e * K * std::pow(std::max(F0, 1e-9) / K, (e - 1.0) / e) : K; };
  double kLinSp = linear(Ksp), kLinRp = linear(Krp);
  if (!hertz) {
    // Without a contact law the meshes are linear springs of the ISO mesh stiffness.
    Value cg = ev.attribute(st, Q::MeshStiffness, a);
    double k = (cg.isNumber() ? cg.mid() : 16e9) * b;
    Ksp = Krp = kLinSp = kLinRp = k;
    prov.push_back(fmt::format("linear mesh stiffness {:.4g} N/m ({})", k, cg.isNumber() ? "c_gamma given x b" : "c_gamma 16 N/(mm*um) x b assumed"));
  }
  Fourier fourier;
  int harmonics = 0;
  if (varying) {
    harmonics = ov.harmonics ? *ov.harmonics : static_cast<int>(settingValue(*effectParam(varying, Q::Harmonics)));
    // Spur meshes: contact ratio from the standard geometry of each pair.
    auto epsAlpha = [&](double z1, double z2, bool internal) {
      double ra1 = 0.5 * z1 * mod + mod, rb1 = 0.5 * z1 * mod * std::cos(alpha);
      double ra2 = internal ? 0.5 * z2 * mod - mod : 0.5 * z2 * mod + mod, rb2 = 0.5 * z2 * mod * std::cos(alpha);
      double a0 = internal ? 0.5 * (z2 - z1) * mod : 0.5 * (z1 + z2) * mod;
      double path = std::sqrt(ra1 * ra1 - rb1 * rb1) + (internal ? -1.0 : 1.0) * std::sqrt(ra2 * ra2 - rb2 * rb2) +
                    (internal ? 1.0 : -1.0) * a0 * std::sin(alpha);
      return path / (M_PI * mod * std::cos(alpha));
    };
    double eSp = epsAlpha(zs, zp, false);
    fourier = contactLineSeries(eSp, 0.0, harmonics);
    prov.push_back(fmt::format("contact-line stiffness variation, {} harmonics, eps_alpha {:.4f} (sun-planet)", harmonics, eSp));
  }
  // Meshes: sun-planet i and ring-planet i, phased by the planets' positions.
  std::vector<Mesh> meshes;
  for (int i = 0; i < N; ++i) {
    meshes.push_back({Ksp, std::fmod(zs * i / static_cast<double>(N), 1.0), false, i});
    meshes.push_back({Krp, std::fmod(zr * i / static_cast<double>(N), 1.0), true, i});
  }
  double halfClearance = backlash ? 0.5 * settingValue(*effectParam(backlash, Q::Clearance)) : 0.0;
  double teMean = 0, teAmp = 0, tePhase = 0;
  if (te) {
    teMean = settingValue(*effectParam(te, Q::Mean));
    teAmp = settingValue(*effectParam(te, Q::Amplitude));
    tePhase = settingValue(*effectParam(te, Q::Phase));
    prov.push_back("transmission error on every mesh, F = dk(t) e(t), phased with the mesh");
  }
  double cSp = 0, cRp = 0;
  if (damping) {
    double mEq = Jp / (rbp * rbp);
    if (const auto* s = effectParam(damping, Q::Coefficient)) cSp = cRp = settingValue(*s);
    else {
      double z = settingValue(*effectParam(damping, Q::DampingRatio));
      cSp = 2 * z * std::sqrt(kLinSp * mEq);
      cRp = 2 * z * std::sqrt(kLinRp * mEq);
    }
  }
  // Degrees of freedom: q = [theta_c, phi_1..phi_N]; state = [q, q'] (+ drive angle).
  size_t nq = static_cast<size_t>(N) + 1;
  size_t dim = 2 * nq + (drive.needsState() ? 1 : 0);
  auto sunAngle = [&](double t, const double* y) { return drive.needsState() ? y[2 * nq] : drive.angle(t); };
  // Mesh deflection and its rate: sun-planet rbs(ts - tc) + rbp phi; ring-planet -rbp phi - rbr tc.
  auto deflection = [&](const Mesh& me, double t, const double* y, double& rate) {
    double tc = y[0], phi = y[1 + static_cast<size_t>(me.planet)], wc = y[nq], wphi = y[nq + 1 + static_cast<size_t>(me.planet)];
    if (me.ring) {
      rate = -rbp * wphi - rbr * wc;
      return -rbp * phi - rbr * tc;
    }
    rate = rbs * (drive.speed(t) - wc) + rbp * wphi;
    return rbs * (sunAngle(t, y) - tc) + rbp * phi;
  };
  auto carrierAngle = [&](const double* y) { return y[0]; };
  auto force = [&](const Mesh& me, double t, const double* y) {
    double rate;
    double d = deflection(me, t, y, rate);
    double rel = 1.0;
    if (varying) {
      // Mesh phase in the carrier frame: ring teeth passing per carrier turn.
      double tau = zr * carrierAngle(y) / (2.0 * M_PI) + me.phase0;
      rel = relativeStiffness(fourier, tau);
    }
    double K = me.K * rel;
    double c = me.ring ? cRp : cSp;
    // Transmission error: F = dk(t) e(t) on a mesh always in contact (DOMAIN.md §3); with
    // contact loss a displacement inside the contact law, so the force stays continuous.
    double tau = zr * carrierAngle(y) / (2.0 * M_PI) + me.phase0;
    double err = te ? teMean + teAmp * std::sin(2.0 * M_PI * tau + tePhase) : 0.0;
    double teForce = te && varying && !backlash && !hertz ? me.K * (rel - 1.0) * err : 0.0;
    if (backlash || hertz) d -= err;
    if (backlash) {
      // Dead zone: both flanks, contact lost inside the clearance.
      double e2 = d > halfClearance ? d - halfClearance : d < -halfClearance ? d + halfClearance : 0.0;
      return e2 != 0 ? K * e2 + c * rate : 0.0;  // no contact, no force
    }
    if (hertz) {
      if (d <= 0) return 0.0;
      double s = ramp > 0 ? std::min(1.0, d / ramp) : 1.0;
      double C = (me.ring ? hertzDampingRp : hertzDampingSp) * s * s * (3.0 - 2.0 * s);
      double de = e == 1.5 ? d * std::sqrt(d) : std::pow(d, e);
      return std::max(0.0, K * de + (C + c) * rate);
    }
    return K * d + c * rate + teForce;
  };
  auto load = [&](double t) { return tMean + tAmp * std::sin(tOmega * t); };
  System sys;
  sys.dim = dim;
  sys.rhs = [&](double t, const double* y, double* dy) {
    for (size_t i = 0; i < nq; ++i) dy[i] = y[nq + i];
    double torqueC = -load(t);
    std::array<double, 32> spin{};  // planets (at most 32, checked above)
    for (const auto& me : meshes) {
      double f = force(me, t, y);
      torqueC += f * (me.ring ? rbr : rbs);
      spin[static_cast<size_t>(me.planet)] += me.ring ? f * rbp : -f * rbp;
    }
    dy[nq] = torqueC / JcEff;
    for (int i = 0; i < N; ++i) dy[nq + 1 + static_cast<size_t>(i)] = spin[static_cast<size_t>(i)] / Jp;
    if (drive.needsState()) dy[2 * nq] = drive.speed(t);
  };
  auto error = [&](const Mesh& me, const double* y) {
    double tau = zr * carrierAngle(y) / (2.0 * M_PI) + me.phase0;
    return te ? teMean + teAmp * std::sin(2.0 * M_PI * tau + tePhase) : 0.0;
  };
  if (hertz)
    for (const auto& me : meshes)
      sys.events.push_back([&, me](double t, const double* y) {
        double rate;
        return deflection(me, t, y, rate) - error(me, y);
      });
  if (backlash)
    for (const auto& me : meshes)
      for (double side : {1.0, -1.0})
        sys.events.push_back([&, me, side](double t, const double* y) {
          double rate;
          return deflection(me, t, y, rate) - error(me, y) - side * halfClearance;
        });
  // Linearised model: stiffness K = sum k g g^T with g = d(deflection)/dq; modes from
  // the generalised eigenproblem K v = w^2 M v.
  Eigen::MatrixXd Km = Eigen::MatrixXd::Zero(static_cast<long>(nq), static_cast<long>(nq)), M = Km;
  M(0, 0) = JcEff;
  for (int i = 0; i < N; ++i) M(1 + i, 1 + i) = Jp;
  for (const auto& me : meshes) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<long>(nq));
    g(0) = me.ring ? -rbr : -rbs;
    g(1 + me.planet) = me.ring ? -rbp : rbp;
    Km += (me.ring ? kLinRp : kLinSp) * g * g.transpose();
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Km, M);
  double fmax = 0;
  for (long i = 0; i < eig.eigenvalues().size(); ++i) {
    double lam = eig.eigenvalues()(i);
    double f = lam > 0 ? std::sqrt(lam) / (2.0 * M_PI) : 0.0;
    run.modes.push_back(f);
    fmax = std::max(fmax, f);
    for (int k = 1; k <= 10 && f > 0; ++k)
      if (std::fabs(k * run.meshFrequency - f) <= 0.1 * f)
        prov.push_back(fmt::format("warning: mesh harmonic {} x {:.2f} Hz lies within 10 % of the mode at {:.2f} Hz", k, run.meshFrequency, f));
  }
  prov.push_back(fmt::format("mesh frequency {:.4f} Hz; linearised modes {} Hz", run.meshFrequency,
                             [&] {
                               std::string s;
                               for (double f : run.modes) s += (s.empty() ? "" : ", ") + fmt::format("{:.1f}", f);
                               return s;
                             }()));
  double Tn = fmax > 0 ? 1.0 / fmax : Tz;
  acc.maxStep = std::min(Tz, Tn) / 20.0;
  run.plan = timePlan(scene, Tz);
  // Initial state: the static deflection on every mesh, at the kinematic speeds.
  double d0 = hertz ? std::pow(F0 / Ksp, 1.0 / e) : F0 / Ksp + halfClearance;
  std::vector<double> y(dim, 0.0);
  y[0] = -2.0 * d0 / (rbs + rbr);
  for (int i = 0; i < N; ++i) y[1 + static_cast<size_t>(i)] = (d0 - rbs * (sunAngle(0, y.data()) - y[0])) / rbp;
  double ws0 = drive.speed(0);
  y[nq] = ws0 / ratio;
  for (int i = 0; i < N; ++i) y[nq + 1 + static_cast<size_t>(i)] = -rbs * (ws0 - y[nq]) / rbp;
  sys.scale.assign(dim, 1.0);
  for (size_t i = 0; i < nq; ++i) {
    sys.scale[i] = d0 / rbp;
    sys.scale[nq + i] = std::max(speed, d0 / rbp / Tn);
  }
  Integrator integ(sys, acc);
  double t = 0;
  bool ok = integ.advance(t, y, run.plan.end, run.plan.samples, [&](double ts, const double* ys) {
    std::vector<double> dy(dim);
    sys.rhs(ts, ys, dy.data());
    double rate;
    double d = deflection(meshes[0], ts, ys, rate);
    double f = force(meshes[0], ts, ys);
    run.t.push_back(ts);
    using cat::Signal;
    series(run.signals, Signal::Displacement).push_back(d);
    series(run.signals, Signal::Velocity).push_back(rate);
    series(run.signals, Signal::Acceleration).push_back(rbs * (drive.acceleration(ts) - dy[nq]) + rbp * dy[nq + 1]);
    series(run.signals, Signal::MeshForce).push_back(f);
    series(run.signals, Signal::ContactForce).push_back(f);
    series(run.signals, Signal::Stiffness).push_back(varying ? meshes[0].K * relativeStiffness(fourier, zr * ys[0] / (2.0 * M_PI)) : meshes[0].K);
    series(run.signals, Signal::TransmissionError).push_back(0.0);
    series(run.signals, Signal::InputSpeed).push_back(drive.speed(ts) * upstream);
    series(run.signals, Signal::OutputSpeed).push_back(ys[nq] / downstream);
  });
  run.stats = integ.stats();
  if (!ok) run.failure = integ.error();
  run.staticLoad = F0;
  return run;
}

} // namespace gbx::rt::dyn
