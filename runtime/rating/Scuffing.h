#pragma once
// Scuffing by the flash temperature (ISO/TS 6336-20) and by the integral temperature
// (ISO/TS 6336-21), and micropitting by the specific film thickness (ISO/TS 6336-22
// method B) of one cylindrical mesh, along its path of contact (docs/rating.md). An internal
// mesh is written in the signed convention (its ring's z2, tip diameter and the centre
// distance negative); the standards are written for external gears, so its results are for
// information. Inputs are SI; inside, the formulas run in the standards' units (mm, N, m/s,
// N/mm^2, mPa s, degC).
#include <array>
#include <limits>
#include <vector>

namespace gbx::rt::rating {

// The standards' editions where they differ (docs/rating.md names each difference).
enum class ScuffingEdition { TS, TR };

enum class OilBase { Mineral, Polyalphaolefin, Polyglycol, PhosphateEster, Traction };

struct Lubricant {
  double nu40 = 0, nu100 = 0;        // kinematic viscosity at 40 and 100 degC [m^2/s]
  double density15 = 890;            // at 15 degC [kg/m^3]
  double oilTemperature = 0;         // sump or injection [K]
  int fzgStage = 0;                  // FZG A/8.3/90 failure load stage (0: scuffing not rated)
  int fvaStage = 0;                  // FVA 54/7 failure load stage (0: micropitting not rated)
  OilBase base = OilBase::Mineral;
  bool injection = false;

  // The ASTM D341 line through (40 degC, nu40) and (100 degC, nu100): log log (nu + 0.7)
  // linear in log T, nu in mm^2/s. T in K; results SI.
  double kinematic(double T) const;
  double density(double T) const;  // ISO/TS 6336-22: rho15 - 0.7 kg/m^3 per K above 289 K
  double dynamic(double T) const;  // [Pa s]
};

// The mesh as the ISO 6336 rating found it: geometry, the load with its factors, speed.
struct ScuffingMesh {
  double z1 = 0, z2 = 0;                             // pinion (driving) and wheel tooth counts (a ring's negative)
  double mn = 0, alphaN = 0, beta = 0, a = 0, b = 0; // [m], [rad], working centre distance [m] (negative: internal)
  double da1 = 0, da2 = 0;                           // tip diameters [m] (a ring's negative)
  double Ft = 0;                  // nominal tangential force at the reference circle [N]
  double KA = 1, Kgamma = 1, Kv = 1, KHbeta = 1, KHalpha = 1;
  double speed1 = 0;              // pinion [rad/s]
  double power = 0;               // [W]
  std::array<double, 2> E{206e9, 206e9}, nu{0.3, 0.3};
  // Thermal contact coefficient sqrt(lambda rho c) [N/(m s^0.5 K)]; steel: lambda 50 W/(m K),
  // rho c 3.8 N/(mm^2 K) (ISO/TS 6336-21).
  std::array<double, 2> BM{13784.0, 13784.0};
  double Ra = 0;                  // flank roughness, the mean of both gears [m]
  std::array<double, 2> Ca{0, 0}; // tip relief of pinion and wheel [m]
  double cgamma = 20e9;           // mesh stiffness c_gamma_alpha [N/m per m] (the effective tip relief C_eff)
  double XW = 1;                  // structural factor (scuffing)
  double WW = 1;                  // material factor (micropitting)
  double Xmp = 1;                 // multiple mating factor (1 + n_p)/2 of a gear in n_p meshes
  int grade = 0;                  // ISO 1328-1 grade (a spur mesh's load sharing; 0: unknown, as 7)

  // K_A K_gamma K_v K_Hbeta K_Halpha, the load factors of w_Bt and of the local pressure.
  double loadFactor() const { return KA * Kgamma * Kv * KHbeta * KHalpha; }
  // The effective tip relief C_eff = K_A F_t / (b c_gamma) [um].
  double effectiveRelief() const { return KA * Ft / (b * 1e3 * cgamma * 1e-9); }
};

struct PathPoint {
  double gamma;       // position on the path of contact: rho_1 / rho_C1 - 1 (0 at the pitch point)
  double XGamma;      // load sharing factor (with the buttressing factor)
  double thetaFla;    // flash temperature [K above theta_M]
  double thetaB;      // contact temperature [K]
  double h;           // film thickness [m]
  double lambda;      // specific film thickness h / Ra
};

struct ScuffingRating {
  bool scuffing = false, micropitting = false;
  // Geometry on the path of contact.
  double gammaA = 0, gammaB = 0, gammaD = 0, gammaE = 0, epsAlpha = 0, epsBeta = 0;
  // Flash temperature (TS 6336-20).
  double wBt = 0, KBgamma = 1, XalphaBeta = 0, XM = 0, XL = 0, XS = 1, XR = 0, etaOil = 0, muM = 0, Ceff = 0;
  double vw = 0;  // pitch-line velocity on the working circle [m/s] (the methods' tests reach 80)
  double thetaFlm = 0, thetaM = 0, thetaS = 0, thetaBmax = 0, gammaMax = 0, XGammaMax = 0, SB = 0;
  // Integral temperature (TS 6336-21).
  double thetaFlaInt = 0, thetaMInt = 0, thetaInt = 0, thetaIntS = 0, SintS = 0;
  // Micropitting (TS 6336-22 method B).
  double muMmp = 0, thetaMmp = 0, lambdaGFT = 0, lambdaGFP = 0, lambdaMin = 0, gammaLambdaMin = 0, Slambda = 0;
  std::vector<PathPoint> path;  // A to E
};

// Every value above; throws std::domain_error with a sentence when the mesh admits none.
ScuffingRating rateScuffing(const ScuffingMesh& m, const Lubricant& oil, ScuffingEdition edition = ScuffingEdition::TS);

// The pinion torque of an FZG load stage [N m] (A/8.3/90 and FVA 54/7 share the steps).
double fzgPinionTorque(int stage);

} // namespace gbx::rt::rating
