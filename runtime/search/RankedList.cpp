#include "search/RankedList.h"

namespace gbx::rt {

std::vector<Design> DesignList::all() const {
  std::vector<Design> out(size());
  for (size_t i = 0; i < out.size(); ++i)
    get(i, out[i]);
  return out;
}

RankedList::RankedList(const Model& m, std::vector<std::vector<Candidate>> lists, std::vector<size_t> listOf,
                       size_t keys)
    : nSlots_(m.slots.size()), lists_(std::move(lists)), listOf_(std::move(listOf)), k_(listOf_.size()), nk_(keys) {
  for (const auto& st : m.stages)
    slots_.push_back(st.slots);
}

void RankedList::reserve(size_t designs) {
  cand_.reserve(designs * k_);
  keys_.reserve(designs * nk_);
}

void RankedList::add(const std::uint32_t* cand, const double* keys) {
  cand_.insert(cand_.end(), cand, cand + k_);
  keys_.insert(keys_.end(), keys, keys + nk_);
  ++n_;
}

void RankedList::get(size_t i, Design& d) const {
  const std::uint32_t* cand = cand_.data() + i * k_;
  d.choice.assign(nSlots_, -1);
  d.undecided = false;
  for (size_t s = 0; s < k_; ++s) {
    const Candidate& c = lists_[listOf_[s]][cand[s]];
    for (size_t j = 0; j < slots_[s].size(); ++j)
      d.choice[static_cast<size_t>(slots_[s][j])] = c.idx[j];
    d.undecided = d.undecided || c.undecided;
  }
  d.ratio = productOf(static_cast<int>(k_),
                      [&](int s) -> const Rational& { return lists_[listOf_[static_cast<size_t>(s)]][cand[s]].ratio; });
  d.keys.assign(keys_.begin() + static_cast<std::ptrdiff_t>(i * nk_),
                keys_.begin() + static_cast<std::ptrdiff_t>((i + 1) * nk_));
  d.freedoms.clear();
}

} // namespace gbx::rt
