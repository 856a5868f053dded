#include "search/Conjuncts.h"

#include <algorithm>

#include <fmt/format.h>

#include "catalogue/Settings.h"
#include "model/Deadline.h"
#include "model/Evaluator.h"

namespace gbx::rt {

using ir::Op;

namespace {

bool isGearboxRatio(const ir::QuantityRef& r) { return r.owner == ir::QuantityRef::Gearbox && r.key == Q::Ratio; }

std::optional<Rational> rationalConst(const ir::Expr& e) {
  if (e.op == Op::Const && e.type.isNumber() && e.value.isRational()) return e.value.rational();
  return std::nullopt;
}

bool isRatio(const ir::Expr& e) { return e.op == Op::Quantity && isGearboxRatio(e.ref); }

} // namespace

void dependencies(const Model& m, const ir::Expr& e, Conjunct& c, int depth) {
  if (depth > 64) return;
  int all = static_cast<int>(m.stages.size());
  switch (e.op) {
  case Op::Quantity: {
    const ir::QuantityRef& r = e.ref;
    if (r.owner == ir::QuantityRef::Gearbox) {
      for (int s = 0; s < all; ++s)
        c.stages.insert(s);
      if (!m.freedoms.empty() && r.key != Q::Ratio) c.freedom = true;
      break;
    }
    // A shaft's quantity: the stages of its gears and every stage before them (their torques
    // and speeds come down the train), solved once the candidates' cheaper rules have passed.
    if (r.owner == ir::QuantityRef::Shaft) {
      int last = -1;
      for (const auto& p : m.gearbox.shafts[static_cast<size_t>(r.index)].placed) last = std::max(last, p.stage);
      for (int s = 0; s <= (last < 0 ? all - 1 : last); ++s) {
        c.stages.insert(s);
        if (!m.stages[static_cast<size_t>(s)].freedoms.empty()) c.freedom = true;
      }
      c.strength = true;
      break;
    }
    if (r.owner != ir::QuantityRef::Stage) {
      c.unsupported = true;
      break;
    }
    int st = r.index;
    if (cat::isRatingQuantity(r.key)) c.strength = true;
    // A rating that reads the shafts reads every stage whose gears they carry.
    if (int up = m.stages[static_cast<size_t>(st)].shaftStagesUpTo; up >= 0 && cat::isRatingQuantity(r.key))
      for (int s = 0; s <= up; ++s) {
        c.stages.insert(s);
        if (!m.stages[static_cast<size_t>(s)].freedoms.empty()) c.freedom = true;
      }
    if (cat::dependsOnOperatingPoint(r.key))
      for (int s = 0; s <= st; ++s)
        c.stages.insert(s);
    c.stages.insert(st);
    if (int f = m.freedomOf(st, r.gear, r.key); f >= 0 && !m.freedoms[static_cast<size_t>(f)].solved) c.freedom = true;
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

std::string ruleText(const ir::Expr& e) {
  // `input.A.life >= 20000 h`: a bound on a quantity in the unit its column shows.
  bool compare = e.op == Op::Ge || e.op == Op::Gt || e.op == Op::Le || e.op == Op::Lt || e.op == Op::Eq;
  if (!compare || e.args.size() != 2 || !e.args[0] || !e.args[1]) return ir::print(e);
  const ir::Expr& q = *e.args[0];
  const ir::Expr& k = *e.args[1];
  // `abs(input.slope_at(hs.pinion)) <= 0.1 mrad` alike, in the quantity's unit.
  const bool absOf =
      q.op == Op::Call && q.fn == cat::Fn::Abs && q.args.size() == 1 && q.args[0] && q.args[0]->op == Op::Quantity;
  if ((q.op != Op::Quantity && !absOf) || k.op != Op::Const || !k.type.isNumber()) return ir::print(e);
  units::DisplayUnit u = displayUnitOf(absOf ? *q.args[0] : q);
  const char* op = e.op == Op::Ge ? ">=" : e.op == Op::Gt ? ">" : e.op == Op::Le ? "<=" : e.op == Op::Lt ? "<" : "==";
  std::string lhs = absOf ? fmt::format("abs({})", q.args[0]->name) : q.name;
  return fmt::format("{} {} {:g}{}", lhs, op, u.shown(k.value.toDouble()), u.name.empty() ? "" : " " + u.name);
}

void split(const ir::Expr& e, std::vector<const ir::Expr*>& out) {
  if (e.op == Op::And || e.op == Op::Forall) {
    for (const auto& a : e.args)
      split(*a, out);
    return;
  }
  out.push_back(&e);
}

std::string Window::str() const {
  return fmt::format("{}{}, {}{}", loStrict ? "(" : "[", lo ? lo->str() : "-inf", hi ? hi->str() : "inf",
                     hiStrict ? ")" : "]");
}

bool asWindow(const ir::Expr& e, Window& w) {
  auto bound = [&](const ir::Expr& x, const ir::Expr& k, bool ratioLeft) {
    auto v = rationalConst(k);
    if (!v || !isRatio(x)) return false;
    bool strict = e.op == Op::Lt || e.op == Op::Gt;
    bool upper = (e.op == Op::Lt || e.op == Op::Le) == ratioLeft;
    if (upper)
      w.upper(*v, strict);
    else
      w.lower(*v, strict);
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

Verdict decide(const Evaluator& ev, Assignment& a, const std::vector<const Conjunct*>& rules,
               const std::vector<int>& freedoms) {
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
    // Past the time limit every rule that runs a scene fails at once: undecided, not infeasible.
    if (Deadline::expired()) {
      undecided = true;
      break;
    }
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
    for (int f : freedoms)
      mid.push_back(0.5 * (box.b[static_cast<size_t>(f)].first + box.b[static_cast<size_t>(f)].second));
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
      for (size_t k = 0; k < freedoms.size(); ++k)
        a.box[static_cast<size_t>(freedoms[k])] = {p[k], p[k]};
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

} // namespace gbx::rt
