// Shafts through the language: the reactions and bearing lives of a spec against a hand
// calculation (statics of a simply supported shaft, ISO 281 by its formulas), rules over
// bearing lives in the search, and the diagnostics of a shaft block.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "Compiled.h"
#include "Din743Reference.h"
#include "Iso281Reference.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"

using namespace gbx;

namespace {

std::string spec(const std::string& pinion, const std::string& extra) {
  return R"(import materials;
gearbox G {
  stage hs: helical {
    )" + pinion +
         R"(  wheel.z = 71;  normal_module = 3 mm;  helix_angle = 15 deg;  face_width = 40 mm;
    material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1500 rpm;  input_torque = 300 N*m; }
  shaft input {
    material = steel_42CrMo4;
    segment 0 mm .. 60 mm { diameter = 45 mm; }
    segment 60 mm .. 290 mm { diameter = 60 mm;  bore = 20 mm; }
    segment 290 mm .. 350 mm { diameter = 45 mm; }
    gear hs.pinion at 175 mm;
    coupling at 0 mm;
    bearing A at 30 mm { kind = cylindrical_roller;  C = 112 kN;  C0 = 120 kN;  radial_stiffness = 800 N/um; }
    bearing B at 320 mm { kind = deep_groove_ball;  C = 62 kN;  C0 = 38 kN;  axial = held;  e = 0.3;  X = 0.56;  Y = 1.5; }
  }
)" + extra +
         "}\n";
}

} // namespace

TEST(ShaftSpec, ReactionsAndLivesMatchAHandCalculation) {
  Compiled c = compileFirst(spec("pinion.z = 23;", ""));
  const rt::Model& m = *c.m;
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  auto q = [&](const char* p) { return ev.quantity(p, a).mid(); };
  // The pinion's forces at its working pitch circle (no shift: the reference circle).
  const double deg = std::numbers::pi / 180, d = 23 * 3e-3 / std::cos(15 * deg),
               alphaT = std::atan(std::tan(20 * deg) / std::cos(15 * deg));
  const double Ft = 2 * 300 / d, Fr = Ft * std::tan(alphaT), Fa = Ft * std::tan(15 * deg), M = Fa * d / 2;
  // Centred between bearings 290 mm apart: half of each force, and the thrust's couple. The
  // right-hand pinion drives and turns positively: its thrust points to B (which holds it),
  // and at the pitch point, on its mate's side, that thrust relieves A and loads B.
  const double RA = std::hypot(Ft / 2, Fr / 2 - M / 0.29), RB = std::hypot(Ft / 2, Fr / 2 + M / 0.29);
  EXPECT_NEAR(q("input.A.reaction"), RA, 1e-9 * RA);
  EXPECT_NEAR(q("input.B.reaction"), RB, 1e-9 * RB);
  EXPECT_NEAR(q("input.B.axial_reaction"), Fa, 1e-9 * Fa);
  EXPECT_NEAR(q("input.A.axial_reaction"), 0, 1e-9);
  // ISO 281: A a cylindrical roller bearing (p = 10/3), B a ball bearing beyond e.
  const double hours = 3600, rev = 1500 * 60.0;
  EXPECT_NEAR(q("input.A.life") / hours, std::pow(112e3 / RA, 10.0 / 3) * 1e6 / rev, 1e-6);
  const double PB = 0.56 * RB + 1.5 * Fa;
  EXPECT_NEAR(q("input.B.life") / hours, std::pow(62e3 / PB, 3) * 1e6 / rev, 1e-6);
  EXPECT_NEAR(q("input.B.static_safety"), 38e3 / std::max(RB, 0.6 * RB + 0.5 * Fa), 1e-9);
  EXPECT_GT(q("input.deflection"), 0);
  EXPECT_GT(q("input.critical_speed"), 1500 * std::numbers::pi / 30); // a stiff shaft: well above its speed
  // Mass: three hollow and solid cylinders of 7850 kg/m^3.
  const double pi4 = std::numbers::pi / 4;
  double mass = 7850 * pi4 * (0.045 * 0.045 * 0.060 + (0.06 * 0.06 - 0.02 * 0.02) * 0.230 + 0.045 * 0.045 * 0.060);
  EXPECT_NEAR(q("input.mass"), mass, 1e-9 * mass);
}

TEST(ShaftSpec, ARuleOnABearingLifeRemovesTheDesignsThatFallShort) {
  auto count = [](const std::string& rule) {
    auto c = driver::compileText("s.gbx", spec("pinion.z in 17..30;", rule));
    EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
    std::ostringstream out, err;
    auto path = std::filesystem::temp_directory_path() / "gbx_shaft_rule.gbx";
    std::ofstream(path) << spec("pinion.z in 17..30;", rule);
    EXPECT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, out, err), 0) << err.str();
    std::filesystem::remove(path);
    std::string s = out.str();
    return std::count(s.begin(), s.end(), '\n') - 1;
  };
  long all = count(""), kept = count("  require input.B.life >= 12000 h;\n");
  EXPECT_EQ(all, 14);
  // A smaller pinion pushes harder on the same torque: the smallest ones fall short.
  EXPECT_GT(kept, 0);
  EXPECT_LT(kept, all);
}

TEST(ShaftSpec, AShaftBlockIsCheckedBeforeTheSearch) {
  auto without = [](const std::string& from, const std::string& to) {
    std::string s = spec("pinion.z = 23;", "");
    s.replace(s.find(from), from.size(), to);
    return diagnosticCodes(s);
  };
  EXPECT_EQ(without("    bearing A at 30 mm { kind = cylindrical_roller;  C = 112 kN;  C0 = 120 kN;  radial_stiffness "
                    "= 800 N/um; }\n",
                    ""),
            "E0225 ");
  EXPECT_EQ(without("gear hs.pinion", "gear hs.pinon"), "E0201 ");
  EXPECT_EQ(without("coupling at 0 mm;", "coupling at 0;"), "E0302 ");
  EXPECT_EQ(without("segment 60 mm .. 290 mm", "segment 70 mm .. 290 mm"), "E0405 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch shoulder at 100 mm { radius = 2 mm; }"), "E0405 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch shouldr at 60 mm { radius = 2 mm; }"), "E0225 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch groove at 100 mm { radius = 1 mm; }"), "E0225 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch groove at 100 mm { radius = 1 mm; depth = 30 mm; }"), "E0405 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch keyway at 100 mm { radius = 1 mm; }"), "E0224 ");
  EXPECT_EQ(without("coupling at 0 mm;", "notch hole at 100 mm { }"), "E0225 ");
  EXPECT_EQ(without("material = steel_42CrMo4;\n    segment 0 mm .. 60 mm { diameter = 45 mm; }",
                    "material = steel_18CrNiMo7_6;\n    segment 0 mm .. 60 mm { diameter = 45 mm; }\n"
                    "    notch shoulder at 60 mm { radius = 2 mm; }"),
            "E0233 ");
  EXPECT_EQ(without("coupling at 0 mm;", "strength { load_case = 3; }"), "E0405 ");
  EXPECT_EQ(without("C0 = 38 kN;", ""), "E0225 ");
  EXPECT_EQ(diagnosticCodes(spec("pinion.z = 23;", "  require input.B.lfe >= 1 h;\n")), "E0219 ");
  EXPECT_EQ(diagnosticCodes(spec("pinion.z = 23;", "  require input.D.life >= 1 h;\n")), "E0219 ");
}

// The helix hand sets the thrust's sense: a left-hand pinion loads A where a right-hand one
// loads B, and the reactions trade places.
TEST(ShaftSpec, ALeftHandPinionSwapsWhichBearingTheThrustCoupleLoads) {
  auto reactions = [](const std::string& hand) {
    Compiled c = compileFirst(spec("pinion.z = 23;  " + hand, ""));
    const rt::Model& m = *c.m;
    rt::Evaluator ev(m);
    rt::Assignment a(m);
    return std::make_pair(ev.quantity("input.A.reaction", a).mid(), ev.quantity("input.B.reaction", a).mid());
  };
  auto right = reactions(""), left = reactions("helix_hand = left;");
  EXPECT_LT(right.first, right.second);
  EXPECT_NEAR(left.first, right.second, 1e-9 * right.second);
  EXPECT_NEAR(left.second, right.first, 1e-9 * right.first);
}

// Shigley's stepped shaft (Ex. 7-3 in SI) written as a spec: its gear forces as loads, in
// the tangential plane (angle 90 deg) and the radial one (angle 0), on rigid bearings with
// shear off; the published reactions and deflections through the language.
TEST(ShaftSpec, ShigleysSteppedShaftAsASpec) {
  const char* text = R"(material shigley_steel { youngs_modulus = 206843 MPa;  poisson = 0.3;  density = 7850 kg/m^3; }
gearbox S {
  shaft counter {
    material = shigley_steel;  shear = off;  speed = 1000 rpm;
    segment 0 mm .. 31.75 mm { diameter = 25.4 mm; }
    segment 31.75 mm .. 44.45 mm { diameter = 35.56 mm; }
    segment 44.45 mm .. 88.9 mm { diameter = 41.275 mm; }
    segment 88.9 mm .. 190.5 mm { diameter = 50.8 mm; }
    segment 190.5 mm .. 247.65 mm { diameter = 41.275 mm; }
    segment 247.65 mm .. 260.35 mm { diameter = 35.56 mm; }
    segment 260.35 mm .. 292.1 mm { diameter = 25.4 mm; }
    bearing A at 19.05 mm { kind = deep_groove_ball;  C = 30 kN;  C0 = 20 kN; }
    bearing B at 273.05 mm { kind = deep_groove_ball;  C = 30 kN;  C0 = 20 kN; }
    load at 69.85 mm { radial = -876.3 N;  angle = 0 deg; }
    load at 69.85 mm { radial = 2402 N;  angle = 90 deg; }
    load at 215.9 mm { radial = -3936.7 N;  angle = 0 deg; }
    load at 215.9 mm { radial = -10813.6 N;  angle = 90 deg; }
  }
  operating { input_speed = 1000 rpm;  input_torque = 1 N*m; }
}
)";
  Compiled c = compileFirst(text);
  const rt::Model& m = *c.m;
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  auto q = [&](const char* p) { return ev.quantity(p, a).mid(); };
  // Published: A 511.5 N and 1586.7 N, B 7900 N and 3226.3 N (from lbf, 4 digits).
  EXPECT_NEAR(q("counter.A.reaction"), std::hypot(511.5, 1586.7), 2e-3 * 1667);
  EXPECT_NEAR(q("counter.B.reaction"), std::hypot(7900.0, 3226.3), 2e-3 * 8533);
  // The largest deflection lies between the gears, beyond gear 4's published 44.62 um (the
  // beam model itself meets the gears' values to 0.5 %: BeamTest).
  EXPECT_GE(q("counter.deflection") * 1e6, 44.62 * 0.995);
  EXPECT_LT(q("counter.deflection") * 1e6, 60);
}

// The shoulder at 60 mm between the coupling and the pinion, rated through the spec, against
// the independent DIN 743 reference fed by statics: the bending moment there is bearing A's
// reaction times its 30 mm lever, the torque the input's 300 N m, no axial force (B holds
// the thrust beyond the pinion); Rz 8 um where the segment gives none, d_eff the largest
// diameter (60 mm), load case 2.
TEST(ShaftSpec, AShouldersSafetiesMatchTheReferenceOnStatics) {
  std::string text = spec("pinion.z = 23;", "");
  text.replace(text.find("coupling at 0 mm;"), 17,
               "coupling at 0 mm;\n    notch shoulder at 60 mm { radius = 2 mm; }\n    strength { peak_factor = 1.5; }");
  Compiled c = compileFirst(text);
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  const double deg = std::numbers::pi / 180, d = 23 * 3e-3 / std::cos(15 * deg),
               alphaT = std::atan(std::tan(20 * deg) / std::cos(15 * deg));
  const double Ft = 2 * 300 / d, Fr = Ft * std::tan(alphaT), Fa = Ft * std::tan(15 * deg), Mc = Fa * d / 2;
  const double RA = std::hypot(Ft / 2, Fr / 2 - Mc / 0.29), M = RA * 0.030;
  gbx::test::Din743Input in;
  in.material = {1100.0, 900.0, gbx::test::Din743SteelGroup::quenched_tempered};
  in.dEff = 60.0;
  in.notch = gbx::test::Din743Shoulder{45.0, 60.0, 2.0};
  in.bendingNm = {0.0, M, 1.5 * M};
  in.torsionNm = {300.0, 0.0, 450.0};
  in.loadCase = gbx::test::Din743LoadCase::two;
  in.rzUm = 8.0;
  auto ref = gbx::test::din743Reference(in);
  // The beam's moments come from its element stiffness: round-off of about 1e-8 relative.
  EXPECT_NEAR(ev.quantity("input.fatigue_safety", a).mid(), ref.SD, 1e-7 * ref.SD);
  EXPECT_NEAR(ev.quantity("input.static_safety", a).mid(), ref.SF, 1e-7 * ref.SF);
  // The one notch's own safeties, read by its position.
  EXPECT_NEAR(ev.quantity("input.notch_at(60 mm).fatigue_safety", a).mid(), ref.SD, 1e-7 * ref.SD);
  EXPECT_NEAR(ev.quantity("input.notch_at(60 mm).static_safety", a).mid(), ref.SF, 1e-7 * ref.SF);
  EXPECT_EQ(diagnosticCodes(text + "gearbox H extends G { require input.notch_at(61 mm).fatigue_safety >= 1; }\n"), "E0219 ");
}

// Without `life.viscosity`, kappa takes the oil of the rated stage the shaft carries: nu at
// its oil temperature on the ASTM D341 line through nu40 and nu100 (written out here), at
// the bearing's speed and pitch diameter (1.4 times the shaft's 45 mm at B).
TEST(ShaftSpec, KappaTakesTheStagesOilAtItsTemperature) {
  std::string text = spec("pinion.z = 23;", "");
  text.replace(text.find("    material = steel_18CrNiMo7_6;\n  }"), 37,
               "    material = steel_18CrNiMo7_6;  accuracy = 6;\n    rating { life = 20000 h;  lubricant { viscosity_40 = 220 mm^2/s;  "
               "viscosity_100 = 19 mm^2/s;  oil_temperature = 70 degC; }  roughness { flank = 0.6 um;  root = 2 um; } }\n  }");
  Compiled c = compileFirst(text);
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  // ASTM D341: log10 log10 (nu + 0.7) = A - B log10 T, nu in mm^2/s, T in K.
  auto loglog = [](double nu) { return std::log10(std::log10(nu + 0.7)); };
  double T40 = 313.15, T100 = 373.15, T = 343.15;
  double B = (loglog(220) - loglog(19)) / (std::log10(T100) - std::log10(T40));
  double A = loglog(220) + B * std::log10(T40);
  double nu = std::pow(10.0, std::pow(10.0, A - B * std::log10(T))) - 0.7;
  double kappa = gbx::test::iso281Kappa(nu, 1500, 1.4 * 45);
  double L10h = ev.quantity("input.B.life", a).mid() / 3600;
  double P = std::pow(62e3, 1.0) / std::cbrt(L10h * 60 * 1500 / 1e6);  // back from L10 = (C/P)^3
  auto aIso = gbx::test::iso281AIso(gbx::test::Iso281BearingType::radial_ball, kappa, 0.55, 38e3 / 22, P);
  EXPECT_NEAR(ev.quantity("input.B.modified_life", a).mid() / 3600, aIso.aIso * L10h, 1e-6 * aIso.aIso * L10h);
  EXPECT_GT(aIso.aIso, 1.0);
}

TEST(ShaftSpec, TheLargestDeflectionIsTheLinesPeakNotASample) {
  // 10 kN a from A (a third of a 300 mm span) on a solid 50 mm shaft (Euler-Bernoulli): the
  // peak F a (L^2 - a^2)^(3/2) / (9 sqrt(3) L E I) stands in the longer part, sqrt((L^2 - a^2)/3)
  // from B, between the stations, not under the load.
  Compiled c = compileFirst(R"(material beam_steel { youngs_modulus = 210 GPa;  poisson = 0.3;  density = 7850 kg/m^3; }
gearbox G {
  operating { input_speed = 1500 rpm;  input_torque = 100 N*m; }
  shaft input {
    material = beam_steel;  shear = off;  speed = 1500 rpm;
    segment 0 mm .. 300 mm { diameter = 50 mm; }
    load at 100 mm { radial = 10 kN; }
    bearing A at 0 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
    bearing B at 300 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
  }
}
)");
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  const double F = 10e3, L = 0.3, aF = 0.1, E = 210e9, I = std::numbers::pi * std::pow(0.05, 4) / 64;
  const double peak = F * aF * std::pow(L * L - aF * aF, 1.5) / (9 * std::sqrt(3.0) * L * E * I);
  EXPECT_NEAR(ev.quantity("input.deflection", a).mid(), peak, 1e-9 * peak);
  std::string err;
  auto s = rt::computeShaft(ev, 0, a, &err);
  ASSERT_TRUE(s) << err;
  EXPECT_NEAR(s->deflectionAt, L - std::sqrt((L * L - aF * aF) / 3), 1e-6);
}

TEST(ShaftSpec, TheBearingHoldingTheThrustGivesItsEquivalentLoadFactors) {
  // Without e, X and Y the held bearing's life has no equivalent load: said at check time,
  // not as a rule that could not be evaluated.
  std::string s = spec("pinion.z = 23;", "  require input.deflection <= 30 um;\n");
  const std::string factors = "  e = 0.3;  X = 0.56;  Y = 1.5;";
  s.replace(s.find(factors), factors.size(), "");
  EXPECT_NE(diagnosticCodes(s).find("E0225"), std::string::npos) << diagnosticCodes(s);
  EXPECT_EQ(diagnosticCodes(spec("pinion.z = 23;", "")), "");
}
