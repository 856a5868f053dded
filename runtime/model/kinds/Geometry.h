#pragma once
// Involute geometry shared by the cylindrical kinds (docs/dynamics.md).
#include <algorithm>
#include <cmath>

namespace gbx::rt::geometry {

inline double involute(double a) { return std::tan(a) - a; }

// Inverse involute by Newton's method on inv(a) = t; converges for 0 < t < 1.
inline double inverseInvolute(double t) {
  double a = std::cbrt(3.0 * t);
  for (int i = 0; i < 30; ++i) {
    double f = involute(a) - t, d = std::tan(a) * std::tan(a);
    if (d == 0) break;
    double next = a - f / d;
    if (std::fabs(next - a) < 1e-16) return next;
    a = next;
  }
  return a;
}

// The working pressure angle of a pair without backlash: inv(a_w) = inv(a) + 2 tan(a_n) (x_a + x_b) / (z_a + z_b)
// (an internal pair: the ring's shift and teeth count negative, the planet's positive).
inline double workingPressureAngle(double alphaT, double alphaN, double zSum, double xSum) {
  return xSum == 0 ? alphaT : inverseInvolute(involute(alphaT) + 2.0 * xSum * std::tan(alphaN) / zSum);
}

// The working centre distance of a spur pair (module m, pressure angle alpha) meshing without
// backlash at the shifts x1, x2: a cos(alpha) / cos(alpha_w).
inline double workingCenterDistance(double z1, double z2, double m, double alpha, double x1, double x2) {
  double aw = workingPressureAngle(alpha, alpha, z1 + z2, x1 + x2);
  return 0.5 * m * (z1 + z2) * std::cos(alpha) / std::cos(aw);
}

// Helical/spur pair with profile shifts: working centre distance, working pressure angle
// and tip radii with the tip shortening. A given centre distance aw (> 0) sets the working
// pressure angle (cos a_wt = a cos a_t / a_w); otherwise the pair meshes without backlash.
// The tips are shortened by the amount the centre distance falls short of a + (x1 + x2) m_n,
// never lengthened (ISO 21771).
struct CylPair {
  double alphaT, alphaWt, a0, a, d1, d2, rb1, rb2, ra1, ra2;
};

inline CylPair cylPair(double z1, double z2, double mn, double beta, double alphaN, double x1, double x2, double haP = 1.0,
                       double aw = 0) {
  CylPair p{};
  p.alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  p.d1 = z1 * mn / std::cos(beta);
  p.d2 = z2 * mn / std::cos(beta);
  p.a0 = 0.5 * (p.d1 + p.d2);
  if (aw > 0) {
    p.a = aw;
    double c = p.a0 * std::cos(p.alphaT) / aw;
    p.alphaWt = c <= 1 ? std::acos(c) : NAN;  // closer than the base circles allow: no mesh
  } else {
    p.alphaWt = workingPressureAngle(p.alphaT, alphaN, z1 + z2, x1 + x2);
    p.a = p.a0 * std::cos(p.alphaT) / std::cos(p.alphaWt);
  }
  double dy = std::max(0.0, (x1 + x2) - (p.a - p.a0) / mn);
  p.rb1 = 0.5 * p.d1 * std::cos(p.alphaT);
  p.rb2 = 0.5 * p.d2 * std::cos(p.alphaT);
  p.ra1 = 0.5 * p.d1 + mn * (haP + x1 - dy);
  p.ra2 = 0.5 * p.d2 + mn * (haP + x2 - dy);
  return p;
}

// The backlash of an external pair at the centre distance a (ISO 21771): each tooth's
// transverse thickness on the working pitch circle, from its normal thickness
// m_n (pi/2 + 2 x tan a_n) + A_s on the reference circle; j_t is what the two leave of the
// working pitch, j_n the same play normal to the flanks. Negative: the flanks interfere;
// NaN: a closer than the base circles allow.
struct Backlash {
  double jt, jn;  // circumferential (working pitch circle) and normal [m]
};

inline Backlash backlash(double z1, double z2, double mn, double beta, double alphaN, double x1, double x2, double As1, double As2,
                         double a) {
  constexpr double pi = 3.14159265358979323846;
  double alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  double cosWt = 0.5 * (z1 + z2) * mn / std::cos(beta) * std::cos(alphaT) / a;
  if (!(cosWt <= 1)) return {NAN, NAN};
  double alphaWt = std::acos(cosWt);
  // On the working pitch circle d_w = d cos a_t / cos a_wt: s_w = d_w (s_t / d + inv a_t - inv a_wt).
  auto thickness = [&](double z, double x, double As) {
    double d = z * mn / std::cos(beta), st = (mn * (pi / 2 + 2 * x * std::tan(alphaN)) + As) / std::cos(beta);
    double dw = d * std::cos(alphaT) / cosWt;
    return dw * (st / d + involute(alphaT) - involute(alphaWt));
  };
  double pw = pi * (z1 * mn / std::cos(beta)) * std::cos(alphaT) / cosWt / z1;
  double jt = pw - thickness(z1, x1, As1) - thickness(z2, x2, As2);
  double betaB = std::asin(std::sin(beta) * std::cos(alphaN));
  return {jt, jt * cosWt * std::cos(betaB)};
}

} // namespace gbx::rt::geometry
