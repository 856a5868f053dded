#include "shaft/ShaftStrength.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "catalogue/Keys.h"

namespace gbx::rt::shaft {

using cat::Q;

namespace {

// The axial force a section carries, tension positive: what the loads and the thrust bearing
// put on the shaft to its left, reversed.
double axialForce(const Model& m, const Solution& s, double x) {
  double left = 0;
  for (const auto& l : m.loads)
    if (l.x < x) left += l.Fx;
  for (size_t k = 0; k < m.bearings.size(); ++k)
    if (m.bearings[k].x < x) left += s.reactions[k].Fx;
  return -left;
}

const Section* sectionAt(const Model& m, double x, bool left) {
  for (const auto& sec : m.sections)
    if (left ? x > sec.x0 && x <= sec.x1 : x >= sec.x0 && x < sec.x1) return &sec;
  return nullptr;
}

} // namespace

std::array<din743::Load, 3> sectionLoads(const Model& m, const Solution& s, double x, double peak) {
  constexpr double eps = 1e-9;
  double x0 = s.x.front(), x1 = s.x.back();
  double M = 0, T = 0, N = 0;
  for (double at : {std::max(x0, x - eps), std::min(x1, x + eps)}) {
    M = std::max(M, std::hypot(s.moment(Solution::Plane::Y, at), s.moment(Solution::Plane::Z, at)));
    if (std::fabs(s.torqueAt(at)) > std::fabs(T)) T = s.torqueAt(at);
    double n = axialForce(m, s, at);
    if (std::fabs(n) > std::fabs(N)) N = n;
  }
  // What round-off leaves where nothing loads the section (outboard of a bearing) is nothing.
  double Mscale = 0, Tscale = 0, Nscale = 0;
  for (size_t i = 0; i < s.x.size(); ++i) {
    Mscale = std::max(Mscale, std::hypot(s.momentY[i], s.momentZ[i]));
    Nscale = std::max(Nscale, std::fabs(axialForce(m, s, s.x[i])));
  }
  for (double t : s.torque)
    Tscale = std::max(Tscale, std::fabs(t));
  if (M <= 1e-9 * Mscale) M = 0;
  if (std::fabs(T) <= 1e-9 * Tscale) T = 0;
  if (std::fabs(N) <= 1e-9 * Nscale) N = 0;
  return {din743::Load{N, 0, peak * std::fabs(N)}, din743::Load{0, M, peak * M},
          din743::Load{std::fabs(T), 0, peak * std::fabs(T)}};
}

std::vector<NotchRating> rateNotches(const ir::Shaft& sh, const Model& m, const Solution& s,
                                     const StrengthSettings& st) {
  std::vector<NotchRating> out;
  for (const auto& p : sh.placed) {
    if (p.kind != ir::Shaft::Place::Notch) continue;
    NotchRating r;
    r.kind = p.name;
    r.x = p.at.toDouble();
    auto& n = r.notch;
    n.kind = static_cast<din743::NotchKind>(p.notch);
    const Section* left = sectionAt(m, r.x, true);
    const Section* right = sectionAt(m, r.x, false);
    // A shoulder's section is its smaller side; the others lie within one segment (the right
    // one at a segment's end, as the stations are read).
    const Section* at = right ? right : left;
    if (n.kind == din743::NotchKind::Shoulder && left && right && left->diameter < right->diameter) at = left;
    if (!at) throw std::invalid_argument(fmt::format("the {} at {:g} mm lies off the shaft", r.kind, r.x * 1e3));
    double D = at->diameter;
    if (n.kind == din743::NotchKind::Shoulder && left && right) D = std::max(left->diameter, right->diameter);
    auto given = [&](Q key) {
      const ir::Setting* x = ir::findSetting(p.settings, key);
      return x && x->value ? x->value->toDouble() : 0.0;
    };
    n.radius = given(Q::NotchRadius);
    n.depth = given(Q::NotchDepth);
    n.holeDiameter = given(Q::Diameter);
    n.keys = given(Q::Keys) > 0 ? static_cast<int>(given(Q::Keys)) : 1;
    n.bore = at->bore;
    n.roughness = at->roughness > 0 ? at->roughness : 8e-6;
    n.D = D;
    bool cut = n.kind == din743::NotchKind::Groove || n.kind == din743::NotchKind::VNotch;
    n.d = cut ? D - 2 * n.depth : at->diameter;
    r.loads = sectionLoads(m, s, r.x, st.peak);
    try {
      r.result = din743::rate(n, st.material, r.loads, st.din);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("the {} at {:g} mm: {}", r.kind, r.x * 1e3, e.what()));
    }
    out.push_back(std::move(r));
  }
  return out;
}

} // namespace gbx::rt::shaft
