#pragma once
// Load capacity of one cylindrical gear mesh by ISO 6336-1, -2, -3 (2006 with
// Corrigendum 1:2008), method B unless a factor is given (docs/rating.md). Inputs and
// outputs are SI except where the standard's factor is conventionally a pure number in
// its own units (Z_E in sqrt(N/mm^2)). Internally the formulas run in the standard's
// units: mm, N, um, N/mm^2.
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "rating/Scuffing.h"

namespace gbx::rt::rating {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Treatment { CaseHardened, Nitrided, ThroughHardened };
enum class KvRange { Given, Subcritical, MainResonance, Intermediate, Supercritical };

struct GearInput {
  double z = 0;              // tooth count (external gears)
  double x = 0;              // profile shift coefficient
  double tipDiameter = kNaN; // [m]; NaN: from the basic rack, the shift and the tip alteration
  double fpb = 0;            // base pitch deviation [m]
  double ffa = 0;            // profile form deviation [m]
  double fHb = 0;            // helix slope deviation [m]
  double speed = 0;          // [rad/s]
  double cyclesPerRev = 1;   // load cycles per revolution
  double YM = 1;             // mean stress factor (0.7 for a gear loaded on both flanks)
  double webFactor = 1;      // C_R of the gear blank (1 for a solid gear)
  double bore = 0;           // inner diameter of the gear blank [m] (0: solid)
  double sigmaHlim = 0, sigmaFlim = 0;  // [Pa]
  bool internal = false;     // an internal gear (the wheel of the pair only): z, d signed negative inside
  // A gear of its own material (`pinion.material`): its treatment and elastic constants;
  // unset, the pair's. brinell: HB of a through-hardened gear (its Z_W against a harder mate).
  std::optional<Treatment> treatment = std::nullopt;
  double E = kNaN, nu = kNaN, brinell = kNaN;
  // Normal tooth-thickness allowances A_sne, A_sni [m]: the report's backlash (NaN: not given).
  double upperAllowance = kNaN, lowerAllowance = kNaN;
  // An internal gear's pinion-type cutter (teeth 0: not given, and its root is not rated; tip
  // radius NaN: the basic rack's root radius) and its rim under the root s_R [m] (NaN: Y_B 1).
  double cutterTeeth = 0, cutterShift = 0, cutterTipRadius = kNaN;
  double rimThickness = kNaN;
  double RzFlank = kNaN, RzRoot = kNaN; // this gear's own roughness [m]; NaN: the pair's
};

struct PairInput {
  std::array<GearInput, 2> gear;  // pinion (driving), wheel
  double mn = 0, alphaN = 0, beta = 0, b = 0;
  double a = kNaN;         // working centre distance [m]; NaN: from the shifts
  double aAllowance = 0;   // centre distance allowance A_a, either way [m] (the report's backlash)
  double torque1 = 0;      // pinion torque [N m]
  double E = 206e9, nu = 0.3, density = 7830;  // [Pa], [-], [kg/m^3]
  Treatment treatment = Treatment::CaseHardened;
  bool optimumLife = false;
  int grade = 0;           // ISO 1328-1 grade, 0 when not given (Y_DT)
  double KA = 1, Kgamma = 1;
  double life = 0;         // [s]
  double nu40 = 0;         // [m^2/s]
  double RzFlank = 0, RzRoot = 0;  // [m]
  double haP = 1.0, hfP = 1.25, rhoFP = 0.38;
  double KHbetaGiven = kNaN, KvGiven = kNaN, KHalphaGiven = kNaN;
  double cgammaGiven = kNaN;  // c_gamma_alpha [N/m per m]
  double tipRelief = kNaN;    // C_a [m]; NaN: the running-in amount
  double fma = kNaN;          // mesh misalignment [m]; NaN: the larger f_Hbeta
  double B1 = 1, B2 = 1;      // lead modification factors of F_betax (crowning, helix correction)
  double SHmin = 1, SFmin = 1;
  int planets = 0;            // a sun meshing with this many planets (reduced mass of K_v)
  // Scuffing and micropitting (ISO/TS 6336-20, -21, -22; rating/Scuffing.h): the oil, with its
  // FZG or FVA load stage; without one, neither is rated.
  std::optional<Lubricant> oil = std::nullopt;
  double RaFlank = kNaN;      // [m]
  double SBmin = 1.5, SintSmin = 1.8, SLmin = 1.0;
};

struct GearRating {
  double tipDiameter, rootDiameter, cycles;
  double fpb, ffa, fHb;  // the deviations rated with [m]
  double ZNT, ZL, Zv, ZR, ZW, ZX, ZBD;
  double sFn, hFe, rhoF, alphaFen, YF, YS, Ybeta, YB, YDT, YNT, YdeltarelT, YRrelT, YX, YM;
  double sigmaH, sigmaHP, SH, sigmaF0, sigmaF, sigmaFP, SF;
  // Under a load spectrum (rating/Spectrum.h): SH and SF are its safeties, these the
  // operating torque's; the Miner sums of the spectrum (or of the operating torque alone).
  double SHoperating = kNaN, SFoperating = kNaN, contactDamage = kNaN, bendingDamage = kNaN;
};

struct PairRating {
  double Ft, v, u, alphaWt, epsAlpha, epsBeta, epsGamma;
  double Fbt;         // transverse force along the line of action, F_t / cos alpha_t [N]
  double b, dPinion;  // face width and the smaller external gear's reference diameter [m]
  double cprime, cgammaAlpha, cgammaBeta, mred, nE1, N, NS;
  KvRange kvRange;
  double fsh, fma, FbetaX, FbetaY, yBeta, yAlpha;  // fma: the manufacturing misalignment used [m]
  double B1, B2;                                   // the lead modification factors used
  double Kgamma;                                   // the mesh load factor rated with (the input's)
  double Kv, KHbeta, KFbeta, KHalpha, KFalpha;
  double ZH, ZE, Zeps, Zbeta, sigmaH0;
  std::array<GearRating, 2> gear;
  std::optional<ScuffingRating> scuffing = std::nullopt;  // when the oil's load stages are given
  std::string rootError; // why an internal gear's root is not rated though its cutter is given
};

// Every factor and both safeties of the mesh. Throws std::domain_error with a sentence
// when the geometry admits no rating (no contact, no 30-degree tangent in the fillet).
// An internal wheel's tooth root is rated from its pinion-type cutter (rating/InternalRoot.h);
// without one its bending values are NaN.
PairRating rate(const PairInput& in);

// A treatment's life curve: its static point and its knee (ISO 6336-2 Table 2, ISO 6336-3
// Table 3); beyond the knee it falls to the end value at 10^10 cycles.
struct LifeCurve {
  double nStatic, fStatic, nKnee;
};
LifeCurve contactCurve(Treatment t);
LifeCurve bendingCurve(Treatment t);

// The material and lubrication factors ISO 10300 takes from ISO 6336 (the standards' units:
// N/mm^2, mm^2/s, m/s, um, mm). Life factor Z_NT or Y_NT on a life curve ("normal" ends at
// 0.85 at 10^10 cycles, "optimum" at 1).
double lifeFactorOf(double cycles, const LifeCurve& c, bool optimum);
// The running-in allowance of a deviation f [um] on a flank of this treatment (y_alpha, y_p).
double runningIn(double f, Treatment t, double sigmaHlim, double v);
// Z_W: a through-hardened gear of Brinell hardness HB against a surface-hardened mate.
double workHardeningFactor(Treatment mine, Treatment mate, double brinell);
// Z_L, Z_v, Z_R at endurance from the softer flank's sigma_Hlim, nu40, the pitch-line
// velocity, the mean flank Rz and the relative radius of curvature; then at a gear's cycles
// (below the knee they move toward 1 as Z_NT does).
struct FlankFactors {
  double ZL, Zv, ZR;
};
FlankFactors flankFactors(double sigmaHlim, double nu40, double v, double Rz, double rhoRed);
FlankFactors flankFactorsAt(const FlankFactors& endurance, double cycles, Treatment t);
// Y_deltarelT (method B, from the notch parameter q_s), Y_RrelT and Y_X (from the module) at
// a gear's cycles.
struct RootFactors {
  double YdeltarelT, YRrelT, YX;
};
RootFactors rootFactors(Treatment t, double qs, double YS, double RzRoot, double mn, double cycles);

// ISO 6336-3 method B for one external gear of the pair: the critical section (30-degree
// tangent) of the fillet the basic rack generates, the load at the outer point of single
// pair contact. Lengths in mm, angles in rad.
struct ToothForm {
  double sFn, hFe, rhoF, alphaFen, YF, YS, theta;
  double gamma;  // half the tooth's angle at the load diameter (its thickness there: gamma d)
};
// The same construction for any load diameter d_load of the normal section's virtual gear of
// z_n teeth, with a thickness modification x_sm (ISO 10300-3 takes it at the tip); the rack's
// dedendum and root radius as multiples of m_n. Unchecked: the caller refuses a section
// without a tangent.
ToothForm filletForm(double zn, double mn, double alphaN, double x, double xsm, double hfP, double rhoFP, double dLoad);
// Y_F and Y_S of a critical section (its s_Fn, h_Fe, rho_F, alpha_Fen in mm and rad), by
// ISO 6336-3's formulas, external or internal alike.
void formAndStressFactors(ToothForm& t, double mn, double alphaN);
ToothForm toothForm(double z, double x, double tipDiameter, double mn, double alphaN, double beta, double epsAlpha,
                    double hfP, double rhoFP);

} // namespace gbx::rt::rating
