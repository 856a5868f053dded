// Sanity checks of the geometric backlash reference in BacklashReference.h.
#include "BacklashReference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace gbx::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMm = 1e-3;
constexpr double kUm = 1e-6;

double inv(double alpha) { return std::tan(alpha) - alpha; }

// Transverse pressure angle and base-circle radii sum of a case.
double alphaT(const BacklashCase& c) { return std::atan(std::tan(c.alphaN) / std::cos(c.beta)); }
double baseRadiiSum(const BacklashCase& c) {
  return 0.5 * (c.z1 + c.z2) * c.mn / std::cos(c.beta) * std::cos(alphaT(c));
}

// Zero-backlash centre distance from inv(alpha_wt) = inv(alpha_t) + 2 tan(alpha_n) (x1 + x2) / (z1 + z2).
double textbookZeroBacklashDistance(const BacklashCase& c) {
  const double target = inv(alphaT(c)) + 2 * std::tan(c.alphaN) * (c.x1 + c.x2) / (c.z1 + c.z2);
  double alpha = alphaT(c);
  for (int i = 0; i < 100; ++i)
    alpha -= (inv(alpha) - target) / (std::tan(alpha) * std::tan(alpha));
  return baseRadiiSum(c) / std::cos(alpha);
}

// Minimum of f on [lo, hi]: coarse scan, then golden-section refinement.
template <class F> double minimise(F f, double lo, double hi, int samples) {
  double best = lo;
  double fBest = f(lo);
  const double step = (hi - lo) / samples;
  for (int i = 1; i <= samples; ++i) {
    const double u = lo + i * step;
    const double fu = f(u);
    if (fu < fBest) best = u, fBest = fu;
  }
  double l = std::fmax(lo, best - step), h = std::fmin(hi, best + step);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 200; ++i) {
    const double m1 = h - g * (h - l), m2 = l + g * (h - l);
    if (f(m1) < f(m2))
      h = m2;
    else
      l = m1;
  }
  return 0.5 * (l + h);
}

double distance(const backlash_detail::Vec2& p, const backlash_detail::Vec2& q) {
  return std::hypot(p[0] - q[0], p[1] - q[1]);
}

// Minimum distance between two involute flanks (roll angles 0..2), brute force.
double flankDistance(const backlash_detail::Involute& f1, const backlash_detail::Involute& f2) {
  const auto toF2 = [&](double u1) {
    const auto p = f1.point(u1);
    const double u2 = minimise([&](double u) { return distance(p, f2.point(u)); }, 0.0, 2.0, 400);
    return distance(p, f2.point(u2));
  };
  const double u1 = minimise(toF2, 0.0, 2.0, 100);
  return toF2(u1);
}

BacklashCase caseA() { return {4 * kMm, 20 * kDeg, 0.0, 20, 40, 0.0, 0.0, 120.030 * kMm, -60 * kUm, -60 * kUm}; }
BacklashCase caseB() {
  BacklashCase c{3 * kMm, 20 * kDeg, 15 * kDeg, 23, 71, 0.2, -0.1, 0.0, -80 * kUm, -100 * kUm};
  c.a = referenceZeroBacklashCentreDistance(c) - 20 * kUm;
  return c;
}
BacklashCase caseC() { return {5 * kMm, 25 * kDeg, 22 * kDeg, 17, 52, 0.45, 0.1, 185 * kMm, -120 * kUm, -120 * kUm}; }

TEST(BacklashReference, SpurNominalDistanceZeroAllowancesHasNoBacklash) {
  const BacklashCase c{4 * kMm, 20 * kDeg, 0.0, 20, 40, 0.0, 0.0, 120 * kMm, 0.0, 0.0};
  const BacklashRef r = referenceBacklash(c);
  EXPECT_NEAR(r.jt, 0.0, 1e-9 * kMm);
  EXPECT_NEAR(r.jn, 0.0, 1e-9 * kMm);
  EXPECT_NEAR(referenceZeroBacklashCentreDistance(c), 120 * kMm, 1e-9 * kMm);
}

TEST(BacklashReference, ZeroBacklashDistanceMatchesInvoluteFunctionRelation) {
  for (const BacklashCase& c : {caseA(), caseB(), caseC()}) {
    EXPECT_NEAR(referenceZeroBacklashCentreDistance(c), textbookZeroBacklashDistance(c), 1e-9 * kMm);
  }
}

// First-order approximation (ISO 21771 / DIN 3967):
//   j_n ~ -(A_sn1 + A_sn2) cos(alpha_n) + 2 A_a sin(alpha_wt) cos(beta_b)
//   j_t ~ -(A_sn1 + A_sn2) / cos(beta) * cos(alpha_t) / cos(alpha_wt) + 2 A_a tan(alpha_wt)
// with A_a = a - a_w0 (a_w0: zero-backlash distance) and alpha_wt at the actual distance a.
TEST(BacklashReference, SmallAllowancesAgreeWithFirstOrderFormula) {
  BacklashCase c{3 * kMm, 20 * kDeg, 15 * kDeg, 23, 71, 0.2, -0.1, 0.0, -50 * kUm, -50 * kUm};
  const double aw0 = referenceZeroBacklashCentreDistance(c);
  const double Aa = 30 * kUm;
  c.a = aw0 + Aa;
  const double alphaWt = std::acos(baseRadiiSum(c) / c.a);
  const double cosBetaB = std::sqrt(1 - std::pow(std::sin(c.beta) * std::cos(c.alphaN), 2));
  const double jnApprox = -(c.As1 + c.As2) * std::cos(c.alphaN) + 2 * Aa * std::sin(alphaWt) * cosBetaB;
  const double jtApprox =
      -(c.As1 + c.As2) / std::cos(c.beta) * std::cos(alphaT(c)) / std::cos(alphaWt) + 2 * Aa * std::tan(alphaWt);
  const BacklashRef r = referenceBacklash(c);
  std::printf("first-order check: jt %.6g um (approx %.6g um), jn %.6g um (approx %.6g um)\n", r.jt / kUm,
              jtApprox / kUm, r.jn / kUm, jnApprox / kUm);
  EXPECT_NEAR(r.jt, jtApprox, 0.01 * std::fabs(jtApprox));
  EXPECT_NEAR(r.jn, jnApprox, 0.01 * std::fabs(jnApprox));
  // Transverse and normal values are tied by j_n = j_t cos(alpha_wt) cos(beta_b).
  EXPECT_NEAR(r.jn, r.jt * std::cos(alphaWt) * cosBetaB, 1e-12 * std::fabs(r.jn));
}

// At the contact angle the flanks touch; backed off by dphi they are r_b2 * dphi apart (brute force).
TEST(BacklashReference, ContactPositionsAreTrueTouchingPositions) {
  const BacklashCase c = caseB();
  const backlash_detail::Pair pair(c);
  for (int side : {+1, -1}) {
    const double phi = pair.contactAngle(side);
    const auto f1 = pair.flank1(side);
    EXPECT_NEAR(flankDistance(f1, pair.flank2(side, phi)), 0.0, 1e-12);
    const double dphi = 1e-4;
    const double backedOff = flankDistance(f1, pair.flank2(side, phi - side * dphi));
    EXPECT_NEAR(backedOff, pair.rb2 * dphi, 1e-6 * pair.rb2 * dphi);
  }
}

TEST(BacklashReference, MoreClearanceGivesMoreBacklash) {
  BacklashCase c = caseA();
  const double j0 = referenceBacklash(c).jt;
  c.As1 -= 10 * kUm;
  EXPECT_GT(referenceBacklash(c).jt, j0);
  c.a += 10 * kUm;
  EXPECT_GT(referenceBacklash(c).jt, j0);
}

TEST(BacklashReference, PrintCases) {
  const struct {
    const char* name;
    BacklashCase c;
  } cases[] = {{"A", caseA()}, {"B", caseB()}, {"C", caseC()}};
  for (const auto& k : cases) {
    const BacklashRef r = referenceBacklash(k.c);
    std::printf("case %s: a = %.12g mm, jt = %.6g um, jn = %.6g um\n", k.name, k.c.a / kMm, r.jt / kUm, r.jn / kUm);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", r.jt / kUm);
    RecordProperty(std::string("case") + k.name + "_jt_um", buf);
    std::snprintf(buf, sizeof buf, "%.6g", r.jn / kUm);
    RecordProperty(std::string("case") + k.name + "_jn_um", buf);
  }
  const double aw0B = referenceZeroBacklashCentreDistance(caseB());
  std::printf("case B: zero-backlash centre distance = %.9g mm\n", aw0B / kMm);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", aw0B / kMm);
  RecordProperty("caseB_aw0_mm", buf);
}

} // namespace
} // namespace gbx::test
