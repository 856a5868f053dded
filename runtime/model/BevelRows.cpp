#include "model/BevelRows.h"

#include <cmath>
#include <stdexcept>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/RatingRows.h"

namespace gbx::rt::rating {

namespace {

using cat::gear::Pinion;
using cat::gear::Wheel;
using V = std::vector<double>;

constexpr double kAbsent = -1;  // an optional positive input left out (corner values must be numbers)

// The inputs that vary with the design, as values that may span a freedom's interval.
enum In { Z1, Z2, X1, X2, Xs1, Xs2, Rho1, Rho2, Fpt1, Fpt2, Beta, AlphaN, Coast, Shaft, Re, Mmn, B, Ratio, Cutter, T1, N1, N2, Count };

Value optional(const KindContext& c, int gear, Q k) {
  Value v = givenOnly(c, gear, k);
  return v.isNumber() ? v : Value::number(kAbsent);
}

// The geometry's inputs (every row), then the load's (the rating's).
std::optional<std::vector<Value>> varying(const KindContext& c, bool load) {
  std::vector<Value> x(In::Count, Value::number(kAbsent));
  x[Z1] = c.at(Pinion, Q::Z);
  x[Z2] = c.at(Wheel, Q::Z);
  x[X1] = c.orZero(Pinion, Q::Shift);
  x[X2] = c.orZero(Wheel, Q::Shift);
  x[Xs1] = c.orZero(Pinion, Q::ThicknessModification);
  x[Xs2] = c.orZero(Wheel, Q::ThicknessModification);
  x[Rho1] = optional(c, Pinion, Q::ToolEdgeRadius);
  x[Rho2] = optional(c, Wheel, Q::ToolEdgeRadius);
  x[Fpt1] = optional(c, Pinion, Q::PitchDeviation);
  x[Fpt2] = optional(c, Wheel, Q::PitchDeviation);
  x[Beta] = c.at(Q::SpiralAngle);
  x[AlphaN] = c.at(Q::PressureAngle);
  x[Coast] = optional(c, -1, Q::CoastPressureAngle);
  x[Shaft] = c.at(Q::ShaftAngle);
  x[Re] = optional(c, -1, Q::OuterConeDistance);
  x[Mmn] = optional(c, -1, Q::MeanNormalModule);
  x[B] = optional(c, -1, Q::FaceWidth);
  x[Ratio] = optional(c, -1, Q::FaceRatio);
  x[Cutter] = optional(c, -1, Q::CutterRadius);
  x[T1] = load ? c.derived(Pinion, Q::Torque) : Value::number(0.0);
  x[N1] = load ? c.derived(Pinion, Q::Speed) : Value::number(0.0);
  x[N2] = load ? c.derived(Wheel, Q::Speed) : Value::number(0.0);
  for (int i : {Z1, Z2, X1, X2, Xs1, Xs2, Beta, AlphaN, Shaft, T1, N1, N2})
    if (!x[static_cast<size_t>(i)].isNumber()) return std::nullopt;
  // The size: a cone distance or a module, and a face width or a face ratio.
  if (x[Re].lo == kAbsent && x[Mmn].lo == kAbsent && (x[B].lo == kAbsent || x[Ratio].lo == kAbsent)) return std::nullopt;
  if (x[B].lo == kAbsent && x[Ratio].lo == kAbsent) return std::nullopt;
  return x;
}

BevelInput inputAt(BevelInput in, const V& x) {
  auto given = [&](int i) { return x[static_cast<size_t>(i)] == kAbsent ? kNaN : x[static_cast<size_t>(i)]; };
  for (int g = 0; g < 2; ++g) {
    BevelGearInput& gi = in.gear[static_cast<size_t>(g)];
    gi.z = x[static_cast<size_t>(Z1 + g)];
    gi.xhm = x[static_cast<size_t>(X1 + g)];
    gi.xsm = x[static_cast<size_t>(Xs1 + g)];
    gi.edgeRadius = given(Rho1 + g);
    gi.fpt = std::max(0.0, x[static_cast<size_t>(Fpt1 + g)]);
    gi.speed = std::fabs(x[static_cast<size_t>(N1 + g)]);
  }
  in.betaM = x[Beta];
  in.alphaN = x[AlphaN];
  in.alphaNCoast = given(Coast);
  in.shaftAngle = x[Shaft];
  in.Re = given(Re);
  in.mmn = given(Mmn);
  in.b = given(B);
  in.faceRatio = given(Ratio);
  in.cutterRadius = given(Cutter);
  in.torque1 = std::fabs(x[T1]);
  return in;
}

double num(const KindContext& c, Q k, double dflt) {
  Value v = c.at(k);
  return v.isNumber() ? v.mid() : dflt;
}

// What the geometry reads of the rating block (the contact pattern), with the defaults.
BevelInput geometryInputs(const KindContext& c) {
  BevelInput in;
  in.contactPattern = num(c, Q::RatingContactPattern, 0.85);
  in.khap = num(c, Q::RatingRackAddendum, 1.0);
  in.khfp = num(c, Q::RatingRackDedendum, 1.25);
  return in;
}

// The inputs that do not vary with the design; nullopt when one the rating needs is missing.
std::optional<BevelInput> fixedInputs(const KindContext& c, std::string* why) {
  auto fail = [&](std::string s) -> std::optional<BevelInput> {
    if (why) *why = std::move(s);
    return std::nullopt;
  };
  BevelInput in = geometryInputs(c);
  auto mats = materialsOf(c, Pinion, Wheel, why);
  if (!mats) return std::nullopt;
  applyMaterials(in, *mats);
  in.life = num(c, Q::RatingLife, kNaN);
  in.nu40 = num(c, Q::RatingViscosity40, kNaN);
  if (!std::isfinite(in.life)) return fail("its rating gives no `life`");
  if (!std::isfinite(in.nu40)) return fail("its rating gives no `lubricant.viscosity_40`");
  in.RzFlank = num(c, Q::RatingRoughnessFlankRz, 6 * num(c, Q::RatingRoughnessFlank, kNaN));
  in.RzRoot = num(c, Q::RatingRoughnessRootRz, 6 * num(c, Q::RatingRoughnessRoot, kNaN));
  if (!std::isfinite(in.RzFlank) || !std::isfinite(in.RzRoot)) return fail("its rating gives no flank or root roughness");
  in.KA = num(c, Q::RatingApplicationFactor, 1.0);
  in.KvGiven = num(c, Q::RatingDynamicFactor, kNaN);
  in.KHbetaGiven = num(c, Q::RatingFaceLoadFactor, kNaN);
  in.KHalphaGiven = num(c, Q::RatingTransverseLoadFactor, kNaN);
  in.SHmin = num(c, Q::RatingMinContact, 1.0);
  in.SFmin = num(c, Q::RatingMinBending, 1.0);
  const Model& m = c.ev.model();
  const ir::Attribute* curve = m.attribute(c.stage, Q::RatingLifeCurve);
  in.optimumLife = curve && curve->choice == cat::lifeCurve::Optimum;
  const ir::Attribute* mount = m.attribute(c.stage, Q::RatingMounting);
  if (mount && mount->choice >= 0) in.mounting = static_cast<Mounting>(mount->choice);
  return in;
}

// The pair rated, under the stage's load spectrum where it has one (ISO 6336-6's Miner sum
// over ISO 10300's life factors): the safeties are then the spectrum's.
BevelRating ratedUnder(const BevelInput& in, const std::vector<SpectrumBin>& bins) {
  BevelRating r = rateBevel(in);
  if (bins.empty()) return r;
  BevelSpectrum sp = rateBevelSpectrum(in, bins);
  for (size_t k = 0; k < 2; ++k) {
    r.gear[k].SH = sp.contact[k].safety;
    if (std::isfinite(r.gear[k].SF)) r.gear[k].SF = sp.bending[k].safety;
  }
  return r;
}

using Select = double (*)(const BevelRating&, int gear);
enum Need { Geometry, Load, Rating };

// One value of the pair at the design: from the geometry alone, with the load, or from the rating.
Value value(const KindContext& c, int gear, Select select, Need need) {
  std::optional<BevelInput> fixed = need == Rating ? fixedInputs(c, nullptr) : std::optional<BevelInput>(geometryInputs(c));
  if (!fixed) return Value::invalid();
  std::vector<SpectrumBin> bins;
  if (need == Rating) {
    auto b = spectrumBins(c, nullptr);
    if (!b) return Value::invalid();
    bins = std::move(*b);
  }
  auto x = varying(c, need != Geometry);
  if (!x) return Value::invalid();
  return arith::corners(*x, [&](const V& v) {
    try {
      BevelInput in = inputAt(*fixed, v);
      return select(need == Rating ? ratedUnder(in, bins) : bevelGeometry(in), gear);
    } catch (const std::domain_error&) {
      return kNaN;
    }
  });
}

template <double BevelRating::*M, Need N>
DerivedRow stageRow(Q key) {
  return {key, false, [](const KindContext& c, int g) { return value(c, g, [](const BevelRating& r, int) { return r.*M; }, N); }};
}

template <double BevelGearRating::*M, Need N>
DerivedRow gearRow(Q key) {
  return {key, true, [](const KindContext& c, int g) {
            return value(c, g, [](const BevelRating& r, int gear) { return r.gear[static_cast<size_t>(gear)].*M; }, N);
          }};
}

} // namespace

std::optional<BevelStageRating> rateBevelStage(const KindContext& c, std::string* why) {
  auto fixed = fixedInputs(c, why);
  if (!fixed) return std::nullopt;
  auto bins = spectrumBins(c, why);
  if (!bins) return std::nullopt;
  auto x = varying(c, true);
  if (!x) {
    if (why) *why = "its geometry or load is not known at this design";
    return std::nullopt;
  }
  V mid;
  for (const auto& v : *x) mid.push_back(v.mid());
  try {
    BevelInput in = inputAt(*fixed, mid);
    return BevelStageRating{in, ratedUnder(in, *bins)};
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
}

std::vector<DerivedRow> bevelRows() {
  using R = BevelRating;
  using G = BevelGearRating;
  return {
      // Given, or from the rest of the cone (an absent attribute reads its row).
      stageRow<&R::Re, Geometry>(Q::OuterConeDistance),
      stageRow<&R::mmn, Geometry>(Q::MeanNormalModule),
      stageRow<&R::b, Geometry>(Q::FaceWidth),
      {Q::FaceRatio, false,
       [](const KindContext& c, int g) { return value(c, g, [](const BevelRating& r, int) { return r.b / r.Re; }, Geometry); }},
      stageRow<&R::Rm, Geometry>(Q::MeanConeDistance),
      stageRow<&R::epsVa, Geometry>(Q::VirtualEpsAlpha),
      stageRow<&R::epsVb, Geometry>(Q::VirtualEpsBeta),
      stageRow<&R::epsVg, Geometry>(Q::VirtualContactRatio),
      gearRow<&G::dm, Geometry>(Q::MeanDiameter),
      gearRow<&G::de, Geometry>(Q::OuterPitchDiameter),
      gearRow<&G::ham, Geometry>(Q::MeanAddendum),
      gearRow<&G::hfm, Geometry>(Q::MeanDedendum),
      gearRow<&G::zv, Geometry>(Q::VirtualZ),
      stageRow<&R::Ft, Load>(Q::TangentialForce),
      stageRow<&R::v, Load>(Q::PitchLineVelocity),
      stageRow<&R::Kv, Rating>(Q::KV),
      stageRow<&R::KHbeta, Rating>(Q::KHbeta),
      stageRow<&R::KFbeta, Rating>(Q::KFbeta),
      stageRow<&R::KHalpha, Rating>(Q::KHalpha),
      stageRow<&R::KFalpha, Rating>(Q::KFalpha),
      stageRow<&R::ZMB, Rating>(Q::ZMB),
      stageRow<&R::ZLS, Rating>(Q::ZLS),
      stageRow<&R::ZE, Rating>(Q::ZE),
      stageRow<&R::Zbeta, Rating>(Q::Zbeta),
      stageRow<&R::Yeps, Rating>(Q::Yeps),
      stageRow<&R::YLS, Rating>(Q::YLS),
      stageRow<&R::YBS, Rating>(Q::YBS),
      gearRow<&G::SH, Rating>(Q::ContactSafety),
      gearRow<&G::SF, Rating>(Q::BendingSafety),
      gearRow<&G::sigmaH, Rating>(Q::ContactStress),
      gearRow<&G::sigmaF, Rating>(Q::BendingStress),
      gearRow<&G::sigmaHP, Rating>(Q::PermissibleContactStress),
      gearRow<&G::sigmaFP, Rating>(Q::PermissibleBendingStress),
      gearRow<&G::ZNT, Rating>(Q::ZNT),
      gearRow<&G::ZL, Rating>(Q::ZL),
      gearRow<&G::Zv, Rating>(Q::Zv),
      gearRow<&G::ZR, Rating>(Q::ZR),
      gearRow<&G::ZW, Rating>(Q::ZW),
      gearRow<&G::ZX, Rating>(Q::ZX),
      gearRow<&G::YFa, Rating>(Q::YFa),
      gearRow<&G::YSa, Rating>(Q::YSa),
      gearRow<&G::YNT, Rating>(Q::YNT),
      gearRow<&G::YdeltarelT, Rating>(Q::YdeltarelT),
      gearRow<&G::YRrelT, Rating>(Q::YRrelT),
      gearRow<&G::YX, Rating>(Q::YX),
  };
}

} // namespace gbx::rt::rating
