#pragma once
#include <cmath>
#include <limits>
#include <vector>

namespace gbx::rt::arith {

template <class F>
Value corners(const std::vector<Value>& in, F f) {
  std::vector<double> x(in.size());
  std::vector<size_t> ranged;
  for (size_t i = 0; i < in.size(); ++i) {
    if (!in[i].isNumber()) return Value::invalid();
    x[i] = in[i].lo;
    if (in[i].lo != in[i].hi) ranged.push_back(i);
  }
  if (ranged.empty()) {
    double v = f(x);
    return std::isfinite(v) ? Value::number(v) : Value::invalid();
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t mask = 0; mask < (size_t{1} << ranged.size()); ++mask) {
    for (size_t k = 0; k < ranged.size(); ++k) {
      const Value& v = in[ranged[k]];
      x[ranged[k]] = (mask >> k) & 1 ? v.hi : v.lo;
    }
    double v = f(x);
    if (!std::isfinite(v)) return Value::invalid();
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return Value::range(std::nextafter(lo, -INFINITY), std::nextafter(hi, INFINITY));
}

} // namespace gbx::rt::arith
