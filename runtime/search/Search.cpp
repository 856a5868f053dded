#include "search/Search.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <thread>
#include <unordered_set>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "model/StageKind.h"

namespace gbx::rt {

namespace {

using ir::Op;

// ---- rules: conjuncts, what they depend on, the ratio window ----------------------------

struct Conjunct {
  const ir::Expr* expr = nullptr;
  std::string text;
  std::set<int> stages;
  bool freedom = false;      // depends on a continuous freedom
  bool unsupported = false;  // needs dynamics, load sharing or a baseline: not a search rule
  bool strength = false;     // reads a load-capacity rating: costly, so tested after the cheap rules
};

bool isGearboxRatio(const ir::QuantityRef& r) { return r.owner == ir::QuantityRef::Gearbox && r.key == Q::Ratio; }

void dependencies(const Model& m, const ir::Expr& e, Conjunct& c, int depth = 0) {
  if (depth > 64) return;
  int all = static_cast<int>(m.stages.size());
  switch (e.op) {
  case Op::Quantity: {
    const ir::QuantityRef& r = e.ref;
    if (r.owner == ir::QuantityRef::Gearbox) {
      for (int s = 0; s < all; ++s) c.stages.insert(s);
      if (!m.freedoms.empty() && r.key != Q::Ratio) c.freedom = true;
      break;
    }
    if (r.owner != ir::QuantityRef::Stage) {
      c.unsupported = true;
      break;
    }
    int st = r.index;
    if (cat::isRatingQuantity(r.key)) c.strength = true;
    if (cat::dependsOnOperatingPoint(r.key))
      for (int s = 0; s <= st; ++s) c.stages.insert(s);
    c.stages.insert(st);
    if (m.freedomOf(st, r.gear, r.key) >= 0) c.freedom = true;
    const ir::Attribute* a = m.attribute(st, r.gear, r.key);
    if (!a && !m.stages[static_cast<size_t>(st)].freedoms.empty() && r.key != Q::Ratio) c.freedom = true;
    if (a && a->value && a->role != ir::Attribute::Decision) dependencies(m, *a->value, c, depth + 1);
    break;
  }
  case Op::Let:
    if (e.let >= 0 && m.gearbox.lets[static_cast<size_t>(e.let)].expr)
      dependencies(m, *m.gearbox.lets[static_cast<size_t>(e.let)].expr, c, depth + 1);
    break;
  case Op::SceneOutput:
  case Op::Scatter:
  case Op::Relative: c.unsupported = true; break;
  default: break;
  }
  for (const auto& a : e.args)
    if (a) dependencies(m, *a, c, depth + 1);
}

void split(const ir::Expr& e, std::vector<const ir::Expr*>& out) {
  if (e.op == Op::And || e.op == Op::Forall) {
    for (const auto& a : e.args) split(*a, out);
    return;
  }
  out.push_back(&e);
}

struct Window {
  std::optional<Rational> lo, hi;
  bool loStrict = false, hiStrict = false;
  bool empty() const {
    if (!lo || !hi) return false;
    int c = lo->compare(*hi);
    return c > 0 || (c == 0 && (loStrict || hiStrict));
  }
  void lower(const Rational& v, bool strict) {
    if (!lo || v > *lo || (v == *lo && strict)) {
      lo = v;
      loStrict = strict;
    }
  }
  void upper(const Rational& v, bool strict) {
    if (!hi || v < *hi || (v == *hi && strict)) {
      hi = v;
      hiStrict = strict;
    }
  }
  bool contains(const Rational& r) const {
    if (lo) {
      int c = r.compare(*lo);
      if (c < 0 || (c == 0 && loStrict)) return false;
    }
    if (hi) {
      int c = r.compare(*hi);
      if (c > 0 || (c == 0 && hiStrict)) return false;
    }
    return true;
  }
  std::string str() const {
    return fmt::format("{}{}, {}{}", loStrict ? "(" : "[", lo ? lo->str() : "-inf", hi ? hi->str() : "inf", hiStrict ? ")" : "]");
  }
};

std::optional<Rational> rationalConst(const ir::Expr& e) {
  if (e.op == Op::Const && e.type.isNumber() && e.value.isRational()) return e.value.rational();
  return std::nullopt;
}

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

bool isRatio(const ir::Expr& e) { return e.op == Op::Quantity && isGearboxRatio(e.ref); }

// Recognises `ratio == t +- tol`, `ratio in a..b` and one-sided bounds on the gearbox ratio.
bool asWindow(const ir::Expr& e, Window& w) {
  auto bound = [&](const ir::Expr& x, const ir::Expr& k, bool ratioLeft) {
    auto v = rationalConst(k);
    if (!v || !isRatio(x)) return false;
    bool strict = e.op == Op::Lt || e.op == Op::Gt;
    bool upper = (e.op == Op::Lt || e.op == Op::Le) == ratioLeft;
    if (upper) w.upper(*v, strict);
    else w.lower(*v, strict);
    return true;
  };
  switch (e.op) {
  case Op::Eq: {
    if (!isRatio(*e.args[0])) return false;
    const ir::Expr& t = *e.args[1];
    if (t.op == Op::Tol) {
      auto c = rationalConst(*t.args[0]), d = rationalConst(*t.args[1]);
      if (!c || !d) return false;
      std::optional<Rational> lo, hi;
      if (t.relative) {
        auto one = Rational(1);
        auto a = one.sub(*d), b = one.add(*d);
        if (!a || !b) return false;
        lo = c->mul(*a);
        hi = c->mul(*b);
      } else {
        lo = c->sub(*d);
        hi = c->add(*d);
      }
      if (!lo || !hi) return false;
      w.lower(*lo, false);
      w.upper(*hi, false);
      return true;
    }
    if (auto v = rationalConst(t)) {
      w.lower(*v, false);
      w.upper(*v, false);
      return true;
    }
    return false;
  }
  case Op::Within: {
    auto lo = rationalConst(*e.args[1]), hi = rationalConst(*e.args[2]);
    if (!isRatio(*e.args[0]) || !lo || !hi) return false;
    w.lower(*lo, false);
    w.upper(*hi, false);
    return true;
  }
  case Op::Lt:
  case Op::Le:
  case Op::Gt:
  case Op::Ge: return bound(*e.args[0], *e.args[1], true) || bound(*e.args[1], *e.args[0], false);
  default: return false;
  }
}

// ---- freedoms: is there a point of the box where every rule holds? ----------------------

enum class Verdict { Feasible, Infeasible, Undecided };

Truth truthOf(const Value& v) { return v.kind == Value::Bool ? v.truth : Truth::Unknown; }

Verdict decide(const Evaluator& ev, Assignment& a, const std::vector<const Conjunct*>& rules, const std::vector<int>& freedoms) {
  const Model& m = ev.model();
  std::vector<std::pair<double, double>> saved = a.box;
  struct Box {
    std::vector<std::pair<double, double>> b;
    int depth;
  };
  auto all = [&](Truth& out) {
    out = Truth::True;
    for (const auto* c : rules) {
      out = arith::land(out, truthOf(ev.eval(*c->expr, a)));
      if (out == Truth::False) return;
    }
  };
  std::vector<Box> stack;
  stack.push_back({a.box, 0});
  bool undecided = false;
  int budget = 4000;
  Verdict verdict = Verdict::Infeasible;
  while (!stack.empty() && budget-- > 0) {
    Box box = std::move(stack.back());
    stack.pop_back();
    a.box = box.b;
    Truth t;
    all(t);
    if (t == Truth::False) continue;
    if (t == Truth::True) {
      verdict = Verdict::Feasible;
      break;
    }
    // Witnesses: the midpoint and, for a few freedoms, the corners, where monotone
    // quantities take their extremes.
    std::vector<std::vector<double>> points;
    std::vector<double> mid;
    for (int f : freedoms) mid.push_back(0.5 * (box.b[static_cast<size_t>(f)].first + box.b[static_cast<size_t>(f)].second));
    points.push_back(mid);
    if (freedoms.size() <= 4)
      for (size_t mask = 0; mask < (size_t{1} << freedoms.size()); ++mask) {
        std::vector<double> p;
        for (size_t k = 0; k < freedoms.size(); ++k) {
          const auto& iv = box.b[static_cast<size_t>(freedoms[k])];
          p.push_back((mask >> k) & 1 ? iv.second : iv.first);
        }
        points.push_back(p);
      }
    bool found = false;
    for (const auto& p : points) {
      for (size_t k = 0; k < freedoms.size(); ++k) a.box[static_cast<size_t>(freedoms[k])] = {p[k], p[k]};
      Truth pt;
      all(pt);
      if (pt == Truth::True) {
        found = true;
        break;
      }
    }
    if (found) {
      verdict = Verdict::Feasible;
      break;
    }
    if (box.depth >= 24) {
      undecided = true;
      continue;
    }
    // Bisect the freedom that is widest relative to its domain.
    int widest = freedoms[0];
    double best = -1;
    for (int f : freedoms) {
      const auto& fr = m.freedoms[static_cast<size_t>(f)];
      double span = fr.hi - fr.lo;
      double w = span > 0 ? (box.b[static_cast<size_t>(f)].second - box.b[static_cast<size_t>(f)].first) / span : 0;
      if (w > best) {
        best = w;
        widest = f;
      }
    }
    auto lo = box.b, hi = box.b;
    double midv = 0.5 * (box.b[static_cast<size_t>(widest)].first + box.b[static_cast<size_t>(widest)].second);
    lo[static_cast<size_t>(widest)].second = midv;
    hi[static_cast<size_t>(widest)].first = midv;
    stack.push_back({hi, box.depth + 1});
    stack.push_back({lo, box.depth + 1});
  }
  if (verdict != Verdict::Feasible && (undecided || !stack.empty())) verdict = Verdict::Undecided;
  a.box = saved;
  return verdict;
}

// ---- per-stage candidates ---------------------------------------------------------------

struct Candidate {
  std::vector<int> idx;  // value index per slot of the stage
  Rational ratio;
  double r = 0;
  bool undecided = false;
};

struct StageRule {
  std::string text;
  std::function<Truth(const Evaluator&, const Assignment&)> test;
  const Conjunct* conjunct = nullptr;
};

// The rules the stage's kind implies, before the spec's own.
std::vector<StageRule> implicitRules(const Model& m, int s) {
  std::vector<StageRule> rules;
  for (const auto& r : m.info(s).kind->rules)
    rules.push_back({r.text, [s, test = r.test](const Evaluator& ev, const Assignment& a) { return test(KindContext{ev, s, a}); }});
  return rules;
}

struct StageResult {
  std::vector<Candidate> candidates;
  std::vector<FunnelStep> funnel;
  std::vector<std::string> notes;
};

StageResult filterStage(const Evaluator& ev, int s, const std::vector<const Conjunct*>& local, int jobs) {
  const Model& m = ev.model();
  const StageInfo& info = m.stages[static_cast<size_t>(s)];
  auto rules = implicitRules(m, s);
  for (const auto* c : local) rules.push_back({c->text, nullptr, c});
  std::vector<size_t> sizes;
  size_t total = 1;
  for (int sl : info.slots) {
    sizes.push_back(m.slots[static_cast<size_t>(sl)].values.size());
    total *= sizes.back();
  }
  struct Chunk {
    std::vector<Candidate> out;
    std::vector<double> removed, unevaluable;
    double jointRemoved = 0;
  };
  int threads = std::max(1, std::min<int>(jobs, static_cast<int>(total / 2048) + 1));
  std::vector<Chunk> chunks(static_cast<size_t>(threads));
  auto work = [&](int t) {
    Chunk& ch = chunks[static_cast<size_t>(t)];
    ch.removed.assign(rules.size(), 0);
    ch.unevaluable.assign(rules.size(), 0);
    Assignment a(m);
    size_t begin = total * static_cast<size_t>(t) / static_cast<size_t>(threads);
    size_t end = total * static_cast<size_t>(t + 1) / static_cast<size_t>(threads);
    std::vector<const Conjunct*> open;
    for (size_t k = begin; k < end; ++k) {
      size_t rest = k;
      Candidate c;
      c.idx.resize(info.slots.size());
      for (size_t i = info.slots.size(); i-- > 0;) {
        c.idx[i] = static_cast<int>(rest % sizes[i]);
        rest /= sizes[i];
        a.choice[static_cast<size_t>(info.slots[i])] = c.idx[i];
      }
      open.clear();
      bool dead = false;
      for (size_t r = 0; r < rules.size() && !dead; ++r) {
        Truth t = rules[r].test ? rules[r].test(ev, a) : truthOf(ev.eval(*rules[r].conjunct->expr, a));
        if (t == Truth::False) {
          ch.removed[r] += 1;
          dead = true;
        } else if (t == Truth::Unknown) {
          if (rules[r].conjunct && rules[r].conjunct->freedom) open.push_back(rules[r].conjunct);
          else {
            ch.removed[r] += 1;  // cannot be evaluated: counted, and said in a note
            ch.unevaluable[r] += 1;
            dead = true;
          }
        }
      }
      if (dead) continue;
      if (!open.empty()) {
        Verdict v = decide(ev, a, open, info.freedoms);
        if (v == Verdict::Infeasible) {
          ch.jointRemoved += 1;
          continue;
        }
        c.undecided = v == Verdict::Undecided;
      }
      Value r = ev.derived(s, Q::Ratio, a);
      if (!r.exact) continue;
      c.ratio = *r.exact;
      c.r = r.lo;
      ch.out.push_back(std::move(c));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();

  StageResult res;
  double before = static_cast<double>(total);
  const std::string& name = info.ir->name;
  res.funnel.push_back({"domain", name, 0, -before, true});
  for (size_t r = 0; r < rules.size(); ++r) {
    double removed = 0, unevaluable = 0;
    for (const auto& ch : chunks) {
      removed += ch.removed[r];
      unevaluable += ch.unevaluable[r];
    }
    res.funnel.push_back({rules[r].text, name, before, removed});
    if (unevaluable > 0)
      res.notes.push_back(fmt::format("stage {}: `{}` could not be evaluated for {:.0f} of its {:.0f} candidates, which it removed "
                                      "(a rating refuses their geometry, or an input is missing)",
                                      name, rules[r].text, unevaluable, before));
    before -= removed;
  }
  double joint = 0;
  for (const auto& ch : chunks) joint += ch.jointRemoved;
  if (joint > 0) {
    res.funnel.push_back({"no freedom value satisfies the rules together", name, before, joint});
    before -= joint;
  }
  for (auto& ch : chunks)
    for (auto& c : ch.out) res.candidates.push_back(std::move(c));
  std::sort(res.candidates.begin(), res.candidates.end(), [](const Candidate& x, const Candidate& y) {
    int c = x.ratio.compare(y.ratio);
    return c != 0 ? c < 0 : x.idx < y.idx;
  });
  return res;
}

// ---- symmetry ---------------------------------------------------------------------------

using Perm = std::vector<int>;  // slot -> slot

std::vector<Perm> closeGroup(const std::vector<Perm>& gens, size_t n) {
  Perm id(n);
  for (size_t i = 0; i < n; ++i) id[i] = static_cast<int>(i);
  std::vector<Perm> group = {id};
  std::set<Perm> seen = {id};
  for (size_t i = 0; i < group.size() && group.size() < 5040; ++i)
    for (const auto& g : gens) {
      Perm p(n);
      for (size_t k = 0; k < n; ++k) p[k] = g[static_cast<size_t>(group[i][k])];
      if (seen.insert(p).second) group.push_back(p);
    }
  return group;
}

// One half of the train: every tuple of candidates of stages [from, to), canonical
// within interchangeable blocks, sorted by ratio product. Compact: a double and the
// candidate indices per tuple; exact ratios are recomputed only where they decide.
struct HalfList {
  int from = 0, to = 0, width = 0;
  std::vector<double> r;
  std::vector<std::uint32_t> idx;
};

HalfList buildHalf(const std::vector<StageResult>& stages, const std::vector<std::pair<int, int>>& ordered, int from, int to) {
  HalfList H;
  H.from = from;
  H.to = to;
  H.width = to - from;
  size_t w = static_cast<size_t>(H.width);
  if (w == 0) {
    H.r.push_back(1.0);
    return H;
  }
  for (int s = from; s < to; ++s)
    if (stages[static_cast<size_t>(s)].candidates.empty()) return H;
  std::vector<std::uint64_t> key;
  std::vector<std::uint32_t> idx;
  auto push = [&](double r, const std::uint32_t* cur) {
    std::uint64_t bits;
    std::memcpy(&bits, &r, sizeof bits);
    key.push_back(bits);
    idx.insert(idx.end(), cur, cur + w);
  };
  auto linked = [&](int a, int b) { return std::find(ordered.begin(), ordered.end(), std::make_pair(a, b)) != ordered.end(); };
  if (w == 1) {
    const auto& l0 = stages[static_cast<size_t>(from)].candidates;
    key.reserve(l0.size());
    for (std::uint32_t i = 0; i < l0.size(); ++i) push(l0[i].r, &i);
  } else if (w == 2) {
    const auto& l0 = stages[static_cast<size_t>(from)].candidates;
    const auto& l1 = stages[static_cast<size_t>(from + 1)].candidates;
    bool canon = linked(from, from + 1);
    key.reserve(canon ? l0.size() * (l1.size() + 1) / 2 : l0.size() * l1.size());
    idx.reserve(2 * key.capacity());
    std::uint32_t cur[2];
    for (cur[0] = 0; cur[0] < l0.size(); ++cur[0])
      for (cur[1] = canon ? cur[0] : 0; cur[1] < l1.size(); ++cur[1]) push(l0[cur[0]].r * l1[cur[1]].r, cur);
  } else {
    std::vector<std::uint32_t> cur(w, 0);
    auto start = [&](int s) {
      std::uint32_t lo = 0;
      for (const auto& [a, b] : ordered)
        if (b == s && a >= from && a < s) lo = std::max(lo, cur[static_cast<size_t>(a - from)]);
      return lo;
    };
    for (int s = from; s < to; ++s) cur[static_cast<size_t>(s - from)] = start(s);
    for (;;) {
      bool valid = true;
      double prod = 1;
      for (int s = from; s < to && valid; ++s) {
        const auto& list = stages[static_cast<size_t>(s)].candidates;
        std::uint32_t i = cur[static_cast<size_t>(s - from)];
        if (i >= list.size()) valid = false;
        else prod *= list[i].r;
      }
      if (valid) push(prod, cur.data());
      // Odometer, last stage fastest; a stage restarts at its canonical lower bound.
      int s = to - 1;
      for (; s >= from; --s) {
        auto& c = cur[static_cast<size_t>(s - from)];
        ++c;
        if (c < stages[static_cast<size_t>(s)].candidates.size()) break;
      }
      if (s < from) break;
      for (int t = s + 1; t < to; ++t) cur[static_cast<size_t>(t - from)] = start(t);
    }
  }
  // LSD radix sort on the bits of the (positive) ratios, whose order is the ratios'
  // order. The lowest 16 bits are left unsorted: entries out of order by less than
  // 2^-36 (1.5e-11) of their value lie well inside the sweep's margin of 1e-9, and every
  // match near a bound is confirmed exactly.
  size_t n = key.size();
  std::vector<std::uint64_t> key2(n);
  std::vector<std::uint32_t> pos(n), pos2(n);
  for (size_t i = 0; i < n; ++i) pos[i] = static_cast<std::uint32_t>(i);
  // Short lists: a comparison sort beats three passes over 65536 buckets.
  if (n < 65536) {
    std::stable_sort(pos.begin(), pos.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    for (size_t i = 0; i < n; ++i) key2[i] = key[pos[i]];
    key.swap(key2);
  }
  std::vector<size_t> countOf(n < 65536 ? 0 : 65537);
  for (int pass = 1; pass < 4 && n >= 65536; ++pass) {
    int shift = pass * 16;
    std::fill(countOf.begin(), countOf.end(), 0);
    for (size_t i = 0; i < n; ++i) ++countOf[((key[i] >> shift) & 0xFFFF) + 1];
    for (size_t b = 0; b < 65536; ++b) countOf[b + 1] += countOf[b];
    for (size_t i = 0; i < n; ++i) {
      size_t d = countOf[(key[i] >> shift) & 0xFFFF]++;
      key2[d] = key[i];
      pos2[d] = pos[i];
    }
    key.swap(key2);
    pos.swap(pos2);
  }
  H.r.resize(n);
  H.idx.resize(n * w);
  for (size_t i = 0; i < n; ++i) {
    std::memcpy(&H.r[i], &key[i], sizeof(double));
    for (size_t j = 0; j < w; ++j) H.idx[i * w + j] = idx[static_cast<size_t>(pos[i]) * w + j];
  }
  return H;
}

} // namespace

bool needsOptimiser(const ir::Gearbox& g) {
  auto walk = [](const ir::ExprPtr& e) { return ir::uses(e.get(), {Op::SceneOutput, Op::Relative, Op::Scatter}); };
  return std::any_of(g.rules.begin(), g.rules.end(), [&](const ir::Rule& r) { return walk(r.expr); }) ||
         std::any_of(g.objectives.begin(), g.objectives.end(), [&](const ir::Objective& o) { return walk(o.expr); });
}

SearchResult search(const Model& m, const SearchOptions& opt) {
  SearchResult res;
  Evaluator ev(m);
  const int k = static_cast<int>(m.stages.size());

  // Rules into conjuncts: one-stage ones filter that stage, the ratio window joins stages,
  // the rest are checked on whole designs.
  std::vector<Conjunct> conjuncts;
  for (const auto& r : m.gearbox.rules) {
    std::vector<const ir::Expr*> parts;
    if (r.expr) split(*r.expr, parts);
    for (const auto* p : parts) {
      Conjunct c;
      c.expr = p;
      c.text = parts.size() == 1 ? r.text : ir::print(*p);
      dependencies(m, *p, c);
      if (!r.scope.empty() && c.stages.empty()) c.stages.insert(m.stageIndex(r.scope));
      conjuncts.push_back(std::move(c));
    }
  }
  Window window;
  std::vector<std::string> windowTexts;
  std::vector<std::vector<const Conjunct*>> local(static_cast<size_t>(k));
  std::vector<const Conjunct*> cross, global;
  for (const auto& c : conjuncts) {
    if (c.unsupported) {
      if (opt.deferDynamics) res.deferred.push_back(c.text);
      else res.errors.push_back(fmt::format("rule `{}` needs results the search does not compute (scenes, splits, baselines)", c.text));
      continue;
    }
    if (asWindow(*c.expr, window)) {
      windowTexts.push_back(c.text);
      continue;
    }
    if (c.stages.size() == 1) local[static_cast<size_t>(*c.stages.begin())].push_back(&c);
    else if (c.stages.empty()) global.push_back(&c);
    else cross.push_back(&c);
  }
  // A strength rule runs only on the candidates the cheaper rules kept; the funnel then
  // says how many it removed.
  for (auto& l : local)
    std::stable_sort(l.begin(), l.end(), [](const Conjunct* a, const Conjunct* b) { return !a->strength && b->strength; });
  std::stable_sort(cross.begin(), cross.end(), [](const Conjunct* a, const Conjunct* b) { return !a->strength && b->strength; });
  for (const auto& o : m.gearbox.objectives) {
    Conjunct c;
    if (o.expr) dependencies(m, *o.expr, c);
    if (c.unsupported && !opt.deferDynamics)
      res.errors.push_back(fmt::format("objective `{}` needs results the search does not compute (scenes, baselines)", o.text));
  }
  if (!res.errors.empty()) return res;
  if (window.lo || window.hi) res.window = window.str();

  // Rules on constants alone decide everything at once.
  Assignment none(m);
  for (const auto* c : global) {
    Truth t = truthOf(ev.eval(*c->expr, none));
    res.funnel.push_back({c->text, "", 1, t == Truth::True ? 0.0 : 1.0});
    if (t != Truth::True) return res;
  }

  std::vector<StageResult> stages;
  for (int s = 0; s < k; ++s) {
    stages.push_back(filterStage(ev, s, local[static_cast<size_t>(s)], opt.jobs));
    for (auto& f : stages.back().funnel) res.funnel.push_back(f);
    for (auto& n : stages.back().notes) res.notes.push_back(n);
  }

  // Interchangeable groups as permutations of slots.
  std::vector<Perm> gens;
  bool stageSwapsOnly = true;
  size_t nslots = m.slots.size();
  for (const auto& group : m.gearbox.interchangeable) {
    for (size_t i = 0; i + 1 < group.size(); ++i) {
      Perm p(nslots);
      for (size_t q = 0; q < nslots; ++q) p[q] = static_cast<int>(q);
      const std::string &x = group[i], &y = group[i + 1];
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
        if (gx != -2 && slot.gear != gx) continue;
        int sb = m.slotOf(b, gx == -2 ? slot.gear : gy, slot.key);
        if (sb < 0) {
          std::string px = x.find('.') == std::string::npos ? "" : x.substr(x.find('.') + 1) + ".";
          std::string py = y.find('.') == std::string::npos ? "" : y.substr(y.find('.') + 1) + ".";
          res.errors.push_back(fmt::format("`interchangeable {}, {}`: `{}` has no decision `{}` to match `{}.{}`", x, y, sy,
                                           py + slot.attr.substr(px.size()), sx, slot.attr));
          continue;
        }
        p[static_cast<size_t>(sa)] = sb;
        p[static_cast<size_t>(sb)] = sa;
      }
      gens.push_back(p);
    }
  }
  if (!res.errors.empty()) return res;
  std::vector<Perm> group = closeGroup(gens, nslots);

  // Stages whose swaps make the orbit a multiset: identical candidate lists, and no rule
  // across stages that could tell them apart. Then designs are enumerated canonically
  // (non-decreasing candidate index along the block) instead of deduplicated.
  auto sameList = [&](int a, int b) {
    const auto &ca = stages[static_cast<size_t>(a)].candidates, &cb = stages[static_cast<size_t>(b)].candidates;
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
  };
  std::vector<std::pair<int, int>> ordered;  // (a, b): index of stage a <= index of stage b
  bool fast = stageSwapsOnly && cross.empty();
  if (fast && group.size() > 1) {
    for (const auto& gp : m.gearbox.interchangeable) {
      for (size_t i = 0; i + 1 < gp.size(); ++i) {
        int a = m.stageIndex(gp[i]), b = m.stageIndex(gp[i + 1]);
        if (!sameList(a, b)) fast = false;
        ordered.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  if (!fast) ordered.clear();

  // Meet in the middle over sorted stage ratios: left stages [0, h), right [h, k). Each
  // half is a compact list sorted by its ratio product; one two-pointer sweep joins them.
  // Three stages: the first two are walked row by row (the second stage's index runs
  // fastest, so the left ratio rises along a row) against the sorted third stage, and no
  // list of pairs is built. Otherwise both halves are built and sorted; when the two
  // halves are the same block of interchangeable stages, one list serves both.
  bool rows = k == 3;
  int h = rows ? 2 : k / 2;
  double combos = 1;
  for (const auto& st : stages) combos *= static_cast<double>(st.candidates.size());
  // Blocks of interchangeable stages (union of the `ordered` links).
  std::vector<int> block(static_cast<size_t>(k));
  for (int s = 0; s < k; ++s) block[static_cast<size_t>(s)] = s;
  std::function<int(int)> root = [&](int s) { return block[static_cast<size_t>(s)] == s ? s : root(block[static_cast<size_t>(s)]); };
  for (const auto& [a, b] : ordered) block[static_cast<size_t>(root(b))] = root(a);
  bool sameHalves = !rows && fast && h == k - h && h > 0;
  for (int a = 0; sameHalves && a < h; ++a) sameHalves = root(a) == root(a + h) && sameList(a, a + h);
  for (const auto& [a, b] : ordered) {
    if (!sameHalves) break;
    bool inLeft = b < h, inRight = a >= h;
    auto has = [&](int x, int y) { return std::find(ordered.begin(), ordered.end(), std::make_pair(x, y)) != ordered.end(); };
    if (inLeft && !has(a + h, b + h)) sameHalves = false;
    if (inRight && !has(a - h, b - h)) sameHalves = false;
  }
  HalfList left;
  if (!rows) left = buildHalf(stages, ordered, 0, h);
  HalfList right = sameHalves ? left : buildHalf(stages, ordered, h, k);
  right.from = h;
  right.to = k;
  left.from = 0;
  left.to = h;
  left.width = h;
  // Rows: left entries are (i, j) packed as i * n1 + j.
  const size_t n1 = rows ? stages[1].candidates.size() : 0;
  auto leftIndex = [&](size_t le, int s) -> std::uint32_t {
    if (rows) return static_cast<std::uint32_t>(s == 0 ? le / n1 : le % n1);
    return left.idx[le * static_cast<size_t>(left.width) + static_cast<size_t>(s)];
  };
  auto rightIndex = [&](size_t re, int s) -> std::uint32_t {
    return right.idx[re * static_cast<size_t>(right.width) + static_cast<size_t>(s - h)];
  };
  auto candidateOf = [&](size_t le, size_t re, int s) -> const Candidate& {
    return stages[static_cast<size_t>(s)].candidates[s < h ? leftIndex(le, s) : rightIndex(re, s)];
  };
  auto exactRatio = [&](size_t le, size_t re) {
    Rational q(1);
    for (int s = 0; s < k; ++s) {
      auto n = q.mul(candidateOf(le, re, s).ratio);
      if (n) q = *n;
    }
    return q;
  };
  auto fill = [&](Assignment& a, size_t le, size_t re) {
    for (int s = 0; s < k; ++s) {
      const Candidate& c = candidateOf(le, re, s);
      const auto& slots = m.stages[static_cast<size_t>(s)].slots;
      for (size_t j = 0; j < slots.size(); ++j) a.choice[static_cast<size_t>(slots[j])] = c.idx[j];
    }
  };
  // Objectives that read nothing but the gearbox ratio are evaluated from it alone.
  bool ratioOnly = true;
  std::function<void(const ir::Expr&)> scan = [&](const ir::Expr& e) {
    if ((e.op == Op::Quantity && !isGearboxRatio(e.ref)) || e.op == Op::Let || e.op == Op::SceneOutput || e.op == Op::Relative ||
        e.op == Op::Scatter)
      ratioOnly = false;
    for (const auto& x : e.args)
      if (x) scan(*x);
  };
  if (!opt.deferDynamics)
    for (const auto& o : m.gearbox.objectives)
      if (o.expr) scan(*o.expr);
  if (opt.sortBy) scan(*opt.sortBy);

  auto keysOf = [&](const Assignment& a) {
    std::vector<double> keys;
    if (opt.sortBy) {
      Value v = ev.eval(*opt.sortBy, a);
      keys.push_back(v.isNumber() ? rankingKey(v.lo) : INFINITY);
    }
    for (const auto& o : m.gearbox.objectives) {
      if (opt.deferDynamics) break;  // ranked by the optimiser
      Value v = o.expr ? ev.eval(*o.expr, a) : Value::invalid();
      // Over a freedom the best attainable value counts: the design may choose it.
      keys.push_back(v.isNumber() ? rankingKey(o.minimize ? v.lo : -v.hi) : INFINITY);
    }
    return keys;
  };

  // Per-stage membership, for checking the images of a design under the group.
  bool orbitCheck = !fast && group.size() > 1;
  std::vector<std::set<std::vector<int>>> members(static_cast<size_t>(k));
  if (orbitCheck)
    for (int s = 0; s < k; ++s)
      for (const auto& c : stages[static_cast<size_t>(s)].candidates) members[static_cast<size_t>(s)].insert(c.idx);
  auto valueOf = [&](int slot, int c) -> const Value& { return m.slots[static_cast<size_t>(slot)].values[static_cast<size_t>(c)]; };
  // Image of a design under a permutation: slot values moved; -1 where a value is outside
  // the target slot's domain.
  auto image = [&](const std::vector<int>& choice, const Perm& p) {
    std::vector<int> out(choice.size(), -1);
    for (size_t sl = 0; sl < choice.size(); ++sl) {
      int target = p[sl];
      const Value& v = valueOf(static_cast<int>(sl), choice[sl]);
      const auto& dom = m.slots[static_cast<size_t>(target)].values;
      for (size_t i = 0; i < dom.size(); ++i)
        if (dom[i].exact && v.exact && *dom[i].exact == *v.exact) out[static_cast<size_t>(target)] = static_cast<int>(i);
    }
    return out;
  };
  auto stageTuple = [&](const std::vector<int>& choice, int s) {
    std::vector<int> t;
    for (int sl : m.stages[static_cast<size_t>(s)].slots) t.push_back(choice[static_cast<size_t>(sl)]);
    return t;
  };
  auto feasibleDesign = [&](const std::vector<int>& choice) {
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
  };
  // Orders designs by the ratios of their stages, then by their values: the order of the
  // sorted candidate lists. An orbit is shown by its least member.
  auto less = [&](const std::vector<int>& x, const std::vector<int>& y) {
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
  };

  struct Hit {
    std::vector<double> keys;
    std::vector<std::uint32_t> cand;  // candidate index per stage: the tie-break order
    size_t le = 0;
    std::uint32_t re = 0;
    bool operator<(const Hit& o) const { return keys != o.keys ? keys < o.keys : cand < o.cand; }
  };
  const double eps = 1e-9;  // see buildHalf: larger than the sort's 2^-36
  const double wlo = window.lo ? window.lo->toDouble() : -INFINITY, whi = window.hi ? window.hi->toDouble() : INFINITY;
  size_t n = rows ? stages[0].candidates.size() : left.r.size(), rn = right.r.size();
  int threads = std::max(1, std::min<int>(opt.jobs, static_cast<int>(n / 64) + 1));
  size_t keep = opt.top ? static_cast<size_t>(*opt.top) : SIZE_MAX;
  struct Local {
    std::vector<Hit> heap;  // max-heap of the best `keep`
    unsigned long long count = 0, undecided = 0;
    double inWindow = 0, duplicates = 0;
    std::vector<double> crossRemoved;
  };
  std::vector<Local> locals(static_cast<size_t>(threads));
  // Both bounds of the right window fall as the left ratio rises.
  auto wantLo = [&](double x) { return wlo / x * (1 - eps); };
  auto wantHi = [&](double x) { return whi / x * (1 + eps); };
  // Lowest right entry the canonical order allows for this left entry (rows mode: the
  // third stage's index, which is its position in the sorted list).
  auto rightFloor = [&](size_t le) -> size_t {
    size_t lo = 0;
    if (rows)
      for (const auto& [sa, sb] : ordered)
        if (sa < h && sb == 2) lo = std::max<size_t>(lo, leftIndex(le, sa));
    return lo;
  };
  auto visit = [&](Local& lo, Assignment& a, Hit& hit, size_t le, double x, size_t from, size_t to) {
    for (size_t re = from; re < to && re < rn; ++re) {
      bool canonical = true;
      if (!rows)
        for (const auto& [sa, sb] : ordered)
          if (sa < h && sb >= h && leftIndex(le, sa) > rightIndex(re, sb)) canonical = false;
      if (!canonical) continue;
      double p = x * right.r[re];
      std::optional<Rational> q;
      if (p < wlo * (1 + 4 * eps) || p > whi * (1 - 4 * eps)) {
        q = exactRatio(le, re);
        if (!window.contains(*q)) continue;
      }
      lo.inWindow += 1;
      bool filled = false;
      if (!cross.empty() || orbitCheck) {
        fill(a, le, re);
        filled = true;
        bool ok = true;
        for (size_t c = 0; c < cross.size() && ok; ++c)
          if (truthOf(ev.eval(*cross[c]->expr, a)) == Truth::False) {
            lo.crossRemoved[c] += 1;
            ok = false;
          }
        if (!ok) continue;
        if (orbitCheck) {
          bool rep = true;
          for (size_t g = 1; g < group.size() && rep; ++g) {
            auto img = image(a.choice, group[g]);
            if (img != a.choice && feasibleDesign(img) && less(img, a.choice)) rep = false;
          }
          if (!rep) {
            lo.duplicates += 1;
            continue;
          }
        }
      }
      lo.count += 1;
      bool undecided = false;
      for (int s = 0; s < k; ++s) {
        undecided = undecided || candidateOf(le, re, s).undecided;
        hit.cand[static_cast<size_t>(s)] = s < h ? leftIndex(le, s) : rightIndex(re, s);
      }
      lo.undecided += undecided;
      if (keep == 0) continue;
      if (!ratioOnly && !filled) fill(a, le, re);
      if (ratioOnly && lo.heap.size() >= keep) {
        // Screen in doubles: only a design that may beat the worst kept one is ranked exactly.
        a.ratioApprox = p;
        auto approx = keysOf(a);
        a.ratioApprox.reset();
        const auto& worst = lo.heap.front().keys;
        bool maybe = true;  // all keys too close to call in doubles: rank exactly
        for (size_t i = 0; i < approx.size() && i < worst.size(); ++i) {
          double slack = 1e-9 * (1 + std::fabs(worst[i]));
          if (approx[i] < worst[i] - slack) break;
          if (approx[i] > worst[i] + slack) {
            maybe = false;
            break;
          }
        }
        if (!maybe) continue;
      }
      if (!q) q = exactRatio(le, re);
      a.ratio = *q;
      hit.keys = keysOf(a);
      a.ratio.reset();
      hit.le = le;
      hit.re = static_cast<std::uint32_t>(re);
      if (lo.heap.size() < keep) {
        lo.heap.push_back(hit);
        std::push_heap(lo.heap.begin(), lo.heap.end());
      } else if (hit < lo.heap.front()) {
        std::pop_heap(lo.heap.begin(), lo.heap.end());
        lo.heap.back() = hit;
        std::push_heap(lo.heap.begin(), lo.heap.end());
      }
    }
  };
  auto sweep = [&](int t) {
    Local& lo = locals[static_cast<size_t>(t)];
    lo.crossRemoved.assign(cross.size(), 0);
    Assignment a(m);
    Hit hit;
    hit.cand.resize(static_cast<size_t>(k));
    size_t begin = n * static_cast<size_t>(t) / static_cast<size_t>(threads);
    size_t end = n * static_cast<size_t>(t + 1) / static_cast<size_t>(threads);
    if (begin >= end) return;
    auto lower = [&](double v) { return static_cast<size_t>(std::lower_bound(right.r.begin(), right.r.end(), v) - right.r.begin()); };
    auto upper = [&](double v) { return static_cast<size_t>(std::upper_bound(right.r.begin(), right.r.end(), v) - right.r.begin()); };
    bool report = t == 0 && opt.progress && (rows ? n * n1 : n) > 1000000;
    if (rows) {
      const auto& first = stages[0].candidates;
      const auto& second = stages[1].candidates;
      for (size_t i = begin; i < end; ++i) {
        if (report && (i - begin) % 64 == 0) opt.progress(static_cast<double>(i - begin) / static_cast<double>(end - begin));
        size_t j0 = 0;
        for (const auto& [sa, sb] : ordered)
          if (sa == 0 && sb == 1) j0 = i;
        if (j0 >= second.size()) continue;
        double x0 = first[i].r * second[j0].r;
        size_t loP = lower(wantLo(x0)), hiP = upper(wantHi(x0));
        for (size_t j = j0; j < second.size(); ++j) {
          size_t le = i * n1 + j;
          double x = first[i].r * second[j].r;
          double wl = wantLo(x), wh = wantHi(x);
          while (loP > 0 && right.r[loP - 1] >= wl) --loP;
          while (hiP > 0 && right.r[hiP - 1] > wh) --hiP;
          size_t floor = rightFloor(le);
          // The window only falls and the floor only rises along a row.
          if (hiP <= floor) break;
          visit(lo, a, hit, le, x, std::max(loP, floor), hiP);
        }
      }
      if (report) opt.progress(1.0);
      return;
    }
    size_t loP = lower(wantLo(left.r[begin])), hiP = upper(wantHi(left.r[begin]));
    for (size_t le = begin; le < end; ++le) {
      if (report && (le - begin) % 65536 == 0) opt.progress(static_cast<double>(le - begin) / static_cast<double>(end - begin));
      double x = left.r[le];
      double wl = wantLo(x), wh = wantHi(x);
      while (loP > 0 && right.r[loP - 1] >= wl) --loP;
      while (hiP > 0 && right.r[hiP - 1] > wh) --hiP;
      visit(lo, a, hit, le, x, loP, hiP);
    }
    if (report) opt.progress(1.0);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(sweep, t);
  sweep(0);
  for (auto& th : pool) th.join();
  std::vector<double> crossRemoved(cross.size(), 0);
  double inWindow = 0, duplicates = 0;
  unsigned long long count = 0, undecided = 0;
  std::vector<Hit> hits;
  for (auto& lo : locals) {
    count += lo.count;
    undecided += lo.undecided;
    inWindow += lo.inWindow;
    duplicates += lo.duplicates;
    for (size_t c = 0; c < cross.size(); ++c) crossRemoved[c] += lo.crossRemoved[c];
    for (auto& x : lo.heap) hits.push_back(std::move(x));
  }
  std::sort(hits.begin(), hits.end());
  if (hits.size() > keep) hits.resize(keep);
  std::vector<Design> designs;
  for (const auto& x : hits) {
    Design d;
    Assignment a(m);
    fill(a, x.le, x.re);
    d.choice = a.choice;
    d.ratio = exactRatio(x.le, x.re);
    d.keys = x.keys;
    for (int s = 0; s < k; ++s)
      d.undecided = d.undecided || stages[static_cast<size_t>(s)].candidates[x.cand[static_cast<size_t>(s)]].undecided;
    designs.push_back(std::move(d));
  }

  std::string windowText = windowTexts.empty() ? "ratio (no window)" : fmt::format("{}", fmt::join(windowTexts, " and "));
  // With interchangeable stages enumerated canonically, what passes the window is
  // already one design per orbit.
  if (fast && !ordered.empty()) windowText += " (interchangeable stages: one design per orbit)";
  res.funnel.push_back({windowText, "", combos, combos - inWindow});
  double before = inWindow;
  for (size_t c = 0; c < cross.size(); ++c) {
    res.funnel.push_back({cross[c]->text, "", before, crossRemoved[c]});
    before -= crossRemoved[c];
  }
  if (group.size() > 1 && !fast) res.funnel.push_back({"interchangeable: one design per orbit", "", before, duplicates});
  res.count = count;
  res.undecided = undecided;
  res.designs = std::move(designs);
  return res;
}

} // namespace gbx::rt
