#include "shaft/Iso281.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace gbx::rt::shaft {

bool isBall(BearingKind k) { return k == BearingKind::DeepGrooveBall || k == BearingKind::AngularContactBall; }

const char* kindName(BearingKind k) {
  switch (k) {
  case BearingKind::DeepGrooveBall: return "deep_groove_ball";
  case BearingKind::AngularContactBall: return "angular_contact_ball";
  case BearingKind::CylindricalRoller: return "cylindrical_roller";
  case BearingKind::TaperedRoller: return "tapered_roller";
  case BearingKind::SphericalRoller: return "spherical_roller";
  }
  return "";
}

double lifeFactorA1(double reliability) {
  double r = std::clamp(reliability, 0.9, 0.99);
  return 0.95 * std::pow(std::log(1 / r) / std::log(1 / 0.9), 2.0 / 3.0) + 0.05;
}

double ratedViscosity(double speed, double pitchDiameter) {
  double rpm = speed * 30 / 3.14159265358979323846, dpw = pitchDiameter * 1e3;
  double mm2s = rpm < 1000 ? 45000 * std::pow(rpm, -0.83) / std::sqrt(dpw) : 4500 / std::sqrt(rpm * dpw);
  return mm2s * 1e-6;
}

// ISO 281:2007 Annex A, per kappa band: a_ISO = 0.1 [1 - (A - c / kappa^q)^u (e_C C_u / P)^v]^-w,
// ball (A 2.5671, u 0.83, v 1/3, w 9.3) and roller (A 1.5859, u 1, v 0.4, w 9.185).
double lifeModification(bool ball, double kappa, double eCuP) {
  double k = std::clamp(kappa, 0.1, 4.0), x = std::clamp(eCuP, 0.0, 5.0);
  double q = k < 0.4 ? 0.054381 : k < 1 ? 0.19087 : 0.071739;
  double c = ball ? (k < 0.4 ? 2.2649 : 1.9987) : (k < 0.4 ? 1.3993 : 1.2348);
  // At kappa 0.1 the ball's base rounds to about 0: never a negative power base.
  double inner = ball ? 1 - std::pow(std::max(0.0, 2.5671 - c / std::pow(k, q)), 0.83) * std::cbrt(x)
                      : 1 - (1.5859 - c / std::pow(k, q)) * std::pow(x, 0.4);
  if (inner <= 0) return 50;
  return std::min(50.0, 0.1 * std::pow(inner, ball ? -9.3 : -9.185));
}

namespace {

// P = X Fr + Y Fa beyond Fa/Fr > e, Fr below (ISO 281 clause 5.1); a kind whose factors
// depend on its catalogue needs them given once an axial load acts.
double equivalentLoad(const BearingData& b, const BearingLoad& l, std::string& how) {
  double Fr = std::fabs(l.radial), Fa = std::fabs(l.axial);
  if (Fa == 0) {
    how = "P = F_r";
    return Fr;
  }
  if (b.kind == BearingKind::CylindricalRoller)
    throw std::invalid_argument(
        "a cylindrical roller bearing takes no axial load: let another bearing hold the thrust (`axial = held`)");
  if (b.e < 0 || b.X < 0 || b.Y < 0)
    throw std::invalid_argument(
        fmt::format("an axial load of {:.4g} N acts on this {} bearing: give its catalogue's `e`, `X` and `Y`", Fa,
                    kindName(b.kind)));
  if (Fr > 0 && Fa / Fr <= b.e) {
    how = fmt::format("F_a/F_r {:.3g} <= e {:.3g}: P = F_r", Fa / Fr, b.e);
    return Fr;
  }
  how = fmt::format("F_a/F_r > e {:.3g}: P = {:.3g} F_r + {:.3g} F_a", b.e, b.X, b.Y);
  return b.X * Fr + b.Y * Fa;
}

// P0 = max(Fr, X0 Fr + Y0 Fa) (ISO 76); a deep-groove ball bearing's X0 0.6, Y0 0.5.
double staticLoad(const BearingData& b, const BearingLoad& l) {
  double Fr = std::fabs(l.radial), Fa = std::fabs(l.axial);
  double X0 = b.X0, Y0 = b.Y0;
  if (X0 < 0 || Y0 < 0) {
    if (b.kind == BearingKind::DeepGrooveBall)
      X0 = 0.6, Y0 = 0.5;
    else if (Fa == 0 || b.kind == BearingKind::CylindricalRoller)
      X0 = 1, Y0 = 0;
    else
      throw std::invalid_argument(
          fmt::format("an axial load acts on this {} bearing: give its catalogue's `X0` and `Y0`", kindName(b.kind)));
  }
  return std::max(Fr, X0 * Fr + Y0 * Fa);
}

} // namespace

BearingLife life(const BearingData& b, const BearingLoad& l, const LifeSettings& s) {
  if (!(b.C > 0) || !(b.C0 > 0)) throw std::invalid_argument("a bearing needs its load ratings `C` and `C0`");
  BearingLife out;
  std::string how;
  out.P = equivalentLoad(b, l, how);
  out.P0 = staticLoad(b, l);
  out.s0 = out.P0 > 0 ? b.C0 / out.P0 : INFINITY;
  bool ball = isBall(b.kind);
  double p = ball ? 3.0 : 10.0 / 3.0;
  out.L10 = out.P > 0 ? std::pow(b.C / out.P, p) : INFINITY;
  double rpm = std::fabs(l.speed) * 30 / 3.14159265358979323846;
  out.L10h = rpm > 0 ? out.L10 * 1e6 / (60 * rpm) : INFINITY;
  out.a1 = lifeFactorA1(s.reliability);
  out.method = how + fmt::format(", p = {}", ball ? "3" : "10/3");
  if (s.viscosity > 0 && b.pitchDiameter > 0 && rpm > 0 && out.P > 0) {
    double Cu = b.fatigueLimit;
    if (Cu < 0) {
      // ISO 281 Annex B: C_u from C0, reduced beyond a pitch diameter of 100 mm.
      double dpw = b.pitchDiameter * 1e3;
      Cu = b.C0 / (ball ? 22 : 8.2) * (dpw > 100 ? std::pow(100 / dpw, ball ? 0.5 : 0.3) : 1.0);
    }
    out.kappa = s.viscosity / ratedViscosity(std::fabs(l.speed), b.pitchDiameter);
    out.aIso = lifeModification(ball, out.kappa, s.contamination * Cu / out.P);
    out.Lnmh = out.a1 * out.aIso * out.L10h;
    out.method +=
        fmt::format("; kappa {:.3g}{}, e_C {:.3g}, C_u {:.4g} N: a_ISO {:.3g}", out.kappa,
                    s.viscositySource.empty() ? "" : " (" + s.viscositySource + ")", s.contamination, Cu, out.aIso);
  } else {
    out.Lnmh = out.a1 * out.L10h;
    out.method += "; a_ISO 1 (no viscosity)";
  }
  return out;
}

} // namespace gbx::rt::shaft
