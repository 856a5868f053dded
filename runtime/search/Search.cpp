#include "search/Search.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <thread>
#include <unordered_set>

#include <fmt/format.h>

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
};

bool operatingDependent(const std::string& q) {
  static const std::set<std::string> names = {"input_speed",  "output_speed",     "input_torque",        "output_torque",
                                              "mesh_frequency", "carrier_speed",  "pitch_line_velocity", "tangential_force",
                                              "load_deflection", "speed",         "torque"};
  auto d = q.rfind('.');
  return names.count(d == std::string::npos ? q : q.substr(d + 1)) > 0;
}

void dependencies(const Model& m, const ir::Expr& e, Conjunct& c, int depth = 0) {
  if (depth > 64) return;
  int all = static_cast<int>(m.stages.size());
  switch (e.op) {
  case Op::Quantity: {
    auto dot = e.name.find('.');
    if (dot == std::string::npos) {
      for (int s = 0; s < all; ++s) c.stages.insert(s);
      for (const auto& f : m.freedoms) (void)f, c.freedom = c.freedom || e.name != "ratio";
      break;
    }
    int st = m.stageIndex(e.name.substr(0, dot));
    if (st < 0) {
      c.unsupported = true;
      break;
    }
    std::string rest = e.name.substr(dot + 1);
    if (operatingDependent(rest))
      for (int s = 0; s <= st; ++s) c.stages.insert(s);
    c.stages.insert(st);
    if (m.freedomOf(st, rest) >= 0) c.freedom = true;
    const ir::Attribute* a = m.attribute(st, rest);
    if (!a && !m.stages[static_cast<size_t>(st)].freedoms.empty() && rest != "ratio") c.freedom = true;
    if (a && a->value && a->role != ir::Attribute::Decision) dependencies(m, *a->value, c, depth + 1);
    break;
  }
  case Op::Let:
    for (const auto& l : m.gearbox.lets)
      if (l.name == e.name && l.expr) dependencies(m, *l.expr, c, depth + 1);
    break;
  case Op::SceneOutput:
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

bool isRatio(const ir::Expr& e) { return e.op == Op::Quantity && e.name == "ratio"; }

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
      if (t.name == "relative") {
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

Truth implicit(bool b) { return b ? Truth::True : Truth::False; }

std::vector<StageRule> implicitRules(const Model& m, int s) {
  std::vector<StageRule> rules;
  const ir::Stage& st = *m.stages[static_cast<size_t>(s)].ir;
  auto z = [s](const Evaluator& ev, const Assignment& a, const char* g) { return ev.attribute(s, std::string(g) + ".z", a); };
  auto cmp = [](const Value& x, const Value& y) { return arith::less(y, x, false); };
  switch (st.kind) {
  case ir::StageKind::Planetary:
    rules.push_back({"concentric: ring.z == sun.z + 2 * planet.z", [=](const Evaluator& ev, const Assignment& a) {
                       Value want = arith::add(z(ev, a, "sun"), arith::mul(Value::rational(Rational(2)), z(ev, a, "planet")));
                       return arith::equal(z(ev, a, "ring"), want);
                     }});
    rules.push_back({"assembly: (sun.z + ring.z) / planets is whole", [=](const Evaluator& ev, const Assignment& a) {
                       Value q = arith::div(arith::add(z(ev, a, "sun"), z(ev, a, "ring")), ev.attribute(s, "planets", a));
                       if (!q.exact) return Truth::Unknown;
                       return implicit(q.exact->isInteger());
                     }});
    rules.push_back({"adjacency: (sun.z + planet.z) * sin(pi / planets) > planet.z + 2", [=](const Evaluator& ev, const Assignment& a) {
                       Value n = ev.attribute(s, "planets", a);
                       if (!n.isPoint()) return Truth::Unknown;
                       double lhs = (z(ev, a, "sun").lo + z(ev, a, "planet").lo) * std::sin(M_PI / n.lo);
                       return implicit(lhs > z(ev, a, "planet").lo + 2.0);
                     }});
    break;
  case ir::StageKind::Idler:
    rules.push_back({"reduction: driven.z > driver.z",
                     [=](const Evaluator& ev, const Assignment& a) { return cmp(z(ev, a, "driven"), z(ev, a, "driver")); }});
    break;
  default:
    rules.push_back({"reduction: wheel.z > pinion.z",
                     [=](const Evaluator& ev, const Assignment& a) { return cmp(z(ev, a, "wheel"), z(ev, a, "pinion")); }});
  }
  return rules;
}

struct StageResult {
  std::vector<Candidate> candidates;
  std::vector<FunnelStep> funnel;
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
    std::vector<double> removed;
    double jointRemoved = 0;
  };
  int threads = std::max(1, std::min<int>(jobs, static_cast<int>(total / 2048) + 1));
  std::vector<Chunk> chunks(static_cast<size_t>(threads));
  auto work = [&](int t) {
    Chunk& ch = chunks[static_cast<size_t>(t)];
    ch.removed.assign(rules.size(), 0);
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
            ch.removed[r] += 1;  // cannot be evaluated: reported as an error by the caller
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
      Value r = ev.derived(s, "ratio", a);
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
  res.funnel.push_back({"domain", name, 0, -before});
  for (size_t r = 0; r < rules.size(); ++r) {
    double removed = 0;
    for (const auto& ch : chunks) removed += ch.removed[r];
    res.funnel.push_back({rules[r].text, name, before, removed});
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

} // namespace

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
      res.errors.push_back(fmt::format("rule `{}` needs results the search does not compute (scenes, splits, baselines)", c.text));
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
  for (const auto& o : m.gearbox.objectives) {
    Conjunct c;
    if (o.expr) dependencies(m, *o.expr, c);
    if (c.unsupported) res.errors.push_back(fmt::format("objective `{}` needs results the search does not compute (scenes, baselines)", o.text));
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
      std::string px = x.find('.') == std::string::npos ? "" : x.substr(x.find('.') + 1) + ".";
      std::string py = y.find('.') == std::string::npos ? "" : y.substr(y.find('.') + 1) + ".";
      if (!px.empty()) stageSwapsOnly = false;
      for (int sa : m.stages[static_cast<size_t>(a)].slots) {
        const std::string& attr = m.slots[static_cast<size_t>(sa)].attr;
        if (attr.rfind(px, 0) != 0) continue;
        int sb = m.slotOf(b, py + attr.substr(px.size()));
        if (sb < 0) {
          res.errors.push_back(fmt::format("`interchangeable {}, {}`: `{}` has no decision `{}` to match `{}.{}`", x, y, sy,
                                           py + attr.substr(px.size()), sx, attr));
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

  // Meet in the middle over sorted stage ratios: left stages [0, h), right [h, k).
  int h = k / 2;
  struct Half {
    std::vector<std::uint32_t> idx;  // width entries per tuple
    std::vector<Rational> ratio;
    std::vector<double> r;
    std::vector<std::uint32_t> order;
    int width = 0;
  };
  auto build = [&](int from, int to) {
    Half half;
    half.width = to - from;
    std::vector<std::uint32_t> cur(static_cast<size_t>(half.width));
    std::function<void(int, Rational, double)> rec = [&](int s, Rational q, double d) {
      if (s == to) {
        half.idx.insert(half.idx.end(), cur.begin(), cur.end());
        half.ratio.push_back(q);
        half.r.push_back(d);
        return;
      }
      const auto& list = stages[static_cast<size_t>(s)].candidates;
      std::uint32_t start = 0;
      for (const auto& [a, b] : ordered)
        if (b == s && a >= from) start = std::max(start, cur[static_cast<size_t>(a - from)]);
      for (std::uint32_t i = start; i < list.size(); ++i) {
        cur[static_cast<size_t>(s - from)] = i;
        auto nq = q.mul(list[i].ratio);
        rec(s + 1, nq ? *nq : q, d * list[i].r);
      }
    };
    rec(from, Rational(1), 1.0);
    half.order.resize(half.r.size());
    for (std::uint32_t i = 0; i < half.order.size(); ++i) half.order[i] = i;
    std::sort(half.order.begin(), half.order.end(), [&](std::uint32_t x, std::uint32_t y) { return half.r[x] < half.r[y]; });
    return half;
  };
  double combos = 1;
  for (const auto& st : stages) combos *= static_cast<double>(st.candidates.size());
  Half left = build(0, h), right = build(h, k);

  // Candidates' slot values laid into a full assignment.
  auto fill = [&](Assignment& a, const Half& L, std::uint32_t li, const Half& R, std::uint32_t ri) {
    for (int s = 0; s < k; ++s) {
      const Half& H = s < h ? L : R;
      std::uint32_t t = s < h ? li : ri;
      int off = s < h ? s : s - h;
      const Candidate& c = stages[static_cast<size_t>(s)].candidates[H.idx[static_cast<size_t>(t) * static_cast<size_t>(H.width) + static_cast<size_t>(off)]];
      const auto& slots = m.stages[static_cast<size_t>(s)].slots;
      for (size_t j = 0; j < slots.size(); ++j) a.choice[static_cast<size_t>(slots[j])] = c.idx[j];
    }
  };
  auto undecidedOf = [&](const Half& L, std::uint32_t li, const Half& R, std::uint32_t ri) {
    for (int s = 0; s < k; ++s) {
      const Half& H = s < h ? L : R;
      std::uint32_t t = s < h ? li : ri;
      int off = s < h ? s : s - h;
      if (stages[static_cast<size_t>(s)].candidates[H.idx[static_cast<size_t>(t) * static_cast<size_t>(H.width) + static_cast<size_t>(off)]].undecided)
        return true;
    }
    return false;
  };

  // Objectives: minimised keys. Objectives over the ratio alone are evaluated from the
  // exact ratio without touching the stages.
  auto keysOf = [&](const Assignment& a) {
    std::vector<double> keys;
    if (opt.sortBy) {
      Value v = ev.eval(*opt.sortBy, a);
      keys.push_back(v.isNumber() ? v.lo : INFINITY);
    }
    for (const auto& o : m.gearbox.objectives) {
      Value v = o.expr ? ev.eval(*o.expr, a) : Value::invalid();
      // Over a freedom the best attainable value counts: the design may choose it.
      keys.push_back(v.isNumber() ? (o.minimize ? v.lo : -v.hi) : INFINITY);
    }
    return keys;
  };

  // Per-stage membership, for checking the images of a design under the group.
  std::vector<std::set<std::vector<int>>> members(static_cast<size_t>(k));
  if (!fast && group.size() > 1)
    for (int s = 0; s < k; ++s)
      for (const auto& c : stages[static_cast<size_t>(s)].candidates) members[static_cast<size_t>(s)].insert(c.idx);

  std::vector<double> crossRemoved(cross.size(), 0);
  double inWindow = 0, duplicates = 0;
  std::vector<Design> designs;
  unsigned long long count = 0, undecided = 0;

  auto valueOf = [&](int slot, int c) { return m.slots[static_cast<size_t>(slot)].values[static_cast<size_t>(c)]; };
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
    Value r = ev.gearboxQuantity("ratio", a);
    if (!r.exact || !window.contains(*r.exact)) return false;
    for (const auto* c : cross)
      if (truthOf(ev.eval(*c->expr, a)) == Truth::False) return false;
    return true;
  };
  // Orders designs by the ratios of their stages, then by their values.
  auto less = [&](const std::vector<int>& x, const std::vector<int>& y) {
    Assignment ax(m), ay(m);
    ax.choice = x;
    ay.choice = y;
    for (int s = 0; s < k; ++s) {
      Value rx = ev.derived(s, "ratio", ax), ry = ev.derived(s, "ratio", ay);
      if (rx.exact && ry.exact && *rx.exact != *ry.exact) return *rx.exact < *ry.exact;
      for (int sl : m.stages[static_cast<size_t>(s)].slots) {
        const Value &vx = valueOf(sl, x[static_cast<size_t>(sl)]), &vy = valueOf(sl, y[static_cast<size_t>(sl)]);
        if (vx.lo != vy.lo) return vx.lo < vy.lo;
      }
    }
    return false;
  };

  const double eps = 1e-12;
  size_t n = left.order.size();
  int threads = std::max(1, std::min<int>(opt.jobs, static_cast<int>(n / 256) + 1));
  struct Local {
    std::vector<Design> designs;
    unsigned long long count = 0, undecided = 0;
    double inWindow = 0, duplicates = 0;
    std::vector<double> crossRemoved;
  };
  std::vector<Local> locals(static_cast<size_t>(threads));
  size_t keep = opt.top ? static_cast<size_t>(*opt.top) : SIZE_MAX;
  auto rankLess = [&](const Design& x, const Design& y) {
    if (x.keys != y.keys) return x.keys < y.keys;
    return less(x.choice, y.choice);
  };
  auto sweep = [&](int t) {
    Local& lo = locals[static_cast<size_t>(t)];
    lo.crossRemoved.assign(cross.size(), 0);
    Assignment a(m);
    size_t begin = n * static_cast<size_t>(t) / static_cast<size_t>(threads);
    size_t end = n * static_cast<size_t>(t + 1) / static_cast<size_t>(threads);
    size_t rn = right.order.size();
    for (size_t li = begin; li < end; ++li) {
      std::uint32_t L = left.order[li];
      double x = left.r[L];
      // Double bounds widened by eps; every match is then confirmed exactly.
      double want_lo = window.lo ? window.lo->toDouble() / x * (1 - eps) : -INFINITY;
      double want_hi = window.hi ? window.hi->toDouble() / x * (1 + eps) : INFINITY;
      size_t from = static_cast<size_t>(std::lower_bound(right.order.begin(), right.order.end(), want_lo,
                                                         [&](std::uint32_t i, double v) { return right.r[i] < v; }) -
                                        right.order.begin());
      for (size_t ri = from; ri < rn; ++ri) {
        std::uint32_t R = right.order[ri];
        if (right.r[R] > want_hi) break;
        auto q = left.ratio[L].mul(right.ratio[R]);
        if (!q || !window.contains(*q)) continue;
        bool canonical = true;
        for (const auto& [sa, sb] : ordered)
          if (sa < h && sb >= h &&
              left.idx[static_cast<size_t>(L) * static_cast<size_t>(left.width) + static_cast<size_t>(sa)] >
                  right.idx[static_cast<size_t>(R) * static_cast<size_t>(right.width) + static_cast<size_t>(sb - h)])
            canonical = false;
        if (!canonical) continue;
        lo.inWindow += 1;
        fill(a, left, L, right, R);
        bool ok = true;
        for (size_t c = 0; c < cross.size() && ok; ++c)
          if (truthOf(ev.eval(*cross[c]->expr, a)) == Truth::False) {
            lo.crossRemoved[c] += 1;
            ok = false;
          }
        if (!ok) continue;
        if (!fast && group.size() > 1) {
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
        Design d;
        d.choice = a.choice;
        d.ratio = *q;
        d.undecided = undecidedOf(left, L, right, R);
        lo.count += 1;
        lo.undecided += d.undecided;
        if (keep == 0) continue;
        a.ratio = *q;
        d.keys = keysOf(a);
        a.ratio.reset();
        lo.designs.push_back(std::move(d));
        // Bounded memory: keep twice the designs asked for, trimmed to the best.
        if (lo.designs.size() >= 2 * keep + 1024 && keep != SIZE_MAX) {
          std::nth_element(lo.designs.begin(), lo.designs.begin() + static_cast<long>(keep), lo.designs.end(), rankLess);
          lo.designs.resize(keep);
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(sweep, t);
  sweep(0);
  for (auto& th : pool) th.join();
  for (auto& lo : locals) {
    count += lo.count;
    undecided += lo.undecided;
    inWindow += lo.inWindow;
    duplicates += lo.duplicates;
    for (size_t c = 0; c < cross.size(); ++c) crossRemoved[c] += lo.crossRemoved[c];
    for (auto& d : lo.designs) designs.push_back(std::move(d));
  }
  std::sort(designs.begin(), designs.end(), rankLess);
  if (designs.size() > keep) designs.resize(keep);

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
