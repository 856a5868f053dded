// A planetary gear's mass from its geometry: the sun and a planet solid discs at the
// reference diameter, the ring an annulus from its reference circle to its rim below the root.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "Compiled.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"

using namespace gbx;

TEST(PlanetaryMass, DiscsAndTheRingAnnulusFromTheGeometry) {
  Compiled c = compileFirst(R"(import materials;
gearbox P {
  stage ps: planetary {
    sun.z = 18;  planet.z = 27;  ring.z = 72;  planets = 3;  module = 3 mm;  face_width = 40 mm;
    material = steel_18CrNiMo7_6;  ring.rim_thickness = 12 mm;  planet.mass = 1.5 kg;
  }
}
)");
  const rt::Model& m = *c.m;
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  auto q = [&](const char* path) { return ev.quantity(path, a).mid(); };
  const double rho = q("ps.sun.mass") / (0.040 * std::numbers::pi / 4 * 0.054 * 0.054);
  EXPECT_NEAR(rho, 7850, 1e-9);  // the steel's density, from the sun's disc of d = 54 mm
  // The ring: d = 216 mm, outside 216 + 2 (1.25 * 3 + 12) = 247.5 mm.
  EXPECT_NEAR(q("ps.ring.mass"), rho * 0.040 * std::numbers::pi / 4 * (0.2475 * 0.2475 - 0.216 * 0.216), 1e-9);
  EXPECT_DOUBLE_EQ(q("ps.planet.mass"), 1.5);  // given, not derived
}
