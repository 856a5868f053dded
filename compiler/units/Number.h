#pragma once
// A literal-derived value: exactly r·π^p while only rational arithmetic touched it
// (degrees and rpm carry π), otherwise a double marked inexact.
#include <string>

#include "units/Rational.h"

namespace gbx::units {

class Number {
public:
  Number() = default;
  static Number exact(Rational r, int piPower = 0);
  static Number approx(double v);

  bool isExact() const { return exact_; }
  // Exact and free of π: a plain rational.
  bool isRational() const { return exact_ && pi_ == 0; }
  const Rational& rational() const { return r_; }
  int piPower() const { return pi_; }
  double toDouble() const;
  bool isZero() const { return exact_ ? r_.isZero() : approx_ == 0.0; }
  int sign() const;

  Number add(const Number& o) const;
  Number sub(const Number& o) const;
  Number mul(const Number& o) const;
  Number div(const Number& o) const;
  Number pow(int e) const;
  Number neg() const;

  // Exact comparison where both sides are exact with equal π powers; else by doubles.
  int compare(const Number& o) const;
  // "177/59", "1/6*pi", "0.29" or a shortest round-trip double.
  std::string str() const;

private:
  bool exact_ = true;
  Rational r_;
  int pi_ = 0;
  double approx_ = 0.0;
};

// Shortest decimal that reads back as the same double (%.17g trimmed).
std::string formatDouble(double v);

} // namespace gbx::units
