#pragma once
// A faster meet-in-the-middle for the benchmark's spur cases, written for this one problem
// the way the search issue describes it: the upper half (one pair, or a non-decreasing pair
// of pairs) counting-sorted into log-ratio buckets exactly one window wide, so each lower
// half looks up one or two buckets; no data-dependent loop per row beyond them; a double
// check against the window first and 128-bit integers only for what falls inside it; the
// best `top` by |ratio - target| in a heap. Nothing here is shared with gbxc's search or
// with mitm_reference.h.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace bench {

struct FastDesign {
  double err = 0;
  std::uint32_t a = 0, b = 0, c = 0, d = 0;  // pair indices, non-decreasing (unused ones 0)
  bool operator<(const FastDesign& o) const { return err < o.err; }
};

struct FastPair {
  int p = 0, w = 0;
  double r = 0, lr = 0;
};

struct FastResult {
  unsigned long long count = 0;
  std::vector<FastDesign> best;  // ascending |ratio - target|
  std::vector<FastPair> pairs;
};

// Every design of the window, once per orbit: visit(num, den, a, b, c, d) with the exact
// ratio num/den (not reduced) and the pair indices into `pairs` (d unused with 3 stages).
// stages 3 or 4; the window is 13.36838 +- 1e-6 relative.
template <class Visit> void mitmEach(int stages, int maxTeeth, std::vector<FastPair>& pairs, Visit&& visit) {
  __extension__ using i128 = __int128;
  for (int p = 12; p <= maxTeeth; ++p)
    for (int w = p + 1; w <= maxTeeth; ++w)
      if (std::gcd(p, w) == 1) pairs.push_back({p, w, static_cast<double>(w) / p, std::log(static_cast<double>(w) / p)});
  std::sort(pairs.begin(), pairs.end(), [](const FastPair& x, const FastPair& y) { return x.r < y.r; });
  // Codes pack two pair indices in 16 bits each.
  if (pairs.empty() || pairs.size() > 65535) return;
  const std::uint32_t n = static_cast<std::uint32_t>(pairs.size());
  const double target = 13.36838, lo = target * (1 - 1e-6), hi = target * (1 + 1e-6);
  const double logLo = std::log(lo), logHi = std::log(hi), width = logHi - logLo;
  const i128 loNum = static_cast<i128>(1336838) * 999999, hiNum = static_cast<i128>(1336838) * 1000001;
  const i128 scale = static_cast<i128>(100000000000LL);
  const int upper = stages == 4 ? 2 : 1;
  // Upper entries: index c (one pair) or c << 16 | d (c <= d); log ratio from 0 up.
  const double span = upper * pairs.back().lr;
  const size_t buckets = static_cast<size_t>(span / width) + 2;
  std::vector<std::uint32_t> start(buckets + 1, 0);
  auto bucketOf = [&](double l) { return static_cast<size_t>(l / width); };
  std::vector<std::uint32_t> code;
  if (upper == 1) {
    // One pair: sorted by ratio already, so the table holds where each bucket starts.
    for (std::uint32_t c = 0; c < n; ++c) ++start[bucketOf(pairs[c].lr) + 1];
    for (size_t k = 0; k < buckets; ++k) start[k + 1] += start[k];
  } else {
    for (std::uint32_t c = 0; c < n; ++c)
      for (std::uint32_t d = c; d < n; ++d) ++start[bucketOf(pairs[c].lr + pairs[d].lr) + 1];
    for (size_t k = 0; k < buckets; ++k) start[k + 1] += start[k];
    code.resize(start[buckets]);
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t c = 0; c < n; ++c)
      for (std::uint32_t d = c; d < n; ++d) code[next[bucketOf(pairs[c].lr + pairs[d].lr)]++] = c << 16 | d;
  }
  // Lower half: pairs a <= b; the upper half's first pair is at least b.
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t b = a; b < n; ++b) {
      double lx = pairs[a].lr + pairs[b].lr;
      if (lx + upper * pairs[b].lr > logHi) break;  // the rest of the row is past the window
      double need = logLo - lx;
      size_t k = need < 0 ? 0 : bucketOf(need);
      if (k + 2 > buckets) continue;
      double rx = pairs[a].r * pairs[b].r;
      for (std::uint32_t e = start[k]; e < start[k + 2]; ++e) {
        std::uint32_t c = upper == 1 ? e : code[e] >> 16, d = upper == 1 ? 0 : code[e] & 0xFFFF;
        if (c < b) continue;
        double r = rx * pairs[c].r * (upper == 1 ? 1.0 : pairs[d].r);
        if (r < lo * (1 - 1e-12) || r > hi * (1 + 1e-12)) continue;
        i128 num = static_cast<i128>(pairs[a].w) * pairs[b].w * pairs[c].w, den = static_cast<i128>(pairs[a].p) * pairs[b].p * pairs[c].p;
        if (upper == 2) num *= pairs[d].w, den *= pairs[d].p;
        if (loNum * den > num * scale || num * scale > hiNum * den) continue;
        visit(num, den, a, b, c, d);
      }
    }
}

// The count and the best `top` by |ratio - target| in a heap.
inline FastResult mitmFast(int stages, int maxTeeth, size_t top) {
  FastResult res;
  std::vector<FastDesign> heap;
  auto keep = [&](const FastDesign& x) {
    if (heap.size() < top) {
      heap.push_back(x);
      std::push_heap(heap.begin(), heap.end());
    } else if (top > 0 && x.err < heap.front().err) {
      std::pop_heap(heap.begin(), heap.end());
      heap.back() = x;
      std::push_heap(heap.begin(), heap.end());
    }
  };
  mitmEach(stages, maxTeeth, res.pairs,
           [&](auto num, auto den, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
             ++res.count;
             keep({std::fabs(static_cast<double>(num) / static_cast<double>(den) - 13.36838), a, b, c, d});
           });
  std::sort_heap(heap.begin(), heap.end());
  res.best = std::move(heap);
  return res;
}

} // namespace bench
