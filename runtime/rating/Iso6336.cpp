#include "rating/Iso6336.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "rating/InternalRoot.h"

namespace gbx::rt::rating {

LifeCurve contactCurve(Treatment t) { return t == Treatment::Nitrided ? LifeCurve{1e5, 1.3, 2e6} : LifeCurve{1e5, 1.6, 5e7}; }
LifeCurve bendingCurve(Treatment t) {
  switch (t) {
  case Treatment::Nitrided: return {1e3, 1.6, 3e6};
  case Treatment::ThroughHardened: return {1e4, 2.5, 3e6};
  case Treatment::CaseHardened: break;
  }
  return {1e3, 2.5, 3e6};
}

namespace {

constexpr double kPi = 3.14159265358979323846;
double inv(double a) { return std::tan(a) - a; }
double invInverse(double t) {
  double a = std::cbrt(3.0 * t);
  for (int i = 0; i < 40; ++i) {
    double next = a - (inv(a) - t) / (std::tan(a) * std::tan(a));
    if (std::fabs(next - a) < 1e-15) return next;
    a = next;
  }
  return a;
}
double sq(double x) { return x * x; }

Treatment treatmentOf(const PairInput& in, int i) { return in.gear[static_cast<size_t>(i)].treatment.value_or(in.treatment); }
bool sameMaterials(const PairInput& in) {
  const auto &a = in.gear[0], &b = in.gear[1];
  return treatmentOf(in, 0) == treatmentOf(in, 1) && a.sigmaHlim == b.sigmaHlim;
}

// Running-in allowance of a deviation f [um] (ISO 6336-1 y_alpha, y_p, y_f) of one gear's
// material; two materials take the mean of theirs.
double runInOf(double f, Treatment t, double sigmaHlim, double v) {
  if (t != Treatment::ThroughHardened) return std::min(0.075 * f, 3.0);
  double y = 160.0 / sigmaHlim * f;
  if (v > 10) return std::min(y, 6400.0 / sigmaHlim);
  if (v > 5) return std::min(y, 12800.0 / sigmaHlim);
  return y;
}
double runIn(double f, const PairInput& in, double sigmaHlim, double v) {
  if (sameMaterials(in)) return runInOf(f, treatmentOf(in, 0), sigmaHlim, v);
  return 0.5 * (runInOf(f, treatmentOf(in, 0), in.gear[0].sigmaHlim * 1e-6, v) + runInOf(f, treatmentOf(in, 1), in.gear[1].sigmaHlim * 1e-6, v));
}

// Between a life curve's static point and its knee: 0 at the knee and beyond, 1 at the
// static point and below, log-linear in the cycles between (ISO 6336-2 cl. 10, -3 cl. 12-14:
// the factors move from their endurance to their static values on the life curve's span).
double towardStatic(double n, double nStatic, double nKnee) {
  if (n >= nKnee) return 0;
  if (n <= nStatic) return 1;
  return std::log(nKnee / n) / std::log(nKnee / nStatic);
}
double between(double endurance, double staticValue, double t) { return t <= 0 ? endurance : std::pow(endurance, 1 - t) * std::pow(staticValue, t); }

// Log-log life curve through (nStatic, static), (nKnee, 1), (1e10, end), flat beyond.
double lifeFactor(double n, double nStatic, double fStatic, double nKnee, double fEnd) {
  if (n <= nStatic) return fStatic;
  if (n <= nKnee) return std::pow(nKnee / n, std::log(fStatic) / std::log(nKnee / nStatic));
  if (n >= 1e10) return fEnd;
  return std::pow(nKnee / n, std::log(1.0 / fEnd) / std::log(1e10 / nKnee));
}

} // namespace

double runningIn(double f, Treatment t, double sigmaHlim, double v) { return runInOf(f, t, sigmaHlim, v); }

double workHardeningFactor(Treatment mine, Treatment mate, double brinell) {
  if (mine != Treatment::ThroughHardened || mate == Treatment::ThroughHardened) return 1.0;
  if (!std::isfinite(brinell))
    throw std::domain_error("a through-hardened gear meshes with a surface-hardened mate: its Z_W needs its material's `brinell_hardness`");
  return 1.2 - (std::clamp(brinell, 130.0, 470.0) - 130) / 1700;
}

double lifeFactorOf(double cycles, const LifeCurve& c, bool optimum) {
  return lifeFactor(cycles, c.nStatic, c.fStatic, c.nKnee, optimum ? 1.0 : 0.85);
}

FlankFactors flankFactors(double sigmaHlim, double nu40, double v, double Rz, double rhoRed) {
  FlankFactors f{};
  double CZL = sigmaHlim < 850 ? 0.83 : sigmaHlim > 1200 ? 0.91 : 0.83 + 0.08 * (sigmaHlim - 850) / 350;
  f.ZL = CZL + 4 * (1 - CZL) / sq(1.2 + 134 / nu40);
  double CZv = CZL + 0.02;
  f.Zv = CZv + 2 * (1 - CZv) / std::sqrt(0.8 + 32 / v);
  double Rz10 = Rz * std::cbrt(10 / rhoRed);
  double CZR = sigmaHlim < 850 ? 0.15 : sigmaHlim > 1200 ? 0.08 : 0.32 - 0.0002 * sigmaHlim;
  f.ZR = std::pow(3 / Rz10, CZR);
  return f;
}

RootFactors rootFactors(Treatment tr, double qs, double YS, double RzRoot, double mn, double cycles) {
  RootFactors o{};
  double rhoSlip = tr == Treatment::CaseHardened ? 0.0030 : tr == Treatment::Nitrided ? 0.1005 : 0.0064;
  o.YdeltarelT = (1 + std::sqrt(rhoSlip * (1 + 2 * qs) / 5)) / (1 + std::sqrt(rhoSlip * 1.2));
  double Rz = RzRoot;
  bool nitr = tr == Treatment::Nitrided;
  o.YRrelT = Rz < 1 ? (nitr ? 1.070 : 1.120) : nitr ? 5.306 - 4.203 * std::pow(Rz + 1, 0.01) : 1.674 - 0.529 * std::pow(Rz + 1, 0.1);
  o.YX = tr == Treatment::ThroughHardened ? std::clamp(1.03 - 0.006 * mn, 0.85, 1.0) : std::clamp(1.05 - 0.01 * mn, 0.8, 1.0);
  // Below the knee the notch, surface and size factors move toward their static values as
  // Y_NT does (ISO 6336-3 cl. 12-14): Y_deltarelT to 0.44 Y_S + 0.12 (case hardened),
  // 0.20 Y_S + 0.60 (nitrided), the through-hardened form at sigma_0.2 = 800 N/mm^2; Y_RrelT
  // and Y_X to 1.
  LifeCurve b = bendingCurve(tr);
  double toward = towardStatic(cycles, b.nStatic, b.nKnee);
  if (toward > 0) {
    double q = std::pow(300.0 / 800.0, 0.25);
    double deltaStatic = tr == Treatment::CaseHardened ? 0.44 * YS + 0.12
                         : tr == Treatment::Nitrided   ? 0.20 * YS + 0.60
                                                       : (1 + 0.82 * (YS - 1) * q) / (1 + 0.82 * q);
    o.YdeltarelT = between(o.YdeltarelT, deltaStatic, toward);
    o.YRrelT = between(o.YRrelT, 1.0, toward);
    o.YX = between(o.YX, 1.0, toward);
  }
  return o;
}

FlankFactors flankFactorsAt(const FlankFactors& endurance, double cycles, Treatment t) {
  LifeCurve c = contactCurve(t);
  double w = towardStatic(cycles, c.nStatic, c.nKnee);
  return {between(endurance.ZL, 1.0, w), between(endurance.Zv, 1.0, w), between(endurance.ZR, 1.0, w)};
}

ToothForm filletForm(double zn, double mn, double alphaN, double x, double xsm, double hfP, double rhoFP, double dLoad) {
  double G = rhoFP - hfP + x;
  double E = (kPi / 4 - xsm) * mn - hfP * mn * std::tan(alphaN) - (1 - std::sin(alphaN)) * rhoFP * mn / std::cos(alphaN);
  double H = 2.0 / zn * (kPi / 2 - E / mn) - kPi / 3;
  // theta = 2G/zn tan(theta) - H, by Newton from pi/6.
  double th = kPi / 6;
  for (int i = 0; i < 60; ++i) {
    double f = th - 2 * G / zn * std::tan(th) + H;
    double df = 1 - 2 * G / zn / sq(std::cos(th));
    double next = th - f / df;
    if (std::fabs(next - th) < 1e-14) {
      th = next;
      break;
    }
    th = next;
  }
  ToothForm t{};
  t.theta = th;
  double sFn = mn * (zn * std::sin(kPi / 3 - th) + std::sqrt(3.0) * (G / std::cos(th) - rhoFP));
  double rhoF = mn * (rhoFP + 2 * G * G / (std::cos(th) * (zn * sq(std::cos(th)) - 2 * G)));
  double dbn = mn * zn * std::cos(alphaN);
  double alphaEn = std::acos(dbn / dLoad);
  double gammaE = (kPi / 2 + 2 * (x * std::tan(alphaN) + xsm)) / zn + inv(alphaN) - inv(alphaEn);
  double alphaFen = alphaEn - gammaE;
  double hFe = 0.5 * mn *
               ((std::cos(gammaE) - std::sin(gammaE) * std::tan(alphaFen)) * dLoad / mn - zn * std::cos(kPi / 3 - th) - G / std::cos(th) +
                rhoFP);
  t.sFn = sFn;
  t.rhoF = rhoF;
  t.hFe = hFe;
  t.alphaFen = alphaFen;
  t.gamma = gammaE;
  formAndStressFactors(t, mn, alphaN);
  return t;
}

void formAndStressFactors(ToothForm& t, double mn, double alphaN) {
  t.YF = 6 * (t.hFe / mn) * std::cos(t.alphaFen) / (sq(t.sFn / mn) * std::cos(alphaN));
  double L = t.sFn / t.hFe, qs = t.sFn / (2 * t.rhoF);
  t.YS = (1.2 + 0.13 * L) * std::pow(qs, 1.0 / (1.21 + 2.3 / L));
}

ToothForm toothForm(double z, double x, double da, double mn, double alphaN, double beta, double epsAlpha, double hfP, double rhoFP) {
  double betaB = std::asin(std::sin(beta) * std::cos(alphaN));
  double zn = z / (sq(std::cos(betaB)) * std::cos(beta));
  double d = z * mn / std::cos(beta);
  double dn = mn * zn, dbn = dn * std::cos(alphaN), dan = dn + da - d;
  double epsAn = epsAlpha / sq(std::cos(betaB));
  // The outer point of single pair contact on the normal section's virtual gear.
  double den = 2 * std::sqrt(sq(std::sqrt(sq(dan / 2) - sq(dbn / 2)) - kPi * d * std::cos(beta) * std::cos(alphaN) / z * (epsAn - 1)) +
                             sq(dbn / 2));
  ToothForm t = filletForm(zn, mn, alphaN, x, 0, hfP, rhoFP, den);
  if (!(t.sFn > 0 && t.rhoF > 0 && t.hFe > 0 && std::isfinite(t.YF) && std::isfinite(t.YS)))
    throw std::domain_error("the tooth root has no 30-degree tangent section (check the basic rack and the profile shift)");
  return t;
}

namespace {

// The pair in the standard's units (mm, N, um, N/mm^2). An internal wheel is signed: z2, d2,
// d_b2, d_a2 and the centre distance negative, its shift as ISO 21771 signs it, so one set of
// formulas serves both.
struct Geometry {
  double mn, b, an, beta, z1, z2, x1, x2, sigmaHlim;
  bool internal;
  double s2, z2s, at, mt, d1, d2, db1, db2, betaB, ad, a, awt;
  std::array<double, 2> da, df, d, db;
};

// Deviations that load the mesh and what running-in takes off them (um).
struct Deviations {
  double fpb, ffa, fHb, yf;
};

// ISO 21771: reference, base, tip and root circles, and the working centre distance and
// pressure angle (given, or from the shifts).
Geometry geometryOf(const PairInput& in) {
  Geometry g{};
  g.mn = in.mn * 1e3;
  g.b = in.b * 1e3;
  g.an = in.alphaN;
  g.beta = in.beta;
  g.z1 = in.gear[0].z;
  g.z2 = in.gear[1].z;
  g.x1 = in.gear[0].x;
  g.x2 = in.gear[1].x;
  g.sigmaHlim = std::min(in.gear[0].sigmaHlim, in.gear[1].sigmaHlim) * 1e-6;
  if (!(g.z1 > 0 && g.z2 > 0 && g.mn > 0 && g.b > 0)) throw std::domain_error("the rating needs positive tooth counts, module and face width");
  const double mn = g.mn, an = g.an, beta = g.beta;
  g.internal = in.gear[1].internal;
  g.s2 = g.internal ? -1.0 : 1.0;
  g.z2s = g.s2 * g.z2;
  g.at = std::atan(std::tan(an) / std::cos(beta));
  g.mt = mn / std::cos(beta);
  g.d1 = g.z1 * g.mt;
  g.d2 = g.z2s * g.mt;
  g.db1 = g.d1 * std::cos(g.at);
  g.db2 = g.d2 * std::cos(g.at);
  g.betaB = std::asin(std::sin(beta) * std::cos(an));
  g.ad = 0.5 * (g.d1 + g.d2);
  if (std::isfinite(in.a)) {
    g.a = g.s2 * in.a * 1e3;
    g.awt = std::acos(g.ad * std::cos(g.at) / g.a);
  } else {
    g.awt = (g.x1 + g.x2) == 0 ? g.at : invInverse(inv(g.at) + 2 * std::tan(an) * (g.x1 + g.x2) / (g.z1 + g.z2s));
    g.a = g.ad * std::cos(g.at) / std::cos(g.awt);
  }
  // Tip alteration keeps the bottom clearance of an external pair.
  double k = g.internal ? 0.0 : std::min(0.0, (g.a - g.ad) / mn - (g.x1 + g.x2));
  g.d = {g.d1, g.d2};
  g.db = {g.db1, g.db2};
  for (int i = 0; i < 2; ++i) {
    const auto& gi = in.gear[static_cast<size_t>(i)];
    double sign = i == 1 ? g.s2 : 1.0;
    g.da[i] = std::isfinite(gi.tipDiameter) ? sign * gi.tipDiameter * 1e3 : g.d[i] + 2 * mn * (in.haP + gi.x + k);
    g.df[i] = g.d[i] - 2 * mn * (in.hfP - gi.x);
  }
  return g;
}

// Geometry the method cannot rate, said rather than rated: no working pressure angle, a root
// radius the rack cannot have, a tip inside its base circle, pointed or undercut teeth, a tip
// in the mate's root.
void refuseWhatCannotBeRated(const PairInput& in, const Geometry& g) {
  if (!std::isfinite(g.awt)) throw std::domain_error("the centre distance does not fit the tooth counts and shifts");
  const double an = g.an;
  const char* names[] = {"driving gear", "driven gear"};
  double rhoMax = (kPi / 4 - in.hfP * std::tan(an)) * std::cos(an) / (1 - std::sin(an));
  if (in.rhoFP > rhoMax)
    throw std::domain_error(fmt::format("the basic rack's root radius {:.3f} exceeds the largest its dedendum and pressure angle allow ({:.3f})",
                                        in.rhoFP, rhoMax));
  for (int i = 0; i < 2; ++i) {
    if (i == 1 && g.internal) continue;
    double zg = i == 0 ? g.z1 : g.z2, xg = in.gear[static_cast<size_t>(i)].x;
    // Tooth thickness at the tip circle (transverse), from the reference thickness.
    double dag = std::fabs(g.da[i]), dbg = std::fabs(g.db[i]);
    if (dag <= dbg) throw std::domain_error(fmt::format("the {}'s tip circle lies inside its base circle", names[i]));
    double aa = std::acos(dbg / dag);
    double sa = dag * ((kPi / 2 + 2 * xg * std::tan(an)) / zg + inv(g.at) - inv(aa));
    if (sa <= 0) throw std::domain_error(fmt::format("the {}'s teeth are pointed at the tip diameter {:.3f} mm", names[i], dag));
    // Undercut by the basic rack: the rack's straight flank starts below the base circle.
    double xmin = in.hfP - in.rhoFP * (1 - std::sin(an)) - zg * sq(std::sin(g.at)) / (2 * std::cos(g.beta));
    if (xg < xmin - 1e-9)
      throw std::domain_error(fmt::format("the {} is undercut (shift {:.4f} below {:.4f}); method B assumes a fillet without undercut",
                                          names[i], xg, xmin));
  }
  if (!g.internal) {
    // Bottom clearance at the working centre distance: a tip must clear the mate's root.
    double c1 = std::fabs(g.a) - g.da[0] / 2 - g.df[1] / 2, c2 = std::fabs(g.a) - g.da[1] / 2 - g.df[0] / 2;
    if (c1 < -1e-9 || c2 < -1e-9) throw std::domain_error("a tip diameter reaches into the mating gear's root at this centre distance");
  }
}

void contactRatios(const Geometry& g, PairRating& r) {
  double pbt = kPi * g.mt * std::cos(g.at);
  r.alphaWt = g.awt;
  r.epsAlpha = (std::sqrt(sq(g.da[0] / 2) - sq(g.db1 / 2)) + g.s2 * std::sqrt(sq(g.da[1] / 2) - sq(g.db2 / 2)) - g.a * std::sin(g.awt)) / pbt;
  r.epsBeta = g.b * std::sin(g.beta) / (kPi * g.mn);
  r.epsGamma = r.epsAlpha + r.epsBeta;
  if (!(r.epsAlpha >= 1)) throw std::domain_error(fmt::format("the transverse contact ratio is {:.3f}, below 1: the gears do not mesh continuously", r.epsAlpha));
}

Deviations deviations(const PairInput& in, const Geometry& g, PairRating& r) {
  Deviations dev{};
  dev.fpb = std::max(in.gear[0].fpb, in.gear[1].fpb) * 1e6;
  dev.ffa = std::max(in.gear[0].ffa, in.gear[1].ffa) * 1e6;
  dev.fHb = std::max(in.gear[0].fHb, in.gear[1].fHb) * 1e6;
  r.yAlpha = runIn(dev.fpb, in, g.sigmaHlim, r.v);
  dev.yf = runIn(dev.ffa, in, g.sigmaHlim, r.v);
  return dev;
}

// Stiffness, ISO 6336-1 clause 9 (method B).
void meshStiffness(const PairInput& in, const Geometry& g, double w, PairRating& r) {
  const double an = g.an, beta = g.beta, ea = r.epsAlpha;
  // Virtual tooth counts of the normal section, z / (cos^2 beta_b cos beta).
  double virt = sq(std::cos(g.betaB)) * std::cos(beta);
  // The polynomial's gear 1 is the pinion, the gear with fewer teeth (a sun may have more
  // than its planets); an internal wheel is a rack (1/z_n2 = 0).
  bool swap = !g.internal && g.z2 < g.z1;
  double zA = swap ? g.z2 : g.z1, zB = swap ? g.z1 : g.z2, xA = swap ? g.x2 : g.x1, xB = swap ? g.x1 : g.x2;
  double zn1 = zA / virt, zn2 = g.internal ? INFINITY : zB / virt;
  double q = 0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * xA - 0.11654 * xA / zn1 - 0.00193 * xB - 0.24188 * xB / zn2 +
             0.00529 * xA * xA + 0.00182 * xB * xB;
  double CR = std::min(in.gear[0].webFactor, in.gear[1].webFactor);
  double CB = (1 + 0.5 * (1.2 - in.hfP)) * (1 - 0.02 * (20.0 - an * 180 / kPi));
  double cth = 1 / q;
  r.cprime = cth * 0.8 * CR * CB * std::cos(beta);
  if (w < 100) r.cprime *= std::pow(w / 100, 0.25);
  r.cgammaAlpha = r.cprime * (0.75 * ea + 0.25);
  if (std::isfinite(in.cgammaGiven)) {
    r.cgammaAlpha = in.cgammaGiven * 1e-9;
    r.cprime = r.cgammaAlpha / (0.75 * ea + 0.25);
  }
  r.cgammaBeta = 0.85 * r.cgammaAlpha;
}

// Dynamic factor, clause 6.5 (method B): resonance ratio from the reduced mass.
void dynamicFactor(const PairInput& in, const Geometry& g, const Deviations& dev, double w, PairRating& r) {
  const double eg = r.epsGamma;
  double rho = in.density * 1e-9;  // kg/mm^3
  auto blank = [&](int i) {
    double dm = 0.5 * (g.da[i] + g.df[i]);
    double qi = in.gear[static_cast<size_t>(i)].bore * 1e3 / dm;
    return kPi / 8 * rho * std::pow(dm, 4) * (1 - std::pow(qi, 4)) / sq(g.db[i]);
  };
  // Planetary meshes: a sun drives `planets` planets; a ring counts as infinitely heavy.
  double m1 = blank(0), m2 = g.internal ? INFINITY : blank(1);
  r.mred = g.internal ? m1 : in.planets > 0 ? m1 * m2 / (m1 + in.planets * m2) : m1 * m2 / (m1 + m2);
  r.nE1 = 30000.0 / (kPi * g.z1) * std::sqrt(r.cgammaAlpha / r.mred);
  double n1 = in.gear[0].speed * 30 / kPi;
  r.N = n1 / r.nE1;
  if (!(r.mred > 0) || !std::isfinite(r.N))
    throw std::domain_error("the gear blanks have no mass for K_v (is a bore diameter as large as the gear?)");
  r.NS = w < 100 ? 0.5 + 0.35 * std::sqrt(w / 100) : 0.85;
  double Ca = std::isfinite(in.tipRelief) ? in.tipRelief * 1e6 : (1.0 / 18) * sq(g.sigmaHlim / 97 - 18.45) + 1.5;
  double Bp = r.cprime * std::max(0.0, dev.fpb - r.yAlpha) / w;
  double Bf = r.cprime * std::max(0.0, dev.ffa - dev.yf) / w;
  double Bk = std::fabs(1 - r.cprime * Ca / w);
  double Cv1 = 0.32, Cv2 = eg <= 2 ? 0.34 : 0.57 / (eg - 0.3), Cv3 = eg <= 2 ? 0.23 : 0.096 / (eg - 1.56);
  double Cv4 = eg <= 2 ? 0.90 : (0.57 - 0.05 * eg) / (eg - 1.44), Cv5 = 0.47, Cv6 = eg <= 2 ? 0.47 : 0.12 / (eg - 1.74);
  double Cv7 = eg <= 1.5 ? 0.75 : eg <= 2.5 ? 0.125 * std::sin(kPi * (eg - 2)) + 0.875 : 1.0;
  auto main = [&] { return Cv1 * Bp + Cv2 * Bf + Cv4 * Bk + 1; };
  auto super = [&] { return Cv5 * Bp + Cv6 * Bf + Cv7; };
  if (std::isfinite(in.KvGiven)) {
    r.Kv = in.KvGiven;
    r.kvRange = KvRange::Given;
  } else if (r.N <= r.NS) {
    r.Kv = r.N * (Cv1 * Bp + Cv2 * Bf + Cv3 * Bk) + 1;
    r.kvRange = KvRange::Subcritical;
  } else if (r.N <= 1.15) {
    r.Kv = main();
    r.kvRange = KvRange::MainResonance;
  } else if (r.N < 1.5) {
    r.Kv = super() + (main() - super()) / 0.35 * (1.5 - r.N);
    r.kvRange = KvRange::Intermediate;
  } else {
    r.Kv = super();
    r.kvRange = KvRange::Supercritical;
  }
}

// Face load factor, clause 7.6: the effective mismatch from the pinion's deflection
// (symmetric between its bearings), the manufacturing misalignment and the lead
// modifications, less running-in.
void faceLoadFactors(const PairInput& in, const Geometry& g, const Deviations& dev, PairRating& r) {
  const double b = g.b, sigmaHlim = g.sigmaHlim;
  double Fmb = r.Ft * in.KA * in.Kgamma * r.Kv / b;
  // The pinion's bending and torsion: the smaller gear of an external pair.
  double dPinion = g.internal ? g.d1 : std::min(g.d1, g.d2);
  r.fsh = Fmb * 0.023 * sq(b / dPinion);
  double fma = std::isfinite(in.fma) ? in.fma * 1e6 : dev.fHb;
  r.fma = fma * 1e-6;
  r.B1 = in.B1;
  r.B2 = in.B2;
  r.FbetaX = std::max({1.33 * in.B1 * r.fsh + in.B2 * fma, 0.005 * Fmb, 0.5 * dev.fHb});
  auto yBetaOf = [&](Treatment t, double shl) {
    if (t != Treatment::ThroughHardened) return std::min(0.15 * r.FbetaX, 6.0);
    double y = 320.0 / shl * r.FbetaX;
    // F_betax limited to 80 um (5 < v <= 10 m/s) and 40 um (v > 10 m/s) in y_beta.
    double cap = r.v > 10 ? 12800.0 / shl : r.v > 5 ? 25600.0 / shl : INFINITY;
    return std::min(y, cap);
  };
  r.yBeta = sameMaterials(in) ? yBetaOf(treatmentOf(in, 0), sigmaHlim)
                              : 0.5 * (yBetaOf(treatmentOf(in, 0), in.gear[0].sigmaHlim * 1e-6) + yBetaOf(treatmentOf(in, 1), in.gear[1].sigmaHlim * 1e-6));
  r.FbetaY = r.FbetaX - r.yBeta;
  if (std::isfinite(in.KHbetaGiven)) {
    r.KHbeta = in.KHbetaGiven;
  } else {
    double kb = 1 + r.FbetaY * r.cgammaBeta / (2 * Fmb);
    r.KHbeta = kb <= 2 ? kb : std::sqrt(2 * r.FbetaY * r.cgammaBeta / Fmb);
  }
  double bh = std::max(3.0, b / ((in.haP + in.hfP) * g.mn));
  r.KFbeta = std::pow(r.KHbeta, sq(bh) / (1 + bh + sq(bh)));
}

// Contact factors, ISO 6336-2.
void contactFactors(const PairInput& in, const Geometry& g, PairRating& r) {
  const double ea = r.epsAlpha, eb = r.epsBeta;
  r.ZH = std::sqrt(2 * std::cos(g.betaB) * std::cos(g.awt) / (sq(std::cos(g.at)) * std::sin(g.awt)));
  auto E = [&](int i) { return (std::isfinite(in.gear[static_cast<size_t>(i)].E) ? in.gear[static_cast<size_t>(i)].E : in.E) * 1e-6; };
  auto nu = [&](int i) { return std::isfinite(in.gear[static_cast<size_t>(i)].nu) ? in.gear[static_cast<size_t>(i)].nu : in.nu; };
  if (E(0) == E(1) && nu(0) == nu(1))
    r.ZE = std::sqrt(1 / (kPi * 2 * (1 - sq(nu(0))) / E(0)));
  else
    r.ZE = std::sqrt(1 / (kPi * ((1 - sq(nu(0))) / E(0) + (1 - sq(nu(1))) / E(1))));
  r.Zeps = eb < 1 ? std::sqrt((4 - ea) * (1 - eb) / 3 + eb / ea) : std::sqrt(1 / ea);
  r.Zbeta = 1 / std::sqrt(std::cos(g.beta));
}

// Transverse load factors, clause 8 (method B).
void transverseLoadFactors(const PairInput& in, const Geometry& g, const Deviations& dev, PairRating& r) {
  const double ea = r.epsAlpha, eg = r.epsGamma;
  if (std::isfinite(in.KHalphaGiven)) {
    r.KHalpha = r.KFalpha = in.KHalphaGiven;
    return;
  }
  double FtHb = r.Ft * in.KA * in.Kgamma * r.Kv * r.KHbeta / g.b;
  double qa = r.cgammaAlpha * (std::max(dev.fpb, dev.ffa) - r.yAlpha) / FtHb;
  double raw = eg <= 2 ? eg / 2 * (0.9 + 0.4 * qa) : 0.9 + 0.4 * std::sqrt(2 * (eg - 1) / eg) * qa;
  r.KHalpha = std::clamp(raw, 1.0, std::max(1.0, eg / (ea * sq(r.Zeps))));
  r.KFalpha = std::clamp(raw, 1.0, std::max(1.0, eg / (0.25 * ea + 0.75)));
}

// Single pair contact factors Z_B (pinion) and Z_D (wheel).
std::array<double, 2> singlePairFactors(const Geometry& g, const PairRating& r) {
  const double ea = r.epsAlpha, eb = r.epsBeta;
  double t1 = std::sqrt(sq(g.da[0] / g.db1) - 1), t2 = std::sqrt(sq(g.da[1] / g.db2) - 1);
  double M1 = std::tan(g.awt) / std::sqrt((t1 - 2 * kPi / g.z1) * (t2 - (ea - 1) * 2 * kPi / g.z2));
  double M2 = std::tan(g.awt) / std::sqrt((t2 - 2 * kPi / g.z2) * (t1 - (ea - 1) * 2 * kPi / g.z1));
  auto single = [&](double M) {
    if (eb >= 1) return 1.0;
    double s = M > 1 ? M : 1.0;
    return std::max(1.0, s - eb * (s - 1));
  };
  if (g.internal) return {1.0, 1.0};  // internal meshes: Z_B = Z_D = 1
  return {single(M1), single(M2)};
}

// What the two gears share in their own ratings: the flank factors of the softer flank
// (clause 11), the bending factors of the pair, and the load factors.
struct Shared {
  double ZL, Zv, ZR;
  std::array<double, 2> ZBD;
  double Ybeta, YDT, KH, KF;
};

Shared sharedFactors(const PairInput& in, const Geometry& g, const PairRating& r) {
  Shared s{};
  const double sigmaHlim = g.sigmaHlim, ea = r.epsAlpha, eb = r.epsBeta;
  // Lubricant, velocity and roughness factors (clause 11), from the softer flank.
  double rho1 = 0.5 * g.db1 * std::tan(g.awt), rho2 = 0.5 * g.db2 * std::tan(g.awt);
  // The pair's Rz: the mean of the two flanks' (ISO 6336-2), each the gear's own or the pair's.
  auto rz = [&](size_t i) { return std::isfinite(in.gear[i].RzFlank) ? in.gear[i].RzFlank : in.RzFlank; };
  FlankFactors f =
      flankFactors(sigmaHlim, in.nu40 * 1e6, r.v, 0.5 * (rz(0) + rz(1)) * 1e6, rho1 * rho2 / (rho1 + rho2));
  s.ZL = f.ZL;
  s.Zv = f.Zv;
  s.ZR = f.ZR;
  s.ZBD = singlePairFactors(g, r);
  s.Ybeta = 1 - std::min(eb, 1.0) * std::min(g.beta * 180 / kPi, 30.0) / 120;
  double epsAn = ea / sq(std::cos(g.betaB));
  s.YDT = 1;
  if (in.grade > 0 && in.grade <= 4 && epsAn > 2.05) s.YDT = epsAn > 2.5 ? 0.7 : 2.366 - 0.666 * epsAn;
  s.KH = in.KA * in.Kgamma * r.Kv * r.KHbeta * r.KHalpha;
  s.KF = in.KA * in.Kgamma * r.Kv * r.KFbeta * r.KFalpha;
  return s;
}

// Life factors Z_NT and Y_NT, ISO 6336-2 Table 2 and ISO 6336-3 Table 3.
void lifeFactors(const PairInput& in, Treatment t, GearRating& o) {
  o.ZNT = lifeFactorOf(o.cycles, contactCurve(t), in.optimumLife);
  o.YNT = lifeFactorOf(o.cycles, bendingCurve(t), in.optimumLife);
}

// Z_W of ISO 6336-2 (2006) cl. 13: a through-hardened gear meshing with a surface-hardened
// (case-hardened or nitrided) mate is work-hardened by it; 1.2 - (HB - 130)/1700 for HB in
// 130..470.
double workHardening(const PairInput& in, int i) {
  return workHardeningFactor(treatmentOf(in, i), treatmentOf(in, 1 - i), in.gear[static_cast<size_t>(i)].brinell);
}

// A gear's flank (ISO 6336-2), in N/mm^2.
void rateFlank(const PairInput& in, const PairRating& r, const Shared& s, int i, GearRating& o) {
  const auto& gi = in.gear[static_cast<size_t>(i)];
  // Below the knee Z_L, Z_v and Z_R move toward their static value 1 as Z_NT does.
  FlankFactors f = flankFactorsAt({s.ZL, s.Zv, s.ZR}, o.cycles, treatmentOf(in, i));
  o.ZL = f.ZL;
  o.Zv = f.Zv;
  o.ZR = f.ZR;
  o.ZW = workHardening(in, i);
  o.ZX = 1;
  o.ZBD = s.ZBD[static_cast<size_t>(i)];
  double shl = gi.sigmaHlim * 1e-6;
  o.sigmaH = o.ZBD * r.sigmaH0 * std::sqrt(s.KH);
  double hLimit = shl * o.ZNT * o.ZL * o.Zv * o.ZR * o.ZW * o.ZX;
  o.sigmaHP = hLimit / in.SHmin;
  o.SH = hLimit / o.sigmaH;
}

// A gear's tooth root (ISO 6336-3), in N/mm^2.
void rateRoot(const PairInput& in, const Geometry& g, const PairRating& r, const Shared& s, int i, GearRating& o) {
  const auto& gi = in.gear[static_cast<size_t>(i)];
  const double mn = g.mn;
  const bool internal = i == 1 && g.internal;
  PinionCutter cutter{gi.cutterTeeth, gi.cutterShift,
                      std::isfinite(gi.cutterTipRadius) ? gi.cutterTipRadius : in.rhoFP};
  ToothForm t = internal ? internalToothForm(gi.z, gi.x, std::fabs(g.da[i]), std::fabs(g.df[i]), mn, g.an, g.beta,
                                             r.epsAlpha, in.hfP, cutter)
                         : toothForm(gi.z, gi.x, g.da[i], mn, g.an, g.beta, r.epsAlpha, in.hfP, in.rhoFP);
  o.sFn = t.sFn * 1e-3;
  o.hFe = t.hFe * 1e-3;
  o.rhoF = t.rhoF * 1e-3;
  o.alphaFen = t.alphaFen;
  o.YF = t.YF;
  o.YS = t.YS;
  o.Ybeta = s.Ybeta;
  o.YB = internal && std::isfinite(gi.rimThickness) ? internalRimFactor(gi.rimThickness * 1e3, mn) : 1.0;
  o.YDT = s.YDT;
  double rzRoot = std::isfinite(gi.RzRoot) ? gi.RzRoot : in.RzRoot;
  RootFactors rf = rootFactors(treatmentOf(in, i), t.sFn / (2 * t.rhoF), t.YS, rzRoot * 1e6, mn, o.cycles);
  o.YdeltarelT = rf.YdeltarelT;
  o.YRrelT = rf.YRrelT;
  o.YX = rf.YX;
  o.YM = gi.YM;
  o.sigmaF0 = r.Ft / (g.b * mn) * o.YF * o.YS * o.Ybeta * o.YB * o.YDT;
  o.sigmaF = o.sigmaF0 * s.KF;
  double fLimit = gi.sigmaFlim * 1e-6 * 2.0 * o.YNT * o.YdeltarelT * o.YRrelT * o.YX * o.YM;
  o.sigmaFP = fLimit / in.SFmin;
  o.SF = fLimit / o.sigmaF;
}

// One gear of the pair: its cycles, life factors, flank and root; stresses back to SI.
// A gear's root left unrated (an internal gear without its cutter, or one its cutter cannot
// cut): NaN, which the report lists with the reason.
void unratedRoot(const GearInput& gi, GearRating& o) {
  o.sFn = o.hFe = o.rhoF = o.alphaFen = o.YF = o.YS = o.Ybeta = o.YB = o.YDT = kNaN;
  o.YNT = o.YdeltarelT = o.YRrelT = o.YX = kNaN;
  o.YM = gi.YM;
  o.sigmaF0 = o.sigmaF = o.sigmaFP = o.SF = kNaN;
}

// One gear of the pair: its cycles, life factors, flank and root; stresses back to SI. A
// ring whose root cannot be rated keeps its flank's rating; `rootError` says why.
void rateGear(const PairInput& in, const Geometry& g, const PairRating& r, const Shared& s, int i, GearRating& o,
              std::string& rootError) {
  const auto& gi = in.gear[static_cast<size_t>(i)];
  o.tipDiameter = std::fabs(g.da[i]) * 1e-3;
  o.rootDiameter = std::fabs(g.df[i]) * 1e-3;
  o.cycles = gi.speed / (2 * kPi) * in.life * gi.cyclesPerRev;
  o.fpb = gi.fpb;
  o.ffa = gi.ffa;
  o.fHb = gi.fHb;
  lifeFactors(in, treatmentOf(in, i), o);
  rateFlank(in, r, s, i, o);
  o.sigmaH *= 1e6;
  o.sigmaHP *= 1e6;
  const bool internal = i == 1 && g.internal;
  if (internal && !(gi.cutterTeeth > 0)) return unratedRoot(gi, o);
  try {
    rateRoot(in, g, r, s, i, o);
  } catch (const std::domain_error& e) {
    if (!internal) throw;
    rootError = e.what();
    return unratedRoot(gi, o);
  }
  o.sigmaF0 *= 1e6;
  o.sigmaF *= 1e6;
  o.sigmaFP *= 1e6;
}

} // namespace

PairRating rate(const PairInput& in) {
  PairRating r{};
  const Geometry g = geometryOf(in);
  refuseWhatCannotBeRated(in, g);
  contactRatios(g, r);
  // Load and speed.
  r.u = g.z2s / g.z1;
  r.Ft = 2000.0 * in.torque1 / g.d1;                 // N
  r.Fbt = r.Ft / std::cos(g.at);
  r.v = in.gear[0].speed * in.mn * g.z1 / std::cos(g.beta) / 2;  // m/s
  const double w = in.KA * r.Ft / g.b;                // N/mm
  r.b = in.b;
  r.Kgamma = in.Kgamma;
  r.dPinion = (g.internal ? g.d1 : std::min(g.d1, g.d2)) * 1e-3;
  const Deviations dev = deviations(in, g, r);
  meshStiffness(in, g, w, r);
  dynamicFactor(in, g, dev, w, r);
  faceLoadFactors(in, g, dev, r);
  contactFactors(in, g, r);
  transverseLoadFactors(in, g, dev, r);
  r.sigmaH0 = r.ZH * r.ZE * r.Zeps * r.Zbeta * std::sqrt(r.Ft / (g.d1 * g.b) * (r.u + 1) / r.u);
  const Shared s = sharedFactors(in, g, r);
  for (int i = 0; i < 2; ++i)
    rateGear(in, g, r, s, i, r.gear[static_cast<size_t>(i)], r.rootError);
  r.sigmaH0 *= 1e6;
  return r;
}

} // namespace gbx::rt::rating
