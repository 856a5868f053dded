#include "rating/Iso10300.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace gbx::rt::rating {

namespace {

constexpr double kPi = 3.14159265358979323846;
double sq(double x) { return x * x; }

Treatment treatmentOf(const BevelInput& in, int i) { return in.gear[static_cast<size_t>(i)].treatment.value_or(in.treatment); }

// The pair in the standard's units (mm, N, um, N/mm^2): ISO 23509 cone geometry, then the
// virtual cylindrical gears of ISO 10300-1 Annex A (method B1, no offset: beta_v = beta_m and
// the effective pressure angle is the generated one).
struct Pair {
  double u, Re, Rm, b, bEff, mmn, mmt, betaM, alphaN, alphaVt, betaVb;
  std::array<double, 2> delta, dm, de, ham, hfm, dv, dva, dvb, zv, zvn, dvn, dvan, dvbn;
  double av, uv, pvet, gva, epsVa, epsVb, epsVg, rhoRel;
};

// The size of the pair: R_e given, else from the mean normal module, else from the face width
// and the face ratio; b given, else b/R_e.
void size(const BevelInput& in, Pair& p, bool strict) {
  double z1 = in.gear[0].z;
  bool haveB = std::isfinite(in.b);
  if (std::isfinite(in.Re)) {
    p.Re = in.Re * 1e3;
  } else if (std::isfinite(in.mmn)) {
    // R_m = m_mn z1 / (2 cos beta_m sin delta1), R_e = R_m + b/2.
    double Rm = in.mmn * 1e3 * z1 / (2 * std::cos(in.betaM) * std::sin(p.delta[0]));
    p.Re = haveB ? Rm + in.b * 1e3 / 2 : Rm / (1 - in.faceRatio / 2);
  } else if (haveB && std::isfinite(in.faceRatio) && in.faceRatio > 0) {
    p.Re = in.b * 1e3 / in.faceRatio; // the face width and the face ratio b/R_e fix the cone
  } else {
    throw std::domain_error("the rating needs the outer cone distance or the mean normal module");
  }
  p.b = haveB ? in.b * 1e3 : in.faceRatio * p.Re;
  if (!(p.b > 0 && p.b < p.Re)) throw std::domain_error(fmt::format("the face width {:.4g} mm does not fit the outer cone distance {:.4g} mm", p.b, p.Re));
  p.Rm = p.Re - p.b / 2;
  for (int i = 0; i < 2; ++i) {
    p.dm[i] = 2 * p.Rm * std::sin(p.delta[i]);
    p.de[i] = 2 * p.Re * std::sin(p.delta[i]);
  }
  p.mmt = p.dm[0] / z1;
  p.mmn = p.mmt * std::cos(in.betaM);
  // A face ratio given beside the face width must be the one they make with the cone distance
  // (the search's m_mn/b window reads the ratio, the rating the width).
  if (strict && haveB && std::isfinite(in.faceRatio) && std::fabs(p.b / p.Re / in.faceRatio - 1) > 0.005)
    throw std::domain_error(fmt::format("the face ratio {:.4g} disagrees with the {:.4g} the face width {:.4g} mm and outer cone distance "
                                        "{:.4g} mm make",
                                        in.faceRatio, p.b / p.Re, p.b, p.Re));
  // A mean normal module given beside the cone distance must be the one the cone gives.
  if (strict && std::isfinite(in.mmn) && std::isfinite(in.Re) && std::fabs(in.mmn * 1e3 / p.mmn - 1) > 0.005)
    throw std::domain_error(fmt::format("the mean normal module {:.4g} mm disagrees with the {:.4g} mm the outer cone distance, face width, "
                                        "spiral angle {:.4g} deg and tooth counts give",
                                        in.mmn * 1e3, p.mmn, in.betaM * 180 / kPi));
}

// `strict`: the rating's checks of what the spec over-determines (the geometry quantities read
// the cone as the cone distance and face width make it; the rating refuses a disagreement).
Pair pairOf(const BevelInput& in, bool strict = true) {
  Pair p{};
  double z1 = in.gear[0].z, z2 = in.gear[1].z;
  if (!(z1 > 0 && z2 > 0)) throw std::domain_error("the rating needs positive tooth counts");
  p.u = z2 / z1;
  p.delta[0] = std::atan2(std::sin(in.shaftAngle), std::cos(in.shaftAngle) + p.u);
  p.delta[1] = in.shaftAngle - p.delta[0];
  // Past 90 degrees the wheel is a crown gear or internal: no virtual cylindrical gear.
  for (int i = 0; i < 2; ++i)
    if (!(p.delta[i] > 0 && p.delta[i] < kPi / 2 - 1e-9))
      throw std::domain_error(fmt::format("the {}'s pitch cone angle is {:.3f} deg: method B1's virtual cylindrical gears need cone angles "
                                          "below 90 deg (a smaller shaft angle or ratio)",
                                          i ? "wheel" : "pinion", p.delta[i] * 180 / kPi));
  if (strict && std::isfinite(in.alphaNCoast) && std::fabs(in.alphaNCoast - in.alphaN) > 1e-9)
    throw std::domain_error(fmt::format("the coast flank's pressure angle {:.4g} deg differs from the drive flank's {:.4g} deg: the rating of "
                                        "bevel gears with unequal flank angles is not implemented",
                                        in.alphaNCoast * 180 / kPi, in.alphaN * 180 / kPi));
  p.betaM = in.betaM;
  p.alphaN = in.alphaN;
  size(in, p, strict);
  p.bEff = in.contactPattern * p.b;
  for (int i = 0; i < 2; ++i) {
    double x = in.gear[static_cast<size_t>(i)].xhm;
    p.ham[i] = p.mmn * (in.khap + x);
    p.hfm[i] = p.mmn * (in.khfp - x);
    if (!(p.ham[i] > 0 && p.hfm[i] > 0))
      throw std::domain_error(fmt::format("the {}'s mean addendum or dedendum is not positive (shift {:.4g})", i ? "wheel" : "pinion", x));
  }
  const double cb = std::cos(in.betaM);
  p.alphaVt = std::atan(std::tan(in.alphaN) / cb);
  p.betaVb = std::asin(std::sin(in.betaM) * std::cos(in.alphaN));
  for (int i = 0; i < 2; ++i) {
    p.dv[i] = p.dm[i] / std::cos(p.delta[i]);
    p.zv[i] = p.dv[i] / p.mmt;
    p.dva[i] = p.dv[i] + 2 * p.ham[i];
    p.dvb[i] = p.dv[i] * std::cos(p.alphaVt);
    // The normal section's virtual gear carries the root stress.
    p.zvn[i] = p.zv[i] / (sq(std::cos(p.betaVb)) * cb);
    p.dvn[i] = p.zvn[i] * p.mmn;
    p.dvan[i] = p.dvn[i] + 2 * p.ham[i];
    p.dvbn[i] = p.dvn[i] * std::cos(in.alphaN);
  }
  p.av = (p.dv[0] + p.dv[1]) / 2;
  p.uv = p.dv[1] / p.dv[0];
  p.pvet = kPi * p.mmn * std::cos(p.alphaVt) / cb;
  p.gva = (std::sqrt(sq(p.dva[0]) - sq(p.dvb[0])) + std::sqrt(sq(p.dva[1]) - sq(p.dvb[1]))) / 2 - p.av * std::sin(p.alphaVt);
  p.epsVa = p.gva / p.pvet;
  p.epsVb = p.bEff * std::sin(in.betaM) / (kPi * p.mmn);
  p.epsVg = p.epsVa + p.epsVb;
  if (!(p.epsVa >= 1))
    throw std::domain_error(fmt::format("the virtual gears' transverse contact ratio is {:.3f}, below 1: the teeth do not mesh continuously", p.epsVa));
  // Relative radius of curvature at the pitch point, normal to the contact line.
  p.rhoRel = p.av * std::sin(p.alphaVt) * p.uv / sq(1 + p.uv) / std::cos(p.betaVb);
  return p;
}

// The contact lines of ISO 10300-1 (2023) A.2.7 in the zone of action (face b_eff by path
// g_va, lines inclined at beta_vb): the middle line through the mid-zone point, the tip and
// root lines one normal base pitch either side. A line runs between the zone's tip and root
// edges, no longer than the face allows; the elliptical contact pattern then shortens it.
struct ContactLines {
  double fmax, lbm, lbt, ZLS;
};

ContactLines contactLines(const Pair& p, double b) {
  ContactLines c{};
  const double sb = std::sin(p.betaVb), cbv = std::cos(p.betaVb);
  c.fmax = (p.gva + p.bEff * std::tan(p.betaVb)) * cbv / 2;
  auto across = [&](double f) {
    if (sb < 1e-12) return std::fabs(f) <= p.gva / 2 ? p.bEff : 0.0;
    return std::min(p.gva / sb, p.bEff / cbv);
  };
  const double k = 1 - std::sqrt(p.bEff / b);
  auto reduced = [&](double f) {
    double r2 = sq(f / c.fmax);
    return across(f) * std::max(0.0, 1 - std::sqrt(r2 + k * k * (1 - r2)));
  };
  const double ft = p.pvet * cbv;
  c.lbm = reduced(0);
  c.lbt = reduced(ft);
  // Each line carries a half ellipse of peak 1 - |f/f_max|^3; the middle one's share is Z_LS^2.
  auto load = [&](double f, double l) { return std::max(0.0, 1 - std::pow(std::fabs(f / c.fmax), 3)) * l; };
  double middle = load(0, c.lbm), sides = 2 * load(ft, c.lbt);
  c.ZLS = std::sqrt(middle / (middle + sides));
  return c;
}

// K_v by ISO 10300-1 method B: the pair's resonance speed from c_gamma and the reduced mass
// at the mean point, and the pitch deviation after running-in.
void dynamicFactor(const BevelInput& in, const Pair& p, double fpt, BevelRating& r) {
  double w = r.Ft * in.KA / p.bEff;
  double CF = w >= 100 ? 1.0 : w / 100;
  r.cprime = 14 * CF;
  r.cgamma = 20 * CF;
  double rho = in.density * 1e-9;  // kg/mm^3
  double m1 = kPi / 8 * rho * sq(p.dm[0] / std::cos(in.alphaN)), m2 = kPi / 8 * rho * sq(p.dm[1] / std::cos(in.alphaN));
  r.mred = m1 * m2 / (m1 + m2);
  r.nE1 = 30000 / (kPi * in.gear[0].z) * std::sqrt(r.cgamma / r.mred);
  r.N = in.gear[0].speed * 30 / kPi / r.nE1;
  if (std::isfinite(in.KvGiven)) {
    r.Kv = in.KvGiven;
    r.kvRange = KvRange::Given;
    return;
  }
  double Bp = r.cprime * (fpt - r.yAlpha) / (in.KA * r.Ft / p.b), Bf = Bp, Bk = 1;
  double e = p.epsVg;
  double c1 = 0.32, c2 = e <= 2 ? 0.34 : 0.57 / (e - 0.3), c3 = e <= 2 ? 0.23 : 0.096 / (e - 1.56);
  double c4 = e <= 2 ? 0.90 : (0.57 - 0.05 * e) / (e - 1.44), c5 = 0.47, c6 = e <= 2 ? 0.47 : 0.12 / (e - 1.74);
  double c7 = e <= 1.5 ? 0.75 : e <= 2.5 ? 0.125 * std::sin(kPi * (e - 2)) + 0.875 : 1.0;
  double sub = c1 * Bp + c2 * Bf + c3 * Bk, main = c1 * Bp + c2 * Bf + c4 * Bk, sup = c5 * Bp + c6 * Bf + c7;
  if (r.N <= 0.75) {
    r.Kv = r.N * sub + 1;
    r.kvRange = KvRange::Subcritical;
  } else if (r.N <= 1.25) {
    r.Kv = main + 1;
    r.kvRange = KvRange::MainResonance;
  } else if (r.N < 1.5) {
    r.Kv = sup + (main + 1 - sup) * (1.5 - r.N) / 0.25;
    r.kvRange = KvRange::Intermediate;
  } else {
    r.Kv = sup;
    r.kvRange = KvRange::Supercritical;
  }
}

// K_Hbeta-C from the mounting (contact pattern checked under light load), K_F0 from the
// lengthwise curvature, K_Halpha and K_Falpha by method B.
void loadFactors(const BevelInput& in, const Pair& p, double fpt, double ZLS, BevelRating& r) {
  static const double kBe[] = {1.05, 1.10, 1.25};
  r.KHbetaBe = kBe[static_cast<int>(in.mounting)];
  r.KHbeta = std::isfinite(in.KHbetaGiven) ? in.KHbetaGiven : 1.5 * r.KHbetaBe;
  r.KF0 = 1;
  if (std::isfinite(in.cutterRadius) && in.betaM > 0) {
    double q = 0.279 / std::log10(std::sin(in.betaM));
    r.KF0 = std::clamp(0.211 * std::pow(in.cutterRadius * 1e3 / p.Rm, q) + 0.789, 1.0, 1.15);
  }
  r.KFbeta = r.KHbeta / r.KF0;
  if (std::isfinite(in.KHalphaGiven)) {
    r.KHalpha = r.KFalpha = in.KHalphaGiven;
    return;
  }
  double e = p.epsVg, FmtH = r.Ft * in.KA * r.Kv * r.KHbeta;
  double x = r.cgamma * (fpt - r.yAlpha) / (FmtH / p.b);
  double K = e <= 2 ? e / 2 * (0.9 + 0.4 * x) : 0.9 + 0.4 * std::sqrt(2 * (e - 1) / e) * x;
  r.KHalpha = std::clamp(K, 1.0, e / (p.epsVa * sq(ZLS)));
  r.KFalpha = std::clamp(K, 1.0, e / (0.25 * p.epsVa + 0.75));
}

// Y_Fa and Y_Sa of ISO 10300-3 method B1: ISO 6336-3's 30-degree tangent in the fillet the
// cutter (tool addendum h_a0 = k_hfp m_mn, edge radius rho_a0) generates on the normal
// section's virtual gear, the load at the tip. Lengths in mm.
struct TipForm {
  double sFn, hFa, rhoF, YFa, YSa, qs, sAn;
};

TipForm tipForm(const Pair& p, int i, double xhm, double xsm, double rhoA0, double khfp) {
  const double m = p.mmn;
  ToothForm f = filletForm(p.zvn[i], m, p.alphaN, xhm, xsm, khfp, rhoA0 / m, p.dvan[i]);
  TipForm t{};
  t.sAn = f.gamma * p.dvan[i];
  if (!(t.sAn > 0))
    throw std::domain_error(fmt::format("the {}'s teeth are pointed: no tooth thickness is left at the virtual gear's tip (shift {:.4g}, "
                                        "thickness modification {:.4g})",
                                        i ? "wheel" : "pinion", xhm, xsm));
  t.sFn = f.sFn;
  t.hFa = f.hFe;
  t.rhoF = f.rhoF;
  t.YFa = f.YF;
  t.YSa = f.YS;
  t.qs = f.sFn / (2 * f.rhoF);
  if (!(t.sFn > 0 && t.hFa > 0 && t.rhoF > 0 && std::isfinite(t.YFa) && std::isfinite(t.YSa)))
    throw std::domain_error(fmt::format("the {}'s tooth root has no 30-degree tangent section (check the shift and the cutter edge radius)",
                                        i ? "wheel" : "pinion"));
  return t;
}

// Y_BS, the bevel spiral angle factor of ISO 10300-3: the middle contact line's length across
// the face against the face's, through coefficients in the face over the mean tooth depth.
double spiralFactor(const Pair& p, double lbm) {
  double ba = p.b / std::cos(p.betaM), lbb = lbm * std::cos(p.betaVb) / std::cos(p.betaM);
  double x = 2 * ba / (p.ham[0] + p.hfm[0] + p.ham[1] + p.hfm[1]);
  double a = -0.0182 * x * x + 0.4736 * x - 0.32, b = -0.0032 * x * x + 0.0526 * x + 0.712, c = -0.0050 * x * x + 0.0850 * x + 0.54;
  // The coefficients are fits over the usual face widths (x near 4 to 8); far beyond, c
  // falls to 0 and the factor loses its meaning.
  if (!(x < 15))
    throw std::domain_error(fmt::format("the face width is {:.3g} times the mean tooth depth: beyond the range of the bevel spiral angle "
                                        "factor Y_BS (keep b below about 10 outer modules and R_e/3)",
                                        x));
  return a / c * sq(lbb / ba - 1.05 * b) + 1;
}

// One gear: flank (ISO 10300-2) and root (ISO 10300-3); stresses in N/mm^2 until the end.
void rateGear(const BevelInput& in, const Pair& p, const BevelRating& r, const FlankFactors& flank, int i, BevelGearRating& o) {
  const auto& gi = in.gear[static_cast<size_t>(i)];
  const Treatment t = treatmentOf(in, i);
  o.cycles = gi.speed / (2 * kPi) * in.life;
  o.ZNT = lifeFactorOf(o.cycles, contactCurve(t), in.optimumLife);
  o.YNT = lifeFactorOf(o.cycles, bendingCurve(t), in.optimumLife);
  FlankFactors f = flankFactorsAt(flank, o.cycles, t);
  o.ZL = f.ZL;
  o.Zv = f.Zv;
  o.ZR = f.ZR;
  o.ZW = workHardeningFactor(t, treatmentOf(in, 1 - i), gi.brinell);  // as ISO 6336-2
  o.ZX = 1;
  o.sigmaH = r.sigmaH;
  o.sigmaHG = gi.sigmaHlim * 1e-6 * o.ZNT * o.ZX * o.ZL * o.Zv * o.ZR * o.ZW * r.ZK;
  o.sigmaHP = o.sigmaHG / in.SHmin;
  o.SH = o.sigmaHG / o.sigmaH;
  double rhoA0 = std::isfinite(gi.edgeRadius) ? gi.edgeRadius * 1e3 : 0.2 * p.mmn;
  TipForm tf = tipForm(p, i, gi.xhm, gi.xsm, rhoA0, in.khfp);
  o.sFn = tf.sFn * 1e-3;
  o.sAn = tf.sAn * 1e-3;
  o.hFa = tf.hFa * 1e-3;
  o.rhoF = tf.rhoF * 1e-3;
  o.YFa = tf.YFa;
  o.YSa = tf.YSa;
  RootFactors rf = rootFactors(t, tf.qs, tf.YSa, in.RzRoot * 1e6, p.mmn, o.cycles);
  o.YdeltarelT = rf.YdeltarelT;
  o.YRrelT = rf.YRrelT;
  o.YX = rf.YX;
  o.sigmaF0 = r.Ft / (p.b * p.mmn) * o.YFa * o.YSa * r.Yeps * r.YBS * r.YLS;
  o.sigmaF = o.sigmaF0 * in.KA * r.Kv * r.KFbeta * r.KFalpha;
  o.sigmaFG = gi.sigmaFlim * 1e-6 * 2.0 * o.YNT * o.YdeltarelT * o.YRrelT * o.YX;
  o.sigmaFP = o.sigmaFG / in.SFmin;
  o.SF = o.sigmaFG / o.sigmaF;
  for (double* s : {&o.sigmaH, &o.sigmaHG, &o.sigmaHP, &o.sigmaF0, &o.sigmaF, &o.sigmaFG, &o.sigmaFP}) *s *= 1e6;
}

BevelRating geometryOf(const Pair& p) {
  BevelRating r{};
  r.Re = p.Re * 1e-3;
  r.Rm = p.Rm * 1e-3;
  r.b = p.b * 1e-3;
  r.bEff = p.bEff * 1e-3;
  r.mmn = p.mmn * 1e-3;
  r.mmt = p.mmt * 1e-3;
  r.av = p.av * 1e-3;
  r.uv = p.uv;
  r.alphaVt = p.alphaVt;
  r.betaVb = p.betaVb;
  r.gva = p.gva * 1e-3;
  r.epsVa = p.epsVa;
  r.epsVb = p.epsVb;
  r.epsVg = p.epsVg;
  r.rhoRel = p.rhoRel * 1e-3;
  for (int i = 0; i < 2; ++i) {
    BevelGearRating& o = r.gear[static_cast<size_t>(i)];
    o.cone = p.delta[i];
    o.dm = p.dm[i] * 1e-3;
    o.de = p.de[i] * 1e-3;
    o.ham = p.ham[i] * 1e-3;
    o.hfm = p.hfm[i] * 1e-3;
    o.dv = p.dv[i] * 1e-3;
    o.dva = p.dva[i] * 1e-3;
    o.dvb = p.dvb[i] * 1e-3;
    o.zv = p.zv[i];
    o.zvn = p.zvn[i];
  }
  return r;
}

} // namespace

BevelRating bevelGeometry(const BevelInput& in) {
  const Pair p = pairOf(in, false);
  BevelRating r = geometryOf(p);
  r.Ft = 2000 * in.torque1 / p.dm[0];
  r.v = in.gear[0].speed * p.dm[0] * 1e-3 / 2;
  return r;
}

BevelRating rateBevel(const BevelInput& in) {
  const Pair p = pairOf(in);
  BevelRating r = geometryOf(p);
  r.Ft = 2000 * in.torque1 / p.dm[0];
  r.Fn = r.Ft / (std::cos(in.alphaN) * std::cos(in.betaM));
  r.v = in.gear[0].speed * p.dm[0] * 1e-3 / 2;
  const ContactLines lines = contactLines(p, p.b);
  r.lbm = lines.lbm * 1e-3;
  r.lbt = lines.lbt * 1e-3;
  r.fmax = lines.fmax * 1e-3;
  r.ZLS = lines.ZLS;
  // The larger single pitch deviation after running-in (the softer flank's allowance).
  const double fpt = std::max(in.gear[0].fpt, in.gear[1].fpt) * 1e6;
  const double sigmaHlim = std::min(in.gear[0].sigmaHlim, in.gear[1].sigmaHlim) * 1e-6;
  Treatment soft = in.gear[0].sigmaHlim <= in.gear[1].sigmaHlim ? treatmentOf(in, 0) : treatmentOf(in, 1);
  r.yAlpha = runningIn(fpt, soft, sigmaHlim, r.v);
  dynamicFactor(in, p, fpt, r);
  loadFactors(in, p, fpt, r.ZLS, r);
  // Pitting (ISO 10300-2 method B1): the mid-zone point, F1 and F2 by the face contact ratio.
  double F1 = p.epsVa, F2 = p.epsVa;
  if (p.epsVb < 1) {
    F1 = 2 + (p.epsVa - 2) * p.epsVb;
    F2 = 2 * p.epsVa - 2 + (2 - p.epsVa) * p.epsVb;
  }
  r.ZMB = std::tan(p.alphaVt) / std::sqrt((std::sqrt(sq(p.dva[0] / p.dvb[0]) - 1) - F1 * kPi / p.zv[0]) *
                                          (std::sqrt(sq(p.dva[1] / p.dvb[1]) - 1) - F2 * kPi / p.zv[1]));
  auto compliance = [&](int i) {
    const auto& g = in.gear[static_cast<size_t>(i)];
    double E = std::isfinite(g.E) ? g.E : in.E, nu = std::isfinite(g.nu) ? g.nu : in.nu;
    return (1 - nu * nu) / (E * 1e-6);
  };
  r.ZE = std::sqrt(1 / (kPi * (compliance(0) + compliance(1))));
  r.Zbeta = 1;  // method B1 takes the spiral angle into the contact lines and the curvature
  // The bevel gear factor on the permissible side, as ISO 10300-2 (2023) has it.
  r.ZK = 1.2;
  if (!(lines.lbm > 0 && std::isfinite(r.ZMB))) throw std::domain_error("the mid-zone point lies outside the path of contact");
  r.sigmaH0 = std::sqrt(r.Fn / (lines.lbm * p.rhoRel)) * r.ZMB * r.ZLS * r.ZE * r.Zbeta;
  r.sigmaH = r.sigmaH0 * std::sqrt(in.KA * r.Kv * r.KHbeta * r.KHalpha);
  // Bending (ISO 10300-3 method B1).
  double yeps0 = 0.25 + 0.75 / p.epsVa;
  r.Yeps = p.epsVb >= 1 ? 0.625 : yeps0 - p.epsVb * (yeps0 - 0.625);
  r.YLS = sq(r.ZLS);
  r.YBS = spiralFactor(p, lines.lbm);
  double Rz = in.RzFlank * 1e6;
  const FlankFactors flank = flankFactors(sigmaHlim, in.nu40 * 1e6, r.v, Rz, p.rhoRel);
  for (int i = 0; i < 2; ++i) rateGear(in, p, r, flank, i, r.gear[static_cast<size_t>(i)]);
  r.sigmaH0 *= 1e6;
  r.sigmaH *= 1e6;
  return r;
}

} // namespace gbx::rt::rating
