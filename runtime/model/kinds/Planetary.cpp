// Planetary stages: sun input, ring fixed, carrier output, equally spaced planets.
#include <algorithm>
#include <cmath>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/RatingRows.h"
#include "model/StageKind.h"
#include "model/kinds/Geometry.h"

namespace gbx::rt::kinds {

namespace {

using cat::gear::Planet;
using cat::gear::Ring;
using cat::gear::Sun;

Value half() { return Value::rational(Rational::make(1, 2)); }
Truth truth(bool b) { return b ? Truth::True : Truth::False; }

// Shifts are given to four decimals: 1e-3 m_n is the centre distance that rounding moves.
constexpr double kConcentric = 1e-3;

// The sun-planet working centre distance less the planet-ring one (the ring's shift as ISO
// 21771 writes it for an internal gear), each mesh at its own working pressure angle.
double concentricity(double zs, double zp, double zr, double m, double alpha, const double x[3]) {
  return geometry::workingCenterDistance(zs, zp, m, alpha, x[Sun], x[Planet]) -
         std::fabs(geometry::workingCenterDistance(zp, -zr, m, alpha, x[Planet], x[Ring]));
}

// The one shift given as a range (Freedom::solved), solved from the concentricity: the root
// of the centre distances' difference in its range, by Brent's method (GSL) to 1e-12; an end
// of the range where no root lies inside but that end is concentric within the tolerance;
// else invalid (no shift in the range makes the stage concentric).
Value concentricShift(const KindContext& c, int gear) {
  const Model& model = c.ev.model();
  const int f = model.freedomOf(c.stage, gear, Q::Shift);
  std::vector<Value> v = {c.at(Sun, Q::Z), c.at(Planet, Q::Z), c.at(Ring, Q::Z), c.at(Q::Module), c.at(Q::PressureAngle)};
  for (int g : {Sun, Planet, Ring})
    if (g != gear) v.push_back(c.orZero(g, Q::Shift));
  if (f < 0 || std::any_of(v.begin(), v.end(), [](const Value& x) { return !x.isPoint(); })) return Value::invalid();
  struct Params {
    double zs, zp, zr, m, alpha, x[3];
    int gear;
  } p{v[0].lo, v[1].lo, v[2].lo, v[3].lo, v[4].lo, {0, 0, 0}, gear};
  if (!(p.zr > p.zp)) return Value::invalid();
  for (int g = Sun, k = 5; g <= Ring; ++g)
    if (g != gear) p.x[g] = v[static_cast<size_t>(k++)].lo;
  gsl_function fn;
  fn.function = [](double x, void* q) {
    auto* s = static_cast<Params*>(q);
    s->x[s->gear] = x;
    return concentricity(s->zs, s->zp, s->zr, s->m, s->alpha, s->x);
  };
  fn.params = &p;
  const double lo = model.freedoms[static_cast<size_t>(f)].lo, hi = model.freedoms[static_cast<size_t>(f)].hi;
  const double flo = fn.function(lo, &p), fhi = fn.function(hi, &p);
  if (!std::isfinite(flo) || !std::isfinite(fhi)) return Value::invalid();
  if (flo * fhi > 0) {
    double end = std::fabs(flo) < std::fabs(fhi) ? lo : hi;
    return std::min(std::fabs(flo), std::fabs(fhi)) <= kConcentric * p.m ? Value::number(end) : Value::invalid();
  }
  if (flo == 0 || fhi == 0) return Value::number(flo == 0 ? lo : hi);
  gsl_set_error_handler_off();
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &fn, lo, hi);
  for (int it = 0; it < 100; ++it) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-12, 0) == GSL_SUCCESS) break;
  }
  double root = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  return Value::number(root);
}

std::vector<DerivedRow> rows() {
  auto r = moduleGearRows();
  std::vector<DerivedRow> own = {
      {Q::Ratio, false, [](const KindContext& c, int) { return arith::add(Value::rational(Rational(1)), arith::div(c.at(Ring, Q::Z), c.at(Sun, Q::Z))); }},
      // Ring fixed: each ring tooth meets a planet once per carrier turn.
      {Q::MeshFrequency, false, [](const KindContext& c, int) { return meshFrequency(c, Q::OutputSpeed, Ring); }},
      {Q::CarrierSpeed, false, [](const KindContext& c, int) { return c.derived(Q::OutputSpeed); }},
      // Sun to planet axis: the sun-planet mesh's working centre distance, from its shifts (the
      // mesh runs without backlash), as the rating of that mesh has it.
      {Q::CenterDistance, false,
       [](const KindContext& c, int) {
         Value unshifted = arith::mul(arith::add(c.at(Sun, Q::Z), c.at(Planet, Q::Z)), arith::mul(c.at(Q::Module), half()));
         Value xs = c.orZero(Sun, Q::Shift), xp = c.orZero(Planet, Q::Shift);
         if (xs.isPoint() && xp.isPoint() && xs.lo + xp.lo == 0) return unshifted;  // exact
         return arith::corners({c.at(Sun, Q::Z), c.at(Planet, Q::Z), c.at(Q::Module), c.at(Q::PressureAngle), xs, xp},
                               [](const std::vector<double>& x) { return geometry::workingCenterDistance(x[0], x[1], x[2], x[3], x[4], x[5]); });
       }},
      // Absolute speeds: the sun drives, the ring stands, a planet turns at
      // w_c (1 - z_r / z_p) about its own axis.
      {Q::Speed, true,
       [](const KindContext& c, int g) {
         if (g == Sun) return c.derived(Q::InputSpeed);
         if (g == Ring) return Value::rational(Rational(0));
         return arith::mul(c.derived(Q::OutputSpeed), arith::sub(Value::rational(Rational(1)), arith::div(c.at(Ring, Q::Z), c.at(Planet, Q::Z))));
       }},
      // A gear's mass where the spec gives none: the sun and each planet a solid disc at the
      // reference diameter, the ring an annulus from its reference circle to `rim_thickness`
      // below its root (a dedendum of 1.25 m): rho b pi/4 (D^2 - d^2).
      {Q::Mass, true,
       [](const KindContext& c, int g) {
         Value rim = g == Ring ? c.at(Ring, Q::RimThickness) : Value::number(0.0);
         if (!rim.isNumber()) return Value::invalid();
         return arith::corners({c.at(g, Q::Z), c.at(Q::Module), c.at(Q::FaceWidth), c.material(Q::Density), rim}, [g](const std::vector<double>& x) {
           double d = x[0] * x[1], outer = g == Ring ? d + 2 * (1.25 * x[1] + x[4]) : d;
           double inner = g == Ring ? d : 0;
           return x[3] * x[2] * M_PI / 4 * (outer * outer - inner * inner);
         });
       }},
      // Torques on each member's own axis: T_sun, each planet T_sun z_p / (z_s N), the ring's
      // reaction T_sun z_r / z_s.
      {Q::Torque, true,
       [](const KindContext& c, int g) {
         Value ts = c.derived(Q::InputTorque);
         if (g == Sun) return ts;
         if (g == Ring) return arith::mul(ts, arith::div(c.at(Ring, Q::Z), c.at(Sun, Q::Z)));
         return arith::div(arith::mul(ts, c.at(Planet, Q::Z)), arith::mul(c.at(Sun, Q::Z), c.at(Q::Planets)));
       }},
  };
  r.insert(r.end(), own.begin(), own.end());
  auto rating = rating::pairRows();
  r.insert(r.end(), rating.begin(), rating.end());
  auto bearings = rating::planetBearingRows();
  r.insert(r.end(), bearings.begin(), bearings.end());
  return r;
}

// Whether the stage's shift given as a range (Freedom::solved) has no value: no shift in the
// range makes the stage concentric.
bool solvedShiftMissing(const KindContext& c) {
  const Model& m = c.ev.model();
  for (int g : {Sun, Planet, Ring})
    if (int f = m.freedomOf(c.stage, g, Q::Shift); f >= 0 && m.freedoms[static_cast<size_t>(f)].solved)
      return c.at(g, Q::Shift).kind == Value::Invalid;
  return false;
}

std::vector<ImplicitRule> rules() {
  return {
      // One shift given as a range is solved from the concentricity (concentricShift); the
      // funnel says so where the range holds no solution.
      {"concentric: a value in the range of the shift given as a range makes the working centre distances equal",
       [](const KindContext& c) { return truth(!solvedShiftMissing(c)); }},
      // Without profile shifts the tooth counts fix the concentricity. A stage whose gears
      // carry shifts (NREL 5 MW: 19/17/56) is concentric on its working centre distances: the
      // sun-planet mesh's equals the planet-ring mesh's (the ring's shift in ISO 21771's
      // convention for an internal gear), each mesh at its own working pressure angle.
      {"concentric: ring.z == sun.z + 2 * planet.z, or equal working centre distances with profile shifts",
       [](const KindContext& c) {
         bool shifted = c.at(Sun, Q::Shift).isNumber() || c.at(Planet, Q::Shift).isNumber() || c.at(Ring, Q::Shift).isNumber();
         if (!shifted) {
           Value want = arith::add(c.at(Sun, Q::Z), arith::mul(Value::rational(Rational(2)), c.at(Planet, Q::Z)));
           return arith::equal(c.at(Ring, Q::Z), want);
         }
         std::vector<Value> v = {c.at(Sun, Q::Z), c.at(Planet, Q::Z), c.at(Ring, Q::Z), c.at(Q::Module), c.at(Q::PressureAngle),
                                 c.orZero(Sun, Q::Shift), c.orZero(Planet, Q::Shift), c.orZero(Ring, Q::Shift)};
         for (const auto& x : v)
           if (!x.isPoint()) {
             // A solved shift without a value is removed by the rule before.
             return solvedShiftMissing(c) ? Truth::True : Truth::Unknown;
           }
         double zs = v[0].lo, zp = v[1].lo, zr = v[2].lo, m = v[3].lo, alpha = v[4].lo;
         if (!(zr > zp)) return Truth::False;
         double sunPlanet = geometry::workingCenterDistance(zs, zp, m, alpha, v[5].lo, v[6].lo);
         double planetRing = std::fabs(geometry::workingCenterDistance(zp, -zr, m, alpha, v[6].lo, v[7].lo));
         return truth(std::fabs(sunPlanet - planetRing) <= kConcentric * m);
       }},
      {"assembly: (sun.z + ring.z) / planets is whole",
       [](const KindContext& c) {
         Value q = arith::div(arith::add(c.at(Sun, Q::Z), c.at(Ring, Q::Z)), c.at(Q::Planets));
         if (!q.exact) return Truth::Unknown;
         return truth(q.exact->isInteger());
       }},
      {"adjacency: (sun.z + planet.z) * sin(pi / planets) > planet.z + 2",
       [](const KindContext& c) {
         Value n = c.at(Q::Planets);
         if (!n.isPoint()) return Truth::Unknown;
         double lhs = (c.at(Sun, Q::Z).lo + c.at(Planet, Q::Z).lo) * std::sin(M_PI / n.lo);
         return truth(lhs > c.at(Planet, Q::Z).lo + 2.0);
       }},
  };
}

} // namespace

const StageKindImpl& planetary() {
  static const StageKindImpl k = [] {
    StageKindImpl kind(ir::StageKind::Planetary, SceneModel::Planetary, rows(), rules());
    kind.solvedKey = Q::Shift;
    kind.solve = concentricShift;
    return kind;
  }();
  return k;
}

} // namespace gbx::rt::kinds
