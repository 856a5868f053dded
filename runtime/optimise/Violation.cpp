#include "optimise/Violation.h"

#include <algorithm>
#include <cmath>

namespace gbx::rt {

double violation(const Evaluator& ev, const ir::Expr& e, const Assignment& a) {
  auto rel = [](double over, double scale) { return over > 0 ? over / std::max(std::fabs(scale), 1e-12) : 0.0; };
  auto num = [&](const ir::Expr& x) { return ev.eval(x, a); };
  switch (e.op) {
  case ir::Op::And:
  case ir::Op::Forall: {
    double s = 0;
    for (const auto& x : e.args)
      s += violation(ev, *x, a);
    return s;
  }
  case ir::Op::Or: {
    double s = INFINITY;
    for (const auto& x : e.args)
      s = std::min(s, violation(ev, *x, a));
    return s;
  }
  case ir::Op::Le:
  case ir::Op::Lt: {
    Value x = num(*e.args[0]), y = num(*e.args[1]);
    if (!x.isNumber() || !y.isNumber()) return 1.0;
    return rel(x.mid() - y.mid(), std::max(std::fabs(y.mid()), std::fabs(x.mid())));
  }
  case ir::Op::Ge:
  case ir::Op::Gt: {
    Value x = num(*e.args[0]), y = num(*e.args[1]);
    if (!x.isNumber() || !y.isNumber()) return 1.0;
    return rel(y.mid() - x.mid(), std::max(std::fabs(y.mid()), std::fabs(x.mid())));
  }
  case ir::Op::Within: {
    Value x = num(*e.args[0]), lo = num(*e.args[1]), hi = num(*e.args[2]);
    if (!x.isNumber() || !lo.isNumber() || !hi.isNumber()) return 1.0;
    double scale = std::max({std::fabs(lo.mid()), std::fabs(hi.mid()), std::fabs(x.mid())});
    return rel(lo.mid() - x.mid(), scale) + rel(x.mid() - hi.mid(), scale);
  }
  default: {
    Value t = ev.eval(e, a);
    return t.kind == Value::Bool && t.truth == Truth::True ? 0.0 : 1.0;
  }
  }
}

namespace {

double relative(double d, double x, double y) { return d / std::max({std::fabs(x), std::fabs(y), 1e-300}); }

// Margins of `x` inside [lo, hi]: one per side.
void inside(const Value& x, const Value& lo, const Value& hi, std::vector<double>& out) {
  if (!x.isNumber() || !lo.isNumber() || !hi.isNumber()) {
    out.insert(out.end(), {-1.0, -1.0});
    return;
  }
  out.push_back(relative(x.mid() - lo.lo, x.mid(), lo.lo));
  out.push_back(relative(hi.hi - x.mid(), x.mid(), hi.hi));
}

} // namespace

void margins(const Evaluator& ev, const ir::Expr& e, const Assignment& a, std::vector<double>& out) {
  auto num = [&](const ir::Expr& x) { return ev.eval(x, a); };
  switch (e.op) {
  case ir::Op::And:
  case ir::Op::Forall:
    for (const auto& x : e.args)
      margins(ev, *x, a, out);
    return;
  case ir::Op::Or: {
    double best = -INFINITY;
    for (const auto& x : e.args) {
      std::vector<double> part;
      margins(ev, *x, a, part);
      best = std::max(best, part.empty() ? -1.0 : *std::min_element(part.begin(), part.end()));
    }
    out.push_back(best);
    return;
  }
  case ir::Op::Le:
  case ir::Op::Lt:
  case ir::Op::Ge:
  case ir::Op::Gt: {
    Value x = num(*e.args[0]), y = num(*e.args[1]);
    if (!x.isNumber() || !y.isNumber()) {
      out.push_back(-1.0);
      return;
    }
    double d = e.op == ir::Op::Le || e.op == ir::Op::Lt ? y.mid() - x.mid() : x.mid() - y.mid();
    out.push_back(relative(d, x.mid(), y.mid()));
    return;
  }
  case ir::Op::Within: inside(num(*e.args[0]), num(*e.args[1]), num(*e.args[2]), out); return;
  case ir::Op::Eq: {
    // `x == c +- t` tests membership of an interval; `x == y` of a point.
    Value x = num(*e.args[0]), y = num(*e.args[1]);
    if (y.isNumber() && y.lo < y.hi) {
      inside(x, Value::number(y.lo), Value::number(y.hi), out);
      return;
    }
    if (x.isNumber() && y.isNumber()) {
      out.push_back(-relative(std::fabs(x.mid() - y.mid()), x.mid(), y.mid()));
      return;
    }
    break;
  }
  default: break;
  }
  Value t = ev.eval(e, a);
  out.push_back(t.kind == Value::Bool && t.truth == Truth::True ? 1.0 : -1.0);
}

} // namespace gbx::rt
