// The periodic steady state by harmonic balance, on the product's own mesh models, against
// shooting: the linear marine scene, a Mathieu tongue's stability by Hill's method against
// the Floquet multipliers, and a backlash orbit whose brief contact loss the transform's
// instants step over.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "Specs.h"

#include "SceneFixture.h"
#include "dynamics/HarmonicBalance.h"
#include "dynamics/MeshModel.h"
#include "dynamics/Periodic.h"
#include "dynamics/Scene.h"
#include "model/Evaluator.h"

using namespace gbx;
using namespace gbx::rt::dyn;

namespace {

using test::compile;
using test::Fixture;

std::string replaced(std::string s, const std::string& a, const std::string& b) {
  auto at = s.find(a);
  EXPECT_NE(at, std::string::npos) << a;
  if (at != std::string::npos) s.replace(at, a.size(), b);
  return s;
}

// The scene's mesh model, at an input speed (rad/s) when one is given.
MeshScene sceneAt(const Fixture& f, const ir::Scene& scene, const ir::Study* sweep = nullptr, double speed = 0) {
  rt::Evaluator ev(*f.model);
  if (sweep) ev.setOverride(sweep->swept, rt::Value::number(speed));
  SceneOverrides o;
  o.evaluator = &ev;
  return meshScene(*f.model, *f.design, scene, o);
}

double rpm(double v) { return v * M_PI / 30.0; }

// Largest scaled difference of the HB orbit from a shooting orbit's flow over one period.
double orbitDifference(const MeshModel& model, const BalanceOrbit& hb, const PeriodicOrbit& sh, const Accuracy& acc) {
  const System& sys = model.system();
  std::vector<double> y = sh.y0;
  std::vector<double> samples;
  for (int k = 1; k <= 64; ++k)
    samples.push_back(hb.period * k / 64.0);
  Integrator integ(sys, acc);
  double t = 0, worst = 0;
  auto compare = [&](double ts, const double* ys) {
    std::vector<double> h = hb.state(ts);
    for (size_t a = 0; a < sys.dim; ++a)
      worst = std::max(worst, std::fabs(h[a] - ys[a]) / sys.scale[a]);
  };
  compare(0, y.data());
  EXPECT_TRUE(integ.advance(t, y, hb.period, samples, compare)) << integ.error();
  return worst;
}

} // namespace

TEST(HarmonicBalance, LinearMarineSceneAgreesWithShooting) {
  std::string text = readCorpusSpec("marine_reducer.gbx"); // the contact-line model, 5 stiffness harmonics
  text = replaced(text, "settle = 200 mesh_periods;", "steady_state = periodic;");
  auto f = compile("p.gbx", text, "MarineReducer");
  MeshScene ms = meshScene(*f.model, *f.design, f.scene("vibration"));
  MeshModel model(ms.params, ms.effects);
  ASSERT_TRUE(model.linear());
  Accuracy acc = ms.accuracy;
  acc.rtol = 1e-13;
  PeriodicOptions po;
  po.period = model.excitationPeriod();
  po.linear = true;
  PeriodicOrbit sh = periodicOrbit(model.system(), acc, po, model.initialState());
  ASSERT_TRUE(sh.converged) << sh.failure;
  BalanceOptions bo;
  bo.period = po.period;
  bo.linear = true;
  bo.harmonics = 16;
  bo.floquet = acc;
  BalanceOrbit hb = harmonicBalance(model.system(), bo, model.initialState());
  ASSERT_TRUE(hb.converged) << hb.failure;
  EXPECT_EQ(hb.iterations, 1) << "linear: one step is exact";
  EXPECT_LT(orbitDifference(model, hb, sh, acc), 1e-10);
  EXPECT_LT(hb.gapResidual, 1e-8);
  EXPECT_NEAR(hb.stability, sh.stability, 1e-9);
  // Fewer harmonics: the error grows, and the estimate (the residual between the samples)
  // grows with it and stays above it.
  bo.harmonics = 4;
  bo.gapLimit = INFINITY;
  BalanceOrbit coarse = harmonicBalance(model.system(), bo, model.initialState());
  ASSERT_TRUE(coarse.converged) << coarse.failure;
  double err = orbitDifference(model, coarse, sh, acc);
  EXPECT_GT(err, 1e-9);
  EXPECT_GT(coarse.gapResidual, err);
}

TEST(HarmonicBalance, HillStabilityAgreesWithFloquetAcrossAMathieuTongue) {
  std::string text = test::spurTongueSpec("1e-11", "rms(acceleration), stability");
  auto f = compile("tongue.gbx", text, "SpurTongue");
  const auto& scene = f.scene("mesh");
  const auto& sweep = f.study("tongue");
  auto both = [&](double speed) {
    MeshScene ms = sceneAt(f, scene, &sweep, rpm(speed));
    MeshModel model(ms.params, ms.effects);
    PeriodicOptions po;
    po.period = model.excitationPeriod();
    po.linear = true;
    PeriodicOrbit sh = periodicOrbit(model.system(), ms.accuracy, po, model.initialState());
    BalanceOptions bo;
    bo.period = po.period;
    bo.linear = true;
    bo.harmonics = 24;
    bo.hillLimit = 1000; // Hill's method, not the variational equations
    BalanceOrbit hb = harmonicBalance(model.system(), bo, model.initialState());
    EXPECT_TRUE(sh.converged) << sh.failure;
    EXPECT_TRUE(hb.converged) << hb.failure;
    EXPECT_EQ(hb.stabilityMethod, "Hill's method");
    return std::make_pair(hb.stability, sh.stability);
  };
  for (double speed : {22000.0, 24500.0, 26500.0, 27693.0, 29000.0, 30500.0, 34000.0}) {
    auto [hill, floquet] = both(speed);
    EXPECT_NEAR(hill, floquet, 1e-6 * floquet) << speed << " rpm";
  }
  // The tongue's lower edge, where the largest multiplier crosses 1, by each method.
  auto edge = [&](bool byHill) {
    double lo = 24500, hi = 27693;
    for (int i = 0; i < 30; ++i) {
      double mid = 0.5 * (lo + hi);
      auto [hill, floquet] = both(mid);
      ((byHill ? hill : floquet) < 1.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  double eh = edge(true), ef = edge(false);
  EXPECT_GT(eh, 24500);
  EXPECT_LT(eh, 27693);
  EXPECT_NEAR(eh / ef, 1.0, 1e-6) << "Hill " << eh << " rpm, Floquet " << ef << " rpm";
}

TEST(HarmonicBalance, BriefContactLossIsNotReportedAsConverged) {
  auto f = compile("spur_resonance.gbx", readSpec("spur_resonance.gbx"), "SpurResonance");
  const auto& scene = f.scene("mesh");
  const auto& study = f.study("resonance");
  // On the upper branch near the jump-up speed the teeth separate for part of each period.
  MeshScene ms = sceneAt(f, scene, &study, rpm(12500));
  MeshModel model(ms.params, ms.effects);
  ASSERT_FALSE(model.linear());
  PeriodicOptions po;
  po.period = model.excitationPeriod();
  std::vector<double> knock = model.initialState();
  knock[1] = 40 * model.system().scale[1];
  PeriodicOrbit sh = periodicOrbit(model.system(), ms.accuracy, po, knock);
  ASSERT_TRUE(sh.converged) << sh.failure;
  // The fraction of the period without contact, and the orbit's states, on the shooting orbit.
  Integrator integ(model.system(), ms.accuracy);
  std::vector<double> y = sh.y0, samples;
  const int M = 4000;
  for (int k = 1; k <= M; ++k)
    samples.push_back(po.period * k / M);
  std::vector<std::vector<double>> states = {sh.y0};
  double t = 0;
  int apart = 0;
  ASSERT_TRUE(integ.advance(t, y, po.period, samples, [&](double ts, const double* ys) {
    if (model.signals(ts, ys).contactForce <= 0) ++apart;
    if (states.size() < M) states.emplace_back(ys, ys + y.size());
  }));
  double lost = static_cast<double>(apart) / M;
  ASSERT_GT(lost, 0.05) << "the upper branch loses contact";
  Eigen::MatrixXd guess = seriesOfSamples(states, {}, 64);
  BalanceOptions bo;
  bo.period = po.period;
  // Coarse: eight instants a period step over the changes of contact; the residual between
  // them says so and the orbit is not taken.
  bo.harmonics = 2;
  BalanceOrbit coarse = harmonicBalance(model.system(), bo, model.initialState(), &guess);
  EXPECT_EQ(coarse.timePoints, 8);
  EXPECT_FALSE(coarse.converged) << "gap residual " << coarse.gapResidual;
  EXPECT_FALSE(coarse.failure.empty());
  // Refined until the residual meets a target: the orbit is shooting's.
  bo.floquet = ms.accuracy;
  BalanceOrbit fine = harmonicBalanceTo(model.system(), bo, 1e-3, model.initialState(), 8, 1024, &guess);
  ASSERT_TRUE(fine.converged) << fine.failure;
  EXPECT_LE(fine.truncation, 1e-3);
  std::vector<double> y0 = fine.state(0);
  double diff = 0;
  for (size_t a = 0; a < y0.size(); ++a)
    diff = std::max(diff, std::fabs(y0[a] - sh.y0[a]) / model.system().scale[a]);
  EXPECT_LT(diff, fine.truncation) << "the estimate covers the error";
  EXPECT_LT(diff, 1e-3) << "lost contact over " << lost << " of the period, " << fine.harmonics << " harmonics";
  EXPECT_NEAR(fine.stability, sh.stability, 1e-3) << fine.harmonics << " harmonics";
}

TEST(HarmonicBalance, SceneOutputsEqualShootingsAndCarryTheirEstimate) {
  std::string text = readCorpusSpec("marine_reducer.gbx");
  std::string shooting = replaced(text, "settle = 200 mesh_periods;", "steady_state = periodic;");
  std::string balance =
      replaced(text, "settle = 200 mesh_periods;", "steady_state = harmonic_balance; harmonics = 16;");
  auto fs = compile("s.gbx", shooting, "MarineReducer"), fb = compile("b.gbx", balance, "MarineReducer");
  SceneResult s = runScene(*fs.model, *fs.design, fs.scene("vibration"));
  SceneResult b = runScene(*fb.model, *fb.design, fb.scene("vibration"));
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_EQ(b.balanceHarmonics, 16);
  EXPECT_EQ(b.method, "harmonic_balance");
  // Integrated: only the one period of the variational equations for the stability (66
  // unknowns, above Hill's limit); the samples come from the series.
  EXPECT_TRUE(std::any_of(b.model.begin(), b.model.end(), [](const std::string& l) {
    return l.find("(one period of the variational equations)") != std::string::npos;
  }));
  const SceneNumber* rs = s.find("rms(acceleration)");
  const SceneNumber* rb = b.find("rms(acceleration)");
  ASSERT_TRUE(rs && rb);
  EXPECT_NEAR(rb->value / rs->value, 1.0, 1e-7) << "shooting at the scene's rtol 1e-9 is good to about 4e-8";
  EXPECT_NEAR(rb->value, 50.53239936, 5e-8) << "the independent measurement of docs/dynamics.md";
  EXPECT_NEAR(b.stability, s.stability, 1e-6);
  ASSERT_FALSE(b.errorParts.empty());
  EXPECT_EQ(b.errorParts.front().name, "harmonic truncation");
  EXPECT_LT(b.errorParts.front().value, 1e-8);
}

TEST(HarmonicBalance, ASceneFallsBackToShootingWhereNewtonStalls) {
  std::string text = replaced(readSpec("spur_resonance.gbx"), "steady_state = periodic;",
                              "steady_state = harmonic_balance; harmonics = 16;");
  auto f = compile("b.gbx", text, "SpurResonance");
  // From the teeth apart over the whole period (inside the backlash, at rest) the balance has
  // no stiffness to work with: its least-squares steps stall, and shooting takes over.
  SceneOverrides ov;
  ov.estimateError = false;
  ov.guess = std::vector<double>{0.0, 0.0};
  SceneResult r = runScene(*f.model, *f.design, f.scene("mesh"), ov);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  EXPECT_EQ(r.balanceHarmonics, 0);
  EXPECT_NE(r.method, "harmonic_balance");
  EXPECT_TRUE(std::any_of(r.model.begin(), r.model.end(), [](const std::string& l) {
    return l.find("harmonic balance with 16 harmonics did not find the orbit") != std::string::npos &&
           l.find("shooting instead") != std::string::npos;
  })) << "the fallback is stated in the model";
  EXPECT_TRUE(std::isfinite(r.stability));
}

// A row that is a velocity's unit row at some instants and zero at others is not a kinematic
// equation: the Newton step must not eliminate through it. A linear system's single step then
// solves the Galerkin equations exactly (what is left is rounding).
TEST(HarmonicBalance, ARowThatIsAUnitRowOnlySometimesIsNotEliminated) {
  const double w = 2 * M_PI, T = 1.0;
  auto gate = [&](double t) { return std::sin(w * t) >= 0 ? 1.0 : 0.0; };
  System sys;
  sys.dim = 2;
  sys.scale = {1.0, 1.0};
  sys.rhs = [&](double t, const double* y, double* f) {
    f[0] = gate(t) * y[1] - 0.5 * y[0];
    f[1] = -4.0 * y[0] - 0.2 * y[1] + std::cos(w * t);
  };
  sys.dfdy = [&](double t, const double*, double* J) {
    J[0] = -0.5;
    J[1] = gate(t);
    J[2] = -4.0;
    J[3] = -0.2;
  };
  // The same system with f_0 = gate y_1 alone (row 0 exactly (0, gate)): the trap.
  System trap = sys;
  trap.rhs = [&](double t, const double* y, double* f) {
    f[0] = gate(t) * y[1];
    f[1] = -4.0 * y[0] - 0.2 * y[1] + std::cos(w * t);
  };
  trap.dfdy = [&](double t, const double*, double* J) {
    J[0] = 0.0;
    J[1] = gate(t);
    J[2] = -4.0;
    J[3] = -0.2;
  };
  for (const System* s : {&sys, &trap}) {
    BalanceOptions opt;
    opt.period = T;
    opt.harmonics = 8;
    opt.linear = true;
    opt.stability = false;
    opt.gapLimit = INFINITY; // the gate's jumps fall between the instants: not this test's point
    BalanceOrbit o = harmonicBalance(*s, opt, {0.0, 0.0});
    ASSERT_TRUE(o.converged) << o.failure;
    Stats st;
    Eigen::MatrixXd R = balanceResidual(*s, opt, o.coeffs, nullptr, st);
    EXPECT_LT(R.cwiseAbs().maxCoeff(), 1e-10) << (s == &trap ? "gated kinematic row" : "damped row");
    EXPECT_TRUE(balanceKinematicPairs(*s, opt, o.coeffs).empty());
  }
}
