// The rating through the language: paper P3's mechanism on the project's turbine spec, and
// the search's handling of strength rules.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "Specs.h"

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "model/RatingRows.h"
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

// Paper P3: profile and lead modification lower K_Hbeta (the contact analysis sees 13 um of
// crowning take the peak off the loaded end of the face), so both the contact and the
// bending safety rise, on both gears.
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
  EXPECT_LT(q(ea, after, "hs.K_Hbeta"), q(eb, before, "hs.K_Hbeta") - 0.05);
  EXPECT_LT(q(ea, after, "hs.K_Fbeta"), q(eb, before, "hs.K_Fbeta"));
  EXPECT_LE(q(ea, after, "hs.K_v"), q(eb, before, "hs.K_v"));  // the tip relief replaces running-in in B_k
  for (const char* s : {"hs.pinion.contact_safety", "hs.wheel.contact_safety", "hs.pinion.bending_safety", "hs.wheel.bending_safety"})
    EXPECT_GT(q(ea, after, s), q(eb, before, s) * 1.02) << s;
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
  ASSERT_FALSE(r.designs.empty());
  rt::Evaluator ev(m);
  for (const auto& d : r.designs) {
    rt::Assignment a(m);
    a.choice = d.choice;
    EXPECT_GE(ev.quantity("s1.pinion.contact_safety", a).lo, 1.1);
  }
}

// An idler train is rated as its two spur meshes: the driver as the pinion of the first,
// the driven gear as the wheel of the second, the idler by the weaker of its two meshes
// and with Y_M = 0.7 for its teeth loaded on both flanks.
TEST(RatingSpec, IdlerIsRatedAsItsTwoMeshes) {
  const char* rating = "material = steel_18CrNiMo7_6; accuracy = 6; rating { life = 20000 h; lubricant { viscosity_40 = 220 mm^2/s; } "
                       "roughness { flank = 0.8 um; root = 3 um; } }";
  std::string text = std::string("import materials;\ngearbox I { stage t: idler { driver.z = 20; idler.z = 31; driven.z = 40; module = 3 mm; "
                                 "face_width = 30 mm; ") +
                     rating +
                     " }\n operating { input_speed = 1500 rpm; input_torque = 150 N*m; } }\n"
                     "gearbox S { stage a: spur { pinion.z = 20; wheel.z = 31; normal_module = 3 mm; face_width = 30 mm; " +
                     rating + " }\n stage b: spur { pinion.z = 31; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; " + rating +
                     " }\n operating { input_speed = 1500 rpm; input_torque = 150 N*m; } }\n";
  auto c = driver::compileText("idler.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto i = fixed(c, "I"), s = fixed(c, "S");
  rt::Evaluator ei(*i.model), es(*s.model);
  auto qi = [&](const char* p) { return ei.quantity(p, *i.design).lo; };
  auto qs = [&](const char* p) { return es.quantity(p, *s.design).lo; };
  EXPECT_DOUBLE_EQ(qi("t.driver.contact_safety"), qs("a.pinion.contact_safety"));
  EXPECT_DOUBLE_EQ(qi("t.driver.bending_safety"), qs("a.pinion.bending_safety"));
  EXPECT_DOUBLE_EQ(qi("t.driven.contact_safety"), qs("b.wheel.contact_safety"));
  EXPECT_DOUBLE_EQ(qi("t.driven.bending_safety"), qs("b.wheel.bending_safety"));
  EXPECT_DOUBLE_EQ(qi("t.idler.contact_safety"), std::min(qs("a.wheel.contact_safety"), qs("b.pinion.contact_safety")));
  EXPECT_NEAR(qi("t.idler.bending_safety"), 0.7 * std::min(qs("a.wheel.bending_safety"), qs("b.pinion.bending_safety")), 1e-12);
  EXPECT_DOUBLE_EQ(qi("t.idler.Y_M"), 0.7);
  EXPECT_DOUBLE_EQ(qi("t.driver.Y_M"), 1.0);
}

// A driver larger than its idler: the meshes are rated with the smaller gear as the pinion
// of f_sh and c', as the same pairs rated as spur stages with their pinions driving.
TEST(RatingSpec, IdlerMeshesWithTheLargerGearDriving) {
  const char* rating = "material = steel_18CrNiMo7_6; accuracy = 6; rating { life = 20000 h; lubricant { viscosity_40 = 220 mm^2/s; } "
                       "roughness { flank = 0.8 um; root = 3 um; } }";
  std::string text = std::string("import materials;\ngearbox I { stage t: idler { driver.z = 40; idler.z = 20; driven.z = 50; module = 3 mm; "
                                 "face_width = 30 mm; ") +
                     rating +
                     " }\n operating { input_speed = 1500 rpm; input_torque = 300 N*m; } }\n"
                     "gearbox S { stage a: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; " +
                     rating + " }\n operating { input_speed = 3000 rpm; input_torque = 150 N*m; } }\n";
  auto c = driver::compileText("idler2.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto i = fixed(c, "I"), s = fixed(c, "S");
  rt::Evaluator ei(*i.model), es(*s.model);
  auto qi = [&](const char* p) { return ei.quantity(p, *i.design).lo; };
  auto qs = [&](const char* p) { return es.quantity(p, *s.design).lo; };
  // The driver-idler mesh is the spur pair 20/40 driven from its wheel: same contact stress.
  EXPECT_NEAR(qi("t.driver.contact_stress"), qs("a.wheel.contact_stress"), 1e-6 * qs("a.wheel.contact_stress"));
  EXPECT_NEAR(qi("t.driver.Y_F"), qs("a.wheel.Y_F"), 1e-9);
  EXPECT_GT(qi("t.K_Hbeta"), 1.0);
}

// A planetary stage with profile shifts (NREL 5 MW stage 1: 19/17/56, 53 != 56) is concentric
// on its working centre distances: the search keeps it, and the sun-planet mesh rates as the
// commercial report does; a ring shift that leaves the planet-ring mesh 5 mm short is removed
// by the same rule. Its scuffing is the sun's mesh's; the ring's mesh is not rated for it.
TEST(RatingSpec, ShiftedPlanetaryStageIsConcentricOnWorkingCentreDistances) {
  std::string text = readSpec("nrel5mw_planetary_stage.gbx");
  auto run = [](const std::string& t, size_t* designs) {
    auto c = driver::compileText("planetary.gbx", t);
    ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
    rt::Model m(c->program, c->program.gearboxes[0]);
    auto r = rt::search(m, rt::SearchOptions{});
    ASSERT_TRUE(r.errors.empty());
    *designs = r.designs.size();
    if (r.designs.empty()) return;
    rt::Evaluator ev(m);
    rt::Assignment a(m);
    a.choice = r.designs[0].choice;
    EXPECT_NEAR(ev.quantity("ps.center_distance", a).lo, 0.863, 1e-5);
    EXPECT_NEAR(ev.quantity("ps.sun.contact_safety", a).lo, 1.37, 0.005);
    EXPECT_NEAR(ev.quantity("ps.planet.contact_safety", a).lo, 1.41, 0.01);
    EXPECT_GT(ev.quantity("ps.scuffing_safety", a).lo, 1.5);
    EXPECT_GT(ev.quantity("ps.micropitting_safety", a).lo, 1.0);
  };
  size_t kept = 0, off = 0;
  run(text, &kept);
  EXPECT_EQ(kept, 1u);
  auto at = text.find("ring.shift = -0.5013");
  ASSERT_NE(at, std::string::npos);
  run(text.replace(at, 20, "ring.shift = -0.4000"), &off);
  EXPECT_EQ(off, 0u);
}

// A stage's scuffing quantity is the worst of its meshes': the smallest safety, the largest
// temperature, each by its own mesh (an idler's two meshes differ).
TEST(RatingSpec, StageScuffingQuantitiesAreTheWorstOfTheMeshes) {
  std::string text = R"(import materials;
gearbox I { stage t: idler { driver.z = 19; idler.z = 60; driven.z = 23; module = 3 mm; face_width = 30 mm;
  material = steel_18CrNiMo7_6; accuracy = 6;
  rating { life = 20000 h; roughness { flank = 0.8 um; root = 3 um; }
           lubricant { viscosity_40 = 100 mm^2/s; viscosity_100 = 11 mm^2/s; oil_temperature = 70 degC; fzg_load_stage = 8;
                       micropitting_load_stage = 8; } } }
  operating { input_speed = 3000 rpm; input_torque = 150 N*m; } }
)";
  auto c = driver::compileText("idler3.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto i = fixed(c, "I");
  rt::Evaluator ev(*i.model);
  rt::KindContext kc{ev, 0, *i.design};
  auto meshes = rt::rating::rateStage(kc);
  ASSERT_EQ(meshes.size(), 2u);
  std::vector<rt::rating::ScuffingRating> s;
  for (const auto& m : meshes) {
    auto r = rt::rating::scuffingOf(m.input, m.rating);
    ASSERT_TRUE(r.has_value());
    s.push_back(*r);
  }
  auto q = [&](const char* p) { return ev.quantity(p, *i.design).lo; };
  EXPECT_DOUBLE_EQ(q("t.scuffing_safety"), std::min(s[0].SB, s[1].SB));
  EXPECT_DOUBLE_EQ(q("t.integral_scuffing_safety"), std::min(s[0].SintS, s[1].SintS));
  EXPECT_DOUBLE_EQ(q("t.contact_temperature"), std::max(s[0].thetaBmax, s[1].thetaBmax));
  EXPECT_DOUBLE_EQ(q("t.integral_temperature"), std::max(s[0].thetaInt, s[1].thetaInt));
  EXPECT_DOUBLE_EQ(q("t.micropitting_safety"), std::min(s[0].Slambda, s[1].Slambda));
  // The idler meshes twice: X_mp 1.5 heats both meshes' bulk above a single pair's.
  EXPECT_GT(s[0].thetaM, 343.15);
}

// ISO/TR 10300-30 Sample 1 written as docs/rating.md writes a bevel stage: the published
// values through the language (BevelRatingTest holds the rest of the table).
TEST(RatingSpec, BevelSampleOneThroughTheLanguage) {
  auto c = driver::compileText("iso_tr_10300_sample1.gbx", readSpec("iso_tr_10300_sample1.gbx"));
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto f = fixed(c, "Sample1");
  ASSERT_TRUE(f.model);
  rt::Evaluator ev(*f.model);
  auto q = [&](const char* path) {
    rt::Value v = ev.quantity(path, *f.design);
    EXPECT_TRUE(v.isPoint()) << path;
    return v.lo;
  };
  EXPECT_NEAR(q("upper.K_v"), 1.020, 5e-4);
  EXPECT_NEAR(q("upper.K_Hbeta"), 1.650, 5e-4);
  EXPECT_NEAR(q("upper.K_Halpha"), 1.161, 5e-4);
  EXPECT_NEAR(q("upper.Z_MB"), 0.916, 5e-4);
  EXPECT_NEAR(q("upper.virtual_contact_ratio"), 2.392, 5e-4);
  EXPECT_NEAR(q("upper.pinion.virtual_z"), 14.875, 5e-4);
  EXPECT_NEAR(q("upper.pinion.permissible_contact_stress") * 1e-6, 1617.8, 0.05);
  EXPECT_NEAR(q("upper.pinion.contact_safety") / 0.944, 1, 0.0015);  // Z_LS 0.12 % (BevelRatingTest)
  EXPECT_NEAR(q("upper.pinion.bending_safety") / 1.385, 1, 0.0015);
  EXPECT_NEAR(q("upper.wheel.bending_safety") / 1.328, 1, 0.0015);
  // Given beside the cone distance, the mean normal module reads as written; the rating takes
  // the cone's 3.2133 mm, which it must agree with to 0.5 %.
  EXPECT_DOUBLE_EQ(q("upper.mean_normal_module") * 1e3, 3.213);
}

// A bevel stage without a rating block computes its geometry and load; every quantity that
// then has no value is one the catalogue calls a rating quantity (so that sema asks for the
// `rating` block, the search tests it last, and a report says which rating refused it).
TEST(RatingSpec, WhatABevelStageCannotComputeUnratedIsARatingQuantity) {
  std::string text = readSpec("iso_tr_10300_sample1.gbx");
  auto from = text.find("    rating {"), to = text.find("  operating");
  ASSERT_NE(from, std::string::npos);
  text = text.substr(0, from) + "  }\n" + text.substr(to);
  text = text.substr(0, text.find("  report {")) + "}\n";
  auto c = driver::compileText("unrated.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto f = fixed(c, "Sample1");
  ASSERT_TRUE(f.model);
  rt::Evaluator ev(*f.model);
  const cat::KindSpec* bevel = nullptr;
  for (const auto* k : cat::stageKinds())
    if (k->kind == ir::StageKind::Bevel) bevel = k;
  ASSERT_TRUE(bevel);
  int rated = 0;
  auto check = [&](const cat::AttrSpec& a, const std::string& path) {
    if (a.role == cat::AttrRole::Input || a.value != cat::ValueKind::Number) return;
    bool value = ev.quantity(path, *f.design).isNumber();
    EXPECT_EQ(!value, cat::isRatingQuantity(a.key)) << path << (value ? " computes unrated but is called a rating quantity"
                                                                       : " needs the rating but is not called a rating quantity");
    rated += value ? 0 : 1;
  };
  for (const auto& a : bevel->stage) check(a, "upper." + a.name);
  for (const auto& a : bevel->gear) check(a, "upper.pinion." + a.name);
  EXPECT_GT(rated, 20);
}

namespace {

// Sample 1 with the load factors given (so each stress follows the torque alone: sigma_H as
// its square root, sigma_F in proportion) and a load spectrum inserted in its rating.
double bevelUnder(const std::string& spectrum, const char* path) {
  std::string text = readSpec("iso_tr_10300_sample1.gbx");
  const std::string at = "      life_curve = optimum;";
  auto pos = text.find(at);
  EXPECT_NE(pos, std::string::npos);
  text.insert(pos, "      dynamic_factor = 1.02;  face_load_factor = 1.65;  transverse_load_factor = 1.16;\n" + spectrum);
  auto c = driver::compileText("spectrum.gbx", text);
  EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto f = fixed(c, "Sample1");
  rt::Evaluator ev(*f.model);
  rt::Value v = ev.quantity(path, *f.design);
  EXPECT_TRUE(v.isPoint()) << path;
  return v.lo;
}

} // namespace

// A load spectrum on a bevel stage counts (ISO 6336-6's Miner sum over ISO 10300's life
// factors). One bin at 200 % for the whole life: each bin's cycles are the life's, so the
// safety is the plain rating's at twice the torque, S_H / sqrt(2) and S_F / 2 where the load
// factors are given. One bin at 100 % gives the plain safeties.
TEST(RatingSpec, ALoadSpectrumOnABevelStageCounts) {
  const std::string none, once = "      load_spectrum { bin 100% torque for 100% of life; }\n",
                          twice = "      load_spectrum { bin 200% torque for 100% of life; }\n";
  for (const char* gear : {"upper.pinion", "upper.wheel"}) {
    std::string sh = std::string(gear) + ".contact_safety", sf = std::string(gear) + ".bending_safety";
    const double plainH = bevelUnder(none, sh.c_str()), plainF = bevelUnder(none, sf.c_str());
    EXPECT_NEAR(bevelUnder(once, sh.c_str()) / plainH, 1, 1e-9) << gear;
    EXPECT_NEAR(bevelUnder(once, sf.c_str()) / plainF, 1, 1e-9) << gear;
    EXPECT_NEAR(bevelUnder(twice, sh.c_str()) / plainH, 1 / std::sqrt(2.0), 1e-9) << gear;
    EXPECT_NEAR(bevelUnder(twice, sf.c_str()) / plainF, 0.5, 1e-9) << gear;
  }
}

namespace {

// The turbine pair's K_Hbeta with the pinion crowned by `crowning` (none: the unmodified
// pair), by method B or by the contact analysis.
double turbineKHbeta(const std::string& crowning, bool contactAnalysis) {
  std::string text = readSpec("turbine_modification.gbx");
  if (!contactAnalysis) {
    const std::string line = "      face_load_factor = contact_analysis;\n";
    auto at = text.find(line);
    EXPECT_NE(at, std::string::npos);
    text.erase(at, line.size());
  }
  if (!crowning.empty()) {
    const std::string rule = "max(pinion.bending_deflection + pinion.torsion_deflection, 13 um)";
    auto at = text.find(rule);
    EXPECT_NE(at, std::string::npos);
    text.replace(at, rule.size(), crowning);
  }
  auto c = driver::compileText("turbine.gbx", text);
  EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto f = fixed(c, crowning.empty() ? "TurbineReducerUnmodified" : "TurbineReducer");
  rt::Evaluator ev(*f.model);
  return ev.quantity("hs.K_Hbeta", *f.design).mid();
}

} // namespace

// docs/rating.md quotes the turbine pair's K_Hbeta by crowning and method: the table there
// is what the build computes, to its four decimals.
TEST(RatingSpec, TheTurbineKHbetaTableInTheDocsIsWhatTheBuildComputes) {
  std::ifstream in(std::string(GBX_SOURCE_DIR) + "/docs/rating.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const std::pair<const char*, const char*> rows[] = {{"none", ""}, {"13 µm", "13 um"}, {"40 µm", "40 um"}};
  for (const auto& [label, crowning] : rows) {
    auto at = doc.find(std::string("| ") + label + " | ");
    ASSERT_NE(at, std::string::npos) << label;
    double b = 0, ca = 0;
    ASSERT_EQ(std::sscanf(doc.c_str() + at + 4 + std::strlen(label), "%lf | %lf", &b, &ca), 2) << label;
    EXPECT_NEAR(turbineKHbeta(crowning, false), b, 5e-5) << label << ", method B";
    EXPECT_NEAR(turbineKHbeta(crowning, true), ca, 5e-5) << label << ", contact analysis";
  }
}

// A rated bevel stage sized by its face width and face ratio alone: the two fix the outer cone
// distance, R_e = b / (b/R_e), and Sample 1 so written rates as Sample 1.
TEST(RatingSpec, ABevelStageSizedByFaceWidthAndFaceRatioIsRated) {
  std::string text = readSpec("iso_tr_10300_sample1.gbx");
  for (const std::string line : {"    mean_normal_module = 3.213 mm;  face_width = 25.4 mm;  spiral_angle = 35 deg;\n",
                                 "    outer_cone_distance = 93.973 mm;\n"}) {
    auto at = text.find(line);
    ASSERT_NE(at, std::string::npos) << line;
    text.erase(at, line.size());
  }
  const std::string cone = "    face_width = 25.4 mm;  face_ratio = " + fmt::format("{:.10f}", 25.4 / 93.973) + ";  spiral_angle = 35 deg;\n";
  text.insert(text.find("    pressure_angle"), cone);
  auto c = driver::compileText("sized.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  auto f = fixed(c, "Sample1");
  rt::Evaluator ev(*f.model);
  EXPECT_NEAR(ev.quantity("upper.outer_cone_distance", *f.design).mid() * 1e3, 93.973, 1e-6);
  EXPECT_NEAR(ev.quantity("upper.pinion.contact_safety", *f.design).mid() / 0.944, 1, 0.0015);
  EXPECT_NEAR(ev.quantity("upper.wheel.bending_safety", *f.design).mid() / 1.328, 1, 0.0015);
}
