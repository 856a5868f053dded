#include "rating/Scuffing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace gbx::rt::rating {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kZeroC = 273.15;
double sq(double x) { return x * x; }

// The lubricant factor of friction by base oil (ISO/TS 6336-20 and -22).
double oilTypeFactor(OilBase b) {
  switch (b) {
  case OilBase::Mineral: return 1.0;
  case OilBase::Polyalphaolefin: return 0.8;
  case OilBase::Polyglycol: return 0.7;  // not soluble in water
  case OilBase::PhosphateEster: return 1.3;
  case OilBase::Traction: return 1.5;
  }
  return 1.0;
}

// The mesh on its path of contact, in the standards' units (mm, m/s, N/mm^2).
struct Path {
  double u, alphaT, alphaWt, betaB, rhoC1, pbt, v, omega1;
  double gA, gB, gD, gE, epsAlpha, epsBeta, eps1, eps2, rhoRedC, vSumC;

  double rho1(double g) const { return rhoC1 * (1 + g); }
  double rho2(double g) const { return rhoC1 * (u - g); }
  // Relative radius of curvature in the normal section.
  double rhoN(double g) const { return rho1(g) * rho2(g) / ((rho1(g) + rho2(g)) * std::cos(betaB)); }
  double vr1(double g) const { return omega1 * rho1(g) * 1e-3; }
  double vr2(double g) const { return omega1 / u * rho2(g) * 1e-3; }
};

Path pathOf(const ScuffingMesh& m) {
  Path p;
  double mn = m.mn * 1e3, a = m.a * 1e3;
  p.u = m.z2 / m.z1;
  p.alphaT = std::atan(std::tan(m.alphaN) / std::cos(m.beta));
  p.betaB = std::asin(std::sin(m.beta) * std::cos(m.alphaN));
  double mt = mn / std::cos(m.beta), rb1 = m.z1 * mt / 2 * std::cos(p.alphaT), rb2 = m.z2 * mt / 2 * std::cos(p.alphaT);
  // An internal gear's z2, r_b2, r_a2 and the centre distance a are negative (the signed
  // convention): the same formulas then hold for both kinds of mesh.
  double c = (rb1 + rb2) / a;
  if (!(c > 0 && c < 1)) throw std::domain_error("the centre distance is too small for the base circles");
  p.alphaWt = std::acos(c);
  p.rhoC1 = rb1 * std::tan(p.alphaWt);
  double ra1 = m.da1 * 1e3 / 2, ra2 = m.da2 * 1e3 / 2;
  if (!(ra1 > rb1 && std::fabs(ra2) > std::fabs(rb2) && ra2 * rb2 > 0))
    throw std::domain_error("a tip circle lies inside its base circle");
  double rhoE1 = std::sqrt(sq(ra1) - sq(rb1)), rhoA2 = std::copysign(std::sqrt(sq(ra2) - sq(rb2)), m.z2);
  p.pbt = 2 * kPi * rb1 / m.z1;
  p.gE = rhoE1 / p.rhoC1 - 1;
  p.gA = (a * std::sin(p.alphaWt) - rhoA2) / p.rhoC1 - 1;
  p.gB = p.gE - p.pbt / p.rhoC1;
  p.gD = p.gA + p.pbt / p.rhoC1;
  p.eps1 = p.gE * p.rhoC1 / p.pbt;
  p.eps2 = -p.gA * p.rhoC1 / p.pbt;
  p.epsAlpha = p.eps1 + p.eps2;
  if (!(p.gA < 0 && p.gE > 0 && p.epsAlpha > 0))
    throw std::domain_error("the path of contact does not pass the pitch point (the flash temperature needs both sides of it)");
  p.epsBeta = m.b * 1e3 * std::sin(m.beta) / (kPi * mn);
  p.omega1 = m.speed1;
  p.v = m.speed1 * m.z1 * mt / 2 * 1e-3;
  p.rhoRedC = p.u * a * std::sin(p.alphaWt) / (sq(1 + p.u) * std::cos(p.betaB));
  p.vSumC = 2 * p.v * std::tan(p.alphaWt) * std::cos(p.alphaT);
  return p;
}

// Load sharing X_Gamma on the unmodified flanks with the buttressing factor at the ends of
// the path (ISO/TS 6336-20 clause 9): spur from its accuracy, wide helical 1/eps_alpha,
// narrow helical between the two.
double loadSharing(const Path& p, double g, int grade) {
  double q = std::max(grade > 0 ? grade : 7, 7);
  double end = (q - 2) / 15;
  double spur = g < p.gB ? end + (g - p.gA) / (p.gB - p.gA) / 3 : g > p.gD ? end + (p.gE - g) / (p.gE - p.gD) / 3 : 1.0;
  if (p.gB <= p.gA || p.gD >= p.gE) spur = 1.0;  // eps_alpha <= 1: one pair carries the load
  if (p.gD <= p.gB) spur = 1 / p.epsAlpha;       // eps_alpha >= 2: never one pair alone (beyond the methods' range)
  double x = p.epsBeta >= 1 ? 1 / p.epsAlpha : (1 - p.epsBeta) * spur + p.epsBeta / p.epsAlpha;
  double buttress = p.epsBeta >= 1 ? 1.3 : 1 + 0.3 * p.epsBeta;
  double zone = 0.2 * std::sin(p.betaB);
  if (zone > 0) {
    if (g < p.gA + zone) x *= 1 + (buttress - 1) * (p.gA + zone - g) / zone;
    else if (g > p.gE - zone) x *= 1 + (buttress - 1) * (g - (p.gE - zone)) / zone;
  }
  return x;
}

double helicalLoadFactor(double epsGamma) {
  if (epsGamma <= 2) return 1.0;
  if (epsGamma < 3.5) return 1 + 0.2 * std::sqrt((epsGamma - 2) * (5 - epsGamma));
  return 1.3;
}

// Mean friction coefficient at the pitch point; `roughness` false for ISO/TR 13989-1's
// flash temperature form (no X_R).
double friction(const Path& p, double wBt, double KBgamma, double eta, double Ra, double XL, bool roughness) {
  double w = std::max(wBt, 150.0) * KBgamma, v = std::min(p.vSumC, 2 * 50 * std::tan(p.alphaWt) * std::cos(p.alphaT));
  double XR = 2.2 * std::pow(Ra / p.rhoRedC, 0.25);
  return 0.045 * std::pow(w / (v * p.rhoRedC), 0.2) * std::pow(eta, -0.05) * (roughness ? XR : 1.0) * XL;
}

// X_G; for an internal mesh (u < 0) u + 1 and u - Gamma are both negative and enter as
// magnitudes, their ratio being the concave flank's share of the relative curvature.
double geometryFactor(const Path& p, double g) {
  return 0.51 * std::sqrt(std::fabs(p.u + 1)) * std::fabs(std::sqrt(1 + g) - std::sqrt(1 - g / p.u)) /
         (std::pow(1 + g, 0.25) * std::pow(std::fabs(p.u - g), 0.25));
}

// X_epsilon of the integral temperature (ISO/TS 6336-21) from the addendum contact ratios.
double contactRatioFactor(double ea, double e1, double e2) {
  if (ea < 1) return (sq(e1) + sq(e2)) / (2 * ea);
  double d = 2 * ea * e1;
  if (ea < 2) {
    if (e1 < 1 && e2 < 1) return (0.70 * (sq(e1) + sq(e2)) - 0.22 * ea + 0.52 - 0.60 * e1 * e2) / d;
    if (e1 >= 1) return (0.18 * sq(e1) + 0.70 * sq(e2) + 0.82 * e1 - 0.52 * e2 - 0.30 * e1 * e2) / d;
    return (0.70 * sq(e1) + 0.18 * sq(e2) - 0.52 * e1 + 0.82 * e2 - 0.30 * e1 * e2) / d;
  }
  if (e1 >= e2) return (0.44 * sq(e1) + 0.59 * sq(e2) + 0.30 * e1 - 0.30 * e2 - 0.15 * e1 * e2) / d;
  return (0.59 * sq(e1) + 0.44 * sq(e2) - 0.30 * e1 + 0.30 * e2 - 0.15 * e1 * e2) / d;
}

// Pressure-viscosity coefficient [m^2/N] at theta [degC] (ISO/TS 6336-22).
double pressureViscosity(const Lubricant& oil, double thetaC) {
  double eta38 = oil.dynamic(38 + kZeroC);  // N s/m^2
  double a38 = oil.base == OilBase::Mineral ? 2.657e-8 * std::pow(eta38, 0.1348) : 1.466e-8 * std::pow(eta38, 0.0507);
  return a38 * (1 + 516 * (1 / (thetaC + 273) - 1.0 / 311));
}

// Positions on the path from A to E: `points` even steps and the named points B, C, D,
// so that the pitch point (no sliding) is one of them.
std::vector<double> grid(const Path& p, int points) {
  std::vector<double> g;
  for (int i = 0; i <= points; ++i) g.push_back(p.gA + (p.gE - p.gA) * i / points);
  for (double named : {p.gB, 0.0, p.gD})
    if (named > p.gA && named < p.gE) g.push_back(named);
  std::sort(g.begin(), g.end());
  g.erase(std::unique(g.begin(), g.end(), [](double x, double y) { return std::fabs(x - y) < 1e-12; }), g.end());
  return g;
}

// w_Bt [N/mm]: the tangential force per face width with its load factors.
double lineLoad(const ScuffingMesh& m) { return m.loadFactor() * m.Ft / (m.b * 1e3); }

struct Film {
  double thetaM, mu, lambdaMin, gammaMin;
  std::vector<double> h, lambda;  // at each of the positions given
};

// Film thickness at the positions `gammas` on the path (ISO/TS 6336-22 method B) at the oil
// temperature thetaOil [degC]: the bulk temperature, each point's flash and contact
// temperature, and the Dowson-Higginson film with the local temperature's viscosity.
Film film(const ScuffingMesh& m, const Path& p, const Lubricant& oil, double thetaOil, double Er, double BM, int grade,
          const std::vector<double>& gammas) {
  Film f;
  double KBg = helicalLoadFactor(p.epsAlpha + p.epsBeta);
  f.mu = friction(p, lineLoad(m), KBg, oil.dynamic(thetaOil + kZeroC) * 1e3, m.Ra * 1e6, oilTypeFactor(oil.base), true);
  // The loss factor; an internal mesh's negative z2 lowers it (less sliding).
  double HV = (sq(p.eps1) + sq(p.eps2) + 1 - p.epsAlpha) * (1 / m.z1 + 1 / m.z2) * kPi / std::cos(p.betaB);
  double emax = std::max(p.eps1, p.eps2);
  double XCa = std::min(m.Ca[0], m.Ca[1]) * 1e6 >= m.effectiveRelief() ? 1 + 0.24 * emax + 0.71 * sq(emax) : 1.0;
  double XS = oil.injection ? 1.2 : 1.0;
  f.thetaM = thetaOil +
             7400 * std::pow(m.power * 1e-3 * f.mu * HV / (std::fabs(m.a) * 1e3 * m.b * 1e3), 0.72) * XS / (1.2 * XCa);
  double etaM = oil.dynamic(f.thetaM + kZeroC), alphaM = pressureViscosity(oil, f.thetaM);
  double load = m.loadFactor();
  f.lambdaMin = INFINITY;
  f.gammaMin = p.gA;
  for (double g : gammas) {
    double rho = p.rhoN(g), XY = loadSharing(p, g, grade);
    double pH = std::sqrt(Er / (2 * kPi)) * std::sqrt(m.Ft * XY / (m.b * 1e3 * rho * std::cos(p.alphaT) * std::cos(p.betaB)));
    double pdyn = pH * std::sqrt(load);
    double v1 = p.vr1(g), v2 = p.vr2(g), vg = std::fabs(v1 - v2);
    // Local flash temperature in SI: p [Pa], the contact width [m], B_M [N/(m s^0.5 K)].
    double width = std::sqrt(8 * rho * 1e-3 * pdyn / Er);
    double fla = std::sqrt(kPi) / 2 * f.mu * pdyn * 1e6 * vg * width / (BM * (std::sqrt(v1) + std::sqrt(v2)));
    double thetaB = f.thetaM + fla;
    double G = 1e6 * alphaM * Er;
    double U = etaM * (v1 + v2) / (2000 * Er * rho);
    double W = 2 * kPi * sq(pdyn) / sq(Er);
    double S = pressureViscosity(oil, thetaB) * oil.dynamic(thetaB + kZeroC) / (alphaM * etaM);
    double h = 1600 * rho * std::pow(G, 0.6) * std::pow(U, 0.7) * std::pow(W, -0.13) * std::pow(S, 0.22);  // um
    double lam = h / (m.Ra * 1e6);
    if (!std::isfinite(lam) || !std::isfinite(thetaB))
      throw std::domain_error(fmt::format("the film thickness is not finite at Gamma {:.4g} (contact temperature {:.4g} degC): the oil's "
                                          "viscosity or pressure-viscosity line does not reach that temperature",
                                          g, thetaB));
    f.h.push_back(h * 1e-6);
    f.lambda.push_back(lam);
    if (lam < f.lambdaMin) {
      f.lambdaMin = lam;
      f.gammaMin = g;
    }
  }
  return f;
}

// The FVA 54/7 test (gear C-GF at 8.3 m/s, 90 degC, dip lubrication) at a load stage,
// with the service oil: lambda_GF,min of the test.
double testFilmThickness(const Lubricant& oil, int stage, double Er, double BM, int points) {
  ScuffingMesh t;
  t.z1 = 16;
  t.z2 = 24;
  t.mn = 4.5e-3;
  t.alphaN = 20 * kPi / 180;
  t.a = 91.5e-3;
  t.b = 14e-3;
  t.da1 = 82.46e-3;
  t.da2 = 118.36e-3;
  t.speed1 = 2170 * kPi / 30;
  double T1 = fzgPinionTorque(stage);
  t.Ft = 2 * T1 / (t.z1 * t.mn);
  t.power = T1 * t.speed1;
  t.Ra = 0.5e-6;
  Lubricant test = oil;
  test.injection = false;
  Path p = pathOf(t);
  return film(t, p, test, 90, Er, BM, 5, grid(p, points)).lambdaMin;
}

// The test depends on the oil alone, so a search rating many designs on one oil computes
// it once per thread.
double cachedTestFilmThickness(const Lubricant& oil, int stage, double Er, double BM, int points) {
  using Key = std::array<double, 7>;
  thread_local std::vector<std::pair<Key, double>> cache;
  Key k{oil.nu40, oil.nu100, oil.density15, static_cast<double>(oil.base), static_cast<double>(stage), Er, BM};
  for (const auto& [key, v] : cache)
    if (key == k) return v;
  double v = testFilmThickness(oil, stage, Er, BM, points);
  if (cache.size() > 64) cache.clear();
  cache.emplace_back(k, v);
  return v;
}

// The integral temperature (ISO/TS 6336-21), run in (Phi_E = 1: X_E = 1), into r; muC the
// friction at the pitch point, a [mm].
void integralTemperature(const ScuffingMesh& m, const Path& p, const Lubricant& oil, double muC, double a,
                         ScuffingRating& r) {
  const double thetaOil = oil.oilTemperature - kZeroC, Ltype = oilTypeFactor(oil.base);
  double XBE = geometryFactor(p, p.gE);
  double ratio = p.eps2 / std::max(p.eps1, 1e-12); // approach over recess, pinion driving
  double XQ = ratio <= 1.5 ? 1.0 : ratio < 3 ? 1.4 - 4.0 / 15 * ratio : 0.6;
  double emax = std::max(p.eps1, p.eps2);
  double Ca = std::min(p.eps1 >= p.eps2 ? m.Ca[0] * 1e6 : m.Ca[1] * 1e6, r.Ceff);
  double q = r.Ceff > 0 ? Ca / r.Ceff : 0;
  double XCa = 1 + (0.06 + 0.18 * q) * emax + (0.02 + 0.69 * q) * sq(emax);
  double flaE = muC * r.XM * r.XalphaBeta * XBE * std::pow(r.KBgamma * r.wBt, 0.75) * std::sqrt(p.v) /
                (std::pow(a, 0.25) * XQ * XCa);
  r.thetaFlaInt = flaE * contactRatioFactor(p.epsAlpha, p.eps1, p.eps2);
  r.thetaMInt = thetaOil + 0.7 * m.Xmp * r.XS * r.thetaFlaInt;
  r.thetaInt = r.thetaMInt + 1.5 * r.thetaFlaInt;
  double T1T = fzgPinionTorque(oil.fzgStage);
  double thetaMT = 80 + 0.23 * T1T * Ltype, thetaFlaIntT = 0.2 * T1T * std::pow(100 / (oil.nu40 * 1e6), 0.02) * Ltype;
  r.thetaIntS = thetaMT + 1.5 * thetaFlaIntT;
  // S_intS is a ratio of Celsius temperatures, as the standard states it: it needs both above 0 degC.
  if (!(r.thetaInt > 0))
    throw std::domain_error(
        fmt::format("the integral temperature {:.4g} degC is not above 0 degC, where S_intS (a ratio of Celsius "
                    "temperatures) has no meaning",
                    r.thetaInt));
  r.SintS = r.thetaIntS / r.thetaInt;
}

} // namespace

double Lubricant::kinematic(double T) const {
  // log10 log10(nu + 0.7) = A - B log10 T, nu in mm^2/s.
  double y40 = std::log10(std::log10(nu40 * 1e6 + 0.7)), y100 = std::log10(std::log10(nu100 * 1e6 + 0.7));
  double x40 = std::log10(40 + kZeroC), x100 = std::log10(100 + kZeroC);
  double y = y40 + (y100 - y40) * (std::log10(T) - x40) / (x100 - x40);
  return (std::pow(10.0, std::pow(10.0, y)) - 0.7) * 1e-6;
}

double Lubricant::density(double T) const { return density15 - 0.7 * (T - 289); }

double Lubricant::dynamic(double T) const { return kinematic(T) * density(T); }

double fzgPinionTorque(int stage) { return 3.726 * stage * stage; }

ScuffingRating rateScuffing(const ScuffingMesh& m, const Lubricant& oil, ScuffingEdition edition) {
  if (!(m.z1 > 0 && (m.z2 > 0 || -m.z2 > m.z1) && m.a * m.z2 > 0 && m.da2 * m.z2 > 0))
    throw std::domain_error("an internal mesh's ring needs more teeth than its pinion, and its z, tip diameter and "
                            "centre distance negative");
  if (!(oil.nu40 > oil.nu100 && oil.nu100 > 0))
    throw std::domain_error("the oil's viscosity at 40 degC must exceed its viscosity at 100 degC (the ASTM D341 line)");
  const Path p = pathOf(m);
  ScuffingRating r;
  r.gammaA = p.gA;
  r.gammaB = p.gB;
  r.gammaD = p.gD;
  r.gammaE = p.gE;
  r.epsAlpha = p.epsAlpha;
  r.epsBeta = p.epsBeta;
  const double thetaOil = oil.oilTemperature - kZeroC;
  const double Er = 2 / ((1 - sq(m.nu[0])) / m.E[0] + (1 - sq(m.nu[1])) / m.E[1]) * 1e-6;  // N/mm^2
  const double BM = (m.BM[0] + m.BM[1]) / 2;
  const int grade = m.grade;
  const int points = 400;
  r.wBt = lineLoad(m);
  r.vw = p.v * std::cos(p.alphaT) / std::cos(p.alphaWt);
  r.KBgamma = helicalLoadFactor(p.epsAlpha + p.epsBeta);
  r.XalphaBeta = 1.22 * std::pow(std::sin(p.alphaWt), 0.25) * std::pow(std::cos(m.alphaN), 0.25) * std::pow(std::cos(m.beta), 0.25) /
                 (std::sqrt(std::cos(p.alphaWt)) * std::sqrt(std::cos(p.alphaT)));
  r.XM = 1e3 * std::pow(Er * 1e6, 0.25) / BM;  // in the mixed units of the formula below
  r.etaOil = oil.dynamic(oil.oilTemperature);
  const double etaMPas = r.etaOil * 1e3, Ltype = oilTypeFactor(oil.base);
  const bool tr = edition == ScuffingEdition::TR;
  r.XL = tr ? Ltype * std::pow(etaMPas, -0.05) : Ltype;
  r.XR = 2.2 * std::pow(m.Ra * 1e6 / p.rhoRedC, 0.25);
  r.XS = oil.injection ? 1.2 : 1.0;
  // The friction of the integral and micropitting parts, and of the TS's flash temperature;
  // ISO/TR 13989-1 writes the viscosity term into X_L and has no roughness factor.
  const double muC = friction(p, r.wBt, r.KBgamma, etaMPas, m.Ra * 1e6, Ltype, true);
  r.muM = tr ? friction(p, r.wBt, r.KBgamma, etaMPas, m.Ra * 1e6, Ltype, false) : muC;
  const double Ceff = m.effectiveRelief();  // um
  r.Ceff = Ceff;
  const double a = std::fabs(m.a) * 1e3;
  // Flash temperature along the path (pinion driving: the approach is Gamma < 0).
  const std::vector<double> gammas = grid(p, points);
  std::vector<double> fla, XG;
  double sum = 0;
  for (size_t i = 0; i < gammas.size(); ++i) {
    double g = gammas[i];
    double XJ = g < 0 ? std::max(1.0, 1 + (Ceff - m.Ca[1] * 1e6) / 50 * std::pow(-g / (p.gE - p.gA), 3)) : 1.0;
    XG.push_back(loadSharing(p, g, grade));
    fla.push_back(r.muM * r.XM * XJ * r.XalphaBeta * geometryFactor(p, g) * std::pow(XG.back() * r.wBt, 0.75) * std::sqrt(p.v) /
                  std::pow(a, 0.25));
    if (i > 0) sum += (fla[i] + fla[i - 1]) / 2 * (g - gammas[i - 1]);
  }
  r.thetaFlm = sum / (p.gE - p.gA);
  r.thetaM = thetaOil + 0.47 * r.XS * m.Xmp * r.thetaFlm;
  for (size_t i = 0; i < gammas.size(); ++i) {
    double thetaB = r.thetaM + fla[i];
    r.path.push_back({gammas[i], XG[i], fla[i], thetaB + kZeroC, 0, 0});
    if (i == 0 || thetaB > r.thetaBmax) {
      r.thetaBmax = thetaB;
      r.gammaMax = gammas[i];
      r.XGammaMax = XG[i];
    }
  }
  for (const auto& q : r.path)
    if (!std::isfinite(q.thetaB))
      throw std::domain_error(fmt::format("the contact temperature is not finite at Gamma {:.4g}", q.gamma));
  const double LS2 = sq(oil.fzgStage);
  r.thetaS = 80 + (0.85 + 1.4 * m.XW) * r.XL * LS2;
  if (oil.fzgStage > 0 && !(r.thetaS > thetaOil))
    throw std::domain_error(fmt::format("the scuffing temperature of FZG load stage {} ({:.4g} degC) is not above the oil's {:.4g} degC",
                                        oil.fzgStage, r.thetaS, thetaOil));
  r.SB = (r.thetaS - thetaOil) / (r.thetaBmax - thetaOil);
  integralTemperature(m, p, oil, muC, a, r);
  r.scuffing = oil.fzgStage > 0;
  if (!r.scuffing) r.thetaS = r.SB = r.thetaIntS = r.SintS = std::numeric_limits<double>::quiet_NaN();
  // Micropitting (ISO/TS 6336-22 method B).
  if (oil.fvaStage > 0) {
    Film f = film(m, p, oil, thetaOil, Er, BM, grade, gammas);
    r.muMmp = f.mu;
    r.thetaMmp = f.thetaM + kZeroC;
    r.lambdaMin = f.lambdaMin;
    r.gammaLambdaMin = f.gammaMin;
    for (size_t i = 0; i < r.path.size(); ++i) {
      r.path[i].h = f.h[i];
      r.path[i].lambda = f.lambda[i];
    }
    r.lambdaGFT = cachedTestFilmThickness(oil, oil.fvaStage, Er, BM, points);
    r.lambdaGFP = 1.4 * m.WW * r.lambdaGFT;
    r.Slambda = r.lambdaMin / r.lambdaGFP;
    r.micropitting = true;
  } else {
    r.muMmp = r.thetaMmp = r.lambdaMin = r.lambdaGFT = r.lambdaGFP = r.Slambda = std::numeric_limits<double>::quiet_NaN();
  }
  // Temperatures out in kelvin.
  r.thetaM += kZeroC;
  r.thetaS += kZeroC;
  r.thetaBmax += kZeroC;
  r.thetaMInt += kZeroC;
  r.thetaInt += kZeroC;
  r.thetaIntS += kZeroC;
  return r;
}

} // namespace gbx::rt::rating
