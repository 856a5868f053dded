#pragma once
// Load capacity of a bevel gear pair without hypoid offset by ISO 10300-1, -2, -3, method B1:
// virtual cylindrical gears in the mean normal section (docs/rating.md). The bevel geometry is
// ISO 23509's as far as the rating needs it. Inputs and outputs are SI; the formulas run in
// the standard's units (mm, N, um, N/mm^2).
#include <array>
#include <optional>

#include "rating/Iso6336.h"

namespace gbx::rt::rating {

// Bearing arrangement of the pair (ISO 10300-1 K_Hbeta-be).
enum class Mounting { BothStraddle, OneCantilever, BothCantilever };

struct BevelGearInput {
  double z = 0;
  double xhm = 0;             // mean profile shift coefficient
  double xsm = 0;             // thickness modification coefficient
  double edgeRadius = kNaN;   // cutter edge radius rho_a0 [m]; NaN: 0.2 m_mn
  double fpt = 0;             // single pitch deviation [m]
  double speed = 0;           // [rad/s]
  double sigmaHlim = 0, sigmaFlim = 0;  // [Pa]
  std::optional<Treatment> treatment = std::nullopt;  // unset: the pair's
  double E = kNaN, nu = kNaN, brinell = kNaN;
};

struct BevelInput {
  std::array<BevelGearInput, 2> gear;  // pinion (driving), wheel
  double shaftAngle = 1.5707963267948966, betaM = 0, alphaN = 0.3490658503988659;
  double alphaNCoast = kNaN;   // NaN: the drive flank's
  // Size: the outer cone distance, else the mean normal module; the face width, else the face
  // ratio b/R_e.
  double Re = kNaN, mmn = kNaN, b = kNaN, faceRatio = kNaN;  // [m], [m], [m], [-]
  double cutterRadius = kNaN;  // r_c0 [m]; NaN: K_F0 = 1
  double torque1 = 0;          // pinion torque [N m]
  double E = 206e9, nu = 0.3, density = 7830;
  Treatment treatment = Treatment::CaseHardened;
  bool optimumLife = false;
  double KA = 1, life = 0, nu40 = 0;   // [-], [s], [m^2/s]
  double RzFlank = 0, RzRoot = 0;      // [m]
  double khap = 1.0, khfp = 1.25;      // basic crown gear addendum and dedendum factors
  double contactPattern = 0.85;        // b_eff / b
  Mounting mounting = Mounting::BothStraddle;
  double KvGiven = kNaN, KHbetaGiven = kNaN, KHalphaGiven = kNaN;
  double SHmin = 1, SFmin = 1;
};

struct BevelGearRating {
  // ISO 23509 geometry [m]
  double cone, dm, de, ham, hfm;
  // the virtual cylindrical gear: transverse [m], and its tooth counts
  double dv, dva, dvb, zv, zvn;
  double cycles;
  double ZNT, ZL, Zv, ZR, ZW, ZX;
  double sFn, hFa, rhoF, YFa, YSa, YNT, YdeltarelT, YRrelT, YX;
  double sigmaH, sigmaHG, sigmaHP, SH;       // [Pa]
  double sigmaF0, sigmaF, sigmaFG, sigmaFP, SF;
  double sAn;  // normal tooth thickness at the virtual gear's tip [m]
};

struct BevelRating {
  double Re, Rm, b, bEff, mmn, mmt;        // [m]
  double av, uv, alphaVt, betaVb;          // [m], [-], [rad], [rad]
  double gva, epsVa, epsVb, epsVg;
  double rhoRel, lbm, lbt, fmax;           // [m]
  double Ft, Fn, v;                        // F_mt [N], normal force [N], v_mt [m/s]
  double cprime, cgamma, mred, nE1, N;     // [N/(mm um)], [kg/mm], [rpm]
  KvRange kvRange;
  double yAlpha;                           // running-in of the pitch deviation [um]
  double Kv, KHbetaBe, KHbeta, KF0, KFbeta, KHalpha, KFalpha;
  double ZMB, ZLS, ZE, Zbeta, ZK, sigmaH0, sigmaH;  // [Pa]
  double Yeps, YLS, YBS;
  std::array<BevelGearRating, 2> gear;
};

// Every factor and both safeties of the pair. Throws std::domain_error with a sentence when
// the geometry admits no rating.
BevelRating rateBevel(const BevelInput& in);
// The geometry alone (the cone, the virtual gears and their contact ratios) and the nominal
// load F_mt and speed v_mt, for a stage that is not rated: the rest of the rating is zero.
BevelRating bevelGeometry(const BevelInput& in);

} // namespace gbx::rt::rating
