#include "model/Standards.h"

#include <cmath>
#include <vector>

namespace gbx::rt::iso {

namespace {
// The standard's formulas take mm and give um.
double gradeFactor(int grade) { return std::pow(2.0, 0.5 * (grade - 5)); }
double mm(double m) { return m * 1e3; }
double um(double v) { return v * 1e-6; }
} // namespace

const std::vector<double>& diameterRanges() {
  static const std::vector<double> r{5, 20, 50, 125, 280, 560, 1000, 1600, 2500, 4000, 6000, 8000, 10000};
  return r;
}
const std::vector<double>& moduleRanges() {
  static const std::vector<double> r{0.5, 2, 3.5, 6, 10, 16, 25, 40, 70};
  return r;
}
const std::vector<double>& faceWidthRanges() {
  static const std::vector<double> r{4, 10, 20, 40, 80, 160, 250, 400, 650, 1000};
  return r;
}

namespace {
// The range (lo, hi] of `bounds` that holds v, as its geometric mean (mm).
double rangeMean(double v, const std::vector<double>& bounds) {
  double lo = bounds.front();
  for (double hi : bounds) {
    if (hi <= lo) continue;
    if (v <= hi) return std::sqrt(lo * hi);
    lo = hi;
  }
  return v;  // beyond the table: the value itself
}
double dMean(double d) { return rangeMean(mm(d), diameterRanges()); }
double mMean(double mn) { return rangeMean(mm(mn), moduleRanges()); }
double bMean(double b) { return rangeMean(mm(b), faceWidthRanges()); }
double rounded(double v) { return v > 10 ? std::round(v) : v >= 5 ? std::round(2 * v) / 2 : std::round(10 * v) / 10; }
} // namespace

double tabulatedSinglePitch(int q, double mn, double d) {
  return um(rounded((0.3 * (mMean(mn) + 0.4 * std::sqrt(dMean(d))) + 4.0) * gradeFactor(q)));
}
double tabulatedProfileForm(int q, double mn, double d) {
  return um(rounded((2.5 * std::sqrt(mMean(mn)) + 0.17 * std::sqrt(dMean(d)) + 0.5) * gradeFactor(q)));
}
double tabulatedHelixSlope(int q, double d, double b) {
  return um(rounded((0.07 * std::sqrt(dMean(d)) + 0.45 * std::sqrt(bMean(b)) + 3.0) * gradeFactor(q)));
}

double singlePitch(int q, double mn, double d) { return um((0.3 * (mm(mn) + 0.4 * std::sqrt(mm(d))) + 4.0) * gradeFactor(q)); }
double totalProfile(int q, double mn, double d) {
  return um((3.2 * std::sqrt(mm(mn)) + 0.22 * std::sqrt(mm(d)) + 0.7) * gradeFactor(q));
}
double profileForm(int q, double mn, double d) {
  return um((2.5 * std::sqrt(mm(mn)) + 0.17 * std::sqrt(mm(d)) + 0.5) * gradeFactor(q));
}
double profileSlope(int q, double mn, double d) {
  return um((2.0 * std::sqrt(mm(mn)) + 0.14 * std::sqrt(mm(d)) + 0.5) * gradeFactor(q));
}
double totalHelix(int q, double d, double b) { return um((0.1 * std::sqrt(mm(d)) + 0.63 * std::sqrt(mm(b)) + 4.2) * gradeFactor(q)); }
double totalCumulativePitch(int q, double mn, double d) { return um((0.3 * mm(mn) + 1.25 * std::sqrt(mm(d)) + 7.0) * gradeFactor(q)); }

double meshStiffness(double z1, double z2, double x1, double x2, double beta, double epsAlpha) {
  double zn1 = z1 / std::pow(std::cos(beta), 3), zn2 = z2 / std::pow(std::cos(beta), 3);
  double q = 0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * x1 - 0.11654 * x1 / zn1 - 0.00193 * x2 - 0.24188 * x2 / zn2 +
             0.00529 * x1 * x1 + 0.00182 * x2 * x2;  // mm*um/N
  double cprime = 0.8 / q * std::cos(beta);       // N/(mm*um), CR = CB = 1
  return cprime * (0.75 * epsAlpha + 0.25) * 1e9;  // N/m per m
}

} // namespace gbx::rt::iso
