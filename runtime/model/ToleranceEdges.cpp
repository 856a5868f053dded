#include "model/ToleranceEdges.h"

#include <algorithm>
#include <cmath>

#include "model/StageKind.h"
#include "model/Standards.h"

namespace gbx::rt {

std::vector<std::pair<double, double>> cutAt(double lo, double hi, const std::vector<double>& edges) {
  std::vector<std::pair<double, double>> out;
  double from = lo;
  for (double e : edges) {
    if (!(e > lo && e < hi)) continue;
    out.emplace_back(from, e * (1 - 1e-12));
    from = e * (1 + 1e-12);
  }
  out.emplace_back(from, hi);
  return out;
}

std::vector<double> toleranceEdges(const Evaluator& ev, const Assignment& a, int f) {
  const Model& m = ev.model();
  const Freedom& fr = m.freedoms[static_cast<size_t>(f)];
  if (fr.shaft.setting) return {}; // a shaft's setting: no table of the standards steps with it
  const double lo = a.box[static_cast<size_t>(f)].first, hi = a.box[static_cast<size_t>(f)].second;
  std::vector<double> out;
  auto add = [&](double x) {
    if (x > lo && x < hi) out.push_back(x);
  };
  KindContext c{ev, fr.stage, a};
  auto mid = [](const Value& v) { return v.isNumber() ? v.mid() : NAN; };
  const double mn = mid(c.at(Q::NormalModule)), beta = mid(c.at(Q::HelixAngle));
  const double z[2] = {mid(c.at(0, Q::Z)), mid(c.at(1, Q::Z))};
  switch (fr.key) {
  case Q::FaceWidth:
    for (double b : iso::faceWidthRanges()) add(b * 1e-3);
    break;
  case Q::NormalModule:
    for (double x : iso::moduleRanges()) add(x * 1e-3);
    // d = z mn / cos(beta) crosses a diameter bound.
    for (double zg : z)
      for (double d : iso::diameterRanges()) add(d * 1e-3 * std::cos(std::isnan(beta) ? 0 : beta) / zg);
    break;
  case Q::HelixAngle:
    for (double zg : z)
      for (double d : iso::diameterRanges())
        if (zg * mn <= d * 1e-3) add(std::acos(zg * mn / (d * 1e-3)));
    break;
  default: break;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace gbx::rt
