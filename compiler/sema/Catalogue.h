#pragma once
// What the language knows by name: stage kinds and their attributes, gearbox
// quantities, the operating point, effects and their parameters, scene settings and
// signals, split and study settings, modification targets, material properties and
// functions. Sema checks against these tables; the runtime computes what they promise.
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "units/Dim.h"
#include "units/Number.h"

namespace gbx::sema {

using units::Dim;

enum class AttrRole {
  Input,    // fixed or made a decision by the spec
  Derived,  // computed; cannot be set
  Either,   // derived unless the spec fixes it (center_distance)
};

enum class ValueKind { Number, Material, Symbol, Stage };

struct AttrSpec {
  std::string name;
  Dim dim;
  bool integer = false;
  AttrRole role = AttrRole::Input;
  std::string meaning;
  ValueKind value = ValueKind::Number;
  std::optional<Dim> altDim;           // a second accepted dimension (Hz for deg/s)
  std::optional<units::Number> dflt;   // default when absent (SI)
  bool required = false;
  bool positive = false;               // must be > 0
  bool meshPeriods = false;            // may be given in mesh periods
  std::vector<std::string> symbols;    // accepted words for ValueKind::Symbol
};

struct KindSpec {
  ir::StageKind kind;
  std::string name;
  std::vector<std::string> gears;
  std::vector<AttrSpec> stage;  // stage-level attributes
  std::vector<AttrSpec> gear;   // per-gear attributes (pinion.z)
};

const std::vector<KindSpec>& stageKinds();
const KindSpec* findKind(const std::string& name);
// "pinion.z", "ratio": the attribute spec for a stage kind, or nullptr.
const AttrSpec* findAttr(const KindSpec& k, const std::string& path);
bool isGear(const KindSpec& k, const std::string& name);

const std::vector<AttrSpec>& gearboxQuantities();
const std::vector<AttrSpec>& operatingSettings();
const std::vector<AttrSpec>& materialProperties();

struct EffectSpec {
  std::string name;
  std::string meaning;
  std::vector<AttrSpec> params;
};
const std::vector<EffectSpec>& effects();
const EffectSpec* findEffect(const std::string& name);

const std::vector<AttrSpec>& sceneSettings();
const std::vector<AttrSpec>& accuracySettings();

struct SignalSpec {
  std::string name;
  Dim dim;
  std::vector<std::string> needsAnyEffect;  // empty: always available
  bool scalar = false;                        // a number, not a time series (modes, dynamic_factor)
};
const std::vector<SignalSpec>& sceneSignals();
const SignalSpec* findSignal(const std::string& name);
// rms, peak, mean, min, max (numbers) and spectrum, plot (artefacts).
bool isSignalFunction(const std::string& fn);
bool signalFunctionIsNumber(const std::string& fn);

const std::vector<AttrSpec>& splitSettings();
const std::vector<AttrSpec>& splitOutputs();
const std::vector<AttrSpec>& workPrecisionSettings();

// Tooth modification: targets (lengths, per gear or both) and built-in quantities.
const std::vector<std::string>& modificationTargets();
struct BuiltinSpec {
  std::string name;
  Dim dim;
  bool perGear;
};
const std::vector<BuiltinSpec>& modifyBuiltins();

bool isFunction(const std::string& name);

// Closest known name within two edits, for "did you mean" hints; "" when none.
std::string closest(const std::string& name, const std::vector<std::string>& candidates);
// "; did you mean `x`?" for a hint from `closest`, "" for none.
std::string suggestion(const std::string& hint);

} // namespace gbx::sema
