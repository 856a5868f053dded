#include <gtest/gtest.h>

#include "units/Unit.h"

using namespace gbx::units;

namespace {
Unit atom(const char* n) { return *lookupAtom(n); }
}

TEST(Units, AtomsConvertToSi) {
  EXPECT_EQ(atom("mm").scale.str(), "0.001");
  EXPECT_EQ(atom("\u00B5m").scale.str(), atom("um").scale.str());
  EXPECT_EQ(atom("\u00B0").scale.str(), atom("deg").scale.str());
  EXPECT_EQ(atom("rpm").scale.str(), "1/30*pi");
  EXPECT_EQ(atom("GPa").scale.str(), "1000000000");
  EXPECT_EQ(atom("%").scale.str(), "0.01");
  EXPECT_TRUE(atom("mesh_periods").meshPeriods);
  EXPECT_FALSE(lookupAtom("furlong"));
}

TEST(Units, RevolutionsPerMinuteEqualsRpm) {
  Unit rmin = divide(atom("r"), atom("min"));
  EXPECT_EQ(rmin.dim, dims::angularSpeed);
  EXPECT_EQ(rmin.scale.str(), atom("rpm").scale.str());
}

TEST(Units, DimensionAlgebra) {
  Unit torque = multiply(atom("N"), atom("m"));
  EXPECT_EQ(torque.dim, dims::torque);
  Unit cgamma = divide(atom("N"), multiply(atom("mm"), atom("um")));
  EXPECT_EQ(cgamma.dim, dims::pressure);
  EXPECT_EQ(cgamma.scale.str(), "1000000000");
  Unit dens = divide(atom("kg"), powerOf(atom("m"), 3));
  EXPECT_EQ(dens.dim, dims::density);
  EXPECT_EQ(dims::power, dims::torque / dims::time);
  Dim half;
  EXPECT_TRUE(dims::area.sqrt(half));
  EXPECT_EQ(half, dims::length);
  EXPECT_FALSE(dims::length.sqrt(half));
}

TEST(Units, AngularSpeedIsNotFrequencyAndTorqueIsNamed) {
  EXPECT_NE(dims::angularSpeed, dims::frequency);
  EXPECT_EQ(dims::torque.describe(), "a torque");
  EXPECT_EQ(dims::angularSpeed.describe(), "an angular speed");
  EXPECT_EQ(dims::torque.siUnit(), "kg*m^2/s^2");
  EXPECT_EQ(Dim(1, 1, -2, 0).siUnit(), "kg*m/s^2");
}

TEST(Units, DisplayUnits) {
  EXPECT_EQ(displayUnitFor(dims::length).name, "mm");
  EXPECT_EQ(displayUnitFor(dims::angularSpeed).name, "rpm");
}

TEST(Units, TemperaturesInKelvinInsideAndCelsiusInReports) {
  EXPECT_EQ(atom("K").dim, dims::temperature);
  EXPECT_EQ(atom("degC").dim, dims::temperature);
  EXPECT_EQ(atom("degC").offset.str(), "273.15");
  EXPECT_EQ(atom("K").offset.str(), "0");
  // A compound unit measures differences: no zero.
  EXPECT_EQ(divide(atom("degC"), atom("s")).offset.str(), "0");
  DisplayUnit u = displayUnitFor(dims::temperature);
  EXPECT_EQ(u.name, "degC");
  EXPECT_DOUBLE_EQ(u.shown(373.15), 100.0);
  EXPECT_DOUBLE_EQ(u.si(20.0), 293.15);
  EXPECT_EQ(dims::temperature.siUnit(), "K");
  EXPECT_EQ(dims::temperature.describe(), "a temperature");
  EXPECT_EQ(showQuantity(Number::exact(Rational::make(70315, 100)), dims::temperature), "430 degC");
}
