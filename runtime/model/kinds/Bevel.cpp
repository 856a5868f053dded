// Bevel stages: a pinion driving a wheel across a shaft angle (docs/search.md).
#include <cmath>

#include "catalogue/StageKinds.h"
#include "model/BevelRows.h"
#include "model/Evaluator.h"
#include "model/StageKind.h"

namespace gbx::rt::kinds {

namespace {

using V = std::vector<double>;
using cat::gear::Pinion;
using cat::gear::Wheel;

// The wheel's pitch cone angle from the teeth and the shaft angle.
double wheelCone(double z1, double z2, double shaft) { return std::atan2(std::sin(shaft), z1 / z2 + std::cos(shaft)); }

std::vector<DerivedRow> rows() {
  auto r = pinionWheelRows();
  std::vector<DerivedRow> own = {
      // mmn/b = (2 Re/b - 1) cos(beta_m) sin(delta2)/z2; at 90° sin(delta2)/z2 = 1/sqrt(z1² + z2²).
      {Q::MmnB, false,
       [](const KindContext& c, int) {
         return arith::corners({c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), c.at(Q::SpiralAngle), c.at(Q::FaceRatio), c.at(Q::ShaftAngle)},
                               [](const V& x) { return (2.0 / x[3] - 1.0) * std::cos(x[2]) * std::sin(wheelCone(x[0], x[1], x[4])) / x[1]; });
       }},
      {Q::ConeAngle, true,
       [](const KindContext& c, int g) {
         bool p = g == Pinion;
         return arith::corners({c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), c.at(Q::ShaftAngle)}, [p](const V& x) {
           double d2 = wheelCone(x[0], x[1], x[2]);
           return p ? x[2] - d2 : d2;
         });
       }},
  };
  r.insert(r.end(), own.begin(), own.end());
  auto rating = rating::bevelRows();
  r.insert(r.end(), rating.begin(), rating.end());
  return r;
}

Truth reduction(const KindContext& c) { return arith::less(c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), false); }

} // namespace

const StageKindImpl& bevel() {
  static const StageKindImpl k(ir::StageKind::Bevel, SceneModel::None, rows(), {{"reduction: wheel.z > pinion.z", reduction}});
  return k;
}

} // namespace gbx::rt::kinds
