// The join of the stages' candidates (search/Searcher.h): the walk over rows or over the two
// halves, each window of right entries counted, keyed and kept, and the ranks' shares.
#include "search/Searcher.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <thread>

#include <fmt/format.h>

#include "model/Deadline.h"
#include "parallel/Numbers.h"
#include "parallel/Ranks.h"

namespace gbx::rt::searching {

using ir::Op;

// Designs of the window [from, to) whose ratio is exactly inside; only entries within
// the rounding margin of a bound are confirmed exactly.
unsigned long long Searcher::exactCount(std::uint32_t* cand, double x, size_t from, size_t to) const {
  size_t a = from, b = to, rejected = 0;
  auto outside = [&](size_t re) {
    for (int s = h; s < k; ++s)
      cand[s] = rightIndex(re, s);
    return !window.contains(exactRatio(cand));
  };
  for (; a < b && x * right->ratio(a) < sureLo; ++a)
    rejected += outside(a);
  for (; b > a && x * right->ratio(b - 1) > sureHi; --b)
    rejected += outside(b - 1);
  return static_cast<unsigned long long>(to - from - rejected);
}

// Whether a design that passed the window counts: the rules across stages hold, and it is
// the least of its orbit. Counts what removes it.
bool Searcher::counts(Local& lo, Assignment& a, const std::uint32_t* cand) const {
  if (cross.empty() && !orbitCheck) return true;
  bool filled = false;
  for (size_t c = 0; c < cross.size(); ++c) {
    int holds = -1;
    if (const auto [u, r] = crossAt[c]; u >= 0) {
      const UpstreamStage& up = upstream[static_cast<size_t>(u)];
      double ratio = 1;
      for (int s = 0; s < up.stage; ++s)
        ratio *= candidate(s, cand).r;
      holds = up.brackets[cand[up.stage]][static_cast<size_t>(r)].at(ratio);
    }
    if (holds < 0) {
      // An evaluator call can rate a design (shafts, contact analysis): milliseconds each,
      // so the clock is asked before every one, not only at the walk's intervals.
      if (Deadline::expired()) {
        lo.cutShort = true;
        return false;
      }
      if (!filled) fill(a, cand);
      filled = true;
      lo.asked += 1;
      holds = truthOf(ev.eval(*cross[c]->expr, a)) != Truth::False;
    }
    if (!holds) {
      lo.crossRemoved[c] += 1;
      return false;
    }
  }
  if (!filled) fill(a, cand);
  if (orbitCheck && !representative(a.choice)) {
    lo.duplicates += 1;
    return false;
  }
  return true;
}

void Searcher::leftFloors(Local& lo, size_t le) const {
  lo.leftAt.resize(crossing.size());
  for (size_t c = 0; c < crossing.size(); ++c)
    lo.leftAt[c] = leftIndex(le, crossing[c].first);
}

bool Searcher::canonical(const Local& lo, size_t re) const {
  for (size_t c = 0; c < crossing.size(); ++c)
    if (lo.leftAt[c] > rightIndex(re, crossing[c].second)) return false;
  return true;
}

unsigned long long Searcher::countWindow(Local& lo, std::uint32_t* cand, size_t le, double x, size_t from,
                                         size_t to) const {
  const bool checkCanon = !floorOnly && !crossing.empty();
  unsigned long long count = 0;
  to = std::min(to, rn);
  auto confirm = [&](size_t re) {
    for (int s = h; s < k; ++s)
      cand[s] = rightIndex(re, s);
    return window.contains(exactRatio(cand));
  };
  if (pairView && k - h == 2) {
    // A two-stage right half: each entry's indices against their floors, read from its code.
    const HalfList::PairView& v = *pairView;
    std::uint32_t need[2] = {0, 0};
    for (size_t c = 0; checkCanon && c < crossing.size(); ++c) {
      auto& n = need[crossing[c].second == h ? 0 : 1];
      n = std::max(n, leftIndex(le, crossing[c].first));
    }
    const std::uint32_t need0 = need[0], need1 = need[1];
    for (size_t re = from; re < to; ++re) {
      const std::uint32_t code = v.codes[re], a = code & v.mask0, b = (code >> v.shift1) & v.mask1;
      if (a < need0 || b < need1) continue;
      double p = x * (v.r0[a] * v.r1[b]);
      count += (p >= sureLo && p <= sureHi) || confirm(re);
    }
    return count;
  }
  leftFloors(lo, le);
  for (size_t re = from; re < to; ++re) {
    if (checkCanon && !canonical(lo, re)) continue;
    double p = x * right->ratio(re);
    count += (p >= sureLo && p <= sureHi) || confirm(re);
  }
  return count;
}

// One left entry against the right entries [from, to): each in the window counted (unless
// `counted` says arithmetic did), then keyed and kept when it may rank among the best.
void Searcher::visit(Local& lo, Assignment& a, std::uint32_t* cand, double* scratch, size_t le, double x, size_t from,
                     size_t to, bool counted, bool keyed) const {
  const bool checkCanon = !floorOnly && !crossing.empty();
  leftFloors(lo, le);
  for (size_t re = from; re < to && re < rn; ++re) {
    if (checkCanon && !canonical(lo, re)) continue;
    for (int s = h; s < k; ++s)
      cand[s] = rightIndex(re, s);
    double p = x * right->ratio(re);
    std::optional<Rational> q;
    if (p < sureLo || p > sureHi) {
      q = exactRatio(cand);
      if (!window.contains(*q)) continue;
    }
    if (!counted) {
      lo.inWindow += 1;
      if (!counts(lo, a, cand)) {
        if (lo.cutShort) return;
        continue;
      }
      lo.count += 1;
      if (undecidedAny) {
        bool undecided = false;
        for (int s = 0; s < k; ++s)
          undecided = undecided || candidate(s, cand).undecided;
        lo.undecided += undecided;
      }
    }
    if (keep == 0 || !keyed) continue;
    if (fastKey && full(lo)) {
      // Screen in doubles: only a design that may beat the worst kept one is keyed exactly.
      double w = worst0(lo);
      if (fastKey->lowerAt(cand, p) > w + slack(w)) continue;
    }
    fill(a, cand);
    if (!q) q = exactRatio(cand);
    a.ratio = *q;
    keysInto(a, scratch);
    a.ratio.reset();
    keepHit(lo, scratch, cand);
  }
}

// Whether no design of the window can enter the kept ones (the window's ratios span [rlo, rhi]).
bool Searcher::bounded(const Local& lo, double partial, double rlo, double rhi) const {
  if (!fastKey || !full(lo)) return false;
  double w = worst0(lo);
  double lb = partial + fastKey->ratioLower(rlo * (1 - 1e-12), rhi * (1 + 1e-12)) - fastKey->rounding();
  return lb > w + slack(w);
}

bool Searcher::stopHere(int t, size_t at, size_t begin, size_t end) {
  if (!Deadline::expired() && !timedOut.load(std::memory_order_relaxed) && !overWalked.load(std::memory_order_relaxed))
    return false;
  if (!overWalked) timedOut = true;
  joinDone[static_cast<size_t>(t)] =
      static_cast<double>(at - begin) / static_cast<double>(std::max<size_t>(1, end - begin));
  return true;
}

// Whether to ask about the time limit: at a loop's own interval, or after enough work inside it.
bool Searcher::due(Walk& w, bool interval) {
  if (!interval && w.sinceCheck <= (1u << 16)) return false;
  w.sinceCheck = 0;
  return true;
}

// One left entry against its window of right entries [from, to).
void Searcher::joinEntry(Walk& w, size_t le, double x, size_t from, size_t to, double partial) {
  if (from >= to) return;
  w.sinceCheck += to - from;
  Local& lo = w.lo;
  if (!arith) {
    lo.walked += static_cast<double>(to - from);
    // The exhaustive reference (tests, benchmarks) visits everything by design. A design
    // whose rules its candidates' brackets settle costs a comparison, one they leave to
    // the evaluator some fifty times as much as counting it.
    if ((lo.asked > walkBudget || lo.walked > walkBudget * 50) && !opt.exhaustive) overWalked = true;
    // Counted one by one; keyed only where the window's bound lets a design in.
    bool keyed = keep > 0 && !bounded(lo, partial, x * rightRatio(from), x * rightRatio(to - 1));
    if (!keyed && plainCount) {
      unsigned long long c = countWindow(lo, w.cand.data(), le, x, from, to);
      lo.count += c;
      lo.inWindow += static_cast<double>(c);
      return;
    }
    double asked = lo.asked;
    visit(lo, w.a, w.cand.data(), w.scratch.data(), le, x, from, to, false, keyed);
    // An evaluator call weighs as much as 4 096 entries walked in the check interval; one
    // cut short by the time limit makes the next check stop the walk.
    w.sinceCheck += lo.cutShort ? (1u << 17) : static_cast<size_t>(lo.asked - asked) << 12;
    return;
  }
  unsigned long long c = exactCount(w.cand.data(), x, from, to);
  lo.count += c;
  lo.inWindow += static_cast<double>(c);
  if (c == 0 || keep == 0) return;
  if (bounded(lo, partial, x * right->ratio(from), x * right->ratio(to - 1))) return;
  visit(lo, w.a, w.cand.data(), w.scratch.data(), le, x, from, to, true);
}

namespace {

// The first index in [j, end) where a predicate holds that, once it holds, holds on (end
// where it never does).
template <class P> size_t firstHolding(size_t j, size_t end, P&& holds) {
  for (size_t len = end - std::min(j, end); len > 0;) {
    const size_t half = len / 2;
    if (holds(j + half)) {
      len = half;
    } else {
      j += half + 1;
      len -= half + 1;
    }
  }
  return j;
}

} // namespace

size_t Searcher::shortRowEnd(size_t j, size_t m1, double invI, const double* inv1, const double* r2, size_t fi,
                             bool floorJ) const {
  return firstHolding(j, m1, [&](size_t r) {
    size_t floor = std::max(fi, floorJ ? r : 0);
    return floor >= rn || r2[floor] > wantHiC * (invI * inv1[r]);
  });
}

std::int64_t Searcher::nearBucket(double invI, double lo1) const {
  const double wl = lo1 * invI;
  std::int64_t a;
  std::memcpy(&a, &wl, sizeof a);
  return (a - occupancy.base()) >> occupancy.shift;
}

Searcher::ShortScan Searcher::shortScan(size_t j0, size_t end, double invI, const double* lo1) const {
  // The buckets fall along the row: binary searches for where they come within the table
  // and where they pass below it.
  const auto top = static_cast<std::int64_t>(occupancy.buckets - 1);
  ShortScan sc;
  sc.end = end;
  sc.from = firstHolding(j0, end, [&](size_t j) { return nearBucket(invI, lo1[j]) <= top; });
  sc.below = firstHolding(j0, end, [&](size_t j) { return nearBucket(invI, lo1[j]) < 0; });
  return sc;
}

size_t Searcher::nextShortRow(size_t j, const ShortScan& sc, size_t m1, double invI, const double* lo1) const {
  const std::uint64_t* near = occupancy.near.data();
  auto bit = [&](size_t r) {
    const auto q = static_cast<size_t>(nearBucket(invI, lo1[r]));
    return near[q >> 6] >> (q & 63) & 1;
  };
  j = std::max(j, sc.from);
  const size_t stop = std::min(sc.below, sc.end);
  // Four rows a test: their bits are independent, and one branch serves them.
  for (; j + 4 <= stop; j += 4)
    if (const std::uint64_t b0 = bit(j), b1 = bit(j + 1), b2 = bit(j + 2), b3 = bit(j + 3); b0 | b1 | b2 | b3)
      return j + (b0 ? 0 : b1 ? 1 : b2 ? 2 : 3);
  for (; j < stop; ++j)
    if (bit(j)) return j;
  // Windows that start below the list all read its first bucket.
  return j < sc.end && (near[0] & 1) ? j : m1;
}

void Searcher::locateWindows(WindowBatch& b) const {
  auto locate = [&](auto&& ratio) {
    // Branchless searches over [first, end), every row a step at a time.
    size_t len[WindowBatch::kSize], most = 0;
    for (size_t r = 0; r < b.n; ++r) {
      auto [first, end] = occupancy.rangeOf(b.wl[r]);
      b.from[r] = first;
      len[r] = end - first;
      most = std::max(most, len[r]);
    }
    for (; most > 1; most -= most / 2)
      for (size_t r = 0; r < b.n; ++r) {
        const size_t half = len[r] / 2;
        b.from[r] += half > 0 && ratio(b.from[r] + half - 1) < b.wl[r] ? half : 0;
        len[r] -= half;
      }
    for (size_t r = 0; r < b.n; ++r) {
      b.from[r] += len[r] == 1 && ratio(b.from[r]) < b.wl[r];
      for (b.to[r] = b.from[r]; b.to[r] < rn && ratio(b.to[r]) <= b.wh[r];)
        ++b.to[r];
    }
  };
  withRightRatio(locate);
}

// Inline: it runs once per window of the hot loop.
inline void Searcher::joinRow(Walk& w, size_t i, size_t j, double x, size_t from, size_t to, double rowPart,
                              double rightLeast) {
  w.cand[1] = static_cast<std::uint32_t>(j);
  double partial = 0;
  if (fastKey && full(w.lo))
    partial = rowPart + fastKey->entry(1, w.cand[1]) + (rowMin.empty() ? rightLeast : rowMin.least(from, to));
  joinEntry(w, i * n1 + j, x, from, to, partial);
}

void Searcher::joinBatch(Walk& w, WindowBatch& b, size_t i, const double* r0, const double* r1, double rowPart,
                         double rightLeast) {
  locateWindows(b);
  for (size_t r = 0; r < b.n; ++r)
    if (b.from[r] < b.to[r]) joinRow(w, i, b.j[r], r0[i] * r1[b.j[r]], b.from[r], b.to[r], rowPart, rightLeast);
  b.n = 0;
}

void Searcher::buildOccupancy() {
  if (!rows || right->width() < 1 || rn == 0 || !(wantLoC > 0) || !std::isfinite(wantHiC)) return;
  const double lo = right->ratio(0), hi = right->ratio(rn - 1);
  if (!(lo > 0) || !(hi >= lo) || !std::isfinite(hi)) return;
  // A quarter of a window's keys per bucket (the window measured where the keys are
  // densest, at the list's largest ratio), and no more buckets than the caps allow: 256 an
  // entry for a short list (its tables stay in the caches), 64 for a long one.
  const bool shortList = right->width() == 1;
  std::uint64_t k0 = orderKey(lo), span = orderKey(hi) - k0;
  std::uint64_t window = orderKey(hi * (wantHiC / wantLoC)) - orderKey(hi);
  int shift = 0;
  while (shift < 62 && (std::uint64_t{1} << (shift + 1)) <= window / 4)
    ++shift;
  const std::uint64_t most =
      std::min<std::uint64_t>(std::uint64_t{shortList ? 256u : 64u} * rn, std::uint64_t{1} << 25);
  while (shift < 63 && (span >> shift) + 1 > most)
    ++shift;
  occupancy.key0 = k0;
  occupancy.shift = shift;
  occupancy.buckets = static_cast<size_t>(span >> shift) + 1;
  occupancy.bits.assign((occupancy.buckets + 63) / 64 + 1, 0); // a spare word: any() reads two
  if (!shortList) occupancy.first.assign(occupancy.bits.size(), static_cast<std::uint32_t>(rn));
  // A window's most order keys: its relative width times 2^52 (the key is a double's bits;
  // 2^53 for margin), and two for rounding. It reaches at most ceil(keys / bucket) buckets
  // past its first; a short list's rows read that reach as one bit (a few buckets at most).
  const double windowKeys = std::ldexp(wantHiC / wantLoC - 1, 53) + 2;
  const double reachBuckets = std::ceil(windowKeys / std::ldexp(1, shift));
  const bool near = shortList && reachBuckets <= 8;
  const size_t reach = near ? static_cast<size_t>(reachBuckets) : 0;
  if (near) occupancy.near.assign(occupancy.bits.size(), 0);
  auto mark = [&](auto&& ratio) {
    for (size_t e = 0, w = 0; e < rn; ++e) {
      size_t kb = occupancy.bucket(ratio(e));
      occupancy.bits[kb >> 6] |= std::uint64_t{1} << (kb & 63);
      for (; !shortList && w <= (kb >> 6); ++w)
        occupancy.first[w] = static_cast<std::uint32_t>(e);
      if (near)
        for (size_t q = kb - std::min(kb, reach); q <= kb; ++q)
          occupancy.near[q >> 6] |= std::uint64_t{1} << (q & 63);
    }
  };
  withRightRatio(mark);
}

namespace {

// The least ratio a wider right half's canonical entries can have in row (i, j), from the
// least index each of its stages may take (ratios ascend with the index). Where no right
// stage's floor is the first stage's index, it depends on j alone: one table for every row.
class LeastRight {
public:
  LeastRight(const std::vector<std::vector<double>>& ratios, const std::vector<std::pair<int, int>>& ordered, int k,
             bool wide)
      : ratios_(ratios), k_(k), fl_(static_cast<size_t>(k), 0), floorsOf_(static_cast<size_t>(k)) {
    for (const auto& [sa, sb] : ordered)
      if (sb >= 2) floorsOf_[static_cast<size_t>(sb)].push_back(sa);
    bool fromI = false;
    for (int s = 2; s < k; ++s)
      for (int sa : floorsOf_[static_cast<size_t>(s)])
        fromI = fromI || sa == 0;
    if (!fromI && wide)
      for (size_t j = 0; j < ratios[1].size(); ++j)
        byJ_.push_back(compute(0, j));
  }
  double operator()(size_t i, size_t j) { return byJ_.empty() ? compute(i, j) : byJ_[j]; }

private:
  double compute(size_t i, size_t j) {
    double r = 1;
    for (int s = 2; s < k_; ++s) {
      size_t f = 0;
      for (int sa : floorsOf_[static_cast<size_t>(s)])
        f = std::max(f, sa == 0 ? i : sa == 1 ? j : fl_[static_cast<size_t>(sa)]);
      fl_[static_cast<size_t>(s)] = f;
      const auto& list = ratios_[static_cast<size_t>(s)];
      if (f >= list.size()) return static_cast<double>(INFINITY);
      r *= list[f];
    }
    return r;
  }
  const std::vector<std::vector<double>>& ratios_;
  int k_;
  std::vector<size_t> fl_;
  std::vector<std::vector<int>> floorsOf_; // the stages each right stage's index may not fall below
  std::vector<double> byJ_;
};

} // namespace

// Three to five stages: the first two walked row by row; the tight loop reads raw ratio
// arrays, and the floor of a one-stage right half from flags.
bool Searcher::sweepRows(Walk& w) {
  const double* r0 = ratios[0].data();
  const double* r1 = ratios[1].data();
  const double* r2 = right->width() == 1 ? ratios[2].data() : nullptr;
  const size_t m1 = ratios[1].size();
  bool j0FromI = false, floorI = false, floorJ = false;
  for (const auto& [sa, sb] : ordered) {
    j0FromI = j0FromI || (sa == 0 && sb == 1);
    floorI = floorI || (sa == 0 && sb == 2);
    floorJ = floorJ || (sa == 1 && sb == 2);
  }
  LeastRight leastRight(ratios, ordered, k, !r2);
  const double base = fastKey ? fastKey->constant() : 0;
  double rightLeast = 0;
  if (fastKey)
    for (int s = 2; s < k; ++s)
      rightLeast += fastKey->least(s);
  // Reciprocals once: a row's window then costs products, not divisions (its rounding is
  // far inside the window's margin eps, and every border entry is confirmed exactly).
  std::vector<double> inv0(ratios[0].size()), inv1(m1);
  for (size_t i = 0; i < inv0.size(); ++i)
    inv0[i] = 1 / r0[i];
  for (size_t j = 0; j < m1; ++j)
    inv1[j] = 1 / r1[j];
  // A short right list's rows are scanned by nextShortRow, which reads the occupancy
  // table directly: positive windows only.
  const bool positive = !ratios[0].empty() && r0[0] > 0 && m1 > 0 && r1[0] > 0 && wantLoC > 0 && wantLoC <= wantHiC;
  const bool tight = r2 && !occupancy.near.empty() && positive;
  // The rows' lowest window bounds but for the left index's factor.
  std::vector<double> lo1(tight ? m1 : 0);
  for (size_t j = 0; j < lo1.size(); ++j)
    lo1[j] = wantLoC * inv1[j];
  // A long right list's windows are found in batches: positive windows of a built table.
  const bool batched = !r2 && !occupancy.first.empty() && positive;
  WindowBatch batch;
  auto& cand = w.cand;
  for (size_t i = w.begin; i < w.end; ++i) {
    if (due(w, (i - w.begin) % 64 == 0) && stopHere(w.t, i, w.begin, w.end)) return false;
    if (w.report && (i - w.begin) % 64 == 0)
      opt.progress(static_cast<double>(i - w.begin) / static_cast<double>(w.end - w.begin));
    size_t j0 = j0FromI ? i : 0;
    if (j0 >= m1) continue;
    cand[0] = static_cast<std::uint32_t>(i);
    double x0 = r0[i] * r1[j0];
    size_t loP = right->lowerBound(wantLoC / x0), hiP = right->upperBound(wantHiC / x0);
    double rowPart = fastKey ? base + fastKey->entry(0, cand[0]) : 0;
    const ShortScan scan = tight ? shortScan(j0, shortRowEnd(j0, m1, inv0[i], inv1.data(), r2, floorI ? i : 0, floorJ),
                                             inv0[i], lo1.data())
                                 : ShortScan{};
    for (size_t j = j0; j < m1; ++j) {
      if (tight) {
        const size_t start = j;
        j = nextShortRow(j, scan, m1, inv0[i], lo1.data());
        w.sinceCheck += std::min(j, scan.end) - start;
        if (j >= m1) break;
      }
      if (due(w, false) && stopHere(w.t, i, w.begin, w.end)) return false;
      double x = r0[i] * r1[j];
      double inv = inv0[i] * inv1[j];
      double wl = wantLoC * inv, wh = wantHiC * inv;
      if (r2) {
        // A short list: the row ends where its floor's entry is past the window (the
        // window only falls along a row); a window over buckets that hold no entry is
        // passed over; else two binary searches find it.
        size_t floor = std::max(floorI ? i : 0, floorJ ? j : 0);
        if (floor >= rn || r2[floor] > wh) break;
        if (!occupancy.any(wl, wh)) continue;
        loP = static_cast<size_t>(std::lower_bound(r2, r2 + rn, wl) - r2);
        hiP = static_cast<size_t>(std::upper_bound(r2, r2 + rn, wh) - r2);
      } else {
        // A long one: the row's window ends the row past its least entry; a window over
        // log-ratio buckets that hold no entry is passed over; else it joins the batch.
        if (x * leastRight(i, j) > wantHiC) break;
        if (batched) {
          if (!occupancy.anyPositive(wl, wh)) continue;
          batch.j[batch.n] = static_cast<std::uint32_t>(j);
          batch.wl[batch.n] = wl;
          batch.wh[batch.n] = wh;
          if (++batch.n == WindowBatch::kSize) joinBatch(w, batch, i, r0, r1, rowPart, rightLeast);
          continue;
        }
        loP = right->lowerBound(wl);
        hiP = right->upperBound(wh);
      }
      // The window only falls and the floor only rises along a row.
      size_t from = loP;
      if (floorOnly) {
        size_t floor = std::max(floorI ? i : 0, floorJ ? j : 0);
        if (hiP <= floor) break;
        from = std::max(loP, floor);
      }
      if (from >= hiP) continue;
      joinRow(w, i, j, x, from, hiP, rowPart, rightLeast);
    }
    if (batch.n > 0) joinBatch(w, batch, i, r0, r1, rowPart, rightLeast);
  }
  return true;
}

// Two halves built and sorted: one two-pointer sweep of the left list against the right.
bool Searcher::sweepHalves(Walk& w) {
  double rightLeast = 0;
  if (fastKey) {
    rightLeast = fastKey->constant();
    for (int s = h; s < k; ++s)
      rightLeast += fastKey->least(s);
  }
  size_t loP = right->lowerBound(wantLoC / leftList.ratio(w.begin)),
         hiP = right->upperBound(wantHiC / leftList.ratio(w.begin));
  for (size_t le = w.begin; le < w.end; ++le) {
    if (due(w, (le - w.begin) % 4096 == 0) && stopHere(w.t, le, w.begin, w.end)) return false;
    if (w.report && (le - w.begin) % 65536 == 0)
      opt.progress(static_cast<double>(le - w.begin) / static_cast<double>(w.end - w.begin));
    double x = leftList.ratio(le);
    double inv = 1 / x;
    double wl = wantLoC * inv, wh = wantHiC * inv;
    while (loP > 0 && right->ratio(loP - 1) >= wl)
      --loP;
    while (hiP > 0 && right->ratio(hiP - 1) > wh)
      --hiP;
    size_t from = std::max(loP, rightFloor(le));
    if (from >= hiP) continue;
    double partial = rightLeast;
    for (int s = 0; s < h; ++s) {
      w.cand[static_cast<size_t>(s)] = leftIndex(le, s);
      if (fastKey) partial += fastKey->entry(s, w.cand[static_cast<size_t>(s)]);
    }
    joinEntry(w, le, x, from, hiP, partial);
  }
  return true;
}

// One share of the rows: slot t of all the ranks' threads (locals.size()).
void Searcher::sweep(int t) {
  Local& lo = locals[static_cast<size_t>(t)];
  lo.crossRemoved.assign(cross.size(), 0);
  const size_t slots = locals.size();
  size_t begin = n * static_cast<size_t>(t) / slots;
  size_t end = n * static_cast<size_t>(t + 1) / slots;
  if (begin >= end || rn == 0) return;
  // The bar itself appears only once the solve has taken a second.
  bool report = t == 0 && opt.progress;
  Walk w{t,   lo, Assignment(m), std::vector<std::uint32_t>(kk + 1, 0), std::vector<double>(nk + 1, 0), begin,
         end, 0,  report};
  bool done = rows ? sweepRows(w) : sweepHalves(w);
  // A walk cut short in its last window had no check after it: not all of it was done.
  if (lo.cutShort) {
    timedOut = true;
    joinDone[static_cast<size_t>(t)] = std::min(joinDone[static_cast<size_t>(t)], 0.999);
  }
  if (report && done) opt.progress(1.0);
}

// The join over threads; false when it stopped (the time limit, or the designs checked one
// by one beyond their budget).
bool Searcher::join() {
  const double wlo = window.lo ? window.lo->toDouble() : -INFINITY, whi = window.hi ? window.hi->toDouble() : INFINITY;
  sureLo = wlo * (1 + 4 * eps);
  sureHi = whi * (1 - 4 * eps);
  // Both bounds of the right window fall as the left ratio rises.
  wantLoC = wlo * (1 - eps);
  wantHiC = whi * (1 + eps);
  n = rows ? candidatesOf(0).size() : leftList.size();
  rn = right->size();
  threads = std::max(1, std::min<int>(opt.jobs, static_cast<int>(n / 64) + 1));
  for (int s = 0; s < k; ++s)
    for (const auto& c : candidatesOf(s))
      undecidedAny = undecidedAny || c.undecided;
  // Counted by arithmetic (the window's length, its borders confirmed exactly) when every
  // design in a window counts: no rule across stages, no orbit test, no undecided freedom,
  // and the canonical order at most a floor.
  arith = !opt.exhaustive && cross.empty() && !orbitCheck && !undecidedAny && (floorOnly || crossing.empty());
  plainCount = !opt.exhaustive && cross.empty() && !orbitCheck && !undecidedAny;
  buildOccupancy();
  // The rows dealt to every rank's threads; each rank sweeps its own slots and receives
  // the others' counts and kept designs (a fixed point: every rank searches alike).
  const int ranks = par::sharingRanks();
  const size_t slots = static_cast<size_t>(threads) * static_cast<size_t>(ranks);
  locals.resize(slots);
  walkBudget = opt.maxDesigns * kCheckedShare / static_cast<double>(slots);
  joinDone.assign(slots, 1.0);
  auto shares = par::map(
      static_cast<size_t>(ranks), 1,
      [&](size_t r) {
        int first = static_cast<int>(r) * threads;
        std::vector<std::thread> pool;
        for (int t = 1; t < threads; ++t)
          pool.emplace_back([this, first, t] { sweep(first + t); });
        sweep(first);
        for (auto& th : pool)
          th.join();
        return ranks > 1 ? packShare(first) : std::vector<double>{};
      },
      true);
  if (ranks > 1)
    for (size_t r = 0; r < shares.size(); ++r)
      if (static_cast<int>(r) != par::rank()) unpackShare(shares[r], static_cast<int>(r) * threads);
  if (overWalked) {
    res.errors.push_back(
        fmt::format("the rules across stages are checked design by design, and more than {:.3g} designs (a fiftieth "
                    "of the search budget, --max-designs {:.3g}) of the {:.3g} combinations need them evaluated, "
                    "or more than {:.3g} visited; narrow the ranges or the ratio window, or raise --max-designs",
                    opt.maxDesigns * kCheckedShare, opt.maxDesigns, combos, opt.maxDesigns));
    return false;
  }
  if (timedOut) {
    double elapsed = Deadline::seconds();
    double done = 0;
    for (double d : joinDone)
      done += d / static_cast<double>(joinDone.size());
    // The designs of the part walked are kept, the report marked partial.
    res.partial = timeLimitMessage("joining the stages' candidates", done, elapsed, combos);
    return true;
  }
  return true;
}

// A rank's share of the join as numbers: the stop flags, then per thread its counts, its
// completed fraction and its kept designs (keys, candidates, heap).
std::vector<double> Searcher::packShare(int first) const {
  par::NumbersOut out;
  out.put(timedOut ? 1.0 : 0.0);
  out.put(overWalked ? 1.0 : 0.0);
  for (int t = first; t < first + threads; ++t) {
    const Local& lo = locals[static_cast<size_t>(t)];
    out.count(lo.count);
    out.count(lo.undecided);
    for (double x : {lo.inWindow, lo.duplicates, lo.walked, lo.overKept ? 1.0 : 0.0, joinDone[static_cast<size_t>(t)]})
      out.put(x);
    out.list(lo.crossRemoved);
    out.list(lo.keys);
    out.list(lo.cand);
    out.list(lo.heap);
  }
  return out.take();
}

void Searcher::unpackShare(const std::vector<double>& v, int first) {
  par::NumbersIn in(v);
  // Another rank's time limit stops this one too, so that every rank reports alike.
  if (in.next() != 0) {
    timedOut = true;
    Deadline::expireNow();
  }
  if (in.next() != 0) overWalked = true;
  for (int t = first; t < first + threads; ++t) {
    Local& lo = locals[static_cast<size_t>(t)];
    lo.count = in.count();
    lo.undecided = in.count();
    lo.inWindow = in.next();
    lo.duplicates = in.next();
    lo.walked = in.next();
    lo.overKept = in.next() != 0;
    joinDone[static_cast<size_t>(t)] = in.next();
    in.list(lo.crossRemoved);
    in.list(lo.keys);
    in.list(lo.cand);
    in.list(lo.heap);
  }
}

} // namespace gbx::rt::searching
