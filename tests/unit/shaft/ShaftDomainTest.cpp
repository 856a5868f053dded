// A shaft's settings searched like a stage's attributes: a continuous range decided at each
// design (the diameter where a deflection rule binds, against the closed form of a centred
// load on a simply supported Euler-Bernoulli beam), a set searched with the tooth counts, and
// the diagnostics of a domain a shaft setting cannot take.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "Compiled.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"

using namespace gbx;

namespace {

// A spur pinion centred on a 200 mm shaft between two rigid bearings, 30 kW at 1500 rpm.
std::string spec(const std::string& diameter, const std::string& extra) {
  return R"(import materials;
gearbox G {
  stage hs: spur {
    pinion.z = 20;  wheel.z = 60;  normal_module = 3 mm;  face_width = 40 mm;
    material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1500 rpm;  power = 30 kW; }
  shaft input {
    material = steel_42CrMo4;
    shear = off;
    segment 0 mm .. 200 mm { )" +
         diameter + R"( }
    gear hs.pinion at 100 mm;
    bearing A at 0 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
    bearing B at 200 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
  }
)" + extra +
         "}\n";
}

// The mesh force on the pinion (no shift: the reference circle), N.
double meshForce() {
  const double T = 30e3 / (1500 * std::numbers::pi / 30), Ft = 2 * T / 0.060;
  return Ft / std::cos(20 * std::numbers::pi / 180);
}

// The centre deflection of the beam: F L^3 / (48 E I), I = pi d^4 / 64.
double centreDeflection(double d) {
  const double I = std::numbers::pi * std::pow(d, 4) / 64;
  return meshForce() * std::pow(0.2, 3) / (48 * 206e9 * I);
}

// `gbxc solve` as CSV: the rows below the header, split at commas.
std::vector<std::vector<std::string>> rows(const std::string& text) {
  auto path = std::filesystem::temp_directory_path() / "gbx_shaft_domain.gbx";
  std::ofstream(path) << text;
  std::ostringstream out, err;
  int status = driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, out, err);
  std::filesystem::remove(path);
  EXPECT_EQ(status, 0) << err.str();
  std::vector<std::vector<std::string>> v;
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    v.emplace_back();
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');)
      v.back().push_back(c);
  }
  return v;
}

} // namespace

TEST(ShaftDomain, TheModelReadsAFreedomsPointFromTheAssignment) {
  Compiled c = compileFirst(spec("diameter in 30 mm .. 60 mm;", ""));
  const rt::Model& m = *c.m;
  ASSERT_EQ(m.freedoms.size(), 1u);
  EXPECT_EQ(m.freedoms[0].path, "input.segment(0..200 mm).diameter");
  EXPECT_TRUE(m.shaftFreedoms);
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  // Over the whole range the shaft has no one deflection.
  EXPECT_FALSE(ev.quantity("input.deflection", a).isNumber());
  for (double d : {0.035, 0.05}) {
    a.box[0] = {d, d};
    EXPECT_NEAR(ev.quantity("input.deflection", a).mid(), centreDeflection(d), 1e-9 * centreDeflection(d));
  }
}

TEST(ShaftDomain, ARangeIsDecidedWhereTheDeflectionRuleBinds) {
  auto v = rows(spec("diameter in 30 mm .. 60 mm;", "  require input.deflection <= 20 um;\n  minimize input.mass;\n"
                                                    "  report { columns input.deflection; }\n"));
  ASSERT_EQ(v.size(), 1u);
  // The lightest shaft whose centre deflection is 20 um, rounded up to the printed digits.
  const double exact = std::pow(64 * meshForce() * 0.008 / (48 * 206e9 * std::numbers::pi * 20e-6), 0.25);
  const double decided = std::stod(v[0][4]) * 1e-3;
  EXPECT_GE(decided, exact - 1e-12);
  EXPECT_LE(decided, exact + 1.0001e-7);
  EXPECT_LE(std::stod(v[0][6]), 20.0);
}

TEST(ShaftDomain, ASetIsSearchedWithTheToothCounts) {
  auto v = rows(
      spec("diameter in {40 mm, 45 mm, 50 mm, 55 mm};",
           "  require input.deflection <= 20 um;\n  minimize input.mass;\n  report { columns input.deflection; }\n"));
  // 40 and 45 mm bend beyond 20 um (the closed form says so too): 50 and 55 mm are kept, lighter first.
  EXPECT_GT(centreDeflection(0.045), 20e-6);
  EXPECT_LT(centreDeflection(0.050), 20e-6);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0][4], "50");
  EXPECT_EQ(v[1][4], "55");
  EXPECT_NEAR(std::stod(v[0][6]) * 1e-6, centreDeflection(0.05), 1e-9 * 20e-6);
}

TEST(ShaftDomain, ADomainASettingCannotTakeIsRefused) {
  // A word-valued setting takes one value.
  std::string kinds = spec("diameter = 50 mm;", "");
  kinds.replace(kinds.find("kind = deep_groove_ball;"), 24, "kind in {deep_groove_ball};");
  EXPECT_NE(diagnosticCodes(kinds).find("E0110"), std::string::npos) << diagnosticCodes(kinds);
  // Bounds in the setting's unit.
  EXPECT_NE(diagnosticCodes(spec("diameter in 30 .. 60;", "")).find("E0302"), std::string::npos);
  EXPECT_NE(diagnosticCodes(spec("diameter in 60 mm .. 30 mm;", "")).find("E0401"), std::string::npos);
  EXPECT_NE(diagnosticCodes(spec("diameter in {};", "")).find("E0", 0), std::string::npos);
  EXPECT_EQ(diagnosticCodes(spec("diameter in 30 mm .. 60 mm;", "")), "");
}

TEST(ShaftDomain, EveryNumericSettingOfAShaftMayBeSearched) {
  // At the shaft's own level too, and a bearing's rating with its unit (N), not as a count.
  std::string s = spec("diameter = 50 mm;", "  require input.deflection <= 30 um;\n");
  const std::string shear = "    shear = off;";
  s.replace(s.find(shear), shear.size(), shear + "\n    heat_treatment_diameter in 40 mm .. 60 mm;");
  EXPECT_EQ(diagnosticCodes(s), "");
  s.replace(s.find("C = 50 kN;"), 10, "C in {40 kN, 50 kN};");
  auto path = std::filesystem::temp_directory_path() / "gbx_shaft_domain_c.gbx";
  std::ofstream(path) << s;
  std::ostringstream out, err;
  EXPECT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, out, err), 0) << err.str();
  std::filesystem::remove(path);
  EXPECT_NE(out.str().find("input.A.C [N]"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("input.heat_treatment_diameter [mm]"), std::string::npos) << out.str();
}

TEST(ShaftDomain, ARangeNeedsAStageToBeSearchedWith) {
  std::string s = R"(import materials;
gearbox G {
  operating { input_speed = 1500 rpm;  input_torque = 300 N*m; }
  shaft input {
    material = steel_42CrMo4;  speed = 1500 rpm;
    segment 0 mm .. 200 mm { diameter in 40 mm .. 60 mm; }
    bearing A at 0 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
    bearing B at 200 mm { kind = deep_groove_ball;  C = 50 kN;  C0 = 30 kN; }
  }
}
)";
  EXPECT_NE(diagnosticCodes(s).find("E0235"), std::string::npos) << diagnosticCodes(s);
}

TEST(ShaftDomain, InterchangeableStagesLeaveAShaftsSetAlone) {
  std::string s = spec("diameter in {40 mm, 50 mm};", "");
  s.replace(s.find("  operating"), 0,
            "  stage b: spur { pinion.z = 20;  wheel.z = 60;  normal_module = 3 mm;  face_width = 40 mm; }\n"
            "  interchangeable hs, b;\n");
  auto v = rows(s);
  EXPECT_EQ(v.size(), 2u);
}
