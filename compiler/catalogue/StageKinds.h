#pragma once
// The registry of stage kinds: one row per kind with its gears and its stage and gear
// attributes. Each kind has one runtime class under runtime/model/kinds/.
#include <string>
#include <vector>

#include "catalogue/Attr.h"
#include "ir/Ir.h"

namespace gbx::cat {

struct KindSpec {
  ir::StageKind kind;
  std::string name;
  std::vector<std::string> gears;
  std::vector<AttrSpec> stage;  // stage-level attributes
  std::vector<AttrSpec> gear;   // per-gear attributes (pinion.z)
};

// Every kind, in the order of ir::StageKind.
std::vector<const KindSpec*> stageKinds();
const KindSpec& kindSpec(ir::StageKind kind);
const KindSpec* findKind(const std::string& name);
// "pinion.z", "ratio": the attribute spec for a stage kind, or nullptr.
const AttrSpec* findAttr(const KindSpec& k, const std::string& path);
bool isGear(const KindSpec& k, const std::string& name);
// The gear's position in the kind's gear list, or -1.
int gearIndex(const KindSpec& k, const std::string& name);

// Gear positions by role: the first gear drives, the last is driven.
namespace gear {
inline constexpr int Pinion = 0, Wheel = 1;
inline constexpr int Sun = 0, Planet = 1, Ring = 2;
inline constexpr int Driver = 0, Idler = 1, Driven = 2;
} // namespace gear

} // namespace gbx::cat
