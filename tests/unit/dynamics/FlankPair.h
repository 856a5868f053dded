#pragma once
// Gear pairs for the loaded-mesh tests, built from their basic data (SI).
#include <cmath>

#include "dynamics/LoadedMesh.h"

namespace gbx::rt::dyn::testing {

// A pair on standard centre distance with tips d + 2 mn (no shift), SI.
inline LoadedMeshInput pair(double z1, double z2, double mn, double betaDeg, double b, double cPrime, double load,
                            double alphaDeg = 20) {
  LoadedMeshInput in;
  double beta = betaDeg * M_PI / 180, alphaN = alphaDeg * M_PI / 180;
  double alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  double d1 = z1 * mn / std::cos(beta), d2 = z2 * mn / std::cos(beta);
  in.g.rb1 = 0.5 * d1 * std::cos(alphaT);
  in.g.rb2 = 0.5 * d2 * std::cos(alphaT);
  in.g.ra1 = 0.5 * d1 + mn;
  in.g.ra2 = 0.5 * d2 + mn;
  in.g.centerDistance = 0.5 * (d1 + d2);
  in.g.workingPressureAngle = alphaT;
  in.g.basePitch = M_PI * mn * std::cos(alphaT) / std::cos(beta);
  in.g.baseHelix = std::atan(std::tan(beta) * std::cos(alphaT));
  in.g.faceWidth = b;
  in.singleStiffness = cPrime;
  in.load = load;
  return in;
}

} // namespace gbx::rt::dyn::testing
