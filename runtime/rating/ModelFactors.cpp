#include "rating/ModelFactors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "dynamics/LoadedMeshInputs.h"
#include "dynamics/Scene.h"
#include "model/Recent.h"

namespace gbx::rt::rating {

namespace {

} // namespace

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

FaceLoad contactAnalysis(const Evaluator& ev, const Assignment& a, int stage, double load, double fma, double deflectionScale) {
  thread_local Recent<std::pair<std::uint64_t, std::vector<double>>, FaceLoad> cache;
  std::vector<std::string> prov;
  dyn::LoadedMeshInput in;
  try {
    in = dyn::loadedMeshInput(ev, a, stage, load, kFaceSlices, kFacePositions, prov, {fma, true, deflectionScale});
  } catch (const dyn::SceneFailure& f) {
    FaceLoad out;
    out.failure = f.what;
    return out;
  }
  // Across the face the standard's stiffness is c_gammabeta = 0.85 c_gammaalpha (ISO 6336-1
  // cl. 9): the slices carry it. Pitch and profile deviations and tip relief load the pairs
  // along the path of contact, which K_Halpha rates: the face's distribution is the lead's.
  in.singleStiffness *= 0.85;
  prov.push_back(
      "contact analysis: the slices' stiffness is c_gammabeta = 0.85 c_gammaalpha, as ISO 6336-1 takes it across the "
      "face; the "
      "pitch and profile deviations and the tip relief, which load the pairs along the path (K_Halpha), are left out");
  auto key = std::make_pair(ev.model().serial, dyn::loadedMeshKey(in));
  if (const FaceLoad* hit = cache.find(key)) return *hit;
  FaceLoad out = faceLoad(in);
  out.model = std::move(prov);
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
