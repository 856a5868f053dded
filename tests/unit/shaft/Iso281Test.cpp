// Bearing life against ISO 281's published check values and the independent reference
// (Iso281Reference.h): L10, L10h, a1, kappa and a_ISO across its three kappa bands.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "Iso281Reference.h"
#include "shaft/Iso281.h"

using namespace gbx::rt::shaft;
using gbx::test::Iso281BearingType;

namespace {
constexpr double kRpm = std::numbers::pi / 30;
}

TEST(Iso281, DeepGrooveBall6309LivesAsPublished) {
  BearingData b;
  b.C = 55.3e3;
  b.C0 = 31e3;
  auto at10kN = life(b, {10e3, 0, 3000 * kRpm}, {});
  EXPECT_NEAR(at10kN.L10, 169.0, 0.5);
  EXPECT_NEAR(at10kN.L10h, 940, 940 * 0.005);
  auto at4kN = life(b, {4e3, 0, 1800 * kRpm}, {});
  EXPECT_NEAR(at4kN.L10h, 24500, 24500 * 0.005);
  EXPECT_NEAR(at4kN.L10h,
              gbx::test::iso281L10h(gbx::test::iso281L10(55.3e3, 4e3, Iso281BearingType::radial_ball), 1800),
              1e-9 * 24500);
}

TEST(Iso281, ReliabilityFactorFollowsTheTable) {
  const double table[][2] = {{0.90, 1}, {0.95, 0.64}, {0.96, 0.55}, {0.97, 0.47}, {0.98, 0.37}, {0.99, 0.25}};
  for (const auto& [r, a1] : table)
    EXPECT_NEAR(lifeFactorA1(r), a1, 0.005) << r;
}

TEST(Iso281, LifeModificationMatchesTheReferenceAndIsContinuousAtTheBandEdges) {
  for (bool ball : {true, false}) {
    auto type = ball ? Iso281BearingType::radial_ball : Iso281BearingType::radial_roller;
    for (double kappa : {0.15, 0.3, 0.5, 0.9, 1.5, 3.0})
      for (double x : {0.05, 0.3, 1.0, 3.0}) {
        double ref = gbx::test::iso281AIso(type, kappa, 1.0, x, 1.0).aIso;
        EXPECT_NEAR(lifeModification(ball, kappa, x), ref, 1e-9 * ref) << ball << " " << kappa << " " << x;
      }
    // Continuous at kappa = 0.4 and 1 (the published coefficients are rounded: 1e-3).
    for (double edge : {0.4, 1.0})
      for (double x : {0.05, 0.5, 1.0}) {
        double below = lifeModification(ball, edge * (1 - 1e-12), x), above = lifeModification(ball, edge, x);
        EXPECT_NEAR(below, above, 1e-3 * above) << ball << " " << edge << " " << x;
      }
  }
}

TEST(Iso281, KappaFromTheRatedViscosityInBothSpeedBands) {
  for (double rpm : {500.0, 1500.0, 3000.0}) {
    double nu1 = ratedViscosity(rpm * kRpm, 0.072) * 1e6;
    EXPECT_NEAR(nu1, gbx::test::iso281Nu1(rpm, 72), 1e-9 * nu1) << rpm;
  }
  BearingData b;
  b.C = 55.3e3;
  b.C0 = 31e3;
  b.pitchDiameter = 0.072;
  LifeSettings s;
  s.viscosity = 68e-6;
  s.contamination = 0.5;
  auto l = life(b, {4e3, 0, 1800 * kRpm}, s);
  EXPECT_NEAR(l.kappa, 68 / gbx::test::iso281Nu1(1800, 72), 1e-9);
  EXPECT_NEAR(l.Lnmh, l.a1 * l.aIso * l.L10h, 1e-9 * l.Lnmh);
  EXPECT_GT(l.aIso, 1); // a clean, well-lubricated bearing outlives L10
}

TEST(Iso281, AxialLoadNeedsTheCatalogueFactorsAndARollerRefusesIt) {
  BearingData b;
  b.C = 55.3e3;
  b.C0 = 31e3;
  EXPECT_THROW(life(b, {4e3, 2e3, 100}, {}), std::invalid_argument);
  b.e = 0.3;
  b.X = 0.56;
  b.Y = 1.5;
  auto l = life(b, {4e3, 2e3, 100}, {});
  EXPECT_DOUBLE_EQ(l.P, 0.56 * 4e3 + 1.5 * 2e3);
  EXPECT_DOUBLE_EQ(l.P0, std::max(4e3, 0.6 * 4e3 + 0.5 * 2e3));
  EXPECT_DOUBLE_EQ(life(b, {10e3, 2e3, 100}, {}).P, 10e3); // F_a/F_r 0.2 <= e
  b.kind = BearingKind::CylindricalRoller;
  EXPECT_THROW(life(b, {4e3, 2e3, 100}, {}), std::invalid_argument);
}
