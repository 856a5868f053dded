// The periodic steady state of a planetary stage, found by shooting, against a long
// transient from rest.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "dynamics/Planetary.h"
#include "model/Evaluator.h"
#include "model/Model.h"

using namespace gbx;
using namespace gbx::rt::dyn;

namespace {

// Hertz contact on every mesh with a light mesh damping: the slowest transient decays by a
// factor of about 0.8 per mesh period, so a run from rest needs over a hundred periods.
// (The contact damping `0.01 * stiffness` of specs/electric_cylinder.gbx overdamps the
// contact at its static penetration: that transient is gone within three mesh periods.)
const char* kHertz = R"(varying_stiffness { harmonics = 5; }
      hertz_contact { exponent = 1.5; penetration_ramp = 0.1 mm; }
      damping { ratio = 0.002; })";
const char* kHertzDamped = R"(varying_stiffness { harmonics = 5; }
      hertz_contact { exponent = 1.5; penetration_ramp = 0.1 mm; damping = 0.01 * stiffness; })";

// The electric cylinder's planetary stage (specs/electric_cylinder.gbx, 19/23/65) with the
// given effects and time settings, run as Scene.cpp runs it.
PlanetaryRun runStage(const std::string& effects, const std::string& timing, bool periodic, double rtol = 1e-10) {
  auto c = driver::compileText("planet.gbx", R"(gearbox P {
  stage p: planetary { sun.z = 19; planet.z = 23; ring.z = 65; planets = 3; module = 0.6 mm; face_width = 6 mm; }
  operating { input_speed = 600 rpm; output_torque = 3 N*m; }
  scene s on p {
    effects { )" + effects + R"( }
    )" + timing + R"(
    output rms(contact_force);
  }
})");
  EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  if (!c->ok()) return {};
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::Assignment a(m);
  rt::Evaluator ev(m);
  const rt::ScenePlan& scene = m.scenes[0];
  int st = scene.stage;
  Accuracy acc;
  acc.method = scene.method;
  acc.rtol = rtol;
  double upstream = ev.ratioProduct(0, st, a).mid();
  double downstream = ev.ratioProduct(st + 1, static_cast<int>(m.stages.size()), a).mid();
  double speed = ev.derived(st, Q::InputSpeed, a).mid();
  return runPlanetary(ev, a, st, scene, acc, SceneOverrides{}, upstream, downstream, speed, 206e9, 0.3, 7850, true, periodic);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}
const std::vector<double>& sig(const PlanetaryRun& r, cat::Signal s) { return r.signals[static_cast<size_t>(s)]; }

} // namespace

namespace {

struct Figures {
  double rmsForce, meanForce, rmsAcceleration;
};
Figures figures(const PlanetaryRun& r) {
  const auto& f = sig(r, cat::Signal::ContactForce);
  return {rms(f), mean(f), rms(sig(r, cat::Signal::Acceleration))};
}
double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }
std::string settled(long periods) { return "settle = " + std::to_string(periods) + " mesh_periods; record = 1 mesh_period;"; }

} // namespace

TEST(PlanetaryPeriodic, SteadyStateMatchesALongTransient) {
  PlanetaryRun p = runStage(kHertz, "record = 1 mesh_period;", true);
  ASSERT_TRUE(p.failure.empty()) << p.failure;
  EXPECT_TRUE(p.periodic);
  ASSERT_GT(p.stability, 0.0);
  ASSERT_LT(p.stability, 1.0);
  ASSERT_EQ(p.t.size(), 160u);
  EXPECT_EQ(p.t.front(), 0.0);
  // Settle until the slowest transient, |multiplier|^N, is below 1e-12; N and 2N agree.
  long N = static_cast<long>(std::ceil(std::log(1e-12) / std::log(p.stability)));
  PlanetaryRun r1 = runStage(kHertz, settled(N), false), r2 = runStage(kHertz, settled(2 * N), false);
  ASSERT_TRUE(r1.failure.empty()) << r1.failure;
  ASSERT_TRUE(r2.failure.empty()) << r2.failure;
  Figures fp = figures(p), f1 = figures(r1), f2 = figures(r2);
  // At rtol 1e-10 the orbit's residual is ~1e-11 of the state scale and the transient's
  // accumulated error ~1e-10: the force figures agree far inside 1e-8. The acceleration
  // is the mesh stiffness times the deflection error, about 1e3 times less well resolved.
  EXPECT_LT(rel(f1.rmsForce, f2.rmsForce), 1e-8);
  EXPECT_LT(rel(f1.meanForce, f2.meanForce), 1e-8);
  EXPECT_LT(rel(fp.rmsForce, f2.rmsForce), 1e-8);
  EXPECT_LT(rel(fp.meanForce, f2.meanForce), 1e-8);
  EXPECT_LT(rel(fp.rmsAcceleration, f2.rmsAcceleration), 1e-6);
  double ratio = static_cast<double>(r1.stats.rhsEvaluations) / static_cast<double>(p.stats.rhsEvaluations);
  std::printf("stability %.6f, settle %ld mesh periods; rhs: periodic %ld (%d Newton iterations), transient %ld and %ld (ratio %.1f); "
              "relative differences: rms force %.2e, mean force %.2e, rms acceleration %.2e\n",
              p.stability, N, p.stats.rhsEvaluations, p.newtonIterations, r1.stats.rhsEvaluations, r2.stats.rhsEvaluations, ratio,
              rel(fp.rmsForce, f2.rmsForce), rel(fp.meanForce, f2.meanForce), rel(fp.rmsAcceleration, f2.rmsAcceleration));
  EXPECT_GT(ratio, 5.0);
  bool said = false;
  for (const auto& l : p.provenance) said |= l.rfind("periodic steady state: period", 0) == 0;
  EXPECT_TRUE(said);
}

TEST(PlanetaryPeriodic, OverdampedContactSettlesInAFewPeriods) {
  PlanetaryRun p = runStage(kHertzDamped, "record = 1 mesh_period;", true);
  ASSERT_TRUE(p.failure.empty()) << p.failure;
  EXPECT_LT(p.stability, 1e-3);
  PlanetaryRun r = runStage(kHertzDamped, settled(20), false);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  Figures fp = figures(p), fr = figures(r);
  EXPECT_LT(rel(fp.rmsForce, fr.rmsForce), 1e-8);
  EXPECT_LT(rel(fp.meanForce, fr.meanForce), 1e-8);
  // The acceleration reads the contact forces, whose stiff Hertz law turns state differences at
  // rtol 1e-10 into a few 1e-6 (settling 40 periods instead of 20 changes it by no more).
  EXPECT_LT(rel(fp.rmsAcceleration, fr.rmsAcceleration), 5e-6);
}

TEST(PlanetaryPeriodic, ExcitationWithoutACommonPeriodIsRefused) {
  // A 1 Hz load holds 147.02... mesh periods: whole ones only after 6175 (42 s).
  PlanetaryRun p = runStage(std::string(kHertz) + " torque_fluctuation { mean = 3 N*m; amplitude = 1 N*m; frequency = 1 Hz; }",
                            "record = 1 mesh_period;", true);
  EXPECT_NE(p.failure.find("the excitation is not periodic"), std::string::npos) << p.failure;
  EXPECT_NE(p.failure.find("settle"), std::string::npos) << p.failure;
  PlanetaryRun ramp = runStage(kHertz, "ramp = 0.1 s; duration = 1 s;", true);
  EXPECT_NE(ramp.failure.find("the excitation is not periodic (a `ramp` start-up)"), std::string::npos) << ramp.failure;
}

TEST(PlanetaryPeriodic, TransmissionErrorIsRecordedWhenListed) {
  PlanetaryRun p = runStage(std::string(kHertz) + " transmission_error { amplitude = 2 um; }", "record = 1 mesh_period;", true);
  ASSERT_TRUE(p.failure.empty()) << p.failure;
  const auto& te = sig(p, cat::Signal::TransmissionError);
  ASSERT_EQ(te.size(), p.t.size());
  auto [lo, hi] = std::minmax_element(te.begin(), te.end());
  // One period of the sine, 160 samples: its extremes within 1e-3 of the amplitude.
  EXPECT_NEAR(*hi, 2e-6, 2e-9);
  EXPECT_NEAR(*lo, -2e-6, 2e-9);
  PlanetaryRun none = runStage(kHertz, "record = 1 mesh_period;", true);
  EXPECT_TRUE(sig(none, cat::Signal::TransmissionError).empty());
}

TEST(PlanetaryPeriodic, HarmonicBalanceFindsTheShootingOrbit) {
  // The same Hertz-contact stage (nonlinear: contact law and carrier phase) by harmonic balance,
  // its harmonics doubled until the orbit moves less than rtol, against shooting.
  PlanetaryRun shooting = runStage(kHertz, "record = 1 mesh_period;", true, 1e-10);
  PlanetaryRun balance = runStage(kHertz, "steady_state = harmonic_balance; record = 1 mesh_period;", true, 1e-8);
  ASSERT_TRUE(shooting.failure.empty()) << shooting.failure;
  ASSERT_TRUE(balance.failure.empty()) << balance.failure;
  ASSERT_GT(balance.balanceHarmonics, 0) << (balance.provenance.empty() ? "" : balance.provenance.back());
  ASSERT_EQ(balance.t.size(), shooting.t.size());
  Figures fb = figures(balance), fs = figures(shooting);
  EXPECT_LT(rel(fb.rmsForce, fs.rmsForce), 1e-6);
  EXPECT_LT(rel(fb.meanForce, fs.meanForce), 1e-6);
  EXPECT_NEAR(balance.stability, shooting.stability, 1e-4);
}
