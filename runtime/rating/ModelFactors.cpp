#include "rating/ModelFactors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "dynamics/LoadedMeshInputs.h"
#include "dynamics/Scene.h"
#include "model/Deadline.h"
#include "model/Recent.h"
#include "shaft/ShaftMesh.h"

namespace gbx::rt::rating {

FaceLoad faceLoad(dyn::LoadedMeshInput in) {
  FaceLoad out;
  in.sliceLoads = true;
  out.slices = in.slices;
  out.positions = in.positions;
  dyn::LoadedMeshTable t = dyn::loadedMesh(in);
  if (!t.failure.empty()) {
    out.failure = t.failure;
    return out;
  }
  if (!(in.load > 0)) {
    out.failure = "the mesh carries no load";
    return out;
  }
  out.lineLoad = t.sliceLineLoad;
  out.meanLineLoad = in.load / in.g.faceWidth;
  out.faceWidth = in.g.faceWidth;
  // The slice that carries the most over a period, and where it lies.
  auto top = std::max_element(out.lineLoad.begin(), out.lineLoad.end());
  size_t j = static_cast<size_t>(top - out.lineLoad.begin());
  out.KHbeta = *top / out.meanLineLoad;
  out.peak = (static_cast<double>(j) + 0.5) / static_cast<double>(out.lineLoad.size());
  return out;
}

namespace {

constexpr double kShaftTolerance = 1e-6; // the line load's largest change over its peak
constexpr int kShaftIterations = 50;

// The loaded mesh of the stage at the design, with the slices at c_gammabeta.
bool meshInput(const Evaluator& ev, const Assignment& a, int stage, double load, const dyn::LoadedMeshUse& use,
               dyn::LoadedMeshInput& in, std::vector<std::string>& prov, std::string& failure) {
  try {
    in = dyn::loadedMeshInput(ev, a, stage, load, kFaceSlices, kFacePositions, prov, use);
  } catch (const dyn::SceneFailure& f) {
    failure = f.what;
    return false;
  }
  // Across the face the standard's stiffness is c_gammabeta = 0.85 c_gammaalpha (ISO 6336-1
  // cl. 9): the slices carry it. Pitch and profile deviations and tip relief load the pairs
  // along the path of contact, which K_Halpha rates: the face's distribution is the lead's.
  in.singleStiffness *= 0.85;
  prov.push_back(
      "contact analysis: the slices' stiffness is c_gammabeta = 0.85 c_gammaalpha, as ISO 6336-1 takes it across the "
      "face; the "
      "pitch and profile deviations and the tip relief, which load the pairs along the path (K_Halpha), are left out");
  return true;
}

// The next share from the steps so far (x_k, G(x_k)): Anderson's type II over the last three,
// kept a share (non-negative, summing to 1).
Eigen::VectorXd anderson(std::vector<Eigen::VectorXd>& xs, std::vector<Eigen::VectorXd>& gs) {
  constexpr size_t depth = 3;
  if (xs.size() > depth + 1) {
    xs.erase(xs.begin());
    gs.erase(gs.begin());
  }
  size_t k = xs.size() - 1, m = k;
  Eigen::VectorXd next = gs[k];
  if (m > 0) {
    Eigen::MatrixXd dF(xs[0].size(), static_cast<Eigen::Index>(m)), dG(xs[0].size(), static_cast<Eigen::Index>(m));
    for (size_t i = 0; i < m; ++i) {
      dF.col(static_cast<Eigen::Index>(i)) = (gs[i + 1] - xs[i + 1]) - (gs[i] - xs[i]);
      dG.col(static_cast<Eigen::Index>(i)) = gs[i + 1] - gs[i];
    }
    Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(gs[k] - xs[k]);
    if (gamma.allFinite()) next -= dG * gamma;
  }
  next = next.cwiseMax(0.0);
  double sum = next.sum();
  return sum > 0 ? Eigen::VectorXd(next / sum) : gs[k];
}

// Both gears on shafts: the shafts carry the mesh force as the contact analysis spreads it
// across the face, and the contact analysis takes the shafts' separation; from an even
// spread, until the line load stops changing.
FaceLoad shaftFixedPoint(const Evaluator& ev, const Assignment& a, int stage, double load, const dyn::LoadedMeshUse& base,
                         const MeshShafts& ms, dyn::LoadedMeshInput in, std::vector<std::string> prov) {
  FaceLoad out;
  const Eigen::Index S = kFaceSlices;
  Eigen::VectorXd share = Eigen::VectorXd::Constant(S, 1.0 / kFaceSlices);
  // Anderson's mixing over the last few steps: the plain iteration contracts by about the
  // shafts' share of the compliance across the face, too slowly for a search.
  std::vector<Eigen::VectorXd> xs, gs;
  double last = std::numeric_limits<double>::infinity(), relax = 1;
  for (int it = 1; it <= kShaftIterations; ++it) {
    out = faceLoad(in);
    if (!out.failure.empty()) return out;
    Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(out.lineLoad.data(), S);
    g /= g.sum();
    double change = (g - share).cwiseAbs().maxCoeff();
    if (change <= kShaftTolerance * g.maxCoeff()) {
      const auto& shafts = ev.model().gearbox.shafts;
      out.shafts = fmt::format("shafts {}, {}: fixed point in {} iteration{} (line load to {:g})",
                               shafts[static_cast<size_t>(ms.pinion)].name, shafts[static_cast<size_t>(ms.wheel)].name, it,
                               it == 1 ? "" : "s", kShaftTolerance);
      out.model = std::move(prov);
      return out;
    }
    // A residual that grows: the mixing overshot (a slice leaving or entering contact bends
    // the map): start its history again from a damped plain step.
    if (change > last) {
      xs.clear();
      gs.clear();
      relax = std::max(0.125, relax * 0.5);
    }
    last = change;
    xs.push_back(share);
    gs.push_back(share + relax * (g - share));
    share = anderson(xs, gs);
    std::string why;
    dyn::LoadedMeshUse use = base;
    use.shaftProfile = shaftSeparation(ev, a, stage, ms, std::vector<double>(share.data(), share.data() + S), kFaceSlices + 1,
                                       &why);
    if (use.shaftProfile.empty()) {
      out.failure = "the shafts: " + why;
      return out;
    }
    for (double& g : use.shaftProfile)
      g *= base.deflectionScale;
    prov.clear();
    if (!meshInput(ev, a, stage, load, use, in, prov, out.failure)) return out;
  }
  out.failure = fmt::format("the shafts and the line load did not settle in {} iterations", kShaftIterations);
  return out;
}

} // namespace

FaceLoad contactAnalysis(const Evaluator& ev, const Assignment& a, int stage, double load, double fma, double deflectionScale) {
  thread_local Recent<std::pair<std::uint64_t, std::vector<double>>, FaceLoad> cache;
  std::vector<std::string> prov;
  dyn::LoadedMeshInput in;
  dyn::LoadedMeshUse use{fma, true, deflectionScale, {}, 0};
  FaceLoad out;
  auto ms = meshShafts(ev.model().gearbox, stage);
  if (ms) {
    // The shafts under an even spread: what every later step depends on, and the cache's key.
    std::string why;
    use.shaftProfile = shaftSeparation(ev, a, stage, *ms, std::vector<double>(kFaceSlices, 1.0 / kFaceSlices),
                                       kFaceSlices + 1, &why);
    if (use.shaftProfile.empty()) {
      out.failure = "the shafts: " + why;
      return out;
    }
    for (double& g : use.shaftProfile)
      g *= deflectionScale;
    use.sense = use.shaftProfile.back() >= use.shaftProfile.front() ? 1.0 : -1.0;
  }
  if (!meshInput(ev, a, stage, load, use, in, prov, out.failure)) return out;
  auto key = std::make_pair(ev.model().serial, dyn::loadedMeshKey(in));
  if (const FaceLoad* hit = cache.find(key)) return *hit;
  if (ms) {
    use.shaftProfile.clear();
    out = shaftFixedPoint(ev, a, stage, load, use, *ms, in, prov);
  } else {
    out = faceLoad(in);
    out.model = std::move(prov);
  }
  return cache.put(std::move(key), std::move(out));
}

SceneFactor sceneDynamicFactor(const Evaluator& ev, const Assignment& a, int scene, bool estimate) {
  thread_local Recent<std::pair<std::uint64_t, std::vector<double>>, SceneFactor> cache;
  const Model& m = ev.model();
  SceneFactor out;
  if (scene < 0 || static_cast<size_t>(scene) >= m.scenes.size()) {
    out.failure = "the scene it names is not a scene of this gearbox";
    return out;
  }
  std::vector<double> key = {static_cast<double>(scene), estimate ? 1.0 : 0.0};
  for (int c : a.choice)
    key.push_back(c);
  for (const auto& [lo, hi] : a.box) {
    key.push_back(lo);
    key.push_back(hi);
  }
  key.push_back(-1);
  for (double v : ev.offsetKey())
    key.push_back(v);
  key.push_back(-2);
  for (double v : ev.overrideKey())
    key.push_back(v);
  auto k = std::make_pair(m.serial, std::move(key));
  if (const SceneFactor* hit = cache.find(k)) return *hit;
  const ScenePlan& plan = m.scenes[static_cast<size_t>(scene)];
  out.scene = plan.name;
  dyn::SceneOverrides ov;
  ov.evaluator = &ev;
  ov.keepSeries = false;
  ov.dynamicFactor = true;
  ov.estimateError = estimate;
  dyn::SceneResult r = dyn::runScene(m, a, plan, ov);
  const dyn::SceneNumber* n = r.failure.empty() ? r.find(cat::SignalFn::Peak, cat::Signal::DynamicFactor) : nullptr;
  if (!r.failure.empty()) {
    out.failure = r.failure;
    if (Deadline::expired()) return out; // cut short by the time limit: not this design's answer
  } else if (!n || !std::isfinite(n->value)) {
    out.failure = fmt::format("scene `{}` has no steady dynamic factor{}", plan.name,
                              r.unstable ? " (its periodic response is unstable)" : "");
  } else {
    out.Kv = n->value;
    if (estimate) out.error = std::isfinite(n->error) ? n->error : r.errorEstimate;
  }
  return cache.put(std::move(k), std::move(out));
}

} // namespace gbx::rt::rating
