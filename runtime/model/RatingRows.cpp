#include "model/RatingRows.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/Recent.h"
#include "model/Standards.h"
#include "model/ToleranceEdges.h"
#include "rating/LoadSharing.h"
#include "rating/PlanetBearing.h"
#include "shaft/Iso281.h"

namespace gbx::rt::rating {

namespace {

using cat::gear::Pinion;
using cat::gear::Wheel;
using V = std::vector<double>;

constexpr double kAbsent = -1;  // an optional input left out (corner values must be numbers)

double num2(const KindContext& c, int gear, Q k, double dflt) {
  Value v = c.at(gear, k);
  return v.isNumber() ? v.mid() : dflt;
}

// A rated mesh of the stage: its driving and driven gear, and their mean stress factors
// (an idler's teeth are loaded on both flanks).
struct Mesh {
  int g0, g1;
  double YM0 = 1, YM1 = 1;
  bool internal = false;   // g1 is an internal gear (a ring)
  bool planetary = false;  // speeds relative to the carrier, load per planet
};

std::vector<Mesh> meshesOf(const KindContext& c) {
  using namespace cat::gear;
  switch (c.ev.model().info(c.stage).ir->kind) {
  case ir::StageKind::Spur:
  case ir::StageKind::Helical: return {{Pinion, Wheel}};
  case ir::StageKind::Idler: return {{Driver, Idler, 1.0, 0.7}, {Idler, Driven, 0.7, 1.0}};
  // The planets are loaded on both flanks (sun side, ring side).
  case ir::StageKind::Planetary: return {{Sun, Planet, 1.0, 0.7, false, true}, {Planet, Ring, 0.7, 1.0, true, true}};
  default: return {};
  }
}

// Spur and helical stages have a normal module; an idler train one plain module.
Q moduleKey(const KindContext& c) {
  auto k = c.ev.model().info(c.stage).ir->kind;
  return k == ir::StageKind::Idler || k == ir::StageKind::Planetary ? Q::Module : Q::NormalModule;
}

// K_gamma of a planetary stage when the spec gives none: by the number of planets, as
// IEC 61400-4 tabulates it (3: 1.10, 4: 1.25, 5: 1.35, 6: 1.44, 7: 1.47).
double planetaryMeshLoadFactor(double planets) {
  if (planets <= 2) return 1.0;
  if (planets <= 3) return 1.10;
  if (planets <= 4) return 1.25;
  if (planets <= 5) return 1.35;
  if (planets <= 6) return 1.44;
  return 1.47;
}

// The inputs that vary with the design, as values that may span a freedom's interval.
enum In { Z1, Z2, X1, X2, Mn, AlphaN, Beta, B, A, T1, N1, N2, Fpb1, Fpb2, Ffa1, Ffa2, Fhb1, Fhb2, Ca, Da1, Da2, B1, B2, Count };

// What the stage's `modify` block does to the mesh: the tip relief C_a and the lead
// factors B1, B2 of F_betax (ISO 6336-1 Table 8: crowning 0.5/0.5, helix correction
// 0.1/1, both 0.1/0.5, end relief 0.7/0.7).
struct Lead {
  Value tipRelief = Value::number(kAbsent);
  double B1 = 1, B2 = 1;
};

Lead lead(const KindContext& c) {
  Lead out;
  bool crowned = false, corrected = false, endRelieved = false;
  for (const auto& md : c.ev.model().gearbox.modifies) {
    if (md.stageIndex != c.stage) continue;
    for (const auto& r : md.rules) {
      if (!r.value) continue;
      if (r.when) {
        Value w = c.ev.eval(*r.when, c.a);
        if (w.kind != Value::Bool || w.truth != Truth::True) continue;
      }
      Value v = c.ev.eval(*r.value, c.a);
      if (!v.isNumber() || v.hi <= 0) continue;
      switch (static_cast<cat::Mod>(r.modTarget)) {
      case cat::Mod::TipRelief:
        // Both gears relieved alike, or the larger of the two.
        if (!out.tipRelief.isNumber() || out.tipRelief.lo == kAbsent || v.lo > out.tipRelief.lo) out.tipRelief = v;
        break;
      case cat::Mod::LeadCrowning: crowned = true; break;
      case cat::Mod::HelixSlope: corrected = true; break;
      case cat::Mod::EndRelief: endRelieved = true; break;
      default: break;
      }
    }
  }
  if (corrected) {
    out.B1 = 0.1;
    out.B2 = crowned ? 0.5 : 1.0;
  } else if (crowned) {
    out.B1 = out.B2 = 0.5;
  } else if (endRelieved) {
    out.B1 = out.B2 = 0.7;
  }
  return out;
}

} // namespace

Value givenOnly(const KindContext& c, int gear, Q k) {
  const auto& en = c.ev.model().info(c.stage).entry(gear, k);
  if (!en.attr && en.slot < 0 && en.freedom < 0 && !c.ev.overrides(c.stage, gear, k)) return Value::invalid();
  return c.at(gear, k);
}

std::optional<std::array<GearMaterial, 2>> materialsOf(const KindContext& c, int g0, int g1, std::string* why) {
  auto fail = [&](std::string s) -> std::optional<std::array<GearMaterial, 2>> {
    if (why) *why = std::move(s);
    return std::nullopt;
  };
  const Model& m = c.ev.model();
  std::array<GearMaterial, 2> out{};
  // Each gear's material: its own (`pinion.material`), else the stage's.
  for (int slot = 0; slot < 2; ++slot) {
    const ir::Material* mat = m.material(c.stage, slot == 0 ? g0 : g1);
    if (!mat) return fail("the stage names no material");
    auto prop = [&](Q k) -> const ir::Setting* { return ir::findSetting(mat->properties, k); };
    for (Q k : {Q::SigmaHlim, Q::SigmaFlim, Q::YoungsModulus, Q::Poisson, Q::Density})
      if (!prop(k) || !prop(k)->value) return fail("material `" + mat->name + "` does not give " + std::string(cat::keyName(k)));
    const ir::Setting* t = prop(Q::Treatment);
    if (!t || t->choice < 0) return fail("material `" + mat->name + "` does not give its treatment");
    GearMaterial& g = out[static_cast<size_t>(slot)];
    g.treatment = t->choice == cat::treatment::Nitrided          ? Treatment::Nitrided
                  : t->choice == cat::treatment::ThroughHardened ? Treatment::ThroughHardened
                                                                 : Treatment::CaseHardened;
    g.sigmaHlim = prop(Q::SigmaHlim)->value->toDouble();
    g.sigmaFlim = prop(Q::SigmaFlim)->value->toDouble();
    g.E = prop(Q::YoungsModulus)->value->toDouble();
    g.nu = prop(Q::Poisson)->value->toDouble();
    g.density = prop(Q::Density)->value->toDouble();
    if (const ir::Setting* hb = prop(Q::BrinellHardness); hb && hb->value) g.brinell = hb->value->toDouble();
  }
  return out;
}

namespace {

// The inputs that do not vary with the design; nullopt when one the rating needs is missing.
std::optional<PairInput> fixedInputs(const KindContext& c, const Mesh& mesh, std::string* why) {
  auto fail = [&](std::string s) -> std::optional<PairInput> {
    if (why) *why = std::move(s);
    return std::nullopt;
  };
  const Model& m = c.ev.model();
  PairInput in;
  auto mats = materialsOf(c, mesh.g0, mesh.g1, why);
  if (!mats) return std::nullopt;
  applyMaterials(in, *mats);
  auto num = [&](Q k, double dflt) {
    Value v = c.at(k);
    return v.isNumber() ? v.mid() : dflt;
  };
  in.life = num(Q::RatingLife, kNaN);
  in.nu40 = num(Q::RatingViscosity40, kNaN);
  if (!std::isfinite(in.life)) return fail("its rating gives no `life`");
  if (!std::isfinite(in.nu40)) return fail("its rating gives no `lubricant.viscosity_40`");
  // Rz = 6 Ra unless Rz is given (docs/rating.md).
  in.RzFlank = num(Q::RatingRoughnessFlankRz, 6 * num(Q::RatingRoughnessFlank, kNaN));
  in.RzRoot = num(Q::RatingRoughnessRootRz, 6 * num(Q::RatingRoughnessRoot, kNaN));
  if (!std::isfinite(in.RzFlank) || !std::isfinite(in.RzRoot)) return fail("its rating gives no flank or root roughness");
  in.KA = num(Q::RatingApplicationFactor, 1.0);
  in.Kgamma = num(Q::RatingMeshLoadFactor, 1.0);
  in.haP = num(Q::RatingRackAddendum, 1.0);
  in.hfP = num(Q::RatingRackDedendum, 1.25);
  in.rhoFP = num(Q::RatingRackRootRadius, 0.38);
  in.KHbetaGiven = num(Q::RatingFaceLoadFactor, kNaN);
  in.KvGiven = num(Q::RatingDynamicFactor, kNaN);
  in.KHalphaGiven = num(Q::RatingTransverseLoadFactor, kNaN);
  Value cg = givenOnly(c, -1, Q::MeshStiffness);
  in.cgammaGiven = cg.isNumber() ? cg.mid() : kNaN;
  in.fma = num(Q::RatingMeshMisalignment, kNaN);
  in.SHmin = num(Q::RatingMinContact, 1.0);
  in.aAllowance = num(Q::CenterDistanceAllowance, 0.0);
  in.SFmin = num(Q::RatingMinBending, 1.0);
  // The oil of scuffing and micropitting (sema has checked that its line and temperature
  // come with a load stage).
  int fzg = static_cast<int>(num(Q::RatingFzgLoadStage, 0)), fva = static_cast<int>(num(Q::RatingMicropittingLoadStage, 0));

  if (fzg > 0 || fva > 0) {
    Lubricant oil;
    oil.nu40 = in.nu40;
    oil.nu100 = num(Q::RatingViscosity100, kNaN);
    oil.density15 = num(Q::RatingOilDensity, 890);
    oil.oilTemperature = num(Q::RatingOilTemperature, kNaN);
    oil.fzgStage = fzg;
    oil.fvaStage = fva;
    const ir::Attribute* base = m.attribute(c.stage, Q::RatingOilBase);
    if (base && base->choice >= 0) oil.base = static_cast<OilBase>(base->choice);
    const ir::Attribute* supply = m.attribute(c.stage, Q::RatingOilSupply);
    oil.injection = supply && supply->choice == cat::oilSupply::Injection;
    if (!std::isfinite(oil.nu100) || !std::isfinite(oil.oilTemperature))
      return fail("its lubricant gives a load stage but not `viscosity_100` and `oil_temperature`");
    in.oil = oil;
    in.RaFlank = num(Q::RatingRoughnessFlank, in.RzFlank / 6);
    in.SBmin = num(Q::RatingMinScuffing, 1.5);
    in.SintSmin = num(Q::RatingMinIntegralScuffing, 1.8);
    in.SLmin = num(Q::RatingMinMicropitting, 1.0);
  }
  const ir::Attribute* curve = m.attribute(c.stage, Q::RatingLifeCurve);
  in.optimumLife = curve && curve->choice == cat::lifeCurve::Optimum;
  Value grade = c.at(Q::Accuracy);
  in.grade = grade.isPoint() && grade.lo == std::round(grade.lo) ? static_cast<int>(grade.lo) : 0;
  if (mesh.planetary) {
    double planets = c.at(Q::Planets).mid();
    in.Kgamma = num(Q::RatingMeshLoadFactor, planetaryMeshLoadFactor(planets));
    // The sun meets every planet, the ring every planet, per turn relative to the carrier.
    in.gear[0].cyclesPerRev = mesh.internal ? 1 : planets;
    in.gear[1].cyclesPerRev = mesh.internal ? planets : 1;
    in.planets = mesh.internal ? 0 : static_cast<int>(planets);
    in.gear[1].internal = mesh.internal;
    if (mesh.internal) in.KvGiven = num(Q::RatingRingPlanetDynamicFactor, in.KvGiven);
  }
  for (int slot = 0; slot < 2; ++slot) {
    GearInput& gi = in.gear[static_cast<size_t>(slot)];
    int g = slot == 0 ? mesh.g0 : mesh.g1;
    gi.YM = slot == 0 ? mesh.YM0 : mesh.YM1;
    gi.bore = num2(c, g, Q::BoreDiameter, 0.0);
    gi.upperAllowance = num2(c, g, Q::UpperThicknessAllowance, kNaN);
    gi.lowerAllowance = num2(c, g, Q::LowerThicknessAllowance, kNaN);
    double bs = num2(c, g, Q::WebThickness, kNaN), sr = num2(c, g, Q::RimThickness, kNaN);
    double b = c.at(Q::FaceWidth).mid(), mn = c.at(moduleKey(c)).mid();
    // C_R of a webbed blank, ISO 6336-1 eq. (clause 9.3.4): 1 + ln(b_s/b) / (5 e^(s_R/(5 m_n))).
    // b_s/b outside 0.2..1.2 takes the nearer limit; a web as wide as the face is solid.
    if (std::isfinite(bs) && std::isfinite(sr) && bs / b < 1.2)
      gi.webFactor = 1 + std::log(std::max(bs / b, 0.2)) / (5 * std::exp(sr / (5 * mn)));
    gi.RzFlank = num2(c, g, Q::GearFlankRz, kNaN);
    gi.RzRoot = num2(c, g, Q::GearRootRz, kNaN);
    if (mesh.internal && slot == 1) {
      // The ring: its root from its pinion-type cutter, Y_B from its rim.
      gi.cutterTeeth = num2(c, g, Q::CutterTeeth, 0.0);
      gi.cutterShift = num2(c, g, Q::CutterShift, 0.0);
      gi.cutterTipRadius = num2(c, g, Q::CutterTipRadius, kNaN);
      gi.rimThickness = sr;
    }
  }
  return in;
}


// The varying inputs at the design, in `In` order.
std::optional<std::vector<Value>> varyingInputs(const KindContext& c, const PairInput& fixed, const Mesh& mesh, std::string* why) {
  std::vector<Value> x(In::Count);
  const int p = mesh.g0, w = mesh.g1;
  auto kind = c.ev.model().info(c.stage).ir->kind;
  bool cylindrical = kind == ir::StageKind::Spur || kind == ir::StageKind::Helical;
  x[Z1] = c.at(p, Q::Z);
  x[Z2] = c.at(w, Q::Z);
  x[X1] = c.orZero(p, Q::Shift);
  x[X2] = c.orZero(w, Q::Shift);
  x[Mn] = c.at(moduleKey(c));
  x[AlphaN] = c.at(Q::PressureAngle);
  x[Beta] = c.ev.model().info(c.stage).ir->kind == ir::StageKind::Helical ? c.at(Q::HelixAngle) : Value::number(0.0);
  x[B] = c.at(Q::FaceWidth);
  // Given, or from the shifts inside the rating (an interval of its own would pair
  // corners of the centre distance with shifts that cannot produce it). An idler train's
  // centre distance is the driver's to the driven gear's: each mesh's comes from its shifts.
  Value a = cylindrical ? givenOnly(c, -1, Q::CenterDistance) : Value::invalid();
  x[A] = a.isNumber() ? a : Value::number(kAbsent);
  x[T1] = c.derived(p, Q::Torque);
  x[N1] = c.derived(p, Q::Speed);
  x[N2] = c.derived(w, Q::Speed);
  if (mesh.planetary) {
    // Relative to the carrier: the sun at n_s - n_c, a planet at that times z_s / z_p, the
    // ring at n_c; each planet mesh carries T_sun / planets.
    using namespace cat::gear;
    Value carrier = c.derived(Q::CarrierSpeed);
    Value sun = arith::sub(c.derived(Sun, Q::Speed), carrier);
    Value planet = arith::mul(sun, arith::div(c.at(Sun, Q::Z), c.at(Planet, Q::Z)));
    x[T1] = mesh.internal ? c.derived(Planet, Q::Torque) : arith::div(c.derived(Sun, Q::Torque), c.at(Q::Planets));
    x[N1] = mesh.internal ? planet : sun;
    x[N2] = mesh.internal ? carrier : planet;
  }
  auto opt = [&](int g, Q k) {
    Value v = givenOnly(c, g, k);
    return v.isNumber() ? v : Value::number(kAbsent);
  };
  x[Fpb1] = opt(p, Q::PitchDeviation);
  x[Fpb2] = opt(w, Q::PitchDeviation);
  // f_falpha: given as such, else the spec's total profile deviation (the loaded mesh's
  // profile deviation too), else the grade's.
  auto profile = [&](int g) {
    Value v = opt(g, Q::ProfileFormDeviation);
    return v.lo != kAbsent ? v : opt(g, Q::ProfileDeviation);
  };
  x[Ffa1] = profile(p);
  x[Ffa2] = profile(w);
  x[Fhb1] = opt(p, Q::HelixSlopeDeviation);
  x[Fhb2] = opt(w, Q::HelixSlopeDeviation);
  x[Da1] = opt(p, Q::TipDiameter);
  x[Da2] = opt(w, Q::TipDiameter);
  Lead l = lead(c);
  x[Ca] = l.tipRelief;
  x[B1] = Value::number(l.B1);
  x[B2] = Value::number(l.B2);
  for (int i : {Z1, Z2, Mn, AlphaN, B, T1, N1, N2})
    if (!x[static_cast<size_t>(i)].isNumber()) {
      if (why) *why = "its geometry or load is not known at this design";
      return std::nullopt;
    }
  bool deviations = true;
  for (int i : {Fpb1, Fpb2, Ffa1, Ffa2, Fhb1, Fhb2}) deviations = deviations && x[static_cast<size_t>(i)].lo != kAbsent;
  if (!deviations && fixed.grade <= 0) {
    if (why) *why = "it gives neither an `accuracy` grade nor every gear's deviations";
    return std::nullopt;
  }
  return x;
}

// The inputs at one corner of the varying inputs.
PairInput inputAt(PairInput in, const V& x) {
  in.gear[0].z = x[Z1];
  in.gear[1].z = x[Z2];
  in.gear[0].x = x[X1];
  in.gear[1].x = x[X2];
  in.mn = x[Mn];
  in.alphaN = x[AlphaN];
  in.beta = x[Beta];
  in.b = x[B];
  in.a = x[A] == kAbsent ? kNaN : x[A];
  in.torque1 = std::fabs(x[T1]);
  in.gear[0].speed = std::fabs(x[N1]);
  in.gear[1].speed = std::fabs(x[N2]);
  in.tipRelief = x[Ca] == kAbsent ? kNaN : x[Ca];
  in.B1 = x[B1];
  in.B2 = x[B2];
  for (int g = 0; g < 2; ++g) {
    GearInput& gi = in.gear[static_cast<size_t>(g)];
    double d = gi.z * in.mn / std::cos(in.beta);
    auto pick = [&](int idx, double tab) { return x[static_cast<size_t>(idx + g)] == kAbsent ? tab : x[static_cast<size_t>(idx + g)]; };
    int q = in.grade;
    // The base pitch deviation from the grade's single pitch tolerance: f_pb = f_pt cos(alpha_t).
    double alphaT = std::atan(std::tan(in.alphaN) / std::cos(in.beta));
    gi.fpb = pick(Fpb1, q > 0 ? iso::tabulatedSinglePitch(q, in.mn, d) * std::cos(alphaT) : 0);
    gi.ffa = pick(Ffa1, q > 0 ? iso::tabulatedProfileForm(q, in.mn, d) : 0);
    gi.fHb = pick(Fhb1, q > 0 ? iso::tabulatedHelixSlope(q, d, in.b) : 0);
    gi.tipDiameter = x[static_cast<size_t>(Da1 + g)] == kAbsent ? kNaN : x[static_cast<size_t>(Da1 + g)];
  }
  return in;
}

enum class Side { Contact, Bending, Any };

// Over a stage's meshes: the rating of the mesh that governs the asked gear's side (a gear
// in two meshes, the idler, is as safe as its weaker one), or the stage's governing mesh.
int governing(const std::vector<PairRating>& r, const std::vector<Mesh>& meshes, int gear, Side side, double minH, double minF) {
  int best = -1;
  double worst = 1e300;
  for (size_t k = 0; k < r.size(); ++k)
    for (int slot = 0; slot < 2; ++slot) {
      int g = slot == 0 ? meshes[k].g0 : meshes[k].g1;
      if (gear >= 0 && g != gear) continue;
      const GearRating& o = r[k].gear[static_cast<size_t>(slot)];
      double v = side == Side::Contact ? o.SH / minH : side == Side::Bending ? o.SF / minF : std::min(o.SH / minH, o.SF / minF);
      if (v < worst) {
        worst = v;
        best = static_cast<int>(k);
      }
    }
  return best;
}

// `mesh_load_factor = load_sharing`: the first planet's pin error and the sun's support.
struct Sharing {
  double pinError = 0;
  bool floatingSun = false;
};

struct Rated {
  std::vector<SpectrumBin> bins;  // the stage's load spectrum, empty without one
  std::optional<Sharing> sharing;
  std::vector<Mesh> meshes;
  std::vector<PairInput> fixed;  // per mesh
  std::vector<std::vector<Value>> varying;
  std::optional<FaceLoad> faceLoad;
  std::optional<SceneFactor> kv;
};

std::optional<Rated> gather(const KindContext& c, std::string* why) {
  // A `modify` rule that reads a rating quantity would rate the stage inside its own
  // rating; sema refuses it, and this guard keeps any other path from recursing.
  thread_local int active = 0;
  if (active > 0) {
    if (why) *why = "the stage's modification reads its own rating";
    return std::nullopt;
  }
  struct Guard {
    int& n;
    explicit Guard(int& x) : n(x) { ++n; }
    ~Guard() { --n; }
  } guard(active);
  Rated r;
  // Every mesh of the stage (a planet's, an idler's) takes its own share of the bins.
  auto bins = spectrumBins(c, why);
  if (!bins) return std::nullopt;
  r.bins = std::move(*bins);
  r.meshes = meshesOf(c);
  if (r.meshes.empty()) {
    if (why) *why = "this stage kind has no ISO 6336 rating";
    return std::nullopt;
  }
  const Model& m = c.ev.model();
  if (const ir::Attribute* kg = m.attribute(c.stage, Q::RatingMeshLoadFactor);
      kg && kg->choice == cat::meshLoad::LoadSharing) {
    const ir::Attribute* support = m.attribute(c.stage, Q::SunSupport);
    r.sharing =
        Sharing{num2(c, cat::gear::Planet, Q::PinError, 0.0), support && support->choice == cat::sunSupport::Floating};
  }
  for (const auto& mesh : r.meshes) {
    auto fixed = fixedInputs(c, mesh, why);
    if (!fixed) return std::nullopt;
    auto x = varyingInputs(c, *fixed, mesh, why);
    if (!x) return std::nullopt;
    r.fixed.push_back(*fixed);
    r.varying.push_back(std::move(*x));
  }
  return r;
}

// Under a load spectrum the safeties are the spectrum's (ISO 6336-6); `damage` asks for the
// Miner sums too, of the operating torque alone where there is no spectrum.
void underSpectrum(const Rated& g, const PairInput& in, PairRating& r, bool damage) {
  if (g.bins.empty() && !damage) return;
  std::vector<SpectrumBin> one(1);
  one[0].torqueShare = one[0].lifeShare = 1;
  SpectrumRating sp = rateSpectrum(in, g.bins.empty() ? one : g.bins);
  for (size_t k = 0; k < 2; ++k) {
    GearRating& o = r.gear[k];
    o.contactDamage = sp.contact[k].damage;
    o.bendingDamage = sp.bending[k].damage;
    if (g.bins.empty()) continue;
    o.SHoperating = o.SH;
    o.SFoperating = o.SF;
    o.SH = sp.contact[k].safety;
    if (std::isfinite(o.SF)) o.SF = sp.bending[k].safety;
  }
}

// Each mesh's rating at one corner of the concatenated varying inputs; `scuffing` adds the
// scuffing and micropitting ratings where the oil's load stages are given.
std::vector<PairRating> rateMeshes(const Rated& g, const V& x, bool damage, bool scuffing, double Kgamma);

// K_gamma from the planets' load sharing (rating/LoadSharing.h): each planet's path the sun
// and ring meshes' c_gamma_alpha b in series, at the rated load.
double sharedLoadFactor(const Rated& g, const std::vector<PairRating>& r) {
  LoadSharingInput in;
  in.planets = g.fixed[0].planets;
  in.kSun = r[0].cgammaAlpha * 1e9 * r[0].b;
  in.kRing = r[1].cgammaAlpha * 1e9 * r[1].b;
  in.alphaSun = r[0].alphaWt;
  in.alphaRing = r[1].alphaWt;
  in.pinError = {g.sharing->pinError};
  in.floatingSun = g.sharing->floatingSun;
  in.force = r[0].Fbt * in.planets; // along the lines of action, as c_gamma deflects them
  return shareLoad(in).Kgamma;
}

// Each mesh's rating at one corner of the concatenated varying inputs; `scuffing` adds the
// scuffing and micropitting ratings where the oil's load stages are given. With the planets'
// load sharing the meshes are rated twice: first for their stiffness (c_gamma does not
// depend on K_gamma), then at the K_gamma the sharing gives.
std::vector<PairRating> rateAll(const Rated& g, const V& x, bool damage = false, bool scuffing = false) {
  if (!g.sharing) return rateMeshes(g, x, damage, scuffing, kNaN);
  return rateMeshes(g, x, damage, scuffing, sharedLoadFactor(g, rateMeshes(g, x, false, false, 1.0)));
}

// The meshes rated; `Kgamma` replaces the inputs' unless NaN.
std::vector<PairRating> rateMeshes(const Rated& g, const V& x, bool damage, bool scuffing, double Kgamma) {
  std::vector<PairRating> out;
  for (size_t k = 0; k < g.meshes.size(); ++k) {
    auto at = x.begin() + static_cast<long>(k * In::Count);
    V xk(at, at + In::Count);
    // A planet is one gear: in the ring mesh it keeps the tip diameter of the sun mesh
    // (whose tip alteration shortened it), unless the spec gives it.
    if (g.meshes[k].planetary && g.meshes[k].internal && xk[Da1] == kAbsent && !out.empty()) xk[Da1] = out[0].gear[1].tipDiameter;
    PairInput in = inputAt(g.fixed[k], xk);
    if (std::isfinite(Kgamma)) in.Kgamma = Kgamma;
    out.push_back(rate(in));
    underSpectrum(g, in, out.back(), damage);
    // An internal mesh's scuffing and micropitting are for information: not the design's.
    if (scuffing && !g.meshes[k].internal) out.back().scuffing = scuffingOf(in, out.back());
  }
  return out;
}

// K_v from a scene and K_Hbeta from a contact analysis, where the stage asks for them: both
// are computed once at the design (the middle of any freedom's interval) and then enter
// every corner as given factors. A design whose tooth counts are not all chosen has neither.
bool modelFactors(const KindContext& c, Rated& g, std::string* why, bool estimate) {
  const Model& m = c.ev.model();
  const ir::Attribute* kv = m.attribute(c.stage, Q::RatingDynamicFactor);
  const ir::Attribute* kh = m.attribute(c.stage, Q::RatingFaceLoadFactor);
  bool byScene = kv && kv->sceneRef, byContact = kh && kh->choice == cat::faceLoad::ContactAnalysis;
  if (!byScene && !byContact) return true;
  auto fail = [&](std::string s) {
    if (why) *why = std::move(s);
    return false;
  };
  // A scene may be the whole gearbox's, and a stage on shafts reads the others' loads: they
  // need every tooth count; a self-contained stage's contact analysis needs its own.
  const StageInfo& info = m.info(c.stage);
  bool whole = byScene || !info.selfContained;
  bool unchosen = whole ? std::any_of(c.a.choice.begin(), c.a.choice.end(), [](int x) { return x < 0; })
                        : std::any_of(info.slots.begin(), info.slots.end(),
                                      [&](int sl) { return c.a.choice[static_cast<size_t>(sl)] < 0; });
  if (unchosen)
    return fail(whole ? "its K_v or K_Hbeta comes from a model of the whole design, whose tooth counts are not all chosen"
                      : "its K_Hbeta comes from a contact analysis of the stage, whose tooth counts are not all chosen");
  V mid;
  for (const auto& v : g.varying)
    for (const auto& x : v) mid.push_back(x.mid());
  if (byScene) {
    g.kv = sceneDynamicFactor(c.ev, c.a, kv->scene, estimate);
    if (!g.kv->failure.empty()) return fail(fmt::format("K_v by method A: {}", g.kv->failure));
    for (auto& f : g.fixed) f.KvGiven = g.kv->Kv;
  }
  if (byContact) {
    PairRating r;
    try {
      r = rateAll(g, mid)[0];
    } catch (const std::domain_error& e) {
      return fail(e.what());
    }
    const PairInput& in = g.fixed[0];
    double load = r.Ft * in.KA * r.Kgamma * r.Kv;
    g.faceLoad = contactAnalysis(c.ev, c.a, c.stage, load, r.fma, in.KA * r.Kgamma * r.Kv);
    if (!g.faceLoad->failure.empty()) return fail(fmt::format("K_Hbeta by contact analysis: {}", g.faceLoad->failure));
    for (auto& f : g.fixed) f.KHbetaGiven = g.faceLoad->KHbeta;
  }
  return true;
}

// `Scuffing`: a scuffing or micropitting quantity of the stage, the worst over its meshes
// rated for it (the smallest of a safety or film thickness, the largest of a temperature).
enum class Worst { Governing, Smallest, Largest };

// A stage's ratings at every corner of its inputs, as every rating quantity of that design
// reads them: a design's four safeties, its stresses and factors are rated once, not once
// each, and the search's check of a rule over a box rates its corners once for all its rules.
struct RatedCorners {
  std::optional<Rated> g;
  std::vector<std::vector<PairRating>> corners; // one per corner (one: every input a point); none without a value
  std::vector<bool> failed;                     // per corner: the rating refused its geometry
};

// The parts of a rating's key: the model, the stage and what is asked; the evaluator's
// deviations and overrides. No NaN in a key: it compares equal to everything in a map.
std::vector<double> keyHead(const KindContext& c, bool damage, bool scuffing) {
  return {static_cast<double>(c.ev.model().serial), static_cast<double>(c.stage), damage ? 1.0 : 0.0, scuffing ? 1.0 : 0.0,
          c.ev.nominalOnly ? 1.0 : 0.0};
}

std::vector<double> keyTail(std::vector<double> k, const Evaluator& ev) {
  auto offsets = ev.offsetKey(), overrides = ev.overrideKey();
  k.push_back(static_cast<double>(offsets.size()));
  k.insert(k.end(), offsets.begin(), offsets.end());
  k.insert(k.end(), overrides.begin(), overrides.end());
  for (double& x : k)
    if (std::isnan(x)) x = -1.5e308;
  return k;
}

// The whole assignment: cheap to build, and the same for every quantity of one design.
std::vector<double> wholeKey(const KindContext& c, bool damage, bool scuffing) {
  std::vector<double> k = keyHead(c, damage, scuffing);
  k.insert(k.end(), {c.a.ratioApprox ? 1.0 : 0.0, c.a.ratioApprox.value_or(0), c.a.ratio ? 1.0 : 0.0,
                     c.a.ratio ? c.a.ratio->toDouble() : 0, static_cast<double>(c.a.upstreamStage), c.a.upstreamRatio});
  for (int x : c.a.choice) k.push_back(x);
  for (const auto& [lo, hi] : c.a.box) k.insert(k.end(), {lo, hi});
  return keyTail(std::move(k), c.ev);
}

// The key of everything a stage's rating reads: where the stage is self-contained its own
// choices and freedoms and its operating point (the same for every design upstream that
// gives the same ratio), else the whole assignment (`whole`).
std::vector<double> ratedKey(const KindContext& c, bool damage, bool scuffing, const std::vector<double>& whole) {
  const StageInfo& info = c.ev.model().info(c.stage);
  if (!info.selfContained) return whole;
  std::vector<double> k = keyHead(c, damage, scuffing);
  auto push = [&](const Value& v) { k.insert(k.end(), {static_cast<double>(v.kind), v.lo, v.hi}); };
  for (int sl : info.slots) k.push_back(c.a.choice[static_cast<size_t>(sl)]);
  for (int f : info.freedoms) k.insert(k.end(), {c.a.box[static_cast<size_t>(f)].first, c.a.box[static_cast<size_t>(f)].second});
  push(c.upstreamRatio());
  push(c.gearbox(Q::InputSpeed));
  push(c.gearbox(Q::InputTorque));
  return keyTail(std::move(k), c.ev);
}

// The varying inputs with an interval of face width cut where ISO 1328's face-width ranges
// make the tabulated helix slope deviation jump (K_Hbeta rises at b = 80 mm, say): within
// each piece the rating is monotone in the face width, so the corners of the pieces bound it
// where the corners of the whole interval would miss a feasible stretch below a bound.
std::vector<std::vector<Value>> faceWidthPieces(const std::vector<Value>& all) {
  std::vector<std::vector<Value>> out{all};
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = B; k < all.size(); k += In::Count)
    if (all[k].isNumber() && all[k].lo < all[k].hi) {
      lo = std::min(lo, all[k].lo);
      hi = std::max(hi, all[k].hi);
    }
  if (!(lo < hi)) return out;
  std::vector<double> edges;
  for (double e : iso::faceWidthRanges()) edges.push_back(e * 1e-3);
  const auto cuts = cutAt(lo, hi, edges);
  if (cuts.size() == 1) return out;
  out.clear();
  for (const auto& [from, to] : cuts) {
    std::vector<Value> piece = all;
    for (size_t k = B; k < piece.size(); k += In::Count)
      if (piece[k].isNumber() && piece[k].lo < piece[k].hi)
        piece[k] = Value::range(std::max(piece[k].lo, from), std::min(piece[k].hi, to));
    out.push_back(std::move(piece));
  }
  return out;
}

// The stage's ratings at the corners of its inputs (monotone in each: their image's bounds),
// from the thread's recent ones when the same stage was rated just before.
const RatedCorners& ratedCorners(const KindContext& c, bool damage, bool scuffing) {
  // Room for a search's ratings of one stage over the upstream ratios it meets; a narrowed
  // two-stage reducer peaks at 20 MiB with it (164 MiB with room for 32 768).
  thread_local Recent<std::vector<double>, RatedCorners, 2048> recent;
  // The quantities of one design are read one after another: the last design's result is
  // found without building the key of the operating point.
  thread_local struct {
    std::vector<double> whole;
    const RatedCorners* hit = nullptr;
  } last;
  std::vector<double> whole = wholeKey(c, damage, scuffing);
  if (last.hit && whole == last.whole) return *last.hit;
  auto key = ratedKey(c, damage, scuffing, whole);
  if (const RatedCorners* hit = recent.find(key)) {
    last = {std::move(whole), hit};
    return *hit;
  }
  RatedCorners p;
  p.g = gather(c, nullptr);
  if (p.g && !modelFactors(c, *p.g, nullptr, false)) p.g.reset();
  if (p.g) {
    std::vector<Value> all;
    for (const auto& v : p.g->varying) all.insert(all.end(), v.begin(), v.end());
    for (const auto& piece : faceWidthPieces(all))
      arith::corners(piece, [&](const V& x) {
        p.corners.emplace_back();
        p.failed.push_back(false);
        try {
          p.corners.back() = rateAll(*p.g, x, damage, scuffing);
        } catch (const std::domain_error&) {
          p.failed.back() = true;
        }
        return 0.0;
      });
  }
  // A full cache starts again: the last result stays valid only until the next one is put.
  const RatedCorners& out = recent.put(std::move(key), std::move(p));
  last = {std::move(whole), &out};
  return out;
}

// A quantity of the stage's meshes at each rated corner: no value where any corner has none
// (as arith::corners); an enclosure over a box.
template <class F> Value overCorners(const RatedCorners& p, F pick) {
  if (!p.g || p.corners.empty()) return Value::invalid();
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = 0; k < p.corners.size(); ++k) {
    double v = p.failed[k] ? kNaN : pick(p.corners[k]);
    if (!std::isfinite(v)) return Value::invalid();
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (p.corners.size() == 1) return Value::number(lo); // every input a point
  return Value::range(std::nextafter(lo, -INFINITY), std::nextafter(hi, INFINITY));
}

Value rated(const KindContext& c, int gear, Side side, double (*select)(const PairRating&, int slot), bool damage = false,
            Worst worst = Worst::Governing) {
  bool scuffing = worst != Worst::Governing;
  const RatedCorners& p = ratedCorners(c, damage, scuffing);
  if (!p.g || p.corners.empty()) return Value::invalid();
  const Rated& g = *p.g;
  double minH = g.fixed[0].SHmin, minF = g.fixed[0].SFmin;
  auto pick = [&](const std::vector<PairRating>& r) {
    if (scuffing) {
      double out = kNaN;
      for (const auto& m : r) {
        double x = m.scuffing ? select(m, 0) : kNaN;
        if (std::isnan(x)) continue;
        if (std::isnan(out) || (worst == Worst::Smallest ? x < out : x > out)) out = x;
      }
      return out;
    }
    int k = governing(r, g.meshes, gear, side, minH, minF);
    if (k < 0) return kNaN;
    int slot = gear < 0 ? 0 : g.meshes[static_cast<size_t>(k)].g0 == gear ? 0 : 1;
    return select(r[static_cast<size_t>(k)], slot);
  };
  return overCorners(p, pick);
}

template <double PairRating::*M>
DerivedRow stageRow(Q key) {
  return {key, false, [](const KindContext& c, int g) { return rated(c, g, Side::Any, [](const PairRating& r, int) { return r.*M; }); }};
}
// A scuffing or micropitting quantity of the stage: the worst of its meshes' (NaN where no
// mesh is rated for it), by the quantity's direction (docs/language.md).
template <double ScuffingRating::*M, Q K>
DerivedRow scuffingRow() {
  return {K, false, [](const KindContext& c, int g) {
            return rated(
                c, g, Side::Any, [](const PairRating& r, int) { return r.scuffing ? r.scuffing.value().*M : kNaN; }, false,
                cat::betterOf(K) == cat::Better::Smaller ? Worst::Largest : Worst::Smallest);
          }};
}

template <double GearRating::*M, Side S, bool Damage = false>
DerivedRow gearRow(Q key) {
  return {key, true, [](const KindContext& c, int g) {
            return rated(c, g, S, [](const PairRating& r, int slot) { return r.gear[static_cast<size_t>(slot)].*M; }, Damage);
          }};
}

// A planetary stage's two meshes at each rated corner (none where the stage has other meshes).
const RatedCorners& planetMeshes(const KindContext& c) {
  static const RatedCorners none;
  const RatedCorners& p = ratedCorners(c, false, false);
  return p.g && p.g->meshes.size() == 2 && p.g->meshes[1].internal ? p : none;
}

// Each planet bearing's radial load at a corner: the planet's pin load (its two mesh forces)
// times K_gamma (the most loaded planet's) over the bearings that share it.
double planetBearingLoad(const std::vector<PairRating>& r, double count) {
  return planetPinLoad(r[0].Fbt, r[0].alphaWt, r[1].alphaWt) * r[0].Kgamma / count;
}

// A planet bearing's ISO 281 inputs; nullopt without its kind or rating (sema asks for them).
struct PlanetBearingInputs {
  shaft::BearingData data;
  shaft::LifeSettings life;
  double count = 1;
};

std::optional<PlanetBearingInputs> planetBearingInputs(const KindContext& c, bool modified) {
  using cat::gear::Planet;
  const ir::Attribute* kind = c.ev.model().attribute(c.stage, Planet, Q::PlanetBearingKind);
  PlanetBearingInputs in;
  in.data.C = num2(c, Planet, Q::PlanetBearingC, kNaN);
  if (!kind || kind->choice < 0 || !std::isfinite(in.data.C)) return std::nullopt;
  in.data.kind = static_cast<shaft::BearingKind>(kind->choice);
  in.data.C0 = num2(c, Planet, Q::PlanetBearingC0, in.data.C);
  in.data.pitchDiameter = num2(c, Planet, Q::PlanetBearingPitchDiameter, 0.0);
  in.count = num2(c, Planet, Q::PlanetBearingCount, 1.0);
  in.life.contamination = num2(c, Planet, Q::PlanetBearingContamination, 0.5);
  if (modified) {
    Lubricant oil;
    oil.nu40 = c.at(Q::RatingViscosity40).mid();
    oil.nu100 = c.at(Q::RatingViscosity100).mid();
    oil.oilTemperature = c.at(Q::RatingOilTemperature).mid();
    if (!(in.data.pitchDiameter > 0 && oil.nu40 > 0 && oil.nu100 > 0 && oil.oilTemperature > 0)) return std::nullopt;
    in.life.viscosity = oil.kinematic(oil.oilTemperature);
    in.life.viscositySource = "the rating's lubricant at its oil temperature";
  }
  return in;
}

// A planet bearing's life at a corner, at the planet's speed relative to the carrier (the
// planet drives the ring in the second mesh: omega = 2 v / d).
double planetBearingLife(const PlanetBearingInputs& in, const std::vector<PairRating>& r, bool modified) {
  shaft::BearingLoad load{planetBearingLoad(r, in.count), 0.0, 2 * r[1].v / r[1].dPinion};
  try {
    shaft::BearingLife l = shaft::life(in.data, load, in.life);
    return (modified ? l.Lnmh : l.L10h) * 3600;
  } catch (const std::invalid_argument&) {
    return kNaN;
  }
}

template <Q K> DerivedRow planetBearingRow() {
  return {K, true, [](const KindContext& c, int g) {
            if (g != cat::gear::Planet) return Value::invalid();
            if (K == Q::BearingLoad) {
              double count = num2(c, cat::gear::Planet, Q::PlanetBearingCount, 1.0);
              return overCorners(planetMeshes(c),
                                 [&](const std::vector<PairRating>& r) { return planetBearingLoad(r, count); });
            }
            auto in = planetBearingInputs(c, K == Q::BearingModifiedLife);
            if (!in) return Value::invalid();
            return overCorners(planetMeshes(c), [&](const std::vector<PairRating>& r) {
              return planetBearingLife(*in, r, K == Q::BearingModifiedLife);
            });
          }};
}

} // namespace

std::vector<DerivedRow> planetBearingRows() {
  return {planetBearingRow<Q::BearingLoad>(), planetBearingRow<Q::BearingLife>(),
          planetBearingRow<Q::BearingModifiedLife>()};
}

std::optional<std::vector<SpectrumBin>> spectrumBins(const KindContext& c, std::string* why) {
  std::vector<SpectrumBin> out;
  for (const auto& b : c.ev.model().info(c.stage).ir->spectrum) {
    SpectrumBin bin;
    bin.torqueShare = b.load.toDouble();
    bin.lifeShare = b.duration.toDouble();
    if (!b.share || b.cycles) {
      Value torque = c.derived(Q::InputTorque), speed = c.derived(Q::InputSpeed), life = c.at(Q::RatingLife);
      if (!torque.isNumber() || !speed.isNumber() || !life.isNumber() || torque.mid() == 0 || speed.mid() == 0) {
        if (why) *why = "its load spectrum's torques or cycles need the stage's input torque, speed and life";
        return std::nullopt;
      }
      if (!b.share) bin.torqueShare = b.load.toDouble() / std::fabs(torque.mid());
      if (b.cycles) bin.lifeShare = b.duration.toDouble() * 2 * M_PI / (std::fabs(speed.mid()) * life.mid());
    }
    out.push_back(bin);
  }
  return out;
}

std::optional<ScuffingRating> scuffingOf(const PairInput& in, const PairRating& r, ScuffingEdition edition, std::string* why) {
  if (!in.oil) return std::nullopt;
  ScuffingMesh m;
  const double sign = in.gear[1].internal ? -1.0 : 1.0; // a ring in the signed convention
  m.z1 = in.gear[0].z;
  m.z2 = sign * in.gear[1].z;
  m.mn = in.mn;
  m.alphaN = in.alphaN;
  m.beta = in.beta;
  double alphaT = std::atan(std::tan(in.alphaN) / std::cos(in.beta)), mt = in.mn / std::cos(in.beta);
  m.a = (m.z1 + m.z2) * mt / 2 * std::cos(alphaT) / std::cos(r.alphaWt);
  m.b = in.b;
  m.da1 = r.gear[0].tipDiameter;
  m.da2 = sign * r.gear[1].tipDiameter;
  m.Ft = r.Ft;
  m.KA = in.KA;
  m.Kgamma = r.Kgamma;
  m.Kv = r.Kv;
  m.KHbeta = r.KHbeta;
  m.KHalpha = r.KHalpha;
  m.speed1 = std::fabs(in.gear[0].speed);
  m.power = std::fabs(in.torque1) * m.speed1;
  for (size_t k = 0; k < 2; ++k) {
    m.E[k] = std::isfinite(in.gear[k].E) ? in.gear[k].E : in.E;
    m.nu[k] = std::isfinite(in.gear[k].nu) ? in.gear[k].nu : in.nu;
    m.Ca[k] = std::isfinite(in.tipRelief) ? in.tipRelief : 0;
  }
  m.Ra = in.RaFlank;
  m.cgamma = r.cgammaAlpha * 1e9;  // the rating keeps c_gamma in N/(mm um)
  // The structural factor X_W: 1.5 for a nitrided pair, else 1 (carburised, through-hardened).
  auto nitrided = [&](size_t k) { return in.gear[k].treatment.value_or(in.treatment) == Treatment::Nitrided; };
  m.XW = nitrided(0) && nitrided(1) ? 1.5 : 1.0;
  // A gear in n_p meshes heats the bulk by (1 + n_p)/2: the sun among its planets, an idler or
  // a planet between two mates (the planet drives the ring mesh).
  const bool twoMates = in.gear[0].YM < 1 || in.gear[1].YM < 1 || in.gear[1].internal;
  m.Xmp = in.planets > 0 && !in.gear[1].internal ? (1.0 + in.planets) / 2 : twoMates ? 1.5 : 1.0;
  m.grade = in.grade;
  try {
    return rateScuffing(m, *in.oil, edition);
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
}

std::vector<MeshRating> rateStage(const KindContext& c, std::string* why) {
  auto g = gather(c, why);
  if (!g || !modelFactors(c, *g, why, true)) return {};
  V point;
  for (const auto& v : g->varying)
    for (const auto& x : v) point.push_back(x.mid());
  try {
    auto r = rateAll(*g, point, true, true);
    std::vector<MeshRating> out;
    for (size_t k = 0; k < r.size(); ++k) {
      auto at = point.begin() + static_cast<long>(k * In::Count);
      out.push_back({g->meshes[k].g0,
                     g->meshes[k].g1,
                     g->meshes[k].internal,
                     inputAt(g->fixed[k], V(at, at + In::Count)),
                     r[k],
                     g->faceLoad,
                     g->kv,
                     {},
                     {}});
      out.back().input.Kgamma = r[k].Kgamma;
      if (g->sharing)
        out.back().loadSharing =
            fmt::format("load sharing of {} planets, the sun {}, pin error {:g} um", g->fixed[0].planets,
                        g->sharing->floatingSun ? "floating" : "held", g->sharing->pinError * 1e6);
      for (int slot = 0; slot < 2; ++slot) {
        int gear = slot == 0 ? g->meshes[k].g0 : g->meshes[k].g1;
        auto given = [&](Q key) { return givenOnly(c, gear, key).isNumber(); };
        out.back().given[static_cast<size_t>(slot)] = {given(Q::PitchDeviation), given(Q::ProfileFormDeviation), given(Q::ProfileDeviation),
                                                       given(Q::HelixSlopeDeviation)};
      }
    }
    return out;
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return {};
  }
}

std::vector<DerivedRow> pairRows() {
  using P = PairRating;
  using G = GearRating;
  return {
      stageRow<&P::Kv>(Q::KV),
      stageRow<&P::KHbeta>(Q::KHbeta),
      stageRow<&P::KFbeta>(Q::KFbeta),
      stageRow<&P::KHalpha>(Q::KHalpha),
      stageRow<&P::KFalpha>(Q::KFalpha),
      stageRow<&P::ZH>(Q::ZH),
      stageRow<&P::ZE>(Q::ZE),
      stageRow<&P::Zeps>(Q::Zeps),
      stageRow<&P::Zbeta>(Q::Zbeta),
      gearRow<&G::SH, Side::Contact>(Q::ContactSafety),
      gearRow<&G::SF, Side::Bending>(Q::BendingSafety),
      gearRow<&G::sigmaH, Side::Contact>(Q::ContactStress),
      gearRow<&G::sigmaF, Side::Bending>(Q::BendingStress),
      gearRow<&G::sigmaHP, Side::Contact>(Q::PermissibleContactStress),
      gearRow<&G::sigmaFP, Side::Bending>(Q::PermissibleBendingStress),
      gearRow<&G::ZNT, Side::Contact>(Q::ZNT),
      gearRow<&G::ZL, Side::Contact>(Q::ZL),
      gearRow<&G::Zv, Side::Contact>(Q::Zv),
      gearRow<&G::ZR, Side::Contact>(Q::ZR),
      gearRow<&G::ZW, Side::Contact>(Q::ZW),
      gearRow<&G::ZX, Side::Contact>(Q::ZX),
      gearRow<&G::ZBD, Side::Contact>(Q::ZB),
      gearRow<&G::ZBD, Side::Contact>(Q::ZD),
      gearRow<&G::YF, Side::Bending>(Q::YF),
      gearRow<&G::YS, Side::Bending>(Q::YS),
      gearRow<&G::Ybeta, Side::Bending>(Q::Ybeta),
      gearRow<&G::YNT, Side::Bending>(Q::YNT),
      gearRow<&G::YdeltarelT, Side::Bending>(Q::YdeltarelT),
      gearRow<&G::YRrelT, Side::Bending>(Q::YRrelT),
      gearRow<&G::YX, Side::Bending>(Q::YX),
      gearRow<&G::YM, Side::Contact>(Q::YM),
      scuffingRow<&ScuffingRating::SB, Q::ScuffingSafety>(),
      scuffingRow<&ScuffingRating::SintS, Q::IntegralScuffingSafety>(),
      scuffingRow<&ScuffingRating::thetaBmax, Q::ContactTemperature>(),
      scuffingRow<&ScuffingRating::thetaInt, Q::IntegralTemperature>(),
      scuffingRow<&ScuffingRating::thetaS, Q::ScuffingTemperature>(),
      scuffingRow<&ScuffingRating::thetaM, Q::BulkTemperature>(),
      scuffingRow<&ScuffingRating::Slambda, Q::MicropittingSafety>(),
      scuffingRow<&ScuffingRating::lambdaMin, Q::SpecificFilmThickness>(),
      scuffingRow<&ScuffingRating::lambdaGFP, Q::PermissibleFilmThickness>(),
      gearRow<&G::contactDamage, Side::Contact, true>(Q::ContactDamage),
      gearRow<&G::bendingDamage, Side::Bending, true>(Q::BendingDamage),
  };
}

} // namespace gbx::rt::rating
