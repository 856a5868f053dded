#pragma once
// Formulas of the gear standards gbxc uses, in SI in and out.
#include <vector>

namespace gbx::rt::iso {

// ISO 1328-1:1995, tolerances for accuracy grade Q, normal module mn and reference
// diameter d (and face width b for the helix): the grade-5 formula times sqrt(2)^(Q - 5).
double singlePitch(int grade, double mn, double d);       // f_pt
double totalProfile(int grade, double mn, double d);      // F_alpha
double profileForm(int grade, double mn, double d);       // f_f_alpha
double profileSlope(int grade, double mn, double d);      // f_H_alpha
double totalHelix(int grade, double d, double b);         // F_beta
double totalCumulativePitch(int grade, double mn, double d);  // F_p

// The same tolerances as ISO 1328-1:1995 tabulates them, which rating programs use: the
// formula at the geometric mean of the module, diameter and face-width ranges the gear
// falls in, rounded (above 10 um to 1 um, 5-10 um to 0.5 um, below to 0.1 um).
double tabulatedSinglePitch(int grade, double mn, double d);      // f_pt
double tabulatedProfileForm(int grade, double mn, double d);      // f_f_alpha
double tabulatedHelixSlope(int grade, double d, double b);        // f_H_beta

// The ranges ISO 1328-1:1995 tabulates by, as their bounds in mm (a value on a bound is in
// the range below it): a tabulated tolerance jumps where a gear's value crosses one.
const std::vector<double>& diameterRanges();
const std::vector<double>& moduleRanges();
const std::vector<double>& faceWidthRanges();

// ISO 6336-1 method B: mesh stiffness per unit face width c_gamma_alpha (N/m per m) of
// solid gears on the standard basic rack: c'th from the q' polynomial,
// c' = 0.8 c'th cos(beta), c_gamma_alpha = c' (0.75 eps_alpha + 0.25).
double meshStiffness(double z1, double z2, double x1, double x2, double beta, double epsAlpha);

} // namespace gbx::rt::iso
