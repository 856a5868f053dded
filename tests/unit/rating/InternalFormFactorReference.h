#pragma once
// Independent reference calculation (test oracle) for the ISO 6336-3 method B tooth form factor
// Y_F and stress correction factor Y_S of an INTERNAL SPUR gear cut by a pinion-type cutter
// (shaper). Written from the standard's definitions and from first principles; not derived from
// the gbxc sources. Units: lengths in mm, angles in rad (InternalFormFactorResult::tangentDeg and
// the *Deg diagnostics in degrees).
//
// WHAT THE STANDARD SAYS (ISO 6336-3:2006, clause 6.2, method B; 2019 the same in substance), as
// used here:
//  * Y_F = 6 (h_Fe/m_n) cos(alpha_Fen) / ((s_Fn/m_n)^2 cos(alpha_n))            (Y_F equation)
//    Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)), L = s_Fn/h_Fe, q_s = s_Fn/(2 rho_F)  (Y_S eq.)
//  * s_Fn is the chord of the tooth root at the critical section, rho_F the fillet radius there.
//    The critical section touches the fillet where the tangent makes 30 deg with the tooth centre
//    line for EXTERNAL gears and 60 deg for INTERNAL gears.
//  * The bending load acts at the outer point of single pair tooth contact of the virtual gear,
//    d_en from the d_en equation with the internal gear's z, d, d_a, d_b NEGATIVE; alpha_en =
//    arccos(d_bn/d_en); gamma_e = (pi/2 + 2 x tan(alpha_n))/z_n + inv(alpha_n) - inv(alpha_en);
//    alpha_Fen = alpha_en - gamma_e; h_Fe = distance along the tooth centre line from the critical
//    section to the point where the load line crosses the centre line (the first term of the h_Fe
//    equation, 0.5 d_en (cos gamma_e - sin gamma_e tan alpha_Fen), signed, minus the critical
//    section's position).
//  * For internal gears the standard's closed-form s_Fn2 / h_Fe2 / rho_F2 replace the internal
//    gear by a substitute RACK with the internal gear's basic rack profile (the counter-profile of
//    the tool's basic rack: dedendum h_fP2 = tool addendum, fillet radius rho_fP2 = tool tip
//    radius). The printed text of those formulas could NOT be consulted for this reference (no
//    copy of the standard was at hand); they are re-derived below from that description (60 deg
//    tangent on a circular fillet tangent to the root line and the straight flank) and reported
//    only as the diagnostic `rack`. UNVERIFIED against the printed equations.
//
// WHAT IS COMPUTED (main results): the root fillet that the pinion-type cutter actually generates,
// found numerically (the same philosophy as FilletReference.h for external gears): the cutter is
// an external gear z0, x0 with the tool basic rack addendum h_a0 = h_fP* m_n (ISO 53 profile B for
// the NREL ring: 1.25 / 0.30) and tip radius rho_a0, its tip rounding tangent to the tip circle and
// to the involute flank. Its pitch circle r_w0 rolls inside the internal gear's r_w2 (r_w2/r_w0 =
// z/z0, r_w2 - r_w0 = a0). The fillet is the envelope of the tip-rounding circle; the tangent of an
// envelope of equal circles is parallel to the path of their centres, so the 60 deg condition and
// the fillet radius (rho_F = rho_a0 + radius of curvature of the centre path) follow in closed form
// from the first and second derivative of that path; only the search for the 60 deg point is
// numerical (bracketing + bisection).
//
// Cutting centre distance a0 (the standard does not fix it; see the check file):
//  * df > 0 given: the cutter is set to cut that root diameter, a0 = (df - d_a0)/2. The NREL check
//    uses df = |d| + 2 m_n (h_fP* - x) (ISO 21771 root diameter, = 2677.618 mm as printed by the
//    commercial report). With this setting the published s_Fn and h_F are reproduced to 0.15 %.
//  * df <= 0: zero-backlash cutting (ISO 21771: inv alpha_w0 = inv alpha + 2 tan alpha (x2 + x0) /
//    (z2 + z0) with z2 = -z), root diameter = 2 a0 + d_a0.
//  The internal gear's flank (tooth thickness, load point) always follows x; only the fillet
//  follows the cutter.
//
// Sign convention of x: ISO 21771, x > 0 makes the internal gear's tooth THICKER at the reference
// circle (s = m (pi/2 + 2 x tan alpha)), i.e. |d_f| = |d| + 2 m (h_fP - x). NREL ring: x = -0.5013.
// Spur gears only (beta = 0: virtual = actual gear); no protuberance, no grinding stock.

#include <cmath>
#include <limits>

namespace gbx::ref::internal {

struct CutterData {
  double z0;    // teeth of the pinion-type cutter (external gear), z0 < z
  double x0;    // profile shift coefficient of the cutter
  double ha0;   // cutter addendum coefficient h_a0* (= h_fP* of the internal gear's basic rack)
  double rhoA0; // cutter tip radius coefficient rho_a0* (= rho_fP* of the internal gear)
};

struct InternalGearInput {
  double z;        // number of teeth of the internal gear, as a POSITIVE number
  double mn;       // module [mm]
  double alphaN;   // pressure angle [rad]
  double x;        // profile shift coefficient, ISO 21771 sign (see above)
  double da;       // tip diameter, magnitude [mm]
  double df;       // root diameter the cutter is set to, magnitude [mm]; <= 0: zero-backlash
  double epsAlpha; // transverse contact ratio of the rated mesh (internalContactRatio())
  CutterData cutter;
};

struct RackApprox { // substitute rack (ISO 6336-3 internal gears), 60 deg tangent, re-derived
  double sFn, hF, rhoF, YF, YS;
};

struct InternalFormFactorResult {
  bool ok = false; // false: cutter tip pointed / rounding does not fit, no 60 deg point, ...
  // the factors and their intermediates
  double sFn = NAN;      // root chord at the 60 deg critical section [mm]
  double hF = NAN;       // bending moment arm h_Fe [mm]
  double rhoF = NAN;     // fillet radius at the critical section [mm]
  double alphaFen = NAN; // load direction angle [rad]
  double YF = NAN, YS = NAN;
  double L = NAN, qs = NAN; // s_Fn/h_Fe and notch parameter s_Fn/(2 rho_F)
  // load point (virtual internal gear, magnitudes)
  double dEn = NAN;     // diameter of the outer point of single pair contact |d_en| [mm]
  double alphaEn = NAN; // [rad]
  double gammaE = NAN;  // ISO gamma_e with signed z (negative for internal gears) [rad]
  double rLoad = NAN;   // ring centre -> intersection of load line and tooth centre line [mm]
  // critical section
  double ySection = NAN;   // ring centre -> critical section, along the tooth centre line [mm]
  double dsFn = NAN;       // diameter through the critical point [mm]
  double tangentDeg = NAN; // angle fillet tangent / tooth centre line at the point (= 60)
  // generation
  double da0 = NAN;           // cutter tip diameter [mm]
  double a0 = NAN;            // cutting centre distance [mm]
  double alphaW0 = NAN;       // generating pressure angle [rad]
  double dfGen = NAN;         // root diameter cut, 2 a0 + d_a0 [mm]
  double cutterCentreX = NAN; // tip-rounding centre's distance from the cutter tooth axis [mm]
  RackApprox rack{NAN, NAN, NAN, NAN, NAN};
};

namespace detail {

constexpr double kPi = 3.14159265358979323846;

inline double inv(double a) { return std::tan(a) - a; }

inline double invInverse(double v) { // alpha with inv(alpha) = v, 0 < v < ~1
  double a = std::cbrt(3.0 * v);
  for (int i = 0; i < 60; ++i) {
    const double t = std::tan(a);
    a -= (inv(a) - v) / (t * t);
  }
  return a;
}

struct V2 {
  double x, y;
};
inline V2 add(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
inline V2 sub(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
inline V2 mul(double s, V2 a) { return {s * a.x, s * a.y}; }
inline double dot(V2 a, V2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(V2 a, V2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(V2 a) { return std::hypot(a.x, a.y); }
inline V2 rot(V2 a, double b) { // counter-clockwise
  return {a.x * std::cos(b) - a.y * std::sin(b), a.x * std::sin(b) + a.y * std::cos(b)};
}
inline V2 perp(V2 a) { return {-a.y, a.x}; } // +90 deg

// Cutter (external gear, tooth on the +y axis, angle eta measured clockwise from +y so that the
// right flank has x = r sin(eta) > 0). Right-flank involute at radius r:
//   eta(r) = psi0 + inv(alpha) - inv(alpha_r), psi0 = (pi/2 + 2 x0 tan alpha)/z0 (half tooth
//   angle at the reference circle); the flank normal touches the base circle at tau = eta -
//   alpha_r, and points into the tooth along (-cos tau, sin tau).
// The tip rounding centre: on that normal, rho inside the flank, at radius r_a0 - rho (tangent to
// the tip circle). Returns {NaN, NaN} if it does not exist.
inline V2 cutterRoundingCentre(double m, double alpha, const CutterData& c) {
  const double r0 = 0.5 * m * c.z0, rb0 = r0 * std::cos(alpha), ra0 = r0 + m * (c.ha0 + c.x0);
  const double rho = c.rhoA0 * m, psi0 = (0.5 * kPi + 2.0 * c.x0 * std::tan(alpha)) / c.z0;
  auto centre = [&](double r) {
    const double ar = std::acos(rb0 / r), eta = psi0 + inv(alpha) - inv(ar), tau = eta - ar;
    const V2 P{r * std::sin(eta), r * std::cos(eta)};
    return add(P, mul(rho, V2{-std::cos(tau), std::sin(tau)}));
  };
  if (!(ra0 - rho > rb0)) return {NAN, NAN};
  double lo = rb0, hi = ra0; // |centre| - (ra0 - rho) is < 0 at rb0 and > 0 at ra0
  if (norm(centre(hi)) < ra0 - rho) return {NAN, NAN};
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (norm(centre(mid)) < ra0 - rho ? lo : hi) = mid;
  }
  return centre(0.5 * (lo + hi));
}

// Path of the cutter's (right) tip-rounding centre in the frame of the internal gear, whose tooth
// SPACE is centred on +y. psi is the angle of the line of centres from +y (counter-clockwise); the
// cutter centre is at a0 (-sin psi, cos psi) and the cutter body has turned by k psi, k = -(z -
// z0)/z0 (pitch circle r_w0 rolling inside r_w2, no slip: r_w2 psi = r_w0 (psi - k psi)).
struct Path {
  double a0, k;
  V2 Cb;
  V2 C(double p) const { return add(V2{-a0 * std::sin(p), a0 * std::cos(p)}, rot(Cb, k * p)); }
  V2 d1(double p) const { return add(V2{-a0 * std::cos(p), -a0 * std::sin(p)}, mul(k, perp(rot(Cb, k * p)))); }
  V2 d2(double p) const { return add(V2{a0 * std::sin(p), -a0 * std::cos(p)}, mul(-k * k, rot(Cb, k * p))); }
};

} // namespace detail

// Transverse contact ratio of an internal spur pair (pinion z1 with tip diameter da1, internal
// gear z2 with tip diameter |da2|, working centre distance a; magnitudes):
//   eps = (sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + a sin(alpha_w)) / p_b,
//   cos(alpha_w) = (z2 - z1) m cos(alpha) / (2 a).
inline double internalContactRatio(double z1, double da1, double z2, double da2, double m, double alpha, double a) {
  const double rb1 = 0.5 * z1 * m * std::cos(alpha), rb2 = 0.5 * z2 * m * std::cos(alpha);
  const double aw = std::acos((z2 - z1) * m * std::cos(alpha) / (2.0 * a));
  const double ga =
      std::sqrt(0.25 * da1 * da1 - rb1 * rb1) - std::sqrt(0.25 * da2 * da2 - rb2 * rb2) + a * std::sin(aw);
  return ga / (detail::kPi * m * std::cos(alpha));
}

inline InternalFormFactorResult internalFormFactor(const InternalGearInput& in) {
  using namespace detail;
  InternalFormFactorResult r;
  const double m = in.mn, al = in.alphaN, z = in.z;
  const CutterData& c = in.cutter;
  const double rho = c.rhoA0 * m;
  if (!(z > c.z0 && c.z0 > 0 && m > 0 && rho > 0)) return r;

  // --- cutter and cutting centre distance -------------------------------------------------------
  r.da0 = m * (c.z0 + 2.0 * (c.ha0 + c.x0));
  const V2 Cb = cutterRoundingCentre(m, al, c);
  r.cutterCentreX = Cb.x;
  if (!(Cb.x > 0.0)) return r; // pointed or over-rounded cutter tip: not covered
  if (in.df > 0.0) {
    r.a0 = 0.5 * (in.df - r.da0);
    r.alphaW0 = std::acos((z - c.z0) * m * std::cos(al) / (2.0 * r.a0));
  } else { // ISO 21771, signed z2 = -z
    r.alphaW0 = invInverse(inv(al) + 2.0 * std::tan(al) * (in.x + c.x0) / (c.z0 - z));
    r.a0 = (z - c.z0) * m * std::cos(al) / (2.0 * std::cos(r.alphaW0));
  }
  r.dfGen = 2.0 * r.a0 + r.da0;
  const Path path{r.a0, -(z - c.z0) / c.z0, Cb};
  const double rw2 = r.a0 * z / (z - c.z0);

  // --- apex of the centre path (deepest point: root circle), C . C' = 0 --------------------------
  double lo = -kPi / z, hi = kPi / z;
  auto f = [&](double p) { return dot(path.C(p), path.d1(p)); };
  if (!(f(lo) > 0.0 && f(hi) < 0.0)) return r;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double pA = 0.5 * (lo + hi);
  // normal towards the material (outwards at the apex)
  const double sgn = dot(perp(path.d1(pA)), path.C(pA)) > 0.0 ? 1.0 : -1.0;
  auto N = [&](double p) {
    const V2 t = path.d1(p);
    return mul(sgn / norm(t), perp(t));
  };
  auto E = [&](double p) { return add(path.C(p), mul(rho, N(p))); };

  // The tooth next to the space on the +x side: centre line ct at pi/z from +y (clockwise).
  const V2 ct{std::sin(kPi / z), std::cos(kPi / z)}, cn{std::cos(kPi / z), -std::sin(kPi / z)};
  auto tangentAngle = [&](double p) { // angle between fillet tangent (|| C') and ct
    const V2 t = path.d1(p);
    return std::acos(std::min(1.0, std::fabs(dot(t, ct)) / norm(t)));
  };
  // Walk from the apex towards that tooth (distance to its centre line, -E.cn, decreasing); the
  // envelope moves parallel to C' (E' = C' (1 - rho kappa_N), kappa_N < 0 on a concave fillet).
  const double h0 = 1e-9 * rho / rw2;
  const double dir = dot(path.d1(pA), cn) > 0.0 ? 1.0 : -1.0;
  const double target = kPi / 3.0; // 60 deg (internal gears)
  double pIn = pA, pOut = NAN;
  for (double h = h0; h < 2.0 * kPi / z; h *= 1.5) { // bracket, then bisect
    const double p = pA + dir * h;
    if (tangentAngle(p) <= target) {
      pOut = p;
      break;
    }
    pIn = p;
  }
  if (std::isnan(pOut)) return r;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (pIn + pOut);
    (tangentAngle(mid) > target ? pIn : pOut) = mid;
  }
  const double pc = 0.5 * (pIn + pOut);
  const V2 Pc = E(pc);
  r.tangentDeg = tangentAngle(pc) * 180.0 / kPi;
  r.sFn = -2.0 * dot(Pc, cn);
  r.ySection = dot(Pc, ct);
  r.dsFn = 2.0 * norm(Pc);
  // fillet radius: curvature of the centre path, kappa_N = (C'' . N)/|C'|^2; the envelope of the
  // circles is the offset curve, radius |1/kappa_N - rho|; concave fillet needs 1/kappa_N < 0.
  const V2 d1 = path.d1(pc), d2 = path.d2(pc);
  const double kN = dot(d2, N(pc)) / dot(d1, d1);
  r.rhoF = rho - 1.0 / kN;
  if (!(kN < 0.0)) return r;

  // --- load at the outer point of single pair contact (virtual internal gear, z < 0) ------------
  const double zs = -z, d = zs * m, db = d * std::cos(al), dan = -in.da;
  const double pbn = kPi * d * std::cos(al) / z; // pi d cos(beta) cos(alpha_n)/|z|, negative here
  const double rad = std::sqrt(0.25 * dan * dan - 0.25 * db * db) - pbn * (in.epsAlpha - 1.0);
  const double den = 2.0 * (zs / z) * std::sqrt(rad * rad + 0.25 * db * db);
  r.dEn = std::fabs(den);
  r.alphaEn = std::acos(db / den);
  r.gammaE = (0.5 * kPi + 2.0 * in.x * std::tan(al)) / zs + inv(al) - inv(r.alphaEn);
  r.alphaFen = r.alphaEn - r.gammaE;
  // first term of the h_Fe equation, signed (negative for internal gears): radius at which the
  // load line crosses the tooth centre line
  const double yLoadSigned = 0.5 * den * (std::cos(r.gammaE) - std::sin(r.gammaE) * std::tan(r.alphaFen));
  r.rLoad = -yLoadSigned;
  r.hF = yLoadSigned - (-r.ySection); // both positions signed like d_en

  // --- factors -----------------------------------------------------------------------------------
  auto YF = [&](double s, double h) {
    return 6.0 * (h / m) * std::cos(r.alphaFen) / ((s / m) * (s / m) * std::cos(al));
  };
  auto YS = [&](double s, double h, double rf) {
    const double L = s / h, q = s / (2.0 * rf);
    return (1.2 + 0.13 * L) * std::pow(q, 1.0 / (1.21 + 2.3 / L));
  };
  r.YF = YF(r.sFn, r.hF);
  r.YS = YS(r.sFn, r.hF, r.rhoF);
  r.L = r.sFn / r.hF;
  r.qs = r.sFn / (2.0 * r.rhoF);

  // --- substitute rack (diagnostic): fillet circle rho tangent to the root line and to a straight
  // flank of half-thickness pi m/4 at h_a0 above the root; 60 deg tangent point:
  //   s_Fn/m = 2 [pi/4 + (h_a0* - rho*) tan(alpha) + rho*/cos(alpha) - rho* sin(30 deg)]
  //   section rho (1 - cos 30 deg) above the root circle d_fGen; same load point as above.
  const double ar = c.rhoA0;
  r.rack.sFn = 2.0 * m * (0.25 * kPi + (c.ha0 - ar) * std::tan(al) + ar / std::cos(al) - ar * 0.5);
  r.rack.rhoF = rho;
  r.rack.hF = (0.5 * r.dfGen - rho * (1.0 - std::cos(kPi / 6.0))) - r.rLoad;
  r.rack.YF = YF(r.rack.sFn, r.rack.hF);
  r.rack.YS = YS(r.rack.sFn, r.rack.hF, r.rack.rhoF);

  r.ok = std::isfinite(r.YF) && std::isfinite(r.YS) && r.hF > 0.0;
  return r;
}

} // namespace gbx::ref::internal
