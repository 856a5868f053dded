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
  X(SteadyState, "steady_state")                                                                       \
  X(Continuation, "continuation")                                                                      \
  X(Distribution, "distribution")                                                                      \
  X(Seed, "seed")                                                                                      \
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
  X(PreloadDisplacement, "preload_displacement")                                                \
  X(TipDiameter, "tip_diameter")                                                                \
  X(TipRelief, "tip_relief")                                                                    \
  X(TipReliefHeight, "tip_relief_height")                                                       \
  X(LeadCrowning, "lead_crowning")                                                              \
  X(Slices, "slices")                                                                           \
  X(Positions, "positions")                                                                     \
  X(ProfileFormDeviation, "profile_form_deviation")                                             \
  X(HelixSlopeDeviation, "helix_slope_deviation")                                               \
  X(BoreDiameter, "bore_diameter")                                                              \
  X(WebThickness, "web_thickness")                                                              \
  X(RimThickness, "rim_thickness")                                                              \
  X(RatingApplicationFactor, "rating.application_factor")                                       \
  X(RatingLife, "rating.life")                                                                  \
  X(RatingLifeCurve, "rating.life_curve")                                                       \
  X(RatingViscosity40, "rating.lubricant.viscosity_40")                                         \
  X(RatingRoughnessFlank, "rating.roughness.flank")                                             \
  X(RatingRoughnessRoot, "rating.roughness.root")                                               \
  X(RatingRoughnessFlankRz, "rating.roughness.flank_rz")                                        \
  X(RatingRoughnessRootRz, "rating.roughness.root_rz")                                          \
  X(RatingRackAddendum, "rating.basic_rack.addendum")                                           \
  X(RatingRackDedendum, "rating.basic_rack.dedendum")                                           \
  X(RatingRackRootRadius, "rating.basic_rack.root_radius")                                      \
  X(RatingFaceLoadFactor, "rating.face_load_factor")                                            \
  X(RatingDynamicFactor, "rating.dynamic_factor")                                               \
  X(RatingTransverseLoadFactor, "rating.transverse_load_factor")                                \
  X(RatingMeshLoadFactor, "rating.mesh_load_factor")                                            \
  X(RatingMeshMisalignment, "rating.mesh_misalignment")                                         \
  X(RatingMinContact, "rating.min_safety.contact")                                              \
  X(RatingMinBending, "rating.min_safety.bending")                                              \
  X(Treatment, "treatment")                                                                     \
  X(ContactSafety, "contact_safety")                                                            \
  X(BendingSafety, "bending_safety")                                                            \
  X(ContactStress, "contact_stress")                                                            \
  X(BendingStress, "bending_stress")                                                            \
  X(PermissibleContactStress, "permissible_contact_stress")                                     \
  X(PermissibleBendingStress, "permissible_bending_stress")                                     \
  X(KV, "K_v")                                                                                  \
  X(KHbeta, "K_Hbeta")                                                                          \
  X(KFbeta, "K_Fbeta")                                                                          \
  X(KHalpha, "K_Halpha")                                                                        \
  X(KFalpha, "K_Falpha")                                                                        \
  X(ZH, "Z_H")                                                                                  \
  X(ZE, "Z_E")                                                                                  \
  X(Zeps, "Z_eps")                                                                              \
  X(Zbeta, "Z_beta")                                                                            \
  X(ZNT, "Z_NT")                                                                                \
  X(ZL, "Z_L")                                                                                  \
  X(Zv, "Z_v")                                                                                  \
  X(ZR, "Z_R")                                                                                  \
  X(ZW, "Z_W")                                                                                  \
  X(ZX, "Z_X")                                                                                  \
  X(ZB, "Z_B")                                                                                  \
  X(ZD, "Z_D")                                                                                  \
  X(YF, "Y_F")                                                                                  \
  X(YS, "Y_S")                                                                                  \
  X(Ybeta, "Y_beta")                                                                            \
  X(YNT, "Y_NT")                                                                                \
  X(YdeltarelT, "Y_deltarelT")                                                                  \
  X(YRrelT, "Y_RrelT")                                                                          \
  X(YX, "Y_X")                                                                                  \
  X(YM, "Y_M")                                                                                  \
  X(HelixHand, "helix_hand")                                                                    \
  X(TorqueSide, "torque_side")                                                                  \
  X(BrinellHardness, "brinell_hardness")                                                        \
  X(ContactDamage, "contact_damage")                                                            \
  X(BendingDamage, "bending_damage")                                                            \
  X(RatingViscosity100, "rating.lubricant.viscosity_100")                                       \
  X(RatingOilDensity, "rating.lubricant.density")                                               \
  X(RatingOilTemperature, "rating.lubricant.oil_temperature")                                   \
  X(RatingFzgLoadStage, "rating.lubricant.fzg_load_stage")                                      \
  X(RatingMicropittingLoadStage, "rating.lubricant.micropitting_load_stage")                    \
  X(RatingOilBase, "rating.lubricant.base")                                                     \
  X(RatingOilSupply, "rating.lubricant.supply")                                                 \
  X(RatingMinScuffing, "rating.min_safety.scuffing")                                            \
  X(RatingMinIntegralScuffing, "rating.min_safety.integral_scuffing")                           \
  X(RatingMinMicropitting, "rating.min_safety.micropitting")                                    \
  X(ScuffingSafety, "scuffing_safety")                                                          \
  X(IntegralScuffingSafety, "integral_scuffing_safety")                                         \
  X(ContactTemperature, "contact_temperature")                                                  \
  X(IntegralTemperature, "integral_temperature")                                                \
  X(ScuffingTemperature, "scuffing_temperature")                                                \
  X(BulkTemperature, "bulk_temperature")                                                        \
  X(MicropittingSafety, "micropitting_safety")                                                  \
  X(SpecificFilmThickness, "specific_film_thickness")                                           \
  X(PermissibleFilmThickness, "permissible_film_thickness")                                     \
  X(OuterConeDistance, "outer_cone_distance")                                                   \
  X(MeanConeDistance, "mean_cone_distance")                                                     \
  X(CoastPressureAngle, "coast_pressure_angle")                                                 \
  X(CutterRadius, "cutter_radius")                                                              \
  X(HypoidOffset, "offset")                                                                     \
  X(ThicknessModification, "thickness_modification")                                            \
  X(UpperThicknessAllowance, "upper_thickness_allowance")                                      \
  X(LowerThicknessAllowance, "lower_thickness_allowance")                                      \
  X(CenterDistanceAllowance, "center_distance_allowance")                                      \
  X(Diameter, "diameter")                                                                    \
  X(Bore, "bore")                                                                            \
  X(Roughness, "roughness")                                                                  \
  X(Shear, "shear")                                                                          \
  X(HeatTreatmentDiameter, "heat_treatment_diameter")                                        \
  X(BearingKind, "kind")                                                                     \
  X(DynamicRating, "C")                                                                      \
  X(StaticRating, "C0")                                                                      \
  X(RadialStiffness, "radial_stiffness")                                                     \
  X(Axial, "axial")                                                                          \
  X(LoadRatioLimit, "e")                                                                     \
  X(RadialFactor, "X")                                                                       \
  X(AxialFactor, "Y")                                                                        \
  X(StaticRadialFactor, "X0")                                                                \
  X(StaticAxialFactor, "Y0")                                                                 \
  X(PitchDiameter, "pitch_diameter")                                                         \
  X(Radial, "radial")                                                                        \
  X(Angle, "angle")                                                                          \
  X(Width, "width")                                                                          \
  X(Reliability, "reliability")                                                              \
  X(Cleanliness, "cleanliness")                                                              \
  X(Contamination, "contamination")                                                          \
  X(Deflection, "deflection")                                                                \
  X(CriticalSpeed, "critical_speed")                                                         \
  X(Reaction, "reaction")                                                                    \
  X(AxialReaction, "axial_reaction")                                                         \
  X(Life, "life")                                                                            \
  X(ModifiedLife, "modified_life")                                                           \
  X(StaticSafety, "static_safety")                                                           \
  X(OilViscosity, "viscosity")                                                               \
  X(TensileStrength, "tensile_strength")                                                     \
  X(YieldStrength, "yield_strength")                                                         \
  X(SteelGroup, "steel_group")                                                               \
  X(FatigueSafety, "fatigue_safety")                                                         \
  X(NotchRadius, "radius")                                                                   \
  X(NotchDepth, "depth")                                                                     \
  X(Keys, "keys")                                                                            \
  X(DeflectionAt, "deflection_at")                                                           \
  X(SlopeAt, "slope_at")                                                                     \
  X(TorsionAt, "torsion_at")                                                                 \
  X(ToolEdgeRadius, "tool_edge_radius")                                                         \
  X(MeanDiameter, "mean_diameter")                                                              \
  X(OuterPitchDiameter, "outer_pitch_diameter")                                                 \
  X(MeanAddendum, "mean_addendum")                                                              \
  X(MeanDedendum, "mean_dedendum")                                                              \
  X(VirtualZ, "virtual_z")                                                                      \
  X(VirtualEpsAlpha, "virtual_eps_alpha")                                                       \
  X(VirtualEpsBeta, "virtual_eps_beta")                                                         \
  X(VirtualContactRatio, "virtual_contact_ratio")                                               \
  X(ZMB, "Z_MB")                                                                                \
  X(ZLS, "Z_LS")                                                                                \
  X(Yeps, "Y_eps")                                                                              \
  X(YLS, "Y_LS")                                                                                \
  X(YBS, "Y_BS")                                                                                \
  X(YFa, "Y_Fa")                                                                                \
  X(YSa, "Y_Sa")                                                                                \
  X(RatingMounting, "rating.mounting")                                                          \
  X(RatingContactPattern, "rating.contact_pattern")                                            \
  X(SpiralHand, "spiral_hand")                                                                  \
  X(Apex, "apex")                                                                               \
  X(SunSupport, "sun_support")                                                                  \
  X(PinError, "pin_error")                                                                      \
  X(CutterTeeth, "cutter.teeth")                                                                \
  X(CutterShift, "cutter.shift")                                                                \
  X(CutterTipRadius, "cutter.tip_radius")                                                       \
  X(GearFlankRz, "roughness.flank_rz")                                                          \
  X(GearRootRz, "roughness.root_rz")                                                            \
  X(RatingRingPlanetDynamicFactor, "rating.ring_planet.dynamic_factor")                         \
  X(PlanetBearingKind, "bearing.kind")                                                          \
  X(PlanetBearingC, "bearing.C")                                                                \
  X(PlanetBearingC0, "bearing.C0")                                                              \
  X(PlanetBearingCount, "bearing.count")                                                        \
  X(PlanetBearingPitchDiameter, "bearing.pitch_diameter")                                       \
  X(PlanetBearingContamination, "bearing.contamination")                                        \
  X(BearingLoad, "bearing_load")                                                                \
  X(BearingLife, "bearing_life")                                                                \
  X(BearingModifiedLife, "bearing_modified_life")                                                \
  X(CornerContact, "corner_contact")                                                             \
  X(PitchSeed, "pitch_seed")                                                                     \
  X(PinionPitchDeviations, "pinion_pitch_deviations")                                            \
  X(WheelPitchDeviations, "wheel_pitch_deviations")

enum class Q : std::uint16_t {
#define GBX_KEY_ENUM(id, name) id,
  GBX_KEYS(GBX_KEY_ENUM)
#undef GBX_KEY_ENUM
      None
};

inline constexpr int kKeyCount = static_cast<int>(Q::None);

// The word as the language writes it.
std::string_view keyName(Q q);

// Which way a quantity is better (docs/language.md): safeties and permissible stresses
// larger; stresses, mass, deflections, sliding and errors smaller. `worst(q)` reads the
// other end; Unknown where neither is better (a contact ratio, a factor).
enum class Better : std::int8_t { Unknown, Larger, Smaller };
Better betterOf(Q q);
// The id of a word; `ratio` is the quantity (the damping ratio is resolved by its effect).
std::optional<Q> keyOf(std::string_view name);
// Lengths of the micrometre scale (deviations, deflections, modifications, roughness, oil
// films): every report format shows them in um, whatever a value's size (docs/reports.md).
bool readsInMicrometres(Q q);

} // namespace gbx::cat
