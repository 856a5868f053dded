#include "rating/InternalRoot.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace gbx::rt::rating {

namespace {

using V2 = Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;

double inv(double a) { return std::tan(a) - a; }
double sq(double x) { return x * x; }
V2 rotated(const V2& v, double a) {
  return {v.x() * std::cos(a) - v.y() * std::sin(a), v.x() * std::sin(a) + v.y() * std::cos(a)};
}
V2 perp(const V2& v) { return {-v.y(), v.x()}; }

// Bisection of a sign change of f on [lo, hi] (f(lo) and f(hi) of opposite signs).
template <class F> double bisect(F f, double lo, double hi) {
  bool low = f(lo) < 0;
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    ((f(mid) < 0) == low ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The centre of the cutter's tip rounding (radius rho) on its tooth's right flank, the tooth
// on the cutter's +y axis: tangent to the tip circle and to the involute; none where the
// rounding does not fit (a pointed or over-rounded tooth).
std::optional<V2> fittedCentre(double m, double alpha, double z0, double x0, double ha0, double rho) {
  const double r0 = 0.5 * m * z0, rb = r0 * std::cos(alpha), ra = r0 + m * (ha0 + x0);
  const double halfAngle = (kPi / 2 + 2 * x0 * std::tan(alpha)) / z0;
  auto centre = [&](double r) -> V2 {
    double ar = std::acos(rb / r), eta = halfAngle + inv(alpha) - inv(ar), tau = eta - ar;
    return V2(r * std::sin(eta), r * std::cos(eta)) + rho * V2(-std::cos(tau), std::sin(tau));
  };
  auto gap = [&](double r) { return centre(r).norm() - (ra - rho); };
  if (!(ra - rho > rb) || !(gap(rb) < 0) || !(gap(ra) >= 0)) return std::nullopt;
  V2 c = centre(bisect(gap, rb, ra));
  if (!(c.x() > 0)) return std::nullopt;
  return c;
}

// The rounding's centre, or a sentence with the largest tip radius that fits this cutter.
V2 roundingCentre(double m, double alpha, double z0, double x0, double ha0, double rho) {
  if (auto c = fittedCentre(m, alpha, z0, x0, ha0, rho)) return *c;
  double lo = 0, hi = rho;
  for (int i = 0; i < 60; ++i) {
    double mid = 0.5 * (lo + hi);
    (fittedCentre(m, alpha, z0, x0, ha0, mid) ? lo : hi) = mid;
  }
  throw std::domain_error(
      fmt::format("the ring's cutter has no room for its tip radius {:.3f} m_n: with {:g} teeth and shift {:g} "
                  "at most {:.3f} m_n fits",
                  rho / m, z0, x0, lo / m));
}

// The rounding centre's path in the internal gear's frame (its tooth space on +y): the
// cutter's centre at a0 (-sin psi, cos psi), the cutter turned by k psi as its pitch circle
// rolls inside the gear's, k = -(z - z0)/z0.
struct Path {
  double a0, k;
  V2 c;
  V2 at(double p) const { return V2(-a0 * std::sin(p), a0 * std::cos(p)) + rotated(c, k * p); }
  V2 d1(double p) const { return V2(-a0 * std::cos(p), -a0 * std::sin(p)) + k * perp(rotated(c, k * p)); }
  V2 d2(double p) const { return V2(a0 * std::sin(p), -a0 * std::cos(p)) - k * k * rotated(c, k * p); }
};

// The critical section of the generated fillet: chord s_Fn, its distance from the gear's
// centre, and the fillet radius there (mm).
struct Section {
  double sFn, radius, rhoF;
};

Section criticalSection(const Path& path, double z, double rho) {
  // The deepest point of the path (C . C' = 0), then towards the tooth on the +x side.
  auto radial = [&](double p) { return path.at(p).dot(path.d1(p)); };
  double apex = bisect(radial, -kPi / z, kPi / z);
  const double sgn = perp(path.d1(apex)).dot(path.at(apex)) > 0 ? 1.0 : -1.0;
  auto normal = [&](double p) { return V2(sgn * perp(path.d1(p)).normalized()); };
  const V2 axis(std::sin(kPi / z), std::cos(kPi / z)), across(std::cos(kPi / z), -std::sin(kPi / z));
  auto tangentAngle = [&](double p) { return std::acos(std::min(1.0, std::fabs(path.d1(p).normalized().dot(axis)))); };
  const double dir = path.d1(apex).dot(across) > 0 ? 1.0 : -1.0, target = kPi / 3;
  double inside = apex, outside = NAN;
  for (double h = 1e-9; h < 2 * kPi / z; h *= 1.5) {
    if (tangentAngle(apex + dir * h) <= target) {
      outside = apex + dir * h;
      break;
    }
    inside = apex + dir * h;
  }
  if (std::isnan(outside)) throw std::domain_error("the ring's generated fillet has no 60-degree tangent");
  double p = bisect([&](double q) { return tangentAngle(q) - target; }, inside, outside);
  V2 e = path.at(p) + rho * normal(p);
  double kappa = path.d2(p).dot(normal(p)) / path.d1(p).squaredNorm();
  if (!(kappa < 0)) throw std::domain_error("the ring's generated fillet is not concave at its critical section");
  return {-2 * e.dot(across), e.dot(axis), rho - 1 / kappa};
}

} // namespace

ToothForm internalToothForm(double z, double x, double da, double df, double mn, double alphaN, double beta,
                            double epsAlpha, double hfP, const PinionCutter& cutter) {
  if (!(cutter.z0 > 0 && cutter.z0 < z))
    throw std::domain_error(fmt::format("the ring's cutter needs fewer teeth than the ring ({:g})", z));
  // The normal section's virtual gears (a helical ring and its helical cutter).
  const double betaB = std::asin(std::sin(beta) * std::cos(alphaN)), virt = sq(std::cos(betaB)) * std::cos(beta);
  const double zn = z / virt, z0n = cutter.z0 / virt, rho = cutter.rhoA0 * mn;
  const double da0 = mn * (z0n + 2 * (hfP + cutter.x0));
  const double dn = zn * mn, dfn = dn + df - z * mn / std::cos(beta), dan = dn + da - z * mn / std::cos(beta);
  const double a0 = 0.5 * (dfn - da0);
  if (!(a0 > 0) || (zn - z0n) * mn * std::cos(alphaN) / (2 * a0) >= 1)
    throw std::domain_error("the ring's cutter cannot cut its root diameter (check the cutter's teeth and shift)");
  const Path path{a0, -(zn - z0n) / z0n, roundingCentre(mn, alphaN, z0n, cutter.x0, hfP, rho)};
  const Section s = criticalSection(path, zn, rho);

  // The load at the outer point of single pair contact, the gear's diameters negative.
  const double d = -dn, db = d * std::cos(alphaN), dA = -dan;
  const double epsAn = epsAlpha / sq(std::cos(betaB));
  const double pbn = kPi * d * std::cos(alphaN) / zn;
  const double root = std::sqrt(0.25 * sq(dA) - 0.25 * sq(db)) - pbn * (epsAn - 1);
  const double den = -2 * std::sqrt(sq(root) + 0.25 * sq(db));
  ToothForm t{};
  double alphaEn = std::acos(db / den);
  t.gamma = (kPi / 2 + 2 * x * std::tan(alphaN)) / -zn + inv(alphaN) - inv(alphaEn);
  t.alphaFen = alphaEn - t.gamma;
  double loadRadius = -0.5 * den * (std::cos(t.gamma) - std::sin(t.gamma) * std::tan(t.alphaFen));
  t.sFn = s.sFn;
  t.rhoF = s.rhoF;
  t.hFe = s.radius - loadRadius;
  t.theta = kPi / 3;
  if (!(t.sFn > 0 && t.hFe > 0)) throw std::domain_error("the ring's critical section lies above its load point");
  formAndStressFactors(t, mn, alphaN);
  return t;
}

double internalRimFactor(double sR, double mn) {
  double r = sR / mn;
  if (r >= 3.5) return 1.0;
  if (r < 1.75)
    throw std::domain_error(fmt::format(
        "the ring's rim thickness {:.1f} mm is below 1.75 modules: ISO 6336-3's rim factor does not cover it", sR));
  return 1.15 * std::log(8.324 / r);
}

} // namespace gbx::rt::rating
