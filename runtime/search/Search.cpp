#include "search/Searcher.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <unordered_set>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/Deadline.h"
#include "model/StageKind.h"

namespace gbx::rt {

namespace {

using ir::Op;

// ---- symmetry ---------------------------------------------------------------------------

using searching::Perm;

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

namespace searching {

SearchResult Searcher::run() {
  if (splitRules() && constantRules() && filterStages() && symmetry() && downstream() && layout()) {
    rankingKeys();
    orbits();
    if (join()) collect();
  }
  return std::move(res);
}

// Each stage its own copy of its candidates, before one stage's are changed.
void Searcher::unshare() {
  for (size_t s = 0; s < stages.size(); ++s)
    if (source[s] != s) {
      stages[s].candidates = stages[source[s]].candidates;
      source[s] = s;
    }
}

// Rules into conjuncts: one-stage ones filter that stage, the ratio window joins stages,
// the rest are checked on whole designs.
bool Searcher::splitRules() {
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
bool Searcher::constantRules() {
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
bool Searcher::filterStages() {
  for (int s = 0; s < k; ++s) {
    double domain = stageDomain(m, s);
    if (domain > opt.maxDesigns) {
      res.errors.push_back(
          fmt::format("stage `{}` has {:.3g} candidates ({}), beyond the search budget of {:.3g} (--max-designs); "
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
      res.errors.push_back(timeLimitMessage(
          fmt::format("filtering the candidates of stage `{}`", m.stages[static_cast<size_t>(s)].ir->name),
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
bool Searcher::sameFilter(int a, int b) const {
  const ir::Stage &sa = *m.stages[static_cast<size_t>(a)].ir, &sb = *m.stages[static_cast<size_t>(b)].ir;
  if (sa.kind != sb.kind || sa.gears != sb.gears || sa.presets != sb.presets ||
      !stages[static_cast<size_t>(a)].notes.empty())
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
    if (!y || y->role != x.role || y->key != x.key || y->gear != x.gear || y->integer != x.integer ||
        y->symbol != x.symbol || y->choice != x.choice || y->sceneRef != x.sceneRef || !num(x.lo, y->lo) ||
        !num(x.hi, y->hi) || x.members.size() != y->members.size() || !x.value != !y->value ||
        (x.value && ir::print(*x.value) != ir::print(*y->value)))
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

// Interchangeable groups as permutations of slots; sets `stageSwapsOnly` false when a
// group pairs single gears rather than whole stages.
bool Searcher::generators(std::vector<Perm>& gens, bool& stageSwapsOnly) {
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
bool Searcher::sameList(int a, int b) const {
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
bool Searcher::symmetry() {
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
      for (const auto& name : gp)
        inGroup.push_back(m.stageIndex(name));
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

// Cross rules that read one downstream stage and its operating point alone are bracketed
// per candidate over the upstream ratios its designs can have (search/Upstream.h); the
// join asks a design only inside its bracket. Not for the exhaustive reference.
bool Searcher::downstream() {
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
    upstream.push_back(bracketStage(ev, s, stages[static_cast<size_t>(s)].candidates, rules,
                                    local[static_cast<size_t>(s)], upstreamRange(s), placeOne, opt.jobs));
    for (size_t r = 0; r < which.size(); ++r)
      crossAt[which[r]] = {static_cast<int>(upstream.size()) - 1, static_cast<int>(r)};
  }
  return true;
}

// Per candidate of stage s, the upstream ratios a design in the window can give it: the
// products of the stages' least and greatest ratios, cut by the window over the
// candidate's own ratio and those downstream; empty (lo > hi) where none can.
std::vector<std::pair<double, double>> Searcher::upstreamRange(int s) const {
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
    out.emplace_back(std::max(upLo, wlo / (c.r * downHi)) * (1 - 1e-9),
                     std::min(upHi, whi / (c.r * downLo)) * (1 + 1e-9));
  return out;
}

// The join's budget: with a two-sided ratio window it builds and walks its halves; without
// one it visits every combination.
bool Searcher::withinBudget() {
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
  res.errors.push_back(fmt::format("the search space is {:.3g} designs ({}){}, beyond the search budget of {:.3g} "
                                   "(--max-designs); narrow these ranges, "
                                   "{}or raise --max-designs",
                                   combos, fmt::join(lists, "; "),
                                   windowed ? fmt::format(", of which the join walks {:.3g}", walked) : "",
                                   opt.maxDesigns, windowed ? "" : "bound the ratio (`require ratio == … +- …`), "));
  return false;
}

// Whether both halves are the same block of interchangeable stages: one list serves both.
bool Searcher::sameHalves() const {
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
  auto has = [&](int x, int y) {
    return std::find(ordered.begin(), ordered.end(), std::make_pair(x, y)) != ordered.end();
  };
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
bool Searcher::layout() {
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
  if (right->hasPairView()) pairView = right->pairView();
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
std::vector<std::pair<double, double>> Searcher::rightReach() const {
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
  for (int t = 0; t < h; ++t)
    least *= ratios[static_cast<size_t>(t)].front();
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

size_t Searcher::rightFloor(size_t le) const {
  size_t lo = 0;
  if (floorOnly)
    for (const auto& [sa, sb] : crossing)
      lo = std::max<size_t>(lo, leftIndex(le, sa));
  return lo;
}

void Searcher::place(Assignment& a, int s, size_t c) const {
  const StageInfo& info = m.stages[static_cast<size_t>(s)];
  const Candidate& cand = candidatesOf(s)[c];
  for (size_t j = 0; j < info.slots.size(); ++j)
    a.choice[static_cast<size_t>(info.slots[j])] = cand.idx[j];
  for (size_t j = 0; j < info.freedoms.size(); ++j) {
    const auto f = static_cast<size_t>(info.freedoms[j]);
    a.box[f] = cand.box.empty() ? std::pair{m.freedoms[f].lo, m.freedoms[f].hi} : cand.box[j];
  }
}

std::optional<double> Searcher::direct(size_t i, const Assignment& a) const {
  if (!a.ratio || !exactKey[i]) return std::nullopt;
  auto q = exactKey[i]->exactAt(*a.ratio);
  if (!q) return std::nullopt;
  return q->toDouble();
}

// Ranking keys: `sort by`, then the objectives (minimised; maximised ones negated).
void Searcher::keysInto(const Assignment& a, double* out) const {
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

void Searcher::rankingKeys() {
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
void Searcher::screen() {
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

void Searcher::orbits() {
  orbitCheck = !fast && group.size() > 1;
  members.resize(kk);
  if (orbitCheck)
    for (int s = 0; s < k; ++s)
      for (const auto& c : candidatesOf(s))
        members[static_cast<size_t>(s)].insert(c.idx);
}

// Image of a design under a permutation: slot values moved; -1 where a value is outside
// the target slot's domain.
std::vector<int> Searcher::image(const std::vector<int>& choice, const Perm& p) const {
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

std::vector<int> Searcher::stageTuple(const std::vector<int>& choice, int s) const {
  std::vector<int> t;
  for (int sl : m.stages[static_cast<size_t>(s)].slots)
    t.push_back(choice[static_cast<size_t>(sl)]);
  return t;
}

bool Searcher::feasibleDesign(const std::vector<int>& choice) const {
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
bool Searcher::less(const std::vector<int>& x, const std::vector<int>& y) const {
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
bool Searcher::representative(const std::vector<int>& choice) const {
  for (size_t g = 1; g < group.size(); ++g) {
    auto img = image(choice, group[g]);
    if (img != choice && feasibleDesign(img) && less(img, choice)) return false;
  }
  return true;
}

} // namespace searching

SearchResult search(const Model& m, const SearchOptions& opt) { return searching::Searcher(m, opt).run(); }

} // namespace gbx::rt
