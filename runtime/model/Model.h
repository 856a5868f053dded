#pragma once
#include <cstdint>
// A gearbox of the IR arranged for search: its integer decision variables as slots with
// explicit value lists, its continuous freedoms as box dimensions, per stage, and a table
// from (gear, key) to the attribute, slot or freedom that gives it.
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "model/ScenePlan.h"
#include "model/Value.h"

namespace gbx::rt {

class StageKindImpl;
using cat::Q;

// A shaft's setting searched over a set or a range (`diameter in 50 mm..70 mm`): a slot or
// a freedom of the stage of the first gear the shaft carries (the first stage when it carries
// none), kept out of that stage's (gear, key) table.
struct ShaftSetting {
  int shaft = -1;
  const ir::Setting* setting = nullptr;
};

struct Slot {
  std::string path;  // "upper.pinion.z"
  std::string attr;  // "pinion.z"
  int stage = 0;
  int gear = -1;
  Q key = Q::None;
  units::Dim dim;
  std::vector<Value> values;  // the domain, ascending
  std::vector<std::string> texts; // the members as written, when all are literals
  ShaftSetting shaft;
};

struct Freedom {
  std::string path;
  std::string attr;
  int stage = 0;
  int gear = -1;
  Q key = Q::None;
  units::Dim dim;
  ShaftSetting shaft;
  double lo = 0, hi = 0;
  // Fixed by an equation of its stage's kind (a planetary stage's one shift given as a range,
  // by its concentricity): computed at each design, never searched; not among its stage's
  // `freedoms`.
  bool solved = false;
};

// A stage's elastic constants and density: its material's, or steel's (assumed = true).
struct Elastic {
  double E = 206e9, nu = 0.3, density = 7850;
  bool assumed = true;
};

struct StageInfo {
  const ir::Stage* ir = nullptr;
  const StageKindImpl* kind = nullptr;
  const ir::Material* material = nullptr;  // the material it names, found once
  std::vector<const ir::Material*> gearMaterial;  // per gear: its own (`pinion.material`), else the stage's
  Elastic elastic;                         // read from it once
  std::vector<int> slots;
  std::vector<int> freedoms;
  // Nothing of its attributes reads another stage or the gearbox, and the gearbox has no
  // splits: the rest of the design reaches it only through its operating point.
  bool selfContained = false;
  // Both its gears on shafts: its rating reads the shafts, and so every stage whose gears
  // they carry, up to this one (-1: not on shafts).
  int shaftStagesUpTo = -1;
  // (gear + 1) * kKeyCount + key: what gives the attribute.
  struct Entry {
    const ir::Attribute* attr = nullptr;
    int slot = -1, freedom = -1;
  };
  std::vector<Entry> entries;
  const Entry& entry(int gear, Q key) const {
    static const Entry none;
    if (key == Q::None) return none;
    size_t i = static_cast<size_t>(gear + 1) * cat::kKeyCount + static_cast<size_t>(key);
    return i < entries.size() ? entries[i] : none;
  }
};

class Model {
public:
  Model(const ir::Program& program, const ir::Gearbox& gearbox);

  const ir::Program& program;
  const ir::Gearbox& gearbox;
  // Unique per model built in this process: a cache keyed on it cannot meet a later model
  // at the same address.
  const std::uint64_t serial;
  std::vector<StageInfo> stages;
  std::vector<Slot> slots;
  std::vector<Freedom> freedoms;
  std::vector<ScenePlan> scenes;  // the gearbox's scenes, planned once, in its order
  // Per shaft, the slots and freedoms of its searched settings.
  struct ShaftDomains {
    std::vector<int> slots, freedoms;
  };
  std::vector<ShaftDomains> shaftDomains;
  bool shaftFreedoms = false; // some shaft setting is a continuous freedom

  int stageIndex(const std::string& name) const { return gearbox.stageIndex(name); }
  const ir::Attribute* attribute(int stage, int gear, Q key) const { return info(stage).entry(gear, key).attr; }
  const ir::Attribute* attribute(int stage, Q key) const { return attribute(stage, -1, key); }
  int slotOf(int stage, int gear, Q key) const { return info(stage).entry(gear, key).slot; }
  int freedomOf(int stage, int gear, Q key) const { return info(stage).entry(gear, key).freedom; }
  // SI value of an operating setting, when given.
  std::optional<double> operating(Q key) const;
  // The material a stage names, or nullptr.
  const ir::Material* material(int stage) const;
  // A gear's material: its own, else the stage's, or nullptr.
  const ir::Material* material(int stage, int gear) const;
  const StageInfo& info(int stage) const { return stages[static_cast<size_t>(stage)]; }

private:
  void addShaftDomains();

public:
  bool hasStage(int stage) const { return stage >= 0 && static_cast<size_t>(stage) < stages.size(); }
};

// A point of the search: a value index per slot (-1 when unassigned) and the current
// interval of every freedom.
struct Assignment {
  std::vector<int> choice;
  std::vector<std::pair<double, double>> box;
  std::optional<Rational> ratio;  // the gearbox ratio when already known exactly
  std::optional<double> ratioApprox;  // or approximately, to screen designs cheaply
  // The ratio before stage `upstreamStage`, given instead of the choices upstream: a search
  // asks a downstream stage's rules over the upstream ratios its designs can have (-1: none).
  int upstreamStage = -1;
  double upstreamRatio = 1;
  explicit Assignment(const Model& m);
};

// A shaft setting's value at the design: its own, or its slot's or freedom's (an interval
// while the search has not decided it; invalid for a slot not chosen yet).
Value shaftSettingValue(const Model& m, const ir::Setting& s, const Assignment& a);

// Whether an expression reads nothing but stage `stage`'s quantities and materials.
bool readsOwnStage(const ir::Expr& e, int stage, int depth = 0);

} // namespace gbx::rt
