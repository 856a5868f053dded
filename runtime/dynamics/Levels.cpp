#include "dynamics/Levels.h"

#include <algorithm>
#include <cmath>

#include "dynamics/Spectrum.h"

namespace gbx::rt::dyn {

double aWeighting(double f) {
  // IEC 61672-1:2013, equations (E.6) and (E.1): the poles at 20.6, 107.7, 737.9 and 12194 Hz,
  // normalised to 0 dB at 1 kHz by A_1000 = -2.000 dB.
  const double f1 = 20.598997, f2 = 107.65265, f3 = 737.86223, f4 = 12194.217;
  double f2sq = f * f;
  double r =
      f4 * f4 * f2sq * f2sq / ((f2sq + f1 * f1) * std::sqrt((f2sq + f2 * f2) * (f2sq + f3 * f3)) * (f2sq + f4 * f4));
  return 20.0 * std::log10(r) + 2.0;
}

double levelOf(double amplitude, double reference) {
  return amplitude > 0 ? 20.0 * std::log10(amplitude / (std::sqrt(2.0) * reference)) : -INFINITY;
}

double OrderSpectrum::harmonic(int k) const {
  size_t bin = static_cast<size_t>(k) * static_cast<size_t>(periods);
  return k >= 1 && bin <= amplitude.size() ? amplitude[bin - 1] : 0.0;
}

double OrderSpectrum::total(double reference, double meshFrequency) const {
  double energy = 0;
  for (size_t i = 0; i < amplitude.size(); ++i) {
    double a = amplitude[i];
    if (!(a > 0)) continue;
    double gain = 1.0;
    if (meshFrequency > 0)
      gain = std::pow(10.0, aWeighting(static_cast<double>(i + 1) / periods * meshFrequency) / 20.0);
    energy += 0.5 * (a * gain) * (a * gain);
  }
  return energy > 0 ? 10.0 * std::log10(energy / (reference * reference)) : -INFINITY;
}

OrderSpectrum orderSpectrum(const std::vector<double>& samples, int periods) {
  OrderSpectrum s;
  s.periods = std::max(1, periods);
  // The sample spacing in mesh periods: frequencies come out in mesh orders.
  Spectrum sp = spectrum(samples, static_cast<double>(s.periods) / static_cast<double>(samples.size()), 0.0, 0);
  s.amplitude = std::move(sp.amplitude);
  return s;
}

} // namespace gbx::rt::dyn
