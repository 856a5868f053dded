#include "model/Evaluator.h"

#include "shaft/ShaftPlan.h"

#include "model/Builtins.h"
#include "model/Deadline.h"
#include "model/Sampling.h"
#include "parallel/Ranks.h"
#include "model/Split.h"
#include "model/StageKind.h"
#include "lower/Lower.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <mutex>
#include <cmath>
#include <functional>
#include <numeric>
#include <utility>

namespace gbx::rt {

// The guard against cyclic definitions counts the nesting of this thread's evaluations:
// threads of one search share an evaluator. Once a definition nests too deep, the rest of
// that evaluation gives up at once: `face_width = face_width + face_width` would otherwise
// try 2^64 ways before it fails.
thread_local int evalDepth = 0;
thread_local bool evalTooDeep = false;
thread_local bool evalCycled = false;  // since Evaluator::tookCycle() was last asked

namespace {
// One level of that nesting, given back however the evaluation ends.
struct Nesting {
  bool ok;
  Nesting() {
    if (++evalDepth > 64) evalTooDeep = evalCycled = true;
    ok = !evalTooDeep;
  }
  ~Nesting() {
    if (--evalDepth == 0) evalTooDeep = false;
  }
  Nesting(const Nesting&) = delete;
  Nesting& operator=(const Nesting&) = delete;
};
} // namespace


bool Evaluator::tookCycle() { return std::exchange(evalCycled, false); }

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
  case Op::Quantity: return quantity(e.ref, a);
  case Op::Let: {
    if (e.let < 0 || static_cast<size_t>(e.let) >= m_.gearbox.lets.size()) return Value::invalid();
    const auto& l = m_.gearbox.lets[static_cast<size_t>(e.let)];
    if (!l.expr) return Value::invalid();
    Nesting level;
    return level.ok ? eval(*l.expr, a) : Value::invalid();
  }
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
      auto [lo, hi] = toleranceBounds(eval(*tol.args[0], a), eval(*tol.args[1], a), tol.relative);
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
  case Op::SceneOutput: return sceneOutput ? sceneOutput(e, a, *this) : Value::invalid();
  case Op::Scatter: return scatter(e, a);
  case Op::Relative: {
    // The baseline evaluates the argument as lowering resolved it in the baseline gearbox.
    if (!baseline || !e.inBaseline) return Value::invalid();
    // A level in dB against the baseline's is their difference, in dB.
    const ir::Expr& x = *e.args[0];
    if (x.op == Op::SceneOutput && cat::signalFnSpec(x.output.fn).decibels)
      return arith::sub(arg(0), baseline(*e.inBaseline));
    return builtin(cat::Fn::Relative)({arg(0), baseline(*e.inBaseline)});
  }
  default: return Value::invalid();  // Tol and Set stand only inside comparisons
  }
}

Value Evaluator::call(const ir::Expr& e, const Assignment& a) const {
  if (e.args.size() == 1 && e.args[0]->type.kind == ir::Type::PerGear) return perGearReduce(e, a);
  std::vector<Value> v;
  v.reserve(e.args.size());
  for (const auto& x : e.args) {
    v.push_back(eval(*x, a));
    if (v.back().kind == Value::Invalid) return Value::invalid();
  }
  BuiltinFn fn = builtin(e.fn);
  return fn ? fn(v) : Value::invalid();
}

void Evaluator::setOverride(const ir::QuantityRef& r, Value v) {
  for (auto& [k, x] : overrides_)
    if (k == r) {
      x = v;
      return;
    }
  overrides_.emplace_back(r, v);
}

std::vector<double> Evaluator::offsetKey() const {
  std::vector<double> k;
  for (const auto& [r, d] : offsets_) {
    k.push_back(static_cast<double>(r.index) * 1e6 + static_cast<double>(r.gear) * 1e3 + static_cast<double>(r.key));
    k.push_back(d);
  }
  return k;
}

std::vector<double> Evaluator::overrideKey() const {
  std::vector<double> k;
  for (const auto& [r, v] : overrides_) {
    k.push_back(static_cast<double>(r.owner) * 1e9 + static_cast<double>(r.index) * 1e6 + static_cast<double>(r.gear) * 1e3 +
                static_cast<double>(r.key));
    k.push_back(static_cast<double>(v.kind));
    k.push_back(v.lo);
    k.push_back(v.hi);
  }
  return k;
}

void Evaluator::addOffset(const ir::QuantityRef& r, double delta) {
  for (auto& [k, x] : offsets_)
    if (k == r) {
      x += delta;
      return;
    }
  offsets_.emplace_back(r, delta);
}

Value Evaluator::withOffset(int stage, int gear, Q key, Value v) const {
  for (const auto& [k, d] : offsets_)
    if (k.owner == ir::QuantityRef::Stage && k.index == stage && k.gear == gear && k.key == key && v.isNumber())
      return arith::add(v, Value::number(d));
  return v;
}

// Where the context of a `worst(q)` gives no direction (a report column): q's own. A
// catalogue quantity's better direction, every scene output smaller; 0 where none is known
// (then both ends are reported).
int betterSense(const ir::Expr& q) {
  if (q.op == ir::Op::SceneOutput) return 1;
  if (q.op != ir::Op::Quantity) return 0;
  switch (cat::betterOf(q.ref.key)) {
  case cat::Better::Larger: return -1;
  case cat::Better::Smaller: return 1;
  default: return 0;
  }
}

// q at the nominal design and at every corner of the tolerance box (2^n corners, n <= 6 by
// the checker): the worst of them where q stands, or their mean.
Value Evaluator::scatter(const ir::Expr& e, const Assignment& a) const {
  const auto& tol = m_.gearbox.tolerances;
  // The nominal value reads a nested `worst`/`mean` at the nominal design too.
  Evaluator atNominal(*this);
  atNominal.nominalOnly = true;
  Value nominal = nominalOnly ? eval(*e.args[0], a) : atNominal.eval(*e.args[0], a);
  // Already at a corner (a `worst` inside a `mean`, or through a `let`): q there, not a box
  // around the corner.
  if (nominalOnly || tol.empty() || !offsets_.empty() || !nominal.isNumber()) return nominal;
  if (Sampling::of(m_.gearbox).on()) return sampled(e, a);
  std::vector<Value> v;
  if (e.fn == cat::Fn::Worst) v.push_back(Value::number(e.sense != 0 ? e.sense : betterSense(*e.args[0])));
  v.push_back(nominal);
  for (unsigned corner = 0; corner < (1u << tol.size()); ++corner) {
    Evaluator at(*this);
    for (size_t i = 0; i < tol.size(); ++i) at.addOffset(tol[i].ref, (corner >> i) & 1u ? tol[i].amount : -tol[i].amount);
    Value x = at.eval(*e.args[0], a);
    if (!x.isNumber()) return Value::invalid();
    v.push_back(x);
  }
  return builtin(e.fn)(v);
}

namespace {

// The last quantities read over the samples: a column, its note, a rule and the Monte Carlo
// report read the same q at the same design, and each sample may run a scene.
class SampleMemo {
public:
  using Key = std::vector<double>;
  std::optional<std::optional<std::vector<double>>> find(const Key& k) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [key, v] : entries_)
      if (key == k) return v;
    return std::nullopt;
  }
  void put(Key k, std::optional<std::vector<double>> v) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (entries_.size() >= 32) entries_.pop_front();
    entries_.emplace_back(std::move(k), std::move(v));
  }

private:
  std::mutex mutex_;
  std::deque<std::pair<Key, std::optional<std::vector<double>>>> entries_;
};

SampleMemo& sampleMemo() {
  static SampleMemo memo;
  return memo;
}

} // namespace

std::optional<std::vector<double>> Evaluator::overSamples(const ir::Expr& q, const Assignment& a, bool shareRanks) const {
  const auto& tol = m_.gearbox.tolerances;
  Sampling s = Sampling::of(m_.gearbox);
  if (!s.on() || tol.empty()) return std::nullopt;
  // The memo holds quantities that read no scene: a scene's result depends on more than the
  // key says (a sweep's effect parameter, the pass's runs). A call shared over the ranks
  // never asks it (whether it hits must not decide whether the ranks exchange).
  const bool memo = !(sceneOutput && ir::uses(&q, {ir::Op::SceneOutput, ir::Op::Let}));
  SampleMemo::Key key = {static_cast<double>(m_.serial), static_cast<double>(reinterpret_cast<std::uintptr_t>(&q))};
  for (int c : a.choice) key.push_back(c);
  key.push_back(-1);
  for (const auto& [lo, hi] : a.box) {
    key.push_back(lo);
    key.push_back(hi);
  }
  key.push_back(-2);
  for (double v : overrideKey()) key.push_back(v);
  if (memo && !shareRanks)
    if (auto hit = sampleMemo().find(key)) return *hit;
  // The samples over the threads and, under mpirun, the ranks: an empty result marks a
  // sample where q has no value.
  auto values = par::map(static_cast<size_t>(s.samples), par::jobs(), [&](size_t k) {
    if (Deadline::expired()) return std::vector<double>{};  // past the time limit: no value
    Evaluator at(*this);
    std::vector<double> d = s.deviations(tol, static_cast<long>(k));
    for (size_t i = 0; i < tol.size(); ++i) at.addOffset(tol[i].ref, d[i]);
    Value x = at.eval(q, a);
    return x.isNumber() ? std::vector<double>{x.mid()} : std::vector<double>{};
  }, shareRanks);
  std::optional<std::vector<double>> out(std::vector<double>(values.size()));
  for (size_t k = 0; k < values.size() && out; ++k) {
    if (values[k].size() != 1) out.reset();
    else (*out)[k] = values[k][0];
  }
  if (memo) sampleMemo().put(std::move(key), out);
  return out;
}

// `worst`, `mean` and `quantile` over the Monte Carlo samples (not the nominal design: the
// samples stand for the production).
Value Evaluator::sampled(const ir::Expr& e, const Assignment& a) const {
  auto xs = overSamples(*e.args[0], a);
  if (!xs || xs->empty()) return Value::invalid();
  switch (e.fn) {
  case cat::Fn::Mean: return Value::number(sampleMean(*xs));
  case cat::Fn::Quantile: {
    if (e.args.size() < 2) return Value::invalid();
    Value p = eval(*e.args[1], a);
    if (!p.isNumber()) return Value::invalid();
    std::vector<Value> v{p};
    for (double x : *xs) v.push_back(Value::number(x));
    return builtin(cat::Fn::Quantile)(v);
  }
  default: {
    std::vector<Value> v{Value::number(e.sense != 0 ? e.sense : betterSense(*e.args[0]))};
    for (double x : *xs) v.push_back(Value::number(x));
    return builtin(cat::Fn::Worst)(v);
  }
  }
}

std::optional<Evaluator::Where> Evaluator::worstCorner(const ir::Expr& e, const Assignment& a) const {
  const auto& tol = m_.gearbox.tolerances;
  if (e.op != ir::Op::Scatter || e.fn != cat::Fn::Worst || tol.empty() || e.args.empty()) return std::nullopt;
  int sense = e.sense != 0 ? e.sense : betterSense(*e.args[0]);
  if (sense == 0) return std::nullopt;
  if (Sampling s = Sampling::of(m_.gearbox); s.on()) {
    auto xs = overSamples(*e.args[0], a);
    if (!xs || xs->empty()) return std::nullopt;
    // The same choice as `worst` makes: the first of the worst values.
    size_t k = worstIndex(*xs, sense);
    return Where{s.deviations(tol, static_cast<long>(k)), static_cast<long>(k)};
  }
  Evaluator atNominal(*this);
  atNominal.nominalOnly = true;
  Value best = atNominal.eval(*e.args[0], a);
  if (!best.isNumber()) return std::nullopt;
  std::vector<double> where(tol.size(), 0.0);
  for (unsigned corner = 0; corner < (1u << tol.size()); ++corner) {
    Evaluator at(*this);
    std::vector<double> d(tol.size());
    for (size_t i = 0; i < tol.size(); ++i) {
      d[i] = (corner >> i) & 1u ? tol[i].amount : -tol[i].amount;
      at.addOffset(tol[i].ref, d[i]);
    }
    Value x = at.eval(*e.args[0], a);
    if (!x.isNumber()) return std::nullopt;
    // The same choice as `worst` makes: the first strictly worse value.
    if (sense > 0 ? x.mid() > best.mid() : x.mid() < best.mid()) {
      best = x;
      where = d;
    }
  }
  return Where{where, -1};
}

const Value* Evaluator::overridden(const ir::QuantityRef& r) const {
  for (const auto& [k, v] : overrides_)
    if (k == r) return &v;
  return nullptr;
}

bool Evaluator::overrides(int stage, int gear, Q key) const {
  for (const auto& [k, v] : overrides_)
    if (k.owner == ir::QuantityRef::Stage && k.index == stage && k.gear == gear && k.key == key) return true;
  return false;
}

const Value* Evaluator::overridden(Q gearboxKey) const {
  for (const auto& [k, v] : overrides_)
    if (k.owner == ir::QuantityRef::Gearbox && k.key == gearboxKey) return &v;
  return nullptr;
}

Value Evaluator::quantity(const std::string& path, const Assignment& a) const {
  return quantity(lower::quantityRef(m_.program, m_.gearbox, path), a);
}

Value Evaluator::quantity(const ir::QuantityRef& r, const Assignment& a) const {
  if (!overrides_.empty())
    if (const Value* v = overridden(r)) return r.owner == ir::QuantityRef::Stage ? withOffset(r.index, r.gear, r.key, *v) : *v;
  switch (r.owner) {
  case ir::QuantityRef::Gearbox: return gearboxQuantity(r.key, a);
  case ir::QuantityRef::Split:
    if (r.index < 0 || static_cast<size_t>(r.index) >= m_.gearbox.splits.size()) return Value::invalid();
    return splitQuantity(r.index, r.key, a);
  case ir::QuantityRef::Shaft: return shaftQuantity(*this, r, a);
  case ir::QuantityRef::Stage: {
    if (!m_.hasStage(r.index)) return Value::invalid();
    const StageInfo::Entry& en = m_.info(r.index).entry(r.gear, r.key);
    if (en.attr || en.slot >= 0 || !offsets_.empty()) return attribute(r.index, r.gear, r.key, a);
    return derived(r.index, r.gear, r.key, a);
  }
  default: return Value::invalid();  // materials and collections: not search quantities
  }
}

Value Evaluator::splitQuantity(int split, Q key, const Assignment& a) const {
  const ir::Split& sp = m_.gearbox.splits[static_cast<size_t>(split)];
  if (const ir::Setting* s = ir::findSetting(sp.settings, key)) return s->value ? constant(*s->value) : Value::invalid();
  if (key == Q::Install) return Value::invalid();
  auto r = computeSplit(*this, split, a);
  if (!r) return Value::invalid();
  switch (key) {
  case Q::Twist: return Value::number(r->twist);
  case Q::Displacement: return Value::number(r->displacement);
  case Q::Imbalance: return Value::number(r->imbalance);
  case Q::BranchTorque: return Value::number(r->branchTorque);
  case Q::PreloadDisplacement: return Value::number(r->preloadDisplacement);
  default: return Value::invalid();
  }
}

Value Evaluator::attribute(int stage, int gear, Q key, const Assignment& a) const {
  // A tolerance corner's deviation on top of the value the design gives.
  Value v = givenAttribute(stage, gear, key, a);
  return offsets_.empty() ? v : withOffset(stage, gear, key, v);
}

Value Evaluator::givenAttribute(int stage, int gear, Q key, const Assignment& a) const {
  if (!overrides_.empty()) {
    ir::QuantityRef r;
    r.owner = ir::QuantityRef::Stage;
    r.index = static_cast<std::int16_t>(stage);
    r.gear = static_cast<std::int8_t>(gear);
    r.key = key;
    if (const Value* v = overridden(r)) return *v;
  }
  const StageInfo::Entry& en = m_.info(stage).entry(gear, key);
  if (en.slot >= 0) {
    int c = a.choice[static_cast<size_t>(en.slot)];
    if (c < 0) return Value::invalid();
    return m_.slots[static_cast<size_t>(en.slot)].values[static_cast<size_t>(c)];
  }
  if (en.freedom >= 0) {
    if (m_.freedoms[static_cast<size_t>(en.freedom)].solved) return m_.info(stage).kind->solve(KindContext{*this, stage, a}, gear);
    auto [lo, hi] = a.box[static_cast<size_t>(en.freedom)];
    return lo == hi ? Value::number(lo) : Value::range(lo, hi);
  }
  if (!en.attr || !en.attr->value) return derived(stage, gear, key, a);
  Nesting level;
  return level.ok ? eval(*en.attr->value, a) : Value::invalid();
}

Value Evaluator::derived(int stage, int gear, Q key, const Assignment& a) const {
  const StageKindImpl& k = *m_.info(stage).kind;
  DerivedFn fn = gear < 0 ? k.stageFn(key) : k.gearFn(key);
  if (!fn) return Value::invalid();
  return fn(KindContext{*this, stage, a}, gear);
}

void Evaluator::solveFreedoms(Assignment& a, std::vector<double>& freedoms) const {
  for (size_t f = 0; f < m_.freedoms.size() && f < freedoms.size(); ++f) {
    const Freedom& fr = m_.freedoms[f];
    if (!fr.solved) continue;
    Value v = attribute(fr.stage, fr.gear, fr.key, a);
    freedoms[f] = v.isNumber() ? v.mid() : NAN;
    a.box[f] = {freedoms[f], freedoms[f]};
  }
}

Value Evaluator::ratioProduct(int from, int to, const Assignment& a) const {
  if (from == 0 && to > 0 && to == a.upstreamStage) return Value::number(a.upstreamRatio);
  Value r = Value::rational(Rational(1));
  for (int s = from; s < to; ++s) r = arith::mul(r, derived(s, Q::Ratio, a));
  return r;
}

// A per-gear expression (`pitch_deviation`, `bending_deflection + torsion_deflection`)
// evaluated for one gear: its per-gear quantities name that gear.
Value Evaluator::perGear(const ir::Expr& e, int gear, const Assignment& a) const {
  if (e.op == ir::Op::Quantity && e.type.kind == ir::Type::PerGear) {
    ir::QuantityRef r = e.ref;
    r.gear = static_cast<std::int8_t>(gear);
    r.perGear = false;
    return quantity(r, a);
  }
  if (e.type.kind != ir::Type::PerGear) return eval(e, a);
  switch (e.op) {
  case ir::Op::Add: return arith::add(perGear(*e.args[0], gear, a), perGear(*e.args[1], gear, a));
  case ir::Op::Sub: return arith::sub(perGear(*e.args[0], gear, a), perGear(*e.args[1], gear, a));
  default: return Value::invalid();
  }
}

Value Evaluator::perGearReduce(const ir::Expr& call, const Assignment& a) const {
  // The stage of the quantity: that of any per-gear name inside.
  int st = -1;
  std::function<void(const ir::Expr&)> find = [&](const ir::Expr& x) {
    if (x.op == ir::Op::Quantity && x.type.kind == ir::Type::PerGear && st < 0) st = x.ref.index;
    for (const auto& c : x.args)
      if (c) find(*c);
  };
  find(*call.args[0]);
  if (st < 0) return Value::invalid();
  std::vector<Value> vals;
  for (size_t g = 0; g < m_.info(st).ir->gears.size(); ++g) {
    vals.push_back(perGear(*call.args[0], static_cast<int>(g), a));
    if (!vals.back().isNumber()) return Value::invalid();
  }
  Value out = vals[0];
  for (size_t i = 1; i < vals.size(); ++i) {
    if (call.fn == cat::Fn::Mean) out = arith::add(out, vals[i]);
    else if (call.fn == cat::Fn::Max) out = arith::less(out, vals[i], false) == Truth::True ? vals[i] : out;
    else out = arith::less(vals[i], out, false) == Truth::True ? vals[i] : out;
  }
  if (call.fn == cat::Fn::Mean) out = arith::div(out, Value::rational(Rational(static_cast<std::int64_t>(vals.size()))));
  return out;
}

Value Evaluator::gearboxQuantity(Q key, const Assignment& a) const {
  int n = static_cast<int>(m_.stages.size());
  if (key == Q::Ratio) {
    if (a.ratio) return Value::rational(*a.ratio);
    if (a.ratioApprox) return Value::number(*a.ratioApprox);
    return ratioProduct(0, n, a);
  }
  Value total = ratioProduct(0, n, a);
  // A swept load (power, input or output torque) replaces whichever load `operating` gives.
  bool loadSwept = !overrides_.empty() && (overridden(Q::Power) || overridden(Q::InputTorque) || overridden(Q::OutputTorque));
  auto op = [&](Q k) -> std::optional<Value> {
    if (!overrides_.empty())
      if (const Value* v = overridden(k)) return *v;
    if (loadSwept && (k == Q::Power || k == Q::InputTorque || k == Q::OutputTorque)) return std::nullopt;
    if (auto v = m_.operating(k)) return Value::number(*v);
    return std::nullopt;
  };
  Value inSpeed = Value::invalid();
  if (auto v = op(Q::InputSpeed)) inSpeed = *v;
  else if (auto w = op(Q::OutputSpeed)) inSpeed = arith::mul(*w, total);
  if (key == Q::InputSpeed) return inSpeed;
  if (key == Q::OutputSpeed) return arith::div(inSpeed, total);
  Value inTorque = Value::invalid();
  if (auto t = op(Q::InputTorque)) inTorque = *t;
  else if (auto p = op(Q::Power)) inTorque = arith::div(*p, inSpeed);
  else if (auto t2 = op(Q::OutputTorque)) inTorque = arith::div(*t2, total);
  if (key == Q::InputTorque) return inTorque;
  if (key == Q::OutputTorque) return arith::mul(inTorque, total);
  if (key == Q::Power) return arith::mul(inTorque, inSpeed);
  return Value::invalid();
}

Value Evaluator::materialProperty(int stage, Q prop) const {
  const ir::Material* m = m_.material(stage);
  if (!m) return Value::invalid();
  const ir::Setting* s = ir::findSetting(m->properties, prop);
  if (!s || !s->value) return Value::invalid();
  return Value::number(s->value->toDouble());
}

// ---- what a kind's formulas see ----------------------------------------------------------

namespace {

// A length of the micrometre scale: such a quantity, a number read from a length signal, or
// an extreme, mean, tolerance scatter, sum or multiple of them (constants aside).
bool micrometreLength(const ir::Expr& e) {
  if (e.type.dim != units::dims::length) return false;
  switch (e.op) {
  case ir::Op::Quantity: return cat::readsInMicrometres(e.ref.key);
  case ir::Op::SceneOutput: return true;  // a length signal: displacement or transmission error
  case ir::Op::Scatter:
  case ir::Op::Neg:
  case ir::Op::Add:
  case ir::Op::Sub:
  case ir::Op::Call: {
    bool any = false;
    for (const auto& a : e.args) {
      if (!a) return false;
      if (a->op == ir::Op::Const) continue;
      if (!micrometreLength(*a)) return false;
      any = true;
    }
    return any;
  }
  case ir::Op::Mul:
  case ir::Op::Div: {
    // A micrometre length times or over a dimensionless factor.
    if (e.args.size() != 2 || !e.args[0] || !e.args[1]) return false;
    if (e.args[1]->type.dim.dimensionless() && micrometreLength(*e.args[0])) return true;
    return e.op == ir::Op::Mul && e.args[0]->type.dim.dimensionless() && micrometreLength(*e.args[1]);
  }
  default: return false;
  }
}

} // namespace

units::DisplayUnit valueUnitOf(const ir::Expr& e) {
  if (micrometreLength(e)) return units::micrometres();
  return e.op == ir::Op::Quantity ? units::displayUnitFor(e.type.dim) : units::differenceUnitFor(e.type.dim);
}

units::DisplayUnit displayUnitOf(const ir::Expr& e) {
  if (e.op == ir::Op::Quantity && e.ref.key == Q::Imbalance) return {"%", 0.01};
  if (e.op == ir::Op::Quantity && (e.ref.key == Q::Life || e.ref.key == Q::ModifiedLife ||
                                   e.ref.key == Q::BearingLife || e.ref.key == Q::BearingModifiedLife))
    return {"h", 3600};
  if (e.op == ir::Op::Quantity && e.ref.key == Q::SlopeAt) return {"mrad", 1e-3};
  // A level, and a level against the baseline's (their difference).
  const ir::Expr* x = e.op == ir::Op::Relative && !e.args.empty() ? e.args[0].get() : &e;
  if (x->op == ir::Op::SceneOutput && cat::signalFnSpec(x->output.fn).decibels) return {"dB", 1};
  return valueUnitOf(e);
}

Value KindContext::at(Q key) const { return ev.attribute(stage, -1, key, a); }
Value KindContext::at(int gear, Q key) const { return ev.attribute(stage, gear, key, a); }
Value KindContext::orZero(int gear, Q key) const {
  Value v = at(gear, key);
  return v.kind == Value::Invalid ? Value::rational(Rational(0)) : v;
}
Value KindContext::derived(Q key) const { return ev.derived(stage, -1, key, a); }
Value KindContext::derived(int gear, Q key) const { return ev.derived(stage, gear, key, a); }
Value KindContext::gearbox(Q key) const { return ev.gearboxQuantity(key, a); }
Value KindContext::upstreamRatio() const { return ev.ratioProduct(0, stage, a); }
Value KindContext::material(Q property) const { return ev.materialProperty(stage, property); }

} // namespace gbx::rt
