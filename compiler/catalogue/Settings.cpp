#include "catalogue/Settings.h"

#include "catalogue/Budgets.h"
#include "catalogue/Methods.h"

namespace gbx::cat {

using namespace units::dims;
using namespace rows;

const std::vector<AttrSpec>& gearboxQuantities() {
  static const std::vector<AttrSpec> q = attrs(
      derived("ratio", none, "overall reduction, the product of the stage ratios"),
      derived("input_speed", angularSpeed, "input shaft speed"),
      derived("output_speed", angularSpeed, "output shaft speed"), derived("input_torque", torque, "input torque"),
      derived("output_torque", torque, "output torque"), derived("power", power, "transmitted power"));
  return q;
}

const std::vector<AttrSpec>& operatingSettings() {
  static const std::vector<AttrSpec> q =
      attrs(pos("input_speed", angularSpeed, "input shaft speed"),
            pos("output_speed", angularSpeed, "output shaft speed"), pos("input_torque", torque, "input torque"),
            pos("output_torque", torque, "output torque"), pos("power", power, "transmitted power"));
  return q;
}

const std::vector<AttrSpec>& materialProperties() {
  static const std::vector<AttrSpec> q = attrs(
      required(pos("youngs_modulus", pressure, "Young's modulus")), required(pos("poisson", none, "Poisson's ratio")),
      required(pos("density", density, "density")), pos("shear_modulus", pressure, "shear modulus"),
      pos("sigma_hlim", pressure, "ISO 6336-5 allowable contact stress number"),
      pos("sigma_flim", pressure, "ISO 6336-5 nominal bending stress number"),
      pos("hardness", none, "surface hardness (HRC or HV, as the material states)"),
      pos("brinell_hardness", none,
          "Brinell hardness HB of a through-hardened steel (Z_W of ISO 6336-2 when it meshes with a harder pinion)"),
      symbol("treatment", {"case_hardened", "nitrided", "through_hardened"},
             "heat treatment: selects the ISO 6336 life curves, running-in, notch sensitivity and size factors"),
      hinted(
          pos("tensile_strength", pressure, "tensile strength sigma_B at DIN 743's reference diameter 16 mm (shafts)"),
          "MPa"),
      hinted(pos("yield_strength", pressure, "yield strength sigma_S at DIN 743's reference diameter 16 mm (shafts)"),
             "MPa"),
      symbol("steel_group", {"quenched_tempered", "case_hardening", "structural", "nitriding"},
             "DIN 743-2 steel group: how the strengths fall with the heat-treatment diameter (K1)"));
  return q;
}

const std::vector<AttrSpec>& sceneSettings() {
  static const std::vector<AttrSpec> s = [] {
    auto t = [](std::string n, std::string m) {
      auto a = pos(std::move(n), time, std::move(m));
      a.meshPeriods = true;
      return a;
    };
    return attrs(
        t("settle", "transient discarded before recording"), t("record", "recorded steady-state window"),
        withDefault(budgeted(count("samples", "samples per recorded mesh period"), budget::kSamplesPerPeriod),
                    num(160)),
        t("duration", "simulated time from rest"), t("ramp", "smooth start-up time of the drive speed"),
        symbol("steady_state", {"periodic", "harmonic_balance"},
               "solve for the periodic response directly: `periodic` by shooting with Newton (Floquet multipliers), "
               "`harmonic_balance` as a Fourier series (Hill's multipliers)"),
        budgeted(
            count("harmonics",
                  "harmonic balance: the orbit's harmonics (default: doubled from 2 until the orbit moves less than "
                  "rtol of its scale)"),
            budget::kBalanceHarmonics));
  }();
  return s;
}

const std::vector<AttrSpec>& accuracySettings() {
  static const std::vector<AttrSpec> s = [] {
    auto step = pos("max_step", time, "largest step");
    step.meshPeriods = true;
    auto hmin = pos("min_step", time, "smallest step");
    hmin.meshPeriods = true;
    return attrs(symbol("method", methodNames(), "integration method"),
                 withDefault(pos("rtol", none, "relative tolerance"), num(1, 1000000)),
                 pos("atol", none, "absolute tolerance (SI units of the state)"), step, hmin,
                 budgeted(count("max_steps", "step limit"), budget::kMaxSteps));
  }();
  return s;
}

const std::vector<AttrSpec>& splitSettings() {
  static const std::vector<AttrSpec> s = [] {
    auto between = in("between", none, "the stage whose wheel feeds the branches");
    between.value = ValueKind::Stage;
    between.required = true;
    return attrs(between, withDefault(budgeted(count("branches", "number of branches"), budget::kBranches), num(2)),
                 required(pos("torsion_shaft.length", length, "torsion shaft length")),
                 required(pos("torsion_shaft.diameter", length, "torsion shaft diameter")),
                 withDefault(pos("torsion_shaft.shear_modulus", pressure, "shear modulus G"), num(80000000000)),
                 required(in("backlash_difference", length, "difference of circumferential backlash between branches")),
                 required(symbol("install", {"free", "preloaded"}, "installation method")),
                 in("preload_torque", torque, "installation torque M0 (preloaded installation)"));
  }();
  return s;
}

const std::vector<AttrSpec>& splitOutputs() {
  static const std::vector<AttrSpec> s =
      attrs(derived("twist", angle, "torsion-shaft twist at full load"),
            derived("displacement", length, "circumferential displacement at the stage-I wheel"),
            derived("imbalance", none, "load imbalance between the branches"),
            derived("branch_torque", torque, "torque in one branch"),
            derived("preload_displacement", length, "backlash taken up by the preload"));
  return s;
}

const std::vector<AttrSpec>& sweepSettings() {
  static const std::vector<AttrSpec> s = attrs(
      symbol("continuation", {"natural", "arclength"},
             "how a sweep of a scene follows its periodic response: point by point, or by arclength through folds"));
  return s;
}

const std::vector<AttrSpec>& toleranceSettings() {
  // Whole numbers whose range message names both ends (a count would say "positive" first).
  static const std::vector<AttrSpec> s = attrs(
      budgeted(
          bounded(whole("samples", "Monte Carlo samples drawn instead of the box's corners"), num(2), std::nullopt),
          budget::kToleranceSamples),
      symbol("distribution", {"normal", "uniform"},
             "how a deviation is drawn (normal unless given): normal with the amount as three standard deviations, "
             "or uniform between the bounds"),
      bounded(whole("seed", "the random stream's seed: the same seed draws the same samples"), num(0),
              num(4294967295)));
  return s;
}

const std::vector<AttrSpec>& workPrecisionSettings() {
  static const std::vector<AttrSpec> s =
      attrs(pos("rtol", none, "relative tolerances to run"),
            budgeted(count("harmonics", "harmonic counts to run"), budget::kHarmonics),
            symbol("methods", methodNames(), "methods to compare"));
  return s;
}

const std::vector<std::string>& modificationTargets() {
  static const std::vector<std::string> t = {
      "tip_relief",    "tip_relief_height",   "root_relief",  "root_relief_height", "profile_crowning",
      "lead_crowning", "thermal_lead_relief", "end_relief",   "end_relief_width",   "helix_slope",
  };
  return t;
}

const std::vector<BuiltinSpec>& modifyBuiltins() {
  static const std::vector<BuiltinSpec> b = {
      {"load_deflection", length, false},
      {"pitch_deviation", length, true},
      {"profile_deviation", length, true},
      {"whole_depth", length, false},
      {"bending_deflection", length, true},
      {"torsion_deflection", length, true},
      {"pitch_line_velocity", velocity, false},
      {"mesh_stiffness", pressure, false},
      {"tangential_force", force, false},
      {"face_width", length, false},
  };
  return b;
}

bool dependsOnOperatingPoint(Q key) {
  switch (key) {
  case Q::InputSpeed:
  case Q::OutputSpeed:
  case Q::InputTorque:
  case Q::OutputTorque:
  case Q::Power:
  case Q::MeshFrequency:
  case Q::PitchLineVelocity:
  case Q::TangentialForce:
  case Q::LoadDeflection:
  case Q::Speed:
  case Q::Torque:
  case Q::CarrierSpeed:
  case Q::BranchTorque:
  case Q::Twist:
  case Q::Displacement:
  case Q::Imbalance: return true;
  default: return isRatingQuantity(key);
  }
}

bool isRatingQuantity(Q key) {
  auto k = static_cast<int>(key);
  return (k >= static_cast<int>(Q::ContactSafety) && k <= static_cast<int>(Q::YM)) || key == Q::ContactDamage ||
         key == Q::BendingDamage || scuffingInput(key) != Q::None ||
         (k >= static_cast<int>(Q::ZMB) && k <= static_cast<int>(Q::YSa)) || key == Q::BearingLoad ||
         key == Q::BearingLife || key == Q::BearingModifiedLife;
}

Q scuffingInput(Q key) {
  auto k = static_cast<int>(key);
  if (k >= static_cast<int>(Q::ScuffingSafety) && k <= static_cast<int>(Q::BulkTemperature)) return Q::RatingFzgLoadStage;
  if (k >= static_cast<int>(Q::MicropittingSafety) && k <= static_cast<int>(Q::PermissibleFilmThickness)) return Q::RatingMicropittingLoadStage;
  return Q::None;
}

const std::vector<FlagSpec>& flags() {
  static const std::vector<FlagSpec> rows = {
      {Flag::Plot, "plot", "draw the study's outputs against the swept quantity (with -o DIR)"},
      {Flag::Ranges, "ranges", "show each column's attainable interval over the design's freedoms"},
  };
  return rows;
}

const FlagSpec* findFlag(const std::string& word) {
  for (const auto& f : flags())
    if (word == f.word) return &f;
  return nullptr;
}

Block blockOf(std::string_view word) {
  static constexpr std::pair<std::string_view, Block> rows[] = {
      {"tolerances", Block::Tolerances}, {"accuracy", Block::Accuracy}, {"work_precision", Block::WorkPrecision}};
  for (const auto& [w, b] : rows)
    if (w == word) return b;
  return Block::Unknown;
}

} // namespace gbx::cat
