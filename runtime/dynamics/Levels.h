#pragma once
// Levels in decibels of the mesh orders of a scene's signals (docs/dynamics.md): each order's
// RMS against a reference of the signal's kind, and the A-weighting of IEC 61672-1 at the
// order's frequency. They compare the excitation of two designs, not sound at a microphone.
#include <vector>

namespace gbx::rt::dyn {

// IEC 61672-1's A-weighting at f (Hz), dB: 0 at 1 kHz.
double aWeighting(double f);

// 20 log10(rms / reference) of a harmonic of amplitude `amplitude`; -inf for none.
double levelOf(double amplitude, double reference);

// A signal sampled evenly over `periods` mesh periods, `perPeriod` samples each, as its
// amplitude per order of the mesh frequency (bin k is order k / periods).
struct OrderSpectrum {
  int periods = 1;
  std::vector<double> amplitude; // [0] is order 1 / periods; the mean is left out
  // The amplitude at mesh order k (a whole harmonic), 0 past the spectrum's end.
  double harmonic(int k) const;
  // The level of every order together (energies added), each weighted by A at its frequency
  // when meshFrequency > 0, referred to `reference`.
  double total(double reference, double meshFrequency = 0) const;
};
OrderSpectrum orderSpectrum(const std::vector<double>& samples, int periods);

} // namespace gbx::rt::dyn
