#pragma once
// A long listing's ranked designs kept compact: one candidate index per stage and the
// ranking keys, each design made only when it is read. A million designs of four stages
// take some 30 MB this way, against several hundred as `Design`s.
#include <cstdint>
#include <vector>

#include "search/Search.h"
#include "search/StageFilter.h"

namespace gbx::rt {

// The product of k exact ratios part(0) … part(k-1): multiplied out and reduced once, and
// part by part only where that would overflow.
template <class Part> Rational productOf(int k, Part part) {
  units::i128 num = 1, den = 1;
  bool fits = true;
  for (int s = 0; s < k && fits; ++s) {
    const Rational& r = part(s);
    fits = !__builtin_mul_overflow(num, r.num(), &num) && !__builtin_mul_overflow(den, r.den(), &den) &&
           num < (units::i128{1} << 120) && num > -(units::i128{1} << 120) && den < (units::i128{1} << 120);
  }
  if (fits) return Rational::make(num, den);
  Rational q(1);
  for (int s = 0; s < k; ++s) {
    auto p = q.mul(part(s));
    if (p) q = *p;
  }
  return q;
}

class RankedList final : public DesignList {
public:
  // The stages' candidate lists (moved in: the search is done with them), the list of each
  // stage (equal stages share one), and the number of keys.
  RankedList(const Model& m, std::vector<std::vector<Candidate>> lists, std::vector<size_t> listOf, size_t keys);
  void reserve(size_t designs);
  // The next design of the ranking: its candidate per stage and its keys.
  void add(const std::uint32_t* cand, const double* keys);

  size_t size() const override { return n_; }
  void get(size_t i, Design& out) const override;

private:
  std::vector<std::vector<int>> slots_; // per stage: its slots, in its candidates' order
  size_t nSlots_;
  std::vector<std::vector<Candidate>> lists_;
  std::vector<size_t> listOf_;
  size_t k_, nk_;
  size_t n_ = 0;                    // designs (a gearbox without stages has one, of no candidates)
  std::vector<std::uint32_t> cand_; // k_ per design
  std::vector<double> keys_;        // nk_ per design
};

} // namespace gbx::rt
