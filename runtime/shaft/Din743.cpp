#include "shaft/Din743.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

// DIN 743-1 (the safeties), -2 (size, notch and surface factors) and -3 (the material's
// strengths), 2012 editions. Inside, lengths are mm and stresses N/mm^2 as the fits are.

namespace gbx::rt::shaft::din743 {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double lg(double x) { return std::log10(x); }

// K1(d_eff): the technological size factor of 743-2, for sigma_B or (`yield`) sigma_S, d_B 16 mm.
double K1(Group g, double d, bool yield) {
  auto band = [d](double from, double to, double slope, double floor) {
    if (d <= from) return 1.0;
    return d < to ? 1.0 - slope * lg(d / from) : floor;
  };
  switch (g) {
  case Group::QuenchedTempered: return yield ? band(16, 300, 0.34, 0.57) : band(16, 300, 0.26, 0.67);
  case Group::CaseHardening: return band(16, 150, 0.41, 0.6);
  case Group::Structural: return yield ? band(32, 300, 0.26, 0.75) : band(100, 300, 0.23, 0.89);
  case Group::Nitriding: return band(100, 300, 0.23, 0.89);
  }
  return 1.0;
}

// K2(d), the geometric size factor of bending and torsion (743-2; tension 1), and K3(d) for a
// notch factor x, which carries an experimental beta from its test diameter to d.
double K2(double d) { return d < 7.5 ? 1.0 : d < 150 ? 1.0 - 0.2 * lg(d / 7.5) / lg(20.0) : 0.8; }
double K3(double d, double x) {
  return d < 7.5 ? 1.0 : d < 150 ? 1.0 - 0.2 * lg(x) * lg(d / 7.5) / lg(20.0) : 1.0 - 0.2 * lg(x);
}

// K_F for sigma from Rz (um) and sigma_B(d); tau takes 0.575 K_F sigma + 0.425 (743-2).
double roughness(double rz, double tensile) { return 1.0 - 0.22 * lg(std::max(rz, 1.0)) * (lg(tensile / 20.0) - 1.0); }

// gamma_F of 743-1 Table 2 for a circumferential notch from its alpha (or beta), tension and bending.
double yieldIncrease(double x) { return x <= 1.5 ? 1.0 : x <= 2.0 ? 1.05 : x <= 3.0 ? 1.10 : 1.15; }

// A form-factor fit of 743-2 for shoulders and round grooves:
// alpha = 1 + 1 / sqrt(A r/t + 2 B r/d (1 + 2 r/d)^2 + C (r/t)^z d/D).
struct Fit {
  double A, B, C, z;
};
double formFactor(const Fit& f, double d, double D, double r, double t) {
  double rd = r / d, rt = r / t;
  return 1.0 + 1.0 / std::sqrt(f.A * rt + 2 * f.B * rd * (1 + 2 * rd) * (1 + 2 * rd) + f.C * std::pow(rt, f.z) * d / D);
}

constexpr Fit kShoulder[3] = {{0.62, 3.5, 0, 0}, {0.62, 5.8, 0.2, 3}, {3.4, 19, 1, 2}};
constexpr Fit kGroove[3] = {{0.22, 1.37, 0, 0}, {0.2, 2.75, 0, 0}, {0.7, 10.3, 0, 0}};

// The section moduli at the notch (mm^2, mm^3): net of a transverse hole, hollow by the bore.
struct SectionModuli {
  double A, Wb, Wt;
};
SectionModuli moduli(const Notch& n, double d, double bore) {
  double b4 = bore * bore * bore * bore;
  SectionModuli s{kPi / 4 * (d * d - bore * bore), kPi / 32 * (d * d * d * d - b4) / d,
                  kPi / 16 * (d * d * d * d - b4) / d};
  if (n.kind == NotchKind::Hole) {
    double h = n.holeDiameter * 1e3;
    s.A -= h * d;
    s.Wb -= h * d * d / 6;
    s.Wt -= h * d * d / 6;
  }
  return s;
}

// alpha and G' (1/mm) of the notches with a form factor; an experimental beta at its test
// diameter (mm) for the others. Returns the test diameter, 0 for a form factor.
double notchFactors(const Notch& n, double d, double D, double tensile, Result& r, std::vector<std::string>& warn) {
  auto& f = r.f;
  double rad = n.radius * 1e3;
  switch (n.kind) {
  case NotchKind::Shoulder:
  case NotchKind::Groove: {
    double t = n.kind == NotchKind::Groove && n.depth > 0 ? n.depth * 1e3 : (D - d) / 2;
    const Fit* fit = n.kind == NotchKind::Shoulder ? kShoulder : kGroove;
    for (int k = 0; k < 3; ++k)
      f[k].alpha = formFactor(fit[k], d, D, rad, t);
    if (rad / t < 0.03 || d / D > 0.98)
      warn.push_back(fmt::format("r/t {:.3g}, d/D {:.3g}: beyond the fit's range", rad / t, d / D));
    r.phi = d / D > 0.67 ? 1.0 / (4 * std::sqrt(t / rad) + 2) : 0.0;
    double g = n.kind == NotchKind::Shoulder ? 2.3 : 2.0;
    f[Tension].Gprime = f[Bending].Gprime = g / rad * (1 + r.phi);
    f[Torsion].Gprime = (n.kind == NotchKind::Shoulder ? 1.15 : 1.0) / rad;
    return 0;
  }
  case NotchKind::Hole: {
    double h = n.holeDiameter * 1e3, q = h / d;
    if (q > 0.3) warn.push_back(fmt::format("hole d_L/d {:.3g}: beyond the fit's range 0.3", q));
    f[Tension].alpha = 3 - q;
    f[Bending].alpha = 3 + 1.4 * q - 2.8 * std::sqrt(q);
    f[Torsion].alpha = 2.023 - 1.125 * std::sqrt(q);
    f[Tension].Gprime = 2.3 / (h / 2);
    f[Bending].Gprime = 2.3 / (h / 2) + 2 / d;
    f[Torsion].Gprime = 1.15 / (h / 2) + 2 / d;
    return 0;
  }
  case NotchKind::Keyway: {
    double b = 3.0 * std::pow(tensile / 1000, 0.38), two = n.keys == 2 ? 1.15 : 1.0;
    f[Tension].betaTest = f[Bending].betaTest = b * two;
    f[Torsion].betaTest = (0.56 * b + 0.1) * two;
    return 40;
  }
  case NotchKind::PressFit: {
    double b = 2.7 * std::pow(tensile / 1000, 0.43);
    f[Tension].betaTest = f[Bending].betaTest = b;
    f[Torsion].betaTest = 0.65 * b;
    return 40;
  }
  case NotchKind::VNotch: {
    double t = (D - d) / 2;
    if (t / D < 0.05 || t / D > 0.2)
      warn.push_back(fmt::format("V-notch t/D {:.3g}: beyond the tests' range 0.05 .. 0.2", t / D));
    f[Tension].betaTest = 0.109 * tensile / 100 + 1.074;
    f[Bending].betaTest = 0.0923 * tensile / 100 + 0.985;
    f[Torsion].betaTest = 0.8 * f[Bending].betaTest;
    return 15;
  }
  }
  return 0;
}

// The amplitude the notch bears (743-1): load case 1 keeps the mean stress, 2 its ratio to
// the amplitude; both end at the yield line. NaN for load case 2 without an amplitude.
double amplitudeStrength(int loadCase, double mv, double a, const Factors& f) {
  double WK = f.sigmaWK, FK = f.sigmaFK, psi = f.psi;
  if (loadCase == 1) return mv <= (FK - WK) / (1 - psi) ? WK - psi * mv : FK - mv;
  if (a <= 0) return kNaN;
  double k = mv / a;
  return k <= (FK - WK) / (WK - psi * FK) ? WK / (1 + psi * k) : FK / (1 + k);
}

void check(const Notch& n, const Material& m) {
  auto bad = [](const std::string& s) { throw std::invalid_argument(s); };
  if (m.tensile <= 0 || m.yield <= 0) bad("its material needs `tensile_strength` and `yield_strength`");
  if ((n.kind == NotchKind::Groove || n.kind == NotchKind::VNotch) && n.d <= n.bore)
    bad(fmt::format("the {}'s depth leaves no section", notchName(n.kind)));
  if (n.kind == NotchKind::Hole && n.bore > 0) bad("a transverse hole in a hollow segment is not rated (its net section)");
  if (n.d <= 0) bad("the notch lies where the shaft has no diameter");
  if (n.bore >= n.d) bad("the notch's section is all bore");
  if ((n.kind == NotchKind::Shoulder || n.kind == NotchKind::Groove) && n.radius <= 0)
    bad(fmt::format("a {} needs a fillet `radius` above 0", notchName(n.kind)));
  if (n.kind == NotchKind::Shoulder && n.D <= n.d) bad("a shoulder needs a step in diameter at its position");
  if (n.kind == NotchKind::Hole && (n.holeDiameter <= 0 || n.holeDiameter >= n.d))
    bad("the hole's diameter must lie between 0 and the shaft's");
  if (n.kind == NotchKind::Keyway && n.keys != 1 && n.keys != 2) bad("a keyway has 1 or 2 keys");
}

} // namespace

const char* notchName(NotchKind k) {
  static const char* names[] = {"shoulder", "groove", "keyway", "press_fit", "hole", "v_notch"};
  return names[static_cast<int>(k)];
}

Result rate(const Notch& n, const Material& m, const std::array<Load, 3>& loads, const Settings& s) {
  check(n, m);
  Result r;
  double d = n.d * 1e3, D = std::max(n.D, n.d) * 1e3;
  double sB = m.tensile * 1e-6, sS = m.yield * 1e-6, deff = s.effectiveDiameter * 1e3;
  // Nominal stresses at the notch's section.
  SectionModuli sm = moduli(n, d, n.bore * 1e3);
  const double per[3] = {1 / sm.A, 1e3 / sm.Wb, 1e3 / sm.Wt};
  for (int k = 0; k < 3; ++k) {
    r.f[k].mean = loads[k].mean * per[k];
    r.f[k].amplitude = loads[k].amplitude * per[k];
    r.f[k].max = loads[k].max * per[k];
  }
  // The material at d_eff.
  r.K1B = K1(m.group, deff, false);
  r.K1S = K1(m.group, deff, true);
  double B = r.K1B * sB, S = r.K1S * sS;
  r.tensileAt = B * 1e6;
  r.yieldAt = S * 1e6;
  r.f[Tension].K2 = 1;
  r.f[Bending].K2 = r.f[Torsion].K2 = K2(d);
  // The notch factor: alpha / n, or an experimental beta carried to d by K3.
  double test = notchFactors(n, d, D, B, r, r.warnings);
  for (auto& f : r.f) {
    if (test == 0) {
      f.n = 1 + std::sqrt(f.Gprime) * std::pow(10.0, s.hardened ? -0.7 : -(0.33 + S / 712));
      f.beta = f.alpha / f.n;
    } else {
      f.K3Test = K3(test, f.betaTest);
      f.K3 = K3(d, f.betaTest);
      f.beta = f.betaTest * f.K3Test / f.K3;
    }
  }
  // Roughness: keyways and press fits carry it in their beta; a V-notch's tests were at Rz 20.
  double rz = n.roughness * 1e6;
  bool inBeta = n.kind == NotchKind::Keyway || n.kind == NotchKind::PressFit || s.hardened;
  double kfs = inBeta ? 1 : roughness(rz, B), kft = inBeta ? 1 : 0.575 * kfs + 0.425;
  if (n.kind == NotchKind::VNotch && !s.hardened) {
    double ref = roughness(20, B);
    kfs /= ref;
    kft /= 0.575 * ref + 0.425;
  }
  r.f[Tension].KF = r.f[Bending].KF = kfs;
  r.f[Torsion].KF = kft;
  // Fatigue strength of the component and its mean-stress sensitivity.
  const double share[3] = {0.4, 0.5, 0.3}; // sigma_zdW, sigma_bW, tau_tW over sigma_B (743-3)
  for (int k = 0; k < 3; ++k) {
    auto& f = r.f[k];
    f.K = (f.beta / f.K2 + 1 / f.KF - 1) / s.KV;
    f.sigmaW = share[k] * B;
    f.sigmaWK = f.sigmaW / f.K;
    f.psi = f.sigmaWK / (2 * B - f.sigmaWK);
  }
  // Yield limits: gamma_F for circumferential notches, from alpha (or beta without one).
  bool circumferential = n.kind != NotchKind::Keyway && n.kind != NotchKind::Hole;
  for (int k = 0; k < 3; ++k) {
    auto& f = r.f[k];
    // K2F of 743-1: 1.2 in bending and torsion of a solid section, 1.1 and 1.0 of a hollow
    // one, 1 in tension or under a hardened layer; gamma_F raises only a circumferential
    // notch's yield limit, and not under a hardened layer.
    f.K2F = s.hardened || k == Tension ? 1.0 : n.bore > 0 ? (k == Bending ? 1.1 : 1.0) : 1.2;
    f.gammaF = circumferential && !s.hardened && k != Torsion ? yieldIncrease(f.alpha > 0 ? f.alpha : f.beta) : 1.0;
    f.sigmaFK = f.K2F * f.gammaF * S / (k == Torsion ? std::sqrt(3.0) : 1.0);
  }
  // Equivalent mean stresses, the amplitude strengths and the safeties.
  double sm0 = r.f[Tension].mean + r.f[Bending].mean, tm = r.f[Torsion].mean;
  r.sigmaMv = std::sqrt(sm0 * sm0 + 3 * tm * tm);
  r.tauMv = r.sigmaMv / std::sqrt(3.0);
  for (int k = 0; k < 3; ++k)
    r.f[k].sigmaADK = amplitudeStrength(s.loadCase, k == Torsion ? r.tauMv : r.sigmaMv, r.f[k].amplitude, r.f[k]);
  auto q = [](double a, double adk) { return a > 0 ? a / adk : 0.0; };
  double qs = q(r.f[Tension].amplitude, r.f[Tension].sigmaADK) + q(r.f[Bending].amplitude, r.f[Bending].sigmaADK);
  double qt = q(r.f[Torsion].amplitude, r.f[Torsion].sigmaADK);
  r.SD = qs * qs + qt * qt > 0 ? 1 / std::sqrt(qs * qs + qt * qt) : std::numeric_limits<double>::infinity();
  // Load case 1 past the yield line: the mean stress alone yields the section, no amplitude
  // is borne.
  for (const auto& f : r.f)
    if (f.amplitude > 0 && !(f.sigmaADK > 0)) {
      r.SD = 0;
      r.warnings.push_back("the equivalent mean stress exceeds the yield limit: no amplitude is borne (S_D 0)");
      break;
    }
  double ps = std::fabs(r.f[Tension].max) / r.f[Tension].sigmaFK + std::fabs(r.f[Bending].max) / r.f[Bending].sigmaFK;
  double pt = std::fabs(r.f[Torsion].max) / r.f[Torsion].sigmaFK;
  r.SF = ps * ps + pt * pt > 0 ? 1 / std::sqrt(ps * ps + pt * pt) : std::numeric_limits<double>::infinity();
  // Back to SI.
  for (auto& f : r.f) {
    for (double* x : {&f.mean, &f.amplitude, &f.max, &f.sigmaW, &f.sigmaWK, &f.sigmaADK, &f.sigmaFK})
      *x *= 1e6;
    f.Gprime *= 1e3;
  }
  r.sigmaMv *= 1e6;
  r.tauMv *= 1e6;
  return r;
}

} // namespace gbx::rt::shaft::din743
