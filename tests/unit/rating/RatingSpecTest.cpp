// The rating through the language: seed 003's mechanism on the project's turbine spec, and
// the search's handling of strength rules.
#include <gtest/gtest.h>

#include "Specs.h"

#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "search/Search.h"

using namespace gbx;

namespace {

struct Fixed {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
  std::unique_ptr<rt::Assignment> design;
};

Fixed fixed(const std::unique_ptr<driver::Compilation>& c, const std::string& gearbox) {
  Fixed f;
  for (const auto& g : c->program.gearboxes)
    if (g.name == gearbox) {
      f.model = std::make_unique<rt::Model>(c->program, g);
      f.design = std::make_unique<rt::Assignment>(*f.model);
    }
  return f;
}

} // namespace

// Seed 003: profile and lead modification lower K_Hbeta (crowning halves the effective
// mismatch), so both the contact and the bending safety rise, on both gears.
TEST(RatingSpec, TurbineModificationLowersKHbetaAndRaisesBothSafeties) {
  auto c = driver::compileText("turbine_modification.gbx", readSpec("turbine_modification.gbx"));
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto before = fixed(c, "TurbineReducerUnmodified"), after = fixed(c, "TurbineReducer");
  ASSERT_TRUE(before.model && after.model);
  rt::Evaluator eb(*before.model), ea(*after.model);
  auto q = [](rt::Evaluator& ev, Fixed& f, const char* path) {
    rt::Value v = ev.quantity(path, *f.design);
    EXPECT_TRUE(v.isPoint()) << path;
    return v.lo;
  };
  EXPECT_LT(q(ea, after, "hs.K_Hbeta"), q(eb, before, "hs.K_Hbeta") - 0.1);
  EXPECT_LT(q(ea, after, "hs.K_Fbeta"), q(eb, before, "hs.K_Fbeta"));
  EXPECT_LE(q(ea, after, "hs.K_v"), q(eb, before, "hs.K_v"));  // the tip relief replaces running-in in B_k
  for (const char* s : {"hs.pinion.contact_safety", "hs.wheel.contact_safety", "hs.pinion.bending_safety", "hs.wheel.bending_safety"})
    EXPECT_GT(q(ea, after, s), q(eb, before, s) * 1.03) << s;
}

// A strength rule is tested after the cheap rules whatever the order written, and the funnel
// says how many candidates it removed.
TEST(RatingSpec, StrengthRulesRunLastAndShowInTheFunnel) {
  auto c = driver::compileText("s.gbx", R"(import materials;
gearbox G {
  stage s1: helical {
    pinion.z in 14..30; wheel.z in 40..90;
    normal_module = 3 mm; helix_angle = 12 deg; face_width = 40 mm;
    material = steel_18CrNiMo7_6; accuracy = 6;
    rating { life = 20000 h; lubricant { viscosity_40 = 220 mm^2/s; } roughness { flank = 0.8 um; root = 3 um; } }
    require pinion.contact_safety >= 1.1;
    require ratio in 2.9..3.1;
  }
  operating { input_speed = 1500 rpm; input_torque = 250 N*m; }
})");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::SearchOptions o;
  o.top = std::nullopt;
  auto r = rt::search(m, o);
  ASSERT_TRUE(r.errors.empty());
  int ratio = -1, strength = -1;
  for (size_t i = 0; i < r.funnel.size(); ++i) {
    if (r.funnel[i].rule.find("ratio in") != std::string::npos) ratio = static_cast<int>(i);
    if (r.funnel[i].rule.find("contact_safety") != std::string::npos) strength = static_cast<int>(i);
  }
  ASSERT_GE(ratio, 0);
  ASSERT_GE(strength, 0);
  EXPECT_LT(ratio, strength);
  EXPECT_GT(r.funnel[static_cast<size_t>(strength)].removed, 0);
  EXPECT_LT(r.funnel[static_cast<size_t>(strength)].before, r.funnel[static_cast<size_t>(ratio)].before);
  // Every design kept meets the rule.
  rt::Evaluator ev(m);
  for (const auto& d : r.designs) {
    rt::Assignment a(m);
    a.choice = d.choice;
    EXPECT_GE(ev.quantity("s1.pinion.contact_safety", a).lo, 1.1);
  }
}
