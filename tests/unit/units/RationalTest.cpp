#include <gtest/gtest.h>

#include "units/Number.h"
#include "units/Rational.h"

using gbx::units::Number;
using gbx::units::Rational;

TEST(Rational, ParsesDecimalLiteralsExactly) {
  EXPECT_EQ(Rational::parseDecimal("12")->str(), "12");
  EXPECT_EQ(Rational::parseDecimal("0.29")->str(), "29/100");
  EXPECT_EQ(Rational::parseDecimal("1e-6")->str(), "1/1000000");
  EXPECT_EQ(Rational::parseDecimal("2.06e11")->str(), "206000000000");
  EXPECT_EQ(Rational::parseDecimal("3.952")->str(), "494/125");
  EXPECT_FALSE(Rational::parseDecimal("1.2.3"));
  EXPECT_FALSE(Rational::parseDecimal("e5"));
}

TEST(Rational, NormalisesSignAndGcd) {
  EXPECT_EQ(Rational::make(6, -4).str(), "-3/2");
  EXPECT_EQ(Rational::make(0, 7).str(), "0");
  EXPECT_EQ(Rational::make(177, 59).str(), "3");
}

// docs/search.md: in doubles, |177/59 - 3.02| <= 0.02 says false; exactly it is true.
TEST(Rational, RatioWindowBoundaryIsDecidedExactly) {
  Rational u = Rational::make(177, 59);
  Rational target = *Rational::parseDecimal("3.02"), tol = *Rational::parseDecimal("0.02");
  Rational diff = u.sub(target)->abs();
  EXPECT_TRUE(diff <= tol);
  EXPECT_EQ(diff, tol);
  double d = 177.0 / 59.0 - 3.02;
  EXPECT_FALSE((d < 0 ? -d : d) <= 0.02) << "the double comparison this guards against";
}

TEST(Rational, ArithmeticAndComparison) {
  Rational a = Rational::make(1, 3), b = Rational::make(1, 6);
  EXPECT_EQ(a.add(b)->str(), "1/2");
  EXPECT_EQ(a.sub(b)->str(), "1/6");
  EXPECT_EQ(a.mul(b)->str(), "1/18");
  EXPECT_EQ(a.div(b)->str(), "2");
  EXPECT_EQ(Rational(10).pow(-3)->str(), "1/1000");
  EXPECT_TRUE(b < a);
  EXPECT_FALSE(a.div(Rational(0)));
}

TEST(Rational, OverflowIsReportedNotWrapped) {
  Rational big = *Rational(10).pow(30);
  EXPECT_FALSE(big.mul(big));
  EXPECT_FALSE(Rational(10).pow(60));
}

TEST(Rational, CompareNeverOverflows) {
  // Cross products of these exceed 128 bits; the continued-fraction path decides.
  Rational a = Rational::make((static_cast<gbx::units::i128>(1) << 100) + 1, (static_cast<gbx::units::i128>(1) << 100) + 3);
  Rational b = Rational::make((static_cast<gbx::units::i128>(1) << 100) + 2, (static_cast<gbx::units::i128>(1) << 100) + 5);
  // a = 1 - 2/(N+3) and b = 1 - 3/(N+5) with N = 2^100: b is the smaller.
  EXPECT_EQ(a.compare(b), 1);
  EXPECT_EQ(b.compare(a), -1);
  EXPECT_EQ(a.compare(a), 0);
}

TEST(Rational, DecimalRendering) {
  EXPECT_EQ(*Rational::parseDecimal("0.2985")->decimal(), "0.2985");
  EXPECT_EQ(*Rational::parseDecimal("0.05")->neg().decimal(), "-0.05");
  EXPECT_FALSE(Rational::parseDecimal("-0.05")) << "literals carry no sign; `-` is an operator";
  EXPECT_FALSE(Rational::make(1, 3).decimal());
}

TEST(Number, KeepsPiExact) {
  Number deg = Number::exact(Rational::make(1, 180), 1);
  Number thirty = Number::exact(Rational(30)).mul(deg);
  EXPECT_TRUE(thirty.isExact());
  EXPECT_EQ(thirty.str(), "1/6*pi");
  EXPECT_NEAR(thirty.toDouble(), 0.5235987755982988, 1e-15);
  // Sums of different powers of pi cannot stay exact.
  Number s = thirty.add(Number::exact(Rational(1)));
  EXPECT_FALSE(s.isExact());
  EXPECT_NEAR(s.toDouble(), 1.5235987755982988, 1e-15);
}

TEST(Number, FormatsDoublesShortestAndPositional) {
  EXPECT_EQ(gbx::units::formatDouble(3000.0), "3000");
  EXPECT_EQ(gbx::units::formatDouble(0.1), "0.1");
  EXPECT_EQ(gbx::units::formatDouble(-0.003), "-0.003");
  EXPECT_EQ(gbx::units::formatDouble(1e-9), "1e-09");
  EXPECT_EQ(gbx::units::formatDouble(123456.789), "123456.789");
  EXPECT_EQ(gbx::units::formatDouble(2.5e20), "2.5e+20");
}
