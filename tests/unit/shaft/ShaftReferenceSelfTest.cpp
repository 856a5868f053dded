// Self-checks of the DIN 743 and ISO 281 references against the check values of DOMAIN §12
// (S2, S4, S6), and of the DIN 743 notch kinds beyond shoulder and V-notch against hand calculations.
// Each printed value is met to half a unit of its last printed digit.
#include "Din743Cases.h"
#include "Din743Reference.h"
#include "Iso281Reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace gbx::test {
namespace {

// |x - printed| <= half a unit in the printed value's last digit.
void expectPrinted(double x, double printed, int decimals) {
  EXPECT_NEAR(x, printed, 0.5 * std::pow(10.0, -decimals)) << "printed " << printed;
}

TEST(ShaftReference, Din743S2Safeties) {
  const auto r = din743Reference(din743S2Input());
  expectPrinted(r.SD, 2.373, 3);
  expectPrinted(r.SF, 1.464, 3);
}

TEST(ShaftReference, Din743S2Intermediates) {
  const auto r = din743Reference(din743S2Input());
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
  const auto r = din743Reference(din743S2Input());
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
  const auto r = din743Reference(din743S4Input());
  expectPrinted(r.SF, 0.274, 3);
  EXPECT_TRUE(std::isinf(r.SD)); // no amplitude
  EXPECT_EQ(r.K1B, 1.0);
  EXPECT_EQ(r.tension.gammaF, 1.0);
  EXPECT_EQ(r.bending.gammaF, 1.0);
}

// The notch kinds beyond shoulder and V-notch, one case each, checked against a hand calculation done
// step by step outside the header (python3, DIN 743:2012 formulas; values rounded as printed here).
// Common case: 42CrMo4 quenched and tempered, sigma_B 1100, sigma_S 900 at d_B; d = 50, d_eff = 60,
// bending moment amplitude 800 N m (mean 0), torque mean 1000 N m (amplitude 0), load case 2, Rz 8 um.
//   K1B = 1 - 0.26 lg(60/16) = 0.850752, K1S = 1 - 0.34 lg(60/16) = 0.804829
//   sigma_B(d) = 935.8271, sigma_S(d) = 724.3464, K2(50) = 1 - 0.2 lg(50/7.5)/lg 20 = 0.873345
//   K_Fsigma(Rz 8) = 1 - 0.22 lg 8 (lg(935.83/20) - 1) = 0.866852, K_Ftau = 0.575 K_Fsigma + 0.425 = 0.923440
//   sigma_bW = 0.5 * 1100 * K1B = 467.9135, tau_tW = 0.3 * 1100 * K1B = 280.7481
//   solid section: W_b = pi 50^3/32 = 12271.85 mm^3, W_t = 24543.69 mm^3,
//   sigma_ba = 65.18986, tau_tm = 40.74367, sigma_mv = sqrt(3) tau_tm = 70.57010 (k = sigma_mv/sigma_ba = 1.082532)
//   tau_tFK = K1S 1.2 * 900 / sqrt 3 = 501.84193; sigma_bFK = K1S 1.2 gamma_F 900 (869.21572 gamma_F)
//   Load case 2 below the yield line: sigma_bADK = sigma_bWK / (1 + psi k); S_D = sigma_bADK / sigma_ba
//   (torsion has no amplitude); S_F = 1 / sqrt((sigma_ba/sigma_bFK)^2 + (tau_tm/tau_tFK)^2).
Din743Input newKindInput(Din743Notch notch) {
  Din743Input in;
  in.material = {1100.0, 900.0, Din743SteelGroup::quenched_tempered};
  in.dEff = 60.0;
  in.notch = notch;
  in.bendingNm = {0.0, 800.0, std::nullopt};
  in.torsionNm = {1000.0, 0.0, std::nullopt};
  in.loadCase = Din743LoadCase::two;
  in.rzUm = 8.0;
  return in;
}

void expectCommonNewKind(const Din743Result& r) {
  expectPrinted(r.K1B, 0.850752, 6);
  expectPrinted(r.K1S, 0.804829, 6);
  expectPrinted(r.sigmaBd, 935.8271, 4);
  expectPrinted(r.sigmaSd, 724.3464, 4);
  expectPrinted(r.bending.K2, 0.873345, 6);
  expectPrinted(r.torsion.sigmaFK, 501.84193, 5);
  EXPECT_TRUE(std::isnan(r.torsion.sigmaADK)); // no torsion amplitude in load case 2
}

// Round groove D 55, d 50, r 1.5: t = 2.5, r/t = 0.6, r/d = 0.03.
//   alpha = 1 + 1/sqrt(A r/t + B r/d (1 + 2 r/d)^2): zd (0.22, 2.74) 3.111190, b (0.20, 5.5) 2.809547,
//   t (0.70, 20.6) 1.947289
//   d/D = 0.909 > 0.67: phi = 1/(4 sqrt(2.5/1.5) + 2) = 0.139587; G'_sigma = 2/1.5 (1 + phi) = 1.519450,
//   G'_tau = 1/1.5 = 0.666667; n = 1 + sqrt(G') 10^-(0.33 + 724.3464/712): n_sigma = 1.055399, n_tau = 1.036696
//   beta: zd 2.947880, b 2.662070, t 1.878361
//   K_b = 2.662070/0.873345 + 1/0.866852 - 1 = 3.201731 -> sigma_bWK = 146.14394, psi = 0.084696
//   K_t = 1.878361/0.873345 + 1/0.923440 - 1 = 2.233674 -> tau_tWK = 125.68894
//   sigma_bADK = 146.14394 / (1 + 0.084696 * 1.082532) = 133.86991 -> S_D = 2.053539
//   gamma_F: alpha_b 2.81 -> 1.10 (sigma_bFK = 956.13729 -> S_F = 9.432240); alpha_zd 3.11 > 3 -> 1.15
TEST(ShaftReference, Din743RoundGroove) {
  const auto r = din743Reference(newKindInput(Din743Groove{55.0, 50.0, 1.5}));
  expectCommonNewKind(r);
  expectPrinted(r.tension.alpha, 3.111190, 6);
  expectPrinted(r.bending.alpha, 2.809547, 6);
  expectPrinted(r.torsion.alpha, 1.947289, 6);
  expectPrinted(r.phi, 0.139587, 6);
  expectPrinted(r.bending.Gprime, 1.519450, 6);
  expectPrinted(r.torsion.Gprime, 0.666667, 6);
  expectPrinted(r.bending.n, 1.055399, 6);
  expectPrinted(r.torsion.n, 1.036696, 6);
  expectPrinted(r.tension.beta, 2.947880, 6);
  expectPrinted(r.bending.beta, 2.662070, 6);
  expectPrinted(r.torsion.beta, 1.878361, 6);
  expectPrinted(r.bending.KF, 0.866852, 6);
  expectPrinted(r.torsion.KF, 0.923440, 6);
  expectPrinted(r.bending.K, 3.201731, 6);
  expectPrinted(r.bending.sigmaWK, 146.14394, 5);
  expectPrinted(r.torsion.sigmaWK, 125.68894, 5);
  expectPrinted(r.bending.psi, 0.084696, 6);
  expectPrinted(r.sigmaMv, 70.57010, 5);
  expectPrinted(r.bending.sigmaADK, 133.86991, 5);
  EXPECT_EQ(r.tension.gammaF, 1.15);
  EXPECT_EQ(r.bending.gammaF, 1.10);
  EXPECT_TRUE(r.circumferential);
  expectPrinted(r.bending.sigmaFK, 956.13729, 5);
  expectPrinted(r.SD, 2.053539, 6);
  expectPrinted(r.SF, 9.432240, 6);
}

// Transverse hole d_L 8 in d 50: x = d_L/d = 0.16, r = 4.
//   net section: A = pi 50^2/4 - 8*50 = 1563.4954, W_b = pi 50^3/32 - 8*50^2/6 = 8938.5130,
//   W_t = pi 50^3/16 - 8*50^2/6 = 21210.3593 -> sigma_ba = 89.50035, tau_tm = 47.14677, sigma_mv = 81.66061
//   alpha: zd 3 - x = 2.84, b 3 + 1.4 x - 2.8 sqrt x = 2.104, t 2.023 - 1.125 sqrt x = 1.573
//   G': zd 2.3/4 = 0.575, b 0.575 + 2/50 = 0.615, t 1.15/4 + 2/50 = 0.3275
//   n: zd 1.034080, b 1.035245, t 1.025720 -> beta: zd 2.746404, b 2.032369, t 1.533557
//   K_b = 2.480709 -> sigma_bWK = 188.62090, psi = 0.112072; K_t = 1.838866 -> tau_tWK = 152.67461
//   k = 81.66061/89.50035 = 0.912405, sigma_bADK = 171.12273 -> S_D = 1.911978
//   not circumferential: gamma_F = 1 -> sigma_bFK = 869.21572 -> S_F = 7.174354
TEST(ShaftReference, Din743TransverseHole) {
  const auto r = din743Reference(newKindInput(Din743TransverseHole{50.0, 8.0}));
  expectCommonNewKind(r);
  expectPrinted(r.area, 1563.4954, 4);
  expectPrinted(r.Wb, 8938.5130, 4);
  expectPrinted(r.Wt, 21210.3593, 4);
  expectPrinted(r.bending.nominal.amplitude, 89.50035, 5);
  expectPrinted(r.torsion.nominal.mean, 47.14677, 5);
  expectPrinted(r.sigmaMv, 81.66061, 5);
  expectPrinted(r.tension.alpha, 2.84, 6);
  expectPrinted(r.bending.alpha, 2.104, 6);
  expectPrinted(r.torsion.alpha, 1.573, 6);
  expectPrinted(r.tension.Gprime, 0.575, 6);
  expectPrinted(r.bending.Gprime, 0.615, 6);
  expectPrinted(r.torsion.Gprime, 0.3275, 6);
  expectPrinted(r.tension.beta, 2.746404, 6);
  expectPrinted(r.bending.beta, 2.032369, 6);
  expectPrinted(r.torsion.beta, 1.533557, 6);
  expectPrinted(r.bending.KF, 0.866852, 6);
  expectPrinted(r.bending.sigmaWK, 188.62090, 5);
  expectPrinted(r.torsion.sigmaWK, 152.67461, 5);
  expectPrinted(r.bending.sigmaADK, 171.12273, 5);
  EXPECT_FALSE(r.circumferential);
  EXPECT_EQ(r.tension.gammaF, 1.0);
  EXPECT_EQ(r.bending.gammaF, 1.0);
  expectPrinted(r.bending.sigmaFK, 869.21572, 5);
  expectPrinted(r.SD, 1.911978, 6);
  expectPrinted(r.SF, 7.174354, 6);
}

// Keyway (end-milled), d_BK = 40, K_F = 1, gamma_F = 1.
// One key: beta_sigma(40) = 3.0 (935.8271/1000)^0.38 = 2.925335, beta_tau(40) = 0.56 * 2.925335 + 0.1 = 1.738188
//   K3 with beta(40): sigma K3(40) = 0.947901, K3(50) = 0.940957 -> beta_b = beta_zd = 2.946926;
//   tau K3(40) = 0.973167, K3(50) = 0.969591 -> beta_t = 1.744600
//   K_b = 2.946926/0.873345 = 3.374297 -> sigma_bWK = 138.66995, psi = 0.080018; K_t = 1.997606,
//   tau_tWK = 140.54228; sigma_bADK = 127.61562 -> S_D = 1.957599; sigma_bFK = 869.21572 -> S_F = 9.047531
// Two keys (both beta(40) times 1.15): beta_sigma(40) = 3.364135, beta_tau(40) = 1.998916,
//   beta_b = 3.392428, beta_t = 2.008228, sigma_bWK = 120.45944, sigma_bADK = 112.11118 -> S_D = 1.719764,
//   S_F = 9.047531 (unchanged: static strength does not see the key count)
TEST(ShaftReference, Din743Keyway) {
  const auto r = din743Reference(newKindInput(Din743Keyway{50.0, 1}));
  expectCommonNewKind(r);
  expectPrinted(r.dBK, 40.0, 9);
  expectPrinted(r.bending.betaDBK, 2.925335, 6);
  expectPrinted(r.torsion.betaDBK, 1.738188, 6);
  expectPrinted(r.bending.K3dBK, 0.947901, 6);
  expectPrinted(r.bending.K3d, 0.940957, 6);
  expectPrinted(r.torsion.K3dBK, 0.973167, 6);
  expectPrinted(r.torsion.K3d, 0.969591, 6);
  expectPrinted(r.tension.beta, 2.946926, 6);
  expectPrinted(r.bending.beta, 2.946926, 6);
  expectPrinted(r.torsion.beta, 1.744600, 6);
  EXPECT_EQ(r.bending.KF, 1.0);
  EXPECT_EQ(r.torsion.KF, 1.0);
  expectPrinted(r.bending.K, 3.374297, 6);
  expectPrinted(r.bending.sigmaWK, 138.66995, 5);
  expectPrinted(r.torsion.sigmaWK, 140.54228, 5);
  expectPrinted(r.sigmaMv, 70.57010, 5);
  expectPrinted(r.bending.sigmaADK, 127.61562, 5);
  EXPECT_FALSE(r.circumferential);
  EXPECT_EQ(r.bending.gammaF, 1.0);
  expectPrinted(r.SD, 1.957599, 6);
  expectPrinted(r.SF, 9.047531, 6);

  const auto r2 = din743Reference(newKindInput(Din743Keyway{50.0, 2}));
  expectPrinted(r2.bending.betaDBK, 3.364135, 6);
  expectPrinted(r2.torsion.betaDBK, 1.998916, 6);
  expectPrinted(r2.bending.beta, 3.392428, 6);
  expectPrinted(r2.torsion.beta, 2.008228, 6);
  expectPrinted(r2.bending.sigmaWK, 120.45944, 5);
  expectPrinted(r2.bending.sigmaADK, 112.11118, 5);
  expectPrinted(r2.SD, 1.719764, 6);
  expectPrinted(r2.SF, 9.047531, 6);
}

// Press fit on d 50, d_BK = 40, K_F = 1, circumferential (gamma_F from beta).
//   beta_sigma(40) = 2.7 (935.8271/1000)^0.43 = 2.624085, beta_tau(40) = 0.65 * 2.624085 = 1.705655
//   sigma K3(40) = 0.953176, K3(50) = 0.946934 -> beta_b = beta_zd = 2.641381;
//   tau K3(40) = 0.974084, K3(50) = 0.970630 -> beta_t = 1.711726
//   K_b = 3.024442 -> sigma_bWK = 154.71072, psi = 0.090108; K_t = 1.959965 -> tau_tWK = 143.24141
//   sigma_bADK = 140.96070 -> S_D = 2.162310
//   gamma_F(beta_b 2.64) = 1.10 -> sigma_bFK = 956.13729 -> S_F = 9.432240
TEST(ShaftReference, Din743PressFit) {
  const auto r = din743Reference(newKindInput(Din743PressFit{50.0}));
  expectCommonNewKind(r);
  expectPrinted(r.bending.betaDBK, 2.624085, 6);
  expectPrinted(r.torsion.betaDBK, 1.705655, 6);
  expectPrinted(r.bending.K3dBK, 0.953176, 6);
  expectPrinted(r.bending.K3d, 0.946934, 6);
  expectPrinted(r.torsion.K3dBK, 0.974084, 6);
  expectPrinted(r.torsion.K3d, 0.970630, 6);
  expectPrinted(r.tension.beta, 2.641381, 6);
  expectPrinted(r.bending.beta, 2.641381, 6);
  expectPrinted(r.torsion.beta, 1.711726, 6);
  EXPECT_EQ(r.bending.KF, 1.0);
  EXPECT_EQ(r.torsion.KF, 1.0);
  expectPrinted(r.bending.K, 3.024442, 6);
  expectPrinted(r.bending.sigmaWK, 154.71072, 5);
  expectPrinted(r.torsion.sigmaWK, 143.24141, 5);
  expectPrinted(r.sigmaMv, 70.57010, 5);
  expectPrinted(r.bending.sigmaADK, 140.96070, 5);
  EXPECT_TRUE(r.circumferential);
  EXPECT_EQ(r.tension.gammaF, 1.10);
  EXPECT_EQ(r.bending.gammaF, 1.10);
  expectPrinted(r.bending.sigmaFK, 956.13729, 5);
  expectPrinted(r.SD, 2.162310, 6);
  expectPrinted(r.SF, 9.432240, 6);
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
