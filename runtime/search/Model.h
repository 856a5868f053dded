#pragma once
// A gearbox of the IR arranged for search: its integer decision variables as slots with
// explicit value lists, its continuous freedoms as box dimensions, per stage.
#include <map>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "search/Value.h"

namespace gbx::rt {

struct Slot {
  std::string path;  // "upper.pinion.z"
  std::string attr;  // "pinion.z"
  int stage = 0;
  std::vector<Value> values;  // the domain, ascending
};

struct Freedom {
  std::string path;
  std::string attr;
  int stage = 0;
  double lo = 0, hi = 0;
};

struct StageInfo {
  const ir::Stage* ir = nullptr;
  std::vector<int> slots;
  std::vector<int> freedoms;
  std::map<std::string, const ir::Attribute*> attrs;
};

class Model {
public:
  Model(const ir::Program& program, const ir::Gearbox& gearbox);

  const ir::Program& program;
  const ir::Gearbox& gearbox;
  std::vector<StageInfo> stages;
  std::vector<Slot> slots;
  std::vector<Freedom> freedoms;

  int stageIndex(const std::string& name) const;
  const ir::Attribute* attribute(int stage, const std::string& name) const;
  int slotOf(int stage, const std::string& attr) const;
  int freedomOf(int stage, const std::string& attr) const;
  // SI value of an operating setting, when given.
  std::optional<double> operating(const std::string& name) const;
};

// A point of the search: a value index per slot (-1 when unassigned) and the current
// interval of every freedom.
struct Assignment {
  std::vector<int> choice;
  std::vector<std::pair<double, double>> box;
  std::optional<Rational> ratio;  // the gearbox ratio when already known exactly
  std::optional<double> ratioApprox;  // or approximately, to screen designs cheaply
  explicit Assignment(const Model& m);
};

} // namespace gbx::rt
