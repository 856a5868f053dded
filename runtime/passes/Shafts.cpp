#include "passes/Shafts.h"

#include <cmath>

#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"

namespace gbx::rt::passes {

Shafts shafts(const Model& m, const Assignment& best) {
  Shafts out;
  Evaluator ev(m);
  for (size_t i = 0; i < m.gearbox.shafts.size(); ++i) {
    ShaftReport r;
    r.name = m.gearbox.shafts[i].name;
    std::string error;
    auto s = computeShaft(ev, static_cast<int>(i), best, &error);
    if (!s) {
      r.error = error;
      out.shafts.push_back(std::move(r));
      continue;
    }
    for (size_t k = 0; k < s->bearings.size(); ++k) {
      const auto& rc = s->solution.reactions[k];
      const auto& l = s->lives[k];
      r.bearings.push_back({s->bearings[k], shaft::kindName(s->kinds[k]), l.method, s->model.bearings[k].x, rc.radial(),
                            std::fabs(rc.Fx), l.P, l.L10h, l.Lnmh, l.s0});
    }
    for (const auto& g : s->gears)
      r.gears.push_back({g.gear, g.x, g.Ft, g.Fr, g.Fa});
    r.speed = s->speed;
    r.criticalSpeed = s->criticalSpeed;
    r.deflection = s->deflection;
    r.deflectionAt = s->deflectionAt;
    r.mass = s->mass;
    r.warnings = s->warnings;
    out.warnings.insert(out.warnings.end(), s->warnings.begin(), s->warnings.end());
    out.shafts.push_back(std::move(r));
  }
  return out;
}

} // namespace gbx::rt::passes
