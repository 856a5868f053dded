#include "units/Number.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <algorithm>

namespace gbx::units {

Number Number::exact(Rational r, int piPower) {
  Number n;
  n.exact_ = true;
  n.r_ = r;
  n.pi_ = r.isZero() ? 0 : piPower;
  return n;
}

Number Number::approx(double v) {
  Number n;
  n.exact_ = false;
  n.approx_ = v;
  return n;
}

double Number::toDouble() const {
  if (!exact_) return approx_;
  return r_.toDouble() * std::pow(std::numbers::pi, pi_);
}

int Number::sign() const {
  if (exact_) return r_.sign();
  return approx_ > 0 ? 1 : (approx_ < 0 ? -1 : 0);
}

Number Number::add(const Number& o) const {
  if (exact_ && o.exact_) {
    if (r_.isZero()) return o;
    if (o.r_.isZero()) return *this;
    if (pi_ == o.pi_)
      if (auto s = r_.add(o.r_)) return exact(*s, pi_);
  }
  return approx(toDouble() + o.toDouble());
}

Number Number::sub(const Number& o) const { return add(o.neg()); }

Number Number::mul(const Number& o) const {
  if (exact_ && o.exact_)
    if (auto p = r_.mul(o.r_)) return exact(*p, pi_ + o.pi_);
  return approx(toDouble() * o.toDouble());
}

Number Number::div(const Number& o) const {
  if (exact_ && o.exact_ && !o.r_.isZero())
    if (auto q = r_.div(o.r_)) return exact(*q, pi_ - o.pi_);
  return approx(toDouble() / o.toDouble());
}

Number Number::pow(int e) const {
  if (exact_)
    if (auto p = r_.pow(e)) return exact(*p, pi_ * e);
  return approx(std::pow(toDouble(), e));
}

Number Number::neg() const {
  if (exact_) return exact(r_.neg(), pi_);
  return approx(-approx_);
}

int Number::compare(const Number& o) const {
  if (exact_ && o.exact_ && (pi_ == o.pi_ || r_.isZero() || o.r_.isZero())) {
    if (pi_ == o.pi_) return r_.compare(o.r_);
    return sign() < o.sign() ? -1 : (sign() > o.sign() ? 1 : 0);
  }
  double a = toDouble(), b = o.toDouble();
  return a < b ? -1 : (a > b ? 1 : 0);
}

std::string formatDouble(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  int prec = 1;
  for (; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  double a = std::fabs(v);
  // Plain positional notation for engineering magnitudes: "3000", not "3e+03".
  if (a >= 1e-5 && a < 1e15 && std::string(buf).find('e') != std::string::npos) {
    int decimals = std::max(0, prec - 1 - static_cast<int>(std::floor(std::log10(a))));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  }
  return buf;
}

std::string Number::str() const {
  if (!exact_) return formatDouble(approx_) + "~";
  std::string base;
  if (auto d = r_.decimal(); d && r_.den() != 1 && d->size() <= 14)
    base = *d;
  else
    base = r_.str();
  if (pi_ == 0) return base;
  std::string p = pi_ == 1 ? "pi" : "pi^" + std::to_string(pi_);
  if (r_ == Rational(1)) return p;
  return base + "*" + p;
}

} // namespace gbx::units
