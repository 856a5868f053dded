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

int bitsFor(size_t n) {
  int b = 1;
  while (b < 63 && (std::uint64_t{1} << b) < n)
    ++b;
  return b;
}

} // namespace

template <class F> void HalfList::forEach(const std::vector<std::pair<int, int>>& ordered, F&& f) const {
  const auto& R = *ratios_;
  const int from = from_, to = from_ + width_;
  if (width_ == 2) {
    const auto &r0 = R[static_cast<size_t>(from)], &r1 = R[static_cast<size_t>(from + 1)];
    bool canon = std::find(ordered.begin(), ordered.end(), std::make_pair(from, from + 1)) != ordered.end();
    const int s1 = shift_[1];
    for (std::uint64_t i = 0; i < r0.size(); ++i) {
      std::uint64_t j0 = canon ? i : 0, j1 = r1.size();
      if (reach_ && i < reach_->size()) {
        // The second stage's ratios ascend: the reachable ones are one run of them.
        auto [lo, hi] = (*reach_)[i];
        j0 = std::max<std::uint64_t>(j0, static_cast<std::uint64_t>(std::lower_bound(r1.begin(), r1.end(), lo / r0[i]) - r1.begin()));
        j1 = static_cast<std::uint64_t>(std::upper_bound(r1.begin(), r1.end(), hi / r0[i]) - r1.begin());
      }
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

template <class Code> void HalfList::fill(const std::vector<std::pair<int, int>>& ordered, std::vector<Code>& out) {
  const auto& R = *ratios_;
  // Bucket bounds from the stages' extreme ratios (positive ratios: the product of the
  // least is the least product); entries outside are clamped, which keeps the order.
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
    forEach(ordered, [&](std::uint64_t, double) { kept += 1; });
    upper = std::max(1.0, kept);
  }
  size_t buckets = static_cast<size_t>(std::clamp(upper / 4, 1.0, static_cast<double>(1 << 22)));
  std::uint64_t k0 = orderKey(lo), span = positive ? orderKey(hi) - k0 : 0;
  int shift = 0;
  while (shift < 64 && (span >> shift) >= buckets)
    ++shift;
  buckets = positive ? static_cast<size_t>(span >> shift) + 1 : 1;
  auto bucketOf = [&](double r) { return bucketIn(r, k0, shift, buckets - 1); };
  // Counting sort: counts into start[b + 2], their prefix sums, then start[b + 1] runs as
  // bucket b's write position and ends as its end, so start[b] is its beginning.
  std::vector<std::uint32_t> start(buckets + 2, 0);
  size_t n = 0;
  forEach(ordered, [&](std::uint64_t, double r) {
    ++start[bucketOf(r) + 2];
    ++n;
  });
  for (size_t b = 0; b + 2 < start.size(); ++b)
    start[b + 2] += start[b + 1];
  out.resize(n);
  n_ = n;
  // A short list holds each entry's ratio: placed with its code (the product forEach made,
  // the same number codeRatio gives), then each bucket put in order by (ratio, code) in
  // place, a fixed order for equal ratios.
  const bool hold = n <= kHeldRatios;
  if (hold) {
    held_.resize(n);
    forEach(ordered, [&](std::uint64_t code, double r) {
      std::uint32_t at = start[bucketOf(r) + 1]++;
      out[at] = static_cast<Code>(code);
      held_[at] = r;
    });
    std::vector<std::pair<double, Code>> scratch;
    for (size_t b = 0; b < buckets; ++b) {
      if (start[b + 1] - start[b] > 32) {
        // A crowded bucket: sorted whole (insertion would take its square).
        scratch.clear();
        for (size_t e = start[b]; e < start[b + 1]; ++e) scratch.emplace_back(held_[e], out[e]);
        std::sort(scratch.begin(), scratch.end());
        for (size_t i = 0; i < scratch.size(); ++i) {
          held_[start[b] + i] = scratch[i].first;
          out[start[b] + i] = scratch[i].second;
        }
        continue;
      }
      for (size_t e = start[b] + 1; e < start[b + 1]; ++e) {
        double r = held_[e];
        Code c = out[e];
        size_t at = e;
        for (; at > start[b] && (held_[at - 1] > r || (held_[at - 1] == r && out[at - 1] > c)); --at) {
          held_[at] = held_[at - 1];
          out[at] = out[at - 1];
        }
        held_[at] = r;
        out[at] = c;
      }
    }
  } else {
    forEach(ordered, [&](std::uint64_t code, double r) { out[start[bucketOf(r) + 1]++] = static_cast<Code>(code); });
    // Each entry's ratio computed once, into a scratch the size of the bucket.
    std::vector<std::pair<double, Code>> scratch;
    for (size_t b = 0; b < buckets; ++b) {
      auto first = out.begin() + start[b], last = out.begin() + start[b + 1];
      if (last - first < 2) continue;
      scratch.clear();
      for (auto it = first; it != last; ++it)
        scratch.emplace_back(codeRatio(*it), *it);
      std::sort(scratch.begin(), scratch.end());
      for (size_t i = 0; i < scratch.size(); ++i)
        first[static_cast<std::ptrdiff_t>(i)] = scratch[i].second;
    }
  }
  // The coarse index: every 2^d fine buckets, about four entries each.
  int d = 0;
  while ((buckets >> d) > std::max<size_t>(1, n / 4))
    ++d;
  key0_ = k0;
  keyShift_ = shift + d;
  size_t coarse = ((buckets - 1) >> d) + 1;
  index_.resize(coarse + 1);
  for (size_t b = 0; b < coarse; ++b)
    index_[b] = start[b << d];
  index_[coarse] = static_cast<std::uint32_t>(n);
}

size_t HalfList::bucketOf(double r) const { return bucketIn(r, key0_, keyShift_, index_.size() - 2); }

size_t HalfList::bound(double v, bool strict) const {
  size_t lo = 0, hi = n_;
  if (!index_.empty() && !std::isnan(v)) {
    size_t b = bucketOf(v);
    lo = index_[b];
    hi = index_[b + 1];
  }
  if (!held_.empty() && lo < hi) {
    // Branchless over the held ratios: the join asks this once per row, and the bucket's
    // few entries would mispredict a branchy search about every other step.
    const double* base = held_.data() + lo;
    size_t len = hi - lo;
    while (len > 1) {
      size_t half = len / 2;
      base += (strict ? base[half - 1] <= v : base[half - 1] < v) ? half : 0;
      len -= half;
    }
    size_t at = static_cast<size_t>(base - held_.data());
    return at + ((strict ? *base <= v : *base < v) ? 1 : 0);
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
  if (bits <= 32)
    H.fill(ordered, H.codes_);
  else
    H.fill(ordered, H.wide_);
  H.reach_ = nullptr;
  return H;
}

} // namespace gbx::rt
