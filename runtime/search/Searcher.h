#pragma once
// One search, phase by phase (docs/language.md): rules into conjuncts, constant rules, the
// budget and each stage's filter, interchangeable stages, the halves of the join and its
// budget, the ranking keys, the join itself, and the ranked list with its funnel. Each phase
// returns false when it ends the search (the result then says why). The phases are defined
// by topic: Search.cpp (rules, stages, symmetry, layout, ranking keys, orbits),
// SearchJoin.cpp (the join and the ranks' shares), SearchRanking.cpp (the kept designs
// ranked into the result). Internal to the search: search/Search.h is its interface.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "model/Evaluator.h"
#include "search/Conjuncts.h"
#include "search/FastKey.h"
#include "search/HalfList.h"
#include "search/RankedList.h"
#include "search/Search.h"
#include "search/StageFilter.h"
#include "search/Upstream.h"

namespace gbx::rt::searching {

using Perm = std::vector<int>; // slot -> slot

class Searcher {
public:
  Searcher(const Model& model, const SearchOptions& options)
      : m(model), opt(options), ev(model), k(static_cast<int>(model.stages.size())), kk(static_cast<size_t>(k)) {}

  SearchResult run();

private:
  // A thread's share of the join: its counts and its kept designs.
  struct Local {
    std::vector<double> keys;        // nk per kept design
    std::vector<std::uint32_t> cand; // k per kept design: candidate index per stage
    std::vector<std::uint32_t> heap; // kept designs, a max-heap when `top` limits them
    unsigned long long count = 0, undecided = 0;
    double inWindow = 0, duplicates = 0;
    std::vector<double> crossRemoved;
    std::vector<std::uint32_t> leftAt; // scratch: the left indices the canonical order compares
    bool overKept = false;             // an unlimited listing reached opt.maxKept
    double walked = 0;                 // designs visited one by one (not counted by arithmetic)
    double asked = 0;                  // of which the evaluator asked the rules across stages
    bool cutShort = false;             // the time limit came before an evaluator call
  };
  // One thread's walk over its range of left entries.
  struct Walk {
    int t;
    Local& lo;
    Assignment a;
    std::vector<std::uint32_t> cand;
    std::vector<double> scratch;
    size_t begin, end;
    size_t sinceCheck = 0; // right entries walked since the time limit was last asked about
    bool report;
  };

  const Model& m;
  const SearchOptions& opt;
  Evaluator ev;
  const int k;
  const size_t kk;
  SearchResult res;

  // Rules.
  std::vector<Conjunct> conjuncts;
  Window window;
  std::vector<std::string> windowTexts;
  std::vector<std::vector<const Conjunct*>> local;
  std::vector<const Conjunct*> cross, global;
  // Per cross rule: its stage's entry in `upstream` and its place there, or -1.
  std::vector<std::pair<int, int>> crossAt;
  std::vector<UpstreamStage> upstream;
  // Stages, symmetry and the join's halves.
  std::vector<StageResult> stages;
  // Per stage: the stage whose result holds its candidates (itself, or an equal earlier one).
  std::vector<size_t> source;
  const std::vector<Candidate>& candidatesOf(int s) const { return stages[source[static_cast<size_t>(s)]].candidates; }
  // Each stage its own copy of its candidates, before one stage's are changed.
  void unshare();
  std::vector<Perm> group;
  std::vector<std::pair<int, int>> ordered; // (a, b): index of stage a <= index of stage b
  bool fast = false;
  bool rows = false;
  int h = 0;
  double combos = 1;
  std::vector<std::vector<double>> ratios;
  HalfList leftList, rightList;
  const HalfList* right = nullptr;
  size_t n1 = 0;
  std::vector<std::pair<int, int>> crossing;
  bool floorOnly = false;
  // Ranking.
  size_t nk = 0;
  std::vector<std::optional<RatioFn>> exactKey;
  double noValue = INFINITY;
  size_t keep = SIZE_MAX;
  bool capped = false;
  std::optional<FastKey> fastKey;
  RangeMin rowMin; // three stages: the third stage's table, by candidate (= position in the right list)
  // Orbits of interchangeable stages checked design by design.
  bool orbitCheck = false;
  std::vector<std::set<std::vector<int>>> members;
  // The join.
  static constexpr double eps = 1e-9; // larger than the rounding of a ratio product
  double sureLo = -INFINITY, sureHi = INFINITY, wantLoC = -INFINITY, wantHiC = INFINITY;
  size_t n = 0, rn = 0;
  int threads = 1;
  bool undecidedAny = false;
  bool arith = false;
  // Every design the window and the canonical order admit counts, one by one: no rule
  // across stages, no orbit test, no undecided freedom (not for the exhaustive reference).
  bool plainCount = false;
  // The right list's codes and tables where it is a two-stage half held in 4 bytes an entry.
  std::optional<HalfList::PairView> pairView;
  std::vector<Local> locals;
  // Set when the time limit stops the join, with each thread's share of its range done
  // (a thread that finished first keeps 1).
  std::atomic<bool> timedOut{false};
  // Set when the designs checked one by one (rules across stages) pass their share of the
  // search budget: each costs an evaluation of the rules, some fifty times a counted one,
  // and a wide ratio window hides how many there are from the estimate before the join.
  std::atomic<bool> overWalked{false};
  static constexpr double kCheckedShare = 0.02;
  double walkBudget = 0;
  std::vector<double> joinDone;

  // ---- rules ----------------------------------------------------------------------------

  // Rules into conjuncts: one-stage ones filter that stage, the ratio window joins stages,
  // the rest are checked on whole designs.
  bool splitRules();

  // Rules on constants alone decide everything at once.
  bool constantRules();

  // The budget, before any work: each stage's domain, counted before its rules filter it;
  // then each stage's candidates.
  bool filterStages();

  // Whether filtering stage b repeats filtering stage a: the same kind, the same
  // attributes (decisions over the same values, fixed values, materials) and the same
  // rules of its own, text for text. A stage's own rules and its kind's read its own
  // attributes only (a rule that reads another stage's decision, as its speed or torque
  // does downstream, is a cross-stage rule), so the candidates and the funnel are a's.
  // Not where a's filter left notes (they name the stage).
  bool sameFilter(int a, int b) const;

  // ---- interchangeable stages -------------------------------------------------------------

  // Interchangeable groups as permutations of slots; sets `stageSwapsOnly` false when a
  // group pairs single gears rather than whole stages.
  bool generators(std::vector<Perm>& gens, bool& stageSwapsOnly);

  // Whether stages a and b have the same candidate list (same attributes, same values).
  bool sameList(int a, int b) const;

  // Stages whose swaps make the orbit a multiset: identical candidate lists, and no rule
  // across stages that could tell them apart. Then designs are enumerated canonically
  // (non-decreasing candidate index along the block) instead of deduplicated.
  bool symmetry();

  // ---- rules a downstream stage's operating point carries ---------------------------------

  // Cross rules that read one downstream stage and its operating point alone are bracketed
  // per candidate over the upstream ratios its designs can have (search/Upstream.h); the
  // join asks a design only inside its bracket. Not for the exhaustive reference.
  bool downstream();

  // Per candidate of stage s, the upstream ratios a design in the window can give it: the
  // products of the stages' least and greatest ratios, cut by the window over the
  // candidate's own ratio and those downstream; empty (lo > hi) where none can.
  std::vector<std::pair<double, double>> upstreamRange(int s) const;

  // ---- the join's halves ------------------------------------------------------------------

  // The join's budget: with a two-sided ratio window it builds and walks its halves; without
  // one it visits every combination.
  bool withinBudget();

  // Whether both halves are the same block of interchangeable stages: one list serves both.
  bool sameHalves() const;

  // Meet in the middle over sorted stage ratios: left stages [0, h), right [h, k). Each
  // half is a compact list sorted by its ratio product; one two-pointer sweep joins them.
  // Three to five stages: the first two are walked row by row (the second stage's index
  // runs fastest, so the left ratio rises along a row, and a row ends where no right
  // entry the canonical order allows can still fit) against the sorted list of the
  // others, and no list of pairs is built. Otherwise both halves are built and sorted.
  bool layout();

  // For each candidate c of the right half's first stage, the ratios its entries must have
  // for some left entry to bring the product into the window: the left stages whose index
  // the canonical order bounds by c reach at most their ratio at c, the others their
  // largest; every left stage at least its least. Widened by 1e-6 of themselves (a screen:
  // entries outside could never be counted). Empty where the window or a ratio is unknown.
  std::vector<std::pair<double, double>> rightReach() const;

  std::uint32_t leftIndex(size_t le, int s) const {
    if (rows) return static_cast<std::uint32_t>(s == 0 ? le / n1 : le % n1);
    return leftList.index(le, s);
  }
  std::uint32_t rightIndex(size_t re, int s) const { return right->index(re, s - h); }
  size_t rightFloor(size_t le) const;
  const Candidate& candidate(int s, const std::uint32_t* cand) const { return candidatesOf(s)[cand[s]]; }
  Rational exactRatio(const std::uint32_t* cand) const {
    return productOf(k, [&](int s) -> const Rational& { return candidate(s, cand).ratio; });
  }
  void place(Assignment& a, int s, size_t c) const;
  void fill(Assignment& a, const std::uint32_t* cand) const {
    for (int s = 0; s < k; ++s)
      place(a, s, cand[s]);
  }

  // ---- ranking ----------------------------------------------------------------------------

  std::optional<double> direct(size_t i, const Assignment& a) const;

  // Ranking keys: `sort by`, then the objectives (minimised; maximised ones negated).
  void keysInto(const Assignment& a, double* out) const;

  void rankingKeys();

  // The first key in doubles, when it is a sum of one-stage terms and functions of the
  // ratio: a screen before the evaluator, and bounds that skip whole windows. Checked
  // against the evaluator on sample designs before it is trusted.
  void screen();

  // ---- orbits checked design by design ------------------------------------------------------

  void orbits();
  const Value& valueOf(int slot, int c) const {
    return m.slots[static_cast<size_t>(slot)].values[static_cast<size_t>(c)];
  }
  // Image of a design under a permutation: slot values moved; -1 where a value is outside
  // the target slot's domain.
  std::vector<int> image(const std::vector<int>& choice, const Perm& p) const;
  std::vector<int> stageTuple(const std::vector<int>& choice, int s) const;
  bool feasibleDesign(const std::vector<int>& choice) const;
  // Orders designs by the ratios of their stages, then by their values: the order of the
  // sorted candidate lists. An orbit is shown by its least member.
  bool less(const std::vector<int>& x, const std::vector<int>& y) const;
  // Whether a design is the least of its orbit (the one the search lists).
  bool representative(const std::vector<int>& choice) const;

  // ---- the join: kept designs -----------------------------------------------------------------

  bool lessRaw(const double* ka, const std::uint32_t* ca, const double* kb, const std::uint32_t* cb) const;
  bool full(const Local& lo) const { return keep != SIZE_MAX && lo.heap.size() >= keep; }
  double worst0(const Local& lo) const { return lo.keys[static_cast<size_t>(lo.heap.front()) * nk]; }
  static double slack(double w) { return 1e-9 * (1 + std::fabs(w)); }

  void keepHit(Local& lo, const double* keys, const std::uint32_t* cand) const;

  // Designs of the window [from, to) whose ratio is exactly inside; only entries within
  // the rounding margin of a bound are confirmed exactly.
  unsigned long long exactCount(std::uint32_t* cand, double x, size_t from, size_t to) const;

  // Whether a design that passed the window counts: the rules across stages hold, and it is
  // the least of its orbit. Counts what removes it.
  bool counts(Local& lo, Assignment& a, const std::uint32_t* cand) const;

  // One left entry against the right entries [from, to): each in the window counted (unless
  // `counted` says arithmetic did), then keyed and kept when it may rank among the best.
  void visit(Local& lo, Assignment& a, std::uint32_t* cand, double* scratch, size_t le, double x, size_t from,
             size_t to, bool counted, bool keyed = true) const;

  // The left entry's indices the canonical order compares, into lo.leftAt (read once a
  // window); then whether right entry re keeps that order.
  void leftFloors(Local& lo, size_t le) const;
  bool canonical(const Local& lo, size_t re) const;

  // The designs of a window none of which can be kept, where plainCount holds: a tight loop
  // over the right entries' codes, the window confirmed exactly only within the rounding
  // margin of its bounds.
  unsigned long long countWindow(Local& lo, std::uint32_t* cand, size_t le, double x, size_t from, size_t to) const;

  // Whether no design of the window can enter the kept ones (the window's ratios span [rlo, rhi]).
  bool bounded(const Local& lo, double partial, double rlo, double rhi) const;

  // ---- the join: walking ------------------------------------------------------------------------

  bool stopHere(int t, size_t at, size_t begin, size_t end);
  // Whether to ask about the time limit: at a loop's own interval, or after enough work inside it.
  static bool due(Walk& w, bool interval);

  // One left entry against its window of right entries [from, to).
  void joinEntry(Walk& w, size_t le, double x, size_t from, size_t to, double partial);

  // Which buckets of the right list's ratios hold an entry, a bit each: most rows' windows
  // fall between the entries, and a bit read from a small table tells so without the
  // index's search. A bucket is a run of the ratio's order keys (orderKey: monotone in the
  // ratio, about uniform in its logarithm), about a quarter of a row's window wide, at most
  // 64 per entry (a short list's table stays in the first-level cache) and 2^25 in all;
  // an entry in [lo, hi] has its bucket between theirs, so the test never misses an entry
  // (it may send a row to the search that finds none).
  struct Occupancy {
    std::uint64_t key0 = 0;
    int shift = 0;
    size_t buckets = 0;
    LargeVector<std::uint64_t> bits;
    // first[w]: the first entry whose bucket is 64 w or above (the list's size past its last
    // entry). A window's first entry is then found from its word, with no search of the list.
    LargeVector<std::uint32_t> first;
    // near[q]: whether buckets q to q + (a window's most buckets) hold an entry, for a short
    // list's row scan: one bit answers for a whole window (or more: a superset).
    std::vector<std::uint64_t> near;
    size_t bucket(double r) const {
      std::uint64_t k = orderKey(r);
      return k <= key0 ? 0 : static_cast<size_t>(std::min<std::uint64_t>((k - key0) >> shift, buckets - 1));
    }
    // The order key's base as the bits of a positive double: bucket = (bits - base) >> shift.
    std::int64_t base() const { return static_cast<std::int64_t>(key0 & ~(std::uint64_t{1} << 63)); }
    bool any(double lo, double hi) const {
      if (bits.empty() || !(lo <= hi) || lo <= 0) return true;
      return anyPositive(lo, hi);
    }
    // Where the first entry >= lo may lie: from its bucket's word's first entry, past one
    // entry for each occupied bucket of that word below lo's (each holds at least one, all
    // below lo), up to the next word's first entry. For a built table.
    std::pair<size_t, size_t> rangeOf(double lo) const {
      const size_t b = bucket(lo), w = b >> 6;
      const std::uint64_t below = bits[w] & ((std::uint64_t{1} << (b & 63)) - 1);
      return {first[w] + static_cast<size_t>(__builtin_popcountll(below)), first[w + 1]};
    }
    // The same for a built table and 0 < lo <= hi.
    bool anyPositive(double lo, double hi) const {
      // Positive ratios (the table is built only for them): their bits order them.
      std::int64_t a, b;
      std::memcpy(&a, &lo, sizeof a);
      std::memcpy(&b, &hi, sizeof b);
      const std::int64_t top = static_cast<std::int64_t>(buckets - 1);
      std::int64_t q0 = (a - base()) >> shift, q1 = (b - base()) >> shift;
      if (q1 < 0 || q0 > top) return false; // wholly below or above the list
      q0 = std::max<std::int64_t>(q0, 0);
      q1 = std::min(q1, top);
      if (q1 - q0 > 62) return true;
      size_t k0 = static_cast<size_t>(q0), k1 = static_cast<size_t>(q1);
      // The bits from k0 to k1 of two adjacent words (the table has one spare word).
      __extension__ using u128 = unsigned __int128;
      size_t w = k0 >> 6, span = k1 - k0 + 1;
      std::uint64_t v = static_cast<std::uint64_t>((static_cast<u128>(bits[w + 1]) << 64 | bits[w]) >> (k0 & 63));
      return (v & ((std::uint64_t{1} << span) - 1)) != 0;
    }
  };
  Occupancy occupancy;
  // Rows of a long right list whose windows' buckets hold an entry, gathered so that their
  // windows are found together: each window's binary search is a chain of dependent loads,
  // and several chains at once keep the core busy where one leaves it waiting.
  struct WindowBatch {
    static constexpr size_t kSize = 64;
    size_t n = 0;
    std::uint32_t j[kSize];
    double wl[kSize], wh[kSize];
    size_t from[kSize], to[kSize];
  };
  // Calls f with the right list's ratio of an entry as a function: a two-stage half's from
  // its code and two tables, inline; any other list's through it.
  template <class F> void withRightRatio(F&& f) const {
    if (pairView) {
      const HalfList::PairView v = *pairView;
      f([v](size_t e) { return v.ratio(e); });
    } else {
      f([this](size_t e) { return right->ratio(e); });
    }
  }
  double rightRatio(size_t e) const { return pairView ? pairView->ratio(e) : right->ratio(e); }
  // Each row's window [wl, wh] as right entries [from, to), for a built occupancy table.
  void locateWindows(WindowBatch& b) const;
  // Row (i, j)'s window [from, to) joined, with the kept designs' bound from the row's part.
  void joinRow(Walk& w, size_t i, size_t j, double x, size_t from, size_t to, double rowPart, double rightLeast);
  // The batch's rows of left index i joined in order, then emptied.
  void joinBatch(Walk& w, WindowBatch& b, size_t i, const double* r0, const double* r1, double rowPart,
                 double rightLeast);

  // A short right list's rows of one left index: where they end, the first j whose floor's
  // entry is past its window (the floor only rises and the window only falls along a row),
  // found by a binary search over [j, m1) with the scan's own products.
  size_t shortRowEnd(size_t j, size_t m1, double invI, const double* inv1, const double* r2, size_t fi,
                     bool floorJ) const;
  // A short list's row scan of one left index: rows [from, below) have their windows' lowest
  // buckets in the table, rows from `below` on start below it, and the row ends at `end`.
  struct ShortScan {
    size_t from = 0, below = 0, end = 0;
  };
  // The bucket of a row's lowest window bound lo1 * invI, unclamped (the scan's one product).
  std::int64_t nearBucket(double invI, double lo1) const;
  ShortScan shortScan(size_t j0, size_t end, double invI, const double* lo1) const;
  // The first row from j whose window's lowest bucket is `near` an occupied one, or m1: a
  // product, a subtraction, a shift and one bit per row. The caller tests the window exactly.
  size_t nextShortRow(size_t j, const ShortScan& sc, size_t m1, double invI, const double* lo1) const;

  void buildOccupancy();

  // Three to five stages: the first two walked row by row; the tight loop reads raw ratio
  // arrays, and the floor of a one-stage right half from flags.
  bool sweepRows(Walk& w);

  // Two halves built and sorted: one two-pointer sweep of the left list against the right.
  bool sweepHalves(Walk& w);

  // One share of the rows: slot t of all the ranks' threads (locals.size()).
  void sweep(int t);

  // The join over threads; false when it stopped (the time limit, or the designs checked one
  // by one beyond their budget).
  bool join();

  // A rank's share of the join as numbers: the stop flags, then per thread its counts, its
  // completed fraction and its kept designs (keys, candidates, heap).
  std::vector<double> packShare(int first) const;
  void unpackShare(const std::vector<double>& v, int first);

  // ---- the ranked list ----------------------------------------------------------------------

  struct Ref {
    double k0;           // the first key, compared before the rest is looked up
    std::uint32_t local; // the thread's share that holds it
    std::uint32_t id;
  };
  const double* keysOf(const Ref& x) const { return locals[x.local].keys.data() + size_t{x.id} * nk; }
  const std::uint32_t* candOf(const Ref& x) const { return locals[x.local].cand.data() + size_t{x.id} * kk; }
  bool refLess(const Ref& x, const Ref& y) const {
    if (x.k0 != y.k0) return x.k0 < y.k0;
    return lessRaw(keysOf(x), candOf(x), keysOf(y), candOf(y));
  }

  // Every kept design in order: the best `keep` of them, or all, by the first key alone (a
  // plain comparison), then each run of equal first keys by the rest (most runs are one design).
  void order(std::vector<Ref>& hits) const;

  // The threads' counts and kept designs merged, ranked, and the funnel's last steps.
  void collect();

  // The ranked designs as candidate indices and keys; the threads' shares are let go once
  // the list is made, and the stages' candidates move into it.
  std::shared_ptr<const DesignList> listing(std::vector<Ref>& hits);
};

} // namespace gbx::rt::searching
