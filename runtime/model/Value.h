#pragma once
// A value during search: a number known exactly (a rational), as a double, or as an
// enclosure [lo, hi] over the continuous freedoms; or a three-valued truth. Exact
// values decide comparisons exactly; enclosures decide them only when they do not
// straddle the bound, and say Unknown otherwise.
#include <optional>

#include "units/Rational.h"

namespace gbx::rt {

using units::Rational;

enum class Truth { False, True, Unknown };

struct Value {
  enum Kind { Number, Bool, Invalid };
  Kind kind = Invalid;
  double lo = 0, hi = 0;
  std::optional<Rational> exact;  // set only when the value is exactly this rational
  Truth truth = Truth::Unknown;

  static Value number(double v) { return {Number, v, v, std::nullopt, Truth::Unknown}; }
  static Value range(double lo, double hi) { return {Number, lo, hi, std::nullopt, Truth::Unknown}; }
  static Value rational(const Rational& r) {
    double d = r.toDouble();
    return {Number, d, d, r, Truth::Unknown};
  }
  static Value boolean(Truth t) { return {Bool, 0, 0, std::nullopt, t}; }
  static Value boolean(bool b) { return boolean(b ? Truth::True : Truth::False); }
  static Value invalid() { return {}; }

  bool isNumber() const { return kind == Number; }
  bool isPoint() const { return kind == Number && lo == hi; }
  double mid() const { return 0.5 * (lo + hi); }
};

} // namespace gbx::rt
