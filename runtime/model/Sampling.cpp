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
  std::uint64_t h = mix(mix(mix(seed) ^ sample) ^ (tolerance * 2 + stream));
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
    double u1 = sampleUniform(seed, static_cast<std::uint64_t>(k), i, 0);
    if (distribution == cat::distribution::Uniform) {
      d[i] = tol[i].amount * (2 * u1 - 1);
      continue;
    }
    // Box-Muller: the amount is three standard deviations.
    double u2 = sampleUniform(seed, static_cast<std::uint64_t>(k), i, 1);
    double z = std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
    d[i] = tol[i].amount / 3 * z;
  }
  return d;
}

const char* Sampling::distributionName() const { return distribution == cat::distribution::Uniform ? "uniform" : "normal"; }

double sampleMean(const std::vector<double>& x) {
  if (x.empty()) return NAN;
  // Pairwise-free but compensated: the same order gives the same bytes.
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
  double band = std::sqrt(n * p * (1 - p));
  double lo = std::clamp((n * p - band) / n, 0.0, 1.0), hi = std::clamp((n * p + band) / n, 0.0, 1.0);
  return (sortedQuantile(s, hi) - sortedQuantile(s, lo)) / 2;
}

} // namespace gbx::rt
