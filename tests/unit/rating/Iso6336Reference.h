#pragma once
// Independent reference (test oracle) for the ISO 6336 life factors, limited-life interpolation,
// work hardening factor and Miner's rule over a load spectrum. Written from the standards' tables
// and formulas; not derived from the gbxc sources. Stresses in N/mm^2, cycles as plain numbers.
//
// SOURCES AND VALUES (each value says which public transcription backs it):
//  * Life curves, "normal" quality (Z_NT, Y_NT >= 0.85: 1.0 at the knee, 0.85 at 1e10, 0.85 beyond),
//    log-log between the tabulated points (the standard's exponents, e.g. 0.0756 / 0.0306 / 0.115,
//    are these slopes rounded; exact slopes are used here, docs/rating.md):
//      ISO 6336-2 Table 2, Z_NT   case-hardened (Eh) and through-hardened (V, "no pitting" row):
//                                 1.6 at N <= 1e5, 1.0 at 5e7;  nitrided (NT, NV nitr.): 1.3 at 1e5, 1.0 at 2e6
//      ISO 6336-3 Table 3, Y_NT   Eh: 2.5 at N <= 1e3, 1.0 at 3e6;  V: 2.5 at 1e4, 1.0 at 3e6;
//                                 nitrided (NT, NV): 1.6 at 1e3, 1.0 at 3e6
//    Backed by: the Table 2 rows transcribed in gfsReboucas/Drivetrain
//    ISO_6336.m (life_factor), a DIN 3990 port (Z_NT stat 1.6/1.3/1.1) and the ISO 6336-6 load
//    exponents p quoted publicly (pitting 6.61 Eh/V, 5.709 NT; root 8.738 Eh, 6.225 V, 17.035 NT),
//    which these points reproduce exactly: p = ln(Nknee/Nstatic)/ln(static) (/2 for contact).
//  * Static values of the other factors (ISO 6336-2:2006 method B limited-life clause with the
//    factor clauses 11-14; ISO 6336-3:2006 clauses 12-14), interpolated as shortLife() does,
//    between the same Nstatic / Nknee as Z_NT (contact) or Y_NT (bending):
//      (Z_L Z_v Z_R)_static = 1.0 ; Z_X static = 1.0 ; Y_RrelT static = 1.0 ; Y_X static = 1.0
//      Z_W static = its endurance value (same factor both ends, i.e. no interpolation)
//      Y_deltarelT static: YdeltarelTStatic() below (ISO 6336-3:2006 clause 12, static formulas)
//    Backed by a public DIN 3990 port (Z_LVRstat = 1, Z_Xstat = 1, Y_RrelTstat = 1, one Z_W for both,
//    same Y_deltarelT,stat formulas) and a public ISO 6336-3:2019-based script (0.44 Y_S + 0.12,
//    static). See ZWRough for the Z_W roughness term of the later edition.
//  * Miner (ISO 6336-6): the S-N curve is the life curve read the other way; the "extended Miner"
//    continuation beyond the knee (slope 2p-1, Haibach) is an option of cyclesToFailure(); the
//    product's variant is the plain curve (docs/rating.md).
#include <algorithm>
#include <cmath>
#include <vector>

namespace gbx::ref6336 {

enum class Treat { CaseHardened, Nitrided, ThroughHardened };

// The tabulated points of one life curve: static value up to Nstatic, 1.0 at Nknee.
struct CurvePts { double staticValue, Nstatic, Nknee; };

// ISO 6336-2 Table 2 (Z_NT rows 2 and 3; "no pitting permitted" row for V and Eh).
inline CurvePts contactPts(Treat t) {
  if (t == Treat::Nitrided) return {1.3, 1e5, 2e6};
  return {1.6, 1e5, 5e7};
}
// ISO 6336-3 Table 3 (Y_NT rows 1, 2 and 3).
inline CurvePts bendingPts(Treat t) {
  if (t == Treat::Nitrided) return {1.6, 1e3, 3e6};
  if (t == Treat::ThroughHardened) return {2.5, 1e4, 3e6};
  return {2.5, 1e3, 3e6};
}

// Limited-life interpolation, ISO 6336-2:2006 method B (sigma_HP between static and endurance) and
// ISO 6336-3:2006 method B (sigma_FP likewise): log(value) linear in log(N) between (Nstatic,
// staticValue) and (Nknee, endurance); staticValue below Nstatic, endurance beyond Nknee.
// Static values per factor: see the header comment (Z_L Z_v Z_R: 1.0, Z_X: 1.0, Z_W: = endurance,
// Y_RrelT: 1.0, Y_X: 1.0, Y_deltarelT: YdeltarelTStatic). Knees: Z_NT's for contact, Y_NT's for bending.
inline double shortLife(double endurance, double staticValue, double NL, double Nstatic, double Nknee) {
  if (NL <= Nstatic) return staticValue;
  if (NL >= Nknee) return endurance;
  const double t = std::log(Nknee / NL) / std::log(Nknee / Nstatic);  // 1 at Nstatic, 0 at Nknee
  return std::exp(std::log(endurance) + t * (std::log(staticValue) - std::log(endurance)));
}

// One life curve (ISO 6336-2 Table 2 / ISO 6336-3 Table 3 shape): static plateau, log-log to 1.0 at
// the knee, log-log to endValue at 1e10, endValue beyond 1e10.
inline double lifeCurve(const CurvePts& c, double N, double endValue = 0.85) {
  if (N <= c.Nknee) return shortLife(1.0, c.staticValue, N, c.Nstatic, c.Nknee);
  if (N >= 1e10) return endValue;
  return std::exp(std::log(endValue) * std::log(N / c.Nknee) / std::log(1e10 / c.Nknee));
}

// Life factor for contact stress, ISO 6336-2:2006 Table 2 (normal quality, 0.85 at 1e10).
inline double ZNT(Treat t, double NL) { return lifeCurve(contactPts(t), NL); }

// Life factor for tooth root stress, ISO 6336-3:2006 Table 3 (normal quality, 0.85 at 1e10).
inline double YNT(Treat t, double NL) { return lifeCurve(bendingPts(t), NL); }

// Relative notch sensitivity factor for STATIC stress, ISO 6336-3:2006 clause 12 (method B):
//   Eh, IF (root) (case-hardened):         0.44 Y_S + 0.12
//   NT, NV (nitrided / nitrocarburized):   0.20 Y_S + 0.60
//   V, GGG perl./bai. (through-hardened, stress-strain curve with 0.2 % proof stress sigma02):
//     (1 + 0.82 (Y_S - 1) (300/sigma02)^0.25) / (1 + 0.82 (300/sigma02)^0.25)
//   (St with a yield point uses 0.93 and 200/sigma_S instead; GG and GGG ferr. 1.0; not needed here.)
// Through-hardened needs sigma02 [N/mm^2]; without it the result is NaN.
inline double YdeltarelTStatic(Treat t, double YS, double sigma02 = NAN) {
  if (t == Treat::CaseHardened) return 0.44 * YS + 0.12;
  if (t == Treat::Nitrided) return 0.20 * YS + 0.60;
  if (!(sigma02 > 0.0)) return NAN;
  const double c = 0.82 * std::pow(300.0 / sigma02, 0.25);
  return (1.0 + c * (YS - 1.0)) / (1.0 + c);
}

// Work hardening factor of a through-hardened wheel meshing with a surface-hardened (case-hardened
// or nitrided) pinion, ISO 6336-2 clause 13 (2006; 1996 Figure 13; DIN 3990-2 likewise):
//   Z_W = 1.2 - (HB - 130)/1700, HB the wheel's Brinell hardness clamped to [130, 470].
inline double ZW(double HBwheel) {
  const double hb = std::min(470.0, std::max(130.0, HBwheel));
  return 1.2 - (hb - 130.0) / 1700.0;
}

// The same with the pinion roughness term (ISO 6336-2:2019 clause 12, surface-hardened on
// through-hardened; which edition first has it is not settled here):
//   Z_W = (1.2 - (HB - 130)/1700) (3/R_zH)^0.15, R_zH clamped to [3, 16] um, with
//   R_zH = R_z1 (10/rho_red)^0.33 (R_z1/R_z2)^0.66 / (nu40 v / 1500)^0.33
// R_z1: hard pinion, R_z2: wheel [um]; rho_red [mm]; nu40 [mm^2/s]; v pitch line velocity [m/s].
// ZW(HB) is this factor at R_zH <= 3 um. (2019 also adds through/through Z_W = 1 + A (u - 1).)
inline double ZWRough(double HB, double RzPinion_um, double RzWheel_um, double rhoRed_mm, double nu40,
                      double v) {
  double RzH = RzPinion_um * std::pow(10.0 / rhoRed_mm, 0.33) *
               std::pow(RzPinion_um / RzWheel_um, 0.66) / std::pow(nu40 * v / 1500.0, 0.33);
  RzH = std::min(16.0, std::max(3.0, RzH));
  return ZW(HB) * std::pow(3.0 / RzH, 0.15);
}

struct Bin { double stress; double cycles; };

// Cycles to failure on the S-N curve of ISO 6336-6 (the life curve of ISO 6336-2/-3 read the other
// way): permissible stress at N is sigmaLimit * f(N), f = lifeCurve({staticFactor, Nstatic, Nknee},
// N, endFactor). Returns sup{N : sigmaLimit f(N) >= stress}: 0 above the static strength, HUGE_VAL
// (infinite) where the stress is below the curve everywhere (r <= endFactor on the plain curve).
// Below the knee N = Nknee r^-q, r = stress/sigmaLimit, q = ln(Nknee/Nstatic)/ln(staticFactor).
// extendedMiner (an option, see the top of this file): beyond the knee the finite-life line is continued with
// Haibach's exponent 2p - 1 instead of the 0.85-at-1e10 branch, and without a fatigue limit.
// p is the exponent of the curve in LOAD terms, p = q * stressPerLoad, where stress ~ load^
// stressPerLoad (bending 1; contact 0.5 gives ISO 6336-6's p = 6.61 for q = 13.22). The default 1
// applies 2p - 1 to the stress exponent itself (q2 = 2q - 1); for contact with stressPerLoad = 0.5
// the stress exponent beyond the knee is 2(2p - 1) = 2q - 2 instead.
inline double cyclesToFailure(double stress, double sigmaLimit, double staticFactor, double Nstatic,
                              double Nknee, double endFactor, bool extendedMiner,
                              double stressPerLoad = 1.0) {
  const double r = stress / sigmaLimit;
  if (!(r > 0.0)) return HUGE_VAL;
  if (r > staticFactor) return 0.0;
  const double q = std::log(Nknee / Nstatic) / std::log(staticFactor);
  if (r >= 1.0) return Nknee * std::pow(r, -q);
  if (extendedMiner) {
    const double p = q * stressPerLoad;
    return Nknee * std::pow(r, -(2.0 * p - 1.0) / stressPerLoad);
  }
  if (r <= endFactor) return HUGE_VAL;
  const double qb = std::log(1e10 / Nknee) / std::log(1.0 / endFactor);
  return Nknee * std::pow(r, -qb);
}

// Palmgren-Miner damage sum D = sum n_i / N_i (ISO 6336-6 linear damage accumulation). Bins with
// n_i <= 0 add nothing; a bin above the static strength makes D infinite.
inline double damage(const std::vector<Bin>& bins, double sigmaLimit, double staticFactor, double Nstatic,
                     double Nknee, double endFactor, bool extendedMiner, double stressPerLoad = 1.0) {
  double D = 0.0;
  for (const Bin& b : bins) {
    if (!(b.cycles > 0.0)) continue;
    const double N = cyclesToFailure(b.stress, sigmaLimit, staticFactor, Nstatic, Nknee, endFactor,
                                     extendedMiner, stressPerLoad);
    if (N <= 0.0) return HUGE_VAL;
    if (N < HUGE_VAL) D += b.cycles / N;
  }
  return D;
}

// Safety of a spectrum (ISO 6336-6: the factor on every bin's stress at which D = 1): bisection in
// log k. D(k) is non-decreasing but can jump (plain curve at r = endFactor; static limit), so the
// result is the switch point sup{k : D(k) <= 1}. For contact the caller passes contact stresses,
// so k is a factor on stress (on torque it would be k^2). HUGE_VAL if no bin carries stress.
inline double spectrumSafety(const std::vector<Bin>& bins, double sigmaLimit, double staticFactor,
                             double Nstatic, double Nknee, double endFactor, bool extendedMiner,
                             double stressPerLoad = 1.0) {
  double smax = 0.0;
  for (const Bin& b : bins)
    if (b.cycles > 0.0) smax = std::max(smax, b.stress);
  if (!(smax > 0.0)) return HUGE_VAL;
  auto D = [&](double k) {
    std::vector<Bin> s(bins);
    for (Bin& b : s) b.stress *= k;
    return damage(s, sigmaLimit, staticFactor, Nstatic, Nknee, endFactor, extendedMiner, stressPerLoad);
  };
  double hi = 2.0 * staticFactor * sigmaLimit / smax;  // above the static strength: D infinite
  double lo = hi * 1e-6;
  for (int i = 0; i < 50 && D(lo) > 1.0; ++i) lo *= 1e-3;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (D(mid) > 1.0 ? hi : lo) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace gbx::ref6336

/* SELF-CHECK, computed by hand (arithmetic done step by step with bc -l, not with this code):
 a  = ln1.6/ln500 = 0.470004/6.214608 = 0.0756288 ; q = 1/a = 13.222468 (contact, Eh/V)
 b  = ln(1/0.85)/ln200 = 0.162519/5.298317 = 0.0306737 ; 1/b = 32.601232 (0.85 branch)
 ay = ln2.5/ln3000 = 0.916291/8.006368 = 0.1144452 (bending, Eh)
 1. ZNT(CaseHardened, 1e7) = (5e7/1e7)^a = exp(1.609438*0.0756288) = exp(0.121720) = 1.129438
 2. YNT(CaseHardened, 1e5) = (3e6/1e5)^ay = exp(3.401197*0.1144452) = exp(0.389250) = 1.475875
 3. ZNT(CaseHardened, 1e9) = (5e7/1e9)^b = exp(-2.995732*0.0306737) = exp(-0.091890) = 0.912205
 4. ZW(300) = 1.2 - (300-130)/1700 = 1.2 - 0.1 = 1.100000
 5. YdeltarelTStatic(CaseHardened, 2.1) = 0.44*2.1 + 0.12 = 1.044 ;
    ThroughHardened, 2.1, sigma02 900: c = 0.82*(1/3)^0.25 = 0.623065, (1+1.1c)/(1+c) = 1.038388
 6. shortLife(0.98, 1.0, 1e6, 1e5, 5e7): t = ln50/ln500 = 0.629488, 0.98^(1-t) = 0.992543
 7. damage, sigmaLimit 1500, Z_NT curve Eh (1.6, 1e5, 5e7, 0.85), plain curve:
    bin (1600, 1e5): r = 1.066667, ln r = 0.0645385, N = 5e7*exp(-13.222468*0.0645385) = 2.129909e7,
                     n/N = 0.00469504
    bin (1400, 1e7): r = 0.933333 < 1, -ln r = 0.0689929, N = 5e7*exp(32.601232*0.0689929)
                     = 4.740324e8, n/N = 0.0210956
    bin (1000, 1e8): r = 0.666667 <= 0.85: N infinite, n/N = 0
    D = 0.00469504 + 0.0210956 = 0.0257906
 8. same, extendedMiner (q2 = 2q - 1 = 25.444937):
    bin 2: N = 5e7*exp(25.444937*0.0689929) = 2.893226e8, n/N = 0.0345635
    bin 3: -ln r = 0.405465, N = 5e7*exp(25.444937*0.405465) = 1.512171e12, n/N = 0.0000661
    D = 0.00469504 + 0.0345635 + 0.0000661 = 0.0393247
 9. spectrumSafety, plain: for 1/0.9333 < k < 0.85/0.6667 bins 1, 2 lie below the knee and bin 3
    adds nothing, so D(k) = k^q [1.066667^q/500 + 0.2*0.933333^q] = k^q (0.00469504 + 0.0803234)
    = 0.0850184 k^q = 1 -> k^q = 11.762151, k = exp(ln(11.762151)/13.222468) = 1.204924
    (check: 0.666667k = 0.8033 < 0.85, 1.066667k = 1.2853 < 1.6).
 10. spectrumSafety, extendedMiner: 0.0850184 k^q + 2 (0.666667 k)^q2 = 1, Newton: k = 1.204240
*/
