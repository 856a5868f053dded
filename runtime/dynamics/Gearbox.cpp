#include "dynamics/Gearbox.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "catalogue/StageKinds.h"
#include "dynamics/Dispatch.h"
#include "dynamics/Drive.h"
#include "dynamics/Effects.h"
#include "dynamics/LoadedMesh.h"
#include "dynamics/LoadedMeshInputs.h"
#include "dynamics/Lumped.h"
#include "dynamics/Periodic.h"
#include "dynamics/SceneBalance.h"
#include "dynamics/Stiffness.h"

namespace gbx::rt::dyn {

namespace {

// One mesh: its deflection along the line of action is sum coef[k] q[dof[k]] over at most
// three members (dof -1: the driven input, whose angle is prescribed).
struct GMesh {
  std::string name;
  bool reported = false;  // a planetary stage reports its first planet's meshes
  int stage = 0;
  int n = 0;
  std::array<int, 3> dof{};
  std::array<double, 3> coef{};
  double K = 0;             // Hertz stiffness (N/m^e), or linear stiffness
  double kLinear = 0;       // the linear stiffness at the static load (modes, damping ratio)
  double hertzDamping = 0;  // the contact law's damping, N*s/m
  double c = 0;             // `damping`, N*s/m
  double normal = 1;        // contact force / mesh force (1 / cos beta_b)
  int fourier = -1;         // its stiffness series
  int loaded = -1;          // its loaded-mesh tables (loaded_mesh)
  int phaseDof = -1;        // the member whose angle counts its mesh periods (-1: the input)
  double phaseGain = 0;     // mesh periods per radian of that member
  double phase0 = 0;        // planet phasing, mesh periods
  double meshFrequency = 0;
};

struct Params {
  size_t nq = 0;                  // members besides the input
  std::vector<double> J;          // their inertias
  std::vector<GMesh> meshes;
  std::vector<Fourier> fouriers;
  struct Loaded {
    PeriodicSeries k, u;  // mesh stiffness and the separation u = e_s - F0/k over a mesh period
  };
  std::vector<Loaded> loaded;
  double e = 1.5, ramp = 0, halfClearance = 0;
  int output = 0;                 // the loaded member
  double outSign = 1;             // its kinematic sense
  double tMean = 0, tAmp = 0, tOmega = 0;
  Drive drive;
  bool audit = false;             // three more states: drive work, load work, dissipation
};

namespace contact {
inline constexpr int Linear = 0, Backlash = 1, Hertz = 2, Loaded = 3;
}
namespace drivephase {
inline constexpr int Closed = 0, State = 1;
}

// The right-hand side compiled per combination of listed effects (as in MeshModel.cpp): an
// effect the scene does not list is absent from it, not tested for.
template <bool Varying, bool Damped, int Contact, bool TorqueFl, int Phase>
struct Kernel {
  static double inputAngle(const Params& p, double t, const double* y) {
    if constexpr (Phase == drivephase::State) return y[2 * p.nq];
    else return p.drive.angle(t);
  }
  static double deflection(const Params& p, const GMesh& me, double tin, double win, const double* y, double& rate) {
    double d = 0;
    rate = 0;
    for (int k = 0; k < me.n; ++k) {
      int j = me.dof[static_cast<size_t>(k)];
      double c = me.coef[static_cast<size_t>(k)];
      if (j < 0) {
        d += c * tin;
        rate += c * win;
      } else {
        d += c * y[j];
        rate += c * y[p.nq + static_cast<size_t>(j)];
      }
    }
    return d;
  }
  // The mesh force and its elastic part (the energy audit's dissipation is the difference);
  // with Slopes also its partial derivatives in the deflection, its rate and the mesh phase.
  template <bool Slopes = false>
  static double force(const Params& p, const GMesh& me, double tin, const double* y, double d, double rate, double& elastic,
                      double* fd = nullptr, double* fv = nullptr, double* ft = nullptr) {
    double K = me.K;
    [[maybe_unused]] double rel = 1.0, drel = 0.0;
    if constexpr (Varying) {
      double phi = me.phaseDof < 0 ? tin : y[me.phaseDof];
      const Fourier& f = p.fouriers[static_cast<size_t>(me.fourier)];
      double tau = me.phaseGain * phi + me.phase0;
      rel = relativeStiffness(f, tau);
      if constexpr (Slopes) drel = relativeStiffnessSlope(f, tau);
      K *= rel;
    }
    [[maybe_unused]] double c = 0;
    if constexpr (Damped) c = me.c;
    if constexpr (Slopes) *fd = *fv = *ft = 0;
    if constexpr (Contact == contact::Loaded) {
      // k(t) (x - u(t)): the loaded tooth contact of the flanks (docs/dynamics.md).
      double phi = me.phaseDof < 0 ? tin : y[me.phaseDof];
      double tau = me.phaseGain * phi + me.phase0;
      const auto& L = p.loaded[static_cast<size_t>(me.loaded)];
      double k = L.k(tau), u = L.u(tau);
      elastic = k * (d - u);
      if constexpr (Slopes) {
        *fd = k;
        *fv = c;
        *ft = relativeStiffnessSlope(L.k.f, tau) * (d - u) - k * relativeStiffnessSlope(L.u.f, tau);
      }
      return elastic + c * rate;
    } else if constexpr (Contact == contact::Backlash) {
      double hc = p.halfClearance;
      double e2 = d > hc ? d - hc : d < -hc ? d + hc : 0.0;
      elastic = K * e2;
      if (e2 == 0) return 0.0;
      if constexpr (Slopes) {
        *fd = K;
        *fv = c;
        *ft = me.K * drel * e2;
      }
      return K * e2 + c * rate;
    } else if constexpr (Contact == contact::Hertz) {
      elastic = 0;
      if (d <= 0) return 0.0;
      double s = p.ramp > 0 ? std::min(1.0, d / p.ramp) : 1.0;
      double C = me.hertzDamping * s * s * (3.0 - 2.0 * s) + c;
      double de = p.e == 1.5 ? d * std::sqrt(d) : std::pow(d, p.e);
      elastic = K * de;
      double f = elastic + C * rate;
      if (f <= 0) return 0.0;  // a contact pushes, never pulls
      if constexpr (Slopes) {
        double dstep = p.ramp > 0 && s < 1.0 ? 6.0 * s * (1.0 - s) / p.ramp : 0.0;
        *fd = p.e * K * de / d + me.hertzDamping * dstep * rate;
        *fv = C;
        *ft = me.K * drel * de;
      }
      return f;
    } else {
      elastic = K * d;
      if constexpr (Slopes) {
        *fd = K;
        *fv = c;
        *ft = me.K * drel * d;
      }
      return K * d + c * rate;
    }
  }
  // The state Jacobian, row-major (the implicit method needs it: the contact damping of the
  // source paper makes the light idler stiff). The energy audit's rows are left out.
  static void dfdy(const Params& p, double t, const double* y, double* Jm) {
    size_t nq = p.nq, n = 2 * nq + (Phase == drivephase::State ? 1 : 0) + (p.audit ? 3 : 0);
    std::fill(Jm, Jm + n * n, 0.0);
    for (size_t i = 0; i < nq; ++i) Jm[i * n + nq + i] = 1.0;
    double tin = inputAngle(p, t, y), win = p.drive.speed(t);
    for (const auto& me : p.meshes) {
      double rate, elastic, fd, fv, ft;
      double d = deflection(p, me, tin, win, y, rate);
      force<true>(p, me, tin, y, d, rate, elastic, &fd, &fv, &ft);
      for (int r = 0; r < me.n; ++r) {
        int j = me.dof[static_cast<size_t>(r)];
        if (j < 0) continue;
        double* row = Jm + (nq + static_cast<size_t>(j)) * n;
        double w = -me.coef[static_cast<size_t>(r)] / p.J[static_cast<size_t>(j)];
        for (int k = 0; k < me.n; ++k) {
          int col = me.dof[static_cast<size_t>(k)];
          double ck = me.coef[static_cast<size_t>(k)];
          if (col >= 0) {
            row[col] += w * fd * ck;
            row[nq + static_cast<size_t>(col)] += w * fv * ck;
          } else if constexpr (Phase == drivephase::State) {
            row[2 * nq] += w * fd * ck;
          }
        }
        if constexpr (Varying || Contact == contact::Loaded) {
          if (me.phaseDof >= 0) row[me.phaseDof] += w * ft * me.phaseGain;
          else if constexpr (Phase == drivephase::State) row[2 * nq] += w * ft * me.phaseGain;
        }
      }
    }
  }
  static double loadTorque(const Params& p, double t) {
    if constexpr (TorqueFl) return p.tMean + p.tAmp * std::sin(p.tOmega * t);
    else return p.tMean;
  }
  static void rhs(const Params& p, double t, const double* y, double* dy) {
    size_t nq = p.nq;
    for (size_t i = 0; i < nq; ++i) {
      dy[i] = y[nq + i];
      dy[nq + i] = 0;
    }
    double tin = inputAngle(p, t, y), win = p.drive.speed(t);
    double T = loadTorque(p, t);
    dy[nq + static_cast<size_t>(p.output)] -= p.outSign * T;
    double driveTorque = 0, dissipation = 0;
    for (const auto& me : p.meshes) {
      double rate, elastic;
      double d = deflection(p, me, tin, win, y, rate);
      double f = force(p, me, tin, y, d, rate, elastic);
      for (int k = 0; k < me.n; ++k) {
        int j = me.dof[static_cast<size_t>(k)];
        if (j < 0) driveTorque += f * me.coef[static_cast<size_t>(k)];
        else dy[nq + static_cast<size_t>(j)] -= f * me.coef[static_cast<size_t>(k)];
      }
      dissipation += (f - elastic) * rate;
    }
    for (size_t i = 0; i < nq; ++i) dy[nq + i] /= p.J[i];
    size_t at = 2 * nq;
    if constexpr (Phase == drivephase::State) dy[at++] = win;
    if (p.audit) {
      dy[at] = driveTorque * win;
      dy[at + 1] = p.outSign * T * y[nq + static_cast<size_t>(p.output)];
      dy[at + 2] = dissipation;
    }
  }
  static double meshForce(const Params& p, const GMesh& me, double t, const double* y) {
    double rate, elastic, tin = inputAngle(p, t, y);
    double d = deflection(p, me, tin, p.drive.speed(t), y, rate);
    return force(p, me, tin, y, d, rate, elastic);
  }
  static double meshDeflection(const Params& p, const GMesh& me, double t, const double* y) {
    double rate;
    return deflection(p, me, inputAngle(p, t, y), p.drive.speed(t), y, rate);
  }
};

struct Compiled {
  std::function<void(double, const double*, double*)> rhs, dfdy;
  std::function<double(const GMesh&, double, const double*)> force, deflection;
};

Compiled compile(const Params& p, bool varying, bool damped, int contactKind, bool torqueFl, int phase) {
  Compiled c;
  withBool(varying, [&](auto V) {
    withBool(damped, [&](auto D) {
      withInt4(contactKind, [&](auto C) {
        withBool(torqueFl, [&](auto Q) {
          withBool(phase == drivephase::State, [&](auto P) {
            using K = Kernel<decltype(V)::value, decltype(D)::value, decltype(C)::value, decltype(Q)::value,
                             decltype(P)::value ? drivephase::State : drivephase::Closed>;
            const Params* pp = &p;
            c.rhs = [pp](double t, const double* y, double* dy) { K::rhs(*pp, t, y, dy); };
            c.dfdy = [pp](double t, const double* y, double* J) { K::dfdy(*pp, t, y, J); };
            c.force = [pp](const GMesh& me, double t, const double* y) { return K::meshForce(*pp, me, t, y); };
            c.deflection = [pp](const GMesh& me, double t, const double* y) { return K::meshDeflection(*pp, me, t, y); };
          });
        });
      });
    });
  });
  return c;
}

double need(const Value& v, const std::string& what) { return needNumber(v, what); }


// A whole-gearbox scene set up and run, step by step: the effects it lists, its members and
// meshes stage by stage, the kinematics, the load and the static deflections, the loaded-mesh
// tables, the damping, the modes at the static load, and the integration.
class GearboxAssembly {
public:
  GearboxAssembly(const Model& model, const Evaluator& evaluator, const Assignment& design, const ScenePlan& sc, Accuracy accuracy,
                  const SceneOverrides& overrides)
      : m(model), ev(evaluator), a(design), scene(sc), acc(accuracy), ov(overrides), prov(run.provenance) {}

  GearboxRun build() {
    effects();
    members();
    kinematics();
    load();
    staticLoad();
    if (loadedFx) loadedMeshes();
    if (damping) meshDamping();
    modes();
    integrate();
    return std::move(run);
  }

private:
  // What the meshes of one stage share.
  struct StageAt {
    int st;
    const ir::Stage& s;
    Elastic mat;
    double Estar, alpha, fz;
  };

  const Model& m;
  const Evaluator& ev;
  const Assignment& a;
  const ScenePlan& scene;
  Accuracy acc;
  const SceneOverrides& ov;
  GearboxRun run;
  std::vector<std::string>& prov;
  // The listed effects, each empty where the scene does not list it.
  const std::optional<SceneEffects::Hertz>& hertz = scene.fx.hertz;
  const std::optional<SceneEffects::Varying>& varying = scene.fx.varying;
  const std::optional<SceneEffects::Damping>& damping = scene.fx.damping;
  const std::optional<SceneEffects::Fluctuation>& torqueFx = scene.fx.torque;
  const std::optional<SceneEffects::Backlash>& backlash = scene.fx.backlash;
  const std::optional<SceneEffects::Loaded>& loadedFx = scene.fx.loaded;
  Params P;
  int harmonics = 0;
  // Members: the driven input shaft first (prescribed), then one per shaft, carrier, planet, idler.
  std::vector<std::string> names = {"input shaft"};
  std::vector<double> J = {0.0};
  int shaft = 0;
  // The sense the current shaft turns in: every mesh is written so that a positive deflection
  // carries the load (the driving flank), whichever way its stage's input turns.
  double sense = 1.0;
  double fastest = 0;
  std::vector<std::string> hertzLines;
  size_t nq = 0;
  long nm = 0;
  Eigen::MatrixXd G;
  Eigen::VectorXd gin, v;
  double speed = 0, Tz = 0, Tn = 0;
  std::vector<double> F0, target;

  // ---- effects ----------------------------------------------------------------------------

  void effects() {
    for (const auto& fx : scene.listed)
      if (const EffectRow* row = effectRow(fx.kind); !row || !row->gearbox)
        throw SceneFailure{fmt::format("effect `{}` is not modelled in a whole-gearbox scene (it takes hertz_contact, backlash, "
                                       "varying_stiffness, loaded_mesh, damping, speed_fluctuation and torque_fluctuation)",
                                       fx.name)};
    if (!m.gearbox.splits.empty()) throw SceneFailure{"a whole-gearbox scene of a power split is not modelled: run the scene on a stage"};
    if (backlash && hertz) throw SceneFailure{"`backlash` and `hertz_contact` both describe the contact: list one"};
    if (loadedFx && (hertz || backlash || varying))
      throw SceneFailure{"`loaded_mesh` gives every mesh its stiffness and separation from the flanks: list it without hertz_contact, backlash "
                         "and varying_stiffness"};
    if (loadedFx)
      for (const auto& st : m.stages)
        if (st.ir->kind != ir::StageKind::Spur && st.ir->kind != ir::StageKind::Helical)
          throw SceneFailure{fmt::format("`loaded_mesh` models spur and helical pairs; stage `{}` is {}", st.ir->name, ir::stageKindName(st.ir->kind))};
    if (hertz) {
      P.e = hertz->exponent;
      P.ramp = hertz->penetrationRamp;
    }
    if (backlash) P.halfClearance = 0.5 * backlash->clearance;
    harmonics = varying ? (ov.harmonics ? *ov.harmonics : varying->harmonics) : 0;
    run.harmonics = harmonics;
  }

  // ---- members and meshes -------------------------------------------------------------------

  int add(const std::string& n, double inertia) {
    names.push_back(n);
    J.push_back(inertia);
    return static_cast<int>(names.size()) - 1;
  }
  // A member index as the state sees it: the input is -1, the others one lower.
  static int dofOf(int member) { return member - 1; }
  double hertzK(const StageAt& at, double rho1, double rho2, bool internal) const {
    double R = 1.0 / (1.0 / rho1 + (internal ? -1.0 : 1.0) / rho2);
    return 4.0 / 3.0 * std::sqrt(R) * at.Estar;
  }
  // Linear stiffness without a contact law: c_gamma x b, given or assumed.
  double linearK(const StageAt& at, double b) const {
    Value cg = ev.attribute(at.st, Q::MeshStiffness, a);
    return (cg.isNumber() ? cg.mid() : 16e9) * b;
  }
  void mesh(const StageAt& at, const std::string& n, bool reported, std::vector<std::pair<int, double>> coupling, double K, double kLin,
            double normal, int fourier, int phaseMember, double gain, double phase0) {
    GMesh me;
    me.name = n;
    me.reported = reported;
    me.stage = at.st;
    me.n = static_cast<int>(coupling.size());
    for (size_t k = 0; k < coupling.size(); ++k) {
      me.dof[k] = dofOf(coupling[k].first);
      me.coef[k] = sense * coupling[k].second;
    }
    me.K = hertz ? K : kLin;
    me.kLinear = kLin;
    me.normal = normal;
    me.fourier = fourier;
    me.phaseDof = dofOf(phaseMember);
    me.phaseGain = sense * gain;
    me.phase0 = phase0;
    me.meshFrequency = at.fz;
    if (hertz) me.hertzDamping = hertz->damping({adamsStiffness(K, P.e)});
    P.meshes.push_back(me);
  }
  double width(const StageAt& at, double mod) {
    Value bw = ev.attribute(at.st, Q::FaceWidth, a);
    if (bw.isNumber()) return bw.mid();
    prov.push_back(fmt::format("stage `{}`: face width {:.2f} mm assumed (10 x module): not given", at.s.name, 10.0 * mod * 1e3));
    return 10.0 * mod;
  }
  double solid(const StageAt& at, int gear, double r, double b) const {
    Value given = ev.attribute(at.st, gear, Q::Inertia, a);
    return given.isNumber() ? given.mid() : 0.5 * at.mat.density * M_PI * b * r * r * r * r;
  }

  void planetary(const StageAt& at) {
    using namespace cat::gear;
    const int st = at.st;
    const ir::Stage& s = at.s;
    const double alpha = at.alpha;
    double zs = need(ev.attribute(st, Sun, Q::Z, a), "sun.z"), zp = need(ev.attribute(st, Planet, Q::Z, a), "planet.z"),
           zr = need(ev.attribute(st, Ring, Q::Z, a), "ring.z"), mod = need(ev.attribute(st, Q::Module, a), "`module`");
    int N = static_cast<int>(need(ev.attribute(st, Q::Planets, a), "planets"));
    if (N < 1 || N > 32) throw SceneFailure{fmt::format("a planetary stage is modelled with 1 to 32 planets, not {}", N)};
    double rbs = 0.5 * zs * mod * std::cos(alpha), rbp = 0.5 * zp * mod * std::cos(alpha), rbr = 0.5 * zr * mod * std::cos(alpha);
    double rc = 0.5 * (zs + zp) * mod, rp = 0.5 * zp * mod, b = width(at, mod);
    double mp = at.mat.density * M_PI * rp * rp * b;
    double Jp = solid(at, Planet, rp, b);
    Value jcGiven = ev.attribute(st, Q::CarrierInertia, a);
    double Rcar = rc + rp;
    double Jc = jcGiven.isNumber() ? jcGiven.mid() : 0.5 * at.mat.density * M_PI * Rcar * Rcar * b * Rcar * Rcar;
    J[static_cast<size_t>(shaft)] += solid(at, Sun, 0.5 * zs * mod, b);
    int carrier = add(s.name + " carrier", Jc + N * mp * rc * rc);
    double tanA = std::tan(alpha);
    double Ksp = hertzK(at, rbs * tanA, rbp * tanA, false), Krp = hertzK(at, rbp * tanA, rbr * tanA, true);
    if (hertz) hertzLines.push_back(fmt::format("`{}` sun-planet {:.4g}, ring-planet {:.4g} N/m^{} (internal curvature subtracted)", s.name, Ksp, Krp, P.e));
    int fourier = -1;
    if (varying) {
      double eps = epsAlphaStandard(zs, zp, mod, alpha, false);
      P.fouriers.push_back(contactLineSeries(eps, 0.0, harmonics));
      fourier = static_cast<int>(P.fouriers.size()) - 1;
      prov.push_back(fmt::format("stage `{}`: contact-line stiffness variation, {} harmonics, eps_alpha {:.4f} (sun-planet, on both meshes)",
                                 s.name, harmonics, eps));
    }
    double kLin = linearK(at, b);
    for (int i = 0; i < N; ++i) {
      int p = add(fmt::format("{} planet {}", s.name, i + 1), Jp);
      // Sun-planet: rbs (theta_sun - theta_c) + rbp phi; ring-planet: -rbp phi - rbr theta_c.
      mesh(at, s.name + ".sun_planet", i == 0, {{shaft, rbs}, {carrier, -rbs}, {p, rbp}}, Ksp, kLin, 1.0, fourier, carrier, zr / (2.0 * M_PI),
           std::fmod(zs * i / static_cast<double>(N), 1.0));
      mesh(at, s.name + ".ring_planet", i == 0, {{p, -rbp}, {carrier, -rbr}}, Krp, kLin, 1.0, fourier, carrier, zr / (2.0 * M_PI),
           1.0 - std::fmod(zr * i / static_cast<double>(N), 1.0));  // Parker and Lin's phasing, as in Planetary.cpp
    }
    prov.push_back(fmt::format("stage `{}`: carrier {:.4g} kg*m^2 with {} planets at r = {:.2f} mm, planet spin {:.4g} kg*m^2 ({})", s.name,
                               Jc + N * mp * rc * rc, N, rc * 1e3, Jp, "solid discs unless given"));
    shaft = carrier;
  }

  void idler(const StageAt& at) {
    using namespace cat::gear;
    const int st = at.st;
    const ir::Stage& s = at.s;
    const double alpha = at.alpha;
    double z1 = need(ev.attribute(st, Driver, Q::Z, a), "driver.z"), z2 = need(ev.attribute(st, Idler, Q::Z, a), "idler.z"),
           z3 = need(ev.attribute(st, Driven, Q::Z, a), "driven.z"), mod = need(ev.attribute(st, Q::Module, a), "`module`");
    double rb1 = 0.5 * z1 * mod * std::cos(alpha), rb2 = 0.5 * z2 * mod * std::cos(alpha), rb3 = 0.5 * z3 * mod * std::cos(alpha);
    double b = width(at, mod), tanA = std::tan(alpha);
    J[static_cast<size_t>(shaft)] += solid(at, Driver, 0.5 * z1 * mod, b);
    int idlerMember = add(s.name + " idler", solid(at, Idler, 0.5 * z2 * mod, b));
    int driven = add(s.name + " driven", solid(at, Driven, 0.5 * z3 * mod, b));
    double K1 = hertzK(at, rb1 * tanA, rb2 * tanA, false), K2 = hertzK(at, rb2 * tanA, rb3 * tanA, false);
    if (hertz) hertzLines.push_back(fmt::format("`{}` driver-idler {:.4g}, idler-driven {:.4g} N/m^{}", s.name, K1, K2, P.e));
    int f1 = -1, f2 = -1;
    if (varying) {
      double e1 = epsAlphaStandard(z1, z2, mod, alpha, false), e2 = epsAlphaStandard(z2, z3, mod, alpha, false);
      P.fouriers.push_back(contactLineSeries(e1, 0.0, harmonics));
      f1 = static_cast<int>(P.fouriers.size()) - 1;
      P.fouriers.push_back(contactLineSeries(e2, 0.0, harmonics));
      f2 = f1 + 1;
      prov.push_back(fmt::format("stage `{}`: contact-line stiffness variation, {} harmonics, eps_alpha {:.4f} and {:.4f}; the two meshes "
                                 "in phase (the idler's angle between its centre lines is not modelled)",
                                 s.name, harmonics, e1, e2));
    }
    double kLin = linearK(at, b);
    // Driver-idler: rb1 theta_1 + rb2 theta_2; idler-driven: -rb2 theta_2 - rb3 theta_3.
    mesh(at, s.name + ".driver_idler", true, {{shaft, rb1}, {idlerMember, rb2}}, K1, kLin, 1.0, f1, shaft, z1 / (2.0 * M_PI), 0.0);
    mesh(at, s.name + ".idler_driven", true, {{idlerMember, -rb2}, {driven, -rb3}}, K2, kLin, 1.0, f2, shaft, z1 / (2.0 * M_PI), 0.0);
    shaft = driven;
  }

  void cylindrical(const StageAt& at) {
    using namespace cat::gear;
    const int st = at.st;
    const ir::Stage& s = at.s;
    double z1 = need(ev.attribute(st, Pinion, Q::Z, a), "pinion.z");
    double d1 = need(ev.derived(st, Pinion, Q::D, a), "the pinion's pitch diameter"), d2 = need(ev.derived(st, Wheel, Q::D, a), "the wheel's pitch diameter");
    double beta = s.kind == ir::StageKind::Helical ? need(ev.attribute(st, Q::HelixAngle, a), "the helix angle") : 0.0;
    double at_ = std::atan(std::tan(at.alpha) / std::cos(beta));
    double rb1 = 0.5 * d1 * std::cos(at_), rb2 = 0.5 * d2 * std::cos(at_);
    Value bw = ev.attribute(st, Q::FaceWidth, a);
    double b = need(bw, fmt::format("the `face_width` of stage `{}`", s.name));
    J[static_cast<size_t>(shaft)] += solid(at, Pinion, 0.5 * d1, b);
    int wheel = add(s.name + " wheel", solid(at, Wheel, 0.5 * d2, b));
    double betab = std::atan(std::tan(beta) * std::cos(at_));
    // Under hertz_contact the same point-contact law as the planetary and idler meshes (the
    // source paper's multibody contact): it ignores the face width of a line contact.
    double kLin = linearK(at, b);
    double K = hertzK(at, rb1 * std::tan(at_), rb2 * std::tan(at_), false);
    if (hertz) hertzLines.push_back(fmt::format("`{}` {:.4g} N/m^{}", s.name, K, P.e));
    int f = -1;
    if (varying) {
      double ea = need(ev.derived(st, Q::EpsAlpha, a), "eps_alpha"), eb = s.kind == ir::StageKind::Helical ? need(ev.derived(st, Q::EpsBeta, a), "eps_beta") : 0.0;
      P.fouriers.push_back(contactLineSeries(ea, eb, harmonics));
      f = static_cast<int>(P.fouriers.size()) - 1;
    }
    mesh(at, s.name, true, {{shaft, rb1}, {wheel, rb2}}, K, kLin, 1.0 / std::cos(betab), f, shaft, z1 / (2.0 * M_PI), 0.0);
    shaft = wheel;
    sense = -sense;  // the wheel turns against the pinion
  }

  void members() {
    for (int st = 0; st < static_cast<int>(m.stages.size()); ++st) {
      const ir::Stage& s = *m.stages[static_cast<size_t>(st)].ir;
      Elastic mat = materialOf(m, st);
      double Estar = mat.E / (2.0 * (1.0 - mat.nu * mat.nu));
      double alpha = need(ev.attribute(st, Q::PressureAngle, a), "a pressure angle");
      double fz = need(ev.derived(st, Q::MeshFrequency, a), fmt::format("the mesh frequency of stage `{}`", s.name));
      fastest = std::max(fastest, fz);
      if (mat.assumed) prov.push_back(fmt::format("stage `{}`: density 7850 kg/m^3, E = 206 GPa, nu = 0.3 (steel assumed: no material given)", s.name));
      StageAt at{st, s, mat, Estar, alpha, fz};
      switch (s.kind) {
      case ir::StageKind::Planetary: planetary(at); break;
      case ir::StageKind::Idler: idler(at); break;
      case ir::StageKind::Spur:
      case ir::StageKind::Helical: cylindrical(at); break;
      default: throw SceneFailure{fmt::format("a whole-gearbox scene does not model {} stages (`{}`)", ir::stageKindName(s.kind), s.name)};
      }
    }
    if (P.meshes.empty()) throw SceneFailure{"the gearbox has no mesh to integrate"};
    if (!hertzLines.empty()) prov.push_back("Hertz stiffness K = 4/3 sqrt(R) E*: " + fmt::format("{}", fmt::join(hertzLines, "; ")));
    nq = names.size() - 1;
    P.nq = nq;
    P.J.assign(J.begin() + 1, J.end());
    for (size_t i = 0; i < nq; ++i)
      if (!(P.J[i] > 0)) throw SceneFailure{fmt::format("`{}` has no inertia", names[i + 1])};
    P.output = dofOf(shaft);
    run.members = names;
  }

  // ---- kinematics, load, static deflections ---------------------------------------------------

  // The member speeds that leave every mesh undeflected, per unit input speed.
  void kinematics() {
    nm = static_cast<long>(P.meshes.size());
    G = Eigen::MatrixXd::Zero(nm, static_cast<long>(nq));
    gin = Eigen::VectorXd::Zero(nm);
    for (long i = 0; i < nm; ++i) {
      const GMesh& me = P.meshes[static_cast<size_t>(i)];
      for (int k = 0; k < me.n; ++k) {
        if (me.dof[static_cast<size_t>(k)] < 0) gin(i) += me.coef[static_cast<size_t>(k)];
        else G(i, me.dof[static_cast<size_t>(k)]) += me.coef[static_cast<size_t>(k)];
      }
    }
    v = G.colPivHouseholderQr().solve(-gin);
    run.kinematic = {1.0};
    for (long i = 0; i < v.size(); ++i) run.kinematic.push_back(v(i));
    P.outSign = v(P.output) >= 0 ? 1.0 : -1.0;
  }

  // The load: the gearbox output torque (or its fluctuation) on the last member, against its
  // sense; the drive at the input.
  void load() {
    P.tMean = need(ev.gearboxQuantity(Q::OutputTorque, a), "an output torque (`operating`)");
    if (torqueFx) {
      P.tMean = torqueFx->mean;
      P.tAmp = torqueFx->amplitude;
      P.tOmega = torqueFx->omega;
      prov.push_back("load torque mean + amplitude sin(frequency t) on the output");
    }
    speed = need(ev.gearboxQuantity(Q::InputSpeed, a), "an input speed (`operating`)");
    Tz = 1.0 / fastest;
    run.meshFrequency = fastest;
    P.drive = sceneDrive(scene, speed, 1.0, Tz);
    P.audit = ov.energyAudit;
  }

  // K = sum k G_i^T G_i with each mesh's current linear stiffness.
  Eigen::MatrixXd stiffness() const {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(static_cast<long>(nq), static_cast<long>(nq));
    for (long i = 0; i < nm; ++i) K += P.meshes[static_cast<size_t>(i)].kLinear * G.row(i).transpose() * G.row(i);
    return K;
  }

  // Static load: the linear model (input held) under the output torque gives each mesh's force.
  void staticLoad() {
    Eigen::MatrixXd Klin = stiffness();
    Eigen::VectorXd loadVec = Eigen::VectorXd::Zero(static_cast<long>(nq));
    loadVec(P.output) = -P.outSign * P.tMean;
    Eigen::VectorXd q0 = Klin.ldlt().solve(loadVec);
    F0.assign(static_cast<size_t>(nm), 0.0);
    target.assign(static_cast<size_t>(nm), 0.0);
    for (long i = 0; i < nm; ++i) {
      GMesh& me = P.meshes[static_cast<size_t>(i)];
      double F = me.kLinear * G.row(i).dot(q0);
      F0[static_cast<size_t>(i)] = F;
      double Fp = std::max(std::fabs(F), 1e-9);
      if (hertz) {
        target[static_cast<size_t>(i)] = std::pow(Fp / me.K, 1.0 / P.e);
        me.kLinear = P.e * me.K * std::pow(Fp / me.K, (P.e - 1.0) / P.e);  // the contact's slope at the static load
      } else {
        target[static_cast<size_t>(i)] = F / me.kLinear + (backlash ? P.halfClearance : 0.0);
      }
    }
  }

  // loaded_mesh: each pair's thin-slice tables at its static load; the mesh force k (x - u).
  void loadedMeshes() {
    int slices = loadedFx->slices * ov.loadedRefine, positions = loadedFx->positions * ov.loadedRefine;
    int H = ov.harmonics ? *ov.harmonics : loadedFx->tableHarmonics();
    run.harmonics = H;
    for (long i = 0; i < nm; ++i) {
      GMesh& me = P.meshes[static_cast<size_t>(i)];
      double F = std::fabs(F0[static_cast<size_t>(i)]);
      std::vector<std::string> lines;
      LoadedMeshTable tab = loadedMesh(loadedMeshInput(ev, a, me.stage, F, slices, positions, lines));
      if (!tab.failure.empty()) throw SceneFailure{fmt::format("the loaded mesh of `{}`: {}", me.name, tab.failure)};
      for (const auto& l : lines) prov.push_back(fmt::format("`{}` {}", me.name, l));
      std::vector<double> u(tab.te.size());
      for (size_t k = 0; k < u.size(); ++k) u[k] = tab.te[k] - F / tab.stiffness[k];
      P.loaded.push_back({periodicSeries(tab.stiffness, H), periodicSeries(u, H)});
      me.loaded = static_cast<int>(P.loaded.size()) - 1;
      me.K = me.kLinear = tab.meanStiffness;
      target[static_cast<size_t>(i)] = F / tab.meanStiffness + P.loaded.back().u.mean;
      prov.push_back(fmt::format("`{}` loaded mesh: {} slices x {} positions, {} harmonics; static transmission error {:.4g} um peak to "
                                 "peak, mesh stiffness {:.4g} N/m mean",
                                 me.name, slices, positions, H, tab.peakToPeakTe * 1e6, tab.meanStiffness));
    }
  }

  // Damping: a coefficient, or a ratio of each mesh's critical damping with the effective mass
  // along its line of action.
  void meshDamping() {
    for (auto& me : P.meshes) {
      if (damping->coefficient) {
        me.c = *damping->coefficient;
        continue;
      }
      double inv = 0;
      for (int k = 0; k < me.n; ++k)
        if (me.dof[static_cast<size_t>(k)] >= 0) inv += me.coef[static_cast<size_t>(k)] * me.coef[static_cast<size_t>(k)] / P.J[static_cast<size_t>(me.dof[static_cast<size_t>(k)])];
      me.c = 2.0 * damping->ratio * std::sqrt(me.kLinear / inv);
    }
  }

  // Modes of the model linearised at the static load (the input held); the step rule and the
  // time plan they set.
  void modes() {
    Eigen::MatrixXd Klin = stiffness();  // the contacts' slopes at the static load
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<long>(nq), static_cast<long>(nq));
    for (size_t i = 0; i < nq; ++i) M(static_cast<long>(i), static_cast<long>(i)) = P.J[i];
    run.modes = naturalFrequencies(Klin, M);
    double fmax = run.modes.empty() ? 0.0 : *std::max_element(run.modes.begin(), run.modes.end());
    prov.push_back(fmt::format("{} members, one rotation each (the driven input first: {}), {} mesh{}; modes at the static load {} Hz",
                               names.size(), fmt::join(names, ", "), nm, nm == 1 ? "" : "es", frequencyList(run.modes)));
    Tn = fmax > 0 ? 1.0 / fmax : Tz;
    run.stepRule = lumpedMaxStep(acc.maxStep, Tz, fmax, ov.maxStepFactor, "Tz/20 (the fastest mesh)");
    run.plan = timePlan(scene, Tz, ov.settlePeriods);
  }

  // ---- the run ------------------------------------------------------------------------------

  // Each mesh at its static deflection (least squares where the planets share), every member
  // at its kinematic speed; and the state's scales.
  std::vector<double> initialState(System& sys, int phaseKind) const {
    std::vector<double> y(sys.dim, 0.0);
    double tin0 = P.drive.angle(0.0), win0 = P.drive.speed(0.0);
    Eigen::VectorXd rhsv(nm);
    for (long i = 0; i < nm; ++i) rhsv(i) = target[static_cast<size_t>(i)] - gin(i) * tin0;
    Eigen::VectorXd qs = G.colPivHouseholderQr().solve(rhsv);
    for (size_t i = 0; i < nq; ++i) {
      y[i] = qs(static_cast<long>(i));
      y[nq + i] = v(static_cast<long>(i)) * win0;
    }
    if (phaseKind == drivephase::State) y[2 * nq] = tin0;
    double dRef = 0;
    for (double d : target) dRef = std::max(dRef, std::fabs(d));
    sys.scale.assign(sys.dim, 1.0);
    for (size_t i = 0; i < nq; ++i) {
      double r = 0;
      for (long k = 0; k < nm; ++k) r = std::max(r, std::fabs(G(k, static_cast<long>(i))));
      sys.scale[i] = std::max(dRef, 1e-9) / std::max(r, 1e-9);
      sys.scale[nq + i] = std::max(speed * std::fabs(v(static_cast<long>(i))), sys.scale[i] / Tn);
    }
    if (P.audit) {
      double Pref = std::fabs(P.tMean) * speed * std::fabs(v(P.output)) * Tz;
      for (size_t k = sys.dim - 3; k < sys.dim; ++k) sys.scale[k] = std::max(Pref, 1e-12);
    }
    return y;
  }

  // The energy stored at a state: kinetic and elastic.
  double energy(const Compiled& model, double t, const double* ys) const {
    double E = 0;
    for (size_t i = 0; i < nq; ++i) E += 0.5 * P.J[i] * ys[nq + i] * ys[nq + i];
    for (const auto& me : P.meshes) {
      double d = model.deflection(me, t, ys);
      if (hertz) E += d > 0 ? me.K * std::pow(d, P.e + 1.0) / (P.e + 1.0) : 0.0;
      else if (backlash) {
        double e2 = d > P.halfClearance ? d - P.halfClearance : d < -P.halfClearance ? d + P.halfClearance : 0.0;
        E += 0.5 * me.K * e2 * e2;
      } else E += 0.5 * me.K * d * d;
    }
    return E;
  }

  // The periodic steady state: every mesh's phase, and the load, repeat after q periods of
  // the fastest mesh (q the fewest, at most 1000); the members' angles advance by their
  // kinematic share of the input's turn, their speeds repeat. By harmonic balance where the
  // scene asks for it and it is found (the samples then from its series), else by shooting;
  // y becomes the orbit's start. False, with run.failure, where there is none.
  template <class Sample> bool steadyState(const System& sys, std::vector<double>& y, Sample& sample, bool& sampled) {
    run.periodic = true;
    if (P.audit || P.drive.ramp > 0 || P.drive.fluctuates)
      return notPeriodic(P.audit            ? "the energy audit integrates work done over the run"
                         : P.drive.ramp > 0 ? "a `ramp` start-up"
                                            : "a fluctuating drive speed");
    std::vector<double> periods;
    for (const auto& me : P.meshes)
      periods.push_back(1.0 / me.meshFrequency);
    if (torqueFx && P.tAmp != 0) periods.push_back(P.tOmega > 0 ? 2.0 * M_PI / P.tOmega : INFINITY);
    int q = wholeMeshPeriods(Tz, periods);
    if (q == 0)
      return notPeriodic(
          "the meshes' periods (and the load's) come round together in no whole number of periods of the "
          "fastest mesh up to 1000: the response is quasi-periodic");
    const double T = q * Tz;
    if (widenToPeriod(run.plan, T))
      prov.push_back(fmt::format("record window widened to the orbit's period, {} periods of the fastest mesh", q));
    PeriodicOptions opt;
    opt.period = T;
    opt.drift.assign(sys.dim, 0.0);
    for (size_t i = 0; i < nq; ++i)
      opt.drift[i] = v(static_cast<long>(i)) * P.drive.speed0 * T;
    opt.linear = !hertz && !backlash && !varying && !loadedFx; // a member's angle sets a mesh's phase
    if (ov.harmonicBalance.value_or(scene.harmonicBalance)) {
      BalanceOptions bo;
      bo.period = T;
      bo.drift = opt.drift;
      bo.linear = opt.linear;
      bo.floquet = acc;
      SceneBalance b = sceneBalance(sys, bo, scene, ov, acc.rtol, y, 2048, q);
      run.stats += b.stats;
      prov.push_back(b.line);
      if (b.orbit) {
        const BalanceOrbit& o = *b.orbit;
        run.newtonIterations = o.iterations;
        run.newtonResidual = o.gapResidual;
        run.stability = o.stability;
        run.balanceHarmonics = o.harmonics;
        run.orbit = o.state(0);
        run.period = T;
        std::vector<double> ys(sys.dim);
        for (double ts : run.plan.samples) {
          o.state(ts, ys.data());
          sample(ts, ys.data());
        }
        sampled = true;
        return true;
      }
    }
    PeriodicOrbit orbit = periodicOrbit(sys, acc, opt, ov.guess && ov.guess->size() == sys.dim ? *ov.guess : y);
    run.stats += orbit.stats;
    run.newtonIterations = orbit.iterations;
    run.newtonResidual = orbit.residual;
    if (!orbit.converged) {
      run.failure = "the periodic steady state was not found: " + orbit.failure;
      return false;
    }
    run.stability = orbit.stability;
    prov.push_back(fmt::format("periodic steady state: period {:.6g} ms ({} period{} of the fastest mesh), Newton {} "
                               "iteration{} (monodromy by {}), residual {:.2e} of the state scale, largest Floquet "
                               "multiplier {:.6f}",
                               T * 1e3, q, q == 1 ? "" : "s", orbit.iterations, orbit.iterations == 1 ? "" : "s",
                               orbit.variational ? "variational equations" : "differences", orbit.residual,
                               orbit.stability));
    y = orbit.y0;
    run.orbit = orbit.y0;
    run.period = T;
    return true;
  }

  bool notPeriodic(const std::string& why) {
    run.failure =
        fmt::format("the excitation is not periodic ({}), so there is no periodic steady state: write `settle = "
                    "N mesh_periods` to settle a transient, or `duration` for a run from rest",
                    why);
    return false;
  }

  void integrate() {
    int contactKind = loadedFx ? contact::Loaded : backlash ? contact::Backlash : hertz ? contact::Hertz : contact::Linear;
    int phaseKind = P.drive.needsState() ? drivephase::State : drivephase::Closed;
    Compiled model = compile(P, varying.has_value(), damping.has_value(), contactKind, torqueFx.has_value(), phaseKind);
    System sys;
    size_t extra = (phaseKind == drivephase::State ? 1 : 0) + (P.audit ? 3 : 0);
    sys.dim = 2 * nq + extra;
    sys.rhs = model.rhs;
    sys.dfdy = model.dfdy;
    // The implicit method's Jacobian: dfdy, and dfdt by a central difference (the terms depend on
    // t only through the drive and the load, both smooth).
    double period = Tz;
    sys.jacobian = [&sys, period](double t, const double* y, double* dfdy, double* dfdt) {
      size_t n = sys.dim;
      sys.dfdy(t, y, dfdy);
      double h = 1e-7 * period;
      std::vector<double> a(n), b(n);
      sys.rhs(t + h, y, a.data());
      sys.rhs(t - h, y, b.data());
      for (size_t i = 0; i < n; ++i) dfdt[i] = (a[i] - b[i]) / (2 * h);
    };
    if (hertz || backlash)
      for (const auto& me : P.meshes)
        for (double side : backlash ? std::vector<double>{1.0, -1.0} : std::vector<double>{0.0})
          sys.events.push_back([&model, me, side, hc = P.halfClearance](double t, const double* y) { return model.deflection(me, t, y) - side * hc; });
    std::vector<double> y = initialState(sys, phaseKind);
    for (const auto& me : P.meshes)
      if (me.reported) run.meshes.push_back({me.name, me.meshFrequency, {}, {}});
    auto sample = [&](double ts, const double* ys) {
      run.t.push_back(ts);
      size_t k = 0;
      for (const auto& me : P.meshes) {
        if (!me.reported) continue;
        double f = model.force(me, ts, ys);
        run.meshes[k].meshForce.push_back(f);
        run.meshes[k].contactForce.push_back(f * me.normal);
        ++k;
      }
      run.inputSpeed.push_back(P.drive.speed(ts));
      run.outputSpeed.push_back(P.outSign * ys[nq + static_cast<size_t>(P.output)]);
    };
    if (P.audit && (varying || loadedFx)) throw SceneFailure{"the energy audit needs a constant mesh stiffness (leave out varying_stiffness and loaded_mesh)"};
    if (run.plan.steady == SteadyMethod::Periodic) {
      bool sampled = false; // harmonic balance's samples come from its series
      if (!steadyState(sys, y, sample, sampled) || sampled) return;
    }
    double E0 = P.audit ? energy(model, 0.0, y.data()) : 0.0;
    Integrator integ(sys, acc);
    double t = 0;
    bool ok = integ.advance(t, y, run.plan.end, run.plan.samples, sample);
    run.stats = integ.stats();
    if (!ok) run.failure = integ.error();
    if (P.audit) {
      size_t at = sys.dim - 3;
      run.driveWork = y[at];
      run.loadWork = y[at + 1];
      run.dissipated = y[at + 2];
      run.energyGained = energy(model, t, y.data()) - E0;
    }
  }
};

} // namespace

GearboxRun runGearbox(const Model& m, const Evaluator& ev, const Assignment& a, const ScenePlan& scene, Accuracy acc,
                      const SceneOverrides& ov) {
  return GearboxAssembly(m, ev, a, scene, acc, ov).build();
}

} // namespace gbx::rt::dyn
