#include "units/Rational.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>

namespace gbx::units {

i128 gcd128(i128 a, i128 b) {
  if (a < 0) a = -a;
  if (b < 0) b = -b;
  while (b != 0) {
    i128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

std::string i128ToString(i128 v) {
  if (v == 0) return "0";
  bool neg = v < 0;
  // The most negative value never arises: make() keeps magnitudes below 2^127.
  u128 u = neg ? static_cast<u128>(-v) : static_cast<u128>(v);
  char buf[48];
  char* end = buf + sizeof buf;
  char* p = end;
  // 64-bit division is done in hardware; 128-bit division only while the value needs it.
  while (u > static_cast<u128>(UINT64_MAX)) {
    *--p = static_cast<char>('0' + static_cast<int>(u % 10));
    u /= 10;
  }
  for (auto w = static_cast<std::uint64_t>(u); w > 0; w /= 10) *--p = static_cast<char>('0' + static_cast<int>(w % 10));
  if (neg) *--p = '-';
  return std::string(p, end);
}

Rational Rational::make(i128 num, i128 den) {
  Rational r;
  if (den < 0) {
    num = -num;
    den = -den;
  }
  // 64-bit division is done in hardware; 128-bit division is a library call.
  const i128 small = static_cast<i128>(1) << 62;
  i128 g = (num < small && num > -small && den < small) ? static_cast<i128>(std::gcd(static_cast<std::int64_t>(num < 0 ? -num : num),
                                                                                       static_cast<std::int64_t>(den)))
                                                        : gcd128(num, den);
  if (g > 1) {
    num /= g;
    den /= g;
  }
  r.num_ = num;
  r.den_ = den == 0 ? 1 : den;
  return r;
}

std::optional<Rational> Rational::parseDecimal(const std::string& text) {
  i128 mant = 0;
  int scale = 0;  // power of ten applied to mant
  size_t i = 0;
  bool any = false;
  const i128 limit = static_cast<i128>(1) << 120;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
    if (mant > limit / 10) return std::nullopt;
    mant = mant * 10 + (text[i] - '0');
    any = true;
  }
  if (i < text.size() && text[i] == '.') {
    ++i;
    for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
      if (mant > limit / 10) return std::nullopt;
      mant = mant * 10 + (text[i] - '0');
      --scale;
      any = true;
    }
  }
  if (!any) return std::nullopt;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    int sign = 1;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
      if (text[i] == '-') sign = -1;
      ++i;
    }
    int e = 0;
    bool digits = false;
    for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
      if (e > 1000) return std::nullopt;
      e = e * 10 + (text[i] - '0');
      digits = true;
    }
    if (!digits) return std::nullopt;
    scale += sign * e;
  }
  if (i != text.size()) return std::nullopt;
  Rational r = make(mant, 1);
  auto p = Rational(10).pow(scale);
  if (!p) return std::nullopt;
  return r.mul(*p);
}

double Rational::toDouble() const {
  // Long division keeps full double precision even for 120-bit parts. Parts that fit 64
  // bits convert in hardware (exactly, as the 128-bit conversion would).
  const i128 lim = static_cast<i128>(1) << 62;
  if (num_ < lim && num_ > -lim && den_ < lim)
    return static_cast<double>(static_cast<long double>(static_cast<std::int64_t>(num_)) /
                               static_cast<long double>(static_cast<std::int64_t>(den_)));
  return static_cast<double>(static_cast<long double>(num_) / static_cast<long double>(den_));
}

std::string Rational::str() const {
  if (den_ == 1) return i128ToString(num_);
  return i128ToString(num_) + "/" + i128ToString(den_);
}

std::optional<std::string> Rational::decimal() const {
  i128 d = den_;
  int twos = 0, fives = 0;
  while (d % 2 == 0) { d /= 2; ++twos; }
  while (d % 5 == 0) { d /= 5; ++fives; }
  if (d != 1) return std::nullopt;
  int places = std::max(twos, fives);
  if (places > 12) return std::nullopt;
  i128 scale = 1;
  for (int k = 0; k < places; ++k) scale *= 10;
  i128 scaled = num_ * (scale / den_);
  bool neg = scaled < 0;
  if (neg) scaled = -scaled;
  std::string digits = i128ToString(scaled);
  if (places > 0) {
    while (static_cast<int>(digits.size()) <= places) digits.insert(digits.begin(), '0');
    digits.insert(digits.end() - places, '.');
  }
  return neg ? "-" + digits : digits;
}

namespace {
bool mulOv(i128 a, i128 b, i128& out) {
  if (__builtin_mul_overflow(a, b, &out)) return true;
  const i128 bound = static_cast<i128>(1) << 126;
  return out > bound || out < -bound;
}
bool addOv(i128 a, i128 b, i128& out) {
  if (__builtin_add_overflow(a, b, &out)) return true;
  const i128 bound = static_cast<i128>(1) << 126;
  return out > bound || out < -bound;
}
} // namespace

std::optional<Rational> Rational::add(const Rational& o) const {
  // Denominators are positive; 64-bit ones take the hardware's division.
  const i128 small = static_cast<i128>(1) << 62;
  i128 g = den_ < small && o.den_ < small
               ? static_cast<i128>(std::gcd(static_cast<std::int64_t>(den_), static_cast<std::int64_t>(o.den_)))
               : gcd128(den_, o.den_);
  i128 a, b, n, d;
  if (mulOv(num_, o.den_ / g, a) || mulOv(o.num_, den_ / g, b) || addOv(a, b, n) ||
      mulOv(den_ / g, o.den_, d))
    return std::nullopt;
  return make(n, d);
}

std::optional<Rational> Rational::sub(const Rational& o) const { return add(o.neg()); }

std::optional<Rational> Rational::mul(const Rational& o) const {
  const i128 small = static_cast<i128>(1) << 31;
  if (num_ < small && num_ > -small && den_ < small && o.num_ < small && o.num_ > -small && o.den_ < small)
    return make(num_ * o.num_, den_ * o.den_);
  i128 g1 = gcd128(num_, o.den_), g2 = gcd128(o.num_, den_);
  if (g1 == 0) g1 = 1;
  if (g2 == 0) g2 = 1;
  i128 n, d;
  if (mulOv(num_ / g1, o.num_ / g2, n) || mulOv(den_ / g2, o.den_ / g1, d)) return std::nullopt;
  return make(n, d);
}

std::optional<Rational> Rational::div(const Rational& o) const {
  if (o.num_ == 0) return std::nullopt;
  return mul(make(o.den_, o.num_));
}

std::optional<Rational> Rational::pow(int e) const {
  if (e < 0) {
    if (num_ == 0) return std::nullopt;
    auto p = pow(-e);
    if (!p) return std::nullopt;
    return Rational(1).div(*p);
  }
  Rational result(1), base = *this;
  while (e > 0) {
    if (e & 1) {
      auto r = result.mul(base);
      if (!r) return std::nullopt;
      result = *r;
    }
    e >>= 1;
    if (e > 0) {
      auto b = base.mul(base);
      if (!b) return std::nullopt;
      base = *b;
    }
  }
  return result;
}

int Rational::compare(const Rational& o) const {
  if (den_ == o.den_) return num_ < o.num_ ? -1 : (num_ > o.num_ ? 1 : 0);
  i128 a, b;
  if (!mulOv(num_, o.den_, a) && !mulOv(o.num_, den_, b)) return a < b ? -1 : (a > b ? 1 : 0);
  // Continued-fraction comparison for the rare values whose cross products overflow.
  int s1 = sign(), s2 = o.sign();
  if (s1 != s2) return s1 < s2 ? -1 : 1;
  if (s1 < 0) return o.neg().compare(neg());
  i128 n1 = num_, d1 = den_, n2 = o.num_, d2 = o.den_;
  int flip = 1;
  for (;;) {
    i128 q1 = n1 / d1, q2 = n2 / d2;
    if (q1 != q2) return (q1 < q2 ? -1 : 1) * flip;
    i128 r1 = n1 % d1, r2 = n2 % d2;
    if (r1 == 0 || r2 == 0) {
      if (r1 == 0 && r2 == 0) return 0;
      return (r1 == 0 ? -1 : 1) * flip;
    }
    n1 = d1; d1 = r1; n2 = d2; d2 = r2;
    flip = -flip;
  }
}

} // namespace gbx::units
