#pragma once
// Rolling bearing life, ISO 281:2007: the basic rating life L10, the modified life
// L_nm = a1 a_ISO L10 with the viscosity ratio kappa and the contamination factor e_C, and the
// static safety s0 = C0 / P0 (ISO 76). SI throughout (N, rad/s, m, m^2/s).
#include <string>

namespace gbx::rt::shaft {

enum class BearingKind { DeepGrooveBall, AngularContactBall, CylindricalRoller, TaperedRoller, SphericalRoller };
bool isBall(BearingKind k);
const char* kindName(BearingKind k);

struct BearingLoad {
  double radial = 0, axial = 0; // N
  double speed = 0;             // rad/s of the ring that turns
};

struct BearingData {
  BearingKind kind = BearingKind::DeepGrooveBall;
  double C = 0, C0 = 0;          // basic dynamic and static load ratings, N
  double e = -1, X = -1, Y = -1; // equivalent-load factors; < 0: the kind's own (a pure radial load where it has none)
  double X0 = -1, Y0 = -1;       // static equivalent-load factors; < 0: the kind's
  double pitchDiameter = 0;      // D_pw, m
  double fatigueLimit = -1;      // C_u, N; < 0: from C0 (ISO 281 Annex B's approximation)
};

struct LifeSettings {
  double reliability = 0.9;   // 0.9 .. 0.99
  double contamination = 0.5; // e_C
  double viscosity = -1;      // nu at the operating temperature, m^2/s; < 0: no modified life
  std::string viscositySource; // where nu came from, for the method line
};

struct BearingLife {
  double P = 0, P0 = 0; // dynamic and static equivalent loads, N
  double L10 = 0;       // million revolutions
  double L10h = 0;      // hours
  double a1 = 1, kappa = 0, aIso = 1;
  double Lnmh = 0;    // modified life, hours (L10h where no viscosity is known)
  double s0 = 0;      // static safety C0 / P0
  std::string method; // how P, kappa and a_ISO were found
};

// a1 of ISO 281 for a reliability between 90 % and 99 %.
double lifeFactorA1(double reliability);
// nu1, the rated viscosity (m^2/s) at a speed (rad/s) and pitch diameter (m).
double ratedViscosity(double speed, double pitchDiameter);
// a_ISO of a radial ball or roller bearing (kappa and e_C C_u / P within ISO 281's caps).
double lifeModification(bool ball, double kappa, double eCuP);

// Throws std::invalid_argument for ratings or loads that are not positive where they must be.
BearingLife life(const BearingData& b, const BearingLoad& l, const LifeSettings& s);

} // namespace gbx::rt::shaft
