#pragma once
// The registries of scene signals and of the functions that read them
// (`scene.rms(acceleration)`). Every number-valued function has one runtime row in
// runtime/dynamics/Statistics.cpp; every signal is recorded by each scene model.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "catalogue/Effects.h"
#include "units/Dim.h"
#include "units/Unit.h"

namespace gbx::cat {

enum class Signal : std::uint8_t {
  Displacement,
  Velocity,
  Acceleration,
  MeshForce,
  Stiffness,
  ContactForce,
  TransmissionError,
  StaticTransmissionError,
  InputSpeed,
  OutputSpeed,
  DynamicFactor,
  Stability,
  Modes,
};

struct SignalSpec {
  Signal id;
  std::string_view name;
  units::Dim dim;
  std::vector<Effect> needsAnyEffect;  // empty: always available
  bool scalar = false;                 // a number, not a time series (modes, dynamic_factor)
};

inline const std::vector<SignalSpec>& sceneSignals() {
  using namespace units::dims;
  static const std::vector<SignalSpec> s = {
      {Signal::Displacement, "displacement", length, {}, false},
      {Signal::Velocity, "velocity", velocity, {}, false},
      {Signal::Acceleration, "acceleration", acceleration, {}, false},
      {Signal::MeshForce, "mesh_force", force, {}, false},
      {Signal::Stiffness, "stiffness", stiffness, {}, false},
      {Signal::ContactForce, "contact_force", force, {Effect::HertzContact, Effect::Backlash}, false},
      {Signal::TransmissionError, "transmission_error", length, {Effect::TransmissionError, Effect::LoadedMesh}, false},
      {Signal::StaticTransmissionError, "static_transmission_error", length, {Effect::LoadedMesh}, false},
      {Signal::InputSpeed, "input_speed", angularSpeed, {}, false},
      {Signal::OutputSpeed, "output_speed", angularSpeed, {}, false},
      {Signal::DynamicFactor, "dynamic_factor", none, {}, true},
      {Signal::Stability, "stability", none, {}, true},
      {Signal::Modes, "modes", frequency, {}, true},
  };
  return s;
}

inline const SignalSpec* findSignal(std::string_view name) {
  for (const auto& s : sceneSignals())
    if (s.name == name) return &s;
  return nullptr;
}

inline const SignalSpec& signalSpec(Signal id) { return sceneSignals()[static_cast<size_t>(id)]; }

// The unit a signal and the numbers read from it show in: its lengths (the mesh's
// displacement, the transmission errors) are micrometres in every format, whatever their size.
inline units::DisplayUnit signalUnit(Signal id) {
  const units::Dim& d = signalSpec(id).dim;
  return d == units::dims::length ? units::micrometres() : units::displayUnitFor(d);
}

// Functions of a signal: a number over the recorded window, or an artefact.
enum class SignalFn : std::uint8_t { Rms, Peak, Mean, Min, Max, PeakToPeak, Spectrum, Plot, Harmonic, Level, LevelA };

// Whether a function takes the order of the mesh frequency as a second argument
// (`harmonic(static_transmission_error, 2)`).
enum class OrderArg : std::uint8_t { None, Optional, Required };

struct SignalFnSpec {
  SignalFn id;
  std::string_view name;
  bool number; // false: a spectrum or a plot
  OrderArg order = OrderArg::None;
  bool decibels = false; // a level in dB (plain), whatever the signal's dimension
};

inline constexpr SignalFnSpec kSignalFns[] = {
    {SignalFn::Rms, "rms", true},
    {SignalFn::Peak, "peak", true},
    {SignalFn::Mean, "mean", true},
    {SignalFn::Min, "min", true},
    {SignalFn::Max, "max", true},
    {SignalFn::PeakToPeak, "peak_to_peak", true},
    {SignalFn::Spectrum, "spectrum", false},
    {SignalFn::Plot, "plot", false},
    // The amplitude of mesh order k; the level in dB of order k (or of every order together);
    // the same A-weighted at each order's frequency (docs/dynamics.md).
    {SignalFn::Harmonic, "harmonic", true, OrderArg::Required},
    {SignalFn::Level, "level", true, OrderArg::Optional, true},
    {SignalFn::LevelA, "level_a", true, OrderArg::Optional, true},
};

inline const SignalFnSpec* findSignalFn(std::string_view name) {
  for (const auto& f : kSignalFns)
    if (f.name == name) return &f;
  return nullptr;
}

inline const SignalFnSpec& signalFnSpec(SignalFn id) { return kSignalFns[static_cast<size_t>(id)]; }

// "rms, peak, …, plot", for messages.
inline std::string signalFnList() {
  std::string out;
  for (const auto& f : kSignalFns) out += (out.empty() ? "" : ", ") + std::string(f.name);
  return out;
}

} // namespace gbx::cat
