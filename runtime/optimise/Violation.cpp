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

} // namespace gbx::rt
