#include "dynamics/Stiffness.h"

#include <cmath>

namespace gbx::rt::dyn {

namespace {
// sin(x)/x without 0/0.
double sinc(double x) { return std::fabs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
} // namespace

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

double relativeStiffness(const Fourier& f, double tau) {
  // One sincos, then the harmonics by the angle-addition recurrence.
  double w = 2.0 * M_PI * (tau - std::floor(tau));
  double c1 = std::cos(w), s1 = std::sin(w);
  double ck = c1, sk = s1, sum = 1.0;
  for (size_t k = 0; k < f.a.size(); ++k) {
    sum += f.a[k] * ck + f.b[k] * sk;
    double cn = ck * c1 - sk * s1, sn = sk * c1 + ck * s1;
    ck = cn;
    sk = sn;
  }
  return sum;
}

} // namespace gbx::rt::dyn
