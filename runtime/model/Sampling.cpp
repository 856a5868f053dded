#include "model/Sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "catalogue/Settings.h"

namespace gbx::rt {

namespace {

// SplitMix64's finaliser: a bijection whose output bits each depend on every input bit.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

} // namespace

double sampleUniform(std::uint64_t seed, std::uint64_t sample, std::uint64_t tolerance, std::uint64_t stream) {
  std::uint64_t h = mix(mix(mix(mix(seed) ^ sample) ^ tolerance) ^ stream);
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;  // never 0 or 1
}

Sampling Sampling::of(const ir::Gearbox& g) {
  Sampling s;
  if (const auto* n = ir::findSetting(g.toleranceSettings, cat::Q::Samples); n && n->value) s.samples = static_cast<long>(n->value->toDouble());
  if (const auto* d = ir::findSetting(g.toleranceSettings, cat::Q::Distribution); d && d->choice >= 0) s.distribution = d->choice;
  if (const auto* r = ir::findSetting(g.toleranceSettings, cat::Q::Seed); r && r->value) s.seed = static_cast<std::uint64_t>(r->value->toDouble());
  return s;
}

std::vector<double> Sampling::deviations(const std::vector<ir::Tolerance>& tol, long k) const {
  std::vector<double> d(tol.size());
  for (size_t i = 0; i < tol.size(); ++i) {
    if (distribution == cat::distribution::Uniform) {
      d[i] = tol[i].amount * (2 * sampleUniform(seed, static_cast<std::uint64_t>(k), i, 0) - 1);
      continue;
    }
    d[i] = tol[i].amount / 3 * sampleNormal(seed, static_cast<std::uint64_t>(k), i);
  }
  return d;
}

double sampleNormal(std::uint64_t seed, std::uint64_t sample, std::uint64_t index) {
  // Box-Muller; a draw beyond three standard deviations is drawn again (the part would fail
  // inspection), so no sample leaves the tolerance and `worst` does not grow with the number
  // of samples. One draw in 370 is redrawn.
  double z = 0;
  for (std::uint64_t attempt = 0; attempt < 64; ++attempt) {
    double a = sampleUniform(seed, sample, index, 2 * attempt);
    double b = sampleUniform(seed, sample, index, 2 * attempt + 1);
    z = std::sqrt(-2 * std::log(a)) * std::cos(2 * std::numbers::pi * b);
    if (std::fabs(z) <= 3) break;
  }
  return std::clamp(z, -3.0, 3.0);
}

const char* Sampling::distributionName() const { return distribution == cat::distribution::Uniform ? "uniform" : "normal"; }

double sampleMean(const std::vector<double>& x) {
  if (x.empty()) return NAN;
  // Compensated (Kahan) in sample order: the same samples give the same bytes.
  double s = 0, c = 0;
  for (double v : x) {
    double y = v - c, t = s + y;
    c = (t - s) - y;
    s = t;
  }
  return s / static_cast<double>(x.size());
}

double sampleStdDev(const std::vector<double>& x) {
  if (x.size() < 2) return NAN;
  double m = sampleMean(x), s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

double sortedQuantile(const std::vector<double>& s, double p) {
  if (s.empty()) return NAN;
  double h = (static_cast<double>(s.size()) - 1) * std::clamp(p, 0.0, 1.0);
  size_t lo = static_cast<size_t>(std::floor(h));
  if (lo + 1 >= s.size()) return s.back();
  return s[lo] + (h - static_cast<double>(lo)) * (s[lo + 1] - s[lo]);
}

double quantileStandardError(const std::vector<double>& s, double p) {
  if (s.size() < 2) return NAN;
  double n = static_cast<double>(s.size());
  // Fewer than five samples beyond the quantile: the order statistics do not resolve it.
  if (n * std::min(p, 1 - p) < 5) return NAN;
  double band = std::sqrt(n * p * (1 - p));
  double lo = std::clamp((n * p - band) / n, 0.0, 1.0), hi = std::clamp((n * p + band) / n, 0.0, 1.0);
  return (sortedQuantile(s, hi) - sortedQuantile(s, lo)) / 2;
}

size_t worstIndex(const std::vector<double>& x, int sense) {
  size_t k = 0;
  for (size_t i = 1; i < x.size(); ++i)
    if (sense > 0 ? x[i] > x[k] : x[i] < x[k]) k = i;
  return k;
}

} // namespace gbx::rt
