// DIN 743 shaft strength against the check values of two worked solutions (S2: a shoulder in
// load case 1; S4: a V-notch, static) and, factor by factor, against the independent reference
// (Din743Reference.h) for every notch kind both know.
#include <gtest/gtest.h>

#include <cmath>

#include "Din743Cases.h"
#include "Din743Reference.h"
#include "shaft/Din743.h"

using namespace gbx::rt::shaft::din743;

namespace {

// |x - printed| <= half a unit in the printed value's last digit.
void expectPrinted(double x, double printed, int decimals) {
  EXPECT_NEAR(x, printed, 0.5 * std::pow(10.0, -decimals)) << "printed " << printed;
}

constexpr double MPa = 1e6;

struct Case {
  Notch notch;
  Material material;
  std::array<Load, 3> loads;
  Settings settings;
};

// S2: 50CrMo4, shoulder 84/100 r 4, d_eff 100, load case 1, Rz 10 um.
Case s2() {
  Case c;
  c.notch = {NotchKind::Shoulder, 0.084, 0.100, 0.004, 0, 0, 1, 10e-6};
  c.material = {1100 * MPa, 900 * MPa, Group::QuenchedTempered};
  c.loads = {Load{443341.6, 0, 443341.6}, Load{23275.43, 2909.429, 26184.86}, Load{13965.26, 0, 13965.26}};
  c.settings = {1, 0.100, false, 1};
  return c;
}

// S4: S235, a V-notch 10 mm deep in an 80 mm shaft, d_eff 80, load case 2, static only.
Case s4() {
  Case c;
  c.notch = {NotchKind::VNotch, 0.060, 0.080, 0, 0.010, 0, 1, 25e-6};
  c.material = {360 * MPa, 235 * MPa, Group::Structural};
  c.loads = {Load{40000, 0, 60000}, Load{12666.667, 0, 19000}, Load{}};
  c.settings = {2, 0.080, false, 1};
  return c;
}

Result rateCase(const Case& c) { return rate(c.notch, c.material, c.loads, c.settings); }

} // namespace

TEST(Din743, S2ShoulderSafetiesAsPrinted) {
  auto r = rateCase(s2());
  expectPrinted(r.SD, 2.373, 3);
  expectPrinted(r.SF, 1.464, 3);
}

TEST(Din743, S2IntermediateFactorsAsPrinted) {
  auto r = rateCase(s2());
  expectPrinted(r.f[Tension].mean / MPa, 80, 0);
  expectPrinted(r.f[Bending].mean / MPa, 400, 0);
  expectPrinted(r.f[Bending].amplitude / MPa, 50, 0);
  expectPrinted(r.f[Torsion].mean / MPa, 120, 0);
  expectPrinted(r.f[Tension].beta, 2.0925, 4);
  expectPrinted(r.f[Bending].beta, 1.9167, 4);
  expectPrinted(r.f[Torsion].beta, 1.4515, 4);
  expectPrinted(r.f[Bending].K2, 0.83871, 5);
  EXPECT_EQ(r.f[Tension].K2, 1.0);
  expectPrinted(r.K1B, 0.79307, 5);
  expectPrinted(r.K1S, 0.72940, 5);
}

TEST(Din743, S4VNotchStaticSafetyAsPrinted) {
  auto r = rateCase(s4());
  expectPrinted(r.SF, 0.274, 3);
  EXPECT_TRUE(std::isinf(r.SD)); // no amplitude: nothing to fatigue
  EXPECT_EQ(r.K1B, 1.0);
}

// Every factor against the reference, which is written from the standard's text alone.
void expectSameAsReference(const Case& c, const gbx::test::Din743Input& in) {
  auto r = rateCase(c);
  auto ref = gbx::test::din743Reference(in);
  auto near = [](double a, double b, const char* what) {
    if (std::isnan(b)) return;
    if (std::isinf(b)) {
      EXPECT_EQ(a, b) << what;
      return;
    }
    EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::fabs(b))) << what;
  };
  near(r.K1B, ref.K1B, "K1B");
  near(r.K1S, ref.K1S, "K1S");
  near(r.phi, ref.phi, "phi");
  near(r.sigmaMv / MPa, ref.sigmaMv, "sigma_mv");
  const gbx::test::Din743LoadFactors* rf[3] = {&ref.tension, &ref.bending, &ref.torsion};
  for (int k = 0; k < 3; ++k) {
    const auto& f = r.f[k];
    const auto& g = *rf[k];
    SCOPED_TRACE(k);
    near(f.mean / MPa, g.nominal.mean, "mean");
    near(f.amplitude / MPa, g.nominal.amplitude, "amplitude");
    near(f.max / MPa, g.nominal.max, "max");
    near(f.K2, g.K2, "K2");
    near(f.beta, g.beta, "beta");
    near(f.KF, g.KF, "K_F");
    near(f.K, g.K, "K");
    near(f.sigmaWK / MPa, g.sigmaWK, "sigma_WK");
    near(f.psi, g.psi, "psi");
    near(f.sigmaFK / MPa, g.sigmaFK, "sigma_FK");
    near(f.gammaF, g.gammaF, "gamma_F");
    if (f.alpha > 0) {
      near(f.alpha, g.alpha, "alpha");
      near(f.n, g.n, "n");
    }
  }
  near(r.SD, ref.SD, "S_D");
  near(r.SF, ref.SF, "S_F");
}

TEST(Din743, ShoulderAndVNotchFactorByFactorAsTheReference) {
  using namespace gbx::test;
  Din743Input a = din743S2Input();
  expectSameAsReference(s2(), a);
  // The same shoulder in load case 2 with a torque amplitude too.
  Case c = s2();
  c.settings.loadCase = 2;
  c.loads[Torsion] = {13965.26, 3000, 16965.26};
  a.loadCase = Din743LoadCase::two;
  a.torsionNm = {13965.26, 3000, 16965.26};
  expectSameAsReference(c, a);
  Din743Input b = din743S4Input();
  expectSameAsReference(s4(), b);
  // The V-notch with a bending amplitude, in both load cases.
  for (int lc : {1, 2}) {
    Case v = s4();
    v.settings.loadCase = lc;
    v.loads[Bending] = {6000, 3000, 9000};
    b.loadCase = lc == 1 ? Din743LoadCase::one : Din743LoadCase::two;
    b.bendingNm = {6000.0, 3000.0, 9000.0};
    expectSameAsReference(v, b);
  }
}

TEST(Din743, ImpossibleGeometryIsRefused) {
  Case c = s2();
  c.notch.radius = 0;
  EXPECT_THROW(rateCase(c), std::invalid_argument);
  c = s2();
  c.notch.D = c.notch.d;
  EXPECT_THROW(rateCase(c), std::invalid_argument);
  c = s2();
  c.notch.kind = NotchKind::Hole;
  c.notch.holeDiameter = 0.1;
  EXPECT_THROW(rateCase(c), std::invalid_argument);
  c = s2();
  c.material.tensile = 0;
  EXPECT_THROW(rateCase(c), std::invalid_argument);
}

// Groove, hole, keyway (one and two keys) and press fit: 42CrMo4 at d 50 mm, d_eff 60, a
// bending amplitude with a steady torque, in both load cases.
TEST(Din743, GrooveHoleKeywayAndPressFitFactorByFactorAsTheReference) {
  using namespace gbx::test;
  struct Kind {
    Notch notch;
    Din743Notch ref;
  };
  const Kind kinds[] = {
      {{NotchKind::Groove, 0.050, 0.055, 0.0015, 0.0025, 0, 1, 8e-6}, Din743Groove{55.0, 50.0, 1.5}},
      {{NotchKind::Hole, 0.050, 0.050, 0, 0, 0.008, 1, 8e-6}, Din743TransverseHole{50.0, 8.0}},
      {{NotchKind::Keyway, 0.050, 0.050, 0, 0, 0, 1, 8e-6}, Din743Keyway{50.0, 1}},
      {{NotchKind::Keyway, 0.050, 0.050, 0, 0, 0, 2, 8e-6}, Din743Keyway{50.0, 2}},
      {{NotchKind::PressFit, 0.050, 0.050, 0, 0, 0, 1, 8e-6}, Din743PressFit{50.0}},
  };
  for (const auto& k : kinds)
    for (int lc : {1, 2}) {
      SCOPED_TRACE(std::string(notchName(k.notch.kind)) + " load case " + std::to_string(lc));
      Case c;
      c.notch = k.notch;
      c.material = {1100 * MPa, 900 * MPa, Group::QuenchedTempered};
      c.loads = {Load{}, Load{0, 800, 1200}, Load{1000, 0, 1500}};
      c.settings = {lc, 0.060, false, 1};
      Din743Input in;
      in.material = {1100.0, 900.0, Din743SteelGroup::quenched_tempered};
      in.dEff = 60.0;
      in.notch = k.ref;
      in.bendingNm = {0.0, 800.0, 1200.0};
      in.torsionNm = {1000.0, 0.0, 1500.0};
      in.loadCase = lc == 1 ? Din743LoadCase::one : Din743LoadCase::two;
      in.rzUm = 8.0;
      expectSameAsReference(c, in);
    }
}

// Load case 1 with a mean stress past the yield line: the section bears no amplitude, S_D 0
// (not the positive number a negative sigma_ADK squared away would give).
TEST(Din743, LoadCaseOnePastTheYieldLineBearsNoAmplitude) {
  Case c = s2();
  c.loads[Bending] = {60000, 3000, 63000};
  auto r = rateCase(c);
  EXPECT_EQ(r.SD, 0);
  EXPECT_FALSE(r.warnings.empty());
}

// A hollow section's K2F (1.1 bending, 1.0 torsion) and a hardened layer's (1, and no gamma_F).
TEST(Din743, HollowAndHardenedYieldFactors) {
  Case c = s2();
  c.notch.bore = 0.030;
  auto r = rateCase(c);
  EXPECT_EQ(r.f[Bending].K2F, 1.1);
  EXPECT_EQ(r.f[Torsion].K2F, 1.0);
  c = s2();
  c.settings.hardened = true;
  r = rateCase(c);
  EXPECT_EQ(r.f[Bending].K2F, 1.0);
  EXPECT_EQ(r.f[Bending].gammaF, 1.0);
  EXPECT_EQ(r.f[Bending].KF, 1.0);
}
