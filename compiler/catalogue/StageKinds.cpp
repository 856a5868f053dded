#include "catalogue/StageKinds.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <mutex>
#include <optional>

#include "catalogue/Budgets.h"
#include "catalogue/Shafts.h"

namespace gbx::cat {

using namespace units::dims;
using namespace rows;
using units::Number;

namespace {

// Rows appended to a table, moved.
void append(std::vector<AttrSpec>& to, std::vector<AttrSpec> rows) {
  for (auto& r : rows)
    to.push_back(std::move(r));
}

AttrSpec material() {
  auto a = in("material", none, "gear material (a `material` declaration)");
  a.value = ValueKind::Material;
  return a;
}

AttrSpec exampled(AttrSpec a, std::string example) {
  a.example = std::move(example);
  return a;
}

std::vector<AttrSpec> commonDerived() {
  return attrs(derived("ratio", none, "reduction: input speed / output speed"),
               derived("input_speed", angularSpeed, "speed of the stage's input member"),
               derived("output_speed", angularSpeed, "speed of the stage's output member"),
               derived("input_torque", torque, "torque on the stage's input member"),
               derived("output_torque", torque, "torque on the stage's output member"),
               derived("mesh_frequency", frequency, "tooth-mesh frequency"));
}

std::vector<AttrSpec> cylindricalGearAttrs() {
  return attrs(required(count("z", "tooth count")), in("shift", none, "profile shift coefficient"),
               pos("pitch_deviation", length, "single (base) pitch deviation"),
               pos("profile_deviation", length, "total profile deviation"),
               bounded(in("bending_deflection", length, "shaft bending deflection across the face (0: a stiff shaft)"),
                       num(0), std::nullopt),
               bounded(in("torsion_deflection", length, "torsional wind-up across the face (0: a stiff shaft)"), num(0),
                       std::nullopt),
               pos("inertia", inertia, "mass moment of inertia about the gear axis"),
               pos("bearing_span", length, "distance between the gear's bearings"),
               pos("shaft_diameter", length, "diameter of the gear's shaft"),
               derived("d", length, "reference diameter"), derived("base_radius", length, "base circle radius"),
               derived("tip_radius", length, "tip circle radius"), derived("speed", angularSpeed, "rotational speed"),
               derived("torque", torque, "transmitted torque"));
}

// Gears of planetary and idler stages: their tip radius has no formula here (the ring is
// internal), so it is not offered.
std::vector<AttrSpec> plainGearAttrs() {
  auto g = cylindricalGearAttrs();
  g.erase(std::remove_if(g.begin(), g.end(), [](const AttrSpec& a) { return a.key == Q::TipRadius; }), g.end());
  return g;
}

// ISO 1328-1:1995 accuracy grades run from 0 to 12.
AttrSpec accuracyRow() {
  auto a = bounded(count("accuracy", "ISO 1328-1 accuracy grade"), num(0), num(12));
  a.positive = false;
  return a;
}

// The `rating { … }` block (docs/rating.md): ISO 6336 inputs of the stage's meshes.
// Absent values take the defaults their meaning names, applied by the rating itself.
std::vector<AttrSpec> ratingInputs() {
  const Dim viscosity{2, 0, -1, 0};
  auto factor = [](std::string n, std::string meaning) {
    return bounded(pos(std::move(n), none, std::move(meaning)), num(1), std::nullopt);
  };
  auto um = [](std::int64_t v) { return num(v, 1000000); };
  return attrs(
      factor("rating.application_factor", "application factor K_A (default 1.0)"),
      hinted(pos("rating.life", time, "required service life"), "h"),
      symbol("rating.life_curve", {"normal", "optimum"},
             "life-factor curves beyond the endurance knee (default normal: Z_NT, Y_NT >= 0.85)"),
      hinted(pos("rating.lubricant.viscosity_40", viscosity, "lubricant kinematic viscosity at 40 degC"), "mm^2/s"),
      // Scuffing and micropitting (ISO/TS 6336-20, -21, -22; docs/rating.md).
      hinted(pos("rating.lubricant.viscosity_100", viscosity,
                 "lubricant kinematic viscosity at 100 degC (with viscosity_40: the ASTM D341 line)"),
             "mm^2/s"),
      hinted(bounded(pos("rating.lubricant.density", units::dims::density,
                         "lubricant density at 15 degC (default 890 kg/m^3)"),
                     num(600), num(1200)),
             "kg/m^3"),
      hinted(bounded(pos("rating.lubricant.oil_temperature", units::dims::temperature,
                         "oil temperature: sump (dip) or injection"),
                     num(22315, 100), num(47315, 100)),
             "degC"),
      bounded(count("rating.lubricant.fzg_load_stage", "FZG A/8.3/90 failure load stage of the oil (scuffing)"), num(1),
              num(14)),
      bounded(
          count("rating.lubricant.micropitting_load_stage", "FVA 54/7 failure load stage of the oil (micropitting)"),
          num(1), num(12)),
      symbol("rating.lubricant.base", {"mineral", "polyalphaolefin", "polyglycol", "phosphate_ester", "traction"},
             "base oil (default mineral): the lubricant factor of the friction coefficient"),
      symbol("rating.lubricant.supply", {"dip", "injection"},
             "how the oil reaches the mesh (default dip): the lubrication factor X_S of the bulk temperature"),
      hinted(bounded(pos("rating.roughness.flank", length, "flank arithmetic mean roughness Ra"), std::nullopt, um(25)),
             "um"),
      hinted(bounded(pos("rating.roughness.root", length, "root arithmetic mean roughness Ra"), std::nullopt, um(25)),
             "um"),
      hinted(bounded(pos("rating.roughness.flank_rz", length, "flank mean peak-to-valley roughness Rz (default 6 Ra)"),
                     std::nullopt, um(150)),
             "um"),
      hinted(bounded(pos("rating.roughness.root_rz", length, "root mean peak-to-valley roughness Rz (default 6 Ra)"),
                     std::nullopt, um(150)),
             "um"),
      pos("rating.basic_rack.addendum", none, "basic rack addendum h_aP* (default 1.0)"),
      pos("rating.basic_rack.dedendum", none, "basic rack dedendum h_fP* (default 1.25)"),
      pos("rating.basic_rack.root_radius", none, "basic rack root radius rho_fP* (default 0.38)"),
      [&] {
        auto a = factor("rating.face_load_factor", "face load factor K_Hbeta: given, or `contact_analysis` (from the "
                                                   "loaded mesh's line load); method B when absent");
        a.symbols = {"contact_analysis"};
        return a;
      }(),
      [&] {
        auto a = factor(
            "rating.dynamic_factor",
            "dynamic factor K_v: given, or `scene NAME` (method A from that periodic scene); method B when absent");
        a.sceneRef = true;
        return a;
      }(),
      factor("rating.transverse_load_factor", "transverse load factor K_Halpha, given (method B when absent)"),
      factor("rating.mesh_load_factor", "mesh load factor K_gamma of multi-path drives (default 1.0; planetary: by the "
                                        "number of planets, IEC 61400-4)"),
      hinted(in("rating.mesh_misalignment", length,
                "mesh misalignment from manufacture f_ma (default the helix slope tolerance f_Hbeta)"),
             "um"),
      pos("rating.min_safety.contact", none, "minimum contact safety S_Hmin (default 1.0)"),
      pos("rating.min_safety.bending", none, "minimum bending safety S_Fmin (default 1.0)"),
      pos("rating.min_safety.scuffing", none, "minimum scuffing safety S_Bmin, flash temperature (default 1.5)"),
      pos("rating.min_safety.integral_scuffing", none,
          "minimum scuffing safety S_intS,min, integral temperature (default 1.8)"),
      pos("rating.min_safety.micropitting", none, "minimum micropitting safety S_lambda,min (default 1.0)"));
}

// A planetary stage's rating inputs: K_gamma may come from the planets' load sharing, with
// the sun held or floating (docs/rating.md "Load sharing of a planetary stage").
std::vector<AttrSpec> planetaryRatingInputs() {
  auto a = ratingInputs();
  for (auto& r : a)
    if (r.key == Q::RatingMeshLoadFactor) {
      r.symbols = {"load_sharing"};
      r.meaning = "mesh load factor K_gamma: given, or `load_sharing` (from the planets' mesh stiffnesses, pin errors "
                  "and the sun's "
                  "support); by the number of planets (IEC 61400-4) when absent";
    }
  for (const auto& r : ratingInputs())
    if (r.key == Q::RatingDynamicFactor) {
      auto kv = r;
      kv.name = "rating.ring_planet.dynamic_factor";
      kv.key = Q::RatingRingPlanetDynamicFactor;
      kv.sceneRef = false;
      kv.meaning =
          "dynamic factor K_v of the planet-ring mesh, where it differs from `dynamic_factor` (the sun-planet mesh's)";
      a.push_back(kv);
    }
  a.push_back(
      symbol("sun_support", {"floating", "fixed"},
             "the sun's support (default fixed): floating leaves its two translations free, as a spline-coupled sun"));
  return a;
}

// What a planetary stage's gears give beyond the plain gear's: a planet's pin position error
// (the load sharing), the ring's pinion-type cutter (its tooth root, ISO 6336-3).
// A shaft bearing's kinds, in their order (the runtime reads a planet bearing's as the same
// ISO 281 kind).
std::vector<std::string> shaftBearingKinds() {
  for (const auto& a : bearingSettings())
    if (a.key == Q::BearingKind) return a.symbols;
  return {};
}

std::vector<AttrSpec> planetaryGearAttrs() {
  auto of = [](std::string gear, AttrSpec a, std::string example) {
    a.exampleGear = std::move(gear);
    a.example = std::move(example);
    return a;
  };
  return attrs(
      of("planet",
         hinted(in("pin_error", length,
                   "tangential position error of a planet's pin (the first planet's; positive: displaced the way the "
                   "sun pushes it, "
                   "so it carries less)"),
                "um"),
         "20 um"),
      of("ring",
         bounded(
             count("cutter.teeth", "teeth of the pinion-type cutter that cuts the ring (its tooth root, ISO 6336-3)"),
             num(8), std::nullopt),
         "36"),
      of("ring", in("cutter.shift", none, "profile shift coefficient of the ring's cutter (default 0)"), "0"),
      // Each planet's bearings (docs/rating.md "Planet bearings"): ISO 281 at the planet's
      // speed relative to the carrier, the load shared equally between `count` bearings.
      of("planet",
         symbol("bearing.kind", shaftBearingKinds(),
                "type of each planet's bearings: the ISO 281 life exponent (ball 3, roller 10/3) and a_ISO curve"),
         "cylindrical_roller"),
      of("planet", hinted(pos("bearing.C", force, "basic dynamic load rating of one planet bearing"), "kN"), "2800 kN"),
      of("planet", hinted(pos("bearing.C0", force, "basic static load rating of one planet bearing"), "kN"), "4300 kN"),
      of("planet",
         bounded(count("bearing.count", "bearings per planet, sharing its load equally (default 1)"), num(1), num(4)),
         "2"),
      of("planet",
         hinted(pos("bearing.pitch_diameter", length,
                    "rolling-element pitch diameter D_pw of a planet bearing (kappa, C_u; for the modified life)"),
                "mm"),
         "500 mm"),
      of("planet",
         bounded(pos("bearing.contamination", none,
                     "contamination factor e_C of ISO 281 (default 0.5, normal cleanliness)"),
                 std::nullopt, num(1)),
         "0.5"),
      of("planet",
         derived(
             "bearing_load", force,
             "radial load on each planet bearing: the planet's two mesh forces summed, times K_gamma, over `count`"),
         ""),
      of("planet", hinted(derived("bearing_life", time, "basic rating life L10h of a planet bearing (ISO 281)"), "h"),
         ""),
      of("planet",
         hinted(derived("bearing_modified_life", time,
                        "modified rating life L_nmh = a1 a_ISO L10h, kappa from the rating's lubricant at its oil "
                        "temperature"),
                "h"),
         ""),
      of("ring",
         bounded(pos("cutter.tip_radius", none,
                     "tip radius of the ring's cutter as a share of the module (default the basic rack's root radius)"),
                 std::nullopt, num(1)),
         "0.3"));
}

std::vector<AttrSpec> ratingStageQuantities() {
  return attrs(
      derived("K_v", none, "dynamic factor (ISO 6336-1 method B)"),
      derived("K_Hbeta", none, "face load factor for contact stress"),
      derived("K_Fbeta", none, "face load factor for tooth root stress"),
      derived("K_Halpha", none, "transverse load factor for contact stress"),
      derived("K_Falpha", none, "transverse load factor for tooth root stress"), derived("Z_H", none, "zone factor"),
      derived("Z_E", none,
              "elasticity factor, as a number in sqrt(N/mm^2) (a unit the dimension system has no half powers for)"),
      derived("Z_eps", none, "contact ratio factor"),
      derived("Z_beta", none, "helix angle factor (Corrigendum 1: 1/sqrt(cos beta))"),
      derived("scuffing_safety", none, "scuffing safety S_B by the flash temperature (ISO/TS 6336-20)"),
      derived("integral_scuffing_safety", none, "scuffing safety S_intS by the integral temperature (ISO/TS 6336-21)"),
      derived("contact_temperature", units::dims::temperature,
              "largest contact temperature theta_B along the path of contact"),
      derived("integral_temperature", units::dims::temperature, "integral temperature theta_int"),
      derived("scuffing_temperature", units::dims::temperature,
              "scuffing temperature theta_S of the oil (FZG load stage)"),
      derived("bulk_temperature", units::dims::temperature, "bulk temperature theta_M of the flash temperature method"),
      derived("micropitting_safety", none, "micropitting safety S_lambda (ISO/TS 6336-22 method B)"),
      derived("specific_film_thickness", none,
              "smallest specific lubricant film thickness lambda_GF,min along the path of contact"),
      derived("permissible_film_thickness", none, "permissible specific film thickness lambda_GFP (FVA load stage)"));
}

// Gear inputs only the rating reads.
std::vector<AttrSpec> ratingGearExtras() {
  auto own = material();
  own.meaning = "this gear's material, where it differs from the stage's `material` (its limits, life curves and Z_W)";
  return attrs(
      own,
      pos("tip_diameter", length, "tip diameter, given (else from the basic rack, the shift and the tip alteration)"),
      pos("profile_form_deviation", length, "profile form deviation f_f_alpha (else ISO 1328-1 from the grade)"),
      pos("helix_slope_deviation", length, "helix slope deviation f_H_beta (else ISO 1328-1 from the grade)"),
      pos("bore_diameter", length, "inner diameter of the gear blank (0: solid; for the reduced mass of K_v)"),
      pos("web_thickness", length, "web thickness b_s of a webbed gear blank (for C_R; solid when absent)"),
      pos("rim_thickness", length,
          "rim thickness s_R under the root: of a webbed gear blank (for C_R), of a ring (for Y_B)"),
      hinted(bounded(pos("roughness.flank_rz", length,
                         "this gear's flank Rz, where it differs from the rating's (the pair's is the mean)"),
                     std::nullopt, num(150, 1000000)),
             "um"),
      hinted(bounded(pos("roughness.root_rz", length, "this gear's root Rz, where it differs from the rating's"),
                     std::nullopt, num(150, 1000000)),
             "um"),
      exampled(hinted(in("upper_thickness_allowance", length,
                         "upper normal tooth-thickness allowance A_sne (thinner teeth: negative; for the backlash of a "
                         "rated stage)"),
                      "um"),
               "-50 um"),
      exampled(hinted(in("lower_thickness_allowance", length,
                         "lower normal tooth-thickness allowance A_sni (with the upper one)"),
                      "um"),
               "-90 um"));
}

std::vector<AttrSpec> ratingGearQuantities() {
  return attrs(
      derived("contact_safety", none, "safety factor for contact stress S_H"),
      derived("bending_safety", none, "safety factor for bending stress S_F"),
      derived("contact_stress", pressure, "contact stress sigma_H"),
      derived("bending_stress", pressure, "tooth root stress sigma_F"),
      derived("permissible_contact_stress", pressure, "permissible contact stress sigma_HP"),
      derived("permissible_bending_stress", pressure, "permissible bending stress sigma_FP"),
      derived("Z_NT", none, "life factor for contact stress"), derived("Z_L", none, "lubricant factor"),
      derived("Z_v", none, "velocity factor"), derived("Z_R", none, "roughness factor for contact stress"),
      derived("Z_W", none, "work hardening factor"), derived("Z_X", none, "size factor for contact stress"),
      derived("Z_B", none, "single pair tooth contact factor (Z_B of the pinion, Z_D of the wheel)"),
      derived("Z_D", none, "single pair tooth contact factor (Z_B of the pinion, Z_D of the wheel)"),
      derived("Y_F", none, "tooth form factor (method B)"), derived("Y_S", none, "stress correction factor (method B)"),
      derived("Y_beta", none, "helix angle factor for bending"),
      derived("Y_NT", none, "life factor for tooth root stress"),
      derived("Y_deltarelT", none, "relative notch sensitivity factor"),
      derived("Y_RrelT", none, "relative surface factor"), derived("Y_X", none, "size factor for tooth root stress"),
      derived("Y_M", none, "mean stress factor (0.7 for a gear loaded on both flanks)"),
      derived("contact_damage", none,
              "Miner's sum for the flank over the life (the load spectrum's, else the operating torque's; 1: used up)"),
      derived("bending_damage", none,
              "Miner's sum for the tooth root over the life (the load spectrum's, else the operating torque's; 1: used "
              "up)"));
}

// Bevel stages (docs/rating.md): the ISO 23509 geometry the rating needs, the ISO 10300
// rating inputs that apply to bevel gears, and the quantities the rating computes.
std::vector<AttrSpec> bevelStageAttrs() {
  std::vector<AttrSpec> a = attrs(
      [] {
        auto a = pos("outer_cone_distance", length,
                     "outer cone distance R_e (else from face_width and face_ratio, or from mean_normal_module)");
        a.role = AttrRole::Either;
        return a;
      }(),
      derived("mean_cone_distance", length, "mean cone distance R_m = R_e - b/2"),
      bounded(pos("coast_pressure_angle", angle,
                  "normal pressure angle of the coast flank (default, and the only one rated: the drive flank's)"),
              deg(10), deg(35)),
      pos("cutter_radius", length,
          "cutter radius r_c0: the lengthwise curvature factor K_F0 of the root stress (1 when absent)"),
      bounded(in("offset", length,
                 "hypoid offset a; only 0: the rating of hypoid gears (ISO 10300 with offset) is not implemented"),
              num(0), num(0)),
      derived("virtual_eps_alpha", none, "transverse contact ratio of the virtual cylindrical gears eps_valpha"),
      derived("virtual_eps_beta", none, "face contact ratio of the virtual cylindrical gears eps_vbeta"),
      derived("virtual_contact_ratio", none, "total contact ratio of the virtual cylindrical gears eps_vgamma"),
      derived("tangential_force", force, "nominal tangential force at the mean diameter F_mt"),
      derived("pitch_line_velocity", velocity, "pitch-line velocity at the mean diameter v_mt"));
  for (auto& r : ratingInputs()) {
    // What ISO 10300 method B1 reads of the `rating` block; scuffing, micropitting, mesh load
    // sharing and the cylindrical rack's root radius belong to ISO 6336.
    switch (r.key) {
    case Q::RatingApplicationFactor:
    case Q::RatingLife:
    case Q::RatingLifeCurve:
    case Q::RatingViscosity40:
    case Q::RatingRoughnessFlank:
    case Q::RatingRoughnessRoot:
    case Q::RatingRoughnessFlankRz:
    case Q::RatingRoughnessRootRz:
    case Q::RatingRackAddendum:
    case Q::RatingRackDedendum:
    case Q::RatingTransverseLoadFactor:
    case Q::RatingMinContact:
    case Q::RatingMinBending: a.push_back(std::move(r)); break;
    case Q::RatingFaceLoadFactor:
    case Q::RatingDynamicFactor:
      r.symbols.clear();
      r.sceneRef = false;
      r.meaning = r.key == Q::RatingDynamicFactor
                      ? "dynamic factor K_v, given (ISO 10300-1 method B when absent)"
                      : "face load factor K_Hbeta, given (K_Hbeta-C from the mounting when absent)";
      a.push_back(std::move(r));
      break;
    default: break;
    }
  }
  a.push_back(symbol("rating.mounting", {"both_straddle", "one_cantilever", "both_cantilever"},
                     "bearing arrangement of the pair (default both_straddle): K_Hbeta-be of ISO 10300-1"));
  a.push_back(bounded(pos("rating.contact_pattern", none,
                          "effective face width over face width b_eff/b, checked under light load (default 0.85)"),
                      num(85, 100), num(1)));
  for (auto& q : attrs(derived("K_v", none, "dynamic factor (ISO 10300-1 method B)"),
                       derived("K_Hbeta", none, "face load factor for contact stress K_Hbeta-C"),
                       derived("K_Fbeta", none, "face load factor for tooth root stress"),
                       derived("K_Halpha", none, "transverse load factor for contact stress (method B)"),
                       derived("K_Falpha", none, "transverse load factor for tooth root stress (method B)"),
                       derived("Z_MB", none, "mid-zone factor Z_M-B"),
                       derived("Z_LS", none, "load sharing factor for contact stress"),
                       derived("Z_E", none, "elasticity factor, as a number in sqrt(N/mm^2)"),
                       derived("Z_beta", none, "spiral angle factor for contact stress"),
                       derived("Y_eps", none, "contact ratio factor for bending"),
                       derived("Y_LS", none, "load sharing factor for bending"),
                       derived("Y_BS", none, "bevel spiral angle factor")))
    a.push_back(std::move(q));
  return a;
}

std::vector<AttrSpec> bevelGearAttrs() {
  std::vector<AttrSpec> g = attrs(
      in("shift", none, "mean profile shift coefficient x_hm (the wheel's is usually the pinion's negative)"),
      in("thickness_modification", none, "thickness modification coefficient x_sm"),
      pos("tool_edge_radius", length, "edge radius of the cutter blade rho_a0 (default 0.2 m_mn)"),
      pos("pitch_deviation", length, "single pitch deviation f_pt"),
      derived("mean_diameter", length, "mean pitch diameter d_m"),
      derived("outer_pitch_diameter", length, "outer pitch diameter d_e"),
      derived("mean_addendum", length, "mean addendum h_am"), derived("mean_dedendum", length, "mean dedendum h_fm"),
      derived("virtual_z", none, "tooth count of the virtual cylindrical gear z_v = z / cos(delta)"),
      derived("Y_Fa", none, "tooth form factor for load at the tip"),
      derived("Y_Sa", none, "stress correction factor for load at the tip"));
  // A gear's own material, and the cylindrical gear's safeties, stresses and material factors
  // that ISO 10300 shares.
  for (auto& q : ratingGearExtras())
    if (q.key == Q::Material) g.push_back(std::move(q));
  for (auto& q : ratingGearQuantities())
    switch (q.key) {
    case Q::ZB:
    case Q::ZD:
    case Q::YF:
    case Q::YS:
    case Q::Ybeta:
    case Q::YM:
    case Q::ContactDamage:
    case Q::BendingDamage: break;
    default: g.push_back(std::move(q));
    }
  return g;
}

std::vector<AttrSpec> cylindricalStage(bool helical) {
  std::vector<AttrSpec> a = attrs(
      pos("normal_module", length, "normal module"),
      withDefault(bounded(pos("pressure_angle", angle, "normal pressure angle"), deg(10), deg(35)), deg(20)),
      pos("face_width", length, "face width"), pos("center_distance", length, "centre distance"),
      hinted(bounded(in("center_distance_allowance", length,
                        "centre distance allowance A_a, either way (+-; for the backlash)"),
                     num(0), std::nullopt),
             "um"),
      material(), accuracyRow(), pos("mesh_stiffness", pressure, "mesh stiffness per unit face width (c_gamma)"),
      derived("pitch_line_velocity", velocity, "pitch-line velocity"),
      derived("eps_alpha", none, "transverse contact ratio"), derived("eps_beta", none, "overlap ratio"),
      derived("mass", units::dims::mass,
              "gear-pair mass of two solid discs at the reference diameters: (pi/4) m_n^2 z1^2 b (1 + u^2) rho / "
              "cos^2 beta"),
      derived("whole_depth", length, "whole depth 2.25 mn"),
      derived("sliding_balance", none,
              "specific-sliding balance: the difference of the two gears' largest specific sliding, 0 when balanced"),
      derived("working_pressure_angle", angle, "transverse working pressure angle"),
      derived("tangential_force", force,
              "nominal tangential force F_t = 2 T / d at the reference circle (ISO 6336; a shaft takes its forces at "
              "the working pitch circle)"),
      derived("load_deflection", length, "elastic deflection w_t / c_gamma"),
      derived("total_contact_ratio", none, "eps_alpha + eps_beta"));
  a[3].role = AttrRole::Either;
  // The hand of a helix is not a sign; beyond 45 deg no parallel-axis pair is made or rated.
  if (helical)
    a.insert(a.begin() + 1,
             required(bounded(in("helix_angle", angle, "helix angle at the reference circle"), deg(0), deg(45))));
  append(a, commonDerived());
  // The sense of the pinion's wind-up and bending mismatch across the face (docs/rating.md).
  if (helical)
    a.push_back(symbol(
        "helix_hand", {"right", "left"},
        "the pinion's helix hand: the sense of its bending mismatch across the face and of its thrust on a shaft"));
  a.push_back(symbol("torque_side", {"coupling", "free"},
                     "the end of the pinion's face where the torque enters: the sense of its wind-up"));
  append(a, ratingInputs());
  append(a, ratingStageQuantities());
  return a;
}

std::vector<AttrSpec> cylindricalGear() {
  auto g = cylindricalGearAttrs();
  append(g, ratingGearExtras());
  append(g, ratingGearQuantities());
  return g;
}

KindSpec bevelKind() {
  std::vector<AttrSpec> a = attrs(
      in("spiral_angle", angle, "mean spiral angle beta_m"),
      pos("face_ratio", none, "face width over outer cone distance b/Re (else from both)"),
      withDefault(pos("shaft_angle", angle, "shaft angle"), deg(90)),
      count("blade_groups", "cutter blade groups (face hobbing)"),
      pos("mean_normal_module", length, "mean normal module (else from the outer cone distance)"),
      pos("face_width", length, "face width (else face_ratio times the outer cone distance)"),
      withDefault(bounded(pos("pressure_angle", angle, "normal pressure angle (the drive flank's)"), deg(10), deg(35)),
                  deg(20)),
      material(), accuracyRow(), derived("mmn_b", none, "mean normal module over face width (docs/search.md)"));
  a[1].role = a[4].role = a[5].role = AttrRole::Either;
  a.insert(a.begin() + 1, symbol("spiral_hand", {"right", "left"},
                                 "the pinion's spiral hand: the sense of the spiral's thrust on a shaft"));
  append(a, commonDerived());
  append(a, bevelStageAttrs());
  std::vector<AttrSpec> g =
      attrs(required(count("z", "tooth count")), derived("cone_angle", angle, "pitch cone angle"),
            derived("speed", angularSpeed, "rotational speed"), derived("torque", torque, "transmitted torque"),
            pos("inertia", inertia, "mass moment of inertia about the gear axis"));
  append(g, bevelGearAttrs());
  return {ir::StageKind::Bevel, "bevel", {"pinion", "wheel"}, std::move(a), std::move(g)};
}

KindSpec planetaryKind() {
  std::vector<AttrSpec> a =
      attrs(required(budgeted(count("planets", "number of planets, equally spaced"), budget::kPlanets)),
            pos("module", length, "module"), withDefault(pos("pressure_angle", angle, "pressure angle"), deg(20)),
            pos("face_width", length, "face width"), material(), accuracyRow(),
            pos("mesh_stiffness", pressure, "mesh stiffness per unit face width (c_gamma)"),
            pos("carrier_inertia", inertia, "carrier moment of inertia"),
            derived("center_distance", length, "sun-planet centre distance"),
            derived("carrier_speed", angularSpeed, "carrier speed"));
  append(a, commonDerived());
  // Rated as its sun-planet and planet-ring meshes (K_gamma: `rating.mesh_load_factor`).
  append(a, planetaryRatingInputs());
  append(a, ratingStageQuantities());
  auto g = plainGearAttrs();
  append(g, planetaryGearAttrs());
  // Given, or from the geometry and the material's density.
  g.push_back(
      pos("mass", mass,
          "gear mass (planets: each); else the sun and a planet solid discs at the reference diameter across the face "
          "width, the ring an annulus from its reference circle to `rim_thickness` below its root (1.25 m)"));
  g.back().role = AttrRole::Either;
  append(g, ratingGearExtras());
  append(g, ratingGearQuantities());
  return {ir::StageKind::Planetary, "planetary", {"sun", "planet", "ring"}, std::move(a), std::move(g)};
}

KindSpec idlerKind() {
  std::vector<AttrSpec> a =
      attrs(pos("module", length, "module"), withDefault(pos("pressure_angle", angle, "pressure angle"), deg(20)),
            pos("face_width", length, "face width"), material(), accuracyRow(),
            derived("center_distance", length,
                    "driver-to-driven distance: the sum of both meshes' working centre distances (with shifts; (z1/2 "
                    "+ z2 + z3/2) m without)"));
  append(a, commonDerived());
  // Rated as two spur meshes; a stage factor is that of the governing mesh.
  append(a, ratingInputs());
  append(a, ratingStageQuantities());
  auto g = plainGearAttrs();
  append(g, ratingGearExtras());
  append(g, ratingGearQuantities());
  return {ir::StageKind::Idler, "idler", {"driver", "idler", "driven"}, std::move(a), std::move(g)};
}

// The kinds in the order of ir::StageKind, named.
constexpr std::pair<const char*, ir::StageKind> kKinds[] = {{"spur", ir::StageKind::Spur},
                                                            {"helical", ir::StageKind::Helical},
                                                            {"bevel", ir::StageKind::Bevel},
                                                            {"planetary", ir::StageKind::Planetary},
                                                            {"idler", ir::StageKind::Idler}};

KindSpec buildKind(ir::StageKind kind) {
  switch (kind) {
  case ir::StageKind::Spur:
    return {ir::StageKind::Spur, "spur", {"pinion", "wheel"}, cylindricalStage(false), cylindricalGear()};
  case ir::StageKind::Helical:
    return {ir::StageKind::Helical, "helical", {"pinion", "wheel"}, cylindricalStage(true), cylindricalGear()};
  case ir::StageKind::Bevel: return bevelKind();
  case ir::StageKind::Planetary: return planetaryKind();
  case ir::StageKind::Idler: break;
  }
  return idlerKind();
}

} // namespace

// Each kind's table is made the first time it is asked for: a spec names one or two kinds,
// and a table holds a few hundred rows.
const KindSpec& kindSpec(ir::StageKind kind) {
  constexpr size_t n = std::size(kKinds);
  static std::array<std::once_flag, n> once;
  static std::array<std::optional<KindSpec>, n> built;
  const auto i = static_cast<size_t>(kind);
  std::call_once(once[i], [&] { built[i].emplace(buildKind(kind)); });
  return *built[i];
}

std::vector<const KindSpec*> stageKinds() {
  std::vector<const KindSpec*> all;
  for (const auto& [name, kind] : kKinds)
    all.push_back(&kindSpec(kind));
  return all;
}

int gearIndex(const KindSpec& k, const std::string& name) {
  auto it = std::find(k.gears.begin(), k.gears.end(), name);
  return it == k.gears.end() ? -1 : static_cast<int>(it - k.gears.begin());
}

const KindSpec* findKind(const std::string& name) {
  for (const auto& [n, kind] : kKinds)
    if (name == n) return &kindSpec(kind);
  return nullptr;
}

bool isGear(const KindSpec& k, const std::string& name) {
  return std::find(k.gears.begin(), k.gears.end(), name) != k.gears.end();
}

const AttrSpec* findAttr(const KindSpec& k, const std::string& path) {
  auto dot = path.find('.');
  if (dot == std::string::npos) {
    for (const auto& a : k.stage)
      if (a.name == path) return &a;
    return nullptr;
  }
  if (!isGear(k, path.substr(0, dot))) {
    for (const auto& a : k.stage) // a block's setting: `rating.life`
      if (a.name == path) return &a;
    return nullptr;
  }
  std::string rest = path.substr(dot + 1);
  for (const auto& a : k.gear)
    if (a.name == rest) return &a;
  return nullptr;
}

} // namespace gbx::cat
