#include <algorithm>

#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "ir/Ir.h"

using namespace gbx;

namespace {

std::unique_ptr<driver::Compilation> compile(const std::string& text) { return driver::compileText("t.gbx", text); }

std::vector<std::string> codes(const driver::Compilation& c) {
  std::vector<std::string> v;
  for (const auto& d : c.diags.sorted()) v.push_back(d.code);
  return v;
}

const ir::Gearbox& gearbox(const driver::Compilation& c, const std::string& name) {
  for (const auto& g : c.program.gearboxes)
    if (g.name == name) return g;
  throw std::runtime_error("no gearbox " + name);
}

} // namespace

TEST(Sema, PresetThenStageThenVariantOverride) {
  auto c = compile(R"(
import klingelnberg;
gearbox A { stage main: bevel with klingelnberg { pinion.z in 11..25; wheel.z in 17..46; face_ratio in 0.30..0.31; } }
gearbox B extends A { main.spiral_angle = 35 deg; }
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& a = gearbox(*c, "A").stages[0];
  EXPECT_EQ(a.find("face_ratio")->origin, "stage");
  EXPECT_EQ(a.find("face_ratio")->lo->str(), "0.3");
  EXPECT_EQ(a.find("spiral_angle")->origin, "preset klingelnberg");
  EXPECT_EQ(a.find("spiral_angle")->role, ir::Attribute::Freedom);
  // `30..35 deg`: the unit written on the right applies to the bare left bound too.
  EXPECT_EQ(a.find("spiral_angle")->lo->str(), "1/6*pi");
  EXPECT_EQ(a.find("spiral_angle")->hi->str(), "7/36*pi");
  const auto& b = gearbox(*c, "B").stages[0];
  EXPECT_EQ(b.find("spiral_angle")->role, ir::Attribute::Fixed);
  EXPECT_EQ(b.find("spiral_angle")->origin, "gearbox B");
  EXPECT_EQ(gearbox(*c, "B").baseline, "A");
}

TEST(Sema, LikeCopiesDeclarationsWithOwnVariables) {
  auto c = compile(R"(
gearbox G {
  stage upper: spur { pinion.z in 11..25; wheel.z in 17..46; require coprime(pinion.z, wheel.z); }
  stage lower like upper;
  lower.wheel.z in 20..30;
}
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  ASSERT_EQ(g.stages.size(), 2u);
  EXPECT_EQ(g.stages[1].likeOf, "upper");
  EXPECT_EQ(g.stages[1].find("wheel.z")->lo->str(), "20");
  EXPECT_EQ(g.stages[0].find("wheel.z")->lo->str(), "17");
  ASSERT_EQ(g.rules.size(), 2u);
  EXPECT_EQ(ir::print(*g.rules[1].expr), "coprime(lower.pinion.z, lower.wheel.z)");
}

TEST(Sema, ObjectivesOfAVariantReplaceTheBaselines) {
  auto c = compile(R"(
gearbox A { stage s: spur { pinion.z in 11..25; wheel.z in 17..46; } minimize s.ratio; require s.ratio > 2; }
gearbox B extends A { maximize s.ratio; require s.ratio < 3; }
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& b = gearbox(*c, "B");
  ASSERT_EQ(b.objectives.size(), 1u);
  EXPECT_FALSE(b.objectives[0].minimize);
  EXPECT_EQ(b.rules.size(), 2u);
}

TEST(Sema, ExactLiteralsAndRelativeTolerance) {
  auto c = compile(R"(
gearbox G { stage s: spur { pinion.z in 11..25; wheel.z in 17..46; } require ratio == 3.952 +- 1%; require ratio == 3.02 +- 0.02; }
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  EXPECT_EQ(ir::print(*g.rules[0].expr), "(ratio == (3.952 +- 0.01 relative))");
  const auto& tol = *g.rules[1].expr->args[1];
  EXPECT_EQ(tol.args[0]->value.rational().str(), "151/50");
  EXPECT_EQ(tol.args[1]->value.rational().str(), "1/50");
}

TEST(Sema, ForallUnrollsOverTeethAndStages) {
  auto c = compile(R"(
gearbox G {
  stage a: bevel { pinion.z in 11..25; wheel.z in 17..46; spiral_angle = 35 deg; face_ratio = 0.3; }
  stage b: bevel { pinion.z in 11..25; wheel.z in 17..46; spiral_angle = 35 deg; face_ratio = 0.3; }
  require forall z in teeth: coprime(z, 5);
  require forall s in stages: s.mmn_b in 0.10..0.14;
}
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  EXPECT_EQ(g.rules[0].expr->args.size(), 4u);
  EXPECT_EQ(ir::print(*g.rules[1].expr), "forall s in stages [(a.mmn_b in 0.1..0.14); (b.mmn_b in 0.1..0.14)]");
}

TEST(Sema, ForallOverStagesChecksEachKind) {
  auto c = compile(R"(
gearbox G {
  stage a: bevel { pinion.z in 11..25; wheel.z in 17..46; }
  stage b: spur { pinion.z in 11..25; wheel.z in 17..46; }
  require forall s in stages: s.mmn_b in 0.10..0.14;
}
)");
  EXPECT_EQ(codes(*c), std::vector<std::string>{"E0219"});
}

TEST(Sema, LetsResolveInAnyOrderAndConstSetsServeAsDomains) {
  auto c = compile(R"(
import modules;
const target = 5.8;
gearbox G {
  stage s: helical { pinion.z in 17..30; wheel.z in 40..90; helix_angle = 10 deg; normal_module in iso54_series1; }
  let err = abs(ratio - goal);
  let goal = target;
  minimize err;
}
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  const auto* m = g.stages[0].find("normal_module");
  EXPECT_EQ(m->role, ir::Attribute::Freedom);
  EXPECT_EQ(m->members.size(), 18u);
  EXPECT_EQ(m->members.front().str(), "0.001");
  EXPECT_EQ(ir::print(*g.lets[0].expr), "abs((ratio - goal))");
  EXPECT_EQ(ir::print(*g.lets[1].expr), "5.8");
}

TEST(Sema, DefaultsAreMadeExplicitByLowering) {
  auto c = compile("gearbox G { stage s: bevel { pinion.z = 14; wheel.z = 31; } }");
  ASSERT_TRUE(c->ok());
  const auto* a = gearbox(*c, "G").stages[0].find("shaft_angle");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->role, ir::Attribute::Default);
  EXPECT_EQ(ir::print(*a->value), "0.5*pi rad");
}

TEST(Sema, UnitMismatchNamesBothSides) {
  auto c = compile("gearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } operating { input_speed = 91670 N*m; } }");
  ASSERT_EQ(codes(*c), std::vector<std::string>{"E0302"});
  EXPECT_EQ(c->diags.all()[0].message,
            "unit mismatch: `input_speed` needs an angular speed, got a torque (N*m); write it in rpm (or any unit of an angular speed)");
}

TEST(Sema, AngularSpeedAcceptsFrequencyOnlyWhereDeclared) {
  auto ok = compile(R"(
gearbox G {
  stage s: planetary { sun.z = 19; planet.z = 23; ring.z = 65; planets = 3; module = 0.6 mm; }
  operating { input_speed = 600 rpm; output_torque = 3.01 N*m; }
  scene f on s {
    effects { speed_fluctuation { mean = 1800 deg/s; amplitude = 900 deg/s; frequency = 5 Hz; } }
    duration = 1 s; output plot(output_speed);
  }
}
)");
  EXPECT_TRUE(ok->ok()) << ok->diags.renderText(ok->sources);
  auto bad = compile("gearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } operating { input_speed = 50 Hz; } }");
  EXPECT_EQ(codes(*bad), std::vector<std::string>{"E0302"});
}

TEST(Sema, ModifyRulesResolveBuiltinsPerGear) {
  auto c = compile(R"(
gearbox T {
  stage hs: helical { pinion.z = 33; wheel.z = 103; normal_module = 6.5 mm; helix_angle = 10.8 deg; face_width = 225 mm;
                      accuracy = 4; pinion.bending_deflection = 2 um; }
  operating { power = 7500 kW; input_speed = 9364 rpm; }
  modify hs {
    tip_relief = round(load_deflection + mean(pitch_deviation), 10 um);
    pinion.lead_crowning = max(bending_deflection + torsion_deflection, 13 um);
  }
}
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& r = gearbox(*c, "T").modifies[0].rules;
  EXPECT_EQ(ir::print(*r[0].value), "round((hs.load_deflection + mean(hs.pitch_deviation)), 0.00001 m)");
  EXPECT_EQ(ir::print(*r[1].value), "max((hs.pinion.bending_deflection + hs.pinion.torsion_deflection), 0.000013 m)");
}

TEST(Sema, ImportsAreLoadedOnceAndResolved) {
  auto c = compile("import materials; import materials; gearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; material = steel_42CrMo4; } }");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  EXPECT_EQ(c->sources.size(), 2);
  ASSERT_TRUE(c->program.findMaterial("steel_42CrMo4"));
  EXPECT_EQ(c->program.findMaterial("steel_20CrMnMo")->properties.size(), 7u);
}

TEST(Sema, ErrorsAreCollectedNotStoppedAtTheFirst) {
  auto c = compile(R"(
gearbox G {
  stage s: spur { pinion.z = 0; wheel.z = 2.5; normal_module = 3 s; face = 2 mm; }
  require s.ratio == 2 +- 1 mm;
  minimize zzz;
}
)");
  auto v = codes(*c);
  for (const char* want : {"E0402", "E0403", "E0302", "E0211", "E0201"})
    EXPECT_NE(std::find(v.begin(), v.end(), want), v.end()) << want;
}

TEST(Sema, PercentagesStayRelativeThroughConsts) {
  auto c = compile(R"(
const tol = 1%;
gearbox G { stage s: spur { pinion.z in 11..25; wheel.z in 17..46; }
  require ratio == 3.952 +- tol; require ratio == 3.952 +- 2 * tol; require ratio == 3.952 +- 0.01; }
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  EXPECT_EQ(ir::print(*g.rules[0].expr), "(ratio == (3.952 +- 0.01 relative))");
  EXPECT_EQ(ir::print(*g.rules[1].expr), "(ratio == (3.952 +- 0.02 relative))");
  EXPECT_EQ(ir::print(*g.rules[2].expr), "(ratio == (3.952 +- 0.01))");
}

// `80 degC` is an absolute temperature (its unit's zero is added), `-10 degC` ten degrees
// below that zero; a compound unit (`degC/s`) measures differences.
TEST(Sema, CelsiusLiteralsAreAbsoluteTemperatures) {
  auto c = compile(R"(
import materials;
gearbox G {
  stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; material = steel_18CrNiMo7_6; accuracy = 6;
    rating { life = 1000 h; roughness { flank = 0.8 um; root = 3 um; }
             lubricant { viscosity_40 = 220 mm^2/s; viscosity_100 = 19 mm^2/s; oil_temperature = 80 degC; fzg_load_stage = 12; } } }
  operating { input_speed = 1500 rpm; input_torque = 100 N*m; }
  require s.contact_temperature < 150 degC;
  require s.bulk_temperature > -10 degC;
  require s.bulk_temperature < 400 K;
}
)");
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  const auto& g = gearbox(*c, "G");
  EXPECT_EQ(g.rules[0].expr->args[1]->value.rational().str(), "8463/20");  // 423.15 K
  EXPECT_EQ(g.rules[1].expr->args[1]->value.rational().str(), "5263/20");  // 263.15 K
  EXPECT_EQ(g.rules[2].expr->args[1]->value.rational().str(), "400");
  auto bad = compile("gearbox G { stage s: spur { pinion.z = 20; wheel.z = 40; } require s.pinion.z > 3 degC; }");
  EXPECT_FALSE(bad->ok());
  // relative() of an absolute temperature is refused; of a difference it is a plain ratio.
  std::string base = "import materials;\ngearbox A { stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; "
                     "material = steel_18CrNiMo7_6; accuracy = 6; rating { life = 1000 h; roughness { flank = 0.8 um; root = 3 um; } "
                     "lubricant { viscosity_40 = 220 mm^2/s; viscosity_100 = 19 mm^2/s; oil_temperature = 80 degC; fzg_load_stage = 12; } } }"
                     " operating { input_speed = 1500 rpm; input_torque = 100 N*m; } }\n";
  auto ratio = compile(base + "gearbox B extends A { report { columns relative(s.contact_temperature); } }");
  EXPECT_EQ(codes(*ratio), std::vector<std::string>{"E0302"});
  auto rise = compile(base + "gearbox B extends A { report { columns relative(s.contact_temperature - 80 degC); } }");
  EXPECT_TRUE(rise->ok()) << rise->diags.renderText(rise->sources);
}

// A planetary gear's mass is given or follows from its geometry and density (the ring's from
// its rim): without those, the spec is refused before the search, not answered with n/a.
TEST(Sema, PlanetaryGearMassNeedsDensityAndTheRingItsRim) {
  auto spec = [](const std::string& stage, const std::string& objective) {
    return "import materials;\ngearbox P {\n  stage ps: planetary { sun.z = 18; planet.z = 27; ring.z = 72; planets = 3; module = 3 mm; "
           "face_width = 40 mm; " +
           stage + " }\n  minimize " + objective + ";\n}\n";
  };
  EXPECT_EQ(codes(*compile(spec("", "ps.sun.mass"))), std::vector<std::string>{"E0233"});
  EXPECT_TRUE(compile(spec("sun.mass = 2 kg;", "ps.sun.mass"))->ok());
  EXPECT_TRUE(compile(spec("material = steel_18CrNiMo7_6;", "ps.sun.mass + ps.planet.mass"))->ok());
  auto ring = compile(spec("material = steel_18CrNiMo7_6;", "ps.ring.mass"));
  EXPECT_EQ(codes(*ring), std::vector<std::string>{"E0233"});
  EXPECT_NE(ring->diags.renderText(ring->sources).find("ring.rim_thickness"), std::string::npos);
  EXPECT_TRUE(compile(spec("material = steel_18CrNiMo7_6; ring.rim_thickness = 12 mm;", "ps.ring.mass"))->ok());
}
