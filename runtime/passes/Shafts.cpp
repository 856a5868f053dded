#include "passes/Shafts.h"

#include <algorithm>
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
    // The deflection line and the bending moment, sampled along the shaft for the charts.
    const auto& sol = s->solution;
    double x0 = sol.x.front(), x1 = sol.x.back();
    std::vector<double> at;
    for (int k = 0; k <= 200; ++k)
      at.push_back(x0 + (x1 - x0) * k / 200);
    // Each station from both sides: a couple there makes the moment jump.
    for (double x : sol.x)
      at.insert(at.end(), {std::max(x0, x - 1e-9), x});
    std::sort(at.begin(), at.end());
    for (double x : at) {
      r.lineX.push_back(x);
      r.lineDeflection.push_back(sol.deflectionAt(x));
      r.lineMoment.push_back(
          std::hypot(sol.moment(shaft::Solution::Plane::Y, x), sol.moment(shaft::Solution::Plane::Z, x)));
    }
    out.warnings.insert(out.warnings.end(), s->warnings.begin(), s->warnings.end());
    out.shafts.push_back(std::move(r));
  }
  return out;
}

} // namespace gbx::rt::passes
