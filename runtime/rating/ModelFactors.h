#pragma once
// The rating's factors from the models (docs/rating.md, docs/rating.md): K_Hbeta from the
// stage's thin-slice loaded mesh (a contact analysis, which ISO 6336-1 method B admits),
// K_v from a periodic scene of the stage (ISO 6336-1 method A).
#include <string>
#include <vector>

#include "dynamics/LoadedMesh.h"
#include "model/Evaluator.h"

namespace gbx::rt::rating {

// The line load across the face from a contact analysis.
struct FaceLoad {
  double KHbeta = 0;            // the largest slice line load over the mean
  double peak = 0;              // where it lies, as y/b from the coupling end (0..1)
  double meanLineLoad = 0;      // F/b along the line of action, N/m
  double faceWidth = 0;         // b, m
  std::vector<double> lineLoad; // per slice from y = 0, the mean over one mesh period, N/m
  int slices = 0, positions = 0;
  std::vector<std::string> model; // how the loaded mesh was built
  std::string shafts;             // with both gears on shafts: which, and how the fixed point settled
  std::string failure;            // set when it could not be computed
};

// The slices and positions a contact analysis uses.
inline constexpr int kFaceSlices = 100, kFacePositions = 128;

// The distribution of one loaded-mesh input (its sliceLoads set here).
FaceLoad faceLoad(dyn::LoadedMeshInput in);

// The stage's contact analysis at the design: its loaded mesh carrying `load` (N: the
// standard's F_m = F_t K_A K_gamma K_v, the load its stiffnesses and K_Hbeta are defined
// with), the slices at c_gammabeta, and the lead deviation `fma` (m) in the adverse sense.
// Repeated calls with the same inputs are answered from a cache.
// `deflectionScale` (F_m / F_t) brings the pinion's deflections, found at the operating
// torque, to that load.
FaceLoad contactAnalysis(const Evaluator& ev, const Assignment& a, int stage, double load, double fma, double deflectionScale);

// K_v by method A: the peak periodic mesh force over the static one, from scene `scene` (an
// index into the model's scenes) at the design; with `estimate`, its own error estimate
// (relative) too, which costs the scene's reruns (the report asks for it, a rule does not).
struct SceneFactor {
  double Kv = 0, error = -1; // error < 0: not estimated
  std::string scene;
  std::string failure;
};
SceneFactor sceneDynamicFactor(const Evaluator& ev, const Assignment& a, int scene, bool estimate);

} // namespace gbx::rt::rating
