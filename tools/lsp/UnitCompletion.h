#pragma once
// Completion of units (docs/language.md): where one may be written, and which fit there. Read
// from the text itself, so that the half-typed statement being edited (which does not parse)
// is understood.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gbx::cat {
struct KindSpec;
}

namespace gbx::lsp {

struct UnitItem {
  std::string label;  // the unit as written (`mm`, `N*m`)
  std::string detail; // its dimension (`a length`)
  std::string sortText;
};

struct UnitCompletion {
  std::string typed; // the part of a unit word already typed before the cursor ("" for none)
  std::vector<UnitItem> items;
};

// The units to offer at byte `offset` of `text`: after a number on its line (`16 |`, `16 m|`,
// `16 N*|`). When the statement sets a catalogue row (a stage attribute, an effect parameter,
// an operating, scene, accuracy, split or material setting), only units of its dimension,
// the display unit first; otherwise all. nullopt where no unit can stand.
// `stageKindOf(gearbox, stage)` finds a stage the text of the gearbox does not declare
// (one it inherits); it may be empty.
using StageKindOf = std::function<const cat::KindSpec*(const std::string& gearbox, const std::string& stage)>;
std::optional<UnitCompletion> unitCompletion(const std::string& text, size_t offset,
                                             const StageKindOf& stageKindOf = {});

} // namespace gbx::lsp
