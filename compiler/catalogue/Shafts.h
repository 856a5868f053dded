#pragma once
// The `shaft` member of a gearbox: its settings and those of its segments, bearings, loads,
// disks and `life` block, and the quantities it reports (docs/language.md, "Shafts and bearings").
#include <string>
#include <vector>

#include "catalogue/Attr.h"

namespace gbx::cat {

const std::vector<AttrSpec>& shaftSettings();   // material, shear, speed, heat_treatment_diameter, life.*
const std::vector<AttrSpec>& segmentSettings(); // diameter, bore, roughness
const std::vector<AttrSpec>& bearingSettings(); // kind, C, C0, radial_stiffness, axial, e, X, Y, X0, Y0, pitch_diameter
const std::vector<AttrSpec>& loadSettings();    // radial, axial, torque, angle
const std::vector<AttrSpec>& diskSettings();    // diameter, width, bore
const std::vector<AttrSpec>& gearSettings();    // apex (a bevel gear's)
const std::vector<std::string>& notchKinds();   // shoulder, groove, keyway, press_fit, hole, v_notch
const std::vector<AttrSpec>& notchSettings();   // radius, depth, diameter, keys
const std::vector<AttrSpec>& shaftOutputs();    // deflection, critical_speed, mass, fatigue_safety, static_safety
const std::vector<AttrSpec>& shaftFunctions();  // deflection_at, slope_at, torsion_at (of a gear on the shaft)
const std::vector<AttrSpec>& notchOutputs();    // fatigue_safety, static_safety (of `notch_at(x)`)
const std::vector<AttrSpec>& bearingOutputs();  // reaction, axial_reaction, life, modified_life, static_safety

namespace bearingKind {
// In the order of bearingSettings()'s `kind` words.
inline constexpr int DeepGrooveBall = 0, AngularContactBall = 1, CylindricalRoller = 2, TaperedRoller = 3,
                     SphericalRoller = 4;
} // namespace bearingKind
namespace notchKind {
// In the order of notchKinds().
inline constexpr int Shoulder = 0, Groove = 1, Keyway = 2, PressFit = 3, Hole = 4, VNotch = 5;
} // namespace notchKind
namespace shaftSurface {
inline constexpr int Plain = 0, Hardened = 1; // the order of `strength.surface`'s words
} // namespace shaftSurface
namespace cleanliness {
// ISO 281 Table 13's guide values of e_C (D_pw < 100 mm), the middle of each band.
inline constexpr double kEc[] = {1.0, 0.7, 0.55, 0.4, 0.2, 0.05};
} // namespace cleanliness

} // namespace gbx::cat
