#include "model/StageKind.h"

#include <cmath>

#include "model/Evaluator.h"

namespace gbx::rt {

StageKindImpl::StageKindImpl(ir::StageKind k, SceneModel s, std::vector<DerivedRow> r, std::vector<ImplicitRule> ru)
    : kind(k), scene(s), rows(std::move(r)), rules(std::move(ru)) {
  for (const auto& row : rows) (row.perGear ? gear_ : stage_)[static_cast<size_t>(row.key)] = row.fn;
}

std::vector<DerivedRow> trainRows() {
  // Speeds run down the train from the input; torques grow by each ratio (no losses).
  return {
      {Q::InputSpeed, false, [](const KindContext& c, int) { return arith::div(c.gearbox(Q::InputSpeed), c.upstreamRatio()); }},
      {Q::OutputSpeed, false, [](const KindContext& c, int) { return arith::div(c.derived(Q::InputSpeed), c.derived(Q::Ratio)); }},
      {Q::InputTorque, false, [](const KindContext& c, int) { return arith::mul(c.gearbox(Q::InputTorque), c.upstreamRatio()); }},
      {Q::OutputTorque, false, [](const KindContext& c, int) { return arith::mul(c.derived(Q::InputTorque), c.derived(Q::Ratio)); }},
  };
}

Value meshFrequency(const KindContext& c, Q speed, int gear) {
  return arith::mul(arith::mul(c.derived(speed), Value::number(1.0 / (2.0 * M_PI))), c.at(gear, Q::Z));
}

std::vector<DerivedRow> pinionWheelRows() {
  constexpr int pinion = 0, wheel = 1;
  auto r = trainRows();
  std::vector<DerivedRow> own = {
      {Q::Ratio, false, [](const KindContext& c, int) { return arith::div(c.at(wheel, Q::Z), c.at(pinion, Q::Z)); }},
      {Q::MeshFrequency, false, [](const KindContext& c, int) { return meshFrequency(c, Q::InputSpeed, pinion); }},
      {Q::Speed, true, [](const KindContext& c, int g) { return c.derived(g == pinion ? Q::InputSpeed : Q::OutputSpeed); }},
      {Q::Torque, true, [](const KindContext& c, int g) { return c.derived(g == pinion ? Q::InputTorque : Q::OutputTorque); }},
  };
  r.insert(r.end(), own.begin(), own.end());
  return r;
}

std::vector<DerivedRow> moduleGearRows() {
  auto r = trainRows();
  r.push_back({Q::D, true, [](const KindContext& c, int g) { return arith::mul(c.at(g, Q::Z), c.at(Q::Module)); }});
  r.push_back({Q::BaseRadius, true, [](const KindContext& c, int g) {
                 return arith::corners({c.derived(g, Q::D), c.at(Q::PressureAngle)},
                                       [](const std::vector<double>& x) { return 0.5 * x[0] * std::cos(x[1]); });
               }});
  return r;
}

const std::vector<const StageKindImpl*>& stageKindImpls() {
  static const std::vector<const StageKindImpl*> all = {&kinds::spur(), &kinds::helical(), &kinds::bevel(), &kinds::planetary(),
                                                        &kinds::idler()};
  return all;
}

const StageKindImpl& stageKindImpl(ir::StageKind kind) {
  static const auto table = [] {
    std::vector<const StageKindImpl*> t(stageKindImpls().size());
    for (const auto* k : stageKindImpls()) t[static_cast<size_t>(k->kind)] = k;
    return t;
  }();
  return *table[static_cast<size_t>(kind)];
}

} // namespace gbx::rt
