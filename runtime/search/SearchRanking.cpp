// The kept designs (search/Searcher.h): each thread's best in a heap as the join finds them,
// then merged, ranked and handed over as designs or as a compact list, with the funnel's last steps.
#include "search/Searcher.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <fmt/format.h>


namespace gbx::rt::searching {

bool Searcher::lessRaw(const double* ka, const std::uint32_t* ca, const double* kb, const std::uint32_t* cb) const {
  for (size_t i = 0; i < nk; ++i)
    if (ka[i] != kb[i]) return ka[i] < kb[i];
  for (size_t s = 0; s < kk; ++s)
    if (ca[s] != cb[s]) return ca[s] < cb[s];
  return false;
}

void Searcher::keepHit(Local& lo, const double* keys, const std::uint32_t* cand) const {
  auto cmp = [&](std::uint32_t x, std::uint32_t y) {
    return lessRaw(lo.keys.data() + x * nk, lo.cand.data() + x * kk, lo.keys.data() + y * nk, lo.cand.data() + y * kk);
  };
  if (keep == SIZE_MAX && lo.heap.size() >= opt.maxKept) {
    lo.overKept = true; // memory stays bounded; the caller says how many were found
    return;
  }
  if (keep == SIZE_MAX || lo.heap.size() < keep) {
    auto id = static_cast<std::uint32_t>(lo.heap.size()); // stored in step with the heap until it is full
    // Appended element by element: a range insert this short costs more than the copy.
    for (size_t i = 0; i < nk; ++i)
      lo.keys.push_back(keys[i]);
    for (size_t i = 0; i < kk; ++i)
      lo.cand.push_back(cand[i]);
    lo.heap.push_back(id);
    // A heap only once it is full: until then nothing is evicted.
    if (lo.heap.size() == keep) std::make_heap(lo.heap.begin(), lo.heap.end(), cmp);
    return;
  }
  std::uint32_t w = lo.heap.front();
  if (!lessRaw(keys, cand, lo.keys.data() + w * nk, lo.cand.data() + w * kk)) return;
  std::pop_heap(lo.heap.begin(), lo.heap.end(), cmp);
  std::copy(keys, keys + nk, lo.keys.begin() + static_cast<std::ptrdiff_t>(w * nk));
  std::copy(cand, cand + kk, lo.cand.begin() + static_cast<std::ptrdiff_t>(w * kk));
  std::push_heap(lo.heap.begin(), lo.heap.end(), cmp);
}

// Every kept design in order: the best `keep` of them, or all, by the first key alone (a
// plain comparison), then each run of equal first keys by the rest (most runs are one design).
void Searcher::order(std::vector<Ref>& hits) const {
  auto byRef = [this](const Ref& x, const Ref& y) { return refLess(x, y); };
  if (hits.size() > keep) {
    std::partial_sort(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(keep), hits.end(), byRef);
    hits.resize(keep);
    return;
  }
  if (hits.size() < 65536) {
    std::sort(hits.begin(), hits.end(), [](const Ref& x, const Ref& y) { return x.k0 < y.k0; });
  } else {
    // A long listing: radix sort on the bits of the first key, mapped to their order.
    std::vector<Ref> other(hits.size());
    std::vector<size_t> at(65537);
    for (int shift = 0; shift < 64; shift += 16) {
      std::fill(at.begin(), at.end(), 0);
      for (const Ref& r : hits)
        ++at[((orderKey(r.k0) >> shift) & 0xFFFF) + 1];
      if (at[1 + ((orderKey(hits[0].k0) >> shift) & 0xFFFF)] == hits.size()) continue; // one digit: already in order
      for (size_t b = 0; b < 65536; ++b)
        at[b + 1] += at[b];
      for (const Ref& r : hits)
        other[at[(orderKey(r.k0) >> shift) & 0xFFFF]++] = r;
      hits.swap(other);
    }
  }
  for (size_t i = 0; i < hits.size();) {
    size_t j = i + 1;
    while (j < hits.size() && !(hits[i].k0 < hits[j].k0))
      ++j;
    if (j - i > 1)
      std::sort(hits.begin() + static_cast<std::ptrdiff_t>(i), hits.begin() + static_cast<std::ptrdiff_t>(j), byRef);
    i = j;
  }
}

// The threads' counts and kept designs merged, ranked, and the funnel's last steps.
void Searcher::collect() {
  std::vector<double> crossRemoved(cross.size(), 0);
  double inWindow = 0, duplicates = 0;
  unsigned long long count = 0, undecided = 0;
  std::vector<Ref> hits;
  size_t all = 0;
  for (const auto& lo : locals)
    all += lo.heap.size();
  hits.reserve(all);
  for (size_t t = 0; t < locals.size(); ++t) {
    const Local& lo = locals[t];
    count += lo.count;
    undecided += lo.undecided;
    inWindow += lo.inWindow;
    duplicates += lo.duplicates;
    for (size_t c = 0; c < cross.size(); ++c)
      crossRemoved[c] += lo.crossRemoved[c];
    for (std::uint32_t id : lo.heap)
      hits.push_back({nk ? lo.keys[size_t{id} * nk] : 0.0, static_cast<std::uint32_t>(t), id});
  }
  if ((capped && count > opt.maxKept) ||
      std::any_of(locals.begin(), locals.end(), [](const Local& lo) { return lo.overKept; })) {
    res.errors.push_back(
        fmt::format("{} designs satisfy the rules, more than the {} a report can list (the budget of kept "
                    "designs); ask for fewer with `report {{ top N; }}`, or narrow the ranges",
                    count, opt.maxKept));
    return;
  }
  order(hits);
  // The ranked designs: the compact list, or every design made whole from it.
  std::shared_ptr<const DesignList> list = listing(hits);
  if (opt.compact)
    res.listing = std::move(list);
  else
    res.designs = list->all();
  std::string windowText =
      windowTexts.empty() ? "ratio (no window)" : fmt::format("{}", fmt::join(windowTexts, " and "));
  // With interchangeable stages enumerated canonically, what passes the window is
  // already one design per orbit.
  if (fast && !ordered.empty()) windowText += " (interchangeable stages: one design per orbit)";
  // One stage: the stage's filter applied the window (and credited it).
  if (k != 1 || windowTexts.empty()) res.funnel.push_back({windowText, "", combos, combos - inWindow});
  double before = inWindow;
  for (size_t c = 0; c < cross.size(); ++c) {
    res.funnel.push_back({cross[c]->text, "", before, crossRemoved[c]});
    before -= crossRemoved[c];
  }
  if (group.size() > 1 && !fast)
    res.funnel.push_back({"interchangeable: one design per orbit", "", before, duplicates});
  res.count = count;
  res.undecided = undecided;
}

// The ranked designs as candidate indices and keys; the threads' shares are let go once
// the list is made, and the stages' candidates move into it.
std::shared_ptr<const DesignList> Searcher::listing(std::vector<Ref>& hits) {
  std::vector<std::vector<Candidate>> lists;
  std::vector<size_t> listOf;
  for (int s = 0; s < k; ++s) {
    const size_t from = source[static_cast<size_t>(s)];
    if (from == static_cast<size_t>(s)) lists.push_back(std::move(stages[from].candidates));
    listOf.push_back(from == static_cast<size_t>(s) ? lists.size() - 1 : listOf[from]);
  }
  auto list = std::make_shared<RankedList>(m, std::move(lists), std::move(listOf), nk);
  list->reserve(hits.size());
  for (const Ref& x : hits)
    list->add(candOf(x), keysOf(x));
  std::vector<Ref>().swap(hits);
  std::vector<Local>().swap(locals);
  return list;
}

} // namespace gbx::rt::searching
