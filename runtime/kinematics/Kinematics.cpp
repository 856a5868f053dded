// Derived quantities of a stage: ratio, speeds and torques along the train, mesh
// frequency, and the geometry of each stage kind (DOMAIN.md §1–§4).
#include <cmath>

#include "kinematics/Standards.h"
#include "search/Evaluator.h"

namespace gbx::rt {

namespace {

using V = std::vector<double>;

double involute(double a) { return std::tan(a) - a; }

// Inverse involute by Newton's method on inv(a) = t; converges for 0 < t < 1.
double inverseInvolute(double t) {
  double a = std::cbrt(3.0 * t);
  for (int i = 0; i < 30; ++i) {
    double f = involute(a) - t, d = std::tan(a) * std::tan(a);
    if (d == 0) break;
    double next = a - f / d;
    if (std::fabs(next - a) < 1e-16) return next;
    a = next;
  }
  return a;
}

// Helical/spur pair with profile shifts (DOMAIN.md §3): working centre distance,
// working pressure angle and tip radii with the tip shortening.
struct CylPair {
  double alphaT, alphaWt, a0, a, d1, d2, rb1, rb2, ra1, ra2;
};

CylPair cylPair(double z1, double z2, double mn, double beta, double alphaN, double x1, double x2) {
  CylPair p{};
  p.alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  double invWt = involute(p.alphaT) + 2.0 * (x1 + x2) * std::tan(alphaN) / (z1 + z2);
  p.alphaWt = (x1 + x2) == 0 ? p.alphaT : inverseInvolute(invWt);
  p.d1 = z1 * mn / std::cos(beta);
  p.d2 = z2 * mn / std::cos(beta);
  p.a0 = 0.5 * (p.d1 + p.d2);
  p.a = p.a0 * std::cos(p.alphaT) / std::cos(p.alphaWt);
  double dy = (x1 + x2) - (p.a - p.a0) / mn;
  p.rb1 = 0.5 * p.d1 * std::cos(p.alphaT);
  p.rb2 = 0.5 * p.d2 * std::cos(p.alphaT);
  p.ra1 = 0.5 * p.d1 + mn * (1.0 + x1 - dy);
  p.ra2 = 0.5 * p.d2 + mn * (1.0 + x2 - dy);
  return p;
}

} // namespace

Value Evaluator::derived(int stage, const std::string& name, const Assignment& a) const {
  const ir::Stage& st = *m_.stages[static_cast<size_t>(stage)].ir;
  auto at = [&](const std::string& n) { return attribute(stage, n, a); };
  auto orZero = [&](const std::string& n) {
    Value v = at(n);
    return v.kind == Value::Invalid ? Value::rational(Rational(0)) : v;
  };
  const auto kind = st.kind;
  bool cyl = kind == ir::StageKind::Spur || kind == ir::StageKind::Helical;
  auto beta = [&]() { return kind == ir::StageKind::Helical ? at("helix_angle") : Value::number(0.0); };
  auto mn = [&]() { return cyl ? at("normal_module") : at("module"); };

  if (name == "ratio") {
    switch (kind) {
    case ir::StageKind::Planetary:
      return arith::add(Value::rational(Rational(1)), arith::div(at("ring.z"), at("sun.z")));
    case ir::StageKind::Idler: return arith::div(at("driven.z"), at("driver.z"));
    default: return arith::div(at("wheel.z"), at("pinion.z"));
    }
  }
  // Speeds run down the train from the input; torques grow by each ratio (no losses).
  if (name == "input_speed") return arith::div(gearboxQuantity("input_speed", a), ratioProduct(0, stage, a));
  if (name == "output_speed") return arith::div(derived(stage, "input_speed", a), derived(stage, "ratio", a));
  if (name == "input_torque") return arith::mul(gearboxQuantity("input_torque", a), ratioProduct(0, stage, a));
  if (name == "output_torque") return arith::mul(derived(stage, "input_torque", a), derived(stage, "ratio", a));
  if (name == "carrier_speed" && kind == ir::StageKind::Planetary) return derived(stage, "output_speed", a);
  if (name == "mesh_frequency") {
    Value perRev = Value::number(1.0 / (2.0 * M_PI));
    switch (kind) {
    case ir::StageKind::Planetary:  // ring fixed: each ring tooth meets a planet once per carrier turn
      return arith::mul(arith::mul(derived(stage, "output_speed", a), perRev), at("ring.z"));
    case ir::StageKind::Idler: return arith::mul(arith::mul(derived(stage, "input_speed", a), perRev), at("driver.z"));
    default: return arith::mul(arith::mul(derived(stage, "input_speed", a), perRev), at("pinion.z"));
    }
  }
  // Gear-level: speed and torque of each member.
  auto dot = name.find('.');
  if (dot != std::string::npos) {
    std::string gear = name.substr(0, dot), q = name.substr(dot + 1);
    bool first = gear == "pinion" || gear == "sun" || gear == "driver";
    if (q == "speed") {
      if (first) return derived(stage, "input_speed", a);
      if (gear == "idler") return arith::mul(derived(stage, "input_speed", a), arith::div(at("driver.z"), at("idler.z")));
      if (gear == "planet" || gear == "ring") return Value::invalid();
      return derived(stage, "output_speed", a);
    }
    if (q == "torque") {
      if (first) return derived(stage, "input_torque", a);
      if (gear == "wheel" || gear == "driven") return derived(stage, "output_torque", a);
      return Value::invalid();
    }
    if (q == "d") {
      if (cyl) return arith::corners({at(gear + ".z"), mn(), beta()}, [](const V& x) { return x[0] * x[1] / std::cos(x[2]); });
      if (kind == ir::StageKind::Planetary || kind == ir::StageKind::Idler) return arith::mul(at(gear + ".z"), at("module"));
      return Value::invalid();
    }
    if (q == "base_radius" && cyl)
      return arith::corners({at(gear + ".z"), mn(), beta(), at("pressure_angle")}, [](const V& x) {
        double at = std::atan(std::tan(x[3]) / std::cos(x[2]));
        return 0.5 * x[0] * x[1] / std::cos(x[2]) * std::cos(at);
      });
    if (q == "tip_radius" && cyl) {
      bool p = gear == "pinion";
      return arith::corners({at("pinion.z"), at("wheel.z"), mn(), beta(), at("pressure_angle"), orZero("pinion.shift"),
                             orZero("wheel.shift")},
                            [p](const V& x) {
                              auto c = cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6]);
                              return p ? c.ra1 : c.ra2;
                            });
    }
    if (cyl && (q == "pitch_deviation" || q == "profile_deviation")) {
      // Not given: the ISO 1328-1 tolerance of the stage's accuracy grade.
      Value grade = at("accuracy");
      if (!grade.exact || !grade.exact->isInteger()) return Value::invalid();
      int g = static_cast<int>(grade.exact->num());
      bool pitch = q == "pitch_deviation";
      return arith::corners({mn(), derived(stage, gear + ".d", a)}, [g, pitch](const V& x) {
        return pitch ? iso::singlePitch(g, x[0], x[1]) : iso::totalProfile(g, x[0], x[1]);
      });
    }
    if (cyl && q == "torsion_deflection") {
      // Wind-up across the face of a solid gear under its torque spread evenly along the
      // face: delta_t = T b (d/2) / (2 G Jp) = 8 T b / (pi G d^3) (DOMAIN.md §4).
      Value G = materialProperty(stage, "shear_modulus");
      if (!G.isNumber()) G = Value::number(80e9);
      return arith::corners({derived(stage, gear + ".torque", a), at("face_width"), G, derived(stage, gear + ".d", a)},
                            [](const V& x) { return 8.0 * std::fabs(x[0]) * x[1] / (M_PI * x[2] * x[3] * x[3] * x[3]); });
    }
    if (cyl && q == "bending_deflection") {
      // A shaft on two bearings loaded by the normal tooth force at mid-span: the bending
      // mismatch across the face is y(L/2) - y(L/2 - b/2), y(x) = W x (3L^2 - 4x^2) / (48 E I).
      Value L = at(gear + ".bearing_span"), ds = at(gear + ".shaft_diameter");
      if (!L.isNumber() || !ds.isNumber()) return Value::invalid();
      Value E = materialProperty(stage, "youngs_modulus");
      if (!E.isNumber()) E = Value::number(206e9);
      return arith::corners({derived(stage, "tangential_force", a), at("pressure_angle"), L, ds, at("face_width"), E}, [](const V& x) {
        double W = x[0] / std::cos(x[1]), Lx = x[2], I = M_PI * std::pow(x[3], 4) / 64.0;
        auto y = [&](double s) { return W * s * (3 * Lx * Lx - 4 * s * s) / (48.0 * x[5] * I); };
        return y(0.5 * Lx) - y(0.5 * Lx - 0.5 * std::min(x[4], Lx));
      });
    }
    if (q == "cone_angle" && kind == ir::StageKind::Bevel) {
      bool p = gear == "pinion";
      return arith::corners({at("pinion.z"), at("wheel.z"), at("shaft_angle")}, [p](const V& x) {
        double d2 = std::atan2(std::sin(x[2]), x[0] / x[1] + std::cos(x[2]));
        return p ? x[2] - d2 : d2;
      });
    }
    return Value::invalid();
  }
  if (kind == ir::StageKind::Bevel && name == "mmn_b") {
    // mmn/b = (2 Re/b - 1) cos(beta_m) sin(delta2)/z2; at 90° sin(delta2)/z2 = 1/sqrt(z1² + z2²).
    return arith::corners({at("pinion.z"), at("wheel.z"), at("spiral_angle"), at("face_ratio"), at("shaft_angle")},
                          [](const V& x) {
                            double d2 = std::atan2(std::sin(x[4]), x[0] / x[1] + std::cos(x[4]));
                            return (2.0 / x[3] - 1.0) * std::cos(x[2]) * std::sin(d2) / x[1];
                          });
  }
  if (name == "center_distance") {
    if (kind == ir::StageKind::Planetary)
      return arith::mul(arith::add(at("sun.z"), at("planet.z")), arith::mul(at("module"), Value::rational(Rational::make(1, 2))));
    if (kind == ir::StageKind::Idler) {
      Value half = Value::rational(Rational::make(1, 2));
      Value teeth = arith::add(arith::add(arith::mul(at("driver.z"), half), at("idler.z")), arith::mul(at("driven.z"), half));
      return arith::mul(teeth, at("module"));
    }
    if (cyl)
      return arith::corners({at("pinion.z"), at("wheel.z"), mn(), beta(), at("pressure_angle"), orZero("pinion.shift"),
                             orZero("wheel.shift")},
                            [](const V& x) { return cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6]).a; });
    return Value::invalid();
  }
  if (!cyl) return Value::invalid();
  if (name == "whole_depth") return arith::mul(Value::rational(Rational::make(9, 4)), mn());
  if (name == "working_pressure_angle")
    return arith::corners({at("pinion.z"), at("wheel.z"), mn(), beta(), at("pressure_angle"), orZero("pinion.shift"),
                           orZero("wheel.shift")},
                          [](const V& x) { return cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6]).alphaWt; });
  if (name == "pitch_line_velocity")
    return arith::mul(derived(stage, "input_speed", a), arith::mul(derived(stage, "pinion.d", a), Value::rational(Rational::make(1, 2))));
  if (name == "tangential_force")
    return arith::div(derived(stage, "input_torque", a), arith::mul(derived(stage, "pinion.d", a), Value::rational(Rational::make(1, 2))));
  if (name == "mesh_stiffness") {
    // Not given: ISO 6336-1 method B.
    return arith::corners({at("pinion.z"), at("wheel.z"), orZero("pinion.shift"), orZero("wheel.shift"), beta(), derived(stage, "eps_alpha", a)},
                          [](const V& x) { return iso::meshStiffness(x[0], x[1], x[2], x[3], x[4], x[5]); });
  }
  if (name == "load_deflection")
    return arith::div(arith::div(derived(stage, "tangential_force", a), at("face_width")), at("mesh_stiffness"));
  if (name == "eps_beta")
    return arith::corners({at("face_width"), mn(), beta()}, [](const V& x) { return x[0] * std::sin(x[2]) / (M_PI * x[1]); });
  if (name == "eps_alpha")
    return arith::corners({at("pinion.z"), at("wheel.z"), mn(), beta(), at("pressure_angle"), orZero("pinion.shift"),
                           orZero("wheel.shift")},
                          [](const V& x) {
                            auto c = cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6]);
                            double pbt = M_PI * x[2] / std::cos(x[3]) * std::cos(c.alphaT);
                            return (std::sqrt(c.ra1 * c.ra1 - c.rb1 * c.rb1) + std::sqrt(c.ra2 * c.ra2 - c.rb2 * c.rb2) -
                                    c.a * std::sin(c.alphaWt)) / pbt;
                          });
  if (name == "total_contact_ratio") return arith::add(derived(stage, "eps_alpha", a), derived(stage, "eps_beta", a));
  if (name == "mass") {
    // f2 = (pi/4) mn² z1² b (1 + i²) rho / cos²(beta) (DOMAIN.md §3).
    return arith::corners({mn(), at("pinion.z"), at("face_width"), derived(stage, "ratio", a), materialProperty(stage, "density"), beta()},
                          [](const V& x) {
                            return M_PI / 4 * x[0] * x[0] * x[1] * x[1] * x[2] * (1 + x[3] * x[3]) * x[4] /
                                   (std::cos(x[5]) * std::cos(x[5]));
                          });
  }
  if (name == "sliding_balance") {
    // (1/u)(C6/C5 - 1) - u C1/(C6 - C1), the balance of specific sliding (DOMAIN.md §3).
    return arith::corners({at("pinion.z"), at("wheel.z"), mn(), beta(), at("pressure_angle"), orZero("pinion.shift"),
                           orZero("wheel.shift")},
                          [](const V& x) {
                            auto c = cylPair(x[0], x[1], x[2], x[3], x[4], x[5], x[6]);
                            double u = x[1] / x[0];
                            double c6 = (c.rb1 + c.rb2) * std::tan(c.alphaWt);
                            double c5 = std::sqrt(c.ra1 * c.ra1 - c.rb1 * c.rb1);
                            double c1 = c6 - std::sqrt(c.ra2 * c.ra2 - c.rb2 * c.rb2);
                            return (1.0 / u) * (c6 / c5 - 1.0) - u * (c1 / (c6 - c1));
                          });
  }
  return Value::invalid();
}

} // namespace gbx::rt
