#pragma once
// Every word the catalogue knows as a quantity, attribute, setting or effect parameter,
// as one enumeration: lowering resolves each name in the program to one of these once,
// and the runtime compares these ids, never the text.
#include <cstdint>
#include <optional>
#include <string_view>

namespace gbx::cat {

// X(id, "name"): one row per word. The name is the text the language uses.
#define GBX_KEYS(X)                                                                                    \
  X(Ratio, "ratio")                                                                                    \
  X(InputSpeed, "input_speed")                                                                         \
  X(OutputSpeed, "output_speed")                                                                       \
  X(InputTorque, "input_torque")                                                                       \
  X(OutputTorque, "output_torque")                                                                     \
  X(Power, "power")                                                                                    \
  X(MeshFrequency, "mesh_frequency")                                                                   \
  X(NormalModule, "normal_module")                                                                     \
  X(HelixAngle, "helix_angle")                                                                         \
  X(PressureAngle, "pressure_angle")                                                                   \
  X(FaceWidth, "face_width")                                                                           \
  X(CenterDistance, "center_distance")                                                                 \
  X(Material, "material")                                                                              \
  X(Accuracy, "accuracy")                                                                              \
  X(MeshStiffness, "mesh_stiffness")                                                                   \
  X(PitchLineVelocity, "pitch_line_velocity")                                                          \
  X(EpsAlpha, "eps_alpha")                                                                             \
  X(EpsBeta, "eps_beta")                                                                               \
  X(Mass, "mass")                                                                                      \
  X(WholeDepth, "whole_depth")                                                                         \
  X(SlidingBalance, "sliding_balance")                                                                 \
  X(WorkingPressureAngle, "working_pressure_angle")                                                    \
  X(TangentialForce, "tangential_force")                                                               \
  X(LoadDeflection, "load_deflection")                                                                 \
  X(TotalContactRatio, "total_contact_ratio")                                                          \
  X(SpiralAngle, "spiral_angle")                                                                       \
  X(FaceRatio, "face_ratio")                                                                           \
  X(ShaftAngle, "shaft_angle")                                                                         \
  X(BladeGroups, "blade_groups")                                                                       \
  X(MeanNormalModule, "mean_normal_module")                                                            \
  X(MmnB, "mmn_b")                                                                                     \
  X(Planets, "planets")                                                                                \
  X(Module, "module")                                                                                  \
  X(CarrierInertia, "carrier_inertia")                                                                 \
  X(CarrierSpeed, "carrier_speed")                                                                     \
  X(Z, "z")                                                                                            \
  X(Shift, "shift")                                                                                    \
  X(PitchDeviation, "pitch_deviation")                                                                 \
  X(ProfileDeviation, "profile_deviation")                                                             \
  X(BendingDeflection, "bending_deflection")                                                           \
  X(TorsionDeflection, "torsion_deflection")                                                           \
  X(Inertia, "inertia")                                                                                \
  X(BearingSpan, "bearing_span")                                                                       \
  X(ShaftDiameter, "shaft_diameter")                                                                   \
  X(D, "d")                                                                                            \
  X(BaseRadius, "base_radius")                                                                         \
  X(TipRadius, "tip_radius")                                                                           \
  X(Speed, "speed")                                                                                    \
  X(Torque, "torque")                                                                                  \
  X(ConeAngle, "cone_angle")                                                                           \
  X(Stages, "stages")                                                                                  \
  X(Teeth, "teeth")                                                                                    \
  X(YoungsModulus, "youngs_modulus")                                                                   \
  X(Poisson, "poisson")                                                                                \
  X(Density, "density")                                                                                \
  X(ShearModulus, "shear_modulus")                                                                     \
  X(SigmaHlim, "sigma_hlim")                                                                           \
  X(SigmaFlim, "sigma_flim")                                                                           \
  X(Hardness, "hardness")                                                                              \
  X(Harmonics, "harmonics")                                                                            \
  X(Stiffness, "stiffness")                                                                            \
  X(DampingRatio, "ratio#damping")                                                                     \
  X(Coefficient, "coefficient")                                                                        \
  X(Mean, "mean")                                                                                      \
  X(Amplitude, "amplitude")                                                                            \
  X(Phase, "phase")                                                                                    \
  X(Clearance, "clearance")                                                                            \
  X(Exponent, "exponent")                                                                              \
  X(PenetrationRamp, "penetration_ramp")                                                               \
  X(Damping, "damping")                                                                                \
  X(Frequency, "frequency")                                                                            \
  X(Settle, "settle")                                                                                  \
  X(Record, "record")                                                                                  \
  X(Samples, "samples")                                                                                \
  X(Duration, "duration")                                                                              \
  X(Ramp, "ramp")                                                                                      \
  X(Method, "method")                                                                                  \
  X(Rtol, "rtol")                                                                                      \
  X(Atol, "atol")                                                                                      \
  X(MaxStep, "max_step")                                                                               \
  X(MinStep, "min_step")                                                                               \
  X(MaxSteps, "max_steps")                                                                             \
  X(Methods, "methods")                                                                                \
  X(Between, "between")                                                                                \
  X(Branches, "branches")                                                                              \
  X(TorsionShaftLength, "torsion_shaft.length")                                                        \
  X(TorsionShaftDiameter, "torsion_shaft.diameter")                                                    \
  X(TorsionShaftShearModulus, "torsion_shaft.shear_modulus")                                           \
  X(BacklashDifference, "backlash_difference")                                                         \
  X(Install, "install")                                                                                \
  X(PreloadTorque, "preload_torque")                                                                   \
  X(Twist, "twist")                                                                                    \
  X(Displacement, "displacement")                                                                      \
  X(Imbalance, "imbalance")                                                                            \
  X(BranchTorque, "branch_torque")                                                                     \
  X(PreloadDisplacement, "preload_displacement")

enum class Q : std::uint8_t {
#define GBX_KEY_ENUM(id, name) id,
  GBX_KEYS(GBX_KEY_ENUM)
#undef GBX_KEY_ENUM
      None
};

inline constexpr int kKeyCount = static_cast<int>(Q::None);

// The word as the language writes it.
std::string_view keyName(Q q);
// The id of a word; `ratio` is the quantity (the damping ratio is resolved by its effect).
std::optional<Q> keyOf(std::string_view name);

} // namespace gbx::cat
