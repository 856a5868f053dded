// Independent reference for ISO 6336-3:2006 method B Y_F / Y_S with a numerically generated
// fillet. See FilletReference.h for scope and units (mm, rad).
#include "FilletReference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gbx::testref {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// The fillet is evaluated in long double: finite differences at fine sampling steps subtract
// coordinates of ~1e2 mm that differ by ~1e-5 mm.
using Real = long double;
struct Pt { Real x, y; };

double involute(double a) { return std::tan(a) - a; }

// Generation of the virtual spur gear (pitch radius r) by the basic rack of the tool.
// Rack frame: u along the rolling (pitch) line, v normal to it, positive away from the gear
// centre, v = 0 on the rolling line; the rack datum line is at v = x*mn. The gear tooth being
// rated is centred on u = 0; the tool tooth to its right is centred on u = pi*mn/2 and its left
// flank (facing the gear tooth) passes u = pi*mn/4 at the datum line. The tool tip line is at
// v = x*mn - h_fP*mn; its rounding (radius rho) is tangent to the tip line and to that flank,
// centre (uc, vc).
// Fixed frame: gear centre at origin, pitch point P = (0, r). When the rack is displaced by s
// (+u), the gear has turned clockwise by phi = s / r; gear-frame coordinates are the fixed ones
// rotated counter-clockwise by phi, so the tooth centre line is the gear-frame y axis.
// Parameter t = fixed-frame abscissa of the tip-circle centre (t = uc + s). By the law of
// gearing the generated point is the point of the tip circle on the line through P and the
// centre that lies on the tool's tip rounding arc (the one facing the root): for vc < 0 (usual)
// F = C + rho (C - P)/|C - P|, for vc > 0 (very large positive shift) F = C - rho (C - P)/|C - P|.
// t = 0 gives the root circle, t = vc cot(alpha) the tangency with the straight flank (start of
// the involute).
struct Generator {
  Real r, uc, vc, rho;
  Pt at(Real t) const {
    const Real phi = (t - uc) / r;
    const Real n = (vc < 0 ? 1 : -1) * std::hypot(t, vc);
    const Real X = t + rho * t / n;
    const Real Y = r + vc + rho * vc / n;
    const Real c = std::cos(phi), s = std::sin(phi);
    return {X * c - Y * s, X * s + Y * c};
  }
  Real roll(Real t) const { return (t - uc) / r; }
  // Angle between the fillet tangent and the tooth centre line (central difference with the
  // signed step dt, which points from the root (t = 0) towards the flank (t = vc cot alpha)).
  Real tangentAngle(Real t, Real dt) const {
    const Pt a = at(t - dt), b = at(t + dt);
    return std::atan2(-(b.x - a.x), b.y - a.y);
  }
};

Real circumradius(Pt a, Pt b, Pt c) {
  const Real ab = std::hypot(b.x - a.x, b.y - a.y), bc = std::hypot(c.x - b.x, c.y - b.y);
  const Real ca = std::hypot(a.x - c.x, a.y - c.y);
  const Real cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return ab * bc * ca / (2 * std::fabs(cross));
}

}  // namespace

FilletResult filletReference(const FilletCase& c, int samples) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  FilletResult res{nan, nan, nan, nan, nan, nan, nan, nan, nan, nan};
  const double mn = c.mn, an = c.alphaN, cb = std::cos(c.beta);
  const FilletGear& g = c.gear;

  // --- actual gear pair: transverse contact ratio (ISO 21771 / ISO 6336-1 geometry) ---
  const double at = std::atan(std::tan(an) / cb);
  const double db1 = g.z * mn * std::cos(at) / cb, db2 = c.mate.z * mn * std::cos(at) / cb;
  const double awt = std::acos((g.z + c.mate.z) * mn * std::cos(at) / (2.0 * c.a * cb));
  const double gAlpha = 0.5 * (std::sqrt(g.da * g.da - db1 * db1) +
                               std::sqrt(c.mate.da * c.mate.da - db2 * db2)) -
                        c.a * std::sin(awt);
  const double epsA = gAlpha / (kPi * mn * std::cos(at) / cb);

  // --- virtual spur gear (ISO 6336-3 clause 6.2, virtual gear parameters) ---
  const double betaB = std::asin(std::sin(c.beta) * std::cos(an));
  const double cbb2 = std::cos(betaB) * std::cos(betaB);
  const double zn = g.z / (cbb2 * cb);
  const double d = g.z * mn / cb, dn = zn * mn, dbn = dn * std::cos(an);
  const double dan = dn + g.da - d;
  const double epsAn = epsA / cbb2;
  const double pbn = kPi * d * cb * std::cos(an) / g.z;  // = pi mn cos(alpha_n)
  const double q = std::sqrt(dan * dan / 4.0 - dbn * dbn / 4.0) - pbn * (epsAn - 1.0);
  const double den = 2.0 * std::sqrt(q * q + dbn * dbn / 4.0);
  const double alphaEn = std::acos(dbn / den);
  const double gammaE = (0.5 * kPi + 2.0 * g.x * std::tan(an)) / zn + involute(an) -
                        involute(alphaEn);
  const double alphaFen = alphaEn - gammaE;
  // Load line (normal to the involute at d_en, i.e. tangent to the base circle) meets the tooth
  // centre line at this distance from the gear centre:
  const double yLoad = 0.5 * den * (std::cos(gammaE) - std::sin(gammaE) * std::tan(alphaFen));
  res.zn = zn; res.epsAlpha = epsA; res.dEn = den; res.alphaFen = alphaFen;

  // --- generated fillet of the virtual gear ---
  const double rho = c.rhoFP * mn;
  Generator gen{};
  gen.r = dn / 2.0;
  gen.rho = rho;
  gen.vc = (g.x - c.hfP + c.rhoFP) * mn;
  gen.uc = kPi * mn / 4.0 + c.hfP * mn * std::tan(an) + rho * (1.0 - std::sin(an)) / std::cos(an);
  if (gen.vc == 0 || samples < 10) return res;    // vc == 0: degenerate (fillet = tool arc)
  const Real tEnd = gen.vc / std::tan(Real(an));  // same sign as vc
  const int n = samples;
  const Real dt = tEnd / (n - 1);                 // signed sampling step
  std::vector<Pt> pts(n);
  for (int i = 0; i < n; ++i) pts[i] = gen.at(i * dt);

  // Scan: angle of the sampled tangent with the centre line decreases from ~90 deg at the root
  // towards the flank; find the first sample interval where it passes 30 deg.
  const Real target = Real(30) * Real(kPi) / 180;
  auto sampledAngle = [&](int i) {
    return std::atan2(-(pts[i + 1].x - pts[i - 1].x), pts[i + 1].y - pts[i - 1].y);
  };
  int hit = -1;
  Real prev = sampledAngle(1) - target;
  for (int i = 2; i < n - 1; ++i) {
    const Real cur = sampledAngle(i) - target;
    if (prev > 0.0 && cur <= 0.0) { hit = i; break; }
    prev = cur;
  }
  if (hit < 0) return res;

  // Refine inside [t_(hit-1), t_hit] by bisection, with the same difference step dt.
  Real tA = (hit - 1) * dt, tB = hit * dt;        // f(tA) > 0 >= f(tB)
  for (int it = 0; it < 200 && std::fabs(tA - tB) > 1e-17L * (1 + std::fabs(tA)); ++it) {
    const Real tm = (tA + tB) / 2;
    (gen.tangentAngle(tm, dt) - target > 0 ? tA : tB) = tm;
  }
  const Real ts = (tA + tB) / 2;
  const Pt crit = gen.at(ts);
  res.sFn = double(2 * crit.x);
  // Fillet radius: circle through three points of the curve at +-hc around the critical point,
  // Richardson-extrapolated from hc and 2hc (O(hc^4)). hc is the sampling step, but at least
  // 1/1000 of the fillet parameter range (finer stencils lose the sagitta to round-off).
  const Real hc = (dt < 0 ? -1 : 1) * std::max(std::fabs(dt), std::fabs(tEnd) / 1000);
  const Real r1 = circumradius(gen.at(ts - hc), crit, gen.at(ts + hc));
  const Real r2 = circumradius(gen.at(ts - 2 * hc), crit, gen.at(ts + 2 * hc));
  res.rhoF = double((4 * r1 - r2) / 3);
  res.thetaDeg = 60.0 + double(gen.roll(ts)) / kDeg;

  // --- factors (ISO 6336-3 clause 6.2: Y_F; clause 7.2: Y_S) ---
  res.hFe = yLoad - double(crit.y);
  res.YF = (6.0 * res.hFe / mn * std::cos(alphaFen)) /
           ((res.sFn / mn) * (res.sFn / mn) * std::cos(an));
  const double L = res.sFn / res.hFe, qs = res.sFn / (2.0 * res.rhoF);
  res.YS = (1.2 + 0.13 * L) * std::pow(qs, 1.0 / (1.21 + 2.3 / L));
  return res;
}

}  // namespace gbx::testref
