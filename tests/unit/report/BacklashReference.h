// Reference backlash of an external cylindrical involute gear pair, computed geometrically in the
// transverse plane (ISO 21771 definitions). Units: metres and radians.
//
// Method: both flanks of one tooth of gear 1 and both flanks of the mating tooth space of gear 2 are
// built as parametric involutes of their base circles. Gear 1 is held fixed; gear 2 is rotated until
// each flank pair touches, found by bisection on the signed gap measured along the common normal
// (line of action). The rotation of gear 2 between the two contacts gives the backlash.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace gbx::test {

struct BacklashCase {
  double mn;       // normal module, m
  double alphaN;   // normal pressure angle, rad
  double beta;     // helix angle at the reference circle, rad (0 for spur)
  int z1, z2;      // tooth counts, both external gears
  double x1, x2;   // profile shift coefficients
  double a;        // actual centre distance, m
  double As1, As2; // normal tooth-thickness allowances at the reference circle, m (negative: thinner teeth)
};

struct BacklashRef {
  double jt; // circumferential (transverse) backlash, arc length on the working pitch circle at distance a, m
  double jn; // normal backlash: distance between the non-working flanks normal to the flanks, m
};

namespace backlash_detail {

using Vec2 = std::array<double, 2>;

inline Vec2 sub(const Vec2& p, const Vec2& q) { return {p[0] - q[0], p[1] - q[1]}; }
inline double dot(const Vec2& p, const Vec2& q) { return p[0] * q[0] + p[1] * q[1]; }
inline double cross(const Vec2& p, const Vec2& q) { return p[0] * q[1] - p[1] * q[0]; }
inline Vec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Root of f in [lo, hi] by bisection; f(lo) and f(hi) must differ in sign. Runs until the interval
// cannot be split any further in double precision.
inline double bisect(const std::function<double(double)>& f, double lo, double hi) {
  double flo = f(lo);
  const double fhi = f(hi);
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  if ((flo < 0.0) == (fhi < 0.0)) throw std::runtime_error("bisect: root not bracketed");
  for (int i = 0; i < 400; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= std::fmin(lo, hi) || mid >= std::fmax(lo, hi)) break;
    const double fm = f(mid);
    if (fm == 0.0) return mid;
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// Involute of the base circle (centre, rb), parametrised by the roll angle u >= 0.
// sense = +1: the string unwinds clockwise, so the polar angle decreases with radius;
// sense = -1: mirror image (polar angle increases with radius).
// With t = theta0 - sense*u the tangent point on the base circle, the curve point is
// P = centre + rb*e(t) + sense*rb*u*e'(t); the flank normal at P is the string direction sense*e'(t).
struct Involute {
  Vec2 centre{0.0, 0.0};
  double rb = 0.0;
  double theta0 = 0.0; // polar angle of the base point (start of the involute)
  int sense = 1;

  Vec2 point(double u) const {
    const double t = theta0 - sense * u;
    return {centre[0] + rb * (std::cos(t) - sense * u * std::sin(t)),
            centre[1] + rb * (std::sin(t) + sense * u * std::cos(t))};
  }
};

// Involute of base circle (centre, rb) with the given sense that passes through the point at radius r
// and polar angle gamma about the centre.
inline Involute involuteThrough(const Vec2& centre, double rb, int sense, double r, double gamma) {
  if (r < rb) throw std::invalid_argument("involuteThrough: radius inside the base circle");
  const Involute probe{{0.0, 0.0}, rb, 0.0, sense};
  const double uR = std::sqrt((r / rb) * (r / rb) - 1.0); // roll angle at which |P| = r
  const Vec2 p = probe.point(uR);
  const double lambda = std::atan2(p[1], p[0]); // polar angle of that point for theta0 = 0
  return Involute{centre, rb, gamma - lambda, sense};
}

// Straight line through p with unit direction dir.
struct Line {
  Vec2 p;
  Vec2 dir;
  double signedDistance(const Vec2& q) const { return cross(dir, sub(q, p)); }
};

// Roll angle at which the involute crosses the line (first crossing for u >= 0).
inline double intersect(const Involute& inv, const Line& line) {
  const auto f = [&](double u) { return line.signedDistance(inv.point(u)); };
  const double f0 = f(0.0);
  if (f0 == 0.0) return 0.0;
  constexpr double step = 0.02;
  for (double u = step; u < 4.0; u += step) {
    if ((f(u) < 0.0) != (f0 < 0.0)) return bisect(f, u - step, u);
  }
  throw std::runtime_error("intersect: involute does not cross the line of action");
}

// Transverse geometry of the pair at centre distance a. Gear 1 centre O1 = (0, 0), gear 2 centre
// O2 = (a, 0). A tooth of gear 1 is centred on the +x axis; the tooth space of gear 2 it engages is
// centred on the -x direction seen from O2 when gear 2 is at rotation phi = 0 (phi positive
// counter-clockwise). "Upper" flanks lie on the +y side, "lower" flanks on the -y side.
struct Pair {
  double rb1 = 0.0, rb2 = 0.0; // base radii
  double r1 = 0.0, r2 = 0.0;   // reference radii
  double psi1 = 0.0;           // half tooth-thickness angle of gear 1 at r1
  double eta2 = 0.0;           // half space-width angle of gear 2 at r2
  double a = 0.0;
  double cosAlphaWt = 0.0; // working transverse pressure angle from the internal tangent of the base circles
  double sinBetaB = 0.0;   // base helix angle

  explicit Pair(const BacklashCase& c) {
    if (c.z1 < 1 || c.z2 < 1) throw std::invalid_argument("referenceBacklash: tooth counts must be positive");
    if (!(c.mn > 0.0)) throw std::invalid_argument("referenceBacklash: module must be positive");
    const double pi = std::numbers::pi;
    const double cosBeta = std::cos(c.beta);
    const double mt = c.mn / cosBeta;                              // transverse module
    const double alphaT = std::atan(std::tan(c.alphaN) / cosBeta); // transverse pressure angle
    r1 = 0.5 * c.z1 * mt;
    r2 = 0.5 * c.z2 * mt;
    rb1 = r1 * std::cos(alphaT);
    rb2 = r2 * std::cos(alphaT);
    const double sn1 = c.mn * (pi / 2 + 2 * c.x1 * std::tan(c.alphaN)) + c.As1;
    const double sn2 = c.mn * (pi / 2 + 2 * c.x2 * std::tan(c.alphaN)) + c.As2;
    psi1 = (sn1 / cosBeta) / (2 * r1);             // s_t = s_n / cos(beta) on the reference cylinder
    eta2 = pi / c.z2 - (sn2 / cosBeta) / (2 * r2); // half pitch angle minus half tooth angle
    a = c.a;
    if (!(a > rb1 + rb2)) throw std::invalid_argument("referenceBacklash: centre distance too small");
    cosAlphaWt = (rb1 + rb2) / a;
    sinBetaB = std::sin(c.beta) * std::cos(c.alphaN);
  }

  double sinAlphaWt() const { return std::sqrt(1.0 - cosAlphaWt * cosAlphaWt); }

  // Flank of gear 1 (fixed). side = +1 upper, -1 lower.
  Involute flank1(int side) const { return involuteThrough({0.0, 0.0}, rb1, side, r1, side * psi1); }

  // Tooth-space flank of gear 2 at rotation phi. side = +1 upper, -1 lower.
  Involute flank2(int side, double phi) const {
    return involuteThrough({a, 0.0}, rb2, side, r2, std::numbers::pi - side * eta2 + phi);
  }

  // Internal common tangent of the base circles on which the side's flanks meet. It touches base
  // circle 1 at polar angle -side*alpha_wt and base circle 2 at pi - side*alpha_wt; the direction
  // points from gear 1's tooth into gear 2's material (outward normal of gear 1's flank).
  Line lineOfAction(int side) const {
    const double s = sinAlphaWt();
    return Line{{rb1 * cosAlphaWt, -side * rb1 * s}, {s, side * cosAlphaWt}};
  }

  // Signed clearance between the side's flank pair along the line of action (> 0: free play).
  double gap(int side, double phi) const {
    const Line loa = lineOfAction(side);
    const Involute f1 = flank1(side);
    const Involute f2 = flank2(side, phi);
    const Vec2 p1 = f1.point(intersect(f1, loa));
    const Vec2 p2 = f2.point(intersect(f2, loa));
    return dot(sub(p2, p1), loa.dir);
  }

  // Rotation of gear 2 at which the side's flanks touch. The upper gap shrinks with growing phi, the
  // lower gap with falling phi.
  double contactAngle(int side) const {
    const auto g = [&](double phi) { return gap(side, phi); };
    // The gear-2 flank moves by about r_b2 * phi along the line of action: use that to centre the bracket.
    const double guess = side * g(0.0) / rb2;
    double h = 1e-9 + 1e-3 * std::fabs(guess);
    for (int i = 0; i < 40; ++i, h *= 4.0) {
      if ((g(guess - h) < 0.0) != (g(guess + h) < 0.0)) return bisect(g, guess - h, guess + h);
    }
    throw std::runtime_error("referenceBacklash: no contact position found");
  }
};

} // namespace backlash_detail

inline BacklashRef referenceBacklash(const BacklashCase& c) {
  const backlash_detail::Pair pair(c);
  const double phiUpper = pair.contactAngle(+1);
  const double phiLower = pair.contactAngle(-1);
  const double dphi = phiUpper - phiLower; // rotation of gear 2 from one flank contact to the other
  // Working pitch radius: the line of action crosses the centre line at r_w2 = r_b2 / cos(alpha_wt).
  const double rw2 = pair.rb2 / pair.cosAlphaWt;
  const double jt = dphi * rw2;
  // Free play along the line of action (transverse plane): the gear-2 flank moves along its own
  // normal by r_b2 * dphi, so j_bt = dphi * r_b2.
  // Normal plane: the flanks are involute helicoids whose normals lie in the plane of action (tangent
  // to both base cylinders). In that plane the contact lines are straight and inclined by beta_b to
  // the axis, so two of them a transverse distance j_bt apart are j_bt * cos(beta_b) apart normal to
  // the flanks. sin(beta_b) = sin(beta) * cos(alpha_n).
  const double jbt = dphi * pair.rb2;
  const double cosBetaB = std::sqrt(1.0 - pair.sinBetaB * pair.sinBetaB);
  return BacklashRef{jt, jbt * cosBetaB};
}

// Centre distance with zero backlash for the pair's profile shifts and zero allowances (c.a, c.As1 and
// c.As2 are ignored); root of jt(a) = 0 by bisection.
inline double referenceZeroBacklashCentreDistance(BacklashCase c) {
  c.As1 = 0.0;
  c.As2 = 0.0;
  const double cosBeta = std::cos(c.beta);
  const double alphaT = std::atan(std::tan(c.alphaN) / cosBeta);
  const double ad = 0.5 * (c.z1 + c.z2) * c.mn / cosBeta;
  const double rbSum = ad * std::cos(alphaT);
  const auto jt = [&](double a) {
    BacklashCase k = c;
    k.a = a;
    return referenceBacklash(k).jt;
  };
  const double centre = ad + (c.x1 + c.x2) * c.mn;
  for (double w = c.mn; w < 16.0 * c.mn; w *= 2.0) {
    const double lo = std::fmax(centre - w, rbSum + 1e-6 * (ad - rbSum));
    const double hi = centre + w;
    if (jt(lo) < 0.0 && jt(hi) > 0.0) return backlash_detail::bisect(jt, lo, hi);
  }
  throw std::runtime_error("referenceZeroBacklashCentreDistance: not bracketed");
}

} // namespace gbx::test
