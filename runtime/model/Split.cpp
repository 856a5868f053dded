#include "model/Split.h"

#include <cmath>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"

namespace gbx::rt {

std::optional<SplitResult> computeSplit(const Evaluator& ev, int index, const Assignment& a, std::string* error) {
  const ir::Split& split = ev.model().gearbox.splits[static_cast<size_t>(index)];
  auto fail = [&](const std::string& what) -> std::optional<SplitResult> {
    if (error) *error = fmt::format("split `{}`: {}", split.name, what);
    return std::nullopt;
  };
  auto setting = [&](Q key) -> std::optional<double> {
    ir::QuantityRef r;
    r.owner = ir::QuantityRef::Split;
    r.index = static_cast<std::int16_t>(index);
    r.key = key;
    Value v = ev.quantity(r, a);
    if (v.isNumber()) return v.mid();
    return std::nullopt;
  };
  const ir::Setting* between = ir::findSetting(split.settings, Q::Between);
  int st = between ? between->stage : -1;
  if (st < 0) return fail("`between` names no stage");
  // The branches start at the stage's wheel: a pinion-wheel pair.
  ir::StageKind kind = ev.model().info(st).ir->kind;
  if (kind == ir::StageKind::Planetary || kind == ir::StageKind::Idler)
    return fail(fmt::format("`between` must name a pinion-wheel stage, not a {} stage", ir::stageKindName(kind)));
  auto branches = setting(Q::Branches), L = setting(Q::TorsionShaftLength), d = setting(Q::TorsionShaftDiameter),
       G = setting(Q::TorsionShaftShearModulus), dl = setting(Q::BacklashDifference);
  if (!branches || !L || !d || !G || !dl) return fail("the torsion shaft and backlash difference must be given");
  Value wheelTorque = ev.derived(st, Q::OutputTorque, a), dI = ev.derived(st, cat::gear::Wheel, Q::D, a);
  if (!wheelTorque.isNumber()) return fail("branch torques need the operating point");
  if (!dI.isNumber()) return fail("the stage-I wheel diameter needs its module");
  SplitResult r;
  double Jp = M_PI * std::pow(*d, 4) / 32.0;
  r.branchTorque = wheelTorque.mid() / *branches;
  r.twist = r.branchTorque * *L / (*G * Jp);
  r.displacement = r.twist * dI.mid() / 2.0;
  const ir::Setting* install = ir::findSetting(split.settings, Q::Install);
  bool preloaded = install && install->choice == cat::install::Preloaded;
  ir::QuantityRef installRef;
  installRef.owner = ir::QuantityRef::Split;
  installRef.index = static_cast<std::int16_t>(index);
  installRef.key = Q::Install;
  Value installOverride = ev.quantity(installRef, a);
  if (installOverride.isNumber()) preloaded = installOverride.mid() > 0.5;
  if (preloaded) {
    auto M0 = setting(Q::PreloadTorque);
    if (!M0) return fail("a preloaded installation needs `preload_torque`");
    double psi0 = *M0 * *L / (*G * Jp);
    r.preloadDisplacement = psi0 * dI.mid() / 2.0;
  }
  r.imbalance = std::max(*dl - r.preloadDisplacement, 0.0) / (2.0 * r.displacement);
  return r;
}

} // namespace gbx::rt
