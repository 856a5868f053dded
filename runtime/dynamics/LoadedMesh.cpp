#include "dynamics/LoadedMesh.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace gbx::rt::dyn {

double singlePairShape(double xi) { return 0.7 + 1.2 * xi * (1.0 - xi); }

LoadedMeshTable loadedMesh(const LoadedMeshInput& in) {
  LoadedMeshTable out;
  const FlankGeometry& g = in.g;
  const FlankSeparations& sep = in.sep;
  double roll1 = std::sqrt(g.ra1 * g.ra1 - g.rb1 * g.rb1), roll2 = std::sqrt(g.ra2 * g.ra2 - g.rb2 * g.rb2);
  double path = roll1 + roll2 - g.centerDistance * std::sin(g.workingPressureAngle);
  out.pathLength = path;
  if (!(path > 0) || !(g.basePitch > 0) || !(g.faceWidth > 0)) {
    out.failure = fmt::format("the flanks have no path of contact (length {:.4g} mm)", path * 1e3);
    return out;
  }
  double p = g.basePitch, b = g.faceWidth, shift = std::tan(g.baseHelix);
  out.epsAlpha = path / p;
  out.epsBeta = b * shift / p;
  int S = std::max(1, in.slices), P = std::max(2, in.positions);
  double db = b / S;
  // The separation of a contact point at s along the path and y across the face.
  auto separation = [&](double s, double y) {
    double gap = 0;
    if (sep.reliefLength[0] > 0 && s > path - sep.reliefLength[0]) gap += sep.tipRelief[0] * (s - (path - sep.reliefLength[0])) / sep.reliefLength[0];
    if (sep.reliefLength[1] > 0 && s < sep.reliefLength[1]) gap += sep.tipRelief[1] * (sep.reliefLength[1] - s) / sep.reliefLength[1];
    double u = 2.0 * y / b - 1.0;
    gap += sep.leadCrowning * u * u + sep.leadSlope * 0.5 * u;
    if (sep.endReliefWidth > 0) {
      double w = sep.endReliefWidth;
      gap += sep.endRelief * (std::max(0.0, w - y) + std::max(0.0, y - (b - w))) / w;
    }
    gap += sep.basePitch * (s - 0.5 * path) / p;
    double w = 2.0 * s / path - 1.0;
    gap -= sep.profileForm * w * w;
    return gap;
  };
  struct Point {
    double gap, c;
    int slice;
    bool operator<(const Point& o) const { return gap < o.gap || (gap == o.gap && c < o.c); }
  };
  std::vector<Point> pts;
  if (in.sliceLoads) out.sliceLineLoad.assign(static_cast<size_t>(S), 0.0);
  double rigidSum = 0;
  for (int i = 0; i < P; ++i) {
    double tau = static_cast<double>(i) / P;
    pts.clear();
    for (int j = 0; j < S; ++j) {
      double y = (j + 0.5) * db;
      double off = y * shift;
      long k0 = static_cast<long>(std::ceil(off / p - tau - 1e-12)), k1 = static_cast<long>(std::floor((path + off) / p - tau + 1e-12));
      for (long k = k0; k <= k1; ++k) {
        double s = (tau + static_cast<double>(k)) * p - off;
        if (s < 0 || s > path) continue;
        double c = in.singleStiffness * singlePairShape(s / path) * db;
        pts.push_back({separation(s, y), c, j});
        rigidSum += c;
      }
    }
    if (pts.empty()) {
      out.failure = fmt::format("no tooth pair touches at mesh position {}/{} (a contact ratio below 1)", i, P);
      return out;
    }
    // F = sum c max(0, delta - gap): piecewise linear and increasing in delta.
    std::sort(pts.begin(), pts.end());
    double K = 0, KG = 0, delta = 0;
    size_t n = pts.size();
    for (size_t m = 0; m < n; ++m) {
      K += pts[m].c;
      KG += pts[m].c * pts[m].gap;
      delta = (in.load + KG) / K;
      if (m + 1 == n || delta <= pts[m + 1].gap) break;
    }
    if (in.sliceLoads)
      for (const auto& q : pts)
        if (delta > q.gap) out.sliceLineLoad[static_cast<size_t>(q.slice)] += q.c * (delta - q.gap) / (db * P);
    out.te.push_back(delta);
    out.stiffness.push_back(K);
  }
  double sumK = 0, sumT = 0;
  for (int i = 0; i < P; ++i) {
    sumK += out.stiffness[static_cast<size_t>(i)];
    sumT += out.te[static_cast<size_t>(i)];
  }
  out.meanStiffness = sumK / P;
  out.meanTe = sumT / P;
  auto [lo, hi] = std::minmax_element(out.te.begin(), out.te.end());
  out.peakToPeakTe = *hi - *lo;
  out.lightLoadStiffness = rigidSum / P;
  return out;
}

PeriodicSeries periodicSeries(const std::vector<double>& table, int harmonics) {
  PeriodicSeries s;
  size_t P = table.size();
  if (P == 0) return s;
  for (double v : table) s.mean += v;
  s.mean /= static_cast<double>(P);
  int H = std::min<int>(harmonics, static_cast<int>((P - 1) / 2));
  for (int k = 1; k <= H; ++k) {
    double a = 0, b = 0;
    for (size_t i = 0; i < P; ++i) {
      double w = 2.0 * M_PI * k * static_cast<double>(i) / static_cast<double>(P);
      a += table[i] * std::cos(w);
      b += table[i] * std::sin(w);
    }
    s.f.a.push_back(2.0 * a / static_cast<double>(P));
    s.f.b.push_back(2.0 * b / static_cast<double>(P));
  }
  return s;
}

} // namespace gbx::rt::dyn
