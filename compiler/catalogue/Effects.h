#pragma once
// The registry of scene effects: one row per effect, with its parameters. Each effect
// has one runtime implementation row in runtime/dynamics/Effects.cpp; the registry test
// fails when either side lacks the other.
#include <string>
#include <vector>

#include "catalogue/Attr.h"
#include "catalogue/Budgets.h"

namespace gbx::cat {

enum class Effect : std::uint8_t {
  VaryingStiffness,
  Damping,
  TransmissionError,
  Backlash,
  HertzContact,
  SpeedFluctuation,
  TorqueFluctuation,
  LoadedMesh,
};

struct EffectSpec {
  Effect id;
  std::string name;
  std::string meaning;
  std::vector<AttrSpec> params;
  std::vector<std::string> locals;  // words an expression of a parameter may use (`stiffness`)
};

inline const std::vector<EffectSpec>& effects() {
  using namespace units::dims;
  using namespace rows;
  static const std::vector<EffectSpec> e = [] {
    auto freq = [](std::string meaning) {
      auto a = required(pos("frequency", angularSpeed, std::move(meaning)));
      a.altDim = frequency;
      return a;
    };
    return std::vector<EffectSpec>{
        {Effect::VaryingStiffness,
         "varying_stiffness",
         "time-varying mesh stiffness from the contact-line length",
         {withDefault(budgeted(count("harmonics", "Fourier harmonics of the contact-line length"), budget::kHarmonics),
                      num(5)),
          pos("stiffness", units::dims::stiffness, "mean mesh stiffness (computed from geometry when absent)")},
         {}},
        {Effect::Damping,
         "damping",
         "viscous mesh damping",
         {keyed(pos("ratio", none, "damping ratio zeta"), Q::DampingRatio),
          pos("coefficient", dampingCoeff, "damping coefficient c")},
         {}},
        {Effect::TransmissionError,
         "transmission_error",
         "static transmission error e(t), force F = dk(t) e(t)",
         {hinted(withDefault(in("mean", length, "mean error e0"), num(0)), "um"),
          hinted(required(in("amplitude", length, "error amplitude er")), "um"),
          withDefault(in("phase", angle, "phase"), num(0))},
         {}},
        {Effect::Backlash,
         "backlash",
         "clearance with contact loss on both flanks",
         {hinted(bounded(required(pos("clearance", length, "total backlash along the line of action")), std::nullopt,
                         num(5, 1000)),
                 "um")},
         {}},
        {Effect::HertzContact,
         "hertz_contact",
         "Hertzian contact force K d^e with penetration-ramp damping",
         {withDefault(pos("exponent", none, "force exponent e"), num(3, 2)),
          hinted(required(pos("penetration_ramp", length, "penetration over which damping ramps in")), "um"),
          withDefault(in("damping", dampingCoeff, "maximum damping coefficient C"), num(0))},
         {"stiffness"}},
        {Effect::SpeedFluctuation,
         "speed_fluctuation",
         "drive speed mean + amplitude sin(frequency t)",
         {required(pos("mean", angularSpeed, "mean drive speed")), required(in("amplitude", angularSpeed, "amplitude")),
          freq("angular frequency of the fluctuation")},
         {}},
        {Effect::TorqueFluctuation,
         "torque_fluctuation",
         "load torque mean + amplitude sin(frequency t)",
         {required(in("mean", torque, "mean load torque")), required(in("amplitude", torque, "amplitude")),
          freq("angular frequency of the fluctuation")},
         {}},
        {Effect::LoadedMesh,
         "loaded_mesh",
         "loaded static transmission error and mesh stiffness from the flank geometry (thin slices), force k(t) (x - "
         "e(t))",
         {withDefault(budgeted(count("slices", "slices across the face width"), budget::kSlices), num(40)),
          withDefault(budgeted(count("positions", "mesh positions per mesh period"), budget::kPositions), num(64)),
          budgeted(count("harmonics", "Fourier harmonics of the tables the dynamics reads (default positions / 4)"),
                   budget::kHarmonics),
          symbol("corner_contact", {"false", "true"},
                 "contact outside the path: a tip corner touching the mating flank under load (false unless given)"),
          bounded(whole("pitch_seed", "draw each tooth's single pitch deviation from its gear's pitch_deviation (three "
                                      "standard deviations) with this seed"),
                  num(0), num(4294967295)),
          hinted(list("pinion_pitch_deviations", length,
                      "the pinion's single pitch deviations, one per tooth in the order they mesh"),
                 "um"),
          hinted(list("wheel_pitch_deviations", length,
                      "the wheel's single pitch deviations, one per tooth in the order they mesh"),
                 "um")},
         {}},
    };
  }();
  return e;
}

inline const EffectSpec* findEffect(const std::string& name) {
  for (const auto& e : effects())
    if (e.name == name) return &e;
  return nullptr;
}

inline const EffectSpec& effectSpec(Effect id) { return effects()[static_cast<size_t>(id)]; }

} // namespace gbx::cat
