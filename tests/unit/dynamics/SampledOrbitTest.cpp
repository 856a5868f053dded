// Shooting in fixed steps that land on the samples, against adaptive shooting at a tight
// tolerance: the marine scene (linear), samples too sparse for one step each, a nonlinear
// (Duffing) oscillator, and the models it does not serve (contact events).
#include <cmath>

#include <gtest/gtest.h>

#include "Specs.h"

#include "SceneFixture.h"
#include "dynamics/MeshModel.h"
#include "dynamics/Periodic.h"
#include "dynamics/SampledOrbit.h"
#include "dynamics/Scene.h"

using namespace gbx;
using namespace gbx::rt::dyn;

namespace {

std::vector<double> flowTo(const System& sys, const Accuracy& acc, std::vector<double> y, double t) {
  Integrator integ(sys, acc);
  double t0 = 0;
  if (t > 0) integ.advance(t0, y, t, {}, [](double, const double*) {});
  return y;
}

// The largest difference of the sampled states from the reference orbit's, of the scale.
double worstAgainst(const System& sys, const SampledOrbit& so, const std::vector<double>& y0, const Accuracy& tight) {
  double worst = 0;
  for (size_t k = 0; k < so.states.size(); ++k) {
    std::vector<double> ref = flowTo(sys, tight, y0, so.dt * static_cast<double>(k));
    for (size_t i = 0; i < ref.size(); ++i)
      worst = std::max(worst, std::fabs(so.states[k][i] - ref[i]) / sys.scale[i]);
  }
  return worst;
}

struct Marine {
  test::Fixture f = test::compile("marine.gbx", readCorpusSpec("marine_reducer.gbx"), "MarineReducer");
  MeshScene ms;
  std::unique_ptr<MeshModel> model;
  Marine() {
    SceneOverrides ov;
    ov.forcePeriodic = true;
    ms = meshScene(*f.model, *f.design, f.scene("vibration"), ov);
    model = std::make_unique<MeshModel>(ms.params, ms.effects);
  }
};

// x'' + 2 zeta w x' + w^2 x + beta x^3 = F cos(W t), stiffening enough to need Newton.
struct Duffing {
  double w = 2 * M_PI, zeta = 0.05, beta = 40.0, F = 6.0, W = 1.3 * 2 * M_PI;
  System sys;
  Duffing() {
    sys.dim = 2;
    sys.rhs = [this](double t, const double* y, double* dy) {
      dy[0] = y[1];
      dy[1] = F * std::cos(W * t) - 2 * zeta * w * y[1] - w * w * y[0] - beta * y[0] * y[0] * y[0];
    };
    sys.dfdy = [this](double, const double* y, double* J) {
      J[0] = 0;
      J[1] = 1;
      J[2] = -w * w - 3 * beta * y[0] * y[0];
      J[3] = -2 * zeta * w;
    };
    sys.scale = {0.1, 0.1 * w};
  }
};

} // namespace

TEST(SampledOrbit, LinearMarineSceneMatchesAdaptiveShootingAtEverySample) {
  Marine mr;
  const System& sys = mr.model->system();
  ASSERT_TRUE(fixedStepsServe(sys, mr.ms.accuracy));
  PeriodicOptions opt;
  opt.period = mr.model->excitationPeriod();
  opt.linear = mr.model->linear();
  ASSERT_TRUE(opt.linear);
  Accuracy acc = mr.ms.accuracy, tight = acc;
  acc.rtol = 1e-8;
  tight.rtol = 1e-13;
  SampledOrbit so = sampledOrbit(sys, acc, opt, mr.model->initialState(), mr.ms.plan.dt);
  ASSERT_TRUE(so.orbit.converged) << so.orbit.failure;
  PeriodicOrbit ref = periodicOrbit(sys, tight, opt, mr.model->initialState());
  ASSERT_TRUE(ref.converged);
  EXPECT_EQ(so.stepsPerSample, 1);
  EXPECT_EQ(so.orbit.iterations, 1);
  EXPECT_EQ(static_cast<double>(so.states.size()), std::round(opt.period / mr.ms.plan.dt));
  // One rk8pd step (13 stages) per sample, and nothing else.
  EXPECT_EQ(so.orbit.stats.rhsEvaluations, 13 * static_cast<long>(so.states.size()));
  EXPECT_LT(worstAgainst(sys, so, ref.y0, tight), 1e-10);
  EXPECT_NEAR(so.orbit.stability, ref.stability, 1e-9);
  // A sample time a whole period later reads the same state.
  EXPECT_EQ(&so.at(3 * mr.ms.plan.dt), &so.at(3 * mr.ms.plan.dt + opt.period));
}

TEST(SampledOrbit, SparseSamplesTakeMoreStepsEachAndKeepTheTolerance) {
  Marine mr;
  const System& sys = mr.model->system();
  PeriodicOptions opt;
  opt.period = mr.model->excitationPeriod();
  opt.linear = true;
  Accuracy acc = mr.ms.accuracy, tight = acc;
  acc.rtol = 1e-10;
  acc.maxStep = 0;
  tight.rtol = 1e-13;
  SampledOrbit so = sampledOrbit(sys, acc, opt, mr.model->initialState(), opt.period / 4);
  ASSERT_TRUE(so.orbit.converged) << so.orbit.failure;
  EXPECT_GT(so.stepsPerSample, 1) << "a quarter period is too long a step at rtol 1e-10";
  PeriodicOrbit ref = periodicOrbit(sys, tight, opt, mr.model->initialState());
  EXPECT_LT(worstAgainst(sys, so, ref.y0, tight), 1e-8);
  // Fixed by the caller (an error estimate's rerun): exactly that many.
  SampledOrbit two = sampledOrbit(sys, acc, opt, mr.model->initialState(), opt.period / 4, 2 * so.stepsPerSample);
  EXPECT_EQ(two.stepsPerSample, 2 * so.stepsPerSample);
}

// The Duffing orbit with `divisions` samples a period at rtol 1e-10, and adaptive shooting's
// at 1e-13 from the same start.
struct DuffingOrbits {
  Duffing d;
  PeriodicOptions opt;
  Accuracy tight;
  SampledOrbit so;
  PeriodicOrbit ref;
  DuffingOrbits(double F, int divisions) {
    d.F = F;
    opt.period = 2 * M_PI / d.W;
    Accuracy acc;
    acc.rtol = 1e-10;
    tight.rtol = 1e-13;
    so = sampledOrbit(d.sys, acc, opt, {0.0, 0.0}, opt.period / divisions);
    ref = periodicOrbit(d.sys, tight, opt, {0.0, 0.0});
  }
  double worst() const { return worstAgainst(d.sys, so, ref.y0, tight); }
};

TEST(SampledOrbit, NonlinearOrbitByNewtonMatchesAdaptiveShooting) {
  DuffingOrbits o(6.0, 200);
  const SampledOrbit& so = o.so;
  ASSERT_TRUE(so.orbit.converged) << so.orbit.failure;
  EXPECT_GT(so.orbit.iterations, 2);
  const PeriodicOrbit& ref = o.ref;
  ASSERT_TRUE(ref.converged);
  EXPECT_LT(o.worst(), 1e-8);
  EXPECT_NEAR(so.orbit.stability, ref.stability, 1e-7);
  double amplitude = 0;
  for (const auto& y : so.states)
    amplitude = std::max(amplitude, std::fabs(y[0]));
  EXPECT_GT(amplitude, 0.05) << "a response, not the trivial orbit";
}

TEST(SampledOrbit, DoesNotServeContactEventsOrAnImplicitMethod) {
  Duffing d;
  Accuracy acc;
  EXPECT_TRUE(fixedStepsServe(d.sys, acc));
  System withEvent = d.sys;
  withEvent.events.push_back([](double, const double* y) { return y[0]; });
  EXPECT_FALSE(fixedStepsServe(withEvent, acc));
  acc.method = cat::Method::Msbdf;
  EXPECT_FALSE(fixedStepsServe(d.sys, acc));
}

TEST(SampledOrbit, TheOrbitsOwnStepsMeetTheToleranceNotOnlyTheGuesses) {
  // Driven hard, the orbit swings far wider than the run from rest: the steps chosen on that
  // run are too long for the orbit, which takes more of its own.
  DuffingOrbits o(20.0, 8);
  ASSERT_TRUE(o.so.orbit.converged) << o.so.orbit.failure;
  EXPECT_GE(o.so.stepsPerSample, 8);
  ASSERT_TRUE(o.ref.converged);
  EXPECT_LT(o.worst(), 1e-9);
}

TEST(SampledOrbit, RefusesSamplesThatDoNotDivideThePeriodAndDriftingCoordinates) {
  Duffing d;
  PeriodicOptions opt;
  opt.period = 2 * M_PI / d.W;
  Accuracy acc;
  SampledOrbit off = sampledOrbit(d.sys, acc, opt, {0.0, 0.0}, opt.period / 7.5);
  EXPECT_FALSE(off.orbit.converged);
  EXPECT_NE(off.orbit.failure.find("do not divide"), std::string::npos) << off.orbit.failure;
  opt.drift = {1.0, 0.0};
  SampledOrbit drifting = sampledOrbit(d.sys, acc, opt, {0.0, 0.0}, opt.period / 8);
  EXPECT_FALSE(drifting.orbit.converged);
  EXPECT_NE(drifting.orbit.failure.find("drift"), std::string::npos) << drifting.orbit.failure;
}

TEST(SampledOrbit, ASampleTimeBeforeTheOrbitsStartReadsTheLastSample) {
  DuffingOrbits o(6.0, 16);
  const SampledOrbit& so = o.so;
  ASSERT_TRUE(so.orbit.converged) << so.orbit.failure;
  ASSERT_EQ(so.states.size(), 16u);
  EXPECT_EQ(&so.at(-so.dt), &so.states[15]);
  EXPECT_EQ(&so.at(17 * so.dt), &so.states[1]);
}
