#include "dynamics/LoadedMeshInputs.h"

#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "dynamics/SceneSupport.h"
#include "model/Sampling.h"
#include "model/Standards.h"

namespace gbx::rt::dyn {

namespace {

using cat::gear::Pinion;
using cat::gear::Wheel;

std::string um(double v) { return fmt::format("{:.4g} um", v * 1e6); }

// A quantity of the stage (gear -1) or of one of its gears.
ir::QuantityRef stageRef(int st, int gear, Q key) {
  ir::QuantityRef ref;
  ref.owner = ir::QuantityRef::Stage;
  ref.index = static_cast<std::int16_t>(st);
  ref.gear = static_cast<std::int8_t>(gear);
  ref.key = key;
  return ref;
}

// The stage's modifications as its `modify` rules give them, a sweep's value first.
struct Mods {
  double tipRelief[2] = {0, 0}, height[2] = {-1, -1}, crowning[2] = {0, 0};
  double endRelief[2] = {0, 0}, endWidth[2] = {0, 0}, helixSlope[2] = {0, 0};
  bool heightGiven[2] = {false, false};
  std::vector<std::string> ignored;
};

Mods modifications(const Evaluator& ev, const Assignment& a, int st, std::vector<std::string>& prov) {
  Mods m;
  const Model& model = ev.model();
  for (const auto& md : model.gearbox.modifies) {
    if (md.stageIndex != st) continue;
    for (const auto& r : md.rules) {
      if (!r.value) continue;
      if (r.when) {
        Value w = ev.eval(*r.when, a);
        if (w.kind != Value::Bool || w.truth != Truth::True) continue;
      }
      Value v = ev.eval(*r.value, a);
      if (!v.isNumber()) throw SceneFailure{fmt::format("the loaded mesh needs the modification `{}`, which cannot be computed for this design", r.target)};
      auto each = [&](double* slot) {
        for (int g = 0; g < 2; ++g)
          if (r.gear < 0 || r.gear == g) slot[g] = v.mid();
      };
      switch (static_cast<cat::Mod>(r.modTarget)) {
      case cat::Mod::TipRelief: each(m.tipRelief); break;
      case cat::Mod::TipReliefHeight:
        each(m.height);
        for (int g = 0; g < 2; ++g)
          if (r.gear < 0 || r.gear == g) m.heightGiven[g] = true;
        break;
      case cat::Mod::LeadCrowning: each(m.crowning); break;
      case cat::Mod::EndRelief: each(m.endRelief); break;
      case cat::Mod::EndReliefWidth: each(m.endWidth); break;
      case cat::Mod::HelixSlope: each(m.helixSlope); break;
      case cat::Mod::ThermalLeadRelief:
        prov.push_back(fmt::format("loaded mesh: `{}` compensates the thermal distortion of the running gear, which the loaded mesh "
                                   "does not model: neither is a separation",
                                   r.target));
        break;
      default: m.ignored.push_back(r.target); break;
      }
    }
  }
  // A sweep of a modification (`sweep hs.tip_relief …`) replaces the rule.
  auto swept = [&](int gear, Q key, double* slot, bool* given) {
    if (!ev.overrides(st, gear, key)) return;
    Value v = ev.quantity(stageRef(st, gear, key), a);
    for (int g = 0; g < 2; ++g)
      if (gear < 0 || gear == g) {
        slot[g] = v.mid();
        if (given) given[g] = true;
      }
  };
  for (int gear : {-1, Pinion, Wheel}) {
    swept(gear, Q::TipRelief, m.tipRelief, nullptr);
    swept(gear, Q::TipReliefHeight, m.height, m.heightGiven);
    swept(gear, Q::LeadCrowning, m.crowning, nullptr);
  }
  return m;
}

// A stage quantity at the design, NaN where the design does not give it.
double optionalQuantity(const Evaluator& ev, const Assignment& a, int st, int gear, Q key) {
  Value v = ev.quantity(stageRef(st, gear, key), a);
  return v.isNumber() && std::isfinite(v.lo) ? v.mid() : NAN;
}

// Separations across the face: the lead modifications, the pinion's deflection in the sense
// its hand and torque side give, and a lead deviation the caller adds.
void leadSeparations(const Evaluator& ev, const Assignment& a, int st, const Mods& mods, const FlankGeometry& g, const LoadedMeshUse& use,
                     FlankSeparations& sep, std::vector<std::string>& prov) {
  auto optional = [&](int gear, Q key) { return optionalQuantity(ev, a, st, gear, key); };
  // A scene takes the lead deviation the spec gives (`helix_slope_deviation`, the larger of
  // the two gears'); the rating passes its own f_ma.
  double leadDeviation = use.leadDeviation;
  if (!use.leadOnly)
    for (int gear : {Pinion, Wheel})
      if (ev.model().attribute(st, gear, Q::HelixSlopeDeviation) || ev.overrides(st, gear, Q::HelixSlopeDeviation)) {
        double f = optional(gear, Q::HelixSlopeDeviation);
        if (std::isfinite(f)) leadDeviation = std::max(leadDeviation, f);
      }
  sep.leadCrowning = mods.crowning[0] + mods.crowning[1];
  // Which gears carry it: the provenance names them (the two amounts add into one separation).
  if (sep.leadCrowning > 0) {
    const double p = mods.crowning[0], w = mods.crowning[1];
    std::string who = p > 0 && w > 0 ? fmt::format("pinion {} + wheel {}", um(p), um(w)) : p > 0 ? "the pinion's" : "the wheel's";
    prov.push_back(fmt::format("loaded mesh: lead crowning {} ({}), parabolic across the face", um(sep.leadCrowning), who));
  }
  // End relief: both gears' amounts add; it runs over the wider of their widths, else a tenth
  // of the face.
  sep.endRelief = mods.endRelief[0] + mods.endRelief[1];
  if (sep.endRelief > 0) {
    double w = std::max(mods.endWidth[0], mods.endWidth[1]);
    sep.endReliefWidth = w > 0 ? std::min(w, 0.5 * g.faceWidth) : 0.1 * g.faceWidth;
    prov.push_back(fmt::format("loaded mesh: end relief {} at both ends of the face, linear over {:.3f} mm{}", um(sep.endRelief),
                               sep.endReliefWidth * 1e3, w > 0 ? "" : " (no `end_relief_width`: a tenth of the face)"));
  }
  for (const auto& t : mods.ignored) prov.push_back(fmt::format("loaded mesh: `{}` is not one of the separations it models", t));
  // The pinion's wind-up and bending under the load tilt its flank across the face. Across
  // the face from the coupling end: the end where the torque enters is wound up ahead of the
  // other, and a right-hand pinion's bending tilts it the same way as a wind-up from the
  // coupling end (a left hand the other way). Without `helix_hand` and `torque_side` the two
  // add, the adverse case.
  double bend = optional(Pinion, Q::BendingDeflection), twist = optional(Pinion, Q::TorsionDeflection);
  const ir::Attribute* hand = ev.model().attribute(st, Q::HelixHand);
  const ir::Attribute* side = ev.model().attribute(st, Q::TorqueSide);
  double handSign = hand && hand->choice == cat::helixHand::Left ? -1.0 : 1.0;
  double sideSign = side && side->choice == cat::torqueSide::Free ? -1.0 : 1.0;
  // One word alone: the other takes the sense that adds, the adverse case.
  if (hand && !side) sideSign = handSign;
  if (side && !hand) handSign = sideSign;
  double tilt = 0; // the shafts' tilt end to end, which a correction opposes and a deviation adds to
  if (!use.shaftProfile.empty()) {
    sep.leadProfile = use.shaftProfile;
    tilt = use.shaftProfile.back() - use.shaftProfile.front();
    double most = *std::max_element(use.shaftProfile.begin(), use.shaftProfile.end());
    prov.push_back(fmt::format("loaded mesh: the shafts' bending and twist with their bearings, on the line of action: {} "
                               "across the face end to end, {} at most",
                               um(std::fabs(tilt)), um(most)));
  } else if (std::isfinite(bend) || std::isfinite(twist)) {
    double b = (std::isfinite(bend) ? bend : 0.0) * use.deflectionScale, t = (std::isfinite(twist) ? twist : 0.0) * use.deflectionScale;
    if (use.deflectionScale != 1)
      prov.push_back(fmt::format("loaded mesh: the pinion's deflections at the operating torque times {:.4f} (F_m / F_t)", use.deflectionScale));
    sep.leadSlope = handSign * b + sideSign * t;
    if (!hand && !side)
      prov.push_back(fmt::format("loaded mesh: pinion bending and torsion deflection {} as a linear separation across the face",
                                 um(sep.leadSlope)));
    else
      prov.push_back(fmt::format("loaded mesh: pinion bending {} ({} hand) and torsion {} (torque at the {} end): {} across the face", um(b),
                                 handSign > 0 ? "right" : "left", um(t), sideSign > 0 ? "coupling" : "free", um(std::fabs(sep.leadSlope))));
  }
  // A helix slope correction takes its amount off the deflection's slope (it is made to
  // compensate it).
  auto sense = [&] { return use.sense != 0 ? use.sense : tilt + sep.leadSlope >= 0 ? 1.0 : -1.0; };
  double correction = mods.helixSlope[0] + mods.helixSlope[1];
  if (correction > 0) {
    sep.leadSlope -= sense() * correction;
    prov.push_back(fmt::format("loaded mesh: helix slope correction {} against the deflection: {} across the face", um(correction),
                               um(std::fabs(tilt + sep.leadSlope))));
  }
  if (leadDeviation > 0) {
    sep.leadSlope += sense() * leadDeviation;
    prov.push_back(fmt::format("loaded mesh: lead deviation {} in the adverse sense: {} across the face in all", um(leadDeviation),
                               um(std::fabs(tilt + sep.leadSlope))));
  }
}

} // namespace

LoadedMeshInput loadedMeshInput(const Evaluator& ev, const Assignment& a, int st, double load, int slices, int positions,
                                std::vector<std::string>& prov, const LoadedMeshUse& use) {
  auto q = [&](int gear, Q key, const char* what) { return needNumber(ev.quantity(stageRef(st, gear, key), a), what); };
  auto optional = [&](int gear, Q key) { return optionalQuantity(ev, a, st, gear, key); };
  const ir::Stage& stage = *ev.model().stages[static_cast<size_t>(st)].ir;
  bool helical = stage.kind == ir::StageKind::Helical;
  LoadedMeshInput in;
  in.load = load;
  in.slices = slices;
  in.positions = positions;
  FlankGeometry& g = in.g;
  g.rb1 = q(Pinion, Q::BaseRadius, "the pinion base radius");
  g.rb2 = q(Wheel, Q::BaseRadius, "the wheel base radius");
  g.ra1 = q(Pinion, Q::TipRadius, "the pinion tip radius");
  g.ra2 = q(Wheel, Q::TipRadius, "the wheel tip radius");
  g.centerDistance = q(-1, Q::CenterDistance, "the centre distance");
  g.workingPressureAngle = q(-1, Q::WorkingPressureAngle, "the working pressure angle");
  g.faceWidth = q(-1, Q::FaceWidth, "`face_width`");
  double mn = q(-1, Q::NormalModule, "`normal_module`"), alphaN = q(-1, Q::PressureAngle, "the pressure angle");
  double beta = helical ? q(-1, Q::HelixAngle, "the helix angle") : 0.0;
  double alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  g.basePitch = M_PI * mn * std::cos(alphaT) / std::cos(beta);
  g.baseHelix = std::atan(std::tan(beta) * std::cos(alphaT));
  double roll1 = std::sqrt(g.ra1 * g.ra1 - g.rb1 * g.rb1), roll2 = std::sqrt(g.ra2 * g.ra2 - g.rb2 * g.rb2);
  double path = roll1 + roll2 - g.centerDistance * std::sin(g.workingPressureAngle);
  double epsAlpha = path / g.basePitch;

  // c' from ISO 6336-1 method B, or from the given c_gamma through c_gamma = c' (0.75 eps_alpha + 0.25).
  double cgamma;
  const ir::Attribute* given = ev.model().attribute(st, Q::MeshStiffness);
  if (given || ev.overrides(st, -1, Q::MeshStiffness)) {
    cgamma = q(-1, Q::MeshStiffness, "`mesh_stiffness`");
  } else {
    double x1 = optional(Pinion, Q::Shift), x2 = optional(Wheel, Q::Shift);
    cgamma = iso::meshStiffness(q(Pinion, Q::Z, "pinion.z"), q(Wheel, Q::Z, "wheel.z"), std::isfinite(x1) ? x1 : 0.0,
                                std::isfinite(x2) ? x2 : 0.0, beta, epsAlpha);
  }
  in.singleStiffness = cgamma / (0.75 * epsAlpha + 0.25);
  prov.push_back(fmt::format("loaded mesh: {} slices x {} positions; single-pair stiffness c' {:.4g} N/(mm*um) ({}c_gamma {:.4g} / (0.75 "
                             "eps_alpha + 0.25)), distributed along the path as c' (0.7 + 1.2 xi (1 - xi))",
                             slices, positions, in.singleStiffness * 1e-9, given ? "given " : "ISO 6336-1 method B ", cgamma * 1e-9));

  // Profile and lead modifications.
  FlankSeparations& sep = in.sep;
  Mods mods = modifications(ev, a, st, prov);
  double rolls[2] = {roll1, roll2}, ra[2] = {g.ra1, g.ra2}, rb[2] = {g.rb1, g.rb2};
  const char* names[2] = {"pinion", "wheel"};
  for (int k = 0; k < 2 && !use.leadOnly; ++k) {
    sep.tipRelief[k] = mods.tipRelief[k];
    if (sep.tipRelief[k] <= 0) continue;
    if (mods.heightGiven[k]) {
      double rs = ra[k] - mods.height[k];
      sep.reliefLength[k] = rolls[k] - (rs > rb[k] ? std::sqrt(rs * rs - rb[k] * rb[k]) : 0.0);
      prov.push_back(fmt::format("loaded mesh: {} tip relief {} over {:.3f} mm of height ({:.3f} mm of roll), linear", names[k],
                                 um(sep.tipRelief[k]), mods.height[k] * 1e3, sep.reliefLength[k] * 1e3));
    } else {
      // A long relief: from the tip down to the point of single-pair contact nearest it.
      sep.reliefLength[k] = std::max(0.0, path - g.basePitch);
      prov.push_back(fmt::format("loaded mesh: {} tip relief {}, linear, long (from the tip to the point of single-pair contact, {:.3f} "
                                 "mm of roll: no `tip_relief_height`)",
                                 names[k], um(sep.tipRelief[k]), sep.reliefLength[k] * 1e3));
    }
  }
  leadSeparations(ev, a, st, mods, g, use, sep, prov);
  if (use.leadOnly) return in;
  // Deviations, in their adverse forms, each the mean of the two gears' (what paper P3's relief
  // rule allows for): the incoming pair early by the base pitch deviation, the ends of the
  // path proud by the profile form deviation.
  double fp1 = optional(Pinion, Q::PitchDeviation), fp2 = optional(Wheel, Q::PitchDeviation);
  double ff1 = optional(Pinion, Q::ProfileDeviation), ff2 = optional(Wheel, Q::ProfileDeviation);
  if (std::isfinite(fp1) && std::isfinite(fp2)) sep.basePitch = 0.5 * (fp1 + fp2);
  if (std::isfinite(ff1) && std::isfinite(ff2)) sep.profileForm = 0.5 * (ff1 + ff2);
  auto dev = [](double v) { return std::isfinite(v) ? um(v) : std::string("none"); };
  prov.push_back(fmt::format("loaded mesh: base pitch deviation {} (mean of {} and {}), each incoming pair early by it; profile form "
                             "deviation {} (mean of {} and {}), the ends of the path proud by it",
                             um(sep.basePitch), dev(fp1), dev(fp2), um(sep.profileForm), dev(ff1), dev(ff2)));
  return in;
}

std::vector<double> toothLateness(const std::vector<double>& singlePitch, double cosAlphaT) {
  size_t z = singlePitch.size();
  double sum = 0;
  for (double f : singlePitch)
    sum += f;
  std::vector<double> out(z);
  double run = 0;
  for (size_t i = 0; i < z; ++i) {
    run += singlePitch[i];
    out[i] = (run - sum * static_cast<double>(i + 1) / static_cast<double>(z)) * cosAlphaT;
  }
  return out;
}

void toothErrors(const Evaluator& ev, const Assignment& a, int st, const ToothErrors& errors, LoadedMeshInput& in,
                 std::vector<std::string>& prov) {
  if (!errors.any()) return;
  const char* names[2] = {"pinion", "wheel"};
  // The transverse pressure angle at the reference circle: the base pitch over the transverse
  // pitch (pi m_t cos alpha_t / pi m_t).
  double mn = needNumber(ev.quantity(stageRef(st, -1, Q::NormalModule), a), "`normal_module`");
  double beta = ev.model().stages[static_cast<size_t>(st)].ir->kind == ir::StageKind::Helical
                    ? needNumber(ev.quantity(stageRef(st, -1, Q::HelixAngle), a), "the helix angle")
                    : 0.0;
  double cosAlphaT = in.g.basePitch / (M_PI * mn / std::cos(beta));
  for (int g = 0; g < 2; ++g) {
    long z = std::lround(needNumber(ev.quantity(stageRef(st, g, Q::Z), a), "the tooth count"));
    std::vector<double> f;
    if (errors.listed[g] && !errors.listed[g]->empty()) {
      f = *errors.listed[g];
      if (static_cast<long>(f.size()) != z)
        throw SceneFailure{
            fmt::format("`{}_pitch_deviations` lists {} teeth; the {} has {}", names[g], f.size(), names[g], z)};
      prov.push_back(fmt::format("loaded mesh: the {}'s {} single pitch deviations as listed", names[g], z));
    } else if (errors.seed) {
      double fpt = optionalQuantity(ev, a, st, g, Q::PitchDeviation);
      if (!std::isfinite(fpt))
        throw SceneFailure{
            fmt::format("`pitch_seed` draws from the {}'s `pitch_deviation`, which it neither gives nor has from an "
                        "`accuracy` grade",
                        names[g])};
      auto seed = static_cast<std::uint64_t>(*errors.seed);
      for (long i = 0; i < z; ++i)
        f.push_back(fpt / 3.0 * sampleNormal(seed, static_cast<std::uint64_t>(g), static_cast<std::uint64_t>(i)));
      double most = 0;
      for (double v : f)
        most = std::max(most, std::fabs(v));
      prov.push_back(
          fmt::format("loaded mesh: the {}'s {} single pitch deviations drawn (seed {}) from f_pt {} as three standard "
                      "deviations, the largest {}",
                      names[g], z, seed, um(fpt), um(most)));
    } else {
      f.assign(static_cast<size_t>(z), 0.0);
    }
    in.toothLateness[g] = toothLateness(f, cosAlphaT);
  }
  // Each tooth's own position takes the place of the adverse base pitch deviation every pair
  // had (the two would count the pitch twice).
  if (in.sep.basePitch != 0)
    prov.push_back(fmt::format(
        "loaded mesh: the teeth's own pitch deviations replace the adverse base pitch deviation of {} per pair",
        um(in.sep.basePitch)));
  in.sep.basePitch = 0;
  long z1 = static_cast<long>(in.toothLateness[0].size()), z2 = static_cast<long>(in.toothLateness[1].size());
  long periods = std::lcm(z1, z2);
  // The table grows with the hunting period: a bound on its work, not on the pairs' count.
  double work = static_cast<double>(periods) * in.positions * in.slices;
  // The tables hold every position of every period: a bound on their size as well.
  if (static_cast<double>(periods) * in.positions > 1e7)
    throw SceneFailure{
        fmt::format("the loaded mesh over the hunting period ({} mesh periods) would hold {:.3g} positions; give fewer "
                    "`positions` (at most 1e7 over the hunting period)",
                    periods, static_cast<double>(periods) * in.positions)};
  if (work > 4e8)
    throw SceneFailure{
        fmt::format("the loaded mesh over the hunting period ({} mesh periods) would take {:.3g} slice positions; give "
                    "fewer `positions` or `slices` (at most 4e8 together)",
                    periods, work)};
  prov.push_back(fmt::format(
      "loaded mesh: over the hunting period, lcm({}, {}) = {} mesh periods, the teeth's pitch deviations along the "
      "line of action (times cos alpha_t {:.4f})",
      z1, z2, periods, cosAlphaT));
}

} // namespace gbx::rt::dyn
