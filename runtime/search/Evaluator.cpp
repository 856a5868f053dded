#include "search/Evaluator.h"

#include "loadshare/LoadShare.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace gbx::rt {

namespace arith {

namespace {
double down(double x) { return std::nextafter(x, -INFINITY); }
double up(double x) { return std::nextafter(x, INFINITY); }
Value widen(double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi)) return Value::invalid();
  return lo == hi ? Value::number(lo) : Value::range(down(lo), up(hi));
}
} // namespace

Value add(const Value& a, const Value& b) {
  if (!a.isNumber() || !b.isNumber()) return Value::invalid();
  if (a.exact && b.exact)
    if (auto r = a.exact->add(*b.exact)) return Value::rational(*r);
  if (a.isPoint() && b.isPoint()) return Value::number(a.lo + b.lo);
  return widen(a.lo + b.lo, a.hi + b.hi);
}

Value neg(const Value& a) {
  if (!a.isNumber()) return Value::invalid();
  if (a.exact) return Value::rational(a.exact->neg());
  Value v = Value::range(-a.hi, -a.lo);
  return v;
}

Value sub(const Value& a, const Value& b) { return add(a, neg(b)); }

Value mul(const Value& a, const Value& b) {
  if (!a.isNumber() || !b.isNumber()) return Value::invalid();
  if (a.exact && b.exact)
    if (auto r = a.exact->mul(*b.exact)) return Value::rational(*r);
  if (a.isPoint() && b.isPoint()) return Value::number(a.lo * b.lo);
  double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return widen(*std::min_element(p, p + 4), *std::max_element(p, p + 4));
}

Value div(const Value& a, const Value& b) {
  if (!a.isNumber() || !b.isNumber()) return Value::invalid();
  if (a.exact && b.exact && !b.exact->isZero())
    if (auto r = a.exact->div(*b.exact)) return Value::rational(*r);
  if (b.lo <= 0 && b.hi >= 0) return Value::invalid();
  if (a.isPoint() && b.isPoint()) return Value::number(a.lo / b.lo);
  double p[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  return widen(*std::min_element(p, p + 4), *std::max_element(p, p + 4));
}

Value powi(const Value& a, int k) {
  if (!a.isNumber()) return Value::invalid();
  if (a.exact)
    if (auto r = a.exact->pow(k)) return Value::rational(*r);
  if (a.isPoint()) return Value::number(std::pow(a.lo, k));
  double x = std::pow(a.lo, k), y = std::pow(a.hi, k);
  double lo = std::min(x, y), hi = std::max(x, y);
  if (k % 2 == 0 && k > 0 && a.lo < 0 && a.hi > 0) lo = 0;
  return widen(lo, hi);
}

Truth less(const Value& a, const Value& b, bool orEqual) {
  if (!a.isNumber() || !b.isNumber()) return Truth::Unknown;
  if (a.exact && b.exact) {
    int c = a.exact->compare(*b.exact);
    return (orEqual ? c <= 0 : c < 0) ? Truth::True : Truth::False;
  }
  if (a.isPoint() && b.isPoint()) return (orEqual ? a.lo <= b.lo : a.lo < b.lo) ? Truth::True : Truth::False;
  if (orEqual ? a.hi <= b.lo : a.hi < b.lo) return Truth::True;
  if (orEqual ? a.lo > b.hi : a.lo >= b.hi) return Truth::False;
  return Truth::Unknown;
}

Truth equal(const Value& a, const Value& b) {
  if (!a.isNumber() || !b.isNumber()) return Truth::Unknown;
  if (a.exact && b.exact) return *a.exact == *b.exact ? Truth::True : Truth::False;
  if (a.isPoint() && b.isPoint()) return a.lo == b.lo ? Truth::True : Truth::False;
  if (a.hi < b.lo || b.hi < a.lo) return Truth::False;
  return Truth::Unknown;
}

Truth land(Truth a, Truth b) {
  if (a == Truth::False || b == Truth::False) return Truth::False;
  if (a == Truth::True && b == Truth::True) return Truth::True;
  return Truth::Unknown;
}
Truth lor(Truth a, Truth b) {
  if (a == Truth::True || b == Truth::True) return Truth::True;
  if (a == Truth::False && b == Truth::False) return Truth::False;
  return Truth::Unknown;
}
Truth lnot(Truth a) { return a == Truth::True ? Truth::False : a == Truth::False ? Truth::True : Truth::Unknown; }

} // namespace arith

namespace {

Value constant(const units::Number& n) {
  if (n.isRational()) return Value::rational(n.rational());
  return Value::number(n.toDouble());
}

// The interval [c - t, c + t] of a tolerance, or [c(1 - t), c(1 + t)] when relative.
std::pair<Value, Value> toleranceBounds(const Value& c, const Value& t, bool relative) {
  if (relative) {
    Value one = Value::rational(Rational(1));
    return {arith::mul(c, arith::sub(one, t)), arith::mul(c, arith::add(one, t))};
  }
  return {arith::sub(c, t), arith::add(c, t)};
}

Truth within(const Value& x, const Value& lo, const Value& hi) {
  return arith::land(arith::less(lo, x, true), arith::less(x, hi, true));
}

} // namespace

Value Evaluator::eval(const ir::Expr& e, const Assignment& a) const {
  using ir::Op;
  auto arg = [&](size_t i) { return eval(*e.args[i], a); };
  switch (e.op) {
  case Op::Const:
    if (e.type.kind == ir::Type::Bool) return Value::boolean(!e.value.isZero());
    return constant(e.value);
  case Op::Quantity: return quantity(e.name, a);
  case Op::Let:
    for (const auto& l : m_.gearbox.lets)
      if (l.name == e.name && l.expr) {
        if (++depth_ > 64) {
          --depth_;
          return Value::invalid();
        }
        Value v = eval(*l.expr, a);
        --depth_;
        return v;
      }
    return Value::invalid();
  case Op::Symbol: return Value::invalid();
  case Op::Neg: return arith::neg(arg(0));
  case Op::Add: return arith::add(arg(0), arg(1));
  case Op::Sub: return arith::sub(arg(0), arg(1));
  case Op::Mul: return arith::mul(arg(0), arg(1));
  case Op::Div: return arith::div(arg(0), arg(1));
  case Op::Pow: {
    Value b = arg(0), x = arg(1);
    if (x.exact && x.exact->isInteger()) return arith::powi(b, static_cast<int>(x.exact->num()));
    if (!b.isNumber() || !x.isNumber() || b.lo <= 0) return Value::invalid();
    return arith::corners({b, x}, [](const std::vector<double>& v) { return std::pow(v[0], v[1]); });
  }
  case Op::Eq:
  case Op::Ne: {
    Value x = arg(0);
    Truth t;
    if (e.args[1]->op == Op::Tol) {
      const auto& tol = *e.args[1];
      auto [lo, hi] = toleranceBounds(eval(*tol.args[0], a), eval(*tol.args[1], a), tol.name == "relative");
      t = within(x, lo, hi);
    } else {
      t = arith::equal(x, arg(1));
    }
    return Value::boolean(e.op == Op::Eq ? t : arith::lnot(t));
  }
  case Op::Lt: return Value::boolean(arith::less(arg(0), arg(1), false));
  case Op::Le: return Value::boolean(arith::less(arg(0), arg(1), true));
  case Op::Gt: return Value::boolean(arith::less(arg(1), arg(0), false));
  case Op::Ge: return Value::boolean(arith::less(arg(1), arg(0), true));
  case Op::Within: return Value::boolean(within(arg(0), arg(1), arg(2)));
  case Op::InSet: {
    Value x = arg(0);
    Truth t = Truth::False;
    for (size_t i = 1; i < e.args.size(); ++i) t = arith::lor(t, arith::equal(x, arg(i)));
    return Value::boolean(t);
  }
  case Op::And:
  case Op::Forall: {
    Truth t = Truth::True;
    for (size_t i = 0; i < e.args.size() && t != Truth::False; ++i) {
      Value v = arg(i);
      t = arith::land(t, v.kind == Value::Bool ? v.truth : Truth::Unknown);
    }
    return Value::boolean(t);
  }
  case Op::Or: {
    Value x = arg(0);
    if (x.kind == Value::Bool && x.truth == Truth::True) return x;
    Value y = arg(1);
    return Value::boolean(arith::lor(x.kind == Value::Bool ? x.truth : Truth::Unknown,
                                     y.kind == Value::Bool ? y.truth : Truth::Unknown));
  }
  case Op::Not: {
    Value x = arg(0);
    return Value::boolean(x.kind == Value::Bool ? arith::lnot(x.truth) : Truth::Unknown);
  }
  case Op::Call: return call(e, a);
  case Op::SceneOutput: return sceneOutput ? sceneOutput(e, a) : Value::invalid();
  case Op::Relative: {
    if (!baseline) return Value::invalid();
    Value base = baseline(*e.args[0]);
    return arith::div(arg(0), base);
  }
  default: return Value::invalid();  // Tol and Set stand only inside comparisons
  }
}

Value Evaluator::call(const ir::Expr& e, const Assignment& a) const {
  const std::string& f = e.name;
  if ((f == "mean" || f == "min" || f == "max") && e.args.size() == 1 && e.args[0]->type.kind == ir::Type::PerGear)
    return perGearReduce(e, a, f);
  std::vector<Value> v;
  for (const auto& x : e.args) v.push_back(eval(*x, a));
  for (const auto& x : v)
    if (x.kind == Value::Invalid) return Value::invalid();
  auto integerOf = [](const Value& x, long long& out) {
    if (!x.exact || !x.exact->isInteger()) return false;
    out = static_cast<long long>(x.exact->num());
    return true;
  };
  if (f == "coprime" || f == "gcd") {
    long long p, q;
    if (!integerOf(v[0], p) || !integerOf(v[1], q)) return Value::invalid();
    long long g = std::gcd(p, q);
    return f == "coprime" ? Value::boolean(g == 1) : Value::rational(Rational(g));
  }
  if (f == "abs") {
    const Value& x = v[0];
    if (x.exact) return Value::rational(x.exact->abs());
    if (x.lo >= 0) return x;
    if (x.hi <= 0) return arith::neg(x);
    return Value::range(0, std::max(-x.lo, x.hi));
  }
  if (f == "min" || f == "max") {
    if (v.size() == 1 && e.args[0]->type.kind == ir::Type::PerGear) return perGearReduce(e, a, f);
    if (v.size() == 1) return v[0];
    Value best = v[0];
    for (size_t i = 1; i < v.size(); ++i) {
      const Value& x = v[i];
      if (best.exact && x.exact) {
        bool take = f == "min" ? *x.exact < *best.exact : *x.exact > *best.exact;
        if (take) best = x;
        continue;
      }
      best = f == "min" ? Value::range(std::min(best.lo, x.lo), std::min(best.hi, x.hi))
                        : Value::range(std::max(best.lo, x.lo), std::max(best.hi, x.hi));
    }
    return best;
  }
  if (f == "mean") {
    Value s = v[0];
    if (v.size() == 1 && e.args[0]->type.kind == ir::Type::PerGear) return perGearReduce(e, a, "mean");
    for (size_t i = 1; i < v.size(); ++i) s = arith::add(s, v[i]);
    return arith::div(s, Value::rational(Rational(static_cast<std::int64_t>(v.size()))));
  }
  if (f == "round") {
    const Value& x = v[0];
    const Value& step = v[1];
    if (x.exact && step.exact && !step.exact->isZero()) {
      auto q = x.exact->div(*step.exact);
      if (q) {
        // Half away from zero, as engineers round a relief to the next 10 µm.
        auto twice = q->mul(Rational(2));
        if (twice) {
          units::i128 n = twice->num(), d = twice->den();
          units::i128 r = (n >= 0 ? (n + d) / (2 * d) : -((-n + d) / (2 * d)));
          if (auto out = Rational::make(r, 1).mul(*step.exact)) return Value::rational(*out);
        }
      }
    }
    return arith::corners({x, step}, [](const std::vector<double>& y) { return std::round(y[0] / y[1]) * y[1]; });
  }
  auto unary = [&](double (*fn)(double)) { return arith::corners({v[0]}, [fn](const std::vector<double>& y) { return fn(y[0]); }); };
  if (f == "sqrt") return v[0].lo < 0 ? Value::invalid() : unary([](double x) { return std::sqrt(x); });
  if (f == "exp") return unary([](double x) { return std::exp(x); });
  if (f == "log") return v[0].lo <= 0 ? Value::invalid() : unary([](double x) { return std::log(x); });
  if (f == "floor" || f == "ceil") {
    if (v[0].exact) {
      units::i128 n = v[0].exact->num(), d = v[0].exact->den();
      units::i128 q = n / d;
      if (f == "floor" && n < 0 && q * d != n) --q;
      if (f == "ceil" && n > 0 && q * d != n) ++q;
      return Value::rational(Rational::make(q, 1));
    }
    return unary(f == "floor" ? static_cast<double (*)(double)>(std::floor) : static_cast<double (*)(double)>(std::ceil));
  }
  if (f == "atan") return unary([](double x) { return std::atan(x); });
  if (f == "asin" || f == "acos") {
    if (v[0].lo < -1 || v[0].hi > 1) return Value::invalid();
    return f == "asin" ? unary([](double x) { return std::asin(x); }) : unary([](double x) { return std::acos(x); });
  }
  if (f == "atan2") {
    if (v[1].lo <= 0 && !v[1].isPoint()) return Value::invalid();
    return arith::corners(v, [](const std::vector<double>& y) { return std::atan2(y[0], y[1]); });
  }
  if (f == "sin" || f == "cos" || f == "tan") {
    const Value& x = v[0];
    if (x.isPoint()) return Value::number(f == "sin" ? std::sin(x.lo) : f == "cos" ? std::cos(x.lo) : std::tan(x.lo));
    // Monotone pieces: include an extremum wherever the interval crosses one.
    double (*fn)(double) = f == "sin" ? static_cast<double (*)(double)>(std::sin)
                           : f == "cos" ? static_cast<double (*)(double)>(std::cos)
                                        : static_cast<double (*)(double)>(std::tan);
    double lo = std::min(fn(x.lo), fn(x.hi)), hi = std::max(fn(x.lo), fn(x.hi));
    double phase = f == "sin" ? M_PI / 2 : 0.0;
    if (f == "tan") {
      double k = std::ceil((x.lo - M_PI / 2) / M_PI);
      if (M_PI / 2 + k * M_PI <= x.hi) return Value::invalid();
    } else {
      for (double k = std::ceil((x.lo - phase) / M_PI); phase + k * M_PI <= x.hi; k += 1) {
        double ext = fn(phase + k * M_PI);
        lo = std::min(lo, ext);
        hi = std::max(hi, ext);
      }
    }
    return Value::range(std::nextafter(lo, -INFINITY), std::nextafter(hi, INFINITY));
  }
  return Value::invalid();
}

const Value* Evaluator::overridden(const std::string& path) const {
  auto it = overrides_.find(path);
  return it == overrides_.end() ? nullptr : &it->second;
}

Value Evaluator::quantity(const std::string& path, const Assignment& a) const {
  if (const Value* v = overridden(path)) return *v;
  auto dot = path.find('.');
  if (dot == std::string::npos) return gearboxQuantity(path, a);
  int st = m_.stageIndex(path.substr(0, dot));
  if (st < 0) {
    // A split: its settings and its results.
    std::string owner = path.substr(0, dot), rest = path.substr(dot + 1);
    for (const auto& sp : m_.gearbox.splits) {
      if (sp.name != owner) continue;
      if (const ir::Setting* s = ir::findSetting(sp.settings, rest)) return s->value ? constant(*s->value) : Value::invalid();
      if (rest == "install") return Value::invalid();
      auto r = computeSplit(*this, sp, a);
      if (!r) return Value::invalid();
      if (rest == "twist") return Value::number(r->twist);
      if (rest == "displacement") return Value::number(r->displacement);
      if (rest == "imbalance") return Value::number(r->imbalance);
      if (rest == "branch_torque") return Value::number(r->branchTorque);
      if (rest == "preload_displacement") return Value::number(r->preloadDisplacement);
    }
    return Value::invalid();  // materials: not search quantities
  }
  std::string rest = path.substr(dot + 1);
  if (m_.attribute(st, rest) || m_.slotOf(st, rest) >= 0) return attribute(st, rest, a);
  return derived(st, rest, a);
}

Value Evaluator::attribute(int stage, const std::string& name, const Assignment& a) const {
  if (!overrides_.empty())
    if (const Value* v = overridden(m_.stages[static_cast<size_t>(stage)].ir->name + "." + name)) return *v;
  int s = m_.slotOf(stage, name);
  if (s >= 0) {
    int c = a.choice[static_cast<size_t>(s)];
    if (c < 0) return Value::invalid();
    return m_.slots[static_cast<size_t>(s)].values[static_cast<size_t>(c)];
  }
  int f = m_.freedomOf(stage, name);
  if (f >= 0) {
    auto [lo, hi] = a.box[static_cast<size_t>(f)];
    return lo == hi ? Value::number(lo) : Value::range(lo, hi);
  }
  const ir::Attribute* attr = m_.attribute(stage, name);
  if (!attr || !attr->value) return derived(stage, name, a);
  if (++depth_ > 64) {
    --depth_;
    return Value::invalid();
  }
  Value v = eval(*attr->value, a);
  --depth_;
  return v;
}

Value Evaluator::ratioProduct(int from, int to, const Assignment& a) const {
  Value r = Value::rational(Rational(1));
  for (int s = from; s < to; ++s) r = arith::mul(r, derived(s, "ratio", a));
  return r;
}

// A per-gear expression (`pitch_deviation`, `bending_deflection + torsion_deflection`)
// evaluated for one gear: its per-gear quantities name that gear.
Value Evaluator::perGear(const ir::Expr& e, const std::string& gear, const Assignment& a) const {
  if (e.op == ir::Op::Quantity && e.type.kind == ir::Type::PerGear) {
    auto dot = e.name.find('.');
    return quantity(e.name.substr(0, dot) + "." + gear + e.name.substr(dot), a);
  }
  if (e.type.kind != ir::Type::PerGear) return eval(e, a);
  switch (e.op) {
  case ir::Op::Add: return arith::add(perGear(*e.args[0], gear, a), perGear(*e.args[1], gear, a));
  case ir::Op::Sub: return arith::sub(perGear(*e.args[0], gear, a), perGear(*e.args[1], gear, a));
  default: return Value::invalid();
  }
}

Value Evaluator::perGearReduce(const ir::Expr& call, const Assignment& a, const std::string& f) const {
  // The stage of the quantity: the first part of any per-gear name inside.
  std::string stage;
  std::function<void(const ir::Expr&)> find = [&](const ir::Expr& x) {
    if (x.op == ir::Op::Quantity && x.type.kind == ir::Type::PerGear && stage.empty()) stage = x.name.substr(0, x.name.find('.'));
    for (const auto& c : x.args)
      if (c) find(*c);
  };
  find(*call.args[0]);
  int st = m_.stageIndex(stage);
  if (st < 0) return Value::invalid();
  std::vector<Value> vals;
  for (const auto& g : m_.stages[static_cast<size_t>(st)].ir->gears) {
    vals.push_back(perGear(*call.args[0], g, a));
    if (!vals.back().isNumber()) return Value::invalid();
  }
  Value out = vals[0];
  for (size_t i = 1; i < vals.size(); ++i) {
    if (f == "mean") out = arith::add(out, vals[i]);
    else if (f == "max") out = arith::less(out, vals[i], false) == Truth::True ? vals[i] : out;
    else out = arith::less(vals[i], out, false) == Truth::True ? vals[i] : out;
  }
  if (f == "mean") out = arith::div(out, Value::rational(Rational(static_cast<std::int64_t>(vals.size()))));
  return out;
}

Value Evaluator::gearboxQuantity(const std::string& name, const Assignment& a) const {
  int n = static_cast<int>(m_.stages.size());
  if (name == "ratio") {
    if (a.ratio) return Value::rational(*a.ratio);
    if (a.ratioApprox) return Value::number(*a.ratioApprox);
    return ratioProduct(0, n, a);
  }
  Value total = ratioProduct(0, n, a);
  // A swept load (power, input or output torque) replaces whichever load `operating` gives.
  bool loadSwept = overridden("power") || overridden("input_torque") || overridden("output_torque");
  auto op = [&](const char* k) -> std::optional<Value> {
    if (const Value* v = overridden(k)) return *v;
    std::string key = k;
    if (loadSwept && (key == "power" || key == "input_torque" || key == "output_torque")) return std::nullopt;
    if (auto v = m_.operating(k)) return Value::number(*v);
    return std::nullopt;
  };
  Value inSpeed = Value::invalid();
  if (auto v = op("input_speed")) inSpeed = *v;
  else if (auto w = op("output_speed")) inSpeed = arith::mul(*w, total);
  if (name == "input_speed") return inSpeed;
  if (name == "output_speed") return arith::div(inSpeed, total);
  Value inTorque = Value::invalid();
  if (auto t = op("input_torque")) inTorque = *t;
  else if (auto p = op("power")) inTorque = arith::div(*p, inSpeed);
  else if (auto t2 = op("output_torque")) inTorque = arith::div(*t2, total);
  if (name == "input_torque") return inTorque;
  if (name == "output_torque") return arith::mul(inTorque, total);
  if (name == "power") return arith::mul(inTorque, inSpeed);
  return Value::invalid();
}

Value Evaluator::materialProperty(int stage, const std::string& prop) const {
  const ir::Attribute* mat = m_.attribute(stage, "material");
  if (!mat || mat->symbol.empty()) return Value::invalid();
  const ir::Material* m = m_.program.findMaterial(mat->symbol);
  if (!m) return Value::invalid();
  const ir::Setting* s = ir::findSetting(m->properties, prop);
  if (!s || !s->value) return Value::invalid();
  return Value::number(s->value->toDouble());
}

} // namespace gbx::rt
