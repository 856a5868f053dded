#pragma once
// A straightforward meet-in-the-middle for the benchmark's spur cases, written the way a
// careful engineer would for this one problem: coprime reduction pairs sorted by ratio,
// the right half (one pair, or a non-decreasing pair of pairs) bucketed by log ratio, each
// left entry scanning the buckets its window covers, every match confirmed in exact
// 128-bit integers, the best `top` by |ratio - target| kept in a heap. Interchangeable
// stages: designs are non-decreasing sequences of pair indices. Nothing here is shared
// with gbxc's search.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace bench {

__extension__ using i128 = __int128;

struct MitmResult {
  unsigned long long count = 0;
  std::vector<double> best; // |ratio - target| of the kept designs, ascending
  size_t written = 0;  // bytes of the CSV lines written
};

// stages: 2..4; the window is 13.36838 +- 1e-6 relative, as in the benchmark's specs. With
// `out`, every design is also written as one CSV line (teeth and ratio) to it.
inline MitmResult mitmReference(int stages, int maxTeeth, size_t top, std::FILE* out = nullptr) {
  struct Pair {
    int p, w;
    double r, lr;
  };
  std::vector<Pair> pairs;
  for (int p = 12; p <= maxTeeth; ++p)
    for (int w = p + 1; w <= maxTeeth; ++w)
      if (std::gcd(p, w) == 1)
        pairs.push_back({p, w, static_cast<double>(w) / p, std::log(static_cast<double>(w) / p)});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.r < b.r; });
  const i128 loNum = static_cast<i128>(1336838) * 999999, hiNum = static_cast<i128>(1336838) * 1000001;
  const i128 scale = static_cast<i128>(100000000000LL);
  const double target = 13.36838, logLo = std::log(13.36838 * (1 - 1e-6)), logHi = std::log(13.36838 * (1 + 1e-6));
  // Left: the first `stages - right` pairs; right: one pair (2 or 3 stages) or two (4).
  const int rightWidth = stages == 4 ? 2 : 1;
  const int leftStages = stages - rightWidth;
  const size_t n = pairs.size();
  // Right entries: codes (c << 16 | d), or c; bucketed by log ratio in two passes.
  auto forRight = [&](auto&& f) {
    if (rightWidth == 1)
      for (std::uint32_t c = 0; c < n; ++c)
        f(c, pairs[c].lr);
    else
      for (std::uint32_t c = 0; c < n; ++c)
        for (std::uint32_t d = c; d < n; ++d)
          f(c << 16 | d, pairs[c].lr + pairs[d].lr);
  };
  const double lmin = rightWidth * pairs.front().lr, lmax = rightWidth * pairs.back().lr;
  size_t entries = rightWidth == 1 ? n : n * (n + 1) / 2;
  size_t buckets = rightWidth == 1 ? 4 * n : entries / 4;
  const double perLog = static_cast<double>(buckets) / ((lmax - lmin) * (1 + 1e-12));
  auto bucketOf = [&](double l) {
    double b = (l - lmin) * perLog;
    return b < 0 ? size_t{0} : std::min(buckets - 1, static_cast<size_t>(b));
  };
  std::vector<std::uint32_t> start(buckets + 1, 0), sorted(entries);
  forRight([&](std::uint32_t, double l) { ++start[bucketOf(l) + 1]; });
  for (size_t b = 0; b < buckets; ++b)
    start[b + 1] += start[b];
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    forRight([&](std::uint32_t code, double l) { sorted[next[bucketOf(l)]++] = code; });
  }
  MitmResult res;
  std::vector<double> heap; // max-heap of the kept |ratio - target|
  std::string line;
  const double lo = 13.36838 * (1 - 1e-6), hi = 13.36838 * (1 + 1e-6);
  // One left sequence (pair indices a <= b, or a alone) against its buckets.
  auto join = [&](size_t a, size_t b, double lx, double rx) {
    size_t floor = leftStages == 1 ? a : b;
    size_t b0 = bucketOf(logLo - lx - 1e-12), b1 = bucketOf(logHi - lx + 1e-12);
    for (size_t e = start[b0]; e < start[b1 + 1]; ++e) {
      std::uint32_t code = sorted[e];
      size_t c = rightWidth == 1 ? code : code >> 16, d = code & 0xFFFF;
      if (c < floor) continue;
      double r = rx * pairs[c].r * (rightWidth == 1 ? 1.0 : pairs[d].r);
      if (r < lo * (1 - 1e-12) || r > hi * (1 + 1e-12)) continue;
      // Exact: lo <= num/den <= hi in 128-bit integers.
      i128 rn = pairs[a].w, rd = pairs[a].p;
      if (leftStages == 2) rn *= pairs[b].w, rd *= pairs[b].p;
      rn *= pairs[c].w, rd *= pairs[c].p;
      if (rightWidth == 2) rn *= pairs[d].w, rd *= pairs[d].p;
      if (loNum * rd > rn * scale || rn * scale > hiNum * rd) continue;
      ++res.count;
      double err = std::fabs(static_cast<double>(rn) / static_cast<double>(rd) - target);
      if (heap.size() < top) {
        heap.push_back(err);
        std::push_heap(heap.begin(), heap.end());
      } else if (top > 0 && err < heap.front()) {
        std::pop_heap(heap.begin(), heap.end());
        heap.back() = err;
        std::push_heap(heap.begin(), heap.end());
      }
      if (out) {
        line.clear();
        fmt::format_to(std::back_inserter(line), "{},{},", pairs[a].p, pairs[a].w);
        if (leftStages == 2) fmt::format_to(std::back_inserter(line), "{},{},", pairs[b].p, pairs[b].w);
        fmt::format_to(std::back_inserter(line), "{},{},", pairs[c].p, pairs[c].w);
        if (rightWidth == 2) fmt::format_to(std::back_inserter(line), "{},{},", pairs[d].p, pairs[d].w);
        fmt::format_to(std::back_inserter(line), "{}\n", static_cast<double>(rn) / static_cast<double>(rd));
        std::fwrite(line.data(), 1, line.size(), out);
        res.written += line.size();
      }
    }
  };
  for (size_t a = 0; a < n; ++a) {
    if (leftStages == 1) {
      // The right pair is at least this one.
      if (pairs[a].lr * (1 + rightWidth) > logHi + 1e-12) break;
      join(a, a, pairs[a].lr, pairs[a].r);
      continue;
    }
    for (size_t b = a; b < n; ++b) {
      double lx = pairs[a].lr + pairs[b].lr;
      // The right pairs are at least pair b: past the window, so is the rest of the row.
      if (lx + rightWidth * pairs[b].lr > logHi + 1e-12) break;
      join(a, b, lx, pairs[a].r * pairs[b].r);
    }
  }
  std::sort_heap(heap.begin(), heap.end());
  res.best = heap;
  return res;
}

} // namespace bench
