// The shaft's beam model against published and closed-form values: Shigley's stepped shaft
// (Ex. 7-3 in SI), a point load on rigid and on elastic supports with and without shear,
// torsion across a face, and Friswell's two-disk rotor at standstill.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shaft/Beam.h"

using namespace gbx::rt::shaft;

namespace {

constexpr double kMm = 1e-3, kUm = 1e-6;

// Shigley Table 7-3: seven steps, bearings at 19.05 and 273.05 mm, two spur gears.
Model shigley(bool shear) {
  Model m;
  const double steps[][3] = {{0, 31.75, 25.4},     {31.75, 44.45, 35.56},   {44.45, 88.9, 41.275},
                             {88.9, 190.5, 50.8},  {190.5, 247.65, 41.275}, {247.65, 260.35, 35.56},
                             {260.35, 292.1, 25.4}};
  for (const auto& s : steps)
    m.sections.push_back({s[0] * kMm, s[1] * kMm, s[2] * kMm, 0});
  m.material.E = 206843e6;
  m.material.G = m.material.E / 2.6;
  m.bearings = {{"A", 19.05 * kMm}, {"B", 273.05 * kMm}};
  // Tangential forces in plane z oppose each other; radial forces in plane y act alike.
  m.loads = {{69.85 * kMm, -876.3, 2402.0}, {215.9 * kMm, -3936.7, -10813.6}};
  m.shear = shear;
  m.elements = 200;
  return m;
}

Model pointLoad(bool shear, double kA = kRigid, double kB = kRigid) {
  Model m;
  m.sections = {{0, 300 * kMm, 50 * kMm, 0}};
  m.material.E = 210e9;
  m.material.G = 210e9 / 2.6;
  m.bearings = {{"A", 0, kA}, {"B", 300 * kMm, kB}};
  m.loads = {{100 * kMm, -10000}};
  m.shear = shear;
  return m;
}

} // namespace

TEST(Beam, ShigleyStepsGiveThePublishedReactionsDeflectionsAndSlopes) {
  Solution s = solve(shigley(false));
  // Reactions: A 511.5 N tangential, 1586.7 N radial; B 7900 N, 3226.3 N as published (from
  // lbf, 4 digits), and exactly the lever rule's.
  EXPECT_NEAR(s.reactions[0].Fz, 511.5, 511.5 * 1e-3);
  EXPECT_NEAR(s.reactions[0].Fy, 1586.7, 1586.7 * 1e-3);
  EXPECT_NEAR(s.reactions[1].Fz, 7900.0, 7900 * 1e-3);
  EXPECT_NEAR(s.reactions[1].Fy, 3226.3, 3226.3 * 1e-3);
  const double span = 254.0, lever3 = 273.05 - 69.85, lever4 = 273.05 - 215.9;
  EXPECT_NEAR(s.reactions[0].Fy, (876.3 * lever3 + 3936.7 * lever4) / span, 1e-9 * 1586.7);
  EXPECT_NEAR(s.reactions[0].Fz, (-2402.0 * lever3 + 10813.6 * lever4) / span, 1e-9 * 1586.7);
  // Every force balances to 1e-9 relative.
  double sy = -876.3 - 3936.7, sz = 2402.0 - 10813.6;
  EXPECT_NEAR(s.reactions[0].Fy + s.reactions[1].Fy, -sy, 1e-9 * std::fabs(sy));
  EXPECT_NEAR(s.reactions[0].Fz + s.reactions[1].Fz, -sz, 1e-9 * std::fabs(sz));
  EXPECT_NEAR(s.deflectionAt(69.85 * kMm) / kUm, 23.26, 23.26 * 0.005);
  EXPECT_NEAR(s.deflectionAt(215.9 * kMm) / kUm, 44.62, 44.62 * 0.005);
  auto slope = [&](double x) { return s.slopeAt(x * kMm) * 1e3; };
  EXPECT_NEAR(slope(19.05), 0.501, 0.501 * 0.005);
  EXPECT_NEAR(slope(273.05), 1.095, 1.095 * 0.005);
  EXPECT_NEAR(slope(69.85), 0.414, 0.414 * 0.005);
  EXPECT_NEAR(slope(215.9), 0.426, 0.426 * 0.005);
}

TEST(Beam, ShigleyWithShearMovesTheLargerGearAboutFifteenPercentMore) {
  double off = solve(shigley(false)).deflectionAt(215.9 * kMm), on = solve(shigley(true)).deflectionAt(215.9 * kMm);
  EXPECT_NEAR(on / kUm, 51.4, 51.4 * 0.01);
  EXPECT_GT(on / off, 1.1);
}

TEST(Beam, PointLoadMatchesTheClosedFormsOnRigidAndElasticSupports) {
  Solution eb = solve(pointLoad(false)), tim = solve(pointLoad(true));
  EXPECT_NEAR(eb.reactions[0].Fy, 20000.0 / 3, 1e-9 * 10000);
  EXPECT_NEAR(eb.reactions[1].Fy, 10000.0 / 3, 1e-9 * 10000);
  EXPECT_NEAR(-eb.deflection(Solution::Plane::Y, 0.1) / kUm, 68.984, 0.001);
  EXPECT_NEAR(-tim.deflection(Solution::Plane::Y, 0.1) / kUm, 73.727, 0.001);
  EXPECT_NEAR(std::fabs(eb.slopeY.front()) * 1e3, 0.86230, 1e-5);
  EXPECT_NEAR(std::fabs(eb.slopeY.back()) * 1e3, 0.68984, 1e-5);
  Solution sp = solve(pointLoad(true, 200e6, 400e6));
  EXPECT_NEAR(-sp.v.front() / kUm, 33.333, 0.001);
  EXPECT_NEAR(-sp.v.back() / kUm, 8.333, 0.001);
  EXPECT_NEAR(-sp.deflection(Solution::Plane::Y, 0.1) / kUm, 98.727, 0.001);
  EXPECT_NEAR(sp.reactions[0].Fy + sp.reactions[1].Fy, 10000, 1e-9 * 10000);
  // The bending moment under the load: P a b / L.
  EXPECT_NEAR(std::fabs(eb.moment(Solution::Plane::Y, 0.1)), 10000 * 0.1 * 0.2 / 0.3, 1e-6 * 666.7);
}

TEST(Beam, TorqueTakenOffUniformlyAcrossAFaceWindsItUpByTbOver2GJ) {
  Model m;
  m.sections = {{0, 0.1, 0.08, 0}};
  m.material.E = 210e9;
  m.material.G = 210e9 / 2.6;
  m.bearings = {{"A", 0}, {"B", 0.1}};
  const int n = 50;
  for (int k = 0; k < n; ++k)
    m.loads.push_back({(k + 0.5) * 0.1 / n, 0, 0, 0, 0, 0, -1000.0 / n});
  m.loads.push_back({0, 0, 0, 0, 0, 0, 1000.0});
  m.torsionFixedAt = 0;
  Solution s = solve(m);
  double wind = s.twist.back() - s.twist.front();
  EXPECT_NEAR(std::fabs(wind) * 1e3, 0.15394, 1e-5);
  EXPECT_NEAR(std::fabs(wind) * 0.04 / kUm, 6.158, 0.001);
}

TEST(Beam, FriswellTwoDiskRotorNaturalFrequenciesAtStandstill) {
  Model m;
  m.sections = {{0, 1.5, 0.05, 0}};
  m.material = {211e9, 81.2e9, 7810};
  m.bearings = {{"A", 0, 1e6}, {"B", 1.5, 1e6}};
  auto disk = [&](double x, double D, double d, double t) {
    double mass = m.material.density * std::numbers::pi / 4 * (D * D - d * d) * t;
    m.disks.push_back({x, mass, mass * (3 * (D * D + d * d) / 4 + t * t) / 12, mass * (D * D + d * d) / 8});
  };
  disk(0.5, 0.28, 0.05, 0.07);
  disk(1.0, 0.35, 0.05, 0.07);
  m.elements = 60;
  // Bending in one plane (the other plane repeats them: the bearings are isotropic), and the
  // first torsional frequency, which the published list of the first four holds third.
  auto w = naturalFrequencies(m, 3);
  ASSERT_EQ(w.size(), 3u);
  const double bending[] = {86.66, 274.31, 716.78};
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(w[static_cast<size_t>(i)], bending[i], bending[i] * 0.005) << i;
  auto t = torsionalFrequencies(m, 1);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0], 650.41, 650.41 * 0.005);
}

TEST(Beam, AShaftThatCannotStandIsRefusedWithAReason) {
  Model m = pointLoad(false);
  m.bearings.pop_back();
  EXPECT_THROW(solve(m), std::invalid_argument);
  m = pointLoad(false);
  m.loads.push_back({0.4, 1});
  EXPECT_THROW(solve(m), std::invalid_argument);
  m = pointLoad(false);
  m.loads[0].Fx = 100;
  EXPECT_THROW(solve(m), std::invalid_argument); // no bearing holds the thrust
}
