// A stage whose two gears sit on shafts takes its mesh misalignment from them: the shafts'
// deflections on the line of action across the face, iterated with the contact analysis'
// line load to a fixed point. Checked by symmetry (a centred gear on a symmetric shaft
// leans not at all; the whole gearbox mirrored end for end mirrors the separation), by the
// fixed point it states, and by what stays as it was without shafts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "Compiled.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "rating/ModelFactors.h"
#include "shaft/ShaftMesh.h"

using namespace gbx;

namespace {

struct Layout {
  std::string hand = "right";
  double gear = 180, pinionCoupling = 0, wheelCoupling = 500; // mm
  bool heldRight = true;                                      // the thrust bearing at 450 mm (else at 50)
  std::string stage = "helical";
};

std::string bearings(bool heldRight) {
  std::string held = "kind = deep_groove_ball;  C = 62 kN;  C0 = 38 kN;  axial = held;  e = 0.3;  X = 0.56;  Y = 1.5;";
  std::string free = "kind = cylindrical_roller;  C = 112 kN;  C0 = 120 kN;";
  return "    bearing L at 50 mm { " + (heldRight ? free : held) + " }\n    bearing R at 450 mm { " +
         (heldRight ? held : free) + " }\n";
}

std::string spec(const Layout& l) {
  auto mm = [](double x) { return std::to_string(x) + " mm"; };
  bool helical = l.stage == "helical";
  return R"(import materials;
gearbox G {
  stage hs: )" +
         l.stage + R"( {
    pinion.z = 23;  wheel.z = 71;  )" +
         (helical ? "normal_module = 3 mm;  helix_angle = 15 deg;  helix_hand = " + l.hand + ";"
                  : "normal_module = 3 mm;") +
         R"(  face_width = 60 mm;
    material = steel_18CrNiMo7_6;  accuracy = 6;
    rating { life = 20000 h;  face_load_factor = contact_analysis;  lubricant { viscosity_40 = 220 mm^2/s; }
             roughness { flank = 0.6 um;  root = 2 um; } }
  }
  operating { input_speed = 1500 rpm;  input_torque = 400 N*m; }
  shaft p {
    material = steel_42CrMo4;
    segment 0 mm .. 100 mm { diameter = 40 mm; }
    segment 100 mm .. 400 mm { diameter = 50 mm; }
    segment 400 mm .. 500 mm { diameter = 40 mm; }
    gear hs.pinion at )" +
         mm(l.gear) + ";\n    coupling at " + mm(l.pinionCoupling) + ";\n" + bearings(l.heldRight) + R"(  }
  shaft w {
    material = steel_42CrMo4;
    segment 0 mm .. 500 mm { diameter = 70 mm; }
    gear hs.wheel at )" +
         mm(l.gear) + ";\n    coupling at " + mm(l.wheelCoupling) + ";\n" + bearings(l.heldRight) + "  }\n}\n";
}

Layout mirrored(Layout l) {
  l.hand = l.hand == "right" ? "left" : "right";
  l.gear = 500 - l.gear;
  l.pinionCoupling = 500 - l.pinionCoupling;
  l.wheelCoupling = 500 - l.wheelCoupling;
  l.heldRight = !l.heldRight;
  return l;
}

std::vector<double> separation(const Layout& l) {
  Compiled c = compileFirst(spec(l));
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  auto ms = rt::meshShafts(c.m->gearbox, 0);
  EXPECT_TRUE(ms);
  std::string why;
  auto gap = rt::shaftSeparation(ev, a, 0, *ms, std::vector<double>(50, 1.0 / 50), 51, &why);
  EXPECT_FALSE(gap.empty()) << why;
  return gap;
}

rt::rating::FaceLoad faceLoad(const Layout& l) {
  Compiled c = compileFirst(spec(l));
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  // The rating's own load: F_t K_A K_gamma K_v, as its K_Hbeta row reads it.
  return rt::rating::contactAnalysis(ev, a, 0, 10000, 8e-6, 1.0);
}

} // namespace

// Mirroring the gearbox end for end (gear, couplings, thrust bearings, and so the helix
// hand) mirrors the shafts' separation across the face, to round-off: the thrust's sense,
// its couple, the twist and the line of action all follow the hand and the layout.
TEST(ShaftMesh, MirroringTheGearboxMirrorsTheSeparation) {
  Layout l;
  auto a = separation(l), b = separation(mirrored(l));
  ASSERT_EQ(a.size(), b.size());
  double top = *std::max_element(a.begin(), a.end());
  EXPECT_GT(top, 1e-6); // an off-centre pinion on slender shafts: microns of mismatch
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], b[b.size() - 1 - i], 1e-9 * top) << i;
  // The hand alone (the layout kept) changes the thrust's couple and so the separation.
  Layout left = l;
  left.hand = "left";
  auto c = separation(left);
  double differ = 0;
  for (size_t i = 0; i < a.size(); ++i)
    differ = std::max(differ, std::fabs(a[i] - c[i]));
  EXPECT_GT(differ, 1e-3 * top);
}

// A spur pinion centred on a symmetric shaft with its wheel centred too: the bending part is
// symmetric about the face centre, so the slope there is nil; only the twist leans.
TEST(ShaftMesh, ACentredGearOnASymmetricShaftHasNoSlope) {
  Layout l;
  l.stage = "spur";
  l.gear = 250;
  Compiled c = compileFirst(spec(l));
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  double slope = ev.quantity("p.slope_at(hs.pinion)", a).mid();
  double deflection = ev.quantity("p.deflection_at(hs.pinion)", a).mid();
  EXPECT_GT(deflection, 1e-6);
  EXPECT_NEAR(slope, 0, 1e-9 * deflection / 0.4);
  // Off centre it leans, towards the nearer bearing's side.
  l.gear = 180;
  Compiled d = compileFirst(spec(l));
  rt::Evaluator ev2(*d.m);
  rt::Assignment a2(*d.m);
  EXPECT_GT(ev2.quantity("p.slope_at(hs.pinion)", a2).mid(), 1e-3 * deflection / 0.4);
}

// The fixed point settles and says so; its K_Hbeta is the contact analysis' at the shafts'
// separation for the line load it ends with (one more step changes nothing).
TEST(ShaftMesh, TheFixedPointSettlesAndSaysSo) {
  auto f = faceLoad(Layout{});
  ASSERT_TRUE(f.failure.empty()) << f.failure;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(f.shafts, m, std::regex("shafts p, w: fixed point in ([0-9]+) iterations")))
      << f.shafts;
  EXPECT_LE(std::stoi(m[1]), 12);
  EXPECT_GT(f.KHbeta, 1.0);
  // Mirrored, the line load's peak moves to the other end of the face; K_Hbeta stays within
  // the contact lines' phase across the face (a hand's lines run the other way): 1 %.
  auto g = faceLoad(mirrored(Layout{}));
  ASSERT_TRUE(g.failure.empty()) << g.failure;
  EXPECT_NEAR(g.peak, 1 - f.peak, 1e-12);
  EXPECT_NEAR(g.KHbeta, f.KHbeta, 0.01 * f.KHbeta);
}

// With the pinion alone on a shaft, the stage keeps its given deflections: the contact
// analysis is the one it would be without any shaft.
TEST(ShaftMesh, AGearOnNoShaftKeepsTheGivenDeflections) {
  std::string with = spec(Layout{});
  with.replace(with.find("  shaft w {"), with.find("}\n}\n") - with.find("  shaft w {") + 2, "");
  with.replace(with.find("accuracy = 6;"), 13, "accuracy = 6;  pinion.bending_deflection = 7 um;");
  std::string without = with;
  without.replace(without.find("  shaft p {"), without.find("}\n}\n") - without.find("  shaft p {") + 2, "");
  auto kh = [](const std::string& text) {
    Compiled c = compileFirst(text);
    rt::Evaluator ev(*c.m);
    rt::Assignment a(*c.m);
    return rt::rating::contactAnalysis(ev, a, 0, 10000, 8e-6, 1.0);
  };
  auto a = kh(with), b = kh(without);
  ASSERT_TRUE(a.failure.empty()) << a.failure;
  EXPECT_TRUE(a.shafts.empty());
  EXPECT_EQ(a.KHbeta, b.KHbeta);
}

// A two-stage gearbox without shafts whose stages rate K_Hbeta by contact analysis: each
// stage's rule is checked on its own candidates (its contact analysis needs its own tooth
// counts only), and the search finds the designs that a whole-design check finds.
TEST(ShaftMesh, AContactAnalysisRuleOfOneStageIsCheckedOnItsOwnCandidates) {
  std::string text = R"(import materials;
gearbox G {
  stage hs: helical {
    pinion.z in 18..22;  wheel.z in 70..80;  normal_module = 2.5 mm;  helix_angle = 12 deg;  face_width = 40 mm;
    material = steel_18CrNiMo7_6;  accuracy = 6;  pinion.bending_deflection = 10 um;
    rating { life = 20000 h;  face_load_factor = contact_analysis;  lubricant { viscosity_40 = 220 mm^2/s; }
             roughness { flank = 0.6 um;  root = 2 um; } }
  }
  stage ls: helical {
    pinion.z in 17..20;  wheel.z in 60..70;  normal_module = 5 mm;  helix_angle = 10 deg;  face_width = 80 mm;
    material = steel_18CrNiMo7_6;  accuracy = 6;  pinion.bending_deflection = 10 um;
    rating { life = 20000 h;  face_load_factor = contact_analysis;  lubricant { viscosity_40 = 220 mm^2/s; }
             roughness { flank = 0.6 um;  root = 2 um; } }
  }
  operating { input_speed = 1500 rpm;  power = 30 kW; }
  require ratio == 14 +- 0.5;
  require hs.pinion.contact_safety >= 1.0;
}
)";
  Compiled c = compileFirst(text);
  EXPECT_TRUE(c.m->info(0).selfContained);
  auto path = std::filesystem::temp_directory_path() / "gbx_contact_two_stage.gbx";
  std::ofstream(path) << text;
  std::ostringstream out, err;
  ASSERT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, out, err), 0) << err.str();
  std::filesystem::remove(path);
  std::string s = out.str();
  EXPECT_GT(std::count(s.begin(), s.end(), '\n'), 1) << s << err.str();
}
