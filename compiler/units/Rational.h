#pragma once
// Exact rational numbers for literals. 128-bit numerator and denominator cover every
// product of tooth counts and decimal literals the language produces; an operation
// that would overflow reports it instead of wrapping, and the caller falls back to a
// double and marks the value inexact.
#include <cstdint>
#include <optional>
#include <string>

namespace gbx::units {

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

class Rational {
public:
  Rational() = default;
  Rational(std::int64_t n) : num_(n), den_(1) {}
  // Normalises sign and gcd; den must be non-zero.
  static Rational make(i128 num, i128 den);
  // Parses a decimal literal such as `12`, `0.29`, `1e-6`, `2.06e11`.
  static std::optional<Rational> parseDecimal(const std::string& text);

  i128 num() const { return num_; }
  i128 den() const { return den_; }
  bool isInteger() const { return den_ == 1; }
  bool isZero() const { return num_ == 0; }
  int sign() const { return num_ > 0 ? 1 : (num_ < 0 ? -1 : 0); }
  double toDouble() const;
  // "177/59", "3", "-1/2".
  std::string str() const;
  // Fixed decimal form when the value is a terminating decimal of at most 12 places.
  std::optional<std::string> decimal() const;

  // Checked arithmetic: nullopt on overflow or division by zero.
  std::optional<Rational> add(const Rational& o) const;
  std::optional<Rational> sub(const Rational& o) const;
  std::optional<Rational> mul(const Rational& o) const;
  std::optional<Rational> div(const Rational& o) const;
  std::optional<Rational> pow(int e) const;
  Rational neg() const { return make(-num_, den_); }
  Rational abs() const { return num_ < 0 ? neg() : *this; }

  // Exact three-way comparison (never overflows: falls back to long division).
  int compare(const Rational& o) const;
  bool operator==(const Rational& o) const { return num_ == o.num_ && den_ == o.den_; }
  bool operator!=(const Rational& o) const { return !(*this == o); }
  bool operator<(const Rational& o) const { return compare(o) < 0; }
  bool operator<=(const Rational& o) const { return compare(o) <= 0; }
  bool operator>(const Rational& o) const { return compare(o) > 0; }
  bool operator>=(const Rational& o) const { return compare(o) >= 0; }

private:
  i128 num_ = 0;
  i128 den_ = 1;
};

std::string i128ToString(i128 v);
i128 gcd128(i128 a, i128 b);

} // namespace gbx::units
