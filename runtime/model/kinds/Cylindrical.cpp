// Spur and helical stages: a pinion driving a wheel (docs/language.md, docs/catalogue.md).
#include <cmath>

#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/Standards.h"
#include "model/StageKind.h"
#include "model/kinds/Geometry.h"
#include "model/RatingRows.h"

namespace gbx::rt::kinds {

namespace {

using V = std::vector<double>;
using cat::gear::Pinion;
using cat::gear::Wheel;
using geometry::cylPair;

template <bool Helical>
struct Cyl {
  static Value beta(const KindContext& c) { return Helical ? c.at(Q::HelixAngle) : Value::number(0.0); }
  static Value mn(const KindContext& c) { return c.at(Q::NormalModule); }
  // The eight inputs of the pair's geometry: teeth, module, helix, pressure angle, shifts,
  // and the centre distance where the design gives it (0: without backlash).
  static std::vector<Value> pair(const KindContext& c) {
    const auto& en = c.ev.model().info(c.stage).entry(-1, Q::CenterDistance);
    bool given = en.attr || en.slot >= 0 || en.freedom >= 0 || c.ev.overrides(c.stage, -1, Q::CenterDistance);
    return {c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), mn(c), beta(c), c.at(Q::PressureAngle), c.orZero(Pinion, Q::Shift),
            c.orZero(Wheel, Q::Shift), given ? c.at(Q::CenterDistance) : Value::number(0.0)};
  }
  static geometry::CylPair geometryOf(const V& x) { return cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6], 1.0, x[7]); }
  // The same with the tip geometry: the basic rack's addendum (the rating's, else 1) and
  // each gear's tip diameter when given (0: from the rack), so that eps_alpha and the tip
  // radii are those the rating uses.
  static std::vector<Value> tips(const KindContext& c) {
    auto v = pair(c);
    Value haP = c.at(Q::RatingRackAddendum);
    v.push_back(haP.isNumber() ? haP : Value::number(1.0));
    for (int g : {Pinion, Wheel}) {
      const auto& en = c.ev.model().info(c.stage).entry(g, Q::TipDiameter);
      bool given = en.attr || en.slot >= 0 || en.freedom >= 0 || c.ev.overrides(c.stage, g, Q::TipDiameter);
      v.push_back(given ? c.at(g, Q::TipDiameter) : Value::number(0.0));
    }
    return v;
  }
  static geometry::CylPair tipped(const V& x) {
    auto p = cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[8], x[7]);
    if (x[9] > 0) p.ra1 = 0.5 * x[9];
    if (x[10] > 0) p.ra2 = 0.5 * x[10];
    return p;
  }

  // The pair's own quantities: geometry at its centre distance, loads, stiffness, ratios, mass.
  static std::vector<DerivedRow> stageRows() {
    return {
        {Q::CenterDistance, false,
         [](const KindContext& c, int) {
           return arith::corners(pair(c), [](const V& x) { return geometryOf(x).a; });
         }},
        {Q::WholeDepth, false, [](const KindContext& c, int) { return arith::mul(Value::rational(Rational::make(9, 4)), mn(c)); }},
        {Q::WorkingPressureAngle, false,
         [](const KindContext& c, int) {
           return arith::corners(pair(c), [](const V& x) { return geometryOf(x).alphaWt; });
         }},
        {Q::PitchLineVelocity, false,
         [](const KindContext& c, int) {
           return arith::mul(c.derived(Q::InputSpeed), arith::mul(c.derived(Pinion, Q::D), Value::rational(Rational::make(1, 2))));
         }},
        {Q::TangentialForce, false,
         [](const KindContext& c, int) {
           return arith::div(c.derived(Q::InputTorque), arith::mul(c.derived(Pinion, Q::D), Value::rational(Rational::make(1, 2))));
         }},
        // Not given: ISO 6336-1 method B.
        {Q::MeshStiffness, false,
         [](const KindContext& c, int) {
           return arith::corners({c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), c.orZero(Pinion, Q::Shift), c.orZero(Wheel, Q::Shift), beta(c),
                                  c.derived(Q::EpsAlpha)},
                                 [](const V& x) { return iso::meshStiffness(x[0], x[1], x[2], x[3], x[4], x[5]); });
         }},
        {Q::LoadDeflection, false,
         [](const KindContext& c, int) {
           return arith::div(arith::div(c.derived(Q::TangentialForce), c.at(Q::FaceWidth)), c.at(Q::MeshStiffness));
         }},
        {Q::EpsBeta, false,
         [](const KindContext& c, int) {
           return arith::corners({c.at(Q::FaceWidth), mn(c), beta(c)}, [](const V& x) { return x[0] * std::sin(x[2]) / (M_PI * x[1]); });
         }},
        {Q::EpsAlpha, false,
         [](const KindContext& c, int) {
           return arith::corners(tips(c), [](const V& x) {
             auto p = tipped(x);
             double pbt = M_PI * x[2] / std::cos(x[3]) * std::cos(p.alphaT);
             return (std::sqrt(p.ra1 * p.ra1 - p.rb1 * p.rb1) + std::sqrt(p.ra2 * p.ra2 - p.rb2 * p.rb2) - p.a * std::sin(p.alphaWt)) / pbt;
           });
         }},
        {Q::TotalContactRatio, false,
         [](const KindContext& c, int) { return arith::add(c.derived(Q::EpsAlpha), c.derived(Q::EpsBeta)); }},
        // f2 = (pi/4) mn² z1² b (1 + i²) rho / cos²(beta) (docs/dynamics.md).
        {Q::Mass, false,
         [](const KindContext& c, int) {
           return arith::corners({mn(c), c.at(Pinion, Q::Z), c.at(Q::FaceWidth), c.derived(Q::Ratio), c.material(Q::Density), beta(c)},
                                 [](const V& x) {
                                   return M_PI / 4 * x[0] * x[0] * x[1] * x[1] * x[2] * (1 + x[3] * x[3]) * x[4] /
                                          (std::cos(x[5]) * std::cos(x[5]));
                                 });
         }},
        // (1/u)(C6/C5 - 1) - u C1/(C6 - C1), the balance of specific sliding (docs/dynamics.md).
        // The tips are those eps_alpha and the rating use.
        {Q::SlidingBalance, false,
         [](const KindContext& c, int) {
           return arith::corners(tips(c), [](const V& x) {
             auto p = tipped(x);
             double u = x[1] / x[0];
             double c6 = (p.rb1 + p.rb2) * std::tan(p.alphaWt);
             double c5 = std::sqrt(p.ra1 * p.ra1 - p.rb1 * p.rb1);
             double c1 = c6 - std::sqrt(p.ra2 * p.ra2 - p.rb2 * p.rb2);
             return (1.0 / u) * (c6 / c5 - 1.0) - u * (c1 / (c6 - c1));
           });
         }},
    };
  }

  // Each gear's quantities: diameters, radii, accuracy-grade deviations, deflections.
  static std::vector<DerivedRow> gearRows() {
    return {
        {Q::D, true,
         [](const KindContext& c, int g) {
           return arith::corners({c.at(g, Q::Z), mn(c), beta(c)}, [](const V& x) { return x[0] * x[1] / std::cos(x[2]); });
         }},
        {Q::BaseRadius, true,
         [](const KindContext& c, int g) {
           return arith::corners({c.at(g, Q::Z), mn(c), beta(c), c.at(Q::PressureAngle)}, [](const V& x) {
             double at = std::atan(std::tan(x[3]) / std::cos(x[2]));
             return 0.5 * x[0] * x[1] / std::cos(x[2]) * std::cos(at);
           });
         }},
        {Q::TipRadius, true,
         [](const KindContext& c, int g) {
           bool p = g == Pinion;
           return arith::corners(tips(c), [p](const V& x) {
             auto q = tipped(x);
             return p ? q.ra1 : q.ra2;
           });
         }},
        // Not given: twice the tip radius above (the rack's, shortened to the centre distance).
        {Q::TipDiameter, true,
         [](const KindContext& c, int g) { return arith::mul(Value::rational(Rational(2)), c.derived(g, Q::TipRadius)); }},
        // Not given: the ISO 1328-1 tolerances of the stage's accuracy grade.
        {Q::PitchDeviation, true, [](const KindContext& c, int g) { return grade(c, g, true); }},
        {Q::ProfileDeviation, true, [](const KindContext& c, int g) { return grade(c, g, false); }},
        // Wind-up across the face of a solid gear under its torque spread evenly along the
        // face: delta_t = T b (d/2) / (2 G Jp) = 8 T b / (pi G d^3) (docs/dynamics.md).
        {Q::TorsionDeflection, true,
         [](const KindContext& c, int g) {
           Value G = c.material(Q::ShearModulus);
           if (!G.isNumber()) G = Value::number(80e9);
           return arith::corners({c.derived(g, Q::Torque), c.at(Q::FaceWidth), G, c.derived(g, Q::D)},
                                 [](const V& x) { return 8.0 * std::fabs(x[0]) * x[1] / (M_PI * x[2] * x[3] * x[3] * x[3]); });
         }},
        // A shaft on two bearings loaded by the normal tooth force at mid-span: the bending
        // mismatch across the face is y(L/2) - y(L/2 - b/2), y(x) = W x (3L^2 - 4x^2) / (48 E I).
        {Q::BendingDeflection, true,
         [](const KindContext& c, int g) {
           Value L = c.at(g, Q::BearingSpan), ds = c.at(g, Q::ShaftDiameter);
           if (!L.isNumber() || !ds.isNumber()) return Value::invalid();
           Value E = c.material(Q::YoungsModulus);
           if (!E.isNumber()) E = Value::number(206e9);
           return arith::corners({c.derived(Q::TangentialForce), c.at(Q::PressureAngle), L, ds, c.at(Q::FaceWidth), E}, [](const V& x) {
             double W = x[0] / std::cos(x[1]), Lx = x[2], I = M_PI * std::pow(x[3], 4) / 64.0;
             auto y = [&](double s) { return W * s * (3 * Lx * Lx - 4 * s * s) / (48.0 * x[5] * I); };
             return y(0.5 * Lx) - y(0.5 * Lx - 0.5 * std::min(x[4], Lx));
           });
         }},
    };
  }

  static std::vector<DerivedRow> rows() {
    auto r = pinionWheelRows();
    for (auto part : {stageRows(), gearRows(), rating::pairRows()})
      r.insert(r.end(), part.begin(), part.end());
    return r;
  }

  static Value grade(const KindContext& c, int g, bool pitch) {
    Value q = c.at(Q::Accuracy);
    if (!q.exact || !q.exact->isInteger()) return Value::invalid();
    int grade = static_cast<int>(q.exact->num());
    return arith::corners({mn(c), c.derived(g, Q::D)}, [grade, pitch](const V& x) {
      return pitch ? iso::singlePitch(grade, x[0], x[1]) : iso::totalProfile(grade, x[0], x[1]);
    });
  }
};

Truth reduction(const KindContext& c) { return arith::less(c.at(Pinion, Q::Z), c.at(Wheel, Q::Z), false); }

} // namespace

const StageKindImpl& spur() {
  static const StageKindImpl k(ir::StageKind::Spur, SceneModel::SingleMesh, Cyl<false>::rows(), {{"reduction: wheel.z > pinion.z", reduction}});
  return k;
}

const StageKindImpl& helical() {
  static const StageKindImpl k(ir::StageKind::Helical, SceneModel::SingleMesh, Cyl<true>::rows(),
                               {{"reduction: wheel.z > pinion.z", reduction}});
  return k;
}

} // namespace gbx::rt::kinds
