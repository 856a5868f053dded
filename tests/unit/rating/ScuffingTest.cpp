// Scuffing and micropitting (ISO/TS 6336-20, -21, -22) of one mesh against an independent
// reference written from the standards (ScuffingReference.h), the published NREL 5 MW
// high-speed stage (docs/rating.md) and the hard cases with their closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "ScuffingReference.h"
#include "rating/Scuffing.h"

namespace {

using namespace gbx::rt::rating;
namespace ref = gbx::refscuff;

constexpr double kPi = 3.14159265358979323846;
constexpr double kZeroC = 273.15;

// The NREL 5 MW high-speed stage with the load factors the published calculation used.
struct Case {
  double T1 = 40953, n1 = 1165.9, Ca1 = 2, Ca2 = 2;
};

ScuffingMesh mesh(const Case& c = {}) {
  ScuffingMesh m;
  m.z1 = 24;
  m.z2 = 95;
  m.mn = 14e-3;
  m.alphaN = 20 * kPi / 180;
  m.beta = 10 * kPi / 180;
  m.a = 861e-3;
  m.b = 360e-3;
  m.da1 = 380.747e-3;
  m.da2 = 1395.376e-3;
  double d1 = m.z1 * m.mn / std::cos(m.beta);
  m.Ft = 2 * c.T1 / d1;
  m.KA = 1.25;
  m.Kv = 1.092;
  m.KHbeta = 1.150;
  m.KHalpha = 1.069;
  m.speed1 = c.n1 * kPi / 30;
  m.power = c.T1 * m.speed1;
  m.BM = {std::sqrt(50 * 3.8e6), std::sqrt(50 * 3.8e6)};
  m.Ra = 0.6e-6;
  m.Ca = {c.Ca1 * 1e-6, c.Ca2 * 1e-6};
  m.grade = 6;
  return m;
}

Lubricant vg220() {
  Lubricant o;
  o.nu40 = 220e-6;
  o.nu100 = 19e-6;
  o.density15 = 890;
  o.oilTemperature = 80 + kZeroC;
  o.fzgStage = 14;
  o.fvaStage = 10;
  return o;
}

ref::Pair refPair(const Case& c = {}) {
  ref::Pair p{};
  p.z1 = 24;
  p.z2 = 95;
  p.mn = 14;
  p.beta_deg = 10;
  p.alpha_n_deg = 20;
  p.a = 861;
  p.b = 360;
  p.x1 = 0.48;
  p.x2 = 0.6691;
  p.da1 = 380.747;
  p.da2 = 1395.376;
  p.E1 = p.E2 = 206000;
  p.nu1 = p.nu2 = 0.3;
  p.lambdaM1 = p.lambdaM2 = 50;
  p.rho1 = p.rho2 = 7830;
  p.cM1 = p.cM2 = 3.8e6 / 7830;
  p.Ra1 = p.Ra2 = 0.6;
  p.Ca1 = c.Ca1;
  p.Ca2 = c.Ca2;
  p.T1 = c.T1;
  p.n1 = c.n1;
  p.KA = 1.25;
  p.Kv = 1.092;
  p.KHb = 1.150;
  p.KHa = 1.069;
  p.KBg = 0;  // from eps_gamma, as the rating finds it
  p.nu40 = 220;
  p.nu100 = 19;
  p.rho15 = 890;
  p.theta_oil = 80;
  p.fzgLoadStage = 14;
  p.fvaLoadStage = 10;
  p.Q = 6;
  return p;
}

double degC(double K) { return K - kZeroC; }

// The point of the path where Gamma is 0 (the pitch point), or none.
const PathPoint* pitchPoint(const ScuffingRating& r) {
  auto c = std::find_if(r.path.begin(), r.path.end(), [](const PathPoint& p) { return p.gamma == 0; });
  return c == r.path.end() ? nullptr : &*c;
}

// Dowson-Higginson's film at a point of pure rolling (SI, E' = E_r): h = 1.6 R G^0.6 U^0.7
// W^-0.13, the oil's viscosity (ASTM D341 line, density rho15 - 0.7 (T - 289)) and ISO/TS
// 6336-22's pressure-viscosity coefficient of a mineral oil at T [K].
double dowsonHigginson(double R, double Er, double ue, double w, double T, const Lubricant& oil) {
  auto eta = [&](double t) { return oil.kinematic(t) * (oil.density15 - 0.7 * (t - 289)); };
  double alpha = 2.657e-8 * std::pow(eta(311.15), 0.1348) * (1 + 516 * (1 / (T - 0.15) - 1.0 / 311));
  return 1.6 * R * std::pow(alpha * Er, 0.6) * std::pow(eta(T) * ue / (Er * R), 0.7) * std::pow(w / (Er * R), -0.13);
}

// Factor by factor against the independent reference, both editions.
void compare(ScuffingEdition e, ref::Edition re) {
  ScuffingRating r = rateScuffing(mesh(), vg220(), e);
  ref::Result x = ref::rate(refPair(), re);
  auto near = [](double a, double b, double tol, const char* what) { EXPECT_NEAR(a / b, 1.0, tol) << what << ": " << a << " vs " << b; };
  near(r.gammaA, x.gammaA, 1e-9, "Gamma_A");
  near(r.gammaE, x.gammaE, 1e-9, "Gamma_E");
  near(r.epsAlpha, x.epsAlpha, 1e-9, "eps_alpha");
  near(r.wBt, x.wBt, 1e-9, "w_Bt");
  near(r.KBgamma, x.KBg, 1e-9, "K_Bgamma");
  near(r.XalphaBeta, x.XalphaBeta, 1e-9, "X_alphabeta");
  near(r.XM, x.XM, 1e-6, "X_M");
  near(r.etaOil * 1e3, x.etaM, 1e-3, "eta_oil");  // the reference's density takes 273 K for 0 degC
  near(r.XL, x.XL, 1e-4, "X_L");
  near(r.muM, x.muM, 1e-4, "mu_m");
  near(r.Ceff, x.Ceff, 1e-9, "C_eff");
  near(r.thetaFlm, x.thetaFlm, 2e-4, "theta_flm");
  near(degC(r.thetaM), x.thetaM, 1e-4, "theta_M");
  near(degC(r.thetaS), x.thetaS, 1e-4, "theta_S");
  near(degC(r.thetaBmax), x.thetaBmax, 1e-4, "theta_B");
  EXPECT_NEAR(r.gammaMax, x.gamma_at_max, 1e-3);
  near(r.XGammaMax, x.XGamma_at_max, 1e-4, "X_Gamma at theta_Bmax");
  near(r.SB, x.SB, 2e-4, "S_B");
  near(r.thetaFlaInt, x.thetaFlaInt, 1e-4, "theta_flaint");
  near(degC(r.thetaInt), x.thetaInt, 1e-4, "theta_int");
  near(degC(r.thetaIntS), x.thetaIntS, 1e-6, "theta_intS");
  near(r.SintS, x.SintS, 1e-4, "S_intS");
  near(r.muMmp, x.muM_mp, 1e-4, "mu_m (micropitting)");
  near(degC(r.thetaMmp), x.thetaM_mp, 1e-4, "theta_M (micropitting)");
  near(r.lambdaMin, x.lambdaGFmin, 2e-3, "lambda_GF,min");
  near(r.lambdaGFT, x.lambdaGFT, 2e-3, "lambda_GFT");
  near(r.lambdaGFP, x.lambdaGFP, 2e-3, "lambda_GFP");
  near(r.Slambda, x.Slambda, 3e-3, "S_lambda");
}

TEST(Scuffing, AgreesWithTheIndependentReferenceFactorByFactor) {
  compare(ScuffingEdition::TS, ref::Edition::TS);
  compare(ScuffingEdition::TR, ref::Edition::TR);
}

// The published calculation (ISO/TR 13989-1/-2:2000, ISO/TR 15144-1:2014 editions).
TEST(Scuffing, ReproducesThePublishedNrelHighSpeedStage) {
  ScuffingRating r = rateScuffing(mesh(), vg220(), ScuffingEdition::TR);
  auto within = [](double a, double published, double tol, const char* what) {
    EXPECT_NEAR(a / published, 1.0, tol) << what << ": " << a << " against " << published;
  };
  within(r.wBt, 1119.63, 0.03, "w_Bt");
  within(r.XalphaBeta, 1.016, 0.03, "X_alphabeta");
  within(r.XL, 0.843, 0.03, "X_L");
  within(r.thetaFlm, 30.20, 0.03, "theta_flm");
  within(degC(r.thetaM), 94.19, 0.03, "theta_M");
  within(degC(r.thetaS), 451.98, 0.03, "theta_S");
  within(degC(r.thetaBmax), 169.50, 0.03, "theta_B");
  within(r.XM, 50.058, 0.03, "X_M");
  within(r.XGammaMax, 0.889, 0.03, "X_Gamma");
  within(r.etaOil * 1e3, 30.09, 0.03, "eta");
  within(r.muM, 0.041, 0.03, "mu_m");
  within(r.SB, 4.156, 0.03, "S_B");
  within(r.thetaFlaInt, 16.25, 0.03, "theta_flaint");
  within(degC(r.thetaInt), 115.75, 0.03, "theta_int");
  within(degC(r.thetaIntS), 455.17, 0.03, "theta_intS");
  within(r.SintS, 3.932, 0.03, "S_intS");
  within(r.muMmp, 0.030, 0.03, "mu_m (micropitting)");
  within(degC(r.thetaMmp), 85.0, 0.03, "theta_M (micropitting)");
  within(r.lambdaMin, 1.053, 0.03, "lambda_GF,min");
  EXPECT_NEAR(r.gammaLambdaMin, r.gammaA, 1e-12) << "lambda_GF,min at point A";
  // The FVA test's film (lambda_GFT) is 5 % below the published 0.102 with the test
  // conditions of ISO/TR 15144-1 (docs/rating.md); lambda_GFP and S_lambda follow it.
  within(r.lambdaGFT, 0.102, 0.06, "lambda_GFT");
  within(r.lambdaGFP, 0.143, 0.06, "lambda_GFP");
  within(r.Slambda, 7.360, 0.06, "S_lambda");
}

TEST(Scuffing, NoFlashTemperatureAtThePitchPoint) {
  ScuffingRating r = rateScuffing(mesh(), vg220());
  const PathPoint* c = pitchPoint(r);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->thetaFla, 0.0);
  EXPECT_DOUBLE_EQ(c->thetaB, r.thetaM);
  for (const auto& p : r.path)
    if (p.gamma != 0) {
      EXPECT_GT(p.thetaFla, 0.0);
    }
}

// The hottest point is an end of the path; the wheel's tip relief against C_eff lowers it
// (the approach factor X_J at A falls with the relief).
TEST(Scuffing, ContactTemperatureIsLargestAtAnEndAndMovesWithTipRelief) {
  ScuffingRating unrelieved = rateScuffing(mesh({40953, 1165.9, 0, 0}), vg220());
  EXPECT_TRUE(unrelieved.gammaMax == unrelieved.gammaA || unrelieved.gammaMax == unrelieved.gammaE);
  EXPECT_EQ(unrelieved.gammaMax, unrelieved.gammaA);
  ScuffingRating relieved = rateScuffing(mesh({40953, 1165.9, 0, 60}), vg220());
  EXPECT_TRUE(relieved.gammaMax == relieved.gammaA || relieved.gammaMax == relieved.gammaE);
  EXPECT_LT(relieved.thetaBmax, unrelieved.thetaBmax);
  EXPECT_GT(relieved.SB, unrelieved.SB);
}

// Doubled torque, everything else fixed, X_J = 1 (a relief above C_eff): theta_fla goes
// with mu_m (w)^0.75 and mu_m with w^0.2, so theta_B - theta_oil scales by 2^0.95 and S_B
// by 2^-0.95.
TEST(Scuffing, SafetyScalesWithLoadAsTheClosedFormSays) {
  ScuffingRating one = rateScuffing(mesh({40953, 1165.9, 0, 200}), vg220());
  ScuffingRating two = rateScuffing(mesh({2 * 40953, 1165.9, 0, 200}), vg220());
  double k = std::pow(2.0, 0.95);
  EXPECT_NEAR(two.muM / one.muM, std::pow(2.0, 0.2), 1e-12);
  EXPECT_NEAR(two.thetaFlm / one.thetaFlm, k, 1e-9);
  EXPECT_NEAR((two.thetaBmax - 353.15) / (one.thetaBmax - 353.15), k, 1e-9);
  EXPECT_NEAR(two.SB, one.SB / k, 1e-9 * one.SB);
}

// At the pitch point there is no sliding, so the local temperature is the bulk one and the
// film is Dowson-Higginson's: h = 1.6 R G^0.6 U^0.7 W^-0.13 (SI, E' = E_r).
TEST(Scuffing, FilmThicknessAtThePitchPointIsDowsonHigginson) {
  ScuffingMesh m = mesh();
  Lubricant oil = vg220();
  ScuffingRating r = rateScuffing(m, oil);
  const PathPoint* c = pitchPoint(r);
  ASSERT_NE(c, nullptr);
  double alphaT = std::atan(std::tan(m.alphaN) / std::cos(m.beta)), betaB = std::asin(std::sin(m.beta) * std::cos(m.alphaN));
  double rb1 = m.z1 * m.mn / std::cos(m.beta) / 2 * std::cos(alphaT), rb2 = rb1 * m.z2 / m.z1;
  double alphaWt = std::acos((rb1 + rb2) / m.a);
  double rho1 = rb1 * std::tan(alphaWt), rho2 = rb2 * std::tan(alphaWt);
  double R = rho1 * rho2 / (rho1 + rho2) / std::cos(betaB);
  double Er = 206e9 / (1 - 0.09);
  double ue = m.speed1 * rho1;  // both surfaces roll at the same speed
  double X = 1 / r.epsAlpha;    // wide helical load sharing away from the ends
  double w = m.Ft * X * m.KA * m.Kv * m.KHalpha * m.KHbeta / (m.b * std::cos(alphaT) * std::cos(betaB));
  double eta38 = oil.kinematic(311.15) * (oil.density15 - 0.7 * (311.15 - 289));  // Pa s
  // A mineral VG 220 oil's pressure-viscosity coefficient is about 2e-8 m^2/N.
  EXPECT_NEAR(2.657e-8 * std::pow(eta38, 0.1348), 2.2e-8, 0.2e-8);
  double h = dowsonHigginson(R, Er, ue, w, r.thetaMmp, oil);
  EXPECT_NEAR(c->h / h, 1.0, 1e-9);
  EXPECT_NEAR(c->lambda, h / m.Ra, 1e-9 * c->lambda);
}

TEST(Scuffing, ViscosityLineThroughItsTwoPoints) {
  Lubricant oil = vg220();
  EXPECT_NEAR(oil.kinematic(40 + kZeroC), 220e-6, 1e-12);
  EXPECT_NEAR(oil.kinematic(100 + kZeroC), 19e-6, 1e-12);
  EXPECT_NEAR(oil.kinematic(80 + kZeroC) * 1e6, ref::kinematicViscosityASTM(220, 19, 80), 1e-9);
}

// The NREL 5 MW planetary stage's planet-ring mesh in the signed convention (the ring's z,
// tip diameter and the centre distance negative), its load as the commercial report's.
ScuffingMesh planetRing() {
  ScuffingMesh m;
  m.z1 = 17;
  m.z2 = -56;
  m.mn = 45e-3;
  m.alphaN = 20 * kPi / 180;
  m.a = -863e-3;
  m.b = 491e-3;
  m.da1 = 905.470e-3;
  m.da2 = -2475.118e-3;
  m.Ft = 779454.877;
  m.KA = 1.25;
  m.Kgamma = 1.1;
  m.Kv = 1.05;
  m.KHbeta = 1.15;
  m.speed1 = 39.86 * kPi / 30; // the planet relative to the carrier
  m.power = m.Ft * m.z1 * m.mn / 2 * m.speed1;
  m.Ra = 0.8e-6;
  m.Ca = {200e-6, 200e-6}; // above C_eff: X_J = 1
  m.grade = 6;
  m.Xmp = 1.5;
  return m;
}

// The path of contact of the planet-ring mesh as the commercial report measures it from the
// planet's tangent point: T1A 105.462, T1C 110.993, T1E 275.277 mm, eps_alpha 1.278.
TEST(ScuffingInternal, PathOfContactAsThePublishedLengths) {
  ScuffingRating r = rateScuffing(planetRing(), vg220());
  EXPECT_NEAR(r.gammaA, 105.462 / 110.993 - 1, 2e-4);
  EXPECT_NEAR(r.gammaE, 275.277 / 110.993 - 1, 2e-4);
  EXPECT_NEAR(r.epsAlpha, 1.278, 1e-3);
}

// Blok's flash temperature from each point's own radii (the ring's flank concave: 1/rho_n =
// 1/rho_1 - 1/|rho_2|) and rolling speeds: the ratio of the factor form to it is one constant
// along the path, and the same as an external mesh's.
TEST(ScuffingInternal, FlashTemperatureFollowsBlokWithTheConcaveFlank) {
  auto ratios = [](const ScuffingMesh& m) {
    ScuffingRating r = rateScuffing(m, vg220());
    const double mt = m.mn * 1e3, rb1 = m.z1 * mt / 2 * std::cos(m.alphaN),
                 rb2 = std::fabs(m.z2) * mt / 2 * std::cos(m.alphaN);
    const double alphaWt = std::acos((rb1 + (m.z2 > 0 ? rb2 : -rb2)) / (m.a * 1e3)),
                 T1T2 = std::fabs(m.a * 1e3) * std::sin(alphaWt);
    const double rhoC1 = rb1 * std::tan(alphaWt), Er = 206000 / (1 - 0.09), omega2 = m.speed1 * m.z1 / std::fabs(m.z2);
    std::vector<double> out;
    for (const auto& q : r.path) {
      if (q.gamma == 0) continue;
      double rho1 = rhoC1 * (1 + q.gamma), rho2 = m.z2 > 0 ? T1T2 - rho1 : T1T2 + rho1;
      double rhoN = m.z2 > 0 ? rho1 * rho2 / (rho1 + rho2) : rho1 * rho2 / (rho2 - rho1);
      double wn = q.XGamma * r.wBt / std::cos(m.alphaN); // the normal load: F_t at the reference circle, spur
      double blok = ref::flashTemperatureBlok(r.muM, wn, m.speed1 * rho1 * 1e-3, omega2 * rho2 * 1e-3, rhoN, Er,
                                              m.BM[0], m.BM[1]);
      out.push_back(q.thetaFla / blok);
    }
    return out;
  };
  ScuffingMesh external = planetRing();
  external.z2 = 56;
  external.a = (17 + 56) * 45e-3 / 2 * std::cos(20 * kPi / 180) / std::cos(24 * kPi / 180);
  external.da2 = (56 + 2) * 45e-3;
  std::vector<double> in = ratios(planetRing()), ex = ratios(external);
  ASSERT_GT(in.size(), 100u);
  for (double x : in)
    EXPECT_NEAR(x / in.front(), 1.0, 1e-9);
  for (double x : ex)
    EXPECT_NEAR(x / ex.front(), 1.0, 1e-9);
  EXPECT_NEAR(in.front() / ex.front(), 1.0, 1e-9);
}

// The micropitting bulk temperature's loss factor H_V with the ring's z negative: 0.161 as
// the commercial report prints it (with +1/56 it would be 0.302), and theta_M from it (a tip
// relief above C_eff: X_Ca = 1 + 0.24 eps_max + 0.71 eps_max^2).
TEST(ScuffingInternal, LossFactorTakesTheRingsTeethNegative) {
  ScuffingMesh m = planetRing();
  ScuffingRating r = rateScuffing(m, vg220());
  const double e1 = (275.277 - 110.993) / 132.846, e2 = (110.993 - 105.462) / 132.846;
  const double HV = (e1 * e1 + e2 * e2 + 1 - (e1 + e2)) * (1 / m.z1 + 1 / m.z2) * kPi;
  EXPECT_NEAR(HV, 0.161, 5e-4);
  const double XCa = 1 + 0.24 * e1 + 0.71 * e1 * e1;
  double rise = 7400 * std::pow(m.power * 1e-3 * r.muMmp * HV / (863 * 491), 0.72) / (1.2 * XCa);
  EXPECT_NEAR(degC(r.thetaMmp) - 80, rise, 2e-3 * rise);
}

// At the pitch point the film is Dowson-Higginson's with the concave flank's relative radius.
TEST(ScuffingInternal, FilmAtThePitchPointWithTheConcaveFlank) {
  ScuffingMesh m = planetRing();
  Lubricant oil = vg220();
  ScuffingRating r = rateScuffing(m, oil);
  const PathPoint* c = pitchPoint(r);
  ASSERT_NE(c, nullptr);
  const double rb1 = 17 * 45e-3 / 2 * std::cos(m.alphaN), rb2 = 56 * 45e-3 / 2 * std::cos(m.alphaN);
  const double alphaWt = std::acos((rb2 - rb1) / 0.863), rho1 = rb1 * std::tan(alphaWt), rho2 = rb2 * std::tan(alphaWt);
  const double R = rho1 * rho2 / (rho2 - rho1), Er = 206e9 / (1 - 0.09), ue = m.speed1 * rho1;
  const double w = m.Ft * c->XGamma * m.loadFactor() / (m.b * std::cos(m.alphaN));
  EXPECT_NEAR(c->h / dowsonHigginson(R, Er, ue, w, r.thetaMmp, oil), 1.0, 1e-9);
}

// A ring with fewer teeth than its pinion, or a sign left positive, is refused with a sentence.
TEST(ScuffingInternal, InconsistentSignsAreRefused) {
  ScuffingMesh m = planetRing();
  m.da2 = -m.da2;
  EXPECT_THROW(rateScuffing(m, vg220()), std::domain_error);
  m = planetRing();
  m.z2 = -12;
  EXPECT_THROW(rateScuffing(m, vg220()), std::domain_error);
}

} // namespace
