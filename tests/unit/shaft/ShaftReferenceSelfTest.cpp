// Self-checks of the DIN 743 and ISO 281 references against the check values of DOMAIN §12
// (S2, S4, S6). Each printed value is met to half a unit of its last printed digit.
#include "Din743Reference.h"
#include "Iso281Reference.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gbx::test {
namespace {

// |x - printed| <= half a unit in the printed value's last digit.
void expectPrinted(double x, double printed, int decimals) {
  EXPECT_NEAR(x, printed, 0.5 * std::pow(10.0, -decimals)) << "printed " << printed;
}

// S2: 50CrMo4, shoulder 84/100 r 4, d_eff 100, load case 1, Rz 10 um.
Din743Input s2Input() {
  Din743Input in;
  in.material = {1100.0, 900.0, Din743SteelGroup::quenched_tempered};
  in.dEff = 100.0;
  in.notch = Din743Shoulder{84.0, 100.0, 4.0};
  in.tensionN = {443341.6, 0.0, 443341.6};
  in.bendingNm = {23275.43, 2909.429, 26184.86};
  in.torsionNm = {13965.26, 0.0, 13965.26};
  in.loadCase = Din743LoadCase::one;
  in.rzUm = 10.0;
  return in;
}

// S4: S235, V-notch 10 mm deep in an 80 mm shaft (root 60), d_eff 80, load case 2, static only.
Din743Input s4Input() {
  Din743Input in;
  in.material = {360.0, 235.0, Din743SteelGroup::structural};
  in.dEff = 80.0;
  in.notch = Din743VNotch{80.0, 60.0};
  in.tensionN = {40000.0, 0.0, 60000.0};
  in.bendingNm = {12666.667, 0.0, 19000.0};
  in.loadCase = Din743LoadCase::two;
  in.rzUm = 25.0;
  return in;
}

TEST(ShaftReference, Din743S2Safeties) {
  const auto r = din743Reference(s2Input());
  expectPrinted(r.SD, 2.373, 3);
  expectPrinted(r.SF, 1.464, 3);
}

TEST(ShaftReference, Din743S2Intermediates) {
  const auto r = din743Reference(s2Input());
  expectPrinted(r.tension.nominal.mean, 80.0, 0);
  expectPrinted(r.bending.nominal.mean, 400.0, 0);
  expectPrinted(r.bending.nominal.amplitude, 50.0, 0);
  expectPrinted(r.torsion.nominal.mean, 120.0, 0);
  expectPrinted(r.tension.beta, 2.0925, 4);
  expectPrinted(r.bending.beta, 1.9167, 4);
  expectPrinted(r.torsion.beta, 1.4515, 4);
  expectPrinted(r.bending.K2, 0.83871, 5);
  expectPrinted(r.torsion.K2, 0.83871, 5);
  EXPECT_EQ(r.tension.K2, 1.0);
  expectPrinted(r.K1B, 0.79307, 5);
  expectPrinted(r.K1S, 0.72940, 5);
}

TEST(ShaftReference, Din743S2Consistency) {
  const auto r = din743Reference(s2Input());
  // S_D here is sigma_bADK / sigma_ba (bending is the only amplitude).
  EXPECT_NEAR(r.SD, r.bending.sigmaADK / r.bending.nominal.amplitude, 1e-12);
  // Load case 1 below the yield line: sigma_ADK = sigma_WK - psi sigma_mv.
  EXPECT_NEAR(r.bending.sigmaADK, r.bending.sigmaWK - r.bending.psi * r.sigmaMv, 1e-9);
  // Shoulder d/D = 0.84 > 0.67: phi = 1/(4 sqrt(2) + 2).
  EXPECT_NEAR(r.phi, 1.0 / (4.0 * std::sqrt(2.0) + 2.0), 1e-12);
  // gamma_F from alpha: both alpha above 2.
  EXPECT_EQ(r.tension.gammaF, 1.10);
  EXPECT_EQ(r.bending.gammaF, 1.10);
  EXPECT_EQ(r.torsion.gammaF, 1.0);
}

TEST(ShaftReference, Din743S4StaticSafety) {
  const auto r = din743Reference(s4Input());
  expectPrinted(r.SF, 0.274, 3);
  EXPECT_TRUE(std::isinf(r.SD)); // no amplitude
  EXPECT_EQ(r.K1B, 1.0);
  EXPECT_EQ(r.tension.gammaF, 1.0);
  EXPECT_EQ(r.bending.gammaF, 1.0);
}

TEST(ShaftReference, Iso281BasicLife) {
  constexpr auto ball = Iso281BearingType::radial_ball;
  const double L10 = iso281L10(55.3, 10.0, ball);
  expectPrinted(L10, 169.0, 0);
  EXPECT_NEAR(iso281L10h(L10, 3000.0), 940.0, 0.005 * 940.0);
  EXPECT_NEAR(iso281L10h(iso281L10(55.3, 4.0, ball), 1800.0), 24500.0, 0.005 * 24500.0);
}

TEST(ShaftReference, Iso281ReliabilityFactor) {
  expectPrinted(iso281A1(90.0), 1.0, 2);
  expectPrinted(iso281A1(95.0), 0.64, 2);
  expectPrinted(iso281A1(96.0), 0.55, 2);
  expectPrinted(iso281A1(97.0), 0.47, 2);
  expectPrinted(iso281A1(98.0), 0.37, 2);
  expectPrinted(iso281A1(99.0), 0.25, 2);
}

// The published 5-digit coefficients leave a step at kappa 0.4 (ball) that grows with e_C C_u/P:
// 3e-4 at 0.05, 1e-3 at 1, 2e-3 at 5. Checked here for e_C C_u/P up to 1.
TEST(ShaftReference, Iso281AIsoContinuousAtBandEdges) {
  for (auto t : {Iso281BearingType::radial_ball, Iso281BearingType::radial_roller}) {
    for (double x : {0.05, 0.2, 0.5, 1.0}) {
      const double lo04 = iso281AIsoBandRaw(t, 0, 0.4, x);
      const double hi04 = iso281AIsoBandRaw(t, 1, 0.4, x);
      EXPECT_NEAR(lo04 / hi04, 1.0, 1e-3) << "kappa 0.4, x " << x;
      const double lo1 = iso281AIsoBandRaw(t, 1, 1.0, x);
      const double hi1 = iso281AIsoBandRaw(t, 2, 1.0, x);
      EXPECT_NEAR(lo1 / hi1, 1.0, 1e-3) << "kappa 1, x " << x;
    }
  }
}

TEST(ShaftReference, Iso281AIsoCaps) {
  constexpr auto ball = Iso281BearingType::radial_ball;
  const auto capped = iso281AIso(ball, 10.0, 1.0, 100.0, 1.0);
  EXPECT_EQ(capped.kappaUsed, 4.0);
  EXPECT_EQ(capped.loadTermUsed, 5.0);
  EXPECT_EQ(capped.aIso, 50.0);
  const auto low = iso281AIso(ball, 0.05, 0.5, 1.0, 10.0);
  EXPECT_TRUE(low.kappaBelowRange);
  EXPECT_EQ(low.band, 0);
  EXPECT_GT(low.aIso, 0.0);
  EXPECT_LT(low.aIso, 0.2);
}

TEST(ShaftReference, Iso281ViscosityRatio) {
  // Below 1000 rpm: 45000 n^-0.83 D_pw^-0.5; from 1000 rpm: 4500 n^-0.5 D_pw^-0.5.
  EXPECT_NEAR(iso281Nu1(500.0, 100.0), 45000.0 * std::pow(500.0, -0.83) / 10.0, 1e-9);
  EXPECT_NEAR(iso281Nu1(3600.0, 100.0), 4500.0 / 60.0 / 10.0, 1e-9);
  EXPECT_NEAR(iso281Kappa(15.0, 3600.0, 100.0), 2.0, 1e-12);
  EXPECT_NEAR(iso281CuApprox(22.0, Iso281BearingType::radial_ball), 1.0, 1e-12);
  EXPECT_NEAR(iso281CuApprox(8.2, Iso281BearingType::radial_roller), 1.0, 1e-12);
}

} // namespace
} // namespace gbx::test
