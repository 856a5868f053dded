#pragma once
// Variable load by ISO 6336-6: Miner's rule over a load spectrum. Each gear's S-N curve is
// its life curve of ISO 6336-2/-3 read the other way (the permissible stress at N cycles,
// with the life-dependent factors at N); each bin's stresses are a rating at its torque.
#include <array>
#include <vector>

#include "rating/Iso10300.h"
#include "rating/Iso6336.h"

namespace gbx::rt::rating {

// A bin as shares of the pair's operating torque and of its life (a spec's torques and
// cycles are turned into shares of the stage's where the stage is gathered).
struct SpectrumBin {
  double torqueShare = kNaN, lifeShare = kNaN;
};

// A gear's S-N curve for one side (contact or bending): log-linear in log N between the
// static point, the knee and 10^10 cycles, flat beyond (ISO 6336-2 Table 2, -3 Table 3).
struct SnCurve {
  double nStatic = 0, sStatic = 0, nKnee = 0, sKnee = 0, sEnd = 0; // stresses [Pa]
  // Cycles to failure at `stress`: 0 above the static strength, infinity below the curve.
  double cycles(double stress) const;
};

struct SpectrumSide {
  double damage = kNaN; // Miner's sum, 1: the life used up
  double safety = kNaN; // the factor on every bin's stress at which the sum reaches 1
};

template <class Rating>
struct SpectrumOf {
  std::array<SpectrumSide, 2> contact, bending; // per gear (NaN: a root not rated)
  std::array<SnCurve, 2> contactCurve, bendingCurve;
  std::vector<Rating> bins; // the rating at each bin's torque
};
using SpectrumRating = SpectrumOf<PairRating>;
using BevelSpectrum = SpectrumOf<BevelRating>;

// `in` as rated at its operating torque and life; each bin rated at its own torque with the
// factors the standard computes at that load (a given K_v or K_Hbeta stays as given).
SpectrumRating rateSpectrum(const PairInput& in, const std::vector<SpectrumBin>& bins);
// The same for a bevel pair (ISO 10300-2/-3): its life curves are ISO 6336's, read through
// its own life factors Z_NT and Y_NT at each number of cycles.
BevelSpectrum rateBevelSpectrum(const BevelInput& in, const std::vector<SpectrumBin>& bins);

} // namespace gbx::rt::rating
