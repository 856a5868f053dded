#pragma once
// Amplitude spectra of sampled signals (GSL's mixed-radix real FFT) and their peaks,
// named as harmonics of the mesh frequency where they fall on one.
#include <vector>

namespace gbx::rt::dyn {

struct Peak {
  double frequency = 0;  // Hz
  double amplitude = 0;  // signal units
  int harmonic = 0;      // k when the peak is k times the mesh frequency, else 0
};

struct Spectrum {
  std::vector<double> frequency, amplitude;  // one-sided, mean removed
  std::vector<Peak> peaks;                   // strongest first
};

// `dt` the sample spacing; peaks are local maxima above 2 % of the largest, at most `most`.
Spectrum spectrum(const std::vector<double>& samples, double dt, double meshFrequency, int most = 6);

} // namespace gbx::rt::dyn
