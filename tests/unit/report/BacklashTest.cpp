// The backlash of the rating table's geometry rows against the geometric reference
// (BacklashReference.h: the flanks built as involutes and turned until they touch).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "BacklashReference.h"
#include "Compiled.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "model/kinds/Geometry.h"
#include "passes/Ratings.h"

using namespace gbx;

namespace {

constexpr double kMm = 1e-3, kUm = 1e-6, kDeg = std::numbers::pi / 180;

test::BacklashCase caseB() { return {3 * kMm, 20 * kDeg, 15 * kDeg, 23, 71, 0.2, -0.1, 0, -80 * kUm, -100 * kUm}; }

void expectSame(const test::BacklashCase& c) {
  auto ref = test::referenceBacklash(c);
  auto ours = rt::geometry::backlash(c.z1, c.z2, c.mn, c.beta, c.alphaN, c.x1, c.x2, c.As1, c.As2, c.a);
  EXPECT_NEAR(ours.jt, ref.jt, 1e-9 * std::fabs(ref.jt) + 1e-13) << "a = " << c.a;
  EXPECT_NEAR(ours.jn, ref.jn, 1e-9 * std::fabs(ref.jn) + 1e-13) << "a = " << c.a;
}

} // namespace

TEST(Backlash, ClosedFormMatchesTheTurnedFlanks) {
  // A spur pair opened by 30 um, a shifted helical pair 20 um closer than its shifts'
  // distance, and a pair pushed 3.7 mm inside it (the flanks interfere: negative).
  expectSame({4 * kMm, 20 * kDeg, 0, 20, 40, 0, 0, 120.030 * kMm, -60 * kUm, -60 * kUm});
  auto b = caseB();
  b.a = test::referenceZeroBacklashCentreDistance(b) - 20 * kUm;
  expectSame(b);
  auto c = test::BacklashCase{5 * kMm, 25 * kDeg, 22 * kDeg, 17, 52, 0.45, 0.1, 185 * kMm, -120 * kUm, -120 * kUm};
  expectSame(c);
  EXPECT_LT(rt::geometry::backlash(c.z1, c.z2, c.mn, c.beta, c.alphaN, c.x1, c.x2, c.As1, c.As2, c.a).jn, 0);
}

// Through the language: the table's least backlash takes the upper allowances at a - A_a,
// its most the lower ones at a + A_a, at the distance the shifts give.
TEST(Backlash, RatingTableRowsAreTheExtremesOfTheAllowances) {
  const char* spec = R"(import materials;
gearbox G {
  stage s: helical {
    pinion.z = 23; wheel.z = 71; normal_module = 3 mm; helix_angle = 15 deg; face_width = 40 mm;
    pinion.shift = 0.2; wheel.shift = -0.1; center_distance_allowance = 20 um;
    pinion.upper_thickness_allowance = -80 um; pinion.lower_thickness_allowance = -120 um;
    wheel.upper_thickness_allowance = -100 um; wheel.lower_thickness_allowance = -140 um;
    material = steel_18CrNiMo7_6; accuracy = 6;
    rating { life = 20000 h; lubricant { viscosity_40 = 220 mm^2/s; } roughness { flank = 0.8 um; root = 3.2 um; } }
  }
  operating { input_speed = 1500 rpm; input_torque = 300 N*m; }
}
)";
  Compiled c = compileFirst(spec);
  const rt::Model& m = *c.m;
  rt::Assignment a(m);
  auto tables = rt::passes::ratings(m, a).ratings;
  ASSERT_EQ(tables.size(), 1u);
  auto row = [&](const std::string& key) {
    for (const auto& r : tables[0].rows)
      if (r.key == key) return r.si;
    ADD_FAILURE() << "no row " << key;
    return std::vector<double>{};
  };
  auto tight = caseB(), loose = caseB();
  double a0 = test::referenceZeroBacklashCentreDistance(tight);
  tight.a = a0 - 20 * kUm;
  loose.a = a0 + 20 * kUm;
  loose.As1 = -120 * kUm;
  loose.As2 = -140 * kUm;
  auto least = test::referenceBacklash(tight), most = test::referenceBacklash(loose);
  EXPECT_NEAR(row("circumferential_backlash_min").at(0), least.jt, 1e-9 * least.jt);
  EXPECT_NEAR(row("normal_backlash_min").at(0), least.jn, 1e-9 * least.jn);
  EXPECT_NEAR(row("circumferential_backlash_max").at(0), most.jt, 1e-9 * most.jt);
  EXPECT_NEAR(row("normal_backlash_max").at(0), most.jn, 1e-9 * most.jn);
  // The literals, read as exact rationals.
  EXPECT_EQ(row("upper_thickness_allowance"), (std::vector<double>{-80e-6, -100e-6}));
}

TEST(Backlash, AllowancesComeInPairsUpperAboveLowerOnARatedStage) {
  auto diag = [](const std::string& gears, bool rated = true) {
    std::string rating =
        rated ? "material = steel_18CrNiMo7_6; accuracy = 6; rating { life = 20000 h; lubricant { viscosity_40 = 220 "
                "mm^2/s; } roughness { flank = 0.8 um; root = 3.2 um; } }"
              : "";
    auto c = driver::compileText(
        "b.gbx", "import materials;\ngearbox G {\n  stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = "
                 "3 mm; face_width = 30 mm; " +
                     gears + rating + " }\n  operating { input_speed = 1500 rpm; input_torque = 100 N*m; }\n}\n");
    return c->diags.renderText(c->sources);
  };
  std::string one = diag("pinion.upper_thickness_allowance = -50 um;");
  EXPECT_NE(one.find("E0225"), std::string::npos) << one;
  EXPECT_NE(one.find("pinion.lower_thickness_allowance"), std::string::npos) << one;
  std::string inverted = diag("pinion.upper_thickness_allowance = -90 um; pinion.lower_thickness_allowance = -50 um;");
  EXPECT_NE(inverted.find("E0401"), std::string::npos) << inverted;
  const std::string both = "pinion.upper_thickness_allowance = -50 um; pinion.lower_thickness_allowance = -90 um;";
  EXPECT_EQ(diag(both).find("error"), std::string::npos) << diag(both);
  EXPECT_NE(diag(both, false).find("W0503"), std::string::npos); // nothing shows them without a rating
}
