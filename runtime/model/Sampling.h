#pragma once
// Monte Carlo samples of a gearbox's `tolerances` (docs/optimisation.md): each tolerance's
// deviation at sample k is drawn from a counter-based stream (the seed, k and the
// tolerance's position), so any share of the samples over threads or ranks draws the same
// numbers, and the statistics the report gives of them.
#include <cstdint>
#include <vector>

#include "ir/Ir.h"

namespace gbx::rt {

struct Sampling {
  long samples = 0;  // 0: no Monte Carlo; `worst` and `mean` visit the box's corners
  int distribution = 0;  // cat::distribution::Normal or Uniform
  std::uint64_t seed = 1;
  bool on() const { return samples > 0; }
  static Sampling of(const ir::Gearbox& g);
  // Every tolerance's deviation (SI) at sample k, in the order of the gearbox's lines.
  std::vector<double> deviations(const std::vector<ir::Tolerance>& tol, long k) const;
  const char* distributionName() const;
};

// A uniform number in (0, 1) from the seed, the sample, the tolerance and a stream (the
// draws of one deviation: two per normal draw and its redraws).
double sampleUniform(std::uint64_t seed, std::uint64_t sample, std::uint64_t tolerance, std::uint64_t stream);

// A standard normal number within +-3 from the same stream (a draw beyond is drawn again).
double sampleNormal(std::uint64_t seed, std::uint64_t sample, std::uint64_t index);

// Statistics of sample values (NaNs left out by the caller).
double sampleMean(const std::vector<double>& x);
double sampleStdDev(const std::vector<double>& x);  // with n - 1
// The p-quantile of sorted values, interpolated between order statistics (Hyndman and Fan's
// definition 7, the one R and NumPy use by default).
double sortedQuantile(const std::vector<double>& sorted, double p);
// Its standard error without assuming a distribution: half the spread of the order
// statistics one binomial standard deviation, sqrt(n p (1 - p)), either side of n p.
double quantileStandardError(const std::vector<double>& sorted, double p);
// The first of the worst samples: the largest where sense > 0, else the smallest.
size_t worstIndex(const std::vector<double>& x, int sense);

} // namespace gbx::rt
