#include "shaft/ShaftPlan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/Shafts.h"
#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/Recent.h"
#include "rating/Scuffing.h"

namespace gbx::rt {

std::optional<double> stageNumber(const Evaluator& ev, const Assignment& a, int stage, int gear, Q key) {
  ir::QuantityRef r;
  r.owner = ir::QuantityRef::Stage;
  r.index = static_cast<std::int16_t>(stage);
  r.gear = static_cast<std::int8_t>(gear);
  r.key = key;
  Value v = ev.quantity(r, a);
  if (!v.isNumber()) return std::nullopt;
  return v.mid();
}

// The sense of rotation of a gear about its own shaft's +x: + on the input; a parallel mesh
// reverses it, a bevel mesh turns the wheel as the two apexes point (its sense the pinion's
// times -a_pinion a_wheel, a = +1 for an apex to the right; reversed when either gear is on
// no shaft) (docs/language.md, "Shafts and bearings").
double senseOf(const Model& model, int stage, bool driving) {
  using Place = ir::Shaft::Place;
  auto apexOf = [&](int st, int gear) -> double {
    for (const auto& sh : model.gearbox.shafts)
      for (const auto& q : sh.placed)
        if (q.kind == Place::Gear && q.stage == st && q.gear == gear) {
          const ir::Setting* a = ir::findSetting(q.settings, Q::Apex);
          return a && a->choice == 1 ? 1 : a ? -1 : 0;
        }
    return 0;
  };
  double sigma = 1;
  for (int st = 0; st < stage || (st == stage && !driving); ++st) {
    double a1 = 0, a2 = 0;
    if (model.info(st).ir->kind == ir::StageKind::Bevel) {
      a1 = apexOf(st, cat::gear::Pinion);
      a2 = apexOf(st, cat::gear::Wheel);
    }
    sigma *= (a1 != 0 && a2 != 0) ? -a1 * a2 : -1;
    if (st == stage) break;
  }
  return sigma;
}

namespace {

constexpr double kPi = 3.14159265358979323846;
using Place = ir::Shaft::Place;

std::optional<double> given(const std::vector<ir::Setting>& s, Q key) {
  const ir::Setting* x = ir::findSetting(s, key);
  if (!x || !x->value) return std::nullopt;
  return x->value->toDouble();
}

std::optional<double> given(const std::vector<ir::Setting>& s, const std::string& name) {
  const ir::Setting* x = ir::findSetting(s, name);
  if (!x || !x->value) return std::nullopt;
  return x->value->toDouble();
}

int choiceOf(const std::vector<ir::Setting>& s, Q key, int dflt) {
  const ir::Setting* x = ir::findSetting(s, key);
  return x && x->choice >= 0 ? x->choice : dflt;
}

struct Ctx {
  const Evaluator& ev;
  const Assignment& a;
  std::string* error;
  const LoadSpread* spread = nullptr;
  std::optional<double> stage(int st, int gear, Q key) const { return stageNumber(ev, a, st, gear, key); }
};

// The shaft's own material: E, G (or E / 2(1 + nu)) and density.
std::optional<shaft::Material> materialOf(const Evaluator& ev, const ir::Shaft& sh) {
  const ir::Setting* m = ir::findSetting(sh.settings, Q::Material);
  if (!m) return std::nullopt;
  int i = ev.model().program.materialIndex(m->symbol);
  if (i < 0) return std::nullopt;
  const auto& props = ev.model().program.materials[static_cast<size_t>(i)].properties;
  auto E = given(props, Q::YoungsModulus), nu = given(props, Q::Poisson), rho = given(props, Q::Density),
       G = given(props, Q::ShearModulus);
  if (!E || !rho || (!G && !nu)) return std::nullopt;
  return shaft::Material{*E, G ? *G : *E / (2 * (1 + *nu)), *rho};
}

double diameterAt(const shaft::Model& m, double x) {
  for (const auto& s : m.sections)
    if (x >= s.x0 - 1e-12 && x <= s.x1 + 1e-12) return s.diameter;
  return m.sections.empty() ? 0 : m.sections.back().diameter;
}

// A gear's mesh forces at its pitch point: tangential (its magnitude), radial (away from its
// mate), axial (along +x), at radius r.
struct MeshForces {
  double Ft = 0, Fr = 0, Fx = 0, r = 0, d = 0;
};

// A spur or helical gear, at the working pitch circle: F_r = F_t tan(alpha_wt), F_a = F_t
// tan(beta_w), its sense from the pinion's helix hand and the rotation.
std::optional<MeshForces> cylindricalForces(const Ctx& c, const ir::Shaft::Placed& p, double T, double sigma,
                                            std::string& why) {
  const Model& model = c.ev.model();
  int st = p.stage, g = p.gear;
  bool helical = model.info(st).ir->kind == ir::StageKind::Helical;
  auto z = c.stage(st, g, Q::Z), mn = c.stage(st, -1, Q::NormalModule);
  auto alphaN = c.stage(st, -1, Q::PressureAngle), alphaWt = c.stage(st, -1, Q::WorkingPressureAngle);
  std::optional<double> beta = helical ? c.stage(st, -1, Q::HelixAngle) : std::optional<double>(0.0);
  if (!z || !mn || !alphaN || !alphaWt || !beta) {
    why = "its geometry is not known at this design";
    return std::nullopt;
  }
  double d = *z * *mn / std::cos(*beta), alphaT = std::atan(std::tan(*alphaN) / std::cos(*beta));
  double dw = d * std::cos(alphaT) / std::cos(*alphaWt);
  double tanBw = std::tan(*beta) * dw / d;
  MeshForces f{2 * std::fabs(T) / dw, 0, 0, dw / 2, d};
  f.Fr = f.Ft * std::tan(*alphaWt);
  bool driving = g == cat::gear::Pinion;
  double Ftheta = driving ? -sigma * f.Ft : sigma * f.Ft;
  const ir::Attribute* hand = model.attribute(st, Q::HelixHand);
  double h = (hand && hand->choice == cat::helixHand::Left) ? -1 : 1;
  if (!driving) h = -h; // the mate's hand is the opposite
  f.Fx = helical ? -h * Ftheta * tanBw : 0;
  return f;
}

// A bevel gear at its mean point (shaft angle 90 deg): with F_mt = 2 T / d_m,
// F_a = F_mt (tan(alpha_n) sin(delta) + s sin(beta_m) cos(delta)) / cos(beta_m) away from the
// apex and F_r = F_mt (tan(alpha_n) cos(delta) - s sin(beta_m) sin(delta)) / cos(beta_m) away
// from the mate, s = +1 on the driving pinion where its spiral hand and its rotation seen from
// its back (its large end) agree (right hand clockwise, left counter-clockwise), -1 where
// they do not, and the opposite on the driven wheel.
std::optional<MeshForces> bevelForces(const Ctx& c, const ir::Shaft::Placed& p, double T, double sigma,
                                      std::string& why) {
  const Model& model = c.ev.model();
  int st = p.stage, g = p.gear;
  auto dm = c.stage(st, g, Q::MeanDiameter), delta = c.stage(st, g, Q::ConeAngle),
       beta = c.stage(st, -1, Q::SpiralAngle), alpha = c.stage(st, -1, Q::PressureAngle),
       sigmaShaft = c.stage(st, -1, Q::ShaftAngle);
  if (!dm || !delta || !beta || !alpha) {
    why = "its geometry is not known at this design";
    return std::nullopt;
  }
  if (sigmaShaft && std::fabs(*sigmaShaft - kPi / 2) > 1e-9) {
    why = "a bevel pair on shafts needs a shaft angle of 90 deg so far";
    return std::nullopt;
  }
  const ir::Setting* apex = ir::findSetting(p.settings, Q::Apex);
  double a = apex && apex->choice == 1 ? 1 : -1;
  bool driving = g == cat::gear::Pinion;
  const ir::Attribute* hand = model.attribute(st, Q::SpiralHand);
  double h = (hand && hand->choice == 1) ? -1 : 1; // the pinion's: right +1, left -1
  if (!driving) h = -h;
  // Seen from its back (the side away from the apex), positive about +x reads clockwise
  // where the apex points to +x.
  bool clockwise = sigma * a > 0;
  double agree = (h > 0) == clockwise ? 1 : -1, s = driving ? agree : -agree;
  double Ft = 2 * std::fabs(T) / *dm, cb = std::cos(*beta), sb = std::sin(*beta), ta = std::tan(*alpha);
  double Fa = Ft * (ta * std::sin(*delta) + s * sb * std::cos(*delta)) / cb;
  double Fr = Ft * (ta * std::cos(*delta) - s * sb * std::sin(*delta)) / cb;
  return MeshForces{Ft, Fr, -a * Fa, *dm / 2, *dm};
}

// A gear's mesh forces on its shaft. The stages lie in one plane: the driving gear's mate at
// +y, the driven gear's at -y; the tangential force opposes a driving gear's rotation and
// drives a driven one's (docs/language.md, "Shafts and bearings").
bool gearLoad(const Ctx& c, const ir::Shaft::Placed& p, shaft::Model& m, ShaftResult& out, double& speed) {
  auto fail = [&](const std::string& s) {
    if (c.error) *c.error = fmt::format("gear `{}`: {}", p.name, s);
    return false;
  };
  const Model& model = c.ev.model();
  int st = p.stage, g = p.gear;
  auto T = c.stage(st, g, Q::Torque), w = c.stage(st, g, Q::Speed), b = c.stage(st, -1, Q::FaceWidth);
  if (!T || !w) return fail("its torque and speed need the operating point");
  if (!b) return fail("its stage gives no `face_width`");
  bool driving = g == cat::gear::Pinion;
  double sigma = senseOf(model, st, driving);
  std::string why;
  auto f = model.info(st).ir->kind == ir::StageKind::Bevel ? bevelForces(c, p, *T, sigma, why)
                                                           : cylindricalForces(c, p, *T, sigma, why);
  if (!f) return fail(why);
  double s = driving ? 1 : -1;
  double Ftheta = driving ? -sigma * f->Ft : sigma * f->Ft;
  const double Ft = f->Ft, Fr = f->Fr, Fa = std::fabs(f->Fx), rw = f->r, d = f->d, Fx = f->Fx;
  double x = p.at.toDouble();
  shaft::PointLoad whole{x, -s * Fr, s * Ftheta, Fx, -s * rw * Fx, 0, rw * Ftheta};
  if (c.spread && c.spread->stage == st && !c.spread->share.empty()) {
    // Across the face, slice by slice, as the contact analysis carries it.
    size_t n = c.spread->share.size();
    for (size_t j = 0; j < n; ++j) {
      double k = c.spread->share[j] * c.spread->scale;
      m.loads.push_back({x + *b * ((static_cast<double>(j) + 0.5) / static_cast<double>(n) - 0.5), k * whole.Fy, k * whole.Fz,
                         k * whole.Fx, k * whole.My, 0, k * whole.T});
    }
  } else {
    m.loads.push_back(whole);
  }
  out.gears.push_back({p.name, x, Ft, Fr, Fa});
  // The gear as a rigid disk for the critical speed: an annulus from the shaft to d.
  auto rho = c.ev.materialProperty(st, Q::Density);
  if (!rho.isNumber())
    out.warnings.push_back(fmt::format("gear `{}`: its stage gives no material (density): its mass is left out of the "
                                       "critical speed",
                                       p.name));
  if (rho.isNumber()) {
    double ds = diameterAt(m, x), R = d / 2, r = ds / 2;
    double mass = rho.mid() * kPi * (R * R - r * r) * *b;
    m.disks.push_back({x, mass, mass * (3 * (R * R + r * r) + *b * *b) / 12, mass * (R * R + r * r) / 2});
  }
  speed = std::fabs(*w);
  return true;
}

// DIN 743 at every notch, with the material's strengths and the `strength` settings.
bool rateStrength(const Evaluator& ev, const ir::Shaft& sh, ShaftResult& out, std::string* error) {
  auto& st = out.strength;
  const ir::Setting* m = ir::findSetting(sh.settings, Q::Material);
  int i = m ? ev.model().program.materialIndex(m->symbol) : -1;
  if (i >= 0) {
    const auto& props = ev.model().program.materials[static_cast<size_t>(i)].properties;
    st.material = {given(props, Q::TensileStrength).value_or(0), given(props, Q::YieldStrength).value_or(0),
                   static_cast<shaft::din743::Group>(choiceOf(props, Q::SteelGroup, 0))};
  }
  st.din.loadCase = static_cast<int>(given(sh.settings, "strength.load_case").value_or(2));
  const ir::Setting* surface = ir::findSetting(sh.settings, "strength.surface");
  st.din.hardened = surface && surface->choice == cat::shaftSurface::Hardened;
  st.din.KV = given(sh.settings, "strength.surface_factor").value_or(1);
  double largest = 0;
  for (const auto& s : out.model.sections)
    largest = std::max(largest, s.diameter);
  st.din.effectiveDiameter = given(sh.settings, Q::HeatTreatmentDiameter).value_or(largest);
  st.peak = given(sh.settings, "strength.peak_factor").value_or(1);
  st.minFatigue = given(sh.settings, "strength.min_safety.fatigue").value_or(1.2);
  st.minStatic = given(sh.settings, "strength.min_safety.static").value_or(1.2);
  try {
    out.notches = shaft::rateNotches(sh, out.model, out.solution, st);
  } catch (const std::invalid_argument& e) {
    if (error) *error = fmt::format("shaft `{}`: {}", sh.name, e.what());
    return false;
  }
  out.fatigueSafety = out.staticSafety = std::numeric_limits<double>::infinity();
  for (const auto& n : out.notches) {
    out.fatigueSafety = std::min(out.fatigueSafety, n.result.SD);
    out.staticSafety = std::min(out.staticSafety, n.result.SF);
    for (const auto& w : n.result.warnings)
      out.warnings.push_back(fmt::format("shaft `{}`: the {} at {:g} mm: {}", sh.name, n.kind, n.x * 1e3, w));
  }
  return true;
}

// Without `life.viscosity`, the oil of the first rated stage whose gear the shaft carries:
// nu at its oil temperature on the ASTM D341 line through nu40 and nu100, else nu40 itself.
void stageOil(const Evaluator& ev, const ir::Shaft& sh, const Assignment& a, shaft::LifeSettings& life) {
  for (const auto& p : sh.placed) {
    if (p.kind != Place::Gear) continue;
    auto value = [&](Q key) -> std::optional<double> {
      Value v = ev.attribute(p.stage, key, a);
      if (!v.isNumber()) return std::nullopt;
      return v.mid();
    };
    auto nu40 = value(Q::RatingViscosity40);
    if (!nu40) continue;
    auto nu100 = value(Q::RatingViscosity100), T = value(Q::RatingOilTemperature);
    const std::string& stage = ev.model().gearbox.stages[static_cast<size_t>(p.stage)].name;
    if (nu100 && T && *nu40 > *nu100) {
      rating::Lubricant oil;
      oil.nu40 = *nu40;
      oil.nu100 = *nu100;
      life.viscosity = oil.kinematic(*T);
      life.viscositySource = fmt::format("nu {:.3g} mm^2/s, stage {}'s oil at {:.0f} degC", life.viscosity * 1e6, stage,
                                         *T - 273.15);
    } else {
      life.viscosity = *nu40;
      life.viscositySource = fmt::format("nu {:.3g} mm^2/s, stage {}'s oil at 40 degC: it gives no viscosity_100 and "
                                         "oil_temperature",
                                         *nu40 * 1e6, stage);
    }
    return;
  }
}

// Each bearing's life at the shaft's speed, with kappa where the oil's viscosity is given;
// what stops a bearing's rating, or "".
std::string bearingLives(const Evaluator& ev, const ir::Shaft& sh, const Assignment& a,
                         const std::vector<const ir::Shaft::Placed*>& bearings, ShaftResult& out) {
  const shaft::Model& m = out.model;
  const double speed = out.speed;
  shaft::LifeSettings life;
  life.reliability = given(sh.settings, "life.reliability").value_or(0.9);
  const ir::Setting* clean = ir::findSetting(sh.settings, "life.cleanliness");
  life.contamination = given(sh.settings, "life.contamination")
                           .value_or(cat::cleanliness::kEc[clean && clean->choice >= 0 ? clean->choice : 2]);
  life.viscosity = given(sh.settings, "life.viscosity").value_or(-1);
  if (life.viscosity < 0) stageOil(ev, sh, a, life);
  for (size_t k = 0; k < bearings.size(); ++k) {
    const auto& p = *bearings[k];
    shaft::BearingData b;
    b.kind = static_cast<shaft::BearingKind>(choiceOf(p.settings, Q::BearingKind, 0));
    out.kinds.push_back(b.kind);
    b.C = given(p.settings, Q::DynamicRating).value_or(0);
    b.C0 = given(p.settings, Q::StaticRating).value_or(0);
    b.e = given(p.settings, Q::LoadRatioLimit).value_or(-1);
    b.X = given(p.settings, Q::RadialFactor).value_or(-1);
    b.Y = given(p.settings, Q::AxialFactor).value_or(-1);
    b.X0 = given(p.settings, Q::StaticRadialFactor).value_or(-1);
    b.Y0 = given(p.settings, Q::StaticAxialFactor).value_or(-1);
    b.pitchDiameter = given(p.settings, Q::PitchDiameter).value_or(1.4 * diameterAt(m, p.at.toDouble()));
    const auto& r = out.solution.reactions[k];
    try {
      out.lives.push_back(shaft::life(b, {r.radial(), r.Fx, speed}, life));
    } catch (const std::invalid_argument& e) {
      return fmt::format("bearing `{}`: {}", p.name, e.what());
    }
  }
  return "";
}

// The largest deflection: sampled eight times per element (the line is a cubic in each plane
// there), then found by golden sections between the best sample's neighbours, where the
// deflection's magnitude has one peak.
void largestDeflection(ShaftResult& out) {
  const auto& sol = out.solution;
  const auto& xs = sol.x;
  double h = 0;
  for (size_t i = 0; i < xs.size(); ++i)
    for (int k = 0; k < (i + 1 < xs.size() ? 8 : 1); ++k) {
      double step = i + 1 < xs.size() ? (xs[i + 1] - xs[i]) / 8 : 0;
      double x = xs[i] + step * k, d = sol.deflectionAt(x);
      if (d > out.deflection) {
        out.deflection = d;
        out.deflectionAt = x;
        h = std::max(step, i > 0 ? (xs[i] - xs[i - 1]) / 8 : step);
      }
    }
  if (h <= 0 || xs.empty()) return;
  double a = std::max(xs.front(), out.deflectionAt - h), b = std::min(xs.back(), out.deflectionAt + h);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double c = b - g * (b - a), d = a + g * (b - a), fc = sol.deflectionAt(c), fd = sol.deflectionAt(d);
  for (int it = 0; it < 60 && b - a > 1e-12 * (1 + std::fabs(b)); ++it) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = sol.deflectionAt(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = sol.deflectionAt(d);
    }
  }
  double x = (a + b) / 2, v = sol.deflectionAt(x);
  if (v > out.deflection) {
    out.deflection = v;
    out.deflectionAt = x;
  }
}

// Whether any setting of the shaft is a range or a set.
bool searchesSettings(const ir::Shaft& sh) {
  auto any = [](const std::vector<ir::Setting>& v) {
    return std::any_of(v.begin(), v.end(),
                       [](const ir::Setting& s) { return s.searched(); });
  };
  return any(sh.settings) ||
         std::any_of(sh.segments.begin(), sh.segments.end(), [&](const auto& g) { return any(g.settings); }) ||
         std::any_of(sh.placed.begin(), sh.placed.end(), [&](const auto& p) { return any(p.settings); });
}

// The shaft with each searched setting at the design's value; nullopt (`why` said) where the
// design has not decided one yet (a freedom's interval, a slot not chosen).
std::optional<ir::Shaft> atDesign(const Model& model, const ir::Shaft& sh, const Assignment& a, std::string& why) {
  auto copy = [&](const std::vector<ir::Setting>& from, std::vector<ir::Setting>& to) {
    for (const auto& x : from) {
      to.push_back(x.clone());
      if (!x.searched()) continue;
      Value v = shaftSettingValue(model, x, a);
      if (!v.isNumber() || v.lo != v.hi) {
        if (why.empty())
          why = model.stages.empty()
                    ? fmt::format("its `{}` is a range or a set, which only a gearbox with stages searches", x.name)
                    : fmt::format("its `{}` is not decided at this design", x.name);
        continue;
      }
      to.back().value = v.exact ? units::Number::exact(*v.exact) : units::Number::approx(v.mid());
    }
  };
  ir::Shaft out;
  out.name = sh.name;
  out.span = sh.span;
  copy(sh.settings, out.settings);
  for (const auto& seg : sh.segments) {
    ir::Shaft::Segment c;
    c.x0 = seg.x0;
    c.x1 = seg.x1;
    c.span = seg.span;
    copy(seg.settings, c.settings);
    out.segments.push_back(std::move(c));
  }
  for (const auto& p : sh.placed) {
    ir::Shaft::Placed c;
    c.kind = p.kind;
    c.name = p.name;
    c.at = p.at;
    c.stage = p.stage;
    c.gear = p.gear;
    c.notch = p.notch;
    c.span = p.span;
    copy(p.settings, c.settings);
    out.placed.push_back(std::move(c));
  }
  if (!why.empty()) return std::nullopt;
  return out;
}

} // namespace

std::optional<ShaftResult> computeShaft(const Evaluator& ev, int index, const Assignment& a, std::string* error, bool modes,
                                        const LoadSpread* spread) {
  const Model& model = ev.model();
  const ir::Shaft& written = model.gearbox.shafts[static_cast<size_t>(index)];
  auto fail = [&](const std::string& what) -> std::optional<ShaftResult> {
    if (error) *error = fmt::format("shaft `{}`: {}", written.name, what);
    return std::nullopt;
  };
  // Searched settings at the design's values.
  std::optional<ir::Shaft> decided;
  if (searchesSettings(written)) {
    std::string why;
    decided = atDesign(model, written, a, why);
    if (!decided) return fail(why);
  }
  const ir::Shaft& sh = decided ? *decided : written;
  ShaftResult out;
  shaft::Model& m = out.model;
  auto mat = materialOf(ev, sh);
  if (!mat) return fail("its material gives no Young's modulus, density, and shear modulus or Poisson's ratio");
  m.material = *mat;
  m.shear = choiceOf(sh.settings, Q::Shear, 0) == 0;
  for (const auto& seg : sh.segments)
    m.sections.push_back({seg.x0.toDouble(), seg.x1.toDouble(), given(seg.settings, Q::Diameter).value_or(0),
                          given(seg.settings, Q::Bore).value_or(0), given(seg.settings, Q::Roughness).value_or(0)});
  Ctx c{ev, a, error, spread};
  double speed = given(sh.settings, Q::Speed).value_or(0);
  bool coupled = false;
  std::vector<const ir::Shaft::Placed*> bearings;
  for (const auto& p : sh.placed) {
    double x = p.at.toDouble();
    switch (p.kind) {
    case Place::Gear: {
      std::string why;
      c.error = &why;
      double w = 0;
      if (!gearLoad(c, p, m, out, w)) return fail(why);
      if (speed == 0) speed = w;
      if (!coupled) m.torsionFixedAt = x;
      break;
    }
    case Place::Coupling:
      if (!coupled) m.torsionFixedAt = x;
      coupled = true;
      break;
    case Place::Load: {
      double radial = given(p.settings, Q::Radial).value_or(0), angle = given(p.settings, Q::Angle).value_or(0);
      m.loads.push_back({x, radial * std::cos(angle), radial * std::sin(angle), given(p.settings, Q::Axial).value_or(0),
                         0, 0, given(p.settings, Q::Torque).value_or(0)});
      break;
    }
    case Place::Disk: {
      double D = given(p.settings, Q::Diameter).value_or(0), t = given(p.settings, Q::Width).value_or(0),
             bore = given(p.settings, Q::Bore).value_or(0);
      double mass = m.material.density * kPi / 4 * (D * D - bore * bore) * t;
      m.disks.push_back(
          {x, mass, mass * (3 * (D * D + bore * bore) / 4 + t * t) / 12, mass * (D * D + bore * bore) / 8});
      break;
    }
    case Place::Notch: break; // rated once the shaft is solved
    case Place::Bearing:
      bearings.push_back(&p);
      out.bearings.push_back(p.name);
      m.bearings.push_back({p.name, x, given(p.settings, Q::RadialStiffness).value_or(shaft::kRigid),
                            choiceOf(p.settings, Q::Axial, 1) == 0});
      break;
    }
  }
  try {
    out.solution = shaft::solve(m);
    if (modes) {
      auto w = shaft::naturalFrequencies(m, 1);
      out.criticalSpeed = w.empty() ? 0 : w[0];
    }
  } catch (const std::invalid_argument& e) {
    return fail(e.what());
  }
  out.speed = speed;
  // A mesh's misalignment reads the deflections alone.
  if (spread) return out;
  largestDeflection(out);
  for (const auto& s : m.sections)
    out.mass += m.material.density * kPi / 4 * (s.diameter * s.diameter - s.bore * s.bore) * (s.x1 - s.x0);
  if (auto why = bearingLives(ev, sh, a, bearings, out); !why.empty()) return fail(why);
  if (!rateStrength(ev, sh, out, error)) return std::nullopt;
  if (speed > 0 && out.criticalSpeed > 0 && std::fabs(speed - out.criticalSpeed) < 0.2 * out.criticalSpeed)
    out.warnings.push_back(
        fmt::format("shaft `{}`: its speed {:.0f} rpm lies within 20 % of its first critical speed {:.0f} rpm", sh.name,
                    speed * 30 / kPi, out.criticalSpeed * 30 / kPi));
  return out;
}

namespace {

// Everything a shaft reads that a design can change: each of its gears' load and geometry,
// and its searched settings. Missing values count as themselves.
std::vector<double> inputsKey(const Evaluator& ev, int index, const Assignment& a, bool modes) {
  std::vector<double> k = {static_cast<double>(ev.model().serial), static_cast<double>(index), modes ? 1.0 : 0.0};
  Ctx c{ev, a, nullptr};
  for (const auto& p : ev.model().gearbox.shafts[static_cast<size_t>(index)].placed) {
    if (p.kind != Place::Gear) continue;
    const bool bevel = ev.model().info(p.stage).ir->kind == ir::StageKind::Bevel;
    static const std::pair<bool, Q> cylindrical[] = {{true, Q::Torque}, {true, Q::Speed}, {true, Q::Z}, {false, Q::NormalModule},
                                                     {false, Q::PressureAngle}, {false, Q::WorkingPressureAngle}, {false, Q::FaceWidth},
                                                     {false, Q::HelixAngle}};
    static const std::pair<bool, Q> conical[] = {{true, Q::Torque}, {true, Q::Speed}, {true, Q::Z}, {true, Q::MeanDiameter},
                                                 {true, Q::ConeAngle}, {false, Q::SpiralAngle}, {false, Q::ShaftAngle},
                                                 {false, Q::PressureAngle}, {false, Q::FaceWidth}};
    for (auto [own, key] : bevel ? std::span<const std::pair<bool, Q>>(conical) : std::span<const std::pair<bool, Q>>(cylindrical)) {
      int g = own ? p.gear : -1;
      k.push_back(c.stage(p.stage, g, key).value_or(-1.5e308));
    }
  }
  // Its searched settings: their choices and intervals.
  const Model& m = ev.model();
  for (int sl : m.shaftDomains[static_cast<size_t>(index)].slots)
    k.push_back(a.choice[static_cast<size_t>(sl)]);
  for (int f : m.shaftDomains[static_cast<size_t>(index)].freedoms)
    k.insert(k.end(), {a.box[static_cast<size_t>(f)].first, a.box[static_cast<size_t>(f)].second});
  return k;
}

} // namespace

// The line at a gear (`r.gear` its placement): deflection and slope at the face centre, the
// wind-up across the face at the reference circle.
Value gearLine(const Evaluator& ev, const ShaftResult& s, const ir::QuantityRef& r, const Assignment& a) {
  const auto& placed = ev.model().gearbox.shafts[static_cast<size_t>(r.index)].placed;
  if (r.gear < 0 || static_cast<size_t>(r.gear) >= placed.size()) return Value::invalid();
  const auto& p = placed[static_cast<size_t>(r.gear)];
  double x = p.at.toDouble();
  if (r.key == Q::DeflectionAt) return Value::number(s.solution.deflectionAt(x));
  if (r.key == Q::SlopeAt) return Value::number(s.solution.slopeAt(x));
  Ctx c{ev, a, nullptr};
  auto b = c.stage(p.stage, -1, Q::FaceWidth), d = c.stage(p.stage, p.gear, Q::D);
  if (!b || !d) return Value::invalid();
  return Value::number(std::fabs(s.solution.twistAt(x + *b / 2) - s.solution.twistAt(x - *b / 2)) * *d / 2);
}

Value shaftQuantity(const Evaluator& ev, const ir::QuantityRef& r, const Assignment& a) {
  if (r.index < 0 || static_cast<size_t>(r.index) >= ev.model().gearbox.shafts.size()) return Value::invalid();
  // The quantities of one design are read one after another (a rule on two bearings' lives,
  // a table's columns): the shaft is solved once for them.
  thread_local Recent<std::vector<double>, std::optional<ShaftResult>, 256> recent;
  bool modes = r.gear < 0 && r.key == Q::CriticalSpeed;
  auto key = inputsKey(ev, r.index, a, modes);
  const std::optional<ShaftResult>* hit = recent.find(key);
  if (!hit) hit = &recent.put(std::move(key), computeShaft(ev, r.index, a, nullptr, modes));
  const std::optional<ShaftResult>& s = *hit;
  if (!s) return Value::invalid();
  if (r.key == Q::DeflectionAt || r.key == Q::SlopeAt || r.key == Q::TorsionAt) return gearLine(ev, *s, r, a);
  if (r.gear <= -2) {
    // A notch's own safety: the rating at its position.
    const auto& placed = ev.model().gearbox.shafts[static_cast<size_t>(r.index)].placed;
    size_t k = static_cast<size_t>(-2 - r.gear);
    if (k >= placed.size()) return Value::invalid();
    double x = placed[k].at.toDouble();
    for (const auto& n : s->notches)
      if (n.x == x && n.kind == placed[k].name)
        return r.key == Q::FatigueSafety ? Value::number(n.result.SD) : Value::number(n.result.SF);
    return Value::invalid();
  }
  if (r.gear < 0) {
    switch (r.key) {
    case Q::Deflection: return Value::number(s->deflection);
    case Q::CriticalSpeed: return Value::number(s->criticalSpeed);
    case Q::Mass: return Value::number(s->mass);
    case Q::FatigueSafety: return s->notches.empty() ? Value::invalid() : Value::number(s->fatigueSafety);
    case Q::StaticSafety: return s->notches.empty() ? Value::invalid() : Value::number(s->staticSafety);
    default: return Value::invalid();
    }
  }
  size_t k = static_cast<size_t>(r.gear);
  if (k >= s->lives.size()) return Value::invalid();
  const auto& l = s->lives[k];
  switch (r.key) {
  case Q::Reaction: return Value::number(s->solution.reactions[k].radial());
  case Q::AxialReaction: return Value::number(std::fabs(s->solution.reactions[k].Fx));
  case Q::Life: return Value::number(l.L10h * 3600);
  case Q::ModifiedLife: return Value::number(l.Lnmh * 3600);
  case Q::StaticSafety: return Value::number(l.s0);
  default: return Value::invalid();
  }
}

} // namespace gbx::rt
