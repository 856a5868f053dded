#include "rating/PairRows.h"

#include <cmath>
#include <stdexcept>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "model/Standards.h"

namespace gbx::rt::rating {

namespace {

using cat::gear::Pinion;
using cat::gear::Wheel;
using V = std::vector<double>;

constexpr double kAbsent = -1;  // an optional input left out (corner values must be numbers)

// A value the spec gives (fixed, chosen or free), not the one a kind derives when absent.
Value givenOnly(const KindContext& c, int gear, Q k) {
  const auto& en = c.ev.model().info(c.stage).entry(gear, k);
  if (!en.attr && en.slot < 0 && en.freedom < 0) return Value::invalid();
  return c.at(gear, k);
}

double num2(const KindContext& c, int gear, Q k, double dflt) {
  Value v = c.at(gear, k);
  return v.isNumber() ? v.mid() : dflt;
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

// The inputs that do not vary with the design; nullopt when one the rating needs is missing.
std::optional<PairInput> fixedInputs(const KindContext& c, std::string* why) {
  auto fail = [&](std::string s) -> std::optional<PairInput> {
    if (why) *why = std::move(s);
    return std::nullopt;
  };
  const Model& m = c.ev.model();
  const ir::Material* mat = m.material(c.stage);
  if (!mat) return fail("the stage names no material");
  auto prop = [&](Q k) -> const ir::Setting* { return ir::findSetting(mat->properties, k); };
  PairInput in;
  for (Q k : {Q::SigmaHlim, Q::SigmaFlim, Q::YoungsModulus, Q::Poisson, Q::Density})
    if (!prop(k) || !prop(k)->value) return fail("its material does not give " + std::string(cat::keyName(k)));
  const ir::Setting* t = prop(Q::Treatment);
  if (!t || t->choice < 0) return fail("its material does not give its treatment");
  in.treatment = t->choice == cat::treatment::Nitrided          ? Treatment::Nitrided
                 : t->choice == cat::treatment::ThroughHardened ? Treatment::ThroughHardened
                                                                : Treatment::CaseHardened;
  for (auto& g : in.gear) {
    g.sigmaHlim = prop(Q::SigmaHlim)->value->toDouble();
    g.sigmaFlim = prop(Q::SigmaFlim)->value->toDouble();
  }
  in.E = prop(Q::YoungsModulus)->value->toDouble();
  in.nu = prop(Q::Poisson)->value->toDouble();
  in.density = prop(Q::Density)->value->toDouble();
  auto num = [&](Q k, double dflt) {
    Value v = c.at(k);
    return v.isNumber() ? v.mid() : dflt;
  };
  in.life = num(Q::RatingLife, kNaN);
  in.nu40 = num(Q::RatingViscosity40, kNaN);
  if (!std::isfinite(in.life)) return fail("its rating gives no `life`");
  if (!std::isfinite(in.nu40)) return fail("its rating gives no `lubricant.viscosity_40`");
  // Rz = 6 Ra unless Rz is given (LANGUAGE.md §11).
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
  in.SFmin = num(Q::RatingMinBending, 1.0);
  const ir::Attribute* curve = m.attribute(c.stage, Q::RatingLifeCurve);
  in.optimumLife = curve && curve->choice == cat::lifeCurve::Optimum;
  Value grade = c.at(Q::Accuracy);
  in.grade = grade.exact && grade.exact->isInteger() ? static_cast<int>(grade.exact->num()) : 0;
  for (int g = 0; g < 2; ++g) {
    GearInput& gi = in.gear[static_cast<size_t>(g)];
    gi.bore = num2(c, g, Q::BoreDiameter, 0.0);
    double bs = num2(c, g, Q::WebThickness, kNaN), sr = num2(c, g, Q::RimThickness, kNaN);
    double b = c.at(Q::FaceWidth).mid(), mn = c.at(Q::NormalModule).mid();
    // C_R of a webbed blank, ISO 6336-1 eq. (clause 9.3.4): 1 + ln(b_s/b) / (5 e^(s_R/(5 m_n))).
    if (std::isfinite(bs) && std::isfinite(sr) && bs / b >= 0.2 && bs / b < 1.2)
      gi.webFactor = 1 + std::log(bs / b) / (5 * std::exp(sr / (5 * mn)));
  }
  return in;
}


// The varying inputs at the design, in `In` order.
std::optional<std::vector<Value>> varyingInputs(const KindContext& c, const PairInput& fixed, std::string* why) {
  std::vector<Value> x(In::Count);
  x[Z1] = c.at(Pinion, Q::Z);
  x[Z2] = c.at(Wheel, Q::Z);
  x[X1] = c.orZero(Pinion, Q::Shift);
  x[X2] = c.orZero(Wheel, Q::Shift);
  x[Mn] = c.at(Q::NormalModule);
  x[AlphaN] = c.at(Q::PressureAngle);
  x[Beta] = c.ev.model().info(c.stage).ir->kind == ir::StageKind::Helical ? c.at(Q::HelixAngle) : Value::number(0.0);
  x[B] = c.at(Q::FaceWidth);
  // Given, or from the shifts inside the rating (an interval of its own would pair
  // corners of the centre distance with shifts that cannot produce it).
  Value a = givenOnly(c, -1, Q::CenterDistance);
  x[A] = a.isNumber() ? a : Value::number(kAbsent);
  x[T1] = c.derived(Pinion, Q::Torque);
  x[N1] = c.derived(Pinion, Q::Speed);
  x[N2] = c.derived(Wheel, Q::Speed);
  auto opt = [&](int g, Q k) {
    Value v = givenOnly(c, g, k);
    return v.isNumber() ? v : Value::number(kAbsent);
  };
  x[Fpb1] = opt(Pinion, Q::PitchDeviation);
  x[Fpb2] = opt(Wheel, Q::PitchDeviation);
  x[Ffa1] = opt(Pinion, Q::ProfileFormDeviation);
  x[Ffa2] = opt(Wheel, Q::ProfileFormDeviation);
  x[Fhb1] = opt(Pinion, Q::HelixSlopeDeviation);
  x[Fhb2] = opt(Wheel, Q::HelixSlopeDeviation);
  x[Da1] = opt(Pinion, Q::TipDiameter);
  x[Da2] = opt(Wheel, Q::TipDiameter);
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

// The rating at one corner of the varying inputs.
PairRating rateAt(PairInput in, const V& x) {
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
    gi.fpb = pick(Fpb1, q > 0 ? iso::tabulatedSinglePitch(q, in.mn, d) : 0);
    gi.ffa = pick(Ffa1, q > 0 ? iso::tabulatedProfileForm(q, in.mn, d) : 0);
    gi.fHb = pick(Fhb1, q > 0 ? iso::tabulatedHelixSlope(q, d, in.b) : 0);
    gi.tipDiameter = x[static_cast<size_t>(Da1 + g)] == kAbsent ? kNaN : x[static_cast<size_t>(Da1 + g)];
  }
  return rate(in);
}

Value rated(const KindContext& c, int gear, double (*select)(const PairRating&, int)) {
  auto fixed = fixedInputs(c, nullptr);
  if (!fixed) return Value::invalid();
  auto x = varyingInputs(c, *fixed, nullptr);
  if (!x) return Value::invalid();
  return arith::corners(*x, [&](const V& v) {
    try {
      return select(rateAt(*fixed, v), gear < 0 ? 0 : gear);
    } catch (const std::domain_error&) {
      return kNaN;
    }
  });
}

template <double PairRating::*M>
DerivedRow stageRow(Q key) {
  return {key, false, [](const KindContext& c, int g) { return rated(c, g, [](const PairRating& r, int) { return r.*M; }); }};
}
template <double GearRating::*M>
DerivedRow gearRow(Q key) {
  return {key, true, [](const KindContext& c, int g) {
            return rated(c, g, [](const PairRating& r, int gear) { return r.gear[static_cast<size_t>(gear)].*M; });
          }};
}

} // namespace

std::optional<PairRating> ratePair(const KindContext& c, std::string* why) {
  auto fixed = fixedInputs(c, why);
  if (!fixed) return std::nullopt;
  auto x = varyingInputs(c, *fixed, why);
  if (!x) return std::nullopt;
  V point;
  for (const auto& v : *x) point.push_back(v.mid());
  try {
    return rateAt(*fixed, point);
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return std::nullopt;
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
      gearRow<&G::SH>(Q::ContactSafety),
      gearRow<&G::SF>(Q::BendingSafety),
      gearRow<&G::sigmaH>(Q::ContactStress),
      gearRow<&G::sigmaF>(Q::BendingStress),
      gearRow<&G::sigmaHP>(Q::PermissibleContactStress),
      gearRow<&G::sigmaFP>(Q::PermissibleBendingStress),
      gearRow<&G::ZNT>(Q::ZNT),
      gearRow<&G::ZL>(Q::ZL),
      gearRow<&G::Zv>(Q::Zv),
      gearRow<&G::ZR>(Q::ZR),
      gearRow<&G::ZW>(Q::ZW),
      gearRow<&G::ZX>(Q::ZX),
      gearRow<&G::ZBD>(Q::ZB),
      gearRow<&G::ZBD>(Q::ZD),
      gearRow<&G::YF>(Q::YF),
      gearRow<&G::YS>(Q::YS),
      gearRow<&G::Ybeta>(Q::Ybeta),
      gearRow<&G::YNT>(Q::YNT),
      gearRow<&G::YdeltarelT>(Q::YdeltarelT),
      gearRow<&G::YRrelT>(Q::YRrelT),
      gearRow<&G::YX>(Q::YX),
      gearRow<&G::YM>(Q::YM),
  };
}

} // namespace gbx::rt::rating
