// Bevel gears on shafts: the mean-point forces of a spiral bevel pair (ISO/TR 10300-30 Sample
// 1's geometry) against the textbook formulas, the sense of the spiral's thrust from the hand
// and the rotation seen from the gear's back, and the reactions of a straddle-mounted pinion
// against statics.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "Compiled.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"

using namespace gbx;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Sample 1's pair, 300 N m on the pinion at 1200 rpm; the pinion centred between two rigid
// bearings 200 mm apart (B holds the thrust), the wheel likewise on its own shaft.
std::string spec(const std::string& hand, const std::string& pinionApex, const std::string& wheelApex) {
  return R"(import materials;
gearbox G {
  stage upper: bevel {
    pinion.z = 14;  wheel.z = 39;
    mean_normal_module = 3.213 mm;  face_width = 25.4 mm;  spiral_angle = 35 deg;  outer_cone_distance = 93.973 mm;
    pressure_angle = 20 deg;  spiral_hand = )" +
         hand + R"(;  material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1200 rpm;  input_torque = 300 N*m; }
  shaft input {
    material = steel_42CrMo4;
    segment 0 mm .. 200 mm { diameter = 50 mm; }
    gear upper.pinion at 100 mm { apex = )" +
         pinionApex + R"(; }
    bearing A at 0 mm { kind = cylindrical_roller;  C = 100 kN;  C0 = 100 kN; }
    bearing B at 200 mm { kind = deep_groove_ball;  C = 60 kN;  C0 = 40 kN;  axial = held;  e = 0.3;  X = 0.56;  Y = 1.5; }
  }
  shaft output_shaft {
    material = steel_42CrMo4;
    segment 0 mm .. 200 mm { diameter = 70 mm; }
    gear upper.wheel at 100 mm { apex = )" +
         wheelApex + R"(; }
    bearing C at 0 mm { kind = cylindrical_roller;  C = 100 kN;  C0 = 100 kN; }
    bearing D at 200 mm { kind = deep_groove_ball;  C = 60 kN;  C0 = 40 kN;  axial = held;  e = 0.3;  X = 0.56;  Y = 1.5; }
  }
}
)";
}

struct Forces {
  double Ft, Fa, Fr, rm; // Fa away from the apex, Fr away from the mate
};

// The pinion's forces: F_mt = 2 T / d_m; s = +1 where hand and rotation seen from the back agree.
Forces pinionForces(const rt::Evaluator& ev, const rt::Assignment& a, double s) {
  const double dm = ev.quantity("upper.pinion.mean_diameter", a).mid();
  const double delta = std::atan(14.0 / 39.0), beta = 35 * kDeg, alpha = 20 * kDeg;
  const double Ft = 2 * 300 / dm;
  return {Ft, Ft * (std::tan(alpha) * std::sin(delta) + s * std::sin(beta) * std::cos(delta)) / std::cos(beta),
          Ft * (std::tan(alpha) * std::cos(delta) - s * std::sin(beta) * std::sin(delta)) / std::cos(beta), dm / 2};
}

} // namespace

TEST(ShaftBevel, APinionsReactionsMatchStaticsForEitherHand) {
  // The input turns positively about +x; with its apex to the right its back faces -x, from
  // where it turns clockwise: a right-hand pinion agrees (thrust away from the apex, towards
  // -x: onto A's side), a left-hand one does not (thrust towards the apex, +x).
  for (const char* hand : {"right", "left"}) {
    Compiled c = compileFirst(spec(hand, "right", "left"));
    rt::Evaluator ev(*c.m);
    rt::Assignment a(*c.m);
    auto q = [&](const char* p) { return ev.quantity(p, a).mid(); };
    const double s = std::string(hand) == "right" ? 1 : -1;
    Forces f = pinionForces(ev, a, s);
    // The thrust along x: -Fa (away from the apex at +x); its couple at the pitch point.
    const double Fx = -f.Fa, M = Fx * f.rm, L = 0.2;
    const double RA = std::hypot(f.Ft / 2, f.Fr / 2 - M / L), RB = std::hypot(f.Ft / 2, f.Fr / 2 + M / L);
    EXPECT_NEAR(q("input.A.reaction"), RA, 1e-9 * RA) << hand;
    EXPECT_NEAR(q("input.B.reaction"), RB, 1e-9 * RB) << hand;
    EXPECT_NEAR(q("input.B.axial_reaction"), std::fabs(f.Fa), 1e-9 * f.Ft) << hand;
  }
  // The textbook's sense: a right-hand pinion turning clockwise seen from its back pushes away
  // from its apex, harder than a left-hand one pulls.
  Compiled c = compileFirst(spec("right", "right", "left"));
  rt::Evaluator ev(*c.m);
  rt::Assignment a(*c.m);
  EXPECT_GT(pinionForces(ev, a, 1).Fa, 0);
  EXPECT_LT(pinionForces(ev, a, -1).Fa, 0);
}

TEST(ShaftBevel, TheWheelsThrustIsThePinionsRadialForce) {
  // At a 90 deg shaft angle the wheel's axial force is the pinion's radial force and its
  // radial force the pinion's axial one; whichever way the wheel's shaft runs.
  for (const char* hand : {"right", "left"})
    for (const char* wheelApex : {"left", "right"}) {
      Compiled c = compileFirst(spec(hand, "right", wheelApex));
      rt::Evaluator ev(*c.m);
      rt::Assignment a(*c.m);
      auto q = [&](const char* p) { return ev.quantity(p, a).mid(); };
      Forces f = pinionForces(ev, a, std::string(hand) == "right" ? 1 : -1);
      EXPECT_NEAR(q("output_shaft.D.axial_reaction"), std::fabs(f.Fr), 1e-9 * f.Ft) << hand << " " << wheelApex;
      EXPECT_NEAR(q("input.B.axial_reaction"), std::fabs(f.Fa), 1e-9 * f.Ft);
      // Both bearings of the wheel's shaft carry the tangential force and the pinion's thrust.
      const double Ft2 = f.Ft, Fr2 = f.Fa, dm2 = f.rm * 2 * 39.0 / 14.0;
      const double M = f.Fr * dm2 / 2, L = 0.2;
      const double lo = std::hypot(Ft2 / 2, std::fabs(Fr2) / 2 - M / L),
                   hi = std::hypot(Ft2 / 2, std::fabs(Fr2) / 2 + M / L);
      double C = q("output_shaft.C.reaction"), D = q("output_shaft.D.reaction");
      EXPECT_NEAR(std::min(C, D), std::min(lo, hi), 1e-6 * Ft2) << hand << " " << wheelApex;
      EXPECT_NEAR(std::max(C, D), std::max(lo, hi), 1e-6 * Ft2) << hand << " " << wheelApex;
    }
}

TEST(ShaftBevel, ABevelGearOnAShaftSaysWhereItsApexPoints) {
  std::string s = spec("right", "right", "left");
  EXPECT_EQ(diagnosticCodes(s), "");
  std::string noApex = s;
  noApex.replace(noApex.find(" { apex = right; }"), 18, ";");
  EXPECT_NE(diagnosticCodes(noApex).find("E0225"), std::string::npos) << diagnosticCodes(noApex);
  std::string noHand = s;
  noHand.replace(noHand.find("spiral_hand = right;"), 20, "");
  EXPECT_NE(diagnosticCodes(noHand).find("E0225"), std::string::npos) << diagnosticCodes(noHand);
}

TEST(ShaftBevel, ASearchedSpiralAngleSolvesTheShaftAtEachValue) {
  // The shaft's cache is keyed on everything a bevel gear's forces read: each spiral angle
  // of a set gives the thrust that angle alone gives.
  auto axial = [](const std::string& text) {
    Compiled c = compileFirst(text);
    rt::Evaluator ev(*c.m);
    rt::Assignment a(*c.m);
    std::vector<double> out;
    if (c.m->slots.empty()) return std::vector<double>{ev.quantity("input.B.axial_reaction", a).mid()};
    for (int k = 0; k < static_cast<int>(c.m->slots[0].values.size()); ++k) {
      a.choice[0] = k;
      out.push_back(ev.quantity("input.B.axial_reaction", a).mid());
    }
    return out;
  };
  std::string base = spec("right", "right", "left"), both = base;
  both.replace(both.find("spiral_angle = 35 deg;"), 22, "spiral_angle in {20 deg, 35 deg};");
  std::string at20 = base;
  at20.replace(at20.find("spiral_angle = 35 deg;"), 22, "spiral_angle = 20 deg;");
  auto v = axial(both);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], axial(at20)[0], 1e-9 * v[0]);
  EXPECT_NEAR(v[1], axial(base)[0], 1e-9 * v[1]);
  EXPECT_GT(std::fabs(v[1] - v[0]), 100);
}

TEST(ShaftBevel, ABevelPairTurnsTheWheelShaftAsItsApexesPoint) {
  // The wheel turns about its own +x with the pinion's sense times -a1 a2; a later stage's
  // gears follow the wheel's shaft.
  for (auto [pa, wa, sense] :
       {std::tuple{"right", "left", 1.0}, {"right", "right", -1.0}, {"left", "left", -1.0}, {"left", "right", 1.0}}) {
    Compiled c = compileFirst(spec("right", pa, wa));
    EXPECT_EQ(rt::senseOf(*c.m, 0, true), 1.0);
    EXPECT_EQ(rt::senseOf(*c.m, 0, false), sense) << pa << " " << wa;
  }
}
