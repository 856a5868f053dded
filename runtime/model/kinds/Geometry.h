#pragma once
// Involute geometry shared by the cylindrical kinds (DOMAIN.md §3).
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

// Helical/spur pair with profile shifts: working centre distance, working pressure angle
// and tip radii with the tip shortening.
struct CylPair {
  double alphaT, alphaWt, a0, a, d1, d2, rb1, rb2, ra1, ra2;
};

inline CylPair cylPair(double z1, double z2, double mn, double beta, double alphaN, double x1, double x2, double haP = 1.0) {
  CylPair p{};
  p.alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  double invWt = involute(p.alphaT) + 2.0 * (x1 + x2) * std::tan(alphaN) / (z1 + z2);
  p.alphaWt = (x1 + x2) == 0 ? p.alphaT : inverseInvolute(invWt);
  p.d1 = z1 * mn / std::cos(beta);
  p.d2 = z2 * mn / std::cos(beta);
  p.a0 = 0.5 * (p.d1 + p.d2);
  p.a = p.a0 * std::cos(p.alphaT) / std::cos(p.alphaWt);
  double dy = (x1 + x2) - (p.a - p.a0) / mn;
  p.rb1 = 0.5 * p.d1 * std::cos(p.alphaT);
  p.rb2 = 0.5 * p.d2 * std::cos(p.alphaT);
  p.ra1 = 0.5 * p.d1 + mn * (haP + x1 - dy);
  p.ra2 = 0.5 * p.d2 + mn * (haP + x2 - dy);
  return p;
}

} // namespace gbx::rt::geometry
