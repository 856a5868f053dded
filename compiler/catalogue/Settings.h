#pragma once
// Catalogue rows outside the stage kinds: gearbox quantities, the operating point,
// material properties, scene and accuracy settings, split settings and results,
// work-precision settings, modification targets and the quantities modify rules read.
#include <string>
#include <vector>

#include "catalogue/Attr.h"

namespace gbx::cat {

const std::vector<AttrSpec>& gearboxQuantities();
const std::vector<AttrSpec>& operatingSettings();
const std::vector<AttrSpec>& materialProperties();
const std::vector<AttrSpec>& sceneSettings();
const std::vector<AttrSpec>& accuracySettings();
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

// Quantities that exist only once the operating point is known (speeds, torques, loads
// and what follows from them).
bool dependsOnOperatingPoint(Q key);

// Install choices of a split, by their position in the `install` row's words.
namespace install {
inline constexpr int Free = 0, Preloaded = 1;
}

} // namespace gbx::cat
