#include "catalogue/Shafts.h"

namespace gbx::cat {

using namespace rows;
using namespace units::dims;

const std::vector<AttrSpec>& shaftSettings() {
  static const std::vector<AttrSpec> s = [] {
    auto mat = required(in("material", none, "the shaft's material (a `material` declaration): E, G or nu, density"));
    mat.value = ValueKind::Material;
    return attrs(
        mat,
        symbol("shear", {"on", "off"},
               "beam model: `on` Timoshenko (shear deformation, the default), `off` Euler-Bernoulli"),
        hinted(pos("speed", angularSpeed, "speed of a shaft that carries no gear (else its gears' stage gives it)"),
               "rpm"),
        hinted(pos("heat_treatment_diameter", length, "DIN 743 d_eff (default the largest diameter)"), "mm"),
        bounded(pos("life.reliability", none, "ISO 281 reliability of the modified life, 0.9 .. 0.99 (default 0.9)"),
                num(9, 10), num(99, 100)),
        symbol("life.cleanliness", {"extreme", "high", "normal", "slight", "typical", "severe"},
               "ISO 281 contamination level: e_C from Table 13's guide values (default normal, e_C 0.55)"),
        bounded(in("life.contamination", none, "ISO 281 contamination factor e_C, given (in place of `cleanliness`)"),
                num(0), num(1)),
        bounded(withDefault(count("strength.load_case", "DIN 743 load case: 1 the mean stress stays as the load grows, "
                                                        "2 (the default) its ratio to the amplitude stays"),
                            num(2)),
                num(1), num(2)),
        bounded(withDefault(pos("strength.peak_factor", none,
                                "the largest load over the nominal one, for the static proof S_F (default 1)"),
                            num(1)),
                num(1), std::nullopt),
        symbol("strength.surface", {"plain", "hardened"},
               "DIN 743 surface: `hardened` (a hardened layer) takes K_F 1, the hard layer's support number and K2F 1"),
        withDefault(pos("strength.surface_factor", none, "DIN 743 K_V, the surface strengthening factor (default 1)"),
                    num(1)),
        withDefault(pos("strength.min_safety.fatigue", none, "minimum fatigue safety S_D (default 1.2)"), num(6, 5)),
        withDefault(pos("strength.min_safety.static", none, "minimum static safety S_F (default 1.2)"), num(6, 5)),
        hinted(
            pos("life.viscosity", kinematicViscosity,
                "oil viscosity at the bearings' temperature (kappa of a_ISO); without it, the oil of the first rated "
                "stage the shaft carries a gear of, at its oil_temperature; with neither, a_ISO 1"),
            "mm^2/s"));
  }();
  return s;
}

const std::vector<AttrSpec>& segmentSettings() {
  static const std::vector<AttrSpec> s =
      attrs(required(hinted(pos("diameter", length, "outer diameter of the segment"), "mm")),
            hinted(bounded(in("bore", length, "bore of a hollow segment (0: solid)"), num(0), std::nullopt), "mm"),
            hinted(pos("roughness", length, "surface roughness Rz (DIN 743's K_F)"), "um"));
  return s;
}

const std::vector<AttrSpec>& bearingSettings() {
  static const std::vector<AttrSpec> s = attrs(
      required(symbol(
          "kind",
          {"deep_groove_ball", "angular_contact_ball", "cylindrical_roller", "tapered_roller", "spherical_roller"},
          "bearing type: the ISO 281 life exponent (ball 3, roller 10/3) and a_ISO curve")),
      required(hinted(pos("C", force, "basic dynamic load rating"), "kN")),
      required(hinted(pos("C0", force, "basic static load rating"), "kN")),
      hinted(pos("radial_stiffness", stiffness, "radial stiffness in either plane (rigid when absent)"), "N/um"),
      symbol("axial", {"held", "free"}, "whether this bearing takes the shaft's axial force (one bearing holds it)"),
      pos("e", none, "limit of F_a/F_r below which P = F_r (the catalogue's)"),
      pos("X", none, "radial factor of P = X F_r + Y F_a beyond e"), pos("Y", none, "axial factor of P beyond e"),
      pos("X0", none, "static radial factor of P0 (deep-groove ball: 0.6)"),
      pos("Y0", none, "static axial factor of P0 (deep-groove ball: 0.5)"),
      hinted(pos("pitch_diameter", length,
                 "rolling-element pitch diameter D_pw (kappa, C_u; default 1.4 times the shaft's diameter there)"),
             "mm"));
  return s;
}

const std::vector<AttrSpec>& loadSettings() {
  static const std::vector<AttrSpec> s = attrs(
      hinted(in("radial", force, "radial force"), "kN"),
      hinted(in("axial", force, "axial force (positive along the shaft's axis)"), "kN"),
      hinted(in("torque", torque, "torque about the shaft's axis"), "N*m"),
      hinted(in("angle", angle, "direction of the radial force about the axis (0: the first stage's line of centres)"),
             "deg"));
  return s;
}

const std::vector<AttrSpec>& gearSettings() {
  static const std::vector<AttrSpec> s = attrs(symbol(
      "apex", {"left", "right"}, "the end of the shaft a bevel gear's cone apex points to (its thrust's sense)"));
  return s;
}

const std::vector<AttrSpec>& diskSettings() {
  static const std::vector<AttrSpec> s =
      attrs(required(hinted(pos("diameter", length, "outer diameter of the disk"), "mm")),
            required(hinted(pos("width", length, "axial width of the disk"), "mm")),
            hinted(bounded(in("bore", length, "bore of the disk"), num(0), std::nullopt), "mm"));
  return s;
}

const std::vector<std::string>& notchKinds() {
  static const std::vector<std::string> k = {"shoulder", "groove", "keyway", "press_fit", "hole", "v_notch"};
  return k;
}

const std::vector<AttrSpec>& notchSettings() {
  static const std::vector<AttrSpec> s =
      attrs(hinted(pos("radius", length, "fillet radius of a shoulder or groove"), "mm"),
            hinted(pos("depth", length, "depth of a groove or V-notch below the segment's diameter"), "mm"),
            hinted(pos("diameter", length, "diameter of a transverse hole"), "mm"),
            bounded(count("keys", "keys in a keyway, 1 or 2 (default 1)"), num(1), num(2)));
  return s;
}

const std::vector<AttrSpec>& shaftOutputs() {
  static const std::vector<AttrSpec> s =
      attrs(hinted(derived("deflection", length, "largest radial deflection along the shaft"), "um"),
            hinted(derived("critical_speed", angularSpeed,
                           "first bending natural frequency on the bearings, gears and disks as rigid disks"),
                   "rpm"),
            derived("mass", mass, "the shaft's mass"),
            derived("fatigue_safety", none, "DIN 743 fatigue safety S_D, the least over the notches"),
            derived("static_safety", none, "DIN 743 static safety S_F, the least over the notches"));
  return s;
}

const std::vector<AttrSpec>& shaftFunctions() {
  static const std::vector<AttrSpec> s =
      attrs(hinted(derived("deflection_at", length,
                           "radial deflection at a gear's face centre: `input.deflection_at(hs.pinion)`"),
                   "um"),
            hinted(derived("slope_at", angle, "slope of the deflection line at a gear's face centre"), "mrad"),
            hinted(derived("torsion_at", length, "wind-up across a gear's face, at its reference circle"), "um"));
  return s;
}

const std::vector<AttrSpec>& notchOutputs() {
  static const std::vector<AttrSpec> s =
      attrs(derived("fatigue_safety", none,
                    "DIN 743 fatigue safety S_D at this notch: `input.notch_at(60 mm).fatigue_safety`"),
            derived("static_safety", none, "DIN 743 static safety S_F at this notch"));
  return s;
}

const std::vector<AttrSpec>& bearingOutputs() {
  static const std::vector<AttrSpec> s =
      attrs(hinted(derived("reaction", force, "radial bearing force"), "N"),
            hinted(derived("axial_reaction", force, "axial bearing force (the bearing that holds the thrust)"), "N"),
            hinted(derived("life", time, "ISO 281 basic rating life L10h"), "h"),
            hinted(derived("modified_life", time, "ISO 281 modified life L_nmh = a1 a_ISO L10h"), "h"),
            derived("static_safety", none, "static safety s0 = C0 / P0"));
  return s;
}

} // namespace gbx::cat
