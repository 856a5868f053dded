#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "Specs.h"

#include "driver/Driver.h"
#include "model/Standards.h"
#include "model/Split.h"
#include "modification/Modify.h"
#include "lower/Lower.h"
#include "model/Evaluator.h"

using namespace gbx;

namespace {

std::string spec(const std::string& name) { return readSpec(name); }

struct Fixed {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
  std::unique_ptr<rt::Assignment> design;
};

Fixed fixed(const std::string& text, const std::string& gearbox) {
  Fixed f;
  f.c = driver::compileText("t.gbx", text);
  if (!f.c->ok()) throw std::runtime_error(f.c->diags.renderText(f.c->sources));
  for (const auto& g : f.c->program.gearboxes)
    if (g.name == gearbox) {
      f.model = std::make_unique<rt::Model>(f.c->program, g);
      f.design = std::make_unique<rt::Assignment>(*f.model);
    }
  return f;
}

std::map<std::string, rt::ModOutcome> rules(const Fixed& f) {
  std::map<std::string, rt::ModOutcome> out;
  for (auto& o : rt::evaluateModify(*f.model, *f.design, f.model->gearbox.modifies.at(0))) out[o.target] = o;
  return out;
}

const double um = 1e-6, mm = 1e-3;

} // namespace

TEST(Iso1328, SinglePitchToleranceOfGradeFour) {
  // docs/dynamics.md: 0.3(m + 0.4 sqrt(d)) + 4 at grade 5, a factor sqrt(2) per grade.
  EXPECT_NEAR(rt::iso::singlePitch(4, 6.5 * mm, 218.4 * mm) / um, 5.46, 0.005);
  EXPECT_NEAR(rt::iso::singlePitch(4, 6.5 * mm, 681.6 * mm) / um, 6.42, 0.005);
  EXPECT_NEAR(rt::iso::singlePitch(5, 6.5 * mm, 218.4 * mm) / rt::iso::singlePitch(4, 6.5 * mm, 218.4 * mm), std::sqrt(2.0), 1e-12);
  // The other tolerances by hand at grade 5, m = 4 mm, d = 100 mm, b = 50 mm.
  EXPECT_NEAR(rt::iso::totalProfile(5, 4 * mm, 100 * mm) / um, 3.2 * 2 + 0.22 * 10 + 0.7, 1e-9);
  EXPECT_NEAR(rt::iso::profileForm(5, 4 * mm, 100 * mm) / um, 2.5 * 2 + 0.17 * 10 + 0.5, 1e-9);
  EXPECT_NEAR(rt::iso::profileSlope(5, 4 * mm, 100 * mm) / um, 2 * 2 + 0.14 * 10 + 0.5, 1e-9);
  EXPECT_NEAR(rt::iso::totalHelix(5, 100 * mm, 50 * mm) / um, 0.1 * 10 + 0.63 * std::sqrt(50.0) + 4.2, 1e-9);
}

TEST(Modification, TurbineReducerReproducesThePaper) {
  auto f = fixed(spec("turbine_modification.gbx"), "TurbineReducer");
  rt::Evaluator ev(*f.model);
  EXPECT_NEAR(ev.quantity("hs.pitch_line_velocity", *f.design).lo, 107.07, 0.005);
  EXPECT_NEAR(ev.quantity("hs.tangential_force", *f.design).lo, 70046, 2);
  EXPECT_NEAR(ev.quantity("hs.load_deflection", *f.design).lo / um, 19.04, 0.005);
  EXPECT_NEAR(ev.quantity("hs.pinion.torsion_deflection", *f.design).lo / um, 5.26, 0.005);
  auto r = rules(f);
  EXPECT_NEAR(*r["tip_relief"].value / um, 30.0, 1e-9);
  EXPECT_NEAR(*r["tip_relief_height"].value / mm, 0.22 * 2.25 * 6.5, 1e-9);
  EXPECT_NEAR(*r["pinion.lead_crowning"].value / um, 13.0, 1e-9);
  EXPECT_TRUE(r["pinion.thermal_lead_relief"].present);
  EXPECT_NEAR(*r["pinion.thermal_lead_relief"].value / um, 8.0, 1e-9);
  for (auto& [k, o] : r) EXPECT_TRUE(o.error.empty()) << k << ": " << o.error;
}

TEST(Modification, ThermalReliefAbsentBelowOneHundredMetresPerSecond) {
  std::string text = spec("turbine_modification.gbx");
  text.replace(text.find("9364 rpm"), 8, "8000 rpm");
  auto f = fixed(text, "TurbineReducer");
  auto r = rules(f);
  EXPECT_FALSE(r["pinion.thermal_lead_relief"].present);
  EXPECT_FALSE(r["pinion.thermal_lead_relief"].value);
  EXPECT_TRUE(r["tip_relief"].present);
}

TEST(LoadSharing, PowerSplitCheckValues) {
  auto pre = fixed(spec("power_split.gbx"), "PowerSplit");
  auto free = fixed(spec("power_split.gbx"), "PowerSplitFree");
  rt::Evaluator ep(*pre.model), ef(*free.model);
  auto p = rt::computeSplit(ep, 0, *pre.design);
  auto q = rt::computeSplit(ef, 0, *free.design);
  ASSERT_TRUE(p && q);
  EXPECT_NEAR(p->branchTorque, 29880, 5);
  EXPECT_NEAR(ep.quantity("first.wheel.d", *pre.design).lo / mm, 793.3, 0.05);
  EXPECT_NEAR(p->twist, 0.0364, 0.00005);
  EXPECT_NEAR(p->displacement / mm, 14.4, 0.05);
  EXPECT_NEAR(p->preloadDisplacement / mm, 0.039, 0.0005);
  EXPECT_NEAR(q->imbalance * 100, 1.04, 0.005);
  EXPECT_NEAR(p->imbalance * 100, 0.91, 0.006);
}

TEST(LoadSharing, TrendsHoldAtEverySweepPoint) {
  auto pre = fixed(spec("power_split.gbx"), "PowerSplit");
  auto free = fixed(spec("power_split.gbx"), "PowerSplitFree");
  auto imbalance = [&](const Fixed& f, const std::string& what, double x) {
    rt::Evaluator ev(*f.model);
    ev.setOverride(lower::quantityRef(f.model->program, f.model->gearbox, what), rt::Value::number(x));
    return ev.quantity("sharing.imbalance", *f.design).lo;
  };
  double lastFree = 0, lastPre = 0;
  for (double d = 60; d <= 130; d += 10) {
    double fr = imbalance(free, "sharing.torsion_shaft.diameter", d * mm), pr = imbalance(pre, "sharing.torsion_shaft.diameter", d * mm);
    EXPECT_GT(fr, pr) << "free installation shares worse at d = " << d;
    EXPECT_GT(fr, lastFree) << "imbalance rises with the shaft diameter";
    EXPECT_GE(pr, lastPre);
    // Free installation: Omega = dl / 2l with l proportional to 1/d^4.
    EXPECT_NEAR(fr / imbalance(free, "sharing.torsion_shaft.diameter", 100 * mm), std::pow(d / 100, 4), 1e-12);
    lastFree = fr;
    lastPre = pr;
  }
  double prevFree = 1e9, prevPre = 1e9;
  for (double P = 1; P <= 3.0001; P += 0.5) {
    double fr = imbalance(free, "power", P * 1e6), pr = imbalance(pre, "power", P * 1e6);
    EXPECT_LT(fr, prevFree) << "imbalance falls as torque rises at constant speed";
    EXPECT_LT(pr, prevPre);
    EXPECT_GT(fr, pr);
    prevFree = fr;
    prevPre = pr;
  }
}
