#pragma once
// The rating quantities of a stage of external meshes (spur, helical, idler) as derived
// rows: each gathers the stage's geometry, load, material, `rating { … }` inputs and
// `modify` lead and tip rules at the design, rates each mesh and reads one factor. A gear
// in two meshes (the idler) takes the mesh that governs its contact or bending safety;
// a stage factor is that of the stage's governing mesh.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/StageKind.h"
#include "rating/Iso6336.h"
#include "rating/ModelFactors.h"
#include "rating/Spectrum.h"

namespace gbx::rt::rating {

std::vector<DerivedRow> pairRows();
// A planetary stage's planet bearings: each bearing's load, basic and modified life (ISO 281).
std::vector<DerivedRow> planetBearingRows();

// The stage's load spectrum (ISO 6336-6) as shares of its operating torque and of its life:
// a bin's torque over the stage's input torque, its cycles as revolutions of the input member
// over those of the life. Empty without one; nullopt, with the reason, where a bin's torque or
// cycles need a load or life the design lacks.
std::optional<std::vector<SpectrumBin>> spectrumBins(const KindContext& c, std::string* why);

// A value the spec gives (fixed, chosen or free), not the one a kind derives when absent.
Value givenOnly(const KindContext& c, int gear, Q k);

// What the rating reads of a gear's material (its own, else the stage's), SI.
struct GearMaterial {
  double sigmaHlim = 0, sigmaFlim = 0, E = 0, nu = 0, density = 0, brinell = kNaN;
  Treatment treatment = Treatment::CaseHardened;
};
// The materials of two gears of the stage; nullopt, with the reason, when one lacks a number.
std::optional<std::array<GearMaterial, 2>> materialsOf(const KindContext& c, int g0, int g1, std::string* why);

// Each gear's material into a pair's inputs (cylindrical or bevel); the pair's own values are
// the driving gear's (the blank masses of K_v share its density).
template <class Pair>
void applyMaterials(Pair& in, const std::array<GearMaterial, 2>& mats) {
  for (size_t k = 0; k < 2; ++k) {
    const GearMaterial& m = mats[k];
    auto& g = in.gear[k];
    g.sigmaHlim = m.sigmaHlim;
    g.sigmaFlim = m.sigmaFlim;
    g.treatment = m.treatment;
    g.E = m.E;
    g.nu = m.nu;
    g.brinell = m.brinell;
  }
  in.treatment = mats[0].treatment;
  in.E = mats[0].E;
  in.nu = mats[0].nu;
  in.density = mats[0].density;
}

// One mesh of a stage rated: its driving and driven gear's positions in the stage.
struct MeshRating {
  int driving, driven;
  bool internal;  // the driven gear is internal (its tooth root is not rated)
  PairInput input;
  PairRating rating;
  std::optional<FaceLoad> faceLoad;  // K_Hbeta by contact analysis
  std::optional<SceneFactor> kv;     // K_v by method A
  // Where each gear's deviations come from (driving, driven): the spec, else the grade.
  struct Given {
    bool pitch = false, profileForm = false, profileTotal = false, helix = false;
  };
  std::array<Given, 2> given;
  std::string loadSharing; // how K_gamma came from the planets' load sharing (empty: given or tabulated)
};

// Every mesh of the stage rated at the design (a freedom spanning an interval is taken at
// its middle), or none when an input is missing or the geometry admits no rating; the
// reason then goes to `why`.
std::vector<MeshRating> rateStage(const KindContext& c, std::string* why = nullptr);

// Scuffing and micropitting of a rated external mesh by one edition of the methods; none for
// an internal mesh, a mesh without the oil's load stages or one whose path of contact does
// not pass the pitch point.
std::optional<ScuffingRating> scuffingOf(const PairInput& in, const PairRating& r, ScuffingEdition edition = ScuffingEdition::TS,
                                         std::string* why = nullptr);

} // namespace gbx::rt::rating
