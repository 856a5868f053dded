#pragma once
// Independent reference (test oracle) for the DIN 743:2012 fatigue (S_D) and static (S_F) safety of
// a solid round shaft at one notch. Written from the published formulas of DIN 743-1, -2 and -3
// (2012 editions). Lengths in mm, forces in N, moments in N·m, stresses in N/mm^2.
//
// Sequence (DIN 743-1 clause 7, DIN 743-2, DIN 743-3):
//   nominal stresses at the notch diameter d
//   -> K1(d_eff) for sigma_B and sigma_S (743-2), sigma_B(d) = K1B sigma_B(d_B) etc.
//   -> K2(d) (743-2; 1 in tension)
//   -> beta: shoulder, round groove, transverse hole: beta = alpha / n (743-2 4.3, form factor
//            fits clause 5, G' table);
//            V-notch, keyway, press fit: experimental beta(d_BK) scaled by K3(d_BK)/K3(d) (743-2 4.2)
//   -> K_F (743-2), K_V, K = (beta/K2 + 1/K_F - 1)/K_V (743-1 eq. 8, 9)
//   -> sigma_WK = sigma_W(d_B) K1B / K (743-1 eq. 5-7), sigma_W(d_B) = 0.4/0.5/0.3 sigma_B(d_B) (743-3)
//   -> psi = sigma_WK / (2 K1B sigma_B(d_B) - sigma_WK) (743-1 eq. 20-22)
//   -> sigma_mv, tau_mv (743-1 eq. 23, 24); sigma_ADK for load case 1 or 2 (743-1)
//   -> sigma_FK = K1S K2F gamma_F sigma_S(d_B) (743-1 eq. 31, 32, K2F Table 3; tau: / sqrt 3)
//   -> S_D, S_F (743-1 eq. 1, 2).
//
// Choices where the published text leaves room (each reproduces the DOMAIN §12 check values):
//  * gamma_F (743-1 Table 2) is read with the form factor alpha where one exists (shoulder, round
//    groove); for notches with only an experimental beta (V-notch, press fit) it is read with beta.
//    Table 2 applies to circumferential notches only: for a transverse hole and a keyway (not
//    circumferential) gamma_F = 1. Torsion: 1.0.
//    Bands: <= 1.5: 1.00; (1.5, 2]: 1.05; (2, 3]: 1.10; > 3: 1.15.
//  * V-notch beta(d_BK), d_BK = 15 mm (743-2 4.2): tension 0.109 sigma_B(d)/100 + 1.074,
//    bending 0.0923 sigma_B(d)/100 + 0.985, torsion 0.8 beta_b(d_BK); K3 per load type with its
//    own beta(d_BK). Roughness: by default K_F(Rz)/K_F(20 um) (test pieces at Rz 20 um).
//  * Load case 2 with a zero amplitude for a load type: that type adds nothing to S_D and its
//    sigma_ADK is reported as NaN (undefined). No amplitude at all: S_D = +inf.
//  * Surface not hardened (n with 10^-(0.33 + sigma_S(d)/712), K2F 1.0 / 1.2 / 1.2).
//
// Further notch kinds (written from memory of DIN 743-2:2012; the confidence of each coefficient is
// stated where it is used):
//  * Round circumferential groove (Rundnut, 743-2 clause 5 / Table 2 fits, Table 3 G'):
//    alpha = 1 + 1/sqrt(A r/t + B r/d (1 + 2 r/d)^2), t = (D - d)/2, (A, B) = tension (0.22, 2.74),
//    bending (0.20, 5.5), torsion (0.70, 20.6); G' = 2/r (1 + phi) (tension, bending), 1/r (torsion),
//    phi as for the shoulder. K_F from Rz (743-2 eq. for K_F), gamma_F from alpha.
//  * Transverse hole (Querbohrung, 743-2 clause 5 fits, Table 3 G'), nominal stresses on the net
//    section: A = pi d^2/4 - d_L d, W_b = pi d^3/32 - d_L d^2/6, W_t = pi d^3/16 - d_L d^2/6;
//    alpha_zd = 3 - d_L/d, alpha_b = 3 + 1.4 d_L/d - 2.8 sqrt(d_L/d), alpha_t = 2.023 - 1.125 sqrt(d_L/d);
//    G' (r = d_L/2) = 2.3/r (tension), 2.3/r + 2/d (bending), 1.15/r + 2/d (torsion), no phi term.
//    K_F from Rz, gamma_F = 1 (not circumferential).
//  * Keyway (Passfeder, end-milled keyseat, 743-2 Table 1), d_BK = 40 mm:
//    beta_sigma(d_BK) = 3.0 (sigma_B(d)/1000)^0.38 (tension and bending), beta_tau(d_BK) =
//    0.56 beta_sigma(d_BK) + 0.1; two keys: both times 1.15. K_F = 1 (roughness is contained in the
//    experimental beta of the shaft-hub connections, 743-2 Table 1), gamma_F = 1 (not circumferential).
//  * Press fit (Pressverband, 743-2 Table 1), d_BK = 40 mm: beta_sigma(d_BK) = 2.7 (sigma_B(d)/1000)^0.43
//    (tension and bending), beta_tau(d_BK) = 0.65 beta_sigma(d_BK). K_F = 1, gamma_F from beta.
//  * Experimental beta (V-notch, keyway, press fit) is brought to d by K3(d_BK)/K3(d), K3 evaluated
//    (743-2 clause 4.2) with that load type's own beta(d_BK) in place of alpha.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <variant>

namespace gbx::test {

enum class Din743SteelGroup { quenched_tempered, structural, case_hardening };
enum class Din743LoadCase { one = 1, two = 2 };

// Strengths at the material's reference diameter d_B (743-3 tables).
struct Din743Material {
  double sigmaB = 0; // sigma_B(d_B), N/mm^2
  double sigmaS = 0; // sigma_S(d_B), N/mm^2
  Din743SteelGroup group = Din743SteelGroup::quenched_tempered;
};

// Shoulder: small diameter d, large diameter D, fillet radius r (mm).
struct Din743Shoulder {
  double d = 0, D = 0, r = 0;
};

// Circumferential V-notch: outer diameter D, root diameter d (mm).
struct Din743VNotch {
  double D = 0, d = 0;
};

// Round circumferential groove (Rundnut): outer diameter D, root diameter d, groove radius r (mm).
struct Din743Groove {
  double D = 0, d = 0, r = 0;
};

// Transverse (radial through) hole (Querbohrung): shaft diameter d, hole diameter dL (mm).
struct Din743TransverseHole {
  double d = 0, dL = 0;
};

// Keyway for a parallel key, keyseat end-milled (Passfeder, Fingerfraeser): shaft diameter d (mm),
// one or two keys (any other number gives NaN results).
struct Din743Keyway {
  double d = 0;
  int keys = 1;
};

// Press fit (Pressverband) of a hub on the shaft: shaft diameter d at the fit (mm).
struct Din743PressFit {
  double d = 0;
};

using Din743Notch =
    std::variant<Din743Shoulder, Din743VNotch, Din743Groove, Din743TransverseHole, Din743Keyway, Din743PressFit>;

// One load type: mean, amplitude and maximum. Without max, max = |mean| + amplitude.
struct Din743Load {
  double mean = 0;
  double amplitude = 0;
  std::optional<double> max;
};

struct Din743Input {
  Din743Material material;
  double dEff = 0; // diameter governing heat treatment (K1), mm
  Din743Notch notch = Din743Shoulder{};
  Din743Load tensionN;  // axial force, N
  Din743Load bendingNm; // bending moment, N·m
  Din743Load torsionNm; // torque, N·m
  Din743LoadCase loadCase = Din743LoadCase::one;
  double rzUm = 1.0; // surface roughness Rz, um
  double KV = 1.0;   // surface hardening factor (1: none)
  bool vNotchKFRelativeToRz20 = true;
};

struct Din743Stress {
  double mean = 0, amplitude = 0, max = 0; // N/mm^2
};

// Every factor of one load type (tension/compression, bending or torsion).
struct Din743LoadFactors {
  Din743Stress nominal;
  double K2 = 1;                                             // geometric size factor
  // alpha, Gprime, n: notches with a form factor (shoulder, groove, transverse hole).
  // betaDBK, K3dBK, K3d: notches with an experimental beta (V-notch, keyway, press fit).
  double alpha = std::numeric_limits<double>::quiet_NaN();   // form factor (shoulder)
  double Gprime = std::numeric_limits<double>::quiet_NaN();  // related stress gradient, 1/mm (shoulder)
  double n = std::numeric_limits<double>::quiet_NaN();       // support number (shoulder)
  double betaDBK = std::numeric_limits<double>::quiet_NaN(); // experimental beta at d_BK (V-notch)
  double K3dBK = std::numeric_limits<double>::quiet_NaN();   // K3(d_BK) (V-notch)
  double K3d = std::numeric_limits<double>::quiet_NaN();     // K3(d) (V-notch)
  double beta = 1;                                           // fatigue notch factor
  double KF = 1;                                             // roughness factor
  double K = 1;                                              // total influence factor
  double sigmaW = 0;                                         // sigma_W(d_B) K1B: material fatigue strength at d_eff
  double sigmaWK = 0;                                        // component fatigue strength
  double psi = 0;                                            // mean stress sensitivity
  double sigmaADK = 0;                                       // amplitude strength for the chosen load case
  double K2F = 1;                                            // static support factor
  double gammaF = 1;                                         // yield increase factor
  double sigmaFK = 0;                                        // component yield limit
};

struct Din743Result {
  double K1B = 1, K1S = 1;         // K1(d_eff) for sigma_B and sigma_S
  double sigmaBd = 0, sigmaSd = 0; // sigma_B(d) = K1B sigma_B(d_B), sigma_S(d) = K1S sigma_S(d_B)
  double phi = 0;                  // shoulder / groove gradient term (743-2 G' table)
  double dBK = std::numeric_limits<double>::quiet_NaN(); // test-piece diameter of an experimental beta, mm
  bool circumferential = true;     // notch runs round the shaft (gamma_F of 743-1 Table 2 applies)
  double area = 0, Wb = 0, Wt = 0; // section at the notch (net section for a transverse hole), mm^2, mm^3
  double KV = 1;
  double sigmaMv = 0, tauMv = 0; // equivalent mean stresses (743-1 eq. 23, 24)
  Din743LoadFactors tension, bending, torsion;
  double SD = 0; // fatigue safety
  double SF = 0; // static safety
};

namespace din743detail {

inline double lg(double x) { return std::log10(x); }

// K1(d_eff), DIN 743-2 (d_B = 16 mm). forYield selects the sigma_S row.
inline double K1(Din743SteelGroup g, double dEff, bool forYield) {
  switch (g) {
  case Din743SteelGroup::quenched_tempered:
    if (dEff <= 16) return 1.0;
    if (dEff < 300) return 1.0 - (forYield ? 0.34 : 0.26) * lg(dEff / 16);
    return forYield ? 0.57 : 0.67;
  case Din743SteelGroup::structural:
    if (forYield) { // 2 d_B = 32 mm
      if (dEff <= 32) return 1.0;
      if (dEff < 300) return 1.0 - 0.26 * lg(dEff / 32);
      return 0.75;
    }
    if (dEff <= 100) return 1.0;
    if (dEff < 300) return 1.0 - 0.23 * lg(dEff / 100);
    return 0.89;
  case Din743SteelGroup::case_hardening: // other than CrNiMo grades
    if (dEff <= 16) return 1.0;
    if (dEff < 150) return 1.0 - 0.41 * lg(dEff / 16);
    return 0.6;
  }
  return 1.0;
}

// K2(d) for bending and torsion, DIN 743-2 (tension: 1).
inline double K2(double d) {
  if (d < 7.5) return 1.0;
  if (d < 150) return 1.0 - 0.2 * lg(d / 7.5) / lg(20.0);
  return 0.8;
}

// K3(d) for a notch factor x (alpha or beta), DIN 743-2 clause 4.2.
inline double K3(double d, double x) {
  if (d < 7.5) return 1.0;
  if (d < 150) return 1.0 - 0.2 * lg(x) * lg(d / 7.5) / lg(20.0);
  return 1.0 - 0.2 * lg(x);
}

// K_F sigma, DIN 743-2 (Rz in um, sigma_B(d) in N/mm^2); K_F tau = 0.575 K_F sigma + 0.425.
inline double KFsigma(double rzUm, double sigmaBd) {
  const double rz = std::max(rzUm, 1.0);
  return 1.0 - 0.22 * lg(rz) * (lg(sigmaBd / 20.0) - 1.0);
}
inline double KFtau(double rzUm, double sigmaBd) { return 0.575 * KFsigma(rzUm, sigmaBd) + 0.425; }

// Shoulder form factor fit, DIN 743-2 clause 5, t = (D - d)/2:
// alpha = 1 + 1 / sqrt(a r/t + b r/d (1 + 2 r/d)^2 + c (r/t)^z d/D), with (a, b, c, z) =
// tension (0.62, 7, 0, -), bending (0.62, 11.6, 0.2, 3), torsion (3.4, 38, 1, 2).
inline double shoulderAlpha(double a, double b, double c, double z, double d, double D, double r) {
  const double t = 0.5 * (D - d);
  const double rd = r / d;
  const double rt = r / t;
  const double s = a * rt + b * rd * (1 + 2 * rd) * (1 + 2 * rd) + c * std::pow(rt, z) * d / D;
  return 1.0 + 1.0 / std::sqrt(s);
}

// Round groove form factor fit, DIN 743-2 clause 5 (same form as the shoulder with c = 0):
// alpha = 1 + 1 / sqrt(a r/t + b r/d (1 + 2 r/d)^2), (a, b) = tension (0.22, 2.74), bending (0.20, 5.5),
// torsion (0.70, 20.6). Confidence: good (the b values are often printed halved, 1.37 / 2.75 / 10.3,
// with the fit written 2 b r/d ...). Range of the fit: r/t >= 0.03, d/D <= 0.98.
inline double grooveAlpha(double a, double b, double d, double D, double r) {
  return shoulderAlpha(a, b, 0.0, 0.0, d, D, r);
}

// Transverse hole form factors, DIN 743-2 clause 5, x = d_L/d (fits for about x <= 0.4), referred to the
// net-section nominal stresses. Confidence: good for the torsion fit, fair for tension and bending.
inline double holeAlphaTension(double x) { return 3.0 - x; }
inline double holeAlphaBending(double x) { return 3.0 + 1.4 * x - 2.8 * std::sqrt(x); }
inline double holeAlphaTorsion(double x) { return 2.023 - 1.125 * std::sqrt(x); }

// Experimental beta of the shaft-hub connections at d_BK = 40 mm, DIN 743-2 Table 1 (sigma_B(d) in N/mm^2).
// Keyway (end-milled keyseat): beta_sigma = 3.0 (sigma_B(d)/1000)^0.38, beta_tau = 0.56 beta_sigma + 0.1.
// Press fit: beta_sigma = 2.7 (sigma_B(d)/1000)^0.43, beta_tau = 0.65 beta_sigma.
// Confidence: good for these four formulas. Two keys: Table 1 footnote raises beta by 1.15; whether it
// raises beta_tau(d_BK) itself or only through 0.56 (1.15 beta_sigma) + 0.1 I am not sure (0.015
// apart); here both beta_sigma(d_BK) and beta_tau(d_BK) are multiplied by 1.15.
inline double keywayBetaSigma(double sigmaBd) { return 3.0 * std::pow(sigmaBd / 1000.0, 0.38); }
inline double keywayBetaTau(double sigmaBd) { return 0.56 * keywayBetaSigma(sigmaBd) + 0.1; }
inline double pressFitBetaSigma(double sigmaBd) { return 2.7 * std::pow(sigmaBd / 1000.0, 0.43); }
inline double pressFitBetaTau(double sigmaBd) { return 0.65 * pressFitBetaSigma(sigmaBd); }

// Experimental beta(d_BK) brought to d, DIN 743-2 clause 4.2: beta(d) = beta(d_BK) K3(d_BK) / K3(d),
// K3 evaluated with beta(d_BK) in place of alpha.
inline void scaleExperimentalBeta(Din743LoadFactors& f, double betaDBK, double dBK, double d) {
  f.betaDBK = betaDBK;
  f.K3dBK = K3(dBK, betaDBK);
  f.K3d = K3(d, betaDBK);
  f.beta = f.betaDBK * f.K3dBK / f.K3d;
}

// Support number n, DIN 743-2 clause 4.3 (surface not hardened), G' in 1/mm, sigma_S(d) in N/mm^2.
inline double supportNumber(double Gprime, double sigmaSd) {
  return 1.0 + std::sqrt(Gprime) * std::pow(10.0, -(0.33 + sigmaSd / 712.0));
}

// Yield increase factor gamma_F, DIN 743-1 Table 2 (tension and bending).
inline double gammaF(double x) {
  if (x <= 1.5) return 1.0;
  if (x <= 2.0) return 1.05;
  if (x <= 3.0) return 1.10;
  return 1.15;
}

inline Din743Stress stress(const Din743Load& l, double section) {
  const double max = l.max ? *l.max : std::abs(l.mean) + std::abs(l.amplitude);
  return {l.mean / section, l.amplitude / section, max / section};
}

// Amplitude strength, DIN 743-1.
// Load case 1 (mean constant): sigma_ADK = sigma_WK - psi sigma_mv, or sigma_FK - sigma_mv past the yield line.
// Load case 2 (mean/amplitude constant): sigma_WK / (1 + psi sigma_mv/sigma_a), or sigma_FK / (1 + sigma_mv/sigma_a).
inline double amplitudeStrength(Din743LoadCase lc, double mv, double a, double WK, double FK, double psi) {
  if (lc == Din743LoadCase::one) {
    if (mv <= (FK - WK) / (1.0 - psi)) return WK - psi * mv;
    return FK - mv;
  }
  if (a <= 0) return std::numeric_limits<double>::quiet_NaN();
  const double k = mv / a;
  if (k <= (FK - WK) / (WK - psi * FK)) return WK / (1.0 + psi * k);
  return FK / (1.0 + k);
}

} // namespace din743detail

inline Din743Result din743Reference(const Din743Input& in) {
  using namespace din743detail;
  Din743Result r;
  const auto& mat = in.material;

  // Notch diameter (every notch kind names it d) and section moduli of the solid section.
  const double d = std::visit([](const auto& n) { return n.d; }, in.notch);
  const auto* shoulderP = std::get_if<Din743Shoulder>(&in.notch);
  const auto* vNotchP = std::get_if<Din743VNotch>(&in.notch);
  const auto* grooveP = std::get_if<Din743Groove>(&in.notch);
  const auto* holeP = std::get_if<Din743TransverseHole>(&in.notch);
  const auto* keywayP = std::get_if<Din743Keyway>(&in.notch);
  const auto* pressFitP = std::get_if<Din743PressFit>(&in.notch);
  double area = std::numbers::pi * d * d / 4.0;
  double Wb = std::numbers::pi * d * d * d / 32.0;
  double Wt = 2.0 * Wb;
  if (holeP) {
    // DIN 743-2: nominal stresses of a transverse hole on the net section (hole through the axis).
    const double dL = holeP->dL;
    area = std::numbers::pi * d * d / 4.0 - dL * d;
    Wb = std::numbers::pi * d * d * d / 32.0 - dL * d * d / 6.0;
    Wt = std::numbers::pi * d * d * d / 16.0 - dL * d * d / 6.0;
  }
  r.area = area;
  r.Wb = Wb;
  r.Wt = Wt;
  r.tension.nominal = stress(in.tensionN, area);
  r.bending.nominal = stress(in.bendingNm, Wb / 1000.0);
  r.torsion.nominal = stress(in.torsionNm, Wt / 1000.0);

  // Technological size factor and strengths at d_eff.
  r.K1B = K1(mat.group, in.dEff, false);
  r.K1S = K1(mat.group, in.dEff, true);
  r.sigmaBd = r.K1B * mat.sigmaB;
  r.sigmaSd = r.K1S * mat.sigmaS;

  // Geometric size factor.
  r.tension.K2 = 1.0;
  r.bending.K2 = K2(d);
  r.torsion.K2 = K2(d);

  // Roughness factor.
  double kfs = KFsigma(in.rzUm, r.sigmaBd);
  double kft = KFtau(in.rzUm, r.sigmaBd);

  if (shoulderP) {
    const auto& s = *shoulderP;
    const double t = 0.5 * (s.D - s.d);
    r.tension.alpha = shoulderAlpha(0.62, 7.0, 0.0, 0.0, s.d, s.D, s.r);
    r.bending.alpha = shoulderAlpha(0.62, 11.6, 0.2, 3.0, s.d, s.D, s.r);
    r.torsion.alpha = shoulderAlpha(3.4, 38.0, 1.0, 2.0, s.d, s.D, s.r);
    // DIN 743-2 G' table: phi for d/D > 0.67, else 0.
    r.phi = (s.d / s.D > 0.67 && s.r > 0) ? 1.0 / (4.0 * std::sqrt(t / s.r) + 2.0) : 0.0;
    r.tension.Gprime = 2.3 / s.r * (1.0 + r.phi);
    r.bending.Gprime = 2.3 / s.r * (1.0 + r.phi);
    r.torsion.Gprime = 1.15 / s.r;
  } else if (vNotchP) {
    // DIN 743-2 4.2: experimental beta at d_BK = 15 mm, scaled to d with K3.
    constexpr double dBK = 15.0;
    r.dBK = dBK;
    const double bending = 0.0923 * r.sigmaBd / 100.0 + 0.985;
    scaleExperimentalBeta(r.tension, 0.109 * r.sigmaBd / 100.0 + 1.074, dBK, d);
    scaleExperimentalBeta(r.bending, bending, dBK, d);
    scaleExperimentalBeta(r.torsion, 0.8 * bending, dBK, d);
    if (in.vNotchKFRelativeToRz20) {
      kfs /= KFsigma(20.0, r.sigmaBd);
      kft /= KFtau(20.0, r.sigmaBd);
    }
  } else if (grooveP) {
    // DIN 743-2 clause 5 fits and Table 3 G' for a round groove; beta = alpha / n (4.3).
    const auto& g = *grooveP;
    const double t = 0.5 * (g.D - g.d);
    r.tension.alpha = grooveAlpha(0.22, 2.74, g.d, g.D, g.r);
    r.bending.alpha = grooveAlpha(0.20, 5.5, g.d, g.D, g.r);
    r.torsion.alpha = grooveAlpha(0.70, 20.6, g.d, g.D, g.r);
    // G' = 2/r (1 + phi) for tension and bending, 1/r for torsion (confidence: good for the 2/r, 1/r;
    // the phi term for d/D > 0.67 as for the shoulder).
    r.phi = (g.d / g.D > 0.67 && g.r > 0) ? 1.0 / (4.0 * std::sqrt(t / g.r) + 2.0) : 0.0;
    r.tension.Gprime = 2.0 / g.r * (1.0 + r.phi);
    r.bending.Gprime = 2.0 / g.r * (1.0 + r.phi);
    r.torsion.Gprime = 1.0 / g.r;
  } else if (holeP) {
    // DIN 743-2 clause 5 fits and Table 3 G' for a transverse hole, r = d_L/2; beta = alpha / n.
    // G': 2.3/r (tension), 2.3/r + 2/d (bending), 1.15/r + 2/d (torsion); confidence: fair (the 2/d
    // terms of bending and torsion are as I remember them, not checked against the printed table).
    r.circumferential = false;
    const double x = holeP->dL / d;
    const double rh = 0.5 * holeP->dL;
    r.tension.alpha = holeAlphaTension(x);
    r.bending.alpha = holeAlphaBending(x);
    r.torsion.alpha = holeAlphaTorsion(x);
    r.tension.Gprime = 2.3 / rh;
    r.bending.Gprime = 2.3 / rh + 2.0 / d;
    r.torsion.Gprime = 1.15 / rh + 2.0 / d;
  } else if (keywayP) {
    // DIN 743-2 Table 1: experimental beta at d_BK = 40 mm (test pieces of the connection, roughness
    // included: K_F = 1). Not circumferential: gamma_F = 1.
    constexpr double dBK = 40.0;
    r.dBK = dBK;
    r.circumferential = false;
    const int keys = keywayP->keys;
    const double kk = keys == 1 ? 1.0 : keys == 2 ? 1.15 : std::numeric_limits<double>::quiet_NaN();
    scaleExperimentalBeta(r.tension, kk * keywayBetaSigma(r.sigmaBd), dBK, d);
    scaleExperimentalBeta(r.bending, kk * keywayBetaSigma(r.sigmaBd), dBK, d);
    scaleExperimentalBeta(r.torsion, kk * keywayBetaTau(r.sigmaBd), dBK, d);
    kfs = 1.0;
    kft = 1.0;
  } else if (pressFitP) {
    // DIN 743-2 Table 1: experimental beta at d_BK = 40 mm, K_F = 1; circumferential.
    constexpr double dBK = 40.0;
    r.dBK = dBK;
    scaleExperimentalBeta(r.tension, pressFitBetaSigma(r.sigmaBd), dBK, d);
    scaleExperimentalBeta(r.bending, pressFitBetaSigma(r.sigmaBd), dBK, d);
    scaleExperimentalBeta(r.torsion, pressFitBetaTau(r.sigmaBd), dBK, d);
    kfs = 1.0;
    kft = 1.0;
  }
  // A notch with a form factor: beta = alpha / n (743-2 4.3).
  if (shoulderP || grooveP || holeP)
    for (auto* f : {&r.tension, &r.bending, &r.torsion}) {
      f->n = supportNumber(f->Gprime, r.sigmaSd);
      f->beta = f->alpha / f->n;
    }
  r.tension.KF = kfs;
  r.bending.KF = kfs;
  r.torsion.KF = kft;

  // Total influence factor and component fatigue strength (sigma_W(d_B) from DIN 743-3).
  r.KV = in.KV;
  r.tension.sigmaW = 0.4 * mat.sigmaB * r.K1B;
  r.bending.sigmaW = 0.5 * mat.sigmaB * r.K1B;
  r.torsion.sigmaW = 0.3 * mat.sigmaB * r.K1B;
  for (auto* f : {&r.tension, &r.bending, &r.torsion}) {
    f->K = (f->beta / f->K2 + 1.0 / f->KF - 1.0) / r.KV;
    f->sigmaWK = f->sigmaW / f->K;
    f->psi = f->sigmaWK / (2.0 * r.K1B * mat.sigmaB - f->sigmaWK);
  }

  // Yield limits.
  r.tension.K2F = 1.0;
  r.bending.K2F = 1.2;
  r.torsion.K2F = 1.2;
  // gamma_F (743-1 Table 2): circumferential notches only; read with alpha where the notch has one.
  if (r.circumferential) {
    const bool hasAlpha = shoulderP || grooveP;
    r.tension.gammaF = gammaF(hasAlpha ? r.tension.alpha : r.tension.beta);
    r.bending.gammaF = gammaF(hasAlpha ? r.bending.alpha : r.bending.beta);
  } else {
    r.tension.gammaF = 1.0;
    r.bending.gammaF = 1.0;
  }
  r.torsion.gammaF = 1.0;
  r.tension.sigmaFK = r.K1S * r.tension.K2F * r.tension.gammaF * mat.sigmaS;
  r.bending.sigmaFK = r.K1S * r.bending.K2F * r.bending.gammaF * mat.sigmaS;
  r.torsion.sigmaFK = r.K1S * r.torsion.K2F * r.torsion.gammaF * mat.sigmaS / std::sqrt(3.0);

  // Equivalent mean stresses and amplitude strengths.
  const double sm = r.tension.nominal.mean + r.bending.nominal.mean;
  const double tm = r.torsion.nominal.mean;
  r.sigmaMv = std::sqrt(sm * sm + 3.0 * tm * tm);
  r.tauMv = r.sigmaMv / std::sqrt(3.0);
  r.tension.sigmaADK = amplitudeStrength(in.loadCase, r.sigmaMv, r.tension.nominal.amplitude, r.tension.sigmaWK,
                                         r.tension.sigmaFK, r.tension.psi);
  r.bending.sigmaADK = amplitudeStrength(in.loadCase, r.sigmaMv, r.bending.nominal.amplitude, r.bending.sigmaWK,
                                         r.bending.sigmaFK, r.bending.psi);
  r.torsion.sigmaADK = amplitudeStrength(in.loadCase, r.tauMv, r.torsion.nominal.amplitude, r.torsion.sigmaWK,
                                         r.torsion.sigmaFK, r.torsion.psi);

  // Safeties, DIN 743-1 eq. 1 and 2.
  auto ratio = [](double a, double adk) { return a > 0 ? a / adk : 0.0; };
  const double qs =
      ratio(r.tension.nominal.amplitude, r.tension.sigmaADK) + ratio(r.bending.nominal.amplitude, r.bending.sigmaADK);
  const double qt = ratio(r.torsion.nominal.amplitude, r.torsion.sigmaADK);
  const double qD = qs * qs + qt * qt;
  r.SD = qD > 0 ? 1.0 / std::sqrt(qD) : std::numeric_limits<double>::infinity();
  // Load case 1 past the yield line (sigma_ADK = sigma_FK - sigma_mv <= 0): no amplitude is
  // borne, S_D = 0 (squaring a negative ratio would hide it).
  for (const auto* f : {&r.tension, &r.bending, &r.torsion})
    if (f->nominal.amplitude > 0 && !(f->sigmaADK > 0)) r.SD = 0.0;

  const double ps = r.tension.nominal.max / r.tension.sigmaFK + r.bending.nominal.max / r.bending.sigmaFK;
  const double pt = r.torsion.nominal.max / r.torsion.sigmaFK;
  const double qF = ps * ps + pt * pt;
  r.SF = qF > 0 ? 1.0 / std::sqrt(qF) : std::numeric_limits<double>::infinity();
  return r;
}

} // namespace gbx::test
