// Idler trains: a driver, a free idler and a driven gear in line.
#include <cmath>

#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/StageKind.h"
#include "model/kinds/Geometry.h"
#include "model/RatingRows.h"

namespace gbx::rt::kinds {

namespace {

using cat::gear::Driven;
using cat::gear::Driver;
using cat::gear::Idler;

std::vector<DerivedRow> rows() {
  auto r = moduleGearRows();
  std::vector<DerivedRow> own = {
      {Q::Ratio, false, [](const KindContext& c, int) { return arith::div(c.at(Driven, Q::Z), c.at(Driver, Q::Z)); }},
      {Q::MeshFrequency, false, [](const KindContext& c, int) { return meshFrequency(c, Q::InputSpeed, Driver); }},
      // Driver to driven along the line of centres: the sum of both meshes' working centre
      // distances, each from its shifts (the meshes run without backlash).
      {Q::CenterDistance, false,
       [](const KindContext& c, int) {
         Value half = Value::rational(Rational::make(1, 2));
         Value teeth = arith::add(arith::add(arith::mul(c.at(Driver, Q::Z), half), c.at(Idler, Q::Z)), arith::mul(c.at(Driven, Q::Z), half));
         Value unshifted = arith::mul(teeth, c.at(Q::Module));
         Value x1 = c.orZero(Driver, Q::Shift), x2 = c.orZero(Idler, Q::Shift), x3 = c.orZero(Driven, Q::Shift);
         if (x1.isPoint() && x2.isPoint() && x3.isPoint() && x1.lo == 0 && x2.lo == 0 && x3.lo == 0) return unshifted;  // exact
         return arith::corners({c.at(Driver, Q::Z), c.at(Idler, Q::Z), c.at(Driven, Q::Z), c.at(Q::Module), c.at(Q::PressureAngle), x1, x2, x3},
                               [](const std::vector<double>& x) {
                                 return geometry::workingCenterDistance(x[0], x[1], x[3], x[4], x[5], x[6]) +
                                        geometry::workingCenterDistance(x[1], x[2], x[3], x[4], x[6], x[7]);
                               });
       }},
      {Q::Speed, true,
       [](const KindContext& c, int g) {
         if (g == Driver) return c.derived(Q::InputSpeed);
         if (g == Idler) return arith::mul(c.derived(Q::InputSpeed), arith::div(c.at(Driver, Q::Z), c.at(Idler, Q::Z)));
         return c.derived(Q::OutputSpeed);
       }},
      // The idler carries no net torque; at each of its meshes its flanks see T_driver z_i / z_d.
      {Q::Torque, true,
       [](const KindContext& c, int g) {
         if (g == Driver) return c.derived(Q::InputTorque);
         if (g == Idler) return arith::mul(c.derived(Q::InputTorque), arith::div(c.at(Idler, Q::Z), c.at(Driver, Q::Z)));
         return c.derived(Q::OutputTorque);
       }},
  };
  r.insert(r.end(), own.begin(), own.end());
  auto rating = rating::pairRows();
  r.insert(r.end(), rating.begin(), rating.end());
  return r;
}

Truth reduction(const KindContext& c) { return arith::less(c.at(Driver, Q::Z), c.at(Driven, Q::Z), false); }

} // namespace

const StageKindImpl& idler() {
  static const StageKindImpl k(ir::StageKind::Idler, SceneModel::None, rows(), {{"reduction: driven.z > driver.z", reduction}});
  return k;
}

} // namespace gbx::rt::kinds
