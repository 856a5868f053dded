#include "dynamics/Stiffness.h"

#include <algorithm>
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
// Sum over the harmonics of term(k, cos 2 pi (k+1) tau, sin 2 pi (k+1) tau) into acc[lane]:
// one sincos, then (from eight harmonics on) four interleaved angle-addition chains, each
// stepping by 4 w, so the chains (and the sums, one per lane) do not wait on each other.
template <size_t Sums, class Term>
void overHarmonics(size_t n, double tau, double (&acc)[Sums][4], Term term) {
  double w = 2.0 * M_PI * (tau - std::floor(tau));
  double c[4], s[4];
  c[0] = std::cos(w);
  s[0] = std::sin(w);
  for (auto& lanes : acc)
    for (double& v : lanes) v = 0.0;
  if (n < 8) {
    // A few harmonics: one chain costs less than setting up four.
    double ck = c[0], sk = s[0];
    for (size_t k = 0; k < n; ++k) {
      term(k, ck, sk, acc, 0);
      double cn = ck * c[0] - sk * s[0], sn = sk * c[0] + ck * s[0];
      ck = cn;
      sk = sn;
    }
    return;
  }
  for (size_t q = 1; q < 4; ++q) {
    c[q] = c[q - 1] * c[0] - s[q - 1] * s[0];
    s[q] = s[q - 1] * c[0] + c[q - 1] * s[0];
  }
  double c4 = c[3], s4 = s[3];  // the step of each chain: 4 w
  size_t k = 0;
  for (; k + 4 <= n; k += 4)
    for (size_t q = 0; q < 4; ++q) {
      term(k + q, c[q], s[q], acc, q);
      double cn = c[q] * c4 - s[q] * s4, sn = s[q] * c4 + c[q] * s4;
      c[q] = cn;
      s[q] = sn;
    }
  for (size_t q = 0; k < n; ++k, ++q) term(k, c[q], s[q], acc, q);
}

template <size_t Sums>
double total(const double (&acc)[Sums][4], size_t i) {
  return (acc[i][0] + acc[i][1]) + (acc[i][2] + acc[i][3]);
}
} // namespace

double relativeStiffness(const Fourier& f, double tau) {
  double acc[1][4];
  overHarmonics(f.a.size(), tau, acc, [&](size_t k, double c, double s, double (&a)[1][4], size_t q) { a[0][q] += f.a[k] * c + f.b[k] * s; });
  return 1.0 + total(acc, 0);
}

double relativeStiffnessSlope(const Fourier& f, double tau) {
  double acc[1][4];
  overHarmonics(f.a.size(), tau, acc, [&](size_t k, double c, double s, double (&a)[1][4], size_t q) {
    a[0][q] += 2.0 * M_PI * static_cast<double>(k + 1) * (f.b[k] * c - f.a[k] * s);
  });
  return total(acc, 0);
}

void seriesPair(const Fourier& f, const Fourier& g, double tau, double& sf, double& sg) {
  double acc[2][4];
  size_t nf = f.a.size(), ng = g.a.size();
  if (nf == ng) {
    overHarmonics(nf, tau, acc, [&](size_t k, double c, double s, double (&a)[2][4], size_t q) {
      a[0][q] += f.a[k] * c + f.b[k] * s;
      a[1][q] += g.a[k] * c + g.b[k] * s;
    });
  } else {
    overHarmonics(std::max(nf, ng), tau, acc, [&](size_t k, double c, double s, double (&a)[2][4], size_t q) {
      if (k < nf) a[0][q] += f.a[k] * c + f.b[k] * s;
      if (k < ng) a[1][q] += g.a[k] * c + g.b[k] * s;
    });
  }
  sf = total(acc, 0);
  sg = total(acc, 1);
}

} // namespace gbx::rt::dyn
