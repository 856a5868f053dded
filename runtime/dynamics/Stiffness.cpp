#include "dynamics/Stiffness.h"

#include <cmath>

namespace gbx::rt::dyn {

namespace {
// sin(x)/x without 0/0.
double sinc(double x) { return std::fabs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
} // namespace

double epsAlphaStandard(double z1, double z2, double mod, double alpha, bool internal) {
  double ra1 = 0.5 * z1 * mod + mod, rb1 = 0.5 * z1 * mod * std::cos(alpha);
  double ra2 = internal ? 0.5 * z2 * mod - mod : 0.5 * z2 * mod + mod, rb2 = 0.5 * z2 * mod * std::cos(alpha);
  double a0 = internal ? 0.5 * (z2 - z1) * mod : 0.5 * (z1 + z2) * mod;
  double path = std::sqrt(ra1 * ra1 - rb1 * rb1) + (internal ? -1.0 : 1.0) * std::sqrt(ra2 * ra2 - rb2 * rb2) +
                (internal ? 1.0 : -1.0) * a0 * std::sin(alpha);
  return path / (M_PI * mod * std::cos(alpha));
}

Fourier contactLineSeries(double epsAlpha, double epsBeta, int harmonics) {
  Fourier f;
  for (int k = 1; k <= harmonics; ++k) {
    double a = 2.0 * M_PI * k * epsAlpha;
    double b = 2.0 * M_PI * k * epsBeta;
    double sa2 = std::sin(0.5 * a), sb2 = std::sin(0.5 * b);
    // sin(b/2)^2 / b, continued to 0 at b = 0.
    double sb2overB = 0.5 * sb2 * sinc(0.5 * b);
    double A = 2.0 * sinc(b) * std::sin(a) / a - 4.0 * (2.0 * sa2 * sa2) * sb2overB / a;
    double B = 4.0 * sinc(b) * sa2 * sa2 / a + 4.0 * std::sin(a) * sb2overB / a;
    f.a.push_back(A);
    f.b.push_back(B);
  }
  return f;
}

namespace {
// Sum over the harmonics of term(k, cos 2 pi k tau, sin 2 pi k tau): one sincos, then the
// harmonics by the angle-addition recurrence.
template <class Term>
double overHarmonics(const Fourier& f, double tau, Term term) {
  double w = 2.0 * M_PI * (tau - std::floor(tau));
  double c1 = std::cos(w), s1 = std::sin(w);
  double ck = c1, sk = s1, sum = 0.0;
  for (size_t k = 0; k < f.a.size(); ++k) {
    sum += term(k, ck, sk);
    double cn = ck * c1 - sk * s1, sn = sk * c1 + ck * s1;
    ck = cn;
    sk = sn;
  }
  return sum;
}
} // namespace

double relativeStiffness(const Fourier& f, double tau) {
  return 1.0 + overHarmonics(f, tau, [&](size_t k, double c, double s) { return f.a[k] * c + f.b[k] * s; });
}

double relativeStiffnessSlope(const Fourier& f, double tau) {
  return overHarmonics(f, tau, [&](size_t k, double c, double s) {
    return 2.0 * M_PI * static_cast<double>(k + 1) * (f.b[k] * c - f.a[k] * s);
  });
}

} // namespace gbx::rt::dyn
