#pragma once
// Independent reference (test oracle) for ISO 281:2007 rolling bearing life: basic rating life
// L10 (clauses 6, 7), reliability factor a1 (Table 12), viscosity ratio kappa with nu1, and the
// life modification factor a_ISO for radial ball and radial roller bearings (clause 9.3, three
// kappa bands).
// Loads in any consistent unit (C, C0, C_u, P alike), speed in rpm, D_pw in mm, viscosity in mm^2/s.
//
// a_ISO = 0.1 [1 - (x1 - c/kappa^q)^e1 (e_C C_u/P)^e2]^-e3
//   radial ball:   x1 2.5671, e1 0.83, e2 1/3, e3 9.3
//   radial roller: x1 1.5859, e1 1,    e2 0.4, e3 9.185
//   (c_ball, c_roller, q) = (2.2649, 1.3993, 0.054381)  0.1 <= kappa < 0.4
//                           (1.9987, 1.2348, 0.19087)   0.4 <= kappa < 1
//                           (1.9987, 1.2348, 0.071739)  1   <= kappa <= 4
// Caps: e_C C_u/P <= 5, kappa <= 4, a_ISO <= 50. Below kappa 0.1 the fits are not defined; here
// kappa is raised to 0.1 and flagged.
#include <algorithm>
#include <cmath>

namespace gbx::test {

enum class Iso281BearingType { radial_ball, radial_roller };

// Life exponent p: 3 ball, 10/3 roller (ISO 281 clause 6 and 7).
inline double iso281LifeExponent(Iso281BearingType t) { return t == Iso281BearingType::radial_ball ? 3.0 : 10.0 / 3.0; }

// Basic rating life L10 in millions of revolutions: (C/P)^p.
inline double iso281L10(double C, double P, Iso281BearingType t) { return std::pow(C / P, iso281LifeExponent(t)); }

// Basic rating life in hours from L10 (millions of revolutions) and speed (rpm).
inline double iso281L10h(double L10, double rpm) { return L10 * 1e6 / (60.0 * rpm); }

// Reliability factor a1 (ISO 281:2007 Table 12, Weibull fit with slope 1.5 and t0 offset):
// a1 = 0.95 [ln(100/R) / ln(100/90)]^(2/3) + 0.05, R in percent (1 at 90 %).
inline double iso281A1(double reliabilityPercent) {
  const double ratio = std::log(100.0 / reliabilityPercent) / std::log(100.0 / 90.0);
  return 0.95 * std::pow(ratio, 2.0 / 3.0) + 0.05;
}

// Reference kinematic viscosity nu1 (mm^2/s), ISO 281:2007 clause 9.3:
// 45000 n^-0.83 D_pw^-0.5 for n < 1000 rpm, 4500 n^-0.5 D_pw^-0.5 for n >= 1000 rpm.
inline double iso281Nu1(double rpm, double dpw) {
  if (rpm < 1000.0) return 45000.0 * std::pow(rpm, -0.83) / std::sqrt(dpw);
  return 4500.0 / std::sqrt(rpm) / std::sqrt(dpw);
}

// Viscosity ratio kappa = nu / nu1.
inline double iso281Kappa(double nu, double rpm, double dpw) { return nu / iso281Nu1(rpm, dpw); }

// Fatigue load limit estimate, ISO 281:2007 Annex B: C0/22 (ball), C0/8.2 (roller) for D_pw <= 100 mm.
inline double iso281CuApprox(double C0, Iso281BearingType t) {
  return t == Iso281BearingType::radial_ball ? C0 / 22.0 : C0 / 8.2;
}
// With the size term for D_pw > 100 mm: ball (100/D_pw)^0.5, roller (100/D_pw)^0.3.
inline double iso281CuApprox(double C0, Iso281BearingType t, double dpw) {
  const double base = iso281CuApprox(C0, t);
  if (dpw <= 100.0) return base;
  return base * std::pow(100.0 / dpw, t == Iso281BearingType::radial_ball ? 0.5 : 0.3);
}

struct Iso281BandCoefficients {
  double cBall, cRoller, q;
};

// Band 0: 0.1 <= kappa < 0.4; band 1: 0.4 <= kappa < 1; band 2: 1 <= kappa <= 4.
inline Iso281BandCoefficients iso281Band(int band) {
  switch (band) {
  case 0: return {2.2649, 1.3993, 0.054381};
  case 1: return {1.9987, 1.2348, 0.19087};
  default: return {1.9987, 1.2348, 0.071739};
  }
}

inline int iso281BandOf(double kappa) { return kappa < 0.4 ? 0 : (kappa < 1.0 ? 1 : 2); }

// One band's formula at kappa and x = e_C C_u / P, without band selection or caps (raw value;
// +inf where the bracket is not positive).
inline double iso281AIsoBandRaw(Iso281BearingType t, int band, double kappa, double x) {
  const auto k = iso281Band(band);
  double bracket = 0;
  if (t == Iso281BearingType::radial_ball) {
    const double base = std::max(0.0, 2.5671 - k.cBall / std::pow(kappa, k.q));
    bracket = 1.0 - std::pow(base, 0.83) * std::cbrt(x);
    if (bracket <= 0) return HUGE_VAL;
    return 0.1 * std::pow(bracket, -9.3);
  }
  bracket = 1.0 - (1.5859 - k.cRoller / std::pow(kappa, k.q)) * std::pow(x, 0.4);
  if (bracket <= 0) return HUGE_VAL;
  return 0.1 * std::pow(bracket, -9.185);
}

struct Iso281AIso {
  double aIso = 0;              // capped at 50
  double kappaUsed = 0;         // kappa after the caps (0.1 ... 4)
  double loadTermUsed = 0;      // e_C C_u / P after the cap (<= 5)
  int band = 0;                 // 0, 1, 2 as iso281Band
  bool kappaBelowRange = false; // kappa < 0.1 was raised to 0.1
};

// Life modification factor a_ISO (ISO 281:2007 clause 9.3) with its caps.
inline Iso281AIso iso281AIso(Iso281BearingType t, double kappa, double eC, double Cu, double P) {
  Iso281AIso r;
  r.kappaBelowRange = kappa < 0.1;
  r.kappaUsed = std::clamp(kappa, 0.1, 4.0);
  r.loadTermUsed = std::min(eC * Cu / P, 5.0);
  r.band = iso281BandOf(r.kappaUsed);
  r.aIso = std::min(iso281AIsoBandRaw(t, r.band, r.kappaUsed, r.loadTermUsed), 50.0);
  return r;
}

// Modified rating life L_nm = a1 a_ISO L10 (same unit as L10).
inline double iso281Lnm(double a1, double aIso, double L10) { return a1 * aIso * L10; }

} // namespace gbx::test
