#pragma once
// Load sharing among the planets of a planetary stage (a static model; docs/rating.md
// "Load sharing of a planetary stage"): each planet is one load path, its sun-planet and
// planet-ring meshes in series; a planet's pin position error shortens or lengthens its path
// along the lines of action; the sun turns (and, floating, translates in its plane) until
// the paths carry the torque. K_gamma = the most loaded planet's share over the mean.
#include <vector>

namespace gbx::rt::rating {

struct LoadSharingInput {
  int planets = 0;
  double kSun = 0, kRing = 0;         // one planet's sun-planet and planet-ring mesh stiffness c_gamma b [N/m]
  double alphaSun = 0, alphaRing = 0; // the two meshes' working transverse pressure angles [rad]
  // Each planet's tangential pin position error [m] (missing ones 0); positive: displaced in
  // the sense the planet is pushed, so its meshes close later and it carries less.
  std::vector<double> pinError;
  bool floatingSun = false; // the sun's two translations free (else held by its bearings)
  double force = 0;         // the total tangential load of all planets' sun meshes [N]
};

struct LoadSharing {
  std::vector<double> share; // each planet's load over the mean load
  double Kgamma = 1;         // the largest share
  int unloaded = 0;          // planets that carry nothing (meshes open, or just touching)
};

// Throws std::domain_error with a sentence when the inputs admit no solution (no planets,
// no stiffness, no load, a floating sun whose loaded planets cannot balance it).
LoadSharing shareLoad(const LoadSharingInput& in);

} // namespace gbx::rt::rating
