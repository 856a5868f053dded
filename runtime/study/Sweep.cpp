#include "study/Sweep.h"

#include <cmath>

#include "model/Evaluator.h"

namespace gbx::rt {

namespace {
// Imbalances and other fractions read best in percent.
units::DisplayUnit unitFor(const ir::Expr& e) {
  if (e.op == ir::Op::Quantity && e.ref.key == Q::Imbalance) return {"%", 0.01};
  return units::displayUnitFor(e.type.dim);
}
} // namespace

SweepStudy sweep(const Model& m, const Assignment& a, const ir::Study& st) {
  SweepStudy r;
  r.name = st.name;
  r.target = st.target;
  r.plot = st.plot;
  r.unit = units::displayUnitFor(st.dim.value_or(units::Dim{}));
  for (size_t i = 0; i < st.outputs.size(); ++i) r.outputs.push_back({st.outputTexts[i], unitFor(*st.outputs[i])});
  double lo = st.lo->toDouble(), hi = st.hi->toDouble(), step = st.step->toDouble();
  long n = static_cast<long>(std::floor((hi - lo) / step * (1 + 1e-12))) + 1;
  for (long k = 0; k < n; ++k) {
    double x = lo + static_cast<double>(k) * step;
    Evaluator ev(m);
    ev.setOverride(st.swept, Value::number(x));
    SweepStudy::Point p{x, {}};
    for (size_t i = 0; i < st.outputs.size(); ++i) {
      Value v = ev.eval(*st.outputs[i], a);
      p.y.push_back(v.isNumber() ? v.mid() : NAN);
    }
    r.points.push_back(std::move(p));
  }
  return r;
}

} // namespace gbx::rt
