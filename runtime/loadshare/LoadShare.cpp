#include "loadshare/LoadShare.h"

#include <cmath>

#include <fmt/format.h>

#include "search/Evaluator.h"

namespace gbx::rt {

std::optional<SplitResult> computeSplit(const Evaluator& ev, const ir::Split& split, const Assignment& a, std::string* error) {
  auto fail = [&](const std::string& what) -> std::optional<SplitResult> {
    if (error) *error = fmt::format("split `{}`: {}", split.name, what);
    return std::nullopt;
  };
  auto setting = [&](const std::string& n) -> std::optional<double> {
    Value v = ev.quantity(split.name + "." + n, a);
    if (v.isNumber()) return v.mid();
    return std::nullopt;
  };
  const ir::Setting* between = ir::findSetting(split.settings, "between");
  int st = between ? ev.model().stageIndex(between->symbol) : -1;
  if (st < 0) return fail("`between` names no stage");
  auto branches = setting("branches"), L = setting("torsion_shaft.length"), d = setting("torsion_shaft.diameter"),
       G = setting("torsion_shaft.shear_modulus"), dl = setting("backlash_difference");
  if (!branches || !L || !d || !G || !dl) return fail("the torsion shaft and backlash difference must be given");
  Value wheelTorque = ev.derived(st, "output_torque", a), dI = ev.derived(st, "wheel.d", a);
  if (!wheelTorque.isNumber()) return fail("branch torques need the operating point");
  if (!dI.isNumber()) return fail("the stage-I wheel diameter needs its module");
  SplitResult r;
  double Jp = M_PI * std::pow(*d, 4) / 32.0;
  r.branchTorque = wheelTorque.mid() / *branches;
  r.twist = r.branchTorque * *L / (*G * Jp);
  r.displacement = r.twist * dI.mid() / 2.0;
  const ir::Setting* install = ir::findSetting(split.settings, "install");
  bool preloaded = install && install->symbol == "preloaded";
  Value installOverride = ev.quantity(split.name + ".install", a);
  if (installOverride.isNumber()) preloaded = installOverride.mid() > 0.5;
  if (preloaded) {
    auto M0 = setting("preload_torque");
    if (!M0) return fail("a preloaded installation needs `preload_torque`");
    double psi0 = *M0 * *L / (*G * Jp);
    r.preloadDisplacement = psi0 * dI.mid() / 2.0;
  }
  r.imbalance = std::max(*dl - r.preloadDisplacement, 0.0) / (2.0 * r.displacement);
  return r;
}

} // namespace gbx::rt
