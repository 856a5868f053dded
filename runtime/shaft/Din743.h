#pragma once
// Shaft strength to DIN 743:2012 at one notch: the fatigue safety S_D and the static safety
// S_F, with every factor of the sequence kept for the report. SI in and out (m, N, N m, Pa);
// the standard's fits are written in its own units (mm, N/mm^2) inside.
#include <array>
#include <string>
#include <vector>

namespace gbx::rt::shaft::din743 {

// In the order of the catalogue's `steel_group` words.
enum class Group { QuenchedTempered, CaseHardening, Structural, Nitriding };
// In the order of the catalogue's notch words.
enum class NotchKind { Shoulder, Groove, Keyway, PressFit, Hole, VNotch };
const char* notchName(NotchKind k);

// The notch's geometry. `d` is the diameter of the loaded section at the notch: the smaller
// diameter of a shoulder, the root of a groove or V-notch, the shaft at a keyway, press fit
// or hole. `D` the larger (shoulder) or outer (groove, V-notch) diameter.
struct Notch {
  NotchKind kind = NotchKind::Shoulder;
  double d = 0, D = 0;
  double radius = 0;       // fillet of a shoulder or groove
  double depth = 0;        // groove or V-notch depth (0: (D - d)/2)
  double holeDiameter = 0; // transverse hole
  int keys = 1;            // keyway: one or two keys
  double roughness = 8e-6; // Rz
  double bore = 0;         // a hollow shaft's bore
};

struct Material {
  double tensile = 0, yield = 0; // sigma_B(d_B), sigma_S(d_B)
  Group group = Group::QuenchedTempered;
};

// One load type at the notch: its mean, amplitude and largest value (tension N, bending and
// torsion N m).
struct Load {
  double mean = 0, amplitude = 0, max = 0;
};
enum Type { Tension = 0, Bending = 1, Torsion = 2 };

struct Settings {
  int loadCase = 2;             // 1: mean stress stays; 2: mean over amplitude stays
  double effectiveDiameter = 0; // d_eff for K1
  bool hardened = false;        // a hardened surface layer: K_F 1, n from 10^-0.7, K2F 1
  double KV = 1;                // surface strengthening factor
};

// Every factor of one load type, in the standard's order.
struct Factors {
  double mean = 0, amplitude = 0, max = 0; // nominal stresses, Pa
  double K2 = 1;
  double alpha = 0;                        // form factor (0: none, beta is experimental)
  double Gprime = 0;                       // related stress gradient, 1/m
  double n = 1;                            // support number
  double betaTest = 0, K3Test = 1, K3 = 1; // experimental beta at the test diameter and its K3 scaling
  double beta = 1, KF = 1, K = 1;
  double sigmaW = 0, sigmaWK = 0, psi = 0, sigmaADK = 0; // Pa
  double K2F = 1, gammaF = 1, sigmaFK = 0;               // sigmaFK in Pa
};

struct Result {
  double K1B = 1, K1S = 1;
  double tensileAt = 0, yieldAt = 0; // sigma_B(d_eff), sigma_S(d_eff), Pa
  double phi = 0;
  double sigmaMv = 0, tauMv = 0; // Pa
  std::array<Factors, 3> f;      // by Type
  double SD = 0, SF = 0;
  std::vector<std::string> warnings; // a fit used beyond the range the standard gives it
};

// Throws std::invalid_argument for a geometry the notch cannot have (a fillet of 0, a hole
// wider than the shaft) or a material without strengths.
Result rate(const Notch& notch, const Material& m, const std::array<Load, 3>& loads, const Settings& s);

} // namespace gbx::rt::shaft::din743
