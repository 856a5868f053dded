#pragma once
// ISO/TR 6336-30 Example 1's pair as the rating takes it: the mesh the benchmarks rate as
// their yardstick.
#include <cmath>

#include "rating/Iso6336.h"

inline gbx::rt::rating::PairInput trExample1Pair() {
  constexpr double deg = M_PI / 180, rpm = M_PI / 30;
  gbx::rt::rating::PairInput in;
  in.gear[0] = {17, 0.145, 159.66e-3, 8e-6, 10e-6, 11e-6, 360 * rpm, 1, 1, 1, 0, 1500e6, 500e6};
  in.gear[1] = {103, 0, 872.35e-3, 9.5e-6, 12e-6, 13e-6, 360 * rpm * 17 / 103, 1, 1, 1, 0, 1500e6, 500e6};
  in.mn = 8e-3;
  in.alphaN = 20 * deg;
  in.beta = 15.8 * deg;
  in.b = 100e-3;
  in.a = 500e-3;
  in.torque1 = 9000;
  in.life = 50000 * 3600.0;
  in.nu40 = 320e-6;
  in.RzFlank = in.RzRoot = 6e-6;
  in.hfP = 1.4;
  in.rhoFP = 0.39;
  return in;
}
