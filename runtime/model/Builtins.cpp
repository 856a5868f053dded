#include "model/Builtins.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "model/Evaluator.h"
#include "model/Sampling.h"

namespace gbx::rt {

namespace {

using cat::Fn;
using V = std::vector<Value>;

Value unary(const Value& x, double (*fn)(double)) {
  return arith::corners({x}, [fn](const std::vector<double>& y) { return fn(y[0]); });
}

bool integerOf(const Value& x, long long& out) {
  if (!x.exact || !x.exact->isInteger()) return false;
  out = static_cast<long long>(x.exact->num());
  return true;
}

Value gcdOf(const V& v, bool coprime) {
  long long p, q;
  if (!integerOf(v[0], p) || !integerOf(v[1], q)) return Value::invalid();
  long long g = std::gcd(p, q);
  return coprime ? Value::boolean(g == 1) : Value::rational(Rational(g));
}

Value extreme(const V& v, bool lowest) {
  Value best = v[0];
  for (size_t i = 1; i < v.size(); ++i) {
    const Value& x = v[i];
    if (best.exact && x.exact) {
      bool take = lowest ? *x.exact < *best.exact : *x.exact > *best.exact;
      if (take) best = x;
      continue;
    }
    best = lowest ? Value::range(std::min(best.lo, x.lo), std::min(best.hi, x.hi))
                  : Value::range(std::max(best.lo, x.lo), std::max(best.hi, x.hi));
  }
  return best;
}

Value mean(const V& v) {
  Value s = v[0];
  for (size_t i = 1; i < v.size(); ++i) s = arith::add(s, v[i]);
  return arith::div(s, Value::rational(Rational(static_cast<std::int64_t>(v.size()))));
}

Value roundTo(const V& v) {
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
  // An exact step n/d (10 um is 1/100000 m): the multiple as q n / d, rounded once, so that
  // 3 steps of 10 um is the double of 30 um (3e-05), not 3 * 1e-05 (3.0000000000000004e-05).
  if (step.exact && !step.exact->isZero()) {
    double n = static_cast<double>(step.exact->num()), d = static_cast<double>(step.exact->den());
    if (std::fabs(n) < 0x1p53 && d < 0x1p53)
      return arith::corners({x, step}, [n, d](const std::vector<double>& y) { return std::round(y[0] / y[1]) * n / d; });
  }
  return arith::corners({x, step}, [](const std::vector<double>& y) { return std::round(y[0] / y[1]) * y[1]; });
}

Value wholePart(const Value& x, bool up) {
  if (x.exact) {
    units::i128 n = x.exact->num(), d = x.exact->den();
    units::i128 q = n / d;
    if (!up && n < 0 && q * d != n) --q;
    if (up && n > 0 && q * d != n) ++q;
    return Value::rational(Rational::make(q, 1));
  }
  return unary(x, up ? static_cast<double (*)(double)>(std::ceil) : static_cast<double (*)(double)>(std::floor));
}

// sin, cos, tan over an interval: monotone pieces, with an extremum wherever the
// interval crosses one.
Value periodic(const Value& x, Fn f) {
  double (*fn)(double) = f == Fn::Sin   ? static_cast<double (*)(double)>(std::sin)
                         : f == Fn::Cos ? static_cast<double (*)(double)>(std::cos)
                                        : static_cast<double (*)(double)>(std::tan);
  if (x.isPoint()) return Value::number(fn(x.lo));
  double lo = std::min(fn(x.lo), fn(x.hi)), hi = std::max(fn(x.lo), fn(x.hi));
  double phase = f == Fn::Sin ? M_PI / 2 : 0.0;
  if (f == Fn::Tan) {
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

Value absOf(const Value& x) {
  if (x.exact) return Value::rational(x.exact->abs());
  if (x.lo >= 0) return x;
  if (x.hi <= 0) return arith::neg(x);
  return Value::range(0, std::max(-x.lo, x.hi));
}

// A function-local table: ready whenever it is first asked for.
const std::vector<BuiltinRow>& kRowsTable() {
  static const std::vector<BuiltinRow> rows = {
    {Fn::Abs, [](const V& v) { return absOf(v[0]); }},
    {Fn::Sqrt, [](const V& v) { return v[0].lo < 0 ? Value::invalid() : unary(v[0], [](double x) { return std::sqrt(x); }); }},
    {Fn::Sin, [](const V& v) { return periodic(v[0], Fn::Sin); }},
    {Fn::Cos, [](const V& v) { return periodic(v[0], Fn::Cos); }},
    {Fn::Tan, [](const V& v) { return periodic(v[0], Fn::Tan); }},
    {Fn::Asin,
     [](const V& v) { return v[0].lo < -1 || v[0].hi > 1 ? Value::invalid() : unary(v[0], [](double x) { return std::asin(x); }); }},
    {Fn::Acos,
     [](const V& v) { return v[0].lo < -1 || v[0].hi > 1 ? Value::invalid() : unary(v[0], [](double x) { return std::acos(x); }); }},
    {Fn::Atan, [](const V& v) { return unary(v[0], [](double x) { return std::atan(x); }); }},
    {Fn::Atan2,
     [](const V& v) {
       if (v[1].lo <= 0 && !v[1].isPoint()) return Value::invalid();
       return arith::corners(v, [](const std::vector<double>& y) { return std::atan2(y[0], y[1]); });
     }},
    {Fn::Exp, [](const V& v) { return unary(v[0], [](double x) { return std::exp(x); }); }},
    {Fn::Log, [](const V& v) { return v[0].lo <= 0 ? Value::invalid() : unary(v[0], [](double x) { return std::log(x); }); }},
    {Fn::Min, [](const V& v) { return extreme(v, true); }},
    {Fn::Max, [](const V& v) { return extreme(v, false); }},
    {Fn::Mean, [](const V& v) { return mean(v); }},
    {Fn::Round, [](const V& v) { return roundTo(v); }},
    {Fn::Floor, [](const V& v) { return wholePart(v[0], false); }},
    {Fn::Ceil, [](const V& v) { return wholePart(v[0], true); }},
    {Fn::Coprime, [](const V& v) { return gcdOf(v, true); }},
    {Fn::Gcd, [](const V& v) { return gcdOf(v, false); }},
    // relative(x): x over its value in the baseline gearbox, given as the second argument.
    {Fn::Relative, [](const V& v) { return arith::div(v[0], v[1]); }},
    // quantile(q, p) over the Monte Carlo samples: v[0] p, then the samples.
    {Fn::Quantile,
     [](const V& v) {
       std::vector<double> xs;
       for (size_t i = 1; i < v.size(); ++i) xs.push_back(v[i].mid());
       std::sort(xs.begin(), xs.end());
       return xs.empty() ? Value::invalid() : Value::number(sortedQuantile(xs, v[0].mid()));
     }},
    // worst(q) over the tolerance box: v[0] the sense (+1 the largest is worst, -1 the
    // smallest, 0 not known: both ends, as an interval), v[1] the nominal value, then the
    // corners (or the Monte Carlo samples).
    {Fn::Worst,
     [](const V& v) {
       double sense = v[0].mid();
       size_t lo = 1, hi = 1;
       for (size_t i = 2; i < v.size(); ++i) {
         if (v[i].mid() < v[lo].mid()) lo = i;
         if (v[i].mid() > v[hi].mid()) hi = i;
       }
       if (sense > 0) return v[hi];
       if (sense < 0) return v[lo];
       return Value::range(v[lo].lo, v[hi].hi);
     }},
  };
  return rows;
}

} // namespace

const std::vector<BuiltinRow>& builtinRows() { return kRowsTable(); }

BuiltinFn builtin(cat::Fn id) {
  static const auto table = [] {
    std::array<BuiltinFn, cat::kFunctionCount> t{};
    for (const auto& r : kRowsTable()) t[static_cast<size_t>(r.id)] = r.fn;
    return t;
  }();
  return table[static_cast<size_t>(id)];
}

} // namespace gbx::rt
