#pragma once
// The runtime side of the stage-kind registry: what each kind computes (its derived
// quantities, stage-level and per gear), the rules its geometry implies for the search,
// and which scene model runs on it. One class per kind under model/kinds/; the list is
// in StageKinds.cpp. The registry test checks every catalogue row has its runtime row.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "catalogue/Keys.h"
#include "ir/Ir.h"
#include "model/Value.h"

namespace gbx::rt {

class Evaluator;
struct Assignment;
using cat::Q;

// What a kind's formulas see: the stage's attributes and derived quantities at a design.
struct KindContext {
  const Evaluator& ev;
  int stage;
  const Assignment& a;

  Value at(Q key) const;
  Value at(int gear, Q key) const;
  Value orZero(int gear, Q key) const;  // an optional attribute (profile shift) or 0
  Value derived(Q key) const;
  Value derived(int gear, Q key) const;
  Value gearbox(Q key) const;
  Value upstreamRatio() const;  // the product of the ratios before this stage
  Value material(Q property) const;
};

using DerivedFn = Value (*)(const KindContext&, int gear);

struct DerivedRow {
  Q key;
  bool perGear;  // a quantity of each gear (`pinion.d`), else of the stage
  DerivedFn fn;
};

// A rule the kind's geometry implies, applied by the search before the spec's own rules.
struct ImplicitRule {
  std::string text;  // as the elimination funnel names it
  Truth (*test)(const KindContext&);
};

enum class SceneModel { SingleMesh, Planetary, None };

class StageKindImpl {
public:
  StageKindImpl(ir::StageKind kind, SceneModel scene, std::vector<DerivedRow> rows, std::vector<ImplicitRule> rules);

  ir::StageKind kind;
  SceneModel scene;
  std::vector<DerivedRow> rows;
  std::vector<ImplicitRule> rules;
  // An attribute a condition of the kind fixes where it alone of its key is given as a
  // range (a planetary stage's shift, by concentricity): its key, and its value at a design
  // (invalid where no value in its range meets the condition).
  Q solvedKey = Q::None;
  DerivedFn solve = nullptr;

  DerivedFn stageFn(Q key) const { return stage_[static_cast<size_t>(key)]; }
  DerivedFn gearFn(Q key) const { return gear_[static_cast<size_t>(key)]; }

private:
  std::array<DerivedFn, cat::kKeyCount + 1> stage_{}, gear_{};
};

// The rows every kind shares: speeds and torques along the train.
std::vector<DerivedRow> trainRows();
// The rows of a pinion driving a wheel (spur, helical, bevel): the ratio, the mesh
// frequency, each gear's speed and torque; with the train's rows.
std::vector<DerivedRow> pinionWheelRows();
// The rows of gears cut to one plain `module` (planetary, idler): each gear's reference
// diameter z m and base radius; with the train's rows.
std::vector<DerivedRow> moduleGearRows();
// Teeth passing per second: a member's speed over 2 pi times its tooth count.
Value meshFrequency(const KindContext& c, Q speed, int gear);

const StageKindImpl& stageKindImpl(ir::StageKind kind);
const std::vector<const StageKindImpl*>& stageKindImpls();

// The kinds, each defined in model/kinds/.
namespace kinds {
const StageKindImpl& spur();
const StageKindImpl& helical();
const StageKindImpl& bevel();
const StageKindImpl& planetary();
const StageKindImpl& idler();
} // namespace kinds

} // namespace gbx::rt
