#pragma once
// The checked, lowered program the runtime consumes: every name resolved to a
// quantity path, every literal in SI and exact where it can be, every expression typed.
// The runtime never sees the AST; this header is the whole contract between them.
#include <map>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "catalogue/Effects.h"
#include "catalogue/Functions.h"
#include "catalogue/Keys.h"
#include "catalogue/Methods.h"
#include "catalogue/Signals.h"
#include "source/Source.h"
#include "units/Dim.h"
#include "units/Number.h"

namespace gbx::ir {

using source::Span;
using units::Dim;
using units::Number;

struct Type {
  enum Kind { Number, Bool, Interval, Set, Stage, Gear, Collection, Signal, Symbol, Material, Scene, Split, PerGear, Block, Shaft, Bearing, Notch, Error };
  Kind kind = Error;
  Dim dim;
  bool integer = false;
  std::string detail;  // stage kind, gear role, collection name, block path

  static Type number(Dim d, bool integer = false) { return {Number, d, integer, {}}; }
  static Type boolean() { return {Bool, {}, false, {}}; }
  static Type error() { return {Error, {}, false, {}}; }
  bool isNumber() const { return kind == Number; }
  bool isError() const { return kind == Error; }
  std::string str() const;
};

enum class Op {
  Const,        // value
  Quantity,     // name: a path in the gearbox's quantities ("main.pinion.z", "ratio")
  Let,          // name: a `let`
  Symbol,       // name: an enumerator or effect-local word (`preloaded`, `rk8pd`, `stiffness`)
  Neg, Add, Sub, Mul, Div, Pow,
  Eq, Ne, Lt, Le, Gt, Ge,  // Eq/Ne against a Tol operand test membership of its interval
  Within,       // args: x, lo, hi (inclusive)
  InSet,        // args: x, members…
  Tol,          // args: centre, tolerance; name "relative" when the tolerance is a fraction
  Set,          // args: members
  And, Or, Not,
  Call,         // name: function; args
  Forall,       // name: variable, detail in type: collection; args: one instance per element
  SceneOutput,  // name: "scene.fn(signal)"
  Relative,     // args[0] divided by its value in the baseline gearbox (`inBaseline`)
  Scatter,      // fn Worst or Mean: args[0] over the gearbox's `tolerances` (docs/dynamics.md)
};

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

using cat::Q;

// A quantity as lowering resolves it: who owns it, and which catalogue word it is.
struct QuantityRef {
  enum Owner : std::uint8_t { Unresolved, Gearbox, Stage, Split, Material, Collection, Shaft };
  Owner owner = Unresolved;
  std::int16_t index = -1;  // the stage, split, material or shaft
  std::int8_t gear = -1;    // the gear's position in its stage (a shaft's bearing); -1 a stage (shaft) quantity;
                            // -2 - k: a shaft's notch, k its position among the shaft's placements
  bool perGear = false;     // `pitch_deviation` of every gear of the stage (modify rules)
  Q key = Q::None;
  bool operator==(const QuantityRef&) const = default;
};

// A literal's unit that must survive folding: a percentage stays a relative tolerance,
// mesh periods scale with the scene's mesh period.
enum class Marker : std::uint8_t { None, Percent, MeshPeriods };

// `scene.fn(signal)`, resolved.
struct SceneOutputRef {
  int scene = -1;
  bool bare = false;  // a single result (`scene.dynamic_factor`): matched by its signal alone
  cat::SignalFn fn = cat::SignalFn::Rms;
  cat::Signal signal = cat::Signal::Displacement;
  int order = 0; // `harmonic(x, k)`: k
};

struct Expr {
  Op op = Op::Const;
  Type type;
  Number value;
  std::string name;
  std::vector<ExprPtr> args;
  Span span;
  // Resolved by lowering; the runtime reads these, `name` stays for reports.
  QuantityRef ref;           // Quantity
  int let = -1;              // Let: index in the gearbox's lets; Symbol: in its effect's own words
  cat::Fn fn = cat::Fn::Abs; // Call
  Marker marker = Marker::None;  // Const
  bool relative = false;     // Tol: the tolerance is a fraction of the centre
  SceneOutputRef output;     // SceneOutput
  ExprPtr inBaseline;        // Relative: args[0] resolved in the baseline gearbox (its ids, not ours)
  // Scatter with fn Worst: +1 the largest value is the worst (minimised, or below a bound), -1
  // the smallest, 0 the one farthest from the nominal (a report column).
  std::int8_t sense = 0;

  ExprPtr clone() const;
  bool isConst() const { return op == Op::Const; }
};

ExprPtr makeConst(Number v, Dim d, bool integer, Span span = {});

// Whether e (or anything inside it) is one of these operations; false for no expression.
bool uses(const Expr* e, std::initializer_list<Op> ops);

enum class StageKind { Spur, Helical, Bevel, Planetary, Idler };
const char* stageKindName(StageKind k);

// A stage or gear attribute as the design fixes or frees it.
struct Attribute {
  enum Role { Fixed, Decision, Freedom, Default };
  std::string name;  // "pinion.z", "spiral_angle"
  Q key = Q::None;   // resolved by lowering
  int gear = -1;     // the gear's position, -1 for a stage attribute
  Dim dim;
  bool integer = false;
  Role role = Fixed;
  ExprPtr value;               // Fixed/Default: the expression (Const when it folds)
  std::optional<Number> lo, hi;  // Decision/Freedom over a range
  std::vector<Number> members;   // Decision over a set
  std::vector<std::string> memberTexts;  // each member as written (`0.2 rad`), in members' order; empty if not all literals
  std::string origin;          // where the binding came from: "stage", "preset klingelnberg", "like upper", "gearbox Name"
  Span span;
  std::string symbol;          // material or other named value
  int choice = -1;             // resolved by lowering: an enumerated value's position in its row's words
  bool sceneRef = false;       // `dynamic_factor = scene vib`: symbol names a scene
  int scene = -1;              // resolved by lowering: that scene's index in the gearbox
};

struct Rule {
  ExprPtr expr;
  std::string text;  // source text, for funnels and reports
  std::string scope; // stage name when declared inside a stage
  Span span;
};

// One bin of a rating's `load_spectrum` (ISO 6336-6): a load for a duration.
struct SpectrumBin {
  Number load;       // a share of the operating torque (share), or a torque [N m]
  bool share = true;
  Number duration;   // a share of the life, or load cycles of the driving gear (cycles)
  bool cycles = false;
  Span span;
};

struct Stage {
  std::string name;
  StageKind kind = StageKind::Spur;
  std::vector<std::string> gears;  // roles: pinion/wheel, sun/planet/ring, driver/idler/driven
  std::vector<Attribute> attributes;
  std::vector<std::string> presets;
  std::string likeOf;
  std::vector<SpectrumBin> spectrum;  // the rating's load spectrum, empty without one
  Span span;
  const Attribute* find(const std::string& name) const;
};

struct Let {
  std::string name;
  ExprPtr expr;
  Span span;
};

struct Objective {
  bool minimize = true;
  ExprPtr expr;
  std::string text;
  Span span;
};

// A named setting of a scene, effect, split, study or accuracy block.
struct Setting {
  std::string name;   // "settle", "torsion_shaft.diameter"
  Q key = Q::None;    // resolved by lowering
  int choice = -1;    // an enumerated value: its position in the catalogue row's words
  std::vector<int> choices;  // a list of enumerated values (`methods in {rk8pd, msbdf}`)
  int stage = -1;     // a stage-valued setting (`between`): the stage's index
  Dim dim;
  bool integer = false;
  bool meshPeriods = false;  // value counts the scene's mesh periods
  std::optional<Number> value;
  std::string symbol;        // enumerated value: `preloaded`, `rk8pd`, a stage name, a scene (sceneRef)
  bool sceneRef = false;
  ExprPtr expr;              // when the value is an expression over other quantities
  std::vector<Number> members;  // `rtol in {…}`
  std::optional<Number> lo, hi; // `harmonics in 1..8`, a shaft's `diameter in 50 mm..70 mm`
  std::vector<std::string> memberTexts; // a shaft setting's set, as written
  Span span;
  Setting clone() const;
  // A range or a set in place of one value (a shaft's searched setting).
  bool searched() const { return !value && (lo || !members.empty()); }
};

const Setting* findSetting(const std::vector<Setting>& s, const std::string& name);
const Setting* findSetting(const std::vector<Setting>& s, Q key);

struct Effect {
  std::string name;
  cat::Effect kind = cat::Effect::VaryingStiffness;  // resolved by lowering
  std::vector<Setting> params;
  Span span;
};

struct SceneOutput {
  std::string function;  // rms, peak, mean, min, max, spectrum, plot, or "" for a bare name (modes)
  std::string signal;
  bool bare = true;                       // resolved by lowering: no function
  cat::SignalFn fn = cat::SignalFn::Rms;  // when not bare
  cat::Signal id = cat::Signal::Displacement;
  std::string mesh;  // a whole-gearbox scene's mesh, "stage.mesh" or "stage" (docs/dynamics.md)
  int order = 0;     // the mesh order a function takes (`harmonic(x, 2)`); 0: none
  std::string key() const {
    std::string s = mesh.empty() ? signal : signal + "(" + mesh + ")";
    if (order > 0) s += ", " + std::to_string(order);
    return function.empty() ? s : function + "(" + s + ")";
  }
  Span span;
};

struct Scene {
  std::string name;
  std::string target;  // stage name, or "" for the whole gearbox
  int stage = -1;      // resolved by lowering: the target's index, -1 the whole gearbox
  std::vector<Effect> effects;
  std::vector<Setting> settings;  // settle, record, samples, duration, ramp
  std::vector<Setting> accuracy;  // method, rtol, atol, max_step, …
  std::vector<SceneOutput> outputs;
  Span span;
  bool hasEffect(const std::string& n) const;
  const Effect* findEffect(cat::Effect kind) const;
  cat::Method method() const;  // the accuracy block's method, or the default
  Scene clone() const;         // a sweep of an effect parameter changes a copy
};

struct ModRule {
  std::string target;  // "tip_relief", "pinion.lead_crowning"
  int gear = -1;       // resolved by lowering: the gear it is for, -1 both
  int modTarget = -1;  // resolved by lowering: the target's position in cat::modificationTargets()
  ExprPtr value;
  ExprPtr when;
  std::string text;
  Span span;
};

struct Modify {
  std::string stage;
  int stageIndex = -1;  // resolved by lowering
  std::vector<ModRule> rules;
  Span span;
};

struct Split {
  std::string name;
  std::vector<Setting> settings;  // between, branches, torsion_shaft.length, install, …
  Span span;
};

// A shaft of the gearbox (docs/language.md, "Shafts and bearings"): positions along its own axis from its left end.
struct Shaft {
  std::string name;
  std::vector<Setting> settings;  // material (symbol), shear, speed, heat_treatment_diameter, life.*
  struct Segment {
    Number x0, x1;
    std::vector<Setting> settings;  // diameter, bore, roughness
    Span span;
  };
  std::vector<Segment> segments;  // contiguous from 0, left to right
  enum class Place : std::uint8_t { Gear, Coupling, Bearing, Load, Disk, Notch };
  struct Placed {
    Place kind = Place::Load;
    std::string name;  // a bearing's name, a gear's `stage.gear`
    Number at;
    int stage = -1, gear = -1;  // a gear: its stage and position
    int notch = -1;             // a notch: its kind, in the order of cat::notchKinds()
    std::vector<Setting> settings;
    Span span;
  };
  std::vector<Placed> placed;
  Span span;
  int bearingIndex(const std::string& n) const;  // among the bearings, in order; -1 if none
};

struct Study {
  enum Kind { Sweep, WorkPrecision };
  std::string name;
  Kind kind = Sweep;
  std::string target;  // swept quantity path, or the scene of a work-precision study
  QuantityRef swept;   // resolved by lowering: the swept quantity
  // An effect parameter of a scene (`vibration.damping.ratio`), resolved by lowering: the
  // scene, the effect's position in it and the parameter's key; scene < 0 otherwise.
  struct EffectParam {
    int scene = -1, effect = -1;
    Q key = Q::None;
  } sweptEffect;
  // `hs.tip_relief in {0 um, 20 um};` in a sweep: the sweep is run once per value, a line each
  // on its plot. Resolved by lowering like the swept quantity.
  struct Series {
    std::string target;
    QuantityRef ref;
    EffectParam effect;
    Dim dim;
    std::vector<Number> members;
  };
  std::optional<Series> series;
  // The swept quantity and the series as the baseline gearbox names them (`relative(…)` in an
  // output reads the baseline at the same point), resolved by lowering.
  QuantityRef sweptInBaseline, seriesInBaseline;
  EffectParam sweptEffectInBaseline, seriesEffectInBaseline;
  int scene = -1;      // resolved by lowering: the scene of a work-precision study
  std::optional<Dim> dim;
  std::optional<Number> lo, hi, step;
  std::vector<ExprPtr> outputs;
  std::vector<std::string> outputTexts;
  bool plot = false;
  std::vector<Setting> settings;  // rtol in {…}, harmonics in a..b, methods in {…}
  Span span;
};

struct Report {
  std::optional<long long> top;
  ExprPtr sortBy;
  std::vector<ExprPtr> columns;
  std::vector<std::string> columnTexts;
  std::vector<bool> ratioColumn;  // resolved by lowering: the column is the gearbox ratio, always shown
  bool ranges = false;  // `ranges;`: beside each column, its interval over the freedoms' whole box
  Span span;
};

// One line of `tolerances { main.face_width +- 1 mm; }`: a stage attribute's scatter.
struct Tolerance {
  std::string target;  // "main.face_width"
  QuantityRef ref;     // resolved by lowering
  Dim dim;
  double amount = 0;   // SI, >= 0
  Span span;
};

struct Gearbox {
  std::string name;
  std::string baseline;  // the gearbox it extends, or ""
  std::vector<Stage> stages;
  std::vector<Let> lets;
  std::vector<Rule> rules;
  std::vector<std::vector<std::string>> interchangeable;
  std::vector<Objective> objectives;
  std::vector<Setting> operating;
  std::vector<Scene> scenes;
  std::vector<Modify> modifies;
  std::vector<Split> splits;
  std::vector<Shaft> shafts;
  std::vector<Study> studies;
  std::vector<Tolerance> tolerances;
  std::vector<Setting> toleranceSettings;  // samples, distribution, seed: Monte Carlo (docs/optimisation.md)
  std::optional<Report> report;
  Span span;
  const Stage* findStage(const std::string& name) const;
  int stageIndex(const std::string& name) const;
  int splitIndex(const std::string& name) const;
  int shaftIndex(const std::string& name) const;
};

struct Material {
  std::string name;
  std::vector<Setting> properties;
  Span span;
};

// A `const` as checked: its value in SI (an editor's hover shows it; `dump ir` does not).
struct ConstValue {
  std::string name;
  units::Number value;
  units::Dim dim;
  bool isSet = false;  // a set of values, not one number
};

struct Program {
  std::vector<Material> materials;
  std::vector<Gearbox> gearboxes;
  std::vector<ConstValue> consts;
  const Material* findMaterial(const std::string& name) const;
  int materialIndex(const std::string& name) const;
};

// `dump ir`: a stable text rendering of the whole program.
std::string print(const Program& p);
std::string print(const Expr& e);

} // namespace gbx::ir
