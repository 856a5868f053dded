// Load sharing among planets (rating/LoadSharing.h) against closed forms derived by hand for N
// equally spaced planets of equal path stiffness k = k_s k_r / (k_s + k_r), total load F, one
// planet's pin error e (its path error along the lines of action eps = e (cos a_s + cos a_r)):
//   sun held,     that planet late  (e > 0): K_gamma = 1 + k eps / F
//   sun held,     that planet early (e < 0): K_gamma = 1 + (N - 1) k |eps| / F
//   sun floating: the sun's translation d solves (N/2) d = (2 eps / N)... = eps n_0 (sum of n_i n_i^T
//   is N/2 for N >= 3), so planet i carries k (u + (2 eps/N) cos(2 pi i/N) - eps [i = 0]) with
//   u = (F/k + eps)/N:
//     late:  K_gamma = 1 + (1 + 2 cos(2 pi/N)) k eps / F   (N = 3: exactly 1; N = 4: 1 + k eps/F)
//     early: K_gamma = 1 + (N - 3) k |eps| / F             (N = 3: exactly 1)
// Each holds while every planet keeps contact; a large error unloads a planet (held sun: the
// others share the load equally, K_gamma = N/(N-1)).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rating/LoadSharing.h"

namespace {

using gbx::rt::rating::LoadSharingInput;
using gbx::rt::rating::shareLoad;

constexpr double kDeg = std::numbers::pi / 180;

LoadSharingInput stage(int planets, double pinError, bool floating) {
  LoadSharingInput in;
  in.planets = planets;
  in.kSun = 8e9;
  in.kRing = 12e9;
  in.alphaSun = 24 * kDeg;
  in.alphaRing = 19 * kDeg;
  in.pinError = {pinError};
  in.floatingSun = floating;
  in.force = 2.4e6;
  return in;
}

double pathStiffness(const LoadSharingInput& in) { return in.kSun * in.kRing / (in.kSun + in.kRing); }
double pathError(const LoadSharingInput& in) {
  return in.pinError[0] * (std::cos(in.alphaSun) + std::cos(in.alphaRing));
}

TEST(LoadSharing, HeldSunOnePlanetLateOrEarly) {
  for (int n : {3, 4, 5}) {
    for (double e : {10e-6, -10e-6}) {
      LoadSharingInput in = stage(n, e, false);
      double x = pathStiffness(in) * std::fabs(pathError(in)) / in.force;
      double expected = e > 0 ? 1 + x : 1 + (n - 1) * x;
      auto r = shareLoad(in);
      EXPECT_NEAR(r.Kgamma, expected, 1e-12) << n << " planets, e " << e;
      EXPECT_EQ(r.unloaded, 0);
      double sum = 0;
      for (double s : r.share)
        sum += s;
      EXPECT_NEAR(sum, n, 1e-12); // the shares carry the whole load
    }
  }
}

TEST(LoadSharing, FloatingSunAbsorbsOnePinErrorWithThreePlanets) {
  for (double e : {20e-6, -20e-6, 200e-6}) {
    auto r = shareLoad(stage(3, e, true));
    EXPECT_NEAR(r.Kgamma, 1.0, 1e-12) << e;
    for (double s : r.share)
      EXPECT_NEAR(s, 1.0, 1e-12);
  }
}

TEST(LoadSharing, FloatingSunWithFourOrMorePlanetsDoesNotAbsorbIt) {
  for (int n : {4, 5, 6}) {
    for (double e : {10e-6, -10e-6}) {
      LoadSharingInput in = stage(n, e, true);
      double x = pathStiffness(in) * std::fabs(pathError(in)) / in.force;
      double expected = e > 0 ? 1 + (1 + 2 * std::cos(2 * std::numbers::pi / n)) * x : 1 + (n - 3) * x;
      auto r = shareLoad(in);
      EXPECT_GT(r.Kgamma, 1.0 + 1e-6);
      EXPECT_NEAR(r.Kgamma, expected, 1e-12) << n << " planets, e " << e;
    }
  }
}

TEST(LoadSharing, WithoutErrorsEveryPlanetCarriesItsShare) {
  for (bool floating : {false, true}) {
    auto r = shareLoad(stage(5, 0.0, floating));
    EXPECT_NEAR(r.Kgamma, 1.0, 1e-12);
  }
}

// A pin error larger than the load's deflection unloads that planet (held sun): the others
// share the load equally, and more error changes nothing.
TEST(LoadSharing, AnUnloadedPlanetLeavesTheOthersEqual) {
  for (int n : {3, 4, 5}) {
    LoadSharingInput in = stage(n, 1e-3, false);
    auto r = shareLoad(in);
    EXPECT_EQ(r.unloaded, 1);
    EXPECT_EQ(r.share[0], 0.0);
    EXPECT_NEAR(r.Kgamma, n / (n - 1.0), 1e-12);
  }
  // A floating sun with four planets, one far early: the sun slides towards it until its
  // neighbours lose contact; it and the opposite planet balance each other, half the load
  // each (K_gamma = 2), and the neighbours stay open.
  auto r = shareLoad(stage(4, -1e-3, true));
  EXPECT_EQ(r.unloaded, 2);
  EXPECT_NEAR(r.share[0], 2.0, 1e-9);
  EXPECT_NEAR(r.share[2], 2.0, 1e-9);
  EXPECT_NEAR(r.Kgamma, 2.0, 1e-9);
}

TEST(LoadSharing, RefusesWhatHasNoSolution) {
  LoadSharingInput in = stage(3, 0, false);
  in.kSun = 0;
  EXPECT_THROW(shareLoad(in), std::domain_error);
  in = stage(3, 0, false);
  in.force = 0;
  EXPECT_THROW(shareLoad(in), std::domain_error);
  in = stage(0, 0, false);
  EXPECT_THROW(shareLoad(in), std::domain_error);
}

} // namespace
