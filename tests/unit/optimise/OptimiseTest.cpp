#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "Specs.h"

#include "driver/Driver.h"
#include "optimise/Optimise.h"
#include "model/Evaluator.h"

using namespace gbx;

namespace {

struct Setup {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model, base;
  std::unique_ptr<rt::Assignment> baseDesign;
  std::vector<rt::Design> candidates;
};

// The acceptance corpus's marine example (no strength rules), or the project's rated one.
std::string corpus(const std::string& name) {
  std::ifstream in(std::string(GBX_GOLDEN_DIR) + "/ir/" + name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Setup setup(bool rated = false) {
  Setup s;
  s.c = driver::compileText("marine_reducer.gbx", rated ? readSpec("marine_reducer.gbx") : corpus("marine_reducer.gbx"));
  s.base = std::make_unique<rt::Model>(s.c->program, s.c->program.gearboxes[0]);
  s.model = std::make_unique<rt::Model>(s.c->program, s.c->program.gearboxes[1]);
  rt::SearchOptions bo;
  bo.deferDynamics = true;
  auto br = rt::search(*s.base, bo);
  s.baseDesign = std::make_unique<rt::Assignment>(*s.base);
  s.baseDesign->choice = br.designs.at(0).choice;
  rt::SearchOptions so;
  so.deferDynamics = true;
  so.top = std::nullopt;
  auto r = rt::search(*s.model, so);
  EXPECT_TRUE(r.errors.empty());
  s.candidates = r.designs;
  return s;
}

} // namespace

TEST(Optimise, MarineOptimumIsLighterAndQuieterThanTheBaseline) {
  auto s = setup();
  ASSERT_GE(s.candidates.size(), 5u) << "tooth counts in the ratio window with feasible freedoms";
  rt::OptimiseOptions o;
  o.jobs = 2;
  auto r = rt::optimise(*s.model, s.base.get(), s.baseDesign.get(), s.candidates, o);
  ASSERT_FALSE(r.ranked.empty());
  ASSERT_EQ(r.termNames.size(), 2u);
  const auto& best = r.ranked[0];
  EXPECT_LT(best.terms[0] / r.baselineTerms[0], 1.0) << "quieter";
  EXPECT_LT(best.terms[1] / r.baselineTerms[1], 1.0) << "lighter";
  EXPECT_NEAR(r.baselineTerms[1], 4603.4, 0.5) << "the baseline's mass by the paper's formula";
  // The optimum satisfies every rule at its freedoms.
  rt::Evaluator ev(*s.model);
  rt::Assignment a(*s.model);
  a.choice = best.choice;
  for (size_t f = 0; f < best.freedoms.size(); ++f) a.box[f] = {best.freedoms[f], best.freedoms[f]};
  for (const auto& rule : s.model->gearbox.rules) {
    auto v = ev.eval(*rule.expr, a);
    EXPECT_EQ(v.truth, rt::Truth::True) << rule.text;
  }
  EXPECT_LE(ev.quantity("main.sliding_balance", a).lo, 0.001);
  // The Pareto front is non-dominated.
  for (size_t i = 1; i < r.pareto.size(); ++i) {
    EXPECT_GE(r.pareto[i].first, r.pareto[i - 1].first);
    EXPECT_LT(r.pareto[i].second, r.pareto[i - 1].second);
  }
  EXPECT_NE(r.rankCheck.find("keep their ranks"), std::string::npos) << r.rankCheck;
}

// Without strength rules the optimum (18/71 at x 0.6077/0.2508, beta 8.63 deg) overloads
// the flanks (contact safety 0.96); with them every ranked optimum meets each rule.
TEST(Optimise, MarineStrengthRulesExcludeTheOverloadedOptimum) {
  auto s = setup(true);
  rt::OptimiseOptions o;
  o.jobs = 2;
  o.rankCheck = 0;
  auto r = rt::optimise(*s.model, s.base.get(), s.baseDesign.get(), s.candidates, o);
  ASSERT_FALSE(r.ranked.empty());
  rt::Evaluator ev(*s.model);
  bool seen = false;
  for (const auto& opt : r.ranked) {
    rt::Assignment a(*s.model);
    a.choice = opt.choice;
    for (size_t f = 0; f < opt.freedoms.size(); ++f) a.box[f] = {opt.freedoms[f], opt.freedoms[f]};
    if (ev.quantity("main.pinion.z", a).lo == 18 && ev.quantity("main.wheel.z", a).lo == 71) {
      seen = true;
      // The unrated optimum's own point, rated.
      rt::Assignment old = a;
      for (size_t f = 0; f < s.model->freedoms.size(); ++f) {
        const auto& fr = s.model->freedoms[f];
        double v = fr.key == cat::Q::HelixAngle ? 8.6298 * M_PI / 180 : fr.gear == 0 ? 0.6077 : 0.2508;
        old.box[f] = {v, v};
      }
      EXPECT_NEAR(ev.quantity("main.pinion.contact_safety", old).lo, 0.958, 0.002);
    }
    EXPECT_GE(ev.quantity("main.pinion.contact_safety", a).lo, 1.0);
    EXPECT_GE(ev.quantity("main.wheel.contact_safety", a).lo, 1.0);
    EXPECT_GE(ev.quantity("main.pinion.bending_safety", a).lo, 1.4);
    EXPECT_GE(ev.quantity("main.wheel.bending_safety", a).lo, 1.4);
  }
  EXPECT_TRUE(seen) << "18/71 stays a candidate at other freedoms";
}

TEST(Optimise, ResultsDoNotDependOnJobs) {
  auto s = setup();
  s.candidates.resize(std::min<size_t>(s.candidates.size(), 4));
  rt::OptimiseOptions one, two;
  one.jobs = 1;
  two.jobs = 2;
  one.rankCheck = two.rankCheck = 0;
  auto a = rt::optimise(*s.model, s.base.get(), s.baseDesign.get(), s.candidates, one);
  auto b = rt::optimise(*s.model, s.base.get(), s.baseDesign.get(), s.candidates, two);
  ASSERT_EQ(a.ranked.size(), b.ranked.size());
  for (size_t i = 0; i < a.ranked.size(); ++i) {
    EXPECT_EQ(a.ranked[i].choice, b.ranked[i].choice);
    EXPECT_EQ(a.ranked[i].freedoms, b.ranked[i].freedoms);
    EXPECT_EQ(a.ranked[i].objective, b.ranked[i].objective);
  }
}

// relative(x) evaluates x in the baseline as the baseline names it: a variant whose own
// lets, stages or scenes sit at other positions must not read the baseline's by position.
TEST(Optimise, RelativeResolvesItsArgumentInTheBaseline) {
  auto c = driver::compileText("rel.gbx", R"(gearbox B {
  stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
  let m = s.center_distance;
}
gearbox A extends B {
  stage aux: spur { pinion.z = 20; wheel.z = 40; normal_module = 1 mm; let k = 3; }
  s.normal_module = 3 mm;
  minimize relative(m);
})");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const ir::Gearbox *a = nullptr, *b = nullptr;
  for (const auto& g : c->program.gearboxes) (g.name == "A" ? a : b) = &g;
  ASSERT_TRUE(a && b);
  ASSERT_NE(a->lets.size(), b->lets.size());  // the let `m` stands at another position in A
  rt::Model ma(c->program, *a), mb(c->program, *b);
  rt::Assignment da(ma), db(mb);
  rt::Evaluator ev(ma);
  rt::installHooks(ev, ma, &mb, &db, 1e-6);
  rt::Value v = ev.eval(*a->objectives[0].expr, da);
  ASSERT_TRUE(v.isNumber());
  EXPECT_NEAR(v.mid(), 120.0 / 80.0, 1e-12);  // centre distance 120 mm in A, 80 mm in B
}
