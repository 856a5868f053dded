#include "dynamics/CornerContact.h"

#include <cmath>

namespace gbx::rt::dyn {

namespace {

double involute(double alpha) { return std::tan(alpha) - alpha; }

// An angle difference brought into (-pi, pi].
double wrapped(double x) { return std::remainder(x, 2.0 * M_PI); }

} // namespace

// The pinion's centre at the origin, the wheel's at (a, 0); the line of action touches the
// pinion's base circle at T1 = rb1 (cos alpha, sin alpha) and runs to T2 on the wheel's. A
// point of it is named by u, its distance from T1 (the pinion's roll length there). An
// involute of the pinion is named by the u at which it crosses the line of action: a point
// K lies on the pinion's involute u_K = rb1 (alpha - (theta_K - inv(alpha_K))), with theta_K
// its polar angle and cos alpha_K = rb1 / |K|; likewise for the wheel about its centre, from
// T2's end. The separation is the pinion's turn, times rb1, that brings its flank (or its
// corner) onto the wheel's corner (or flank) with the wheel held: the transmission error's
// measure for every pair of the loaded mesh.
double cornerSeparation(const FlankGeometry& g, double s) {
  const double a = g.centerDistance, alpha = g.workingPressureAngle, rb1 = g.rb1, rb2 = g.rb2;
  const double L = a * std::sin(alpha);
  const double roll1 = std::sqrt(g.ra1 * g.ra1 - rb1 * rb1), roll2 = std::sqrt(g.ra2 * g.ra2 - rb2 * rb2);
  const double start = L - roll2, path = roll1 + roll2 - L;
  const double u = start + s; // where the flanks would meet, were they long enough
  if (s >= 0 && s <= path) return 0.0;
  if (s < 0) {
    // The wheel's flank meeting the line at u has its tip corner at radius ra2, inv(alpha_a2)
    // on from where its involute leaves the base circle.
    double chi0 = M_PI + alpha - (L - u) / rb2;
    double th = chi0 + involute(std::acos(rb2 / g.ra2));
    double kx = a + g.ra2 * std::cos(th), ky = g.ra2 * std::sin(th), r1 = std::hypot(kx, ky);
    if (!(r1 > rb1)) return INFINITY;
    double uK = rb1 * wrapped(alpha - (std::atan2(ky, kx) - involute(std::acos(rb1 / r1))));
    return uK - u;
  }
  // The pinion's tip corner, on the flank meeting the line at u, against the wheel's flank:
  // the pinion turns on (the wheel held, as for every pair's separation) until its corner
  // reaches the flank. The corner's wheel coordinate rises with the turn: bracket the turn
  // from the wheel's own measure of the gap, then close in by regula falsi (Illinois).
  const double th0 = alpha - u / rb1 + involute(std::acos(rb1 / g.ra1));
  auto miss = [&](double turn) {
    double th = th0 - turn;
    double kx = g.ra1 * std::cos(th), ky = g.ra1 * std::sin(th), r2 = std::hypot(kx - a, ky);
    if (!(r2 > rb2)) return static_cast<double>(NAN);
    return L - rb2 * wrapped(M_PI + alpha - (std::atan2(ky, kx - a) - involute(std::acos(rb2 / r2)))) - u;
  };
  double lo = 0, flo = miss(0);
  if (!std::isfinite(flo)) return INFINITY;
  if (flo >= 0) return 0.0;
  // The wheel's own measure is within a few per cent of the turn: bracket just past it.
  double hi = -1.05 * flo / rb1, fhi = miss(hi);
  for (int k = 0; k < 30 && std::isfinite(fhi) && fhi < 0; ++k) {
    lo = hi;
    flo = fhi;
    hi *= 1.5;
    fhi = miss(hi);
  }
  if (!std::isfinite(fhi) || fhi < 0 || hi > 0.5) return INFINITY; // the corner no longer meets that flank
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-16 * hi; ++it) {
    double mid = (lo * fhi - hi * flo) / (fhi - flo), fm = miss(mid);
    if (!std::isfinite(fm)) return INFINITY;
    if (std::fabs(fm) < 1e-15) return rb1 * mid; // a femtometre of roll
    if (fm < 0) {
      lo = mid;
      flo = fm;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = mid;
      fhi = fm;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return rb1 * 0.5 * (lo + hi);
}

} // namespace gbx::rt::dyn
