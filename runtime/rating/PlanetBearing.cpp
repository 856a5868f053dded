#include "rating/PlanetBearing.h"

#include <cmath>

namespace gbx::rt::rating {

double planetPinLoad(double Fbt, double alphaSun, double alphaRing) {
  return Fbt * std::hypot(std::cos(alphaSun) + std::cos(alphaRing), std::sin(alphaSun) - std::sin(alphaRing));
}

} // namespace gbx::rt::rating
