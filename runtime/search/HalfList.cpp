#include "search/HalfList.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

namespace gbx::rt {

namespace {

// The bucket of r: its order key above k0, shifted, clamped to [0, last] (monotone in r).
size_t bucketIn(double r, std::uint64_t k0, int shift, size_t last) {
  std::uint64_t k = orderKey(r);
  if (k <= k0) return 0;
  std::uint64_t b = shift >= 64 ? 0 : (k - k0) >> shift;
  return static_cast<size_t>(std::min<std::uint64_t>(b, last));
}

// One run of a list's entries put in order by ratio, equal ratios in the order they were
// made: counted into fine buckets of its order-key range (about two an entry), then one
// insertion pass (a bucket holds one entry or none, mostly).
template <class Code> struct RunOrder {
  std::vector<std::pair<double, Code>> entries, placed;
  std::vector<std::uint32_t> count;

  template <class Out, class RatioAt> void load(const Out& out, size_t first, size_t last, RatioAt ratioAt) {
    entries.clear();
    for (size_t e = first; e < last; ++e)
      entries.emplace_back(ratioAt(e), out[e]);
  }

  // The run's keys lie in [base, base + 2^shift) (clamped ones at its ends).
  void byKey(std::uint64_t base, int shift) {
    const size_t m = entries.size();
    if (m < 2) return;
    int bits = 0; // fine buckets 2^bits, no finer than the keys themselves (shift >= bits)
    while (bits < shift && (size_t{1} << bits) < 2 * m)
      ++bits;
    const int fine = shift - bits;
    const size_t buckets = size_t{1} << bits;
    auto bucket = [&](double r) {
      std::uint64_t k = orderKey(r);
      if (k <= base || fine >= 64) return size_t{0};
      return static_cast<size_t>(std::min<std::uint64_t>((k - base) >> fine, buckets - 1));
    };
    count.assign(buckets + 1, 0);
    for (const auto& x : entries)
      ++count[bucket(x.first) + 1];
    for (size_t b = 0; b < buckets; ++b)
      count[b + 1] += count[b];
    placed.resize(m);
    for (const auto& x : entries)
      placed[count[bucket(x.first)]++] = x;
    // Entries of different buckets are in order now, and each bucket's in the order they
    // were made (the counting is stable). One stable insertion pass by ratio puts each
    // bucket in order, a comparison an entry; equal ratios keep the order they were made in
    // (a fixed order). A crowded bucket (clamped keys) is sorted stably first.
    auto byRatio = [](const std::pair<double, Code>& x, const std::pair<double, Code>& y) { return x.first < y.first; };
    for (size_t b = 0, begin = 0; b < buckets; begin = count[b++])
      if (count[b] - begin > 32)
        std::stable_sort(placed.begin() + static_cast<std::ptrdiff_t>(begin),
                         placed.begin() + static_cast<std::ptrdiff_t>(count[b]), byRatio);
    for (size_t e = 1; e < m; ++e) {
      if (!byRatio(placed[e], placed[e - 1])) continue;
      auto x = placed[e];
      size_t at = e;
      for (; at > 0 && byRatio(x, placed[at - 1]); --at)
        placed[at] = placed[at - 1];
      placed[at] = x;
    }
    entries.swap(placed);
  }
};

int bitsFor(size_t n) {
  int b = 1;
  while (b < 63 && (std::uint64_t{1} << b) < n)
    ++b;
  return b;
}

} // namespace

// A two-stage half's entries with first index i: the second's indices [j0, j1).
std::pair<std::uint64_t, std::uint64_t> HalfList::pairRun(std::uint64_t i, bool canon) const {
  const auto& R = *ratios_;
  const auto &r0 = R[static_cast<size_t>(from_)], &r1 = R[static_cast<size_t>(from_ + 1)];
  std::uint64_t j0 = canon ? i : 0, j1 = r1.size();
  if (reach_ && i < reach_->size()) {
    // The second stage's ratios ascend: the reachable ones are one run of them.
    auto [lo, hi] = (*reach_)[i];
    j0 = std::max<std::uint64_t>(
        j0, static_cast<std::uint64_t>(std::lower_bound(r1.begin(), r1.end(), lo / r0[i]) - r1.begin()));
    j1 = static_cast<std::uint64_t>(std::upper_bound(r1.begin(), r1.end(), hi / r0[i]) - r1.begin());
  }
  return {j0, std::max(j0, j1)};
}

bool HalfList::pairCanonical(const std::vector<std::pair<int, int>>& ordered) const {
  return std::find(ordered.begin(), ordered.end(), std::make_pair(from_, from_ + 1)) != ordered.end();
}

template <class F> void HalfList::forEach(const std::vector<std::pair<int, int>>& ordered, F&& f) const {
  const auto& R = *ratios_;
  const int from = from_, to = from_ + width_;
  if (width_ == 2) {
    const auto &r0 = R[static_cast<size_t>(from)], &r1 = R[static_cast<size_t>(from + 1)];
    const bool canon = pairCanonical(ordered);
    const int s1 = shift_[1];
    for (std::uint64_t i = 0; i < r0.size(); ++i) {
      auto [j0, j1] = pairRun(i, canon);
      for (std::uint64_t j = j0; j < j1; ++j)
        f(i | (j << s1), r0[i] * r1[j]);
    }
    return;
  }
  const size_t w = static_cast<size_t>(width_);
  std::vector<std::uint64_t> cur(w, 0);
  auto start = [&](int s) {
    std::uint64_t lo = 0;
    for (const auto& [a, b] : ordered)
      if (b == s && a >= from && a < s) lo = std::max(lo, cur[static_cast<size_t>(a - from)]);
    return lo;
  };
  for (int s = from; s < to; ++s)
    cur[static_cast<size_t>(s - from)] = start(s);
  for (;;) {
    bool valid = true;
    double prod = 1;
    std::uint64_t code = 0;
    for (size_t s = 0; s < w && valid; ++s) {
      const auto& list = R[static_cast<size_t>(from) + s];
      if (cur[s] >= list.size())
        valid = false;
      else {
        prod *= list[cur[s]];
        code |= cur[s] << shift_[s];
      }
    }
    if (valid && reach_ && cur[0] < reach_->size())
      valid = prod >= (*reach_)[cur[0]].first && prod <= (*reach_)[cur[0]].second;
    if (valid) f(code, prod);
    // Odometer, last stage fastest; a stage restarts at its canonical lower bound.
    int s = to - 1;
    for (; s >= from; --s) {
      auto& c = cur[static_cast<size_t>(s - from)];
      ++c;
      if (c < R[static_cast<size_t>(s)].size()) break;
    }
    if (s < from) break;
    for (int t = s + 1; t < to; ++t)
      cur[static_cast<size_t>(t - from)] = start(t);
  }
}

template <class Code> void HalfList::fill(const std::vector<std::pair<int, int>>& ordered, LargeVector<Code>& out) {
  const auto& R = *ratios_;
  // Key bounds from the stages' extreme ratios (positive ratios: the product of the least
  // is the least product); entries outside are clamped, which keeps the order.
  double lo = 1, hi = 1;
  bool positive = true;
  double upper = 1; // tuples before the canonical order removes any
  for (int s = 0; s < width_; ++s) {
    const auto& r = R[static_cast<size_t>(from_ + s)];
    positive = positive && r.front() > 0 && std::isfinite(r.back());
    lo *= r.front();
    hi *= r.back();
    upper *= static_cast<double>(r.size());
  }
  if (reach_ && positive) {
    // Only the reachable entries: their count and the span of their ratios.
    double least = INFINITY, most = 0, kept = 0;
    for (const auto& [a, b] : *reach_) {
      least = std::min(least, a);
      most = std::max(most, b);
    }
    lo = std::max(lo, least);
    hi = std::max(lo, std::min(hi, most));
    if (width_ == 2) {
      // Counted by runs of the second stage, without visiting each entry.
      const bool canon = pairCanonical(ordered);
      for (std::uint64_t i = 0; i < R[static_cast<size_t>(from_)].size(); ++i) {
        auto [j0, j1] = pairRun(i, canon);
        kept += static_cast<double>(j1 - j0);
      }
    } else {
      forEach(ordered, [&](std::uint64_t, double) { kept += 1; });
    }
    upper = std::max(1.0, kept);
  }
  const std::uint64_t k0 = orderKey(lo), span = positive ? orderKey(hi) - k0 : 0;
  // Runs: ranges of the order key holding about kRunEntries entries each, placed in turn.
  const double runsWanted = std::clamp(upper / static_cast<double>(kRunEntries), 1.0, static_cast<double>(1 << 20));
  int runShift = 0;
  while (runShift < 64 && static_cast<double>(span >> runShift) >= runsWanted)
    ++runShift;
  const size_t runs = positive && runShift < 64 ? static_cast<size_t>(span >> runShift) + 1 : 1;
  auto runOf = [&](double r) { return bucketIn(r, k0, runShift, runs - 1); };
  std::vector<std::uint32_t> at(runs + 1, 0);
  size_t n = 0;
  forEach(ordered, [&](std::uint64_t, double r) {
    ++at[runOf(r) + 1];
    ++n;
  });
  for (size_t c = 0; c < runs; ++c)
    at[c + 1] += at[c];
  out.resize(n);
  n_ = n;
  {
    // Each run is a sequential write stream: a few hundred of them (the benchmark's lists)
    // stay in the caches, where a scatter straight to each entry's place would miss on
    // nearly every entry.
    std::vector<std::uint32_t> next(at.begin(), at.end() - 1);
    forEach(ordered, [&](std::uint64_t code, double r) {
      std::uint32_t e = next[runOf(r)]++;
      out[e] = static_cast<Code>(code);
    });
  }
  // The coarse index over the order key, about four entries a bucket, filled as the runs
  // are put in order.
  keyShift_ = 0;
  while (keyShift_ < 64 && (span >> keyShift_) + 1 > std::max<size_t>(1, n / 4))
    ++keyShift_;
  key0_ = k0;
  const size_t coarse = positive && keyShift_ < 64 ? static_cast<size_t>(span >> keyShift_) + 1 : 1;
  index_.assign(coarse + 1, 0);
  size_t indexed = 0; // index_[0, indexed) are set
  RunOrder<Code> order;
  for (size_t c = 0; c < runs; ++c) {
    order.load(out, at[c], at[c + 1], [&](size_t e) { return codeRatio(out[e]); });
    if (positive && runShift < 64)
      order.byKey(k0 + (static_cast<std::uint64_t>(c) << runShift), runShift);
    else
      std::stable_sort(order.entries.begin(), order.entries.end(),
                       [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t i = 0; i < order.entries.size(); ++i) {
      const size_t e = at[c] + i;
      const auto& [r, code] = order.entries[i];
      out[e] = code;
      for (size_t b = bucketIn(r, k0, keyShift_, coarse - 1); indexed <= b;)
        index_[indexed++] = static_cast<std::uint32_t>(e);
    }
  }
  while (indexed <= coarse)
    index_[indexed++] = static_cast<std::uint32_t>(n);
}

size_t HalfList::bucketOf(double r) const { return bucketIn(r, key0_, keyShift_, index_.size() - 2); }

size_t HalfList::bound(double v, bool strict) const {
  size_t lo = 0, hi = n_;
  if (!index_.empty() && !std::isnan(v)) {
    size_t b = bucketOf(v);
    lo = index_[b];
    hi = index_[b + 1];
  }
  if (lo < hi && !identity_ && wide_.empty()) {
    // Branchless over the bucket's codes, each probe a product of two table reads: the join
    // asks this once per row, and a bucket's few entries would mispredict a branchy search
    // about every other step.
    const std::uint32_t* base = codes_.data() + lo;
    size_t len = hi - lo;
    while (len > 1) {
      size_t half = len / 2;
      double r = codeRatio(base[half - 1]);
      base += (strict ? r <= v : r < v) ? half : 0;
      len -= half;
    }
    double r = codeRatio(*base);
    return static_cast<size_t>(base - codes_.data()) + ((strict ? r <= v : r < v) ? 1 : 0);
  }
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    double r = ratio(mid);
    if (strict ? r <= v : r < v)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

HalfList HalfList::build(const std::vector<std::vector<double>>& ratios,
                         const std::vector<std::pair<int, int>>& ordered, int from, int to,
                         const std::vector<std::pair<double, double>>* reach) {
  HalfList H;
  H.ratios_ = &ratios;
  H.reach_ = reach;
  H.from_ = from;
  H.width_ = to - from;
  for (int s = from; s < to; ++s)
    if (ratios[static_cast<size_t>(s)].empty()) {
      H.width_ = 0; // no tuple at all
      return H;
    }
  if (H.width_ == 0) {
    H.n_ = 1; // the empty tuple, ratio 1
    H.identity_ = true;
    return H;
  }
  int bits = 0;
  for (int s = from; s < to; ++s) {
    int b = bitsFor(ratios[static_cast<size_t>(s)].size());
    H.shift_.push_back(bits);
    H.mask_.push_back(b >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << b) - 1);
    bits += b;
  }
  if (H.width_ == 1) {
    H.identity_ = true;
    H.n_ = ratios[static_cast<size_t>(from)].size();
    H.mask_[0] = ~std::uint64_t{0};
    return H;
  }
  if (bits > 64) {
    H.error_ = fmt::format("the join's half over {} stages needs {} bits per entry (more than 64): narrow the tooth "
                           "ranges or split the gearbox",
                           H.width_, bits);
    H.width_ = 0;
    return H;
  }
  double tuples = 1;
  for (int s = from; s < to; ++s)
    tuples *= static_cast<double>(ratios[static_cast<size_t>(s)].size());
  if (tuples >= 4294967295.0) {
    // The canonical order (interchangeable stages) may keep far fewer: count them.
    double kept = 0;
    H.forEach(ordered, [&](std::uint64_t, double) { kept += 1; });
    if (kept >= 4294967295.0) {
      H.error_ = fmt::format(
          "the join's half over {} stages would hold {:.3g} entries (more than 2^32): narrow the tooth ranges",
          H.width_, kept);
      H.width_ = 0;
      return H;
    }
  }
  if (H.width_ == 2) {
    H.pair0_ = ratios[static_cast<size_t>(from)].data();
    H.pair1_ = ratios[static_cast<size_t>(from) + 1].data();
  }
  if (bits <= 32)
    H.fill(ordered, H.codes_);
  else
    H.fill(ordered, H.wide_);
  H.reach_ = nullptr;
  return H;
}

} // namespace gbx::rt
