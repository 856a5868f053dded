#include "search/Search.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <thread>
#include <unordered_set>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Deadline.h"
#include "model/StageKind.h"
#include "parallel/Numbers.h"
#include "parallel/Ranks.h"
#include "search/Conjuncts.h"
#include "search/FastKey.h"
#include "search/HalfList.h"
#include "search/RankedList.h"
#include "search/StageFilter.h"
#include "search/Upstream.h"

namespace gbx::rt {

namespace {

using ir::Op;

// ---- symmetry ---------------------------------------------------------------------------

using Perm = std::vector<int>; // slot -> slot

std::vector<Perm> closeGroup(const std::vector<Perm>& gens, size_t n) {
  Perm id(n);
  for (size_t i = 0; i < n; ++i)
    id[i] = static_cast<int>(i);
  std::vector<Perm> group = {id};
  std::set<Perm> seen = {id};
  for (size_t i = 0; i < group.size() && group.size() < 5040; ++i)
    for (const auto& g : gens) {
      Perm p(n);
      for (size_t k = 0; k < n; ++k)
        p[k] = g[static_cast<size_t>(group[i][k])];
      if (seen.insert(p).second) group.push_back(p);
    }
  return group;
}

} // namespace

// An objective's value as the ranking compares it: to 12 significant digits, so values
// equal but for the rounding of their formulas (a centre distance summed in another order)
// tie, and the documented rule orders them (stage ratios, then values).
double rankingKey(double v) {
  if (v == 0 || !std::isfinite(v)) return v;
  int e = static_cast<int>(std::floor(std::log10(std::fabs(v))));
  double scale = std::pow(10.0, 11 - e);
  double snapped = std::round(v * scale) / scale;
  return std::isfinite(snapped) ? snapped : v;
}


namespace {
// Whether a rule or an objective of the gearbox uses one of `ops`.
bool rulesOrObjectivesUse(const ir::Gearbox& g, std::initializer_list<Op> ops) {
  auto walk = [&](const ir::ExprPtr& e) { return ir::uses(e.get(), ops); };
  return std::any_of(g.rules.begin(), g.rules.end(), [&](const ir::Rule& r) { return walk(r.expr); }) ||
         std::any_of(g.objectives.begin(), g.objectives.end(), [&](const ir::Objective& o) { return walk(o.expr); });
}
} // namespace

bool needsOptimiser(const ir::Gearbox& g) { return rulesOrObjectivesUse(g, {Op::SceneOutput, Op::Relative, Op::Scatter}); }

bool needsScenes(const ir::Gearbox& g) { return rulesOrObjectivesUse(g, {Op::SceneOutput, Op::Relative}); }

bool readsScenes(const ir::Gearbox& g) { return rulesOrObjectivesUse(g, {Op::SceneOutput}); }

namespace {

// One search, phase by phase (docs/language.md): rules into conjuncts, constant rules, the
// budget and each stage's filter, interchangeable stages, the halves of the join and its
// budget, the ranking keys, the join itself, and the ranked list with its funnel. Each phase
// returns false when it ends the search (the result then says why).
class Searcher {
public:
  Searcher(const Model& model, const SearchOptions& options)
      : m(model), opt(options), ev(model), k(static_cast<int>(model.stages.size())), kk(static_cast<size_t>(k)) {}

  SearchResult run() {
    if (splitRules() && constantRules() && filterStages() && symmetry() && downstream() && layout()) {
      rankingKeys();
      orbits();
      if (join()) collect();
    }
    return std::move(res);
  }

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
  void unshare() {
    for (size_t s = 0; s < stages.size(); ++s)
      if (source[s] != s) {
        stages[s].candidates = stages[source[s]].candidates;
        source[s] = s;
      }
  }
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
  bool splitRules() {
    for (const auto& r : m.gearbox.rules) {
      std::vector<const ir::Expr*> parts;
      if (r.expr) split(*r.expr, parts);
      for (const auto* p : parts) {
        Conjunct c;
        c.expr = p;
        c.text = parts.size() == 1 ? r.text : ruleText(*p);
        dependencies(m, *p, c);
        if (!r.scope.empty() && c.stages.empty()) c.stages.insert(m.stageIndex(r.scope));
        conjuncts.push_back(std::move(c));
      }
    }
    local.resize(kk);
    for (const auto& c : conjuncts) {
      if (c.unsupported) {
        if (opt.deferDynamics)
          res.deferred.push_back(c.text);
        else
          res.errors.push_back(
              fmt::format("rule `{}` needs results the search does not compute (scenes, splits, baselines)", c.text));
        continue;
      }
      if (asWindow(*c.expr, window)) {
        windowTexts.push_back(c.text);
        // One stage: its ratio is the gearbox's, so the window is a cheap rule of the
        // stage's filter, asked before the stage's ratings and credited before them.
        if (k == 1) local[0].push_back(&c);
        continue;
      }
      if (c.stages.size() == 1)
        local[static_cast<size_t>(*c.stages.begin())].push_back(&c);
      else if (c.stages.empty())
        global.push_back(&c);
      else
        cross.push_back(&c);
    }
    // A strength rule runs only on the candidates the cheaper rules kept; the funnel then
    // says how many it removed.
    auto cheapFirst = [](const Conjunct* a, const Conjunct* b) { return !a->strength && b->strength; };
    for (auto& l : local)
      std::stable_sort(l.begin(), l.end(), cheapFirst);
    std::stable_sort(cross.begin(), cross.end(), cheapFirst);
    for (const auto& o : m.gearbox.objectives) {
      Conjunct c;
      if (o.expr) dependencies(m, *o.expr, c);
      if (c.unsupported && !opt.deferDynamics)
        res.errors.push_back(
            fmt::format("objective `{}` needs results the search does not compute (scenes, baselines)", o.text));
    }
    if (!res.errors.empty()) return false;
    if (window.lo || window.hi) res.window = window.str();
    return true;
  }

  // Rules on constants alone decide everything at once.
  bool constantRules() {
    Assignment none(m);
    for (const auto* c : global) {
      Truth t = truthOf(ev.eval(*c->expr, none));
      res.funnel.push_back({c->text, "", 1, t == Truth::True ? 0.0 : 1.0});
      if (t != Truth::True) return false;
    }
    return true;
  }

  // The budget, before any work: each stage's domain, counted before its rules filter it;
  // then each stage's candidates.
  bool filterStages() {
    for (int s = 0; s < k; ++s) {
      double domain = stageDomain(m, s);
      if (domain > opt.maxDesigns) {
        res.errors.push_back(fmt::format("stage `{}` has {:.3g} candidates ({}), beyond the search budget of {:.3g} (--max-designs); "
                                         "narrow these ranges, or raise --max-designs",
                                         m.stages[static_cast<size_t>(s)].ir->name, domain, stageRanges(m, s), opt.maxDesigns));
        return false;
      }
    }
    for (int s = 0; s < k; ++s) {
      // A stage like an earlier one in every attribute and rule of its own passes the same
      // candidates (three or four equal stages filter once).
      int same = -1;
      for (int e = 0; e < s && same < 0; ++e)
        if (sameFilter(e, s)) same = e;
      if (same >= 0) {
        // Its candidates are read from that stage's list, not copied.
        source.push_back(source[static_cast<size_t>(same)]);
        stages.emplace_back();
        stages.back().funnel = stages[static_cast<size_t>(same)].funnel;
        for (auto& f : stages.back().funnel) {
          f.scope = m.stages[static_cast<size_t>(s)].ir->name;
          res.funnel.push_back(f);
        }
        continue;
      }
      source.push_back(static_cast<size_t>(s));
      stages.push_back(filterStage(ev, s, local[static_cast<size_t>(s)], opt.jobs, !opt.exhaustive));
      if (stages.back().timedOutAt >= 0) {
        res.errors.push_back(timeLimitMessage(fmt::format("filtering the candidates of stage `{}`", m.stages[static_cast<size_t>(s)].ir->name),
                                              stages.back().timedOutAt, Deadline::seconds(), stageDomain(m, s)));
        return false;
      }
      for (auto& f : stages.back().funnel)
        res.funnel.push_back(f);
      for (auto& note : stages.back().notes)
        res.notes.push_back(note);
    }
    return true;
  }

  // Whether filtering stage b repeats filtering stage a: the same kind, the same
  // attributes (decisions over the same values, fixed values, materials) and the same
  // rules of its own, text for text. A stage's own rules and its kind's read its own
  // attributes only (a rule that reads another stage's decision, as its speed or torque
  // does downstream, is a cross-stage rule), so the candidates and the funnel are a's.
  // Not where a's filter left notes (they name the stage).
  bool sameFilter(int a, int b) const {
    const ir::Stage &sa = *m.stages[static_cast<size_t>(a)].ir, &sb = *m.stages[static_cast<size_t>(b)].ir;
    if (sa.kind != sb.kind || sa.gears != sb.gears || sa.presets != sb.presets || !stages[static_cast<size_t>(a)].notes.empty())
      return false;
    const auto &la = local[static_cast<size_t>(a)], &lb = local[static_cast<size_t>(b)];
    if (la.size() != lb.size() || sa.attributes.size() != sb.attributes.size()) return false;
    for (size_t i = 0; i < la.size(); ++i)
      if (la[i]->text != lb[i]->text || la[i]->freedom != lb[i]->freedom) return false;
    auto num = [](const std::optional<units::Number>& x, const std::optional<units::Number>& y) {
      return x.has_value() == y.has_value() && (!x || (x->isExact() == y->isExact() && x->compare(*y) == 0));
    };
    for (const ir::Attribute& x : sa.attributes) {
      const ir::Attribute* y = sb.find(x.name);
      if (!y || y->role != x.role || y->key != x.key || y->gear != x.gear || y->integer != x.integer || y->symbol != x.symbol ||
          y->choice != x.choice || y->sceneRef != x.sceneRef || !num(x.lo, y->lo) || !num(x.hi, y->hi) ||
          x.members.size() != y->members.size() || !x.value != !y->value || (x.value && ir::print(*x.value) != ir::print(*y->value)))
        return false;
      for (size_t i = 0; i < x.members.size(); ++i)
        if (x.members[i].isExact() != y->members[i].isExact() || x.members[i].compare(y->members[i]) != 0) return false;
    }
    // The decisions: the same attributes over the same values, slot for slot.
    const auto &qa = m.stages[static_cast<size_t>(a)].slots, &qb = m.stages[static_cast<size_t>(b)].slots;
    if (qa.size() != qb.size()) return false;
    for (size_t i = 0; i < qa.size(); ++i) {
      const Slot &x = m.slots[static_cast<size_t>(qa[i])], &y = m.slots[static_cast<size_t>(qb[i])];
      if (x.attr != y.attr || x.values.size() != y.values.size()) return false;
      for (size_t v = 0; v < x.values.size(); ++v)
        if (!x.values[v].exact || !y.values[v].exact || *x.values[v].exact != *y.values[v].exact) return false;
    }
    return true;
  }

  // ---- interchangeable stages -------------------------------------------------------------

  // Interchangeable groups as permutations of slots; sets `stageSwapsOnly` false when a
  // group pairs single gears rather than whole stages.
  bool generators(std::vector<Perm>& gens, bool& stageSwapsOnly) {
    size_t nslots = m.slots.size();
    for (const auto& g : m.gearbox.interchangeable) {
      for (size_t i = 0; i + 1 < g.size(); ++i) {
        Perm p(nslots);
        for (size_t q = 0; q < nslots; ++q)
          p[q] = static_cast<int>(q);
        const std::string &x = g[i], &y = g[i + 1];
        auto sx = x.substr(0, x.find('.')), sy = y.substr(0, y.find('.'));
        int a = m.stageIndex(sx), b = m.stageIndex(sy);
        // `upper.pinion, lower.pinion` pairs one gear's decisions; `upper, lower` whole stages.
        auto gearOf = [&](const std::string& path, int st) {
          auto dot = path.find('.');
          return dot == std::string::npos ? -2 : cat::gearIndex(cat::kindSpec(m.info(st).ir->kind), path.substr(dot + 1));
        };
        int gx = gearOf(x, a), gy = gearOf(y, b);
        if (gx != -2) stageSwapsOnly = false;
        for (int sa : m.stages[static_cast<size_t>(a)].slots) {
          const Slot& slot = m.slots[static_cast<size_t>(sa)];
          if (slot.shaft.setting) continue; // a shaft's searched setting: no stage's own
          if (gx != -2 && slot.gear != gx) continue;
          int sb = m.slotOf(b, gx == -2 ? slot.gear : gy, slot.key);
          if (sb < 0) {
            std::string px = x.find('.') == std::string::npos ? "" : x.substr(x.find('.') + 1) + ".";
            std::string py = y.find('.') == std::string::npos ? "" : y.substr(y.find('.') + 1) + ".";
            res.errors.push_back(fmt::format("`interchangeable {}, {}`: `{}` has no decision `{}` to match `{}.{}`", x, y,
                                             sy, py + slot.attr.substr(px.size()), sx, slot.attr));
            continue;
          }
          p[static_cast<size_t>(sa)] = sb;
          p[static_cast<size_t>(sb)] = sa;
        }
        gens.push_back(p);
      }
    }
    return res.errors.empty();
  }

  // Whether stages a and b have the same candidate list (same attributes, same values).
  bool sameList(int a, int b) const {
    const auto &ca = candidatesOf(a), &cb = candidatesOf(b);
    if (ca.size() != cb.size()) return false;
    const auto &sa = m.stages[static_cast<size_t>(a)].slots, &sb = m.stages[static_cast<size_t>(b)].slots;
    if (sa.size() != sb.size()) return false;
    for (size_t i = 0; i < sa.size(); ++i)
      if (m.slots[static_cast<size_t>(sa[i])].attr != m.slots[static_cast<size_t>(sb[i])].attr) return false;
    for (size_t i = 0; i < ca.size(); ++i)
      for (size_t j = 0; j < sa.size(); ++j) {
        const Value& va = m.slots[static_cast<size_t>(sa[j])].values[static_cast<size_t>(ca[i].idx[j])];
        const Value& vb = m.slots[static_cast<size_t>(sb[j])].values[static_cast<size_t>(cb[i].idx[j])];
        if (!va.exact || !vb.exact || *va.exact != *vb.exact) return false;
      }
    return true;
  }

  // Stages whose swaps make the orbit a multiset: identical candidate lists, and no rule
  // across stages that could tell them apart. Then designs are enumerated canonically
  // (non-decreasing candidate index along the block) instead of deduplicated.
  bool symmetry() {
    std::vector<Perm> gens;
    bool stageSwapsOnly = true;
    if (!generators(gens, stageSwapsOnly)) return false;
    group = closeGroup(gens, m.slots.size());
    fast = stageSwapsOnly && cross.empty();
    if (fast && group.size() > 1) {
      for (const auto& gp : m.gearbox.interchangeable) {
        // Links between neighbours in stage order, whatever order the group is written in
        // (`c, a, b` links a-b and b-c: a chain, so each orbit is enumerated once).
        std::vector<int> inGroup;
        for (const auto& name : gp) inGroup.push_back(m.stageIndex(name));
        std::sort(inGroup.begin(), inGroup.end());
        for (size_t i = 0; i + 1 < inGroup.size(); ++i) {
          if (!sameList(inGroup[i], inGroup[i + 1])) fast = false;
          ordered.emplace_back(inGroup[i], inGroup[i + 1]);
        }
      }
    }
    if (!fast) ordered.clear();
    return true;
  }

  // ---- rules a downstream stage's operating point carries ---------------------------------

  // Cross rules that read one downstream stage and its operating point alone are bracketed
  // per candidate over the upstream ratios its designs can have (search/Upstream.h); the
  // join asks a design only inside its bracket. Not for the exhaustive reference.
  bool downstream() {
    crossAt.assign(cross.size(), {-1, -1});
    if (opt.exhaustive || k < 2) return true;
    for (int s = 0; s < k; ++s)
      if (candidatesOf(s).empty() || !(candidatesOf(s).front().r > 0)) return true;
    for (int s = 1; s < k; ++s) {
      if (!m.stages[static_cast<size_t>(s)].selfContained) continue;
      std::vector<const Conjunct*> rules;
      std::vector<size_t> which;
      for (size_t c = 0; c < cross.size(); ++c) {
        if (*cross[c]->stages.rbegin() == s && readsOwnStage(*cross[c]->expr, s)) {
          rules.push_back(cross[c]);
          which.push_back(c);
        }
      }
      if (rules.empty()) continue;
      auto placeOne = [this, s](Assignment& a, size_t c) { place(a, s, c); };
      if (!m.stages[static_cast<size_t>(s)].freedoms.empty()) unshare(); // bracketing narrows their freedoms
      upstream.push_back(bracketStage(ev, s, stages[static_cast<size_t>(s)].candidates, rules, local[static_cast<size_t>(s)],
                                      upstreamRange(s), placeOne, opt.jobs));
      for (size_t r = 0; r < which.size(); ++r)
        crossAt[which[r]] = {static_cast<int>(upstream.size()) - 1, static_cast<int>(r)};
    }
    return true;
  }

  // Per candidate of stage s, the upstream ratios a design in the window can give it: the
  // products of the stages' least and greatest ratios, cut by the window over the
  // candidate's own ratio and those downstream; empty (lo > hi) where none can.
  std::vector<std::pair<double, double>> upstreamRange(int s) const {
    double upLo = 1, upHi = 1, downLo = 1, downHi = 1;
    for (int j = 0; j < k; ++j) {
      const auto& c = candidatesOf(j);
      if (j == s) continue;
      (j < s ? upLo : downLo) *= c.front().r;
      (j < s ? upHi : downHi) *= c.back().r;
    }
    const double wlo = window.lo ? window.lo->toDouble() : 0, whi = window.hi ? window.hi->toDouble() : INFINITY;
    std::vector<std::pair<double, double>> out;
    for (const auto& c : candidatesOf(s))
      out.emplace_back(std::max(upLo, wlo / (c.r * downHi)) * (1 - 1e-9), std::min(upHi, whi / (c.r * downLo)) * (1 + 1e-9));
    return out;
  }

  // ---- the join's halves ------------------------------------------------------------------

  // The join's budget: with a two-sided ratio window it builds and walks its halves; without
  // one it visits every combination.
  bool withinBudget() {
    for (int s = 0; s < k; ++s)
      combos *= static_cast<double>(candidatesOf(s).size());
    double left = 1, rightSize = 1;
    for (int s = 0; s < k; ++s)
      (s < h ? left : rightSize) *= static_cast<double>(candidatesOf(s).size());
    bool windowed = window.lo && window.hi && k > 1;
    double walked = windowed ? std::max(left, rightSize) : combos;
    if (walked <= opt.maxDesigns) return true;
    std::vector<std::string> lists;
    for (int s = 0; s < k; ++s)
      lists.push_back(fmt::format("`{}` {} candidates ({})", m.stages[static_cast<size_t>(s)].ir->name,
                                  candidatesOf(s).size(), stageRanges(m, s)));
    res.errors.push_back(fmt::format(
        "the search space is {:.3g} designs ({}){}, beyond the search budget of {:.3g} (--max-designs); narrow these ranges, "
        "{}or raise --max-designs",
        combos, fmt::join(lists, "; "), windowed ? fmt::format(", of which the join walks {:.3g}", walked) : "",
        opt.maxDesigns, windowed ? "" : "bound the ratio (`require ratio == … +- …`), "));
    return false;
  }

  // Whether both halves are the same block of interchangeable stages: one list serves both.
  bool sameHalves() const {
    std::vector<int> block(kk);
    for (int s = 0; s < k; ++s)
      block[static_cast<size_t>(s)] = s;
    std::function<int(int)> root = [&](int s) {
      return block[static_cast<size_t>(s)] == s ? s : root(block[static_cast<size_t>(s)]);
    };
    for (const auto& [a, b] : ordered)
      block[static_cast<size_t>(root(b))] = root(a);
    bool same = !rows && fast && h == k - h && h > 0;
    for (int a = 0; same && a < h; ++a)
      same = root(a) == root(a + h) && sameList(a, a + h);
    auto has = [&](int x, int y) { return std::find(ordered.begin(), ordered.end(), std::make_pair(x, y)) != ordered.end(); };
    for (const auto& [a, b] : ordered) {
      if (!same) break;
      if (b < h && !has(a + h, b + h)) same = false;
      if (a >= h && !has(a - h, b - h)) same = false;
    }
    return same;
  }

  // Meet in the middle over sorted stage ratios: left stages [0, h), right [h, k). Each
  // half is a compact list sorted by its ratio product; one two-pointer sweep joins them.
  // Three to five stages: the first two are walked row by row (the second stage's index
  // runs fastest, so the left ratio rises along a row, and a row ends where no right
  // entry the canonical order allows can still fit) against the sorted list of the
  // others, and no list of pairs is built. Otherwise both halves are built and sorted.
  bool layout() {
    rows = k >= 3 && k <= 5;
    h = rows ? 2 : k / 2;
    if (!withinBudget()) return false;
    bool same = sameHalves();
    ratios.resize(kk);
    for (int s = 0; s < k; ++s)
      for (const auto& c : candidatesOf(s))
        ratios[static_cast<size_t>(s)].push_back(c.r);
    if (!rows) leftList = HalfList::build(ratios, ordered, 0, h);
    std::vector<std::pair<double, double>> reach = rightReach();
    if (!same) rightList = HalfList::build(ratios, ordered, h, k, reach.empty() ? nullptr : &reach);
    for (const HalfList* H : {&leftList, &rightList})
      if (!H->error().empty()) res.errors.push_back(H->error());
    if (!res.errors.empty()) return false;
    right = same ? &leftList : &rightList;
    // Rows: left entries are (i, j) packed as i * n1 + j.
    n1 = rows ? candidatesOf(1).size() : 0;
    // Links of the canonical order from a left stage to a right one: a floor on a one-stage
    // right half (its entries are its sorted candidates), a test per entry otherwise.
    for (const auto& [sa, sb] : ordered)
      if (sa < h && sb >= h) crossing.emplace_back(sa, sb);
    floorOnly = right->width() <= 1;
    return true;
  }

  // For each candidate c of the right half's first stage, the ratios its entries must have
  // for some left entry to bring the product into the window: the left stages whose index
  // the canonical order bounds by c reach at most their ratio at c, the others their
  // largest; every left stage at least its least. Widened by 1e-6 of themselves (a screen:
  // entries outside could never be counted). Empty where the window or a ratio is unknown.
  std::vector<std::pair<double, double>> rightReach() const {
    if (!rows || k - h < 2 || !window.lo || !window.hi) return {};
    const double wlo = window.lo->toDouble(), whi = window.hi->toDouble();
    if (!(wlo > 0) || !std::isfinite(whi)) return {};
    for (int s = 0; s < k; ++s) {
      const auto& r = ratios[static_cast<size_t>(s)];
      if (r.empty() || !(r.front() > 0) || !std::isfinite(r.back())) return {};
    }
    // bounded[t]: the left stage's index is at most the first right stage's (directly or
    // through another left stage).
    std::vector<bool> bounded(static_cast<size_t>(h), false);
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [sa, sb] : ordered)
        if (sa < h && !bounded[static_cast<size_t>(sa)] && (sb == h || (sb < h && bounded[static_cast<size_t>(sb)])))
          bounded[static_cast<size_t>(sa)] = changed = true;
    }
    double least = 1;
    for (int t = 0; t < h; ++t) least *= ratios[static_cast<size_t>(t)].front();
    const auto& first = ratios[static_cast<size_t>(h)];
    std::vector<std::pair<double, double>> reach(first.size());
    for (size_t c = 0; c < first.size(); ++c) {
      double most = 1;
      for (int t = 0; t < h; ++t) {
        const auto& r = ratios[static_cast<size_t>(t)];
        most *= bounded[static_cast<size_t>(t)] ? r[std::min(c, r.size() - 1)] : r.back();
      }
      reach[c] = {wlo / most * (1 - 1e-6), whi / least * (1 + 1e-6)};
    }
    return reach;
  }

  std::uint32_t leftIndex(size_t le, int s) const {
    if (rows) return static_cast<std::uint32_t>(s == 0 ? le / n1 : le % n1);
    return leftList.index(le, s);
  }
  std::uint32_t rightIndex(size_t re, int s) const { return right->index(re, s - h); }
  size_t rightFloor(size_t le) const {
    size_t lo = 0;
    if (floorOnly)
      for (const auto& [sa, sb] : crossing)
        lo = std::max<size_t>(lo, leftIndex(le, sa));
    return lo;
  }
  const Candidate& candidate(int s, const std::uint32_t* cand) const { return candidatesOf(s)[cand[s]]; }
  Rational exactRatio(const std::uint32_t* cand) const {
    return productOf(k, [&](int s) -> const Rational& { return candidate(s, cand).ratio; });
  }
  void place(Assignment& a, int s, size_t c) const {
    const StageInfo& info = m.stages[static_cast<size_t>(s)];
    const Candidate& cand = candidatesOf(s)[c];
    for (size_t j = 0; j < info.slots.size(); ++j)
      a.choice[static_cast<size_t>(info.slots[j])] = cand.idx[j];
    for (size_t j = 0; j < info.freedoms.size(); ++j) {
      const auto f = static_cast<size_t>(info.freedoms[j]);
      a.box[f] = cand.box.empty() ? std::pair{m.freedoms[f].lo, m.freedoms[f].hi} : cand.box[j];
    }
  }
  void fill(Assignment& a, const std::uint32_t* cand) const {
    for (int s = 0; s < k; ++s)
      place(a, s, cand[s]);
  }

  // ---- ranking ----------------------------------------------------------------------------

  std::optional<double> direct(size_t i, const Assignment& a) const {
    if (!a.ratio || !exactKey[i]) return std::nullopt;
    auto q = exactKey[i]->exactAt(*a.ratio);
    if (!q) return std::nullopt;
    return q->toDouble();
  }

  // Ranking keys: `sort by`, then the objectives (minimised; maximised ones negated).
  void keysInto(const Assignment& a, double* out) const {
    size_t i = 0;
    if (opt.sortBy) {
      auto d = direct(i, a);
      Value v = d ? Value::number(*d) : ev.eval(*opt.sortBy, a);
      out[i++] = v.isNumber() && !std::isnan(v.lo) ? rankingKey(v.lo) : noValue;
    }
    if (opt.deferDynamics) return; // ranked by the optimiser
    for (const auto& o : m.gearbox.objectives) {
      auto d = direct(i, a);
      Value v = d ? Value::number(*d) : o.expr ? ev.eval(*o.expr, a) : Value::invalid();
      // Over a freedom the best attainable value counts: the design may choose it.
      double x = o.minimize ? v.lo : -v.hi;
      out[i++] = v.isNumber() && !std::isnan(x) ? rankingKey(x) : noValue; // NaN would break the order
    }
  }

  void rankingKeys() {
    nk = (opt.sortBy ? 1 : 0) + (opt.deferDynamics ? 0 : m.gearbox.objectives.size());
    // A key that reads only the gearbox ratio is computed from the exact ratio directly (the
    // same rational the evaluator would reach, without its per-step reductions).
    if (opt.sortBy) exactKey.push_back(RatioFn::compile(*opt.sortBy));
    if (!opt.deferDynamics)
      for (const auto& o : m.gearbox.objectives)
        exactKey.push_back(o.expr ? RatioFn::compile(*o.expr) : std::nullopt);
    // A key with no value ranks last; over freedoms, where the value at the design's decided
    // point may exist though none exists over the whole box, it ranks first: the key is a lower
    // bound, and the design is decided before any that could pass it.
    noValue = m.freedoms.empty() ? INFINITY : -INFINITY;
    // At most one design more than opt.maxKept is kept, whatever `top` says: finding more is
    // a failure, not memory spent.
    const size_t top = opt.top ? static_cast<size_t>(std::max(0LL, *opt.top)) : SIZE_MAX;
    capped = opt.top && top > opt.maxKept;
    keep = capped ? opt.maxKept + 1 : top;
    if (!opt.exhaustive && nk > 0 && keep > 0 && keep != SIZE_MAX && k > 0) screen();
    if (fastKey && k == 3 && fastKey->table(2)) rowMin = RangeMin(*fastKey->table(2));
  }

  // The first key in doubles, when it is a sum of one-stage terms and functions of the
  // ratio: a screen before the evaluator, and bounds that skip whole windows. Checked
  // against the evaluator on sample designs before it is trusted.
  void screen() {
    const ir::Expr* e = opt.sortBy ? opt.sortBy : m.gearbox.objectives[0].expr.get();
    bool maximise = !opt.sortBy && !m.gearbox.objectives[0].minimize;
    std::vector<size_t> sizes;
    for (int s = 0; s < k; ++s)
      sizes.push_back(candidatesOf(s).size());
    bool any = std::all_of(sizes.begin(), sizes.end(), [](size_t x) { return x > 0; });
    auto reads = [&](const ir::Expr& x) {
      Conjunct c;
      dependencies(m, x, c);
      return FastKey::Reads{c.stages, c.freedom || c.unsupported};
    };
    auto placeOne = [this](Assignment& a, int s, size_t c) { place(a, s, c); };
    if (e && any) fastKey = FastKey::build(ev, *e, maximise, sizes, reads, placeOne);
    std::vector<double> want(nk);
    std::vector<std::uint32_t> cand(kk);
    Assignment a(m);
    for (std::uint64_t t = 0; fastKey && t < 16; ++t) {
      double r = 1;
      for (int s = 0; s < k; ++s) {
        cand[static_cast<size_t>(s)] = static_cast<std::uint32_t>(
            (t * 2654435761u + static_cast<std::uint64_t>(s) * 40503u) % sizes[static_cast<size_t>(s)]);
        r *= candidate(s, cand.data()).r;
      }
      fill(a, cand.data());
      a.ratio = exactRatio(cand.data());
      keysInto(a, want.data());
      double got = fastKey->value(cand.data(), r);
      bool same = std::isinf(want[0]) ? got == want[0] : std::fabs(got - want[0]) <= 1e-10 * (1 + std::fabs(want[0]));
      if (!same) fastKey.reset();
    }
  }

  // ---- orbits checked design by design ------------------------------------------------------

  void orbits() {
    orbitCheck = !fast && group.size() > 1;
    members.resize(kk);
    if (orbitCheck)
      for (int s = 0; s < k; ++s)
        for (const auto& c : candidatesOf(s))
          members[static_cast<size_t>(s)].insert(c.idx);
  }
  const Value& valueOf(int slot, int c) const { return m.slots[static_cast<size_t>(slot)].values[static_cast<size_t>(c)]; }
  // Image of a design under a permutation: slot values moved; -1 where a value is outside
  // the target slot's domain.
  std::vector<int> image(const std::vector<int>& choice, const Perm& p) const {
    std::vector<int> out(choice.size(), -1);
    for (size_t sl = 0; sl < choice.size(); ++sl) {
      int target = p[sl];
      const Value& v = valueOf(static_cast<int>(sl), choice[sl]);
      const auto& dom = m.slots[static_cast<size_t>(target)].values;
      for (size_t i = 0; i < dom.size(); ++i)
        if (dom[i].exact && v.exact && *dom[i].exact == *v.exact) out[static_cast<size_t>(target)] = static_cast<int>(i);
    }
    return out;
  }
  std::vector<int> stageTuple(const std::vector<int>& choice, int s) const {
    std::vector<int> t;
    for (int sl : m.stages[static_cast<size_t>(s)].slots)
      t.push_back(choice[static_cast<size_t>(sl)]);
    return t;
  }
  bool feasibleDesign(const std::vector<int>& choice) const {
    for (int c : choice)
      if (c < 0) return false;
    for (int s = 0; s < k; ++s)
      if (!members[static_cast<size_t>(s)].count(stageTuple(choice, s))) return false;
    Assignment a(m);
    a.choice = choice;
    Value r = ev.gearboxQuantity(Q::Ratio, a);
    if (!r.exact || !window.contains(*r.exact)) return false;
    for (const auto* c : cross)
      if (truthOf(ev.eval(*c->expr, a)) == Truth::False) return false;
    return true;
  }
  // Orders designs by the ratios of their stages, then by their values: the order of the
  // sorted candidate lists. An orbit is shown by its least member.
  bool less(const std::vector<int>& x, const std::vector<int>& y) const {
    Assignment ax(m), ay(m);
    ax.choice = x;
    ay.choice = y;
    for (int s = 0; s < k; ++s) {
      Value rx = ev.derived(s, Q::Ratio, ax), ry = ev.derived(s, Q::Ratio, ay);
      if (rx.exact && ry.exact && *rx.exact != *ry.exact) return *rx.exact < *ry.exact;
      for (int sl : m.stages[static_cast<size_t>(s)].slots) {
        const Value &vx = valueOf(sl, x[static_cast<size_t>(sl)]), &vy = valueOf(sl, y[static_cast<size_t>(sl)]);
        if (vx.lo != vy.lo) return vx.lo < vy.lo;
      }
    }
    return false;
  }
  // Whether a design is the least of its orbit (the one the search lists).
  bool representative(const std::vector<int>& choice) const {
    for (size_t g = 1; g < group.size(); ++g) {
      auto img = image(choice, group[g]);
      if (img != choice && feasibleDesign(img) && less(img, choice)) return false;
    }
    return true;
  }

  // ---- the join: kept designs -----------------------------------------------------------------

  bool lessRaw(const double* ka, const std::uint32_t* ca, const double* kb, const std::uint32_t* cb) const {
    for (size_t i = 0; i < nk; ++i)
      if (ka[i] != kb[i]) return ka[i] < kb[i];
    for (size_t s = 0; s < kk; ++s)
      if (ca[s] != cb[s]) return ca[s] < cb[s];
    return false;
  }
  bool full(const Local& lo) const { return keep != SIZE_MAX && lo.heap.size() >= keep; }
  double worst0(const Local& lo) const { return lo.keys[static_cast<size_t>(lo.heap.front()) * nk]; }
  static double slack(double w) { return 1e-9 * (1 + std::fabs(w)); }

  void keepHit(Local& lo, const double* keys, const std::uint32_t* cand) const {
    auto cmp = [&](std::uint32_t x, std::uint32_t y) {
      return lessRaw(lo.keys.data() + x * nk, lo.cand.data() + x * kk, lo.keys.data() + y * nk, lo.cand.data() + y * kk);
    };
    if (keep == SIZE_MAX && lo.heap.size() >= opt.maxKept) {
      lo.overKept = true;  // memory stays bounded; the caller says how many were found
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

  // Designs of the window [from, to) whose ratio is exactly inside; only entries within
  // the rounding margin of a bound are confirmed exactly.
  unsigned long long exactCount(std::uint32_t* cand, double x, size_t from, size_t to) const {
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
  bool counts(Local& lo, Assignment& a, const std::uint32_t* cand) const {
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

  // One left entry against the right entries [from, to): each in the window counted (unless
  // `counted` says arithmetic did), then keyed and kept when it may rank among the best.
  void visit(Local& lo, Assignment& a, std::uint32_t* cand, double* scratch, size_t le, double x, size_t from, size_t to,
             bool counted, bool keyed = true) const {
    // The left indices the canonical order compares, read once.
    const bool checkCanon = !floorOnly && !crossing.empty();
    auto& leftAt = lo.leftAt;
    leftAt.resize(crossing.size());
    for (size_t c = 0; checkCanon && c < crossing.size(); ++c)
      leftAt[c] = leftIndex(le, crossing[c].first);
    for (size_t re = from; re < to && re < rn; ++re) {
      if (checkCanon) {
        bool canonical = true;
        for (size_t c = 0; c < crossing.size() && canonical; ++c)
          canonical = leftAt[c] <= rightIndex(re, crossing[c].second);
        if (!canonical) continue;
      }
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
  bool bounded(const Local& lo, double partial, double rlo, double rhi) const {
    if (!fastKey || !full(lo)) return false;
    double w = worst0(lo);
    double lb = partial + fastKey->ratioLower(rlo * (1 - 1e-12), rhi * (1 + 1e-12)) - fastKey->rounding();
    return lb > w + slack(w);
  }

  // ---- the join: walking ------------------------------------------------------------------------

  bool stopHere(int t, size_t at, size_t begin, size_t end) {
    if (!Deadline::expired() && !timedOut.load(std::memory_order_relaxed) && !overWalked.load(std::memory_order_relaxed))
      return false;
    if (!overWalked) timedOut = true;
    joinDone[static_cast<size_t>(t)] = static_cast<double>(at - begin) / static_cast<double>(std::max<size_t>(1, end - begin));
    return true;
  }
  // Whether to ask about the time limit: at a loop's own interval, or after enough work inside it.
  static bool due(Walk& w, bool interval) {
    if (!interval && w.sinceCheck <= (1u << 16)) return false;
    w.sinceCheck = 0;
    return true;
  }

  // One left entry against its window of right entries [from, to).
  void joinEntry(Walk& w, size_t le, double x, size_t from, size_t to, double partial) {
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
      bool keyed = keep > 0 && !bounded(lo, partial, x * right->ratio(from), x * right->ratio(to - 1));
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

  // How many rows ahead the long right list's index and entries are fetched: a row takes
  // about as long as a load from memory, so the index must arrive before the entries'
  // fetch reads it.
  static constexpr size_t kIndexAhead = 2, kEntriesAhead = 1;

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
    std::vector<std::uint64_t> bits;
    size_t bucket(double r) const {
      std::uint64_t k = orderKey(r);
      return k <= key0 ? 0 : static_cast<size_t>(std::min<std::uint64_t>((k - key0) >> shift, buckets - 1));
    }
    bool any(double lo, double hi) const {
      if (bits.empty() || !(lo <= hi) || lo <= 0) return true;
      return anyPositive(lo, hi);
    }
    // The same for a built table and 0 < lo <= hi.
    bool anyPositive(double lo, double hi) const {
      // Positive ratios (the table is built only for them): their bits order them.
      std::int64_t a, b;
      std::memcpy(&a, &lo, sizeof a);
      std::memcpy(&b, &hi, sizeof b);
      const std::int64_t top = static_cast<std::int64_t>(buckets - 1), base = static_cast<std::int64_t>(key0 & ~(std::uint64_t{1} << 63));
      std::int64_t q0 = (a - base) >> shift, q1 = (b - base) >> shift;
      if (q1 < 0 || q0 > top) return false;  // wholly below or above the list
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

  // A short right list's rows of one left index i, from j on: the first j whose window may
  // hold an entry (the occupancy table), or m1 where the row ends (its floor's entry past
  // the window). Only products, one load and a bit test per row; the table is built (so
  // the windows are positive and finite) and the rows' floors are given as fi and floorJ.
  size_t nextShortRow(size_t j, size_t m1, double invI, const double* inv1, const double* r2, size_t fi, bool floorJ, size_t& scanned) const {
    const size_t start = j;
    for (; j < m1; ++j) {
      double inv = invI * inv1[j];
      double wh = wantHiC * inv;
      size_t floor = std::max(fi, floorJ ? j : 0);
      if (floor >= rn || r2[floor] > wh) {
        j = m1;
        break;
      }
      if (occupancy.anyPositive(wantLoC * inv, wh)) break;
    }
    scanned += j - start;
    return j;
  }

  void buildOccupancy() {
    if (!rows || right->width() < 1 || rn == 0 || !(wantLoC > 0) || !std::isfinite(wantHiC)) return;
    const double lo = right->ratio(0), hi = right->ratio(rn - 1);
    if (!(lo > 0) || !(hi >= lo) || !std::isfinite(hi)) return;
    // A quarter of a window's keys per bucket (the window measured where the keys are
    // densest, at the list's largest ratio), and no more buckets than the caps allow.
    std::uint64_t k0 = orderKey(lo), span = orderKey(hi) - k0;
    std::uint64_t window = orderKey(hi * (wantHiC / wantLoC)) - orderKey(hi);
    int shift = 0;
    while (shift < 62 && (std::uint64_t{1} << (shift + 1)) <= window / 4) ++shift;
    const std::uint64_t most = std::min<std::uint64_t>(std::uint64_t{64} * rn, std::uint64_t{1} << 25);
    while (shift < 63 && (span >> shift) + 1 > most) ++shift;
    occupancy.key0 = k0;
    occupancy.shift = shift;
    occupancy.buckets = static_cast<size_t>(span >> shift) + 1;
    occupancy.bits.assign((occupancy.buckets + 63) / 64 + 1, 0);  // a spare word: any() reads two
    for (size_t e = 0; e < rn; ++e) {
      size_t kb = occupancy.bucket(right->ratio(e));
      occupancy.bits[kb >> 6] |= std::uint64_t{1} << (kb & 63);
    }
  }

  // Three to five stages: the first two walked row by row; the tight loop reads raw ratio
  // arrays, and the floor of a one-stage right half from flags.
  bool sweepRows(Walk& w) {
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
    // A wider right half: the least ratio its canonical entries can have, from the least
    // index each of its stages may take (ratios ascend with the index).
    std::vector<size_t> fl(kk, 0);
    // The stages each right stage's index may not fall below, found once.
    std::vector<std::vector<int>> floorsOf(kk);
    for (const auto& [sa, sb] : ordered)
      if (sb >= 2) floorsOf[static_cast<size_t>(sb)].push_back(sa);
    auto leastRight = [&](size_t i, size_t j) {
      double r = 1;
      for (int s = 2; s < k; ++s) {
        size_t f = 0;
        for (int sa : floorsOf[static_cast<size_t>(s)])
          f = std::max(f, sa == 0 ? i : sa == 1 ? j : fl[static_cast<size_t>(sa)]);
        fl[static_cast<size_t>(s)] = f;
        const auto& list = ratios[static_cast<size_t>(s)];
        if (f >= list.size()) return static_cast<double>(INFINITY);
        r *= list[f];
      }
      return r;
    };
    // Where no right stage's floor is the first stage's index, the least right ratio
    // depends on j alone: one table for every row.
    std::vector<double> byJ;
    bool fromI = false;
    for (int s = 2; s < k; ++s)
      for (int sa : floorsOf[static_cast<size_t>(s)]) fromI = fromI || sa == 0;
    if (!fromI && !r2)
      for (size_t j = 0; j < m1; ++j) byJ.push_back(leastRight(0, j));
    const double base = fastKey ? fastKey->constant() : 0;
    double rightLeast = 0;
    if (fastKey)
      for (int s = 2; s < k; ++s)
        rightLeast += fastKey->least(s);
    // Reciprocals once: a row's window then costs products, not divisions (its rounding is
    // far inside the window's margin eps, and every border entry is confirmed exactly).
    std::vector<double> inv0(ratios[0].size()), inv1(m1);
    for (size_t i = 0; i < inv0.size(); ++i) inv0[i] = 1 / r0[i];
    for (size_t j = 0; j < m1; ++j) inv1[j] = 1 / r1[j];
    // A short right list's rows are scanned by nextShortRow, which reads the occupancy
    // table directly: positive windows only.
    const bool tight = r2 && !occupancy.bits.empty() && !ratios[0].empty() && r0[0] > 0 && m1 > 0 && r1[0] > 0 && wantLoC > 0 &&
                       wantLoC <= wantHiC;
    auto& cand = w.cand;
    for (size_t i = w.begin; i < w.end; ++i) {
      if (due(w, (i - w.begin) % 64 == 0) && stopHere(w.t, i, w.begin, w.end)) return false;
      if (w.report && (i - w.begin) % 64 == 0) opt.progress(static_cast<double>(i - w.begin) / static_cast<double>(w.end - w.begin));
      size_t j0 = j0FromI ? i : 0;
      if (j0 >= m1) continue;
      cand[0] = static_cast<std::uint32_t>(i);
      double x0 = r0[i] * r1[j0];
      size_t loP = right->lowerBound(wantLoC / x0), hiP = right->upperBound(wantHiC / x0);
      double rowPart = fastKey ? base + fastKey->entry(0, cand[0]) : 0;
      for (size_t j = j0; j < m1; ++j) {
        if (tight) {
          j = nextShortRow(j, m1, inv0[i], inv1.data(), r2, floorI ? i : 0, floorJ, w.sinceCheck);
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
          // log-ratio buckets that hold no entry is passed over; else the index jumps to it.
          if (x * (byJ.empty() ? leastRight(i, j) : byJ[j]) > wantHiC) break;
          if (!occupancy.any(wl, wh)) continue;
          // The queries kIndexAhead and kEntriesAhead rows ahead are known: their memory is
          // fetched now.
          if (j + kIndexAhead < m1) right->prefetchIndex(wantLoC * inv0[i] * inv1[j + kIndexAhead]);
          if (j + kEntriesAhead < m1) right->prefetchEntries(wantLoC * inv0[i] * inv1[j + kEntriesAhead]);
          loP = right->lowerBound(wl);
          for (hiP = loP; hiP < rn && right->ratio(hiP) <= wh;)
            ++hiP;
        }
        // The window only falls and the floor only rises along a row.
        size_t from = loP;
        if (floorOnly) {
          size_t floor = std::max(floorI ? i : 0, floorJ ? j : 0);
          if (hiP <= floor) break;
          from = std::max(loP, floor);
        }
        if (from >= hiP) continue;
        cand[1] = static_cast<std::uint32_t>(j);
        double partial = 0;
        if (fastKey && full(w.lo))
          partial = rowPart + fastKey->entry(1, cand[1]) + (rowMin.empty() ? rightLeast : rowMin.least(from, hiP));
        joinEntry(w, i * n1 + j, x, from, hiP, partial);
      }
    }
    return true;
  }

  // Two halves built and sorted: one two-pointer sweep of the left list against the right.
  bool sweepHalves(Walk& w) {
    double rightLeast = 0;
    if (fastKey) {
      rightLeast = fastKey->constant();
      for (int s = h; s < k; ++s)
        rightLeast += fastKey->least(s);
    }
    size_t loP = right->lowerBound(wantLoC / leftList.ratio(w.begin)), hiP = right->upperBound(wantHiC / leftList.ratio(w.begin));
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
  void sweep(int t) {
    Local& lo = locals[static_cast<size_t>(t)];
    lo.crossRemoved.assign(cross.size(), 0);
    const size_t slots = locals.size();
    size_t begin = n * static_cast<size_t>(t) / slots;
    size_t end = n * static_cast<size_t>(t + 1) / slots;
    if (begin >= end || rn == 0) return;
    // The bar itself appears only once the solve has taken a second.
    bool report = t == 0 && opt.progress;
    Walk w{t, lo, Assignment(m), std::vector<std::uint32_t>(kk + 1, 0), std::vector<double>(nk + 1, 0), begin, end, 0, report};
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
  bool join() {
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
    buildOccupancy();
    // The rows dealt to every rank's threads; each rank sweeps its own slots and receives
    // the others' counts and kept designs (a fixed point: every rank searches alike).
    const int ranks = par::sharingRanks();
    const size_t slots = static_cast<size_t>(threads) * static_cast<size_t>(ranks);
    locals.resize(slots);
    walkBudget = opt.maxDesigns * kCheckedShare / static_cast<double>(slots);
    joinDone.assign(slots, 1.0);
    auto shares = par::map(static_cast<size_t>(ranks), 1, [&](size_t r) {
      int first = static_cast<int>(r) * threads;
      std::vector<std::thread> pool;
      for (int t = 1; t < threads; ++t)
        pool.emplace_back([this, first, t] { sweep(first + t); });
      sweep(first);
      for (auto& th : pool)
        th.join();
      return ranks > 1 ? packShare(first) : std::vector<double>{};
    }, true);
    if (ranks > 1)
      for (size_t r = 0; r < shares.size(); ++r)
        if (static_cast<int>(r) != par::rank()) unpackShare(shares[r], static_cast<int>(r) * threads);
    if (overWalked) {
      res.errors.push_back(fmt::format("the rules across stages are checked design by design, and more than {:.3g} designs (a fiftieth "
                                       "of the search budget, --max-designs {:.3g}) of the {:.3g} combinations need them evaluated, "
                                       "or more than {:.3g} visited; narrow the ranges or the ratio window, or raise --max-designs",
                                       opt.maxDesigns * kCheckedShare, opt.maxDesigns, combos, opt.maxDesigns));
      return false;
    }
    if (timedOut) {
      double elapsed = Deadline::seconds();
      double done = 0;
      for (double d : joinDone) done += d / static_cast<double>(joinDone.size());
      // The designs of the part walked are kept, the report marked partial.
      res.partial = timeLimitMessage("joining the stages' candidates", done, elapsed, combos);
      return true;
    }
    return true;
  }

  // A rank's share of the join as numbers: the stop flags, then per thread its counts, its
  // completed fraction and its kept designs (keys, candidates, heap).
  std::vector<double> packShare(int first) const {
    par::NumbersOut out;
    out.put(timedOut ? 1.0 : 0.0);
    out.put(overWalked ? 1.0 : 0.0);
    for (int t = first; t < first + threads; ++t) {
      const Local& lo = locals[static_cast<size_t>(t)];
      out.count(lo.count);
      out.count(lo.undecided);
      for (double x : {lo.inWindow, lo.duplicates, lo.walked, lo.overKept ? 1.0 : 0.0, joinDone[static_cast<size_t>(t)]}) out.put(x);
      out.list(lo.crossRemoved);
      out.list(lo.keys);
      out.list(lo.cand);
      out.list(lo.heap);
    }
    return out.take();
  }
  void unpackShare(const std::vector<double>& v, int first) {
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
  void order(std::vector<Ref>& hits) const {
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
      if (j - i > 1) std::sort(hits.begin() + static_cast<std::ptrdiff_t>(i), hits.begin() + static_cast<std::ptrdiff_t>(j), byRef);
      i = j;
    }
  }

  Design design(const Ref& x) const {
    Design d;
    const std::uint32_t* cand = candOf(x);
    d.choice.assign(m.slots.size(), -1);
    for (int s = 0; s < k; ++s) {
      const auto& slots = m.stages[static_cast<size_t>(s)].slots;
      const auto& idx = candidate(s, cand).idx;
      for (size_t j = 0; j < slots.size(); ++j)
        d.choice[static_cast<size_t>(slots[j])] = idx[j];
    }
    d.ratio = exactRatio(cand);
    d.keys.assign(keysOf(x), keysOf(x) + nk);
    for (int s = 0; s < k; ++s)
      d.undecided = d.undecided || candidate(s, cand).undecided;
    return d;
  }

  // The threads' counts and kept designs merged, ranked, and the funnel's last steps.
  void collect() {
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
    if ((capped && count > opt.maxKept) || std::any_of(locals.begin(), locals.end(), [](const Local& lo) { return lo.overKept; })) {
      res.errors.push_back(fmt::format("{} designs satisfy the rules, more than the {} a report can list (the budget of kept "
                                       "designs); ask for fewer with `report {{ top N; }}`, or narrow the ranges",
                                       count, opt.maxKept));
      return;
    }
    order(hits);
    if (opt.compact) {
      res.listing = listing(hits);
    } else {
      res.designs.reserve(hits.size());
      for (const auto& x : hits)
        res.designs.push_back(design(x));
    }
    std::string windowText = windowTexts.empty() ? "ratio (no window)" : fmt::format("{}", fmt::join(windowTexts, " and "));
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
    if (group.size() > 1 && !fast) res.funnel.push_back({"interchangeable: one design per orbit", "", before, duplicates});
    res.count = count;
    res.undecided = undecided;
  }

  // The ranked designs as candidate indices and keys; the threads' shares are let go once
  // the list is made, and the stages' candidates move into it.
  std::shared_ptr<const DesignList> listing(std::vector<Ref>& hits) {
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
};

} // namespace

SearchResult search(const Model& m, const SearchOptions& opt) { return Searcher(m, opt).run(); }

} // namespace gbx::rt
