#pragma once
// Time-varying mesh stiffness from the length of the contact lines (docs/dynamics.md):
// L(tau) = Lm [1 + sum_k A_k cos(2 pi k tau) + B_k sin(2 pi k tau)], tau in mesh periods.
#include <vector>

namespace gbx::rt::dyn {

struct Fourier {
  std::vector<double> a, b;  // A_k, B_k for k = 1..K
};

// The coefficients for transverse contact ratio epsAlpha and overlap ratio epsBeta,
// with B_k's last term a sine (the source paper's cosine is a misprint). Written as
//   A_k = 2 sinc(b) sin(a)/a - 4 sin(a/2)^2 sin(b/2)^2 * 2/(a b)
//   B_k = 4 sinc(b) sin(a/2)^2/a + 4 sin(a) sin(b/2)^2/(a b),  a = 2 pi k epsAlpha, b = 2 pi k epsBeta,
// exact rearrangements of the published quotients with no cancellation as b -> 0,
// where they meet the spur limit sin(a)/(pi k epsAlpha), (1 - cos a)/(pi k epsAlpha).
Fourier contactLineSeries(double epsAlpha, double epsBeta, int harmonics);

// Transverse contact ratio of a standard spur pair (no shift, addendum one module), external
// or internal: what the planetary and whole-gearbox scene models give their stiffness series.
double epsAlphaStandard(double z1, double z2, double mod, double alpha, bool internal);

// Relative stiffness L(tau)/Lm at phase tau (mesh periods).
double relativeStiffness(const Fourier& f, double tau);
// Its derivative in tau.
double relativeStiffnessSlope(const Fourier& f, double tau);
// The harmonic sums of two series at one phase in one pass (one sincos, one recurrence):
// sum_k f.a_k cos(2 pi k tau) + f.b_k sin(2 pi k tau) into sf, and g's into sg.
void seriesPair(const Fourier& f, const Fourier& g, double tau, double& sf, double& sg);

} // namespace gbx::rt::dyn
