#pragma once
// Catalogue rows outside the stage kinds: gearbox quantities, the operating point,
// material properties, scene and accuracy settings, split settings and results,
// work-precision settings, modification targets and the quantities modify rules read.
#include <string>
#include <string_view>
#include <vector>

#include "catalogue/Attr.h"

namespace gbx::cat {

const std::vector<AttrSpec>& gearboxQuantities();
const std::vector<AttrSpec>& operatingSettings();
const std::vector<AttrSpec>& materialProperties();
const std::vector<AttrSpec>& sceneSettings();
// `steady_state`'s words in the order sceneSettings() lists them (a setting's `choice`).
enum SteadyStateWord : int { kSteadyPeriodic = 0, kSteadyHarmonicBalance = 1 };
const std::vector<AttrSpec>& accuracySettings();
const std::vector<AttrSpec>& splitSettings();
const std::vector<AttrSpec>& splitOutputs();
const std::vector<AttrSpec>& workPrecisionSettings();
const std::vector<AttrSpec>& sweepSettings();
// `tolerances { …; samples = N; distribution = normal; seed = 1; }` (docs/optimisation.md).
const std::vector<AttrSpec>& toleranceSettings();
namespace distribution {
inline constexpr int Normal = 0, Uniform = 1;
}

// Sweep continuation choices, by their position in the `continuation` row's words.
namespace continuation {
inline constexpr int Natural = 0, Arclength = 1;
}

// Words that stand alone as a statement of a block (`plot;` in a study, `ranges;` in a
// report), resolved once by the checker.
enum class Flag { Plot, Ranges };
struct FlagSpec {
  Flag id;
  const char* word;
  const char* meaning;
};
const std::vector<FlagSpec>& flags();
const FlagSpec* findFlag(const std::string& word);

// Named blocks whose name decides what they hold (`tolerances { … }` in a gearbox,
// `accuracy { … }` in a scene, `work_precision of …` in a study), resolved through one table.
enum class Block { Unknown, Tolerances, Accuracy, WorkPrecision };
Block blockOf(std::string_view word);

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

// The results of a load-capacity rating: safeties, stresses and influence factors.
bool isRatingQuantity(Q key);
// The oil's test result a scuffing or micropitting quantity needs (the FZG or the FVA load
// stage); Q::None for every other key.
Q scuffingInput(Q key);

// Modification targets by their position in modificationTargets().
enum class Mod : int {
  TipRelief, TipReliefHeight, RootRelief, RootReliefHeight, ProfileCrowning,
  LeadCrowning, ThermalLeadRelief, EndRelief, EndReliefWidth, HelixSlope,
};
// A modification's amount (a relief, a crowning, a slope) reads in um; where it starts (a
// height, a width) in mm (docs/reports.md).
inline bool modificationReadsInMicrometres(Mod m) {
  return m != Mod::TipReliefHeight && m != Mod::RootReliefHeight && m != Mod::EndReliefWidth;
}

// Heat treatments of a material and the rating's life curves, by their words' positions.
namespace treatment {
inline constexpr int CaseHardened = 0, Nitrided = 1, ThroughHardened = 2;
}
namespace lifeCurve {
inline constexpr int Normal = 0, Optimum = 1;
}
// The pinion's helix hand and the end of its face where the torque enters (docs/rating.md),
// and the word `rating.face_load_factor` takes instead of a number.
namespace helixHand {
inline constexpr int Right = 0, Left = 1;
}
// The base oil (friction's lubricant factor) and how the oil reaches the mesh (X_S).
namespace oilBase {
inline constexpr int Mineral = 0, Polyalphaolefin = 1, Polyglycol = 2, PhosphateEster = 3, Traction = 4;
}
namespace oilSupply {
inline constexpr int Dip = 0, Injection = 1;
}
namespace torqueSide {
inline constexpr int Coupling = 0, Free = 1;
}
namespace faceLoad {
inline constexpr int ContactAnalysis = 0;
}
// The word `rating.mesh_load_factor` of a planetary stage takes, and the sun's support.
namespace meshLoad {
inline constexpr int LoadSharing = 0;
}
namespace sunSupport {
inline constexpr int Floating = 0, Fixed = 1;
}
// A setting of a planet's bearings (`planet.bearing { … }`).
inline bool isPlanetBearingSetting(Q k) {
  return k == Q::PlanetBearingKind || k == Q::PlanetBearingC || k == Q::PlanetBearingC0 || k == Q::PlanetBearingCount ||
         k == Q::PlanetBearingPitchDiameter || k == Q::PlanetBearingContamination;
}
// How a bevel pair is mounted (ISO 10300-1 K_Hbeta-be): straddle or cantilever bearings.
namespace mounting {
inline constexpr int BothStraddle = 0, OneCantilever = 1, BothCantilever = 2;
}

// Install choices of a split, by their position in the `install` row's words.
namespace install {
inline constexpr int Free = 0, Preloaded = 1;
}

} // namespace gbx::cat
