#include "search/Upstream.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "model/Deadline.h"
#include "parallel/Ranks.h"
#include "search/Narrow.h"

namespace gbx::rt {

namespace {

constexpr double kTolerance = 1e-7; // of the upstream ratio

bool passes(const Evaluator& ev, Assignment& a, const Conjunct& c, double u) {
  a.upstreamRatio = u;
  return truthOf(ev.eval(*c.expr, a)) != Truth::False;
}

// One rule over [ulo, uhi]: where its truth changes, by bisection.
Bracket bracket(const Evaluator& ev, Assignment& a, const Conjunct& c, double ulo, double uhi) {
  Bracket b;
  b.below = passes(ev, a, c, ulo);
  b.above = passes(ev, a, c, uhi);
  if (b.below == b.above) {
    b.lo = b.hi = uhi; // the same over the whole range
    b.above = b.below;
    return b;
  }
  double p = ulo, q = uhi;
  while (q - p > kTolerance * q) {
    double mid = 0.5 * (p + q);
    (passes(ev, a, c, mid) == b.below ? p : q) = mid;
  }
  b.lo = p;
  b.hi = q;
  return b;
}

// The candidate's freedoms narrowed where its rules fail for every upstream ratio of its
// range: each rule asked where it is easiest to meet, at the range's least ratio where it
// holds below a limit (a safety), at its greatest where it holds above one.
void narrowCandidate(const Evaluator& ev, Assignment& a, const std::vector<int>& freedoms,
                     const std::vector<const Conjunct*>& own, const std::vector<const Conjunct*>& rules, double ulo,
                     double uhi, Candidate& c) {
  std::vector<const Conjunct*> atLo, atHi;
  for (const auto* r : own)
    if (r->freedom) atLo.push_back(r);
  for (const auto* r : rules)
    (!passes(ev, a, *r, ulo) && passes(ev, a, *r, uhi) ? atHi : atLo).push_back(r);
  std::vector<std::pair<double, double>> box;
  for (int f : freedoms) {
    a.upstreamRatio = ulo;
    auto span = feasibleSpan(ev, a, atLo, f);
    if (!atHi.empty()) {
      a.upstreamRatio = uhi;
      auto other = feasibleSpan(ev, a, atHi, f);
      if (std::max(span.first, other.first) <= std::min(span.second, other.second))
        span = {std::max(span.first, other.first), std::min(span.second, other.second)};
    }
    box.push_back(span);
  }
  c.box = std::move(box);
}

} // namespace

UpstreamStage bracketStage(const Evaluator& ev, int s, std::vector<Candidate>& candidates,
                           const std::vector<const Conjunct*>& rules, const std::vector<const Conjunct*>& own,
                           const std::vector<std::pair<double, double>>& range,
                           const std::function<void(Assignment&, size_t)>& place, int jobs) {
  const Model& m = ev.model();
  const StageInfo& info = m.stages[static_cast<size_t>(s)];
  UpstreamStage out;
  out.stage = s;
  out.rules = rules;
  out.brackets.assign(candidates.size(), std::vector<Bracket>(rules.size()));
  const bool narrow = !info.freedoms.empty();
  std::atomic<size_t> next{0};
  auto work = [&] {
    Assignment a(m);
    a.upstreamStage = s;
    for (size_t i = next++; i < candidates.size(); i = next++) {
      if ((i & 15) == 0 && Deadline::expired()) break;
      const auto [ulo, uhi] = range[i];
      if (!(ulo <= uhi)) continue;
      place(a, i);
      if (narrow) narrowCandidate(ev, a, info.freedoms, own, rules, ulo, uhi, candidates[i]);
      place(a, i);
      for (size_t r = 0; r < rules.size(); ++r)
        out.brackets[i][r] = bracket(ev, a, *rules[r], ulo, uhi);
    }
  };
  par::onThreads(std::max(1, std::min<int>(jobs, static_cast<int>(candidates.size() / 64) + 1)), work);
  return out;
}

} // namespace gbx::rt
