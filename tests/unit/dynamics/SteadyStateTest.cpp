// The periodic steady state on the product's own scenes, with asserted answers: the linear
// marine scene against a long transient, a Mathieu tongue of a spur mesh, and the softening
// jumps of a spur pair with backlash against brute-force transient runs.
#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "Specs.h"

#include "driver/Driver.h"
#include "dynamics/MeshModel.h"
#include "dynamics/Periodic.h"
#include "SceneFixture.h"
#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "study/Sweep.h"

using namespace gbx;
using namespace gbx::rt::dyn;

namespace {

using test::Fixture;
using test::compile;

std::string replaced(std::string s, const std::string& a, const std::string& b) {
  auto at = s.find(a);
  EXPECT_NE(at, std::string::npos) << a;
  if (at != std::string::npos) s.replace(at, a.size(), b);
  return s;
}

double value(const SceneResult& r, const std::string& key) {
  const SceneNumber* n = r.find(key);
  EXPECT_TRUE(n) << key << (r.failure.empty() ? "" : ": " + r.failure);
  return n ? n->value : NAN;
}

// The scene at an input speed (rad/s), through a sweep's override.
SceneResult at(const Fixture& f, const ir::Study& sweep, const ir::Scene& scene, double speed, SceneOverrides ov = {}) {
  rt::Evaluator ev(*f.model);
  ev.setOverride(sweep.swept, rt::Value::number(speed));
  ov.evaluator = &ev;
  ov.keepSeries = false;
  return runScene(*f.model, *f.design, scene, ov);
}

double rpm(double v) { return v * M_PI / 30.0; }

} // namespace

TEST(SteadyState, LinearMarinePeriodicEqualsALongTransient) {
  std::string text = readCorpusSpec("marine_reducer.gbx");  // the contact-line model
  text = replaced(text, "settle = 200 mesh_periods;", "steady_state = periodic;");
  // The transient settles 200 mesh periods (the response decays by e^-1.8 each); the
  // periodic scene solves for the orbit directly. Both at rtol 1e-11.
  std::string periodic = replaced(text, "rtol = 1e-9;", "rtol = 1e-11;");
  std::string transient = replaced(periodic, "steady_state = periodic;", "settle = 200 mesh_periods;");
  auto ft = compile("t.gbx", transient, "MarineReducer"), fp = compile("p.gbx", periodic, "MarineReducer");
  SceneOverrides ov;
  ov.estimateError = false;
  SceneResult t = runScene(*ft.model, *ft.design, ft.scene("vibration"), ov);
  SceneResult p = runScene(*fp.model, *fp.design, fp.scene("vibration"), ov);
  ASSERT_TRUE(t.failure.empty()) << t.failure;
  ASSERT_TRUE(p.failure.empty()) << p.failure;
  EXPECT_EQ(p.steady, SteadyMethod::Periodic);
  EXPECT_EQ(t.steady, SteadyMethod::Settle);
  double rt = value(t, "rms(acceleration)"), rp = value(p, "rms(acceleration)");
  EXPECT_NEAR(rp / rt, 1.0, 1e-9) << "periodic " << rp << " against transient " << rt;
  // An independent measurement (docs/dynamics.md) gives 50.53239936 for this scene.
  EXPECT_NEAR(rp, 50.53239936, 5e-8);
  // Linear: one Newton step is exact (the samples, in fixed steps, by superposition: no
  // second variational period, no record run); the orbit is stable.
  EXPECT_EQ(p.newtonIterations, 1);
  EXPECT_TRUE(std::isfinite(p.newtonResidual));
  EXPECT_LT(p.newtonResidual, 1e-10);
  EXPECT_LT(p.stability, 1.0);
  EXPECT_GT(p.stability, 0.0);
  // The work: a small fraction of the settled transient's.
  EXPECT_LT(p.stats.rhsEvaluations * 10, t.stats.rhsEvaluations)
      << p.stats.rhsEvaluations << " against " << t.stats.rhsEvaluations;
}

TEST(SteadyState, MathieuTongueOfASpurMesh) {
  // The principal parametric resonance of a spur mesh (SceneFixture.h).
  std::string text = test::spurTongueSpec("1e-9", "rms(acceleration), dynamic_factor, stability");
  auto f = compile("tongue.gbx", text, "SpurTongue");
  const auto& scene = f.scene("mesh");
  const auto& sweep = f.study("tongue");
  SceneResult inside = runScene(*f.model, *f.design, scene);
  ASSERT_TRUE(inside.failure.empty()) << inside.failure;
  double fn = inside.naturalFrequency, fm = inside.meshFrequency;
  EXPECT_NEAR(fm / fn, 2.0, 0.01) << "the scene sits at f_mesh = 2 f_n";
  EXPECT_GT(inside.stability, 1.05);
  EXPECT_TRUE(inside.unstable);
  EXPECT_TRUE(std::isnan(value(inside, "rms(acceleration)"))) << "no steady RMS inside the tongue";
  EXPECT_TRUE(std::isnan(value(inside, "dynamic_factor")));
  EXPECT_NEAR(value(inside, "stability"), inside.stability, 0);
  ASSERT_FALSE(inside.warnings.empty());
  EXPECT_NE(inside.warnings.back().find("unstable"), std::string::npos);
  // Just outside the tongue, on both sides: stable, with a steady RMS.
  for (double speed : {24500.0, 30500.0}) {
    SceneResult out = at(f, sweep, scene, rpm(speed));
    ASSERT_TRUE(out.failure.empty()) << out.failure;
    EXPECT_LT(out.stability, 1.0) << speed;
    EXPECT_GT(out.stability, 0.9) << speed << ": lightly damped";
    EXPECT_TRUE(std::isfinite(value(out, "rms(acceleration)"))) << speed;
  }
  // The multiplier is the growth a transient shows: from a state near the orbit, the
  // deviation grows by `stability` every period (a real multiplier) once the other has decayed.
  SceneOverrides ov;
  MeshScene ms = meshScene(*f.model, *f.design, scene, ov);
  MeshModel model(ms.params, ms.effects);
  std::vector<double> y = inside.orbit;
  y[0] *= 1.0 + 1e-9;
  std::vector<double> dev;
  double T = model.excitationPeriod();
  Integrator integ(model.system(), ms.accuracy);
  double t = 0;
  for (int k = 1; k <= 60; ++k) {
    ASSERT_TRUE(integ.advance(t, y, k * T, {}, [](double, const double*) {})) << integ.error();
    dev.push_back(std::hypot((y[0] - inside.orbit[0]) / model.system().scale[0], (y[1] - inside.orbit[1]) / model.system().scale[1]));
  }
  double growth = std::pow(dev[59] / dev[39], 1.0 / 20.0);
  EXPECT_NEAR(growth, inside.stability, 2e-3 * inside.stability);
  // A sweep marks the tongue: unstable points only around f_mesh = 2 f_n.
  rt::SweepStudy s = rt::sweep(*f.model, *f.design, sweep);
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  for (const auto& p : s.points) {
    double ratio = p.x / rpm(27693.0);
    if (std::fabs(ratio - 1.0) < 0.03) {
      EXPECT_GT(p.stability, 1.0) << p.x * 30 / M_PI;
    }
    if (std::fabs(ratio - 1.0) > 0.12) {
      EXPECT_LT(p.stability, 1.0) << p.x * 30 / M_PI;
    }
  }
}

TEST(SteadyState, BacklashSofteningJumpsAgreeWithBruteForceTransients) {
  auto f = compile("spur_resonance.gbx", readSpec("spur_resonance.gbx"), "SpurResonance");
  const auto& scene = f.scene("mesh");
  const auto& study = f.study("resonance");
  rt::SweepStudy s = rt::sweep(*f.model, *f.design, study);
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  EXPECT_EQ(s.continuation, "arclength");
  // Two turning points: the up-sweep's jump-up speed above the down-sweep's jump-down speed.
  ASSERT_EQ(s.folds.size(), 2u);
  double up = s.folds[0], down = s.folds[1];
  EXPECT_GT(up, down);
  EXPECT_GT(up, rpm(12500));
  EXPECT_LT(up, rpm(13600));
  EXPECT_GT(down, rpm(10800));
  EXPECT_LT(down, rpm(11800));
  // Three branches in the order followed; the middle one unstable, the others stable away
  // from the turning points, and the sweep covers the whole range.
  int unstableMiddle = 0, middle = 0;
  for (const auto& p : s.points) {
    ASSERT_GE(p.branch, 1);
    ASSERT_LE(p.branch, 3);
    if (p.branch == 2) {
      ++middle;
      if (p.stability > 1.0) ++unstableMiddle;
    } else if (std::fabs(p.x - up) > rpm(150) && std::fabs(p.x - down) > rpm(150)) {
      EXPECT_LT(p.stability, 1.0) << p.x * 30 / M_PI;
    }
  }
  EXPECT_GE(middle, 5);
  EXPECT_EQ(unstableMiddle, middle);
  EXPECT_EQ(s.points.front().branch, 1);
  EXPECT_EQ(s.points.back().branch, 3);
  EXPECT_NEAR(s.points.front().x, rpm(9000), 1e-9);
  EXPECT_GT(s.points.back().x, rpm(17000));
  // Brute force at three speeds inside the hysteresis region: a transient from the static
  // state settles on the lower branch, one started with a hard knock on the upper branch;
  // the periodic solutions from each end state agree with them, and with each other only
  // where the branches are distinct.
  SceneOverrides settle;
  settle.settlePeriods = 600;
  settle.estimateError = false;
  for (double speed : {down + 0.2 * (up - down), down + 0.5 * (up - down), down + 0.8 * (up - down)}) {
    SceneResult lower = at(f, study, scene, speed, settle);
    ASSERT_TRUE(lower.failure.empty()) << lower.failure;
    SceneOverrides knock = settle;
    MeshScene ms = [&] {
      rt::Evaluator ev(*f.model);
      ev.setOverride(study.swept, rt::Value::number(speed));
      SceneOverrides o;
      o.evaluator = &ev;
      return meshScene(*f.model, *f.design, scene, o);
    }();
    MeshModel model(ms.params, ms.effects);
    // Knocks of 10 to 80 times the static deflection's velocity scale; the largest settled
    // response is the upper branch's.
    SceneResult upper;
    for (double k : {10.0, 20.0, 40.0, 80.0}) {
      std::vector<double> y0 = model.initialState();
      y0[1] = k * model.system().scale[1];
      knock.guess = y0;
      SceneResult r = at(f, study, scene, speed, knock);
      ASSERT_TRUE(r.failure.empty()) << r.failure;
      if (upper.numbers.empty() || value(r, "rms(acceleration)") > value(upper, "rms(acceleration)")) upper = r;
    }
    double rl = value(lower, "rms(acceleration)"), ru = value(upper, "rms(acceleration)");
    EXPECT_GT(ru, 1.5 * rl) << "two coexisting responses at " << speed * 30 / M_PI << " rpm";
    EXPECT_GT(value(lower, "min(contact_force)"), 0.0) << "the lower branch keeps contact";
    EXPECT_LE(value(upper, "min(contact_force)"), 0.0) << "the upper branch loses contact";
    // The continuation's stable branches at this speed, interpolated.
    auto onBranch = [&](int b) {
      const rt::SweepStudy::Point* a = nullptr;
      for (const auto& p : s.points) {
        if (p.branch != b) continue;
        if (a && (a->x - speed) * (p.x - speed) <= 0)
          return a->y[1] + (p.y[1] - a->y[1]) * (speed - a->x) / (p.x - a->x);
        a = &p;
      }
      return static_cast<double>(NAN);
    };
    EXPECT_NEAR(onBranch(1) / rl, 1.0, 0.02) << speed * 30 / M_PI << " rpm, lower branch";
    EXPECT_NEAR(onBranch(3) / ru, 1.0, 0.02) << speed * 30 / M_PI << " rpm, upper branch";
    // Shooting at exactly this speed, started from each transient's settled state: the
    // same orbit, so the same RMS to the integration's accuracy, and stable.
    for (const SceneResult* tr : {&lower, &upper}) {
      ASSERT_EQ(tr->orbit.size(), 2u);
      SceneOverrides ov;
      ov.estimateError = false;
      ov.guess = tr->orbit;
      SceneResult p = at(f, study, scene, speed, ov);
      ASSERT_TRUE(p.failure.empty()) << p.failure;
      EXPECT_NEAR(value(p, "rms(acceleration)") / value(*tr, "rms(acceleration)"), 1.0, 1e-6) << speed * 30 / M_PI << " rpm";
      EXPECT_LT(p.stability, 1.0);
    }
  }
}

TEST(SteadyState, FluctuationFrequencyInHertzIsTwoPiRadiansPerSecond) {
  auto spec = [](const std::string& frequency) {
    return "gearbox G {\n  stage s1: spur { pinion.z = 25; wheel.z = 50; normal_module = 3 mm; face_width = 30 mm; }\n"
           "  operating { input_speed = 3000 rpm; input_torque = 200 N*m; }\n"
           "  scene vib on s1 { effects { torque_fluctuation { mean = 200 N*m; amplitude = 20 N*m; frequency = " +
           frequency + "; } } settle = 10 mesh_periods; record = 1 mesh_period; output rms(acceleration); }\n}\n";
  };
  auto hz = compile("hz.gbx", spec("6.25 Hz"), "G"), deg = compile("deg.gbx", spec("2250 deg/s"), "G");
  MeshScene a = meshScene(*hz.model, *hz.design, hz.scene("vib")), b = meshScene(*deg.model, *deg.design, deg.scene("vib"));
  EXPECT_NEAR(a.effects.torqueOmega, 2 * M_PI * 6.25, 1e-12);
  EXPECT_NEAR(b.effects.torqueOmega, 2 * M_PI * 6.25, 1e-12);
}

TEST(SteadyState, RecordWindowCoversAWholeOrbit) {
  // A load fluctuation at a quarter of the mesh frequency: the orbit repeats after four mesh
  // periods, so one recorded mesh period would see a quarter of it.
  auto spec = [](const std::string& record) {
    return "gearbox G {\n  stage s1: spur { pinion.z = 25; wheel.z = 50; normal_module = 3 mm; face_width = 30 mm; }\n"
           "  operating { input_speed = 3000 rpm; input_torque = 200 N*m; }\n"
           "  scene vib on s1 { effects { varying_stiffness { harmonics = 5; } damping { ratio = 0.05; }\n"
           "    torque_fluctuation { mean = 400 N*m; amplitude = 200 N*m; frequency = 312.5 Hz; } }\n"
           "    steady_state = periodic; record = " +
           record + "; output dynamic_factor, min(mesh_force); }\n}\n";
  };
  auto one = compile("one.gbx", spec("1 mesh_period"), "G"), four = compile("four.gbx", spec("4 mesh_periods"), "G");
  SceneOverrides ov;
  ov.estimateError = false;
  SceneResult a = runScene(*one.model, *one.design, one.scene("vib"), ov), b = runScene(*four.model, *four.design, four.scene("vib"), ov);
  ASSERT_TRUE(a.failure.empty()) << a.failure;
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_NEAR(a.period * a.meshFrequency, 4.0, 1e-9);
  EXPECT_NEAR(value(a, "dynamic_factor"), value(b, "dynamic_factor"), 1e-9 * value(b, "dynamic_factor"));
  EXPECT_NEAR(value(a, "min(mesh_force)"), value(b, "min(mesh_force)"), 1e-6 * std::fabs(value(b, "min(mesh_force)")));
  bool said = false;
  for (const auto& line : a.model) said = said || line.find("record window widened") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(SteadyState, NaturalUpAndDownSweepsRideDifferentBranches) {
  // Inside the hysteresis region an up-sweep rides the lower branch and a down-sweep the
  // upper one: the same speeds, two responses.
  std::string text = readSpec("spur_resonance.gbx");
  auto sweepOf = [&](const std::string& range) {
    std::string t = replaced(text, "sweep input_speed in 9000..18000 rpm step 250 rpm;", "sweep input_speed in " + range + ";");
    t = replaced(t, "continuation = arclength;", "");
    auto f = compile("updown.gbx", t, "SpurResonance");
    rt::SweepStudy s = rt::sweep(*f.model, *f.design, f.study("resonance"));
    EXPECT_TRUE(s.failure.empty()) << s.failure;
    return s;
  };
  rt::SweepStudy up = sweepOf("11000..12500 rpm step 500 rpm"), down = sweepOf("14000..12000 rpm step 500 rpm");
  ASSERT_EQ(up.points.size(), 4u);
  ASSERT_EQ(down.points.size(), 5u);
  EXPECT_GT(down.points[0].x, down.points[4].x) << "the points follow the sweep's direction";
  // 12000 and 12500 rpm: up-sweep points 2 and 3, down-sweep points 4 and 3.
  for (auto [u, d] : {std::pair<size_t, size_t>{2, 4}, {3, 3}}) {
    EXPECT_NEAR(up.points[u].x, down.points[d].x, 1e-9);
    EXPECT_GT(down.points[d].y[1], 2.0 * up.points[u].y[1]) << up.points[u].x * 30 / M_PI << " rpm";
    EXPECT_LT(up.points[u].stability, 1.0);
    EXPECT_LT(down.points[d].stability, 1.0);
  }
}

TEST(SteadyState, BacklashSweepFromLowSpeedCrossesTheSuperharmonicFoldsToTheEnd) {
  // From 1000 rpm the response passes the superharmonic resonances (k f_mesh = f_n for k = 2,
  // 3, …), each bent by the backlash into its own pair of turning points, before the primary
  // one; the continuation reaches the end of the range, and the turning points do not move
  // with the sweep's step.
  std::string base = readSpec("spur_resonance.gbx");
  auto sweepWith = [&](const std::string& range) {
    auto f = compile("low.gbx", replaced(base, "sweep input_speed in 9000..18000 rpm step 250 rpm;", range),
                     "SpurResonance");
    return rt::sweep(*f.model, *f.design, f.study("resonance"));
  };
  rt::SweepStudy coarse = sweepWith("sweep input_speed in 1000..18000 rpm step 250 rpm;");
  rt::SweepStudy fine = sweepWith("sweep input_speed in 1000..18000 rpm step 50 rpm;");
  rt::SweepStudy primary = sweepWith("sweep input_speed in 9000..18000 rpm step 250 rpm;");
  for (const auto* s : {&coarse, &fine, &primary})
    ASSERT_TRUE(s->failure.empty()) << s->failure;
  EXPECT_NEAR(coarse.points.back().x, rpm(18000), 1e-6);
  ASSERT_GE(coarse.folds.size(), 4u) << "the superharmonic resonance below the primary one bends too";
  ASSERT_EQ(coarse.folds.size(), fine.folds.size());
  for (size_t i = 0; i < coarse.folds.size(); ++i)
    EXPECT_NEAR(coarse.folds[i] / fine.folds[i], 1.0, 1e-4) << i;
  // The primary resonance's jumps, the last two, as the sweep from 9000 rpm finds them.
  ASSERT_EQ(primary.folds.size(), 2u);
  EXPECT_NEAR(coarse.folds[coarse.folds.size() - 2] / primary.folds[0], 1.0, 1e-4);
  EXPECT_NEAR(coarse.folds.back() / primary.folds[1], 1.0, 1e-4);
}

TEST(SteadyState, LightlyDampedBacklashSweepFromLowSpeedSaysWhereTheResponseRunsAwayAndReachesTheEnd) {
  // At 2 % damping a branch of the primary resonance climbs without bound below the mesh's
  // parametric instability (at amplitudes far above the clearance the backlash no longer
  // limits it). Both continuations say so, stop following it, settle the response from rest
  // just past it and follow that to the end of the range. The orbit they resume on is the one
  // a long transient from rest settles to at that speed: the same rms acceleration.
  std::string base = readSpec("spur_resonance.gbx");
  base = replaced(base, "damping { ratio = 0.05; }", "damping { ratio = 0.02; }");
  base = replaced(base, "damping { ratio = 0.05; }", "damping { ratio = 0.02; }");
  base = replaced(base, "sweep input_speed in 9000..18000 rpm step 250 rpm;",
                  "sweep input_speed in 1000..18000 rpm step 250 rpm;");
  base = replaced(base, "sweep input_speed in 9000..18000 rpm step 250 rpm;",
                  "sweep input_speed in 1000..18000 rpm step 250 rpm;");
  auto f = compile("light.gbx", base, "SpurResonance");
  for (const char* study : {"resonance", "resonance_balance"}) {
    SCOPED_TRACE(study);
    rt::SweepStudy s = rt::sweep(*f.model, *f.design, f.study(study));
    ASSERT_TRUE(s.failure.empty()) << s.failure;
    EXPECT_NEAR(s.points.back().x, rpm(18000), 1e-6);
    bool said = false;
    for (const auto& note : s.notes)
      said = said || note.find("grows without bound towards input_speed") != std::string::npos;
    EXPECT_TRUE(said);
    ASSERT_GE(s.gaps.size(), 1u);
    EXPECT_NEAR(s.gaps[0].first, rpm(13000), rpm(100));
    auto resumed = std::find_if(s.points.begin(), s.points.end(), [](const auto& p) { return p.afterGap; });
    ASSERT_NE(resumed, s.points.end());
    EXPECT_LT(resumed->stability, 1.0);
    // The transient from rest at that speed: 1500 mesh periods settled.
    std::string settled = replaced(base, "steady_state = periodic;", "settle = 1500 mesh_periods;");
    settled = replaced(settled, "output rms(acceleration), dynamic_factor, stability, min(contact_force);",
                       "output rms(acceleration), dynamic_factor, min(contact_force);");
    auto g = compile("settled.gbx", settled, "SpurResonance");
    SceneResult r = at(g, g.study("resonance"), g.scene("mesh"), resumed->x);
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    EXPECT_NEAR(resumed->y[1] / value(r, "rms(acceleration)"), 1.0, 1e-4) << resumed->x * 30 / M_PI << " rpm";
  }
}

namespace {

// Two spur stages whose meshes come round together in 8 periods of the first (5 of the
// second): 20/40 and 25/50.
std::string twoStageBox(const std::string& ls, const std::string& steady) {
  return R"(import materials;
gearbox TwoStage {
  stage hs: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; pressure_angle = 20 deg; face_width = 30 mm;
                   material = steel_42CrMo4; }
  stage ls: spur { )" +
         ls + R"( normal_module = 4 mm; pressure_angle = 20 deg; face_width = 40 mm;
                   material = steel_42CrMo4; }
  operating { input_speed = 3000 rpm; input_torque = 200 N*m; }
  scene box on TwoStage {
    effects { varying_stiffness { harmonics = 10; } damping { ratio = 0.05; } }
    )" + steady +
         R"(
    accuracy { rtol = 1e-9; }
    output peak(mesh_force(hs)), mean(mesh_force(hs)), peak(mesh_force(ls)), min(mesh_force(ls));
  }
}
)";
}

} // namespace

TEST(SteadyState, WholeGearboxPeriodicEqualsALongSettleAndHarmonicBalance) {
  const std::string teeth = "pinion.z = 25; wheel.z = 50;";
  SceneOverrides ov;
  ov.estimateError = false;
  auto run = [&](const std::string& steady) {
    auto f = compile("box.gbx", twoStageBox(teeth, steady), "TwoStage");
    SceneResult r = runScene(*f.model, *f.design, f.scene("box"), ov);
    EXPECT_TRUE(r.failure.empty()) << r.failure;
    return r;
  };
  SceneResult p = run("steady_state = periodic; record = 1 mesh_period; samples = 64;");
  SceneResult s = run("settle = 1600 mesh_periods; record = 8 mesh_periods; samples = 64;");
  SceneResult b = run("steady_state = harmonic_balance; record = 1 mesh_period; samples = 64;");
  EXPECT_EQ(p.steady, SteadyMethod::Periodic);
  EXPECT_NEAR(p.period * 3000.0 / 60.0 * 20.0, 8.0, 1e-9) << "eight periods of the first mesh";
  EXPECT_LT(p.stability, 1.0);
  EXPECT_GT(p.stability, 0.0);
  bool widened = false;
  for (const auto& line : p.model)
    widened = widened || line.find("8 periods of the fastest mesh") != std::string::npos;
  EXPECT_TRUE(widened);
  for (const char* key :
       {"peak(mesh_force(hs))", "mean(mesh_force(hs))", "peak(mesh_force(ls))", "min(mesh_force(ls))"}) {
    SCOPED_TRACE(key);
    double vp = value(p, key), vs = value(s, key), vb = value(b, key);
    // The settled transient's state has decayed by far more than its tolerance in 1 600 periods.
    EXPECT_NEAR(vp / vs, 1.0, 1e-8);
    // Harmonic balance: its samples from the series, against the integrated orbit's.
    EXPECT_NEAR(vb / vp, 1.0, 1e-5);
  }
  EXPECT_GT(b.balanceHarmonics, 0);
  EXPECT_NEAR(b.stability, p.stability, 1e-6);
  // Its cost: a small fraction of the settled transient's.
  EXPECT_LT(p.stats.rhsEvaluations * 10, s.stats.rhsEvaluations);
}

TEST(SteadyState, WholeGearboxWhoseMeshesNeverComeRoundTogetherIsRefused) {
  // 17/97, 19/89, 23/83: the second mesh turns 19/97 as often as the first, the third
  // 19 23/(97 89): the three come round together only every 97 x 89 = 8 633 periods of the
  // first, beyond the 1 000 a periodic scene takes.
  std::string text = R"(import materials;
gearbox Three {
  stage a: spur { pinion.z = 17; wheel.z = 97; normal_module = 3 mm; pressure_angle = 20 deg; face_width = 30 mm;
                  material = steel_42CrMo4; }
  stage b: spur { pinion.z = 19; wheel.z = 89; normal_module = 4 mm; pressure_angle = 20 deg; face_width = 40 mm;
                  material = steel_42CrMo4; }
  stage c: spur { pinion.z = 23; wheel.z = 83; normal_module = 5 mm; pressure_angle = 20 deg; face_width = 50 mm;
                  material = steel_42CrMo4; }
  operating { input_speed = 3000 rpm; input_torque = 20 N*m; }
  scene box on Three {
    effects { damping { ratio = 0.05; } }
    steady_state = periodic; record = 1 mesh_period;
    output peak(mesh_force(a));
  }
}
)";
  auto f = compile("three.gbx", text, "Three");
  SceneOverrides ov;
  ov.estimateError = false;
  SceneResult r = runScene(*f.model, *f.design, f.scene("box"), ov);
  ASSERT_FALSE(r.failure.empty());
  EXPECT_NE(r.failure.find("quasi-periodic"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("settle"), std::string::npos) << r.failure;
}
