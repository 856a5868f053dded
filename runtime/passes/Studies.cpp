#include "passes/Studies.h"

#include "study/Sweep.h"
#include "study/WorkPrecision.h"

namespace gbx::rt::passes {

std::vector<StudyReport> studies(const Model& m, const Assignment& best, std::function<void(double)> progress,
                                 const Model* baseline, const Assignment* baseDesign) {
  std::vector<StudyReport> out;
  for (const auto& st : m.gearbox.studies) {
    if (st.kind == ir::Study::Sweep) {
      out.push_back({sweep(m, best, st, baseline, baseDesign), {}});
      continue;
    }
    const ScenePlan* scene = st.scene >= 0 ? &m.scenes[static_cast<size_t>(st.scene)] : nullptr;
    if (scene) out.push_back({workPrecision(m, best, st, *scene, progress), {}});
  }
  return out;
}

} // namespace gbx::rt::passes
