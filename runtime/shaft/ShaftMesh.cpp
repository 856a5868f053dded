#include "shaft/ShaftMesh.h"

#include <algorithm>
#include <cmath>

#include "catalogue/StageKinds.h"
#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"

namespace gbx::rt {

std::optional<MeshShafts> meshShafts(const ir::Gearbox& g, int stage) {
  MeshShafts ms;
  for (size_t i = 0; i < g.shafts.size(); ++i)
    for (const auto& p : g.shafts[i].placed)
      if (p.kind == ir::Shaft::Place::Gear && p.stage == stage)
        (p.gear == cat::gear::Pinion ? ms.pinion : ms.wheel) = static_cast<int>(i);
  if (ms.pinion < 0 || ms.wheel < 0) return std::nullopt;
  return ms;
}

namespace {

double stageValue(const Evaluator& ev, const Assignment& a, int st, int gear, Q key) {
  return stageNumber(ev, a, st, gear, key).value_or(std::nan(""));
}

double gearAt(const ir::Shaft& sh, int stage, int gear) {
  for (const auto& p : sh.placed)
    if (p.kind == ir::Shaft::Place::Gear && p.stage == stage && p.gear == gear) return p.at.toDouble();
  return 0;
}

} // namespace

std::vector<double> shaftSeparation(const Evaluator& ev, const Assignment& a, int stage, const MeshShafts& ms,
                                    const std::vector<double>& share, int points, std::string* error) {
  // The face's load in 20 bundles on the shafts (each at its slices' centre): the beam is
  // exact between them, and 100 stations more per shaft would cost five times the solve.
  constexpr size_t kBundles = 20;
  std::vector<double> bundled = share;
  if (share.size() > kBundles && share.size() % kBundles == 0) {
    size_t per = share.size() / kBundles;
    bundled.assign(kBundles, 0.0);
    for (size_t j = 0; j < share.size(); ++j)
      bundled[j / per] += share[j];
  }
  LoadSpread spread{stage, bundled, 1.0};
  auto p = computeShaft(ev, ms.pinion, a, error, false, &spread);
  if (!p) return {};
  auto w = ms.wheel == ms.pinion ? p : computeShaft(ev, ms.wheel, a, error, false, &spread);
  if (!w) return {};
  const auto& shafts = ev.model().gearbox.shafts;
  double xp = gearAt(shafts[static_cast<size_t>(ms.pinion)], stage, cat::gear::Pinion);
  double xw = gearAt(shafts[static_cast<size_t>(ms.wheel)], stage, cat::gear::Wheel);
  double b = stageValue(ev, a, stage, -1, Q::FaceWidth), alpha = stageValue(ev, a, stage, -1, Q::WorkingPressureAngle);
  double rb1 = stageValue(ev, a, stage, cat::gear::Pinion, Q::BaseRadius);
  double rb2 = stageValue(ev, a, stage, cat::gear::Wheel, Q::BaseRadius);
  // The force on the pinion, whose mate lies at +y, pushes it to -y and against its turning
  // (+x on the input, each stage reversing): n is its direction, along which the pinion
  // moving away from the wheel opens the flanks. A twist phi moves the pinion's flank by
  // phi r_w along z, the wheel's (at -y from its centre) by -phi r_w.
  double sigma = senseOf(ev.model(), stage, true);
  double ny = -std::sin(alpha), nz = -sigma * std::cos(alpha);
  using Plane = shaft::Solution::Plane;
  std::vector<double> gap(static_cast<size_t>(points));
  for (int i = 0; i < points; ++i) {
    double y = b * i / std::max(1, points - 1) - b / 2;
    const auto& sp = p->solution;
    const auto& sw = w->solution;
    double dy = sp.deflection(Plane::Y, xp + y) - sw.deflection(Plane::Y, xw + y);
    double dz = sp.deflection(Plane::Z, xp + y) - sw.deflection(Plane::Z, xw + y);
    double twist = sp.twistAt(xp + y) * rb1 + sw.twistAt(xw + y) * rb2;
    gap[static_cast<size_t>(i)] = dy * ny + dz * nz - sigma * twist;
  }
  double least = *std::min_element(gap.begin(), gap.end());
  for (double& g : gap)
    g -= least;
  return gap;
}

} // namespace gbx::rt
