#include "search/Narrow.h"

#include <algorithm>
#include <cmath>

#include "model/ToleranceEdges.h"

namespace gbx::rt {

namespace {

constexpr int kSamples = 5;
constexpr double kTolerance = 1e-4; // of the range
constexpr int kProbes = 5;
constexpr int kDepth = 3;

struct Span {
  const Evaluator& ev;
  Assignment& a;
  const std::vector<const Conjunct*>& rules;
  size_t f;
  double tol;

  // Whether no rule is false with the freedom at x.
  bool passes(double x) {
    a.box[f] = {x, x};
    for (const auto* c : rules)
      if (truthOf(ev.eval(*c->expr, a)) == Truth::False) return false;
    return true;
  }

  // The edge between a failing point and a passing one, as its failing end; then, between
  // it and `out`, a passing island's edge if a probe finds one.
  double edge(double out, double in, int depth = 0) {
    double o = out, i = in;
    while (std::fabs(i - o) > tol) {
      double mid = 0.5 * (o + i);
      (passes(mid) ? i : o) = mid;
    }
    if (depth < kDepth)
      for (int j = 1; j <= kProbes; ++j) {
        double p = o + (out - o) * std::ldexp(1.0, -j);
        if (p != o && passes(p)) return edge(out, p, depth + 1);
      }
    return o;
  }
};

} // namespace

std::pair<double, double> feasibleSpan(const Evaluator& ev, Assignment& a, const std::vector<const Conjunct*>& rules,
                                       int f) {
  const auto fi = static_cast<size_t>(f);
  const auto full = a.box[fi];
  const double lo = full.first, hi = full.second;
  if (!(hi > lo)) return full;
  Span s{ev, a, rules, fi, kTolerance * (hi - lo)};
  // Samples, and either side of each point where a tolerance table jumps.
  std::vector<double> x;
  for (int k = 0; k < kSamples; ++k)
    x.push_back(k == kSamples - 1 ? hi : lo + (hi - lo) * k / (kSamples - 1));
  const auto pieces = cutAt(lo, hi, toleranceEdges(ev, a, f));
  for (size_t k = 0; k + 1 < pieces.size(); ++k) {
    x.push_back(pieces[k].second);
    x.push_back(pieces[k + 1].first);
  }
  std::sort(x.begin(), x.end());
  const int n = static_cast<int>(x.size());
  int first = -1, last = -1;
  for (int k = 0; k < n; ++k)
    if (s.passes(x[static_cast<size_t>(k)])) {
      if (first < 0) first = k;
      last = k;
    }
  std::pair<double, double> out = full;
  auto at = [&](int k) { return x[static_cast<size_t>(k)]; };
  if (first > 0) out.first = s.edge(at(first - 1), at(first));
  if (last >= 0 && last < n - 1) out.second = s.edge(at(last + 1), at(last));
  a.box[fi] = full;
  return out;
}

} // namespace gbx::rt
