#pragma once
// The runtime side of the effect registry (compiler/catalogue/Effects.h): how each
// listed effect enters the single-mesh model (its terms in MeshEffects) and whether the
// planetary model implements it. An effect no scene lists is never applied.
#include <string>
#include <vector>

#include "dynamics/MeshModel.h"
#include "dynamics/SceneSupport.h"

namespace gbx::rt::dyn {

// Reads the effect's own row of the planned effects.
using MeshApply = void (*)(const SceneEffects& e, const SceneOverrides& ov, MeshParameters& p, MeshEffects& fx,
                           std::vector<std::string>& provenance);

struct EffectRow {
  cat::Effect id;
  MeshApply mesh;   // nullptr: the effect acts through the drive (sceneDrive)
  bool drive;       // shapes the drive's speed
  bool planetary;   // the planetary model implements it
  bool gearbox;     // the whole-gearbox model implements it
};

const std::vector<EffectRow>& effectRows();
const EffectRow* effectRow(cat::Effect id);

} // namespace gbx::rt::dyn
