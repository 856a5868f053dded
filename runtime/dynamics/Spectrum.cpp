#include "dynamics/Spectrum.h"

#include <algorithm>
#include <cmath>

#include <gsl/gsl_fft_real.h>

namespace gbx::rt::dyn {

Spectrum spectrum(const std::vector<double>& samples, double dt, double meshFrequency, int most) {
  Spectrum s;
  size_t n = samples.size();
  if (n < 4) return s;
  double mean = 0;
  for (double v : samples) mean += v;
  mean /= static_cast<double>(n);
  std::vector<double> data(n);
  for (size_t i = 0; i < n; ++i) data[i] = samples[i] - mean;
  gsl_fft_real_wavetable* table = gsl_fft_real_wavetable_alloc(n);
  gsl_fft_real_workspace* work = gsl_fft_real_workspace_alloc(n);
  gsl_fft_real_transform(data.data(), 1, n, table, work);
  gsl_fft_real_wavetable_free(table);
  gsl_fft_real_workspace_free(work);
  // Half-complex layout: data[0] real DC, then (re, im) pairs.
  double df = 1.0 / (static_cast<double>(n) * dt);
  for (size_t k = 1; k <= n / 2; ++k) {
    double re = data[2 * k - 1], im = (2 * k < n) ? data[2 * k] : 0.0;
    double amp = (2 * k == n ? 1.0 : 2.0) * std::hypot(re, im) / static_cast<double>(n);
    s.frequency.push_back(static_cast<double>(k) * df);
    s.amplitude.push_back(amp);
  }
  double top = s.amplitude.empty() ? 0 : *std::max_element(s.amplitude.begin(), s.amplitude.end());
  for (size_t i = 0; i < s.amplitude.size(); ++i) {
    double a = s.amplitude[i];
    bool left = i == 0 || a > s.amplitude[i - 1], right = i + 1 == s.amplitude.size() || a >= s.amplitude[i + 1];
    if (!left || !right || a < 0.02 * top || a <= 0) continue;
    Peak p{s.frequency[i], a, 0};
    if (meshFrequency > 0) {
      double k = std::round(p.frequency / meshFrequency);
      if (k >= 1 && std::fabs(p.frequency - k * meshFrequency) <= 0.5 * df + 0.01 * meshFrequency) p.harmonic = static_cast<int>(k);
    }
    s.peaks.push_back(p);
  }
  std::stable_sort(s.peaks.begin(), s.peaks.end(), [](const Peak& a, const Peak& b) { return a.amplitude > b.amplitude; });
  if (s.peaks.size() > static_cast<size_t>(most)) s.peaks.resize(static_cast<size_t>(most));
  return s;
}

} // namespace gbx::rt::dyn
