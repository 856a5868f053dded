#pragma once
// One half of the meet-in-the-middle join: every tuple of candidates of stages [from, to),
// canonical within interchangeable blocks, in ascending order of its ratio product. An
// entry is the tuple's candidate indices packed into one integer (4 bytes when they fit);
// its ratio is recomputed from the stages' candidate ratios when the sweep reads it (for
// two stages, two reads of small tables and a product). Holding the ratios beside the codes
// tripled the list's memory, and a page of memory first touched costs more than the
// products it would save. Sorted by a counting sort over runs of the ratio's bits
// (monotone in the ratio, about uniform in its logarithm), each run then in order by finer
// buckets of its own: no per-entry allocation, no copies of keys.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "search/LargePages.h"

namespace gbx::rt {

// The order of positive doubles is the order of their bits; this map extends it to all.
inline std::uint64_t orderKey(double r) {
  std::uint64_t u;
  std::memcpy(&u, &r, sizeof u);
  return (u >> 63) ? ~u : u | (std::uint64_t{1} << 63);
}

class HalfList {
public:
  HalfList() = default;
  // ratios[s]: the candidate ratios of stage s, ascending. ordered: pairs (a, b) of stages
  // whose candidate indices must not decrease (interchangeable stages, enumerated once).
  // reach: where given, entry ratios outside reach[c] (c the entry's index in its first
  // stage) are left out: no other half can complete them into the window.
  static HalfList build(const std::vector<std::vector<double>>& ratios, const std::vector<std::pair<int, int>>& ordered,
                        int from, int to, const std::vector<std::pair<double, double>>* reach = nullptr);

  size_t size() const { return n_; }
  int width() const { return width_; }
  // Candidate index of the half's s-th stage (0-based within the half) for entry e.
  std::uint32_t index(size_t e, int s) const { return field(code(e), s); }
  [[gnu::always_inline]] double ratio(size_t e) const { return codeRatio(code(e)); }
  // First entry whose ratio is >= v (lowerBound) or > v (upperBound): a jump through a
  // coarse index of the ratio buckets, then a binary search inside one bucket.
  size_t lowerBound(double v) const { return bound(v, false); }
  size_t upperBound(double v) const { return bound(v, true); }
  // A two-stage half held as 4-byte codes, for loops that read many entries: entry e's
  // indices are codes[e] & mask0 and (codes[e] >> shift1) & mask1, its ratio r0[first] *
  // r1[second] (the product ratio() computes).
  struct PairView {
    const std::uint32_t* codes;
    std::uint32_t mask0, mask1;
    int shift1;
    const double *r0, *r1;
    double ratio(size_t e) const {
      const std::uint32_t c = codes[e];
      return r0[c & mask0] * r1[(c >> shift1) & mask1];
    }
  };
  bool hasPairView() const { return pair0_ && wide_.empty() && !identity_; }
  PairView pairView() const {
    return {
        codes_.data(), static_cast<std::uint32_t>(mask_[0]), static_cast<std::uint32_t>(mask_[1]), shift_[1], pair0_,
        pair1_};
  }
  // Why the list could not be built (the tuples do not fit a 64-bit code), or empty.
  const std::string& error() const { return error_; }

private:
  [[gnu::always_inline]] std::uint64_t code(size_t e) const {
    return identity_ ? e : (wide_.empty() ? codes_[e] : wide_[e]);
  }
  std::uint32_t field(std::uint64_t c, int s) const {
    return static_cast<std::uint32_t>((c >> shift_[static_cast<size_t>(s)]) & mask_[static_cast<size_t>(s)]);
  }
  [[gnu::always_inline]] double codeRatio(std::uint64_t c) const {
    // Two stages, the usual half: two table reads and a product (the same product as below).
    if (pair0_) return pair0_[c & mask_[0]] * pair1_[(c >> shift_[1]) & mask_[1]];
    double r = 1;
    for (int s = 0; s < width_; ++s)
      r *= (*ratios_)[static_cast<size_t>(from_ + s)][field(c, s)];
    return r;
  }
  size_t bound(double v, bool strict) const;
  size_t bucketOf(double r) const;
  template <class Code> void fill(const std::vector<std::pair<int, int>>& ordered, LargeVector<Code>& out);
  template <class F> void forEach(const std::vector<std::pair<int, int>>& ordered, F&& f) const;
  std::pair<std::uint64_t, std::uint64_t> pairRun(std::uint64_t i, bool canon) const;
  bool pairCanonical(const std::vector<std::pair<int, int>>& ordered) const;

  const std::vector<std::vector<double>>* ratios_ = nullptr;
  const double *pair0_ = nullptr, *pair1_ = nullptr;               // a two-stage half's ratio tables
  const std::vector<std::pair<double, double>>* reach_ = nullptr;  // during build only
  int from_ = 0, width_ = 0;
  size_t n_ = 0;
  bool identity_ = false; // one stage: entry e is candidate e (the candidates are sorted)
  LargeVector<std::uint32_t> codes_;
  static constexpr size_t kRunEntries = 2048; // entries the build puts in order at a time
  LargeVector<std::uint64_t> wide_;
  std::vector<int> shift_;
  std::vector<std::uint64_t> mask_;
  std::string error_;
  // The coarse index: entries [index_[b], index_[b + 1]) lie in bucket b of the map
  // (orderKey(r) - key0_) >> shift_ (clamped), which is monotone in r.
  LargeVector<std::uint32_t> index_;
  std::uint64_t key0_ = 0;
  int keyShift_ = 0;
};

} // namespace gbx::rt
