#include "passes/Ratings.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "catalogue/StageKinds.h"
#include "model/kinds/Geometry.h"

#include "model/BevelRows.h"
#include "model/Evaluator.h"
#include "model/RatingRows.h"
#include "units/Unit.h"

namespace gbx::rt::passes {

namespace {

using rating::GearRating;
using rating::PairRating;

const char* rangeName(rating::KvRange r) {
  switch (r) {
  case rating::KvRange::Given: return "given";
  case rating::KvRange::Subcritical: return "subcritical";
  case rating::KvRange::MainResonance: return "main resonance";
  case rating::KvRange::Intermediate: return "intermediate";
  case rating::KvRange::Supercritical: return "supercritical";
  }
  return "";
}

// How the factors from the models were found, and the line load across the face.
void modelNotes(const rating::MeshRating& mr, RatingReport& out) {
  const PairRating& r = mr.rating;
  // The deviations rated with, and whose they are.
  auto dev = [&](double GearRating::*m, auto given, const char* what) {
    std::string o = what;
    for (size_t g = 0; g < 2; ++g) o += fmt::format("{} {:.3g} um ({})", g ? "," : "", r.gear[g].*m * 1e6, given(mr.given[g]));
    return o;
  };
  out.model.push_back(
      "deviations: " +
      dev(&GearRating::fpb, [](const auto& s) { return s.pitch ? "given" : "the grade's f_pt cos alpha_t"; }, "f_pb") + "; " +
      dev(&GearRating::ffa,
          [](const auto& s) { return s.profileForm ? "given" : s.profileTotal ? "the spec's profile_deviation" : "the grade's"; },
          "f_falpha") +
      "; " + dev(&GearRating::fHb, [](const auto& s) { return s.helix ? "given" : "the grade's"; }, "f_Hbeta"));
  if (!mr.faceLoad && !std::isfinite(mr.input.KHbetaGiven))
    out.model.push_back(fmt::format("K_Hbeta method B: f_sh {:.3g} um from 0.023 (F_m/b)(b/d1)^2 (a pinion centred between its bearings; "
                                    "a spec's bending_deflection and torsion_deflection reach the contact analysis, not this formula), "
                                    "f_ma {:.3g} um, B1 {:.2g}, B2 {:.2g}: F_betax {:.3g} um, running-in y_beta {:.3g} um",
                                    r.fsh, r.fma * 1e6, r.B1, r.B2, r.FbetaX, r.yBeta));
  if (mr.faceLoad) {
    const rating::FaceLoad& f = *mr.faceLoad;
    out.model.push_back(fmt::format("K_Hbeta: the largest line load across the face over one mesh period, {:.4g} N/mm at {:.1f} mm from "
                                    "{}, over the mean {:.4g} N/mm (the loaded mesh at F_m = F_t K_A K_gamma K_v, "
                                    "misalignment f_ma {:.3g} um; no running-in allowance)",
                                    f.KHbeta * f.meanLineLoad * 1e-3, f.peak * f.faceWidth * 1e3,
                                    f.shafts.empty() ? "the coupling end" : "the face's end nearer the shafts' left ends",
                                    f.meanLineLoad * 1e-3, r.fma * 1e6));
    for (const auto& line : f.model) out.model.push_back(line);
    for (size_t j = 0; j < f.lineLoad.size(); ++j) {
      out.facePosition.push_back((static_cast<double>(j) + 0.5) / static_cast<double>(f.lineLoad.size()) * f.faceWidth * 1e3);
      out.lineLoad.push_back(f.lineLoad[j] * 1e-3);
    }
    out.meanLineLoad = f.meanLineLoad * 1e-3;
  }
  if (mr.kv) {
    // S_H goes with sqrt(K_v), S_F with K_v: the scene's error carried into them.
    if (mr.kv->error >= 0)
      out.model.push_back(fmt::format("K_v: the peak periodic mesh force of scene `{}` over its largest quasi-static force (a fluctuating load torque is K_A's); its error estimate {:.1e} "
                                      "moves S_H by {:.1e} and S_F by {:.1e} (relative)",
                                      mr.kv->scene, mr.kv->error, 0.5 * mr.kv->error, mr.kv->error));
    else
      out.model.push_back(fmt::format("K_v: the peak periodic mesh force of scene `{}` over its largest quasi-static force (a fluctuating load torque is K_A's) (no error estimate)", mr.kv->scene));
  }
}

// The usual speed of an accuracy grade, m/s (helical; spur two thirds of it); none to 4.
double usualSpeed(int grade) {
  static const double helical[] = {0, 0, 0, 0, 0, 40, 30, 20, 12, 8, 5, 3, 2};
  return grade >= 5 && grade <= 12 ? helical[grade] : 0;
}

// What a rating engineer expects to be told (docs/rating.md).
void warnings(const rating::MeshRating& mr, RatingReport& out) {
  const PairRating& r = mr.rating;
  double bd = r.b / r.dPinion;
  if (bd > 1.2)
    out.warnings.push_back(fmt::format("b/d1 = {:.2f}: beyond the usual 1.2 for a pinion between two bearings; the face load "
                                       "distribution (K_Hbeta {:.3f}) rests on the shaft's deflection, which a wide pinion magnifies",
                                       bd, r.KHbeta));
  if (r.KHbeta > 2)
    out.warnings.push_back(fmt::format("K_Hbeta = {:.3f} > 2: the flanks carry load over part of the face only", r.KHbeta));
  if (r.epsAlpha < 1.2)
    out.warnings.push_back(fmt::format("eps_alpha = {:.3f} < 1.2: little transverse overlap; a tip chamfer, wear or a deflection leaves "
                                       "single-pair contact at the tips",
                                       r.epsAlpha));
  double usual = usualSpeed(mr.input.grade) * (r.epsBeta > 0 ? 1.0 : 2.0 / 3.0);
  if (usual > 0 && r.v > usual)
    out.warnings.push_back(fmt::format("pitch-line velocity {:.1f} m/s is beyond the usual {:.0f} m/s of accuracy grade {} for a {} pair", r.v,
                                       usual, mr.input.grade, r.epsBeta > 0 ? "helical" : "spur"));
}

// Under a load spectrum the safeties are its own: the operating torque's and the damage
// sums follow them.
void spectrumRows(const PairRating& r, size_t contactRow, RatingReport& out) {
  using Row = RatingReport::Row;
  auto gear = [&](std::string key, double GearRating::*m, Row::Format f, std::string label) {
    out.rows.push_back({std::move(key), std::move(label), "", 1.0, true, {r.gear[0].*m, r.gear[1].*m}, f, Row::NoMinimum});
  };
  bool spectrum = std::isfinite(r.gear[0].SHoperating);
  // A damage of 0 is no rounding: a stress below the life curve's endurance end does none.
  const char* miner = spectrum ? "Miner over the load spectrum; 0 where every stress is below the endurance limit"
                               : "Miner, the operating torque over the life; 0 below the endurance limit";
  if (spectrum) {
    out.rows.back().method = out.rows[contactRow].method = "under the load spectrum (ISO 6336-6, Miner)";
    gear("contact_safety_operating", &GearRating::SHoperating, Row::Plain, "contact_safety at the operating torque");
    gear("bending_safety_operating", &GearRating::SFoperating, Row::Plain, "bending_safety at the operating torque");
  }
  gear("contact_damage", &GearRating::contactDamage, Row::Count, "contact_damage");
  out.rows.back().method = miner;
  gear("bending_damage", &GearRating::bendingDamage, Row::Count, "bending_damage");
  out.rows.back().method = miner;
}

// Scuffing (ISO/TS 6336-20, -21) and micropitting (ISO/TS 6336-22 method B) of the mesh, with
// the ISO/TR edition's safety beside the TS's where the editions differ.
void scuffingRows(const rating::MeshRating& mr, RatingReport& out) {
  const rating::PairInput& in = mr.input;
  if (!in.oil) return;
  // The standards are written for external gears: an internal mesh's results are printed for
  // information, with no minimum beside them, and stay out of the design's quantities.
  const bool info = mr.internal;
  // The rating of the stage has the TS's; without it, asking again gives the reason.
  std::string why;
  auto ts = mr.rating.scuffing ? mr.rating.scuffing : rating::scuffingOf(in, mr.rating, rating::ScuffingEdition::TS, &why);
  if (!ts) {
    out.notRated.push_back({out.gears[0], "scuffing and micropitting", why});
    return;
  }
  auto tr = rating::scuffingOf(in, mr.rating, rating::ScuffingEdition::TR);
  using Row = RatingReport::Row;
  auto row = [&](std::string key, double v, std::string unit, double scale, std::string method,
                 Row::Minimum min = Row::NoMinimum, double offset = 0) {
    if (info && min != Row::NoMinimum) method += "; for information (written for external gears)";
    Row r{key, key, std::move(unit), scale, false, {v}, Row::Plain, info ? Row::NoMinimum : min, std::move(method)};
    r.offset = offset;
    out.rows.push_back(std::move(r));
  };
  // An absolute temperature in the report's unit (degC), a rise (theta_flm) in K.
  const units::DisplayUnit absolute = units::displayUnitFor(units::dims::temperature), rise = units::differenceUnitFor(units::dims::temperature);
  auto temperature = [&](std::string key, double K, std::string method, Row::Minimum min = Row::NoMinimum) {
    row(std::move(key), K, absolute.name, absolute.scale, std::move(method), min, absolute.offset);
  };
  auto trBeside = [&](double tsValue, double trValue) {
    return std::fabs(trValue / tsValue - 1) > 0.03 ? fmt::format("; ISO/TR 13989: {}", formatNumber(trValue)) : std::string();
  };
  const rating::ScuffingRating& s = *ts;
  std::string supply = in.oil->injection ? "injection" : "dip";
  row("K_Bgamma", s.KBgamma, "", 1, "helical load factor from eps_gamma");
  row("w_Bt", s.wBt * 1e3, "N/mm", 1e3, "K_A K_gamma K_v K_Hbeta K_Halpha F_t / b");
  row("mu_m", s.muM, "", 1, "ISO/TS 6336-20, at the pitch point" + trBeside(s.muM, tr->muM));
  row("X_M", s.XM, "", 1, "thermo-elastic factor, steel");
  row("X_alphabeta", s.XalphaBeta, "", 1, "angle factor");
  row("X_L", s.XL, "", 1, "lubricant factor of the base oil" + trBeside(s.XL, tr->XL));
  row("theta_flm", s.thetaFlm, rise.name, rise.scale, "mean flash temperature over the path");
  temperature("bulk_temperature", s.thetaM, fmt::format("oil + 0.47 X_S X_mp theta_flm, {} lubrication", supply));
  temperature("contact_temperature", s.thetaBmax, fmt::format("largest along the path, at Gamma {}", formatNumber(s.gammaMax)));
  if (s.scuffing) {
    temperature("scuffing_temperature", s.thetaS, fmt::format("FZG A/8.3/90 load stage {}", in.oil->fzgStage) + trBeside(s.thetaS - 273.15, tr->thetaS - 273.15));
    row("scuffing_safety", s.SB, "", 1, "flash temperature, ISO/TS 6336-20" + trBeside(s.SB, tr->SB), Row::Scuffing);
    row("theta_flaint", s.thetaFlaInt, rise.name, rise.scale, "mean flash temperature, ISO/TS 6336-21");
    temperature("integral_temperature", s.thetaInt, "theta_M + 1.5 theta_flaint");
    temperature("integral_scuffing_temperature", s.thetaIntS, fmt::format("FZG load stage {}", in.oil->fzgStage));
    row("integral_scuffing_safety", s.SintS, "", 1, "theta_intS / theta_int in degC, ISO/TS 6336-21", Row::IntegralScuffing);
  }
  if (s.micropitting) {
    temperature("bulk_temperature_micropitting", s.thetaMmp, "ISO/TS 6336-22: from the power loss");
    row("specific_film_thickness", s.lambdaMin, "", 1, fmt::format("smallest along the path, at Gamma {}", formatNumber(s.gammaLambdaMin)));
    row("permissible_film_thickness", s.lambdaGFP, "", 1,
        fmt::format("1.4 W_W lambda_GFT, FVA 54/7 load stage {} (lambda_GFT {})", in.oil->fvaStage, formatNumber(s.lambdaGFT)));
    row("micropitting_safety", s.Slambda, "", 1, "method B, ISO/TS 6336-22", Row::Micropitting);
  }
  if (s.epsAlpha >= 2)
    out.warnings.push_back(fmt::format("eps_alpha = {} is 2 or more: the scuffing methods hold for eps_alpha below 2 (ISO/TS 6336-20); "
                                       "the load is taken as shared evenly along the path",
                                       formatNumber(s.epsAlpha)));
  // ISO/TS 6336-20's running tests reach 80 m/s on the working pitch circle.
  if (s.vw > 80)
    out.warnings.push_back(fmt::format("the pitch-line velocity on the working circle, {} m/s, is beyond the 80 m/s of the running tests "
                                       "behind the scuffing methods (ISO/TS 6336-20): their results are less certain here",
                                       formatNumber(s.vw)));
  out.scuffing = s.scuffing && !info;
  out.micropitting = s.micropitting && !info;
  out.minScuffing = in.SBmin;
  out.minIntegralScuffing = in.SintSmin;
  out.minMicropitting = in.SLmin;
  out.bulkTemperature = s.thetaM - 273.15;
  out.scuffingTemperature = s.scuffing ? s.thetaS - 273.15 : 0;
  for (const auto& p : s.path) {
    out.pathGamma.push_back(p.gamma);
    out.contactTemperature.push_back(p.thetaB - 273.15);
    if (s.micropitting) out.filmThickness.push_back(p.h * 1e6);
  }
}

// The governing side: the smallest safety relative to its minimum, a gear's (contact,
// bending) or the mesh's (scuffing, micropitting).
void governs(RatingReport& out) {
  using Row = RatingReport::Row;
  double worst = 1e300;
  for (const auto& row : out.rows) {
    if (row.minimum == Row::NoMinimum) continue;
    double min = out.minimumOf(row.minimum);
    for (size_t g = 0; g < row.si.size(); ++g) {
      double s = row.si[g];
      if (!std::isfinite(s) || s / min >= worst) continue;  // an internal gear's root: said below
      worst = s / min;
      const char* below = s < min ? " (below the minimum)" : "";
      bool contact = row.minimum == Row::Contact;
      if (row.perGear && (contact || row.minimum == Row::Bending))
        out.governs = fmt::format("{} of the {}: {} {} against {}{}", contact ? "contact" : "bending", out.gears[g], contact ? "S_H" : "S_F",
                                  formatNumber(s), formatNumber(min), below);
      else
        out.governs = fmt::format("{} of the mesh: {} against {}{}", row.key, formatNumber(s), formatNumber(min), below);
    }
  }
  out.governingRatio = worst;
}

const char* treatmentWord(rating::Treatment t) {
  switch (t) {
  case rating::Treatment::CaseHardened: return "case_hardened";
  case rating::Treatment::Nitrided: return "nitrided";
  case rating::Treatment::ThroughHardened: return "through_hardened";
  }
  return "";
}

// The rows a rating table opens with, what it was given: one value of the mesh, or one per
// gear, each in its unit with where it comes from.
struct GivenRows {
  RatingReport& out;
  void both(std::string key, std::string label, const units::DisplayUnit& u, double v0, double v1, std::string method = "") {
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, true, {v0, v1}});
    out.rows.back().method = std::move(method);
  }
  void one(std::string key, std::string label, const units::DisplayUnit& u, double v, std::string method = "") {
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, false, {v}});
    out.rows.back().method = std::move(method);
  }
  void whole() { out.rows.back().format = RatingReport::Row::Whole; }

  // Each gear's material limits, with the treatments beside them.
  void materials(const std::array<double, 2>& hlim, const std::array<double, 2>& flim, const std::string& treatments) {
    const units::DisplayUnit mpa{"MPa", 1e6};
    both("sigma_Hlim", "sigma_Hlim", mpa, hlim[0], hlim[1], "material, " + treatments);
    both("sigma_Flim", "sigma_Flim", mpa, flim[0], flim[1], "material");
  }
  // The life, the oil and the roughness, as the `rating` block gives them.
  void service(double life, double nu40, double rzFlank, double rzRoot) {
    const units::DisplayUnit um{"um", 1e-6}, h{"h", 3600}, cst{"mm^2/s", 1e-6};
    one("life", "life", h, life, "rating.life");
    one("viscosity_40", "nu_40", cst, nu40, "rating.lubricant.viscosity_40");
    one("roughness_flank_rz", "Rz flank", um, rzFlank, "rating.roughness");
    one("roughness_root_rz", "Rz root", um, rzRoot, "rating.roughness");
  }
};

// `case_hardened / case_hardened`: each gear's treatment, its own or the pair's.
template <class Input>
std::string treatments(const Input& in) {
  return fmt::format("{} / {}", treatmentWord(in.gear[0].treatment.value_or(in.treatment)),
                     treatmentWord(in.gear[1].treatment.value_or(in.treatment)));
}

// The allowances and the backlash they leave (ISO 21771), where both gears give theirs: the
// least with the thickest teeth at the shortest centre distance, the most the other way.
void backlashRows(const rating::PairInput& in, const std::array<double, 2>& db, double alphaWt, GivenRows& rows) {
  const auto& g = in.gear;
  if (!std::isfinite(g[0].upperAllowance) || !std::isfinite(g[1].upperAllowance)) return;
  const units::DisplayUnit um{"um", 1e-6};
  rows.both("upper_thickness_allowance", "A_sne", um, g[0].upperAllowance, g[1].upperAllowance, "given");
  rows.both("lower_thickness_allowance", "A_sni", um, g[0].lowerAllowance, g[1].lowerAllowance, "given");
  double a = 0.5 * (db[0] + db[1]) / std::cos(alphaWt), Aa = in.aAllowance;
  auto at = [&](double A1, double A2, double dist) {
    return geometry::backlash(g[0].z, g[1].z, in.mn, in.beta, in.alphaN, g[0].x, g[1].x, A1, A2, dist);
  };
  geometry::Backlash least = at(g[0].upperAllowance, g[1].upperAllowance, a - Aa);
  geometry::Backlash most = at(g[0].lowerAllowance, g[1].lowerAllowance, a + Aa);
  auto where = [&](const char* allowance, const char* sign, double dist) {
    return Aa == 0 ? fmt::format("{} at a = {} mm", allowance, formatNumber(a * 1e3))
                   : fmt::format("{}, a {} A_a = {} mm", allowance, sign, formatNumber(dist * 1e3));
  };
  std::string tight = where("A_sne", "-", a - Aa), loose = where("A_sni", "+", a + Aa);
  if (least.jn < 0) tight += ": the flanks interfere";
  rows.one("circumferential_backlash_min", "j_t min", um, least.jt, tight);
  rows.one("circumferential_backlash_max", "j_t max", um, most.jt, loose);
  rows.one("normal_backlash_min", "j_n min", um, least.jn, "j_t cos alpha_wt cos beta_b");
  rows.one("normal_backlash_max", "j_n max", um, most.jn, "j_t cos alpha_wt cos beta_b");
  // An allowance that takes the whole tooth is a typing slip, not a design.
  for (size_t k = 0; k < 2; ++k) {
    double sn = in.mn * (3.14159265358979323846 / 2 + 2 * g[k].x * std::tan(in.alphaN));
    if (sn + g[k].lowerAllowance <= 0)
      rows.out.warnings.push_back(fmt::format("{}: the lower thickness allowance {} um leaves no tooth (s_n {} mm)", rows.out.gears[k],
                                              formatNumber(g[k].lowerAllowance * 1e6), formatNumber(sn * 1e3)));
  }
}

// What the rating was given, before what it found: each gear's geometry (ISO 21771, with
// nominal tooth thicknesses) and the inputs that decide the factors.
void inputRows(const rating::MeshRating& mr, RatingReport& out) {
  const rating::PairInput& in = mr.input;
  const PairRating& r = mr.rating;
  constexpr double pi = 3.14159265358979323846;
  const units::DisplayUnit mm{"mm", 1e-3}, deg{"deg", pi / 180}, plain{"", 1};
  GivenRows rows{out};
  double alphaT = std::atan(std::tan(in.alphaN) / std::cos(in.beta));
  std::array<double, 2> d{}, db{}, sn{};
  for (size_t g = 0; g < 2; ++g) {
    d[g] = std::fabs(in.gear[g].z) * in.mn / std::cos(in.beta);
    db[g] = d[g] * std::cos(alphaT);
    // ISO 21771: an internal gear's shift thickens its teeth as an external gear's does.
    sn[g] = in.mn * (pi / 2 + 2 * in.gear[g].x * std::tan(in.alphaN));
  }
  rows.both("z", "z", plain, std::fabs(in.gear[0].z), std::fabs(in.gear[1].z), mr.internal ? "the ring internal" : "");
  rows.whole();
  rows.both("shift", "x", plain, in.gear[0].x, in.gear[1].x, "profile shift coefficient");
  rows.both("reference_diameter", "d", mm, d[0], d[1], "z m_n / cos beta");
  rows.both("tip_diameter", "d_a", mm, r.gear[0].tipDiameter, r.gear[1].tipDiameter);
  rows.both("root_diameter", "d_f", mm, r.gear[0].rootDiameter, r.gear[1].rootDiameter, "from the basic rack h_fP*");
  rows.both("base_diameter", "d_b", mm, db[0], db[1], "d cos alpha_t");
  rows.both("tooth_thickness", "s_n", mm, sn[0], sn[1], "nominal, m_n (pi/2 + 2 x tan alpha_n), no allowance");
  rows.one("working_pressure_angle", "alpha_wt", deg, r.alphaWt, std::isfinite(in.a) ? "at the given centre distance" : "from the shifts");
  if (!mr.internal) backlashRows(in, db, r.alphaWt, rows);
  rows.materials({in.gear[0].sigmaHlim, in.gear[1].sigmaHlim}, {in.gear[0].sigmaFlim, in.gear[1].sigmaFlim}, treatments(in));
  if (in.grade > 0) {
    rows.one("accuracy", "accuracy", plain, in.grade, "ISO 1328-1 grade");
    rows.whole();
  }
  rows.service(in.life, in.nu40, in.RzFlank, in.RzRoot);
  for (size_t g = 0; g < 2; ++g)
    if (std::isfinite(in.gear[g].RzFlank) || std::isfinite(in.gear[g].RzRoot)) {
      auto own = [&](double mine, double pair) { return std::isfinite(mine) ? mine : pair; };
      const units::DisplayUnit um{"um", 1e-6};
      rows.both("gear_flank_rz", "Rz flank, each", um, own(in.gear[0].RzFlank, in.RzFlank),
                own(in.gear[1].RzFlank, in.RzFlank), "the gear's roughness; Z_R from their mean");
      rows.both("gear_root_rz", "Rz root, each", um, own(in.gear[0].RzRoot, in.RzRoot),
                own(in.gear[1].RzRoot, in.RzRoot), "the gear's roughness");
      break;
    }
  rows.one("basic_rack", "h_aP*, h_fP*", plain, in.haP, fmt::format("h_fP* {}, rho_fP* {}", formatNumber(in.hfP), formatNumber(in.rhoFP)));
}

// The critical section of each tooth root, shown where a ring's is generated by its cutter.
void criticalSectionRows(const PairRating& r, RatingReport& out) {
  auto gear = [&](std::string key, double GearRating::*m, const units::Dim& d, std::string method) {
    auto u = units::displayUnitFor(d);
    out.rows.push_back({key, key, u.name, u.scale, true, {r.gear[0].*m, r.gear[1].*m}});
    out.rows.back().method = std::move(method);
  };
  gear("s_Fn", &GearRating::sFn, units::dims::length, "tooth root chord at the critical section");
  gear("h_Fe", &GearRating::hFe, units::dims::length,
       "bending moment arm, load at the outer point of single pair contact");
  gear("rho_F", &GearRating::rhoF, units::dims::length, "fillet radius at the critical section");
  gear("alpha_Fen", &GearRating::alphaFen, units::dims::angle, "load direction angle");
}

// How Y_F was found: the 30-degree tangent of external gears, a ring's 60 degrees on the fillet
// its cutter generates.
std::string formFactorMethod(const rating::MeshRating& mr, const RatingReport& out) {
  if (!(mr.internal && mr.input.gear[1].cutterTeeth > 0)) return "method B, 30 deg tangent";
  return fmt::format("method B, 30 deg tangent; the {} 60 deg, cut by a pinion cutter z0 {:g}", out.gears[1], mr.input.gear[1].cutterTeeth);
}

// What an internal mesh leaves unrated: the ring's root without its cutter, its scuffing and
// micropitting.
void internalNotes(const rating::MeshRating& mr, RatingReport& out) {
  if (!mr.internal) return;
  const bool cutter = mr.input.gear[1].cutterTeeth > 0, rootRated = cutter && mr.rating.rootError.empty();
  std::vector<std::string> notes;
  if (cutter && !rootRated) {
    out.notRated.push_back({out.gears[1], "tooth root", mr.rating.rootError + " (its flank is rated)", true});
    notes.push_back(fmt::format("the {}'s tooth root is not rated: {}", out.gears[1], mr.rating.rootError));
  } else if (!rootRated) {
    out.notRated.push_back({out.gears[1], "tooth root",
                            "its pinion-type cutter is not given (`ring.cutter { teeth = …; }`; its flank is rated)",
                            true});
    notes.push_back(fmt::format("the {}'s tooth root is not rated: its pinion-type cutter is not given", out.gears[1]));
  }
  if (mr.input.oil)
    notes.push_back(
        "its scuffing and micropitting are for information: ISO/TS 6336-20, -21 and -22 are written for external "
        "gears");
  out.note = fmt::format("{}", fmt::join(notes, "; "));
}

RatingReport table(const ir::Stage& st, const rating::MeshRating& mr, bool several, double minH, double minF, double ka, double kgamma) {
  const PairRating& r = mr.rating;
  RatingReport out;
  out.stage = st.name;
  out.gears = {st.gears[static_cast<size_t>(mr.driving)], st.gears[static_cast<size_t>(mr.driven)]};
  if (several) out.mesh = out.gears[0] + "-" + out.gears[1];
  out.minContact = minH;
  out.minBending = minF;
  out.kvRange = mr.kv ? "method A, scene " + mr.kv->scene : rangeName(r.kvRange);
  using Row = RatingReport::Row;
  auto mesh = [&](std::string key, double v, const units::Dim& d = units::dims::none) {
    auto u = units::displayUnitFor(d);
    std::string label = key;
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, false, {v}});
  };
  auto gear = [&](std::string key, double GearRating::*m, const units::Dim& d = units::dims::none, Row::Minimum min = Row::NoMinimum,
                  Row::Format f = Row::Plain, std::string label = "") {
    auto u = units::displayUnitFor(d);
    if (label.empty()) label = key;
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, true, {r.gear[0].*m, r.gear[1].*m}, f, min});
  };
  using namespace units::dims;
  auto method = [&](std::string m) { out.rows.back().method = std::move(m); };
  const rating::PairInput& in = mr.input;
  inputRows(mr, out);
  mesh("tangential_force", r.Ft, force);
  mesh("pitch_line_velocity", r.v, velocity);
  mesh("eps_alpha", r.epsAlpha);
  mesh("eps_beta", r.epsBeta);
  mesh("resonance_ratio", r.N);
  mesh("K_A", ka);
  method("application_factor");
  mesh("K_gamma", kgamma);
  method(!mr.loadSharing.empty()         ? mr.loadSharing
         : mr.internal || in.planets > 0 ? "mesh_load_factor, else IEC 61400-4 by the planets"
                                         : "mesh_load_factor, else 1");
  mesh("K_v", r.Kv);
  method(mr.kv ? fmt::format("method A, scene {}", mr.kv->scene)
         : std::isfinite(in.KvGiven) ? std::string("given")
                                     : fmt::format("method B, {}", rangeName(r.kvRange)));
  mesh("K_Hbeta", r.KHbeta);
  method(mr.faceLoad ? fmt::format("contact analysis, {} slices x {} positions{}", mr.faceLoad->slices, mr.faceLoad->positions,
                                    mr.faceLoad->shafts.empty() ? "" : "; " + mr.faceLoad->shafts)
         : std::isfinite(in.KHbetaGiven) ? std::string("given")
                                         : std::string("method B, F_betay c_gammabeta / (2 F_m/b)"));
  if (mr.faceLoad) {
    mesh("line_load_peak", mr.faceLoad->peak * mr.faceLoad->faceWidth, length);
    method(mr.faceLoad->shafts.empty() ? "from the coupling end of the face" : "from the face's end nearer the shafts' left ends");
  }
  mesh("K_Fbeta", r.KFbeta);
  method("K_Hbeta^N_F");
  std::string alpha = std::isfinite(in.KHalphaGiven) ? "given" : "method B";
  mesh("K_Halpha", r.KHalpha);
  method(alpha);
  mesh("K_Falpha", r.KFalpha);
  method(alpha);
  mesh("Z_H", r.ZH);
  method("at alpha_wt, beta_b");
  mesh("Z_E", r.ZE);
  method("from E, nu of both gears");
  mesh("Z_eps", r.Zeps);
  method("from eps_alpha, eps_beta");
  mesh("Z_beta", r.Zbeta);
  method("1/sqrt(cos beta), Corrigendum 1");
  gear("load_cycles", &GearRating::cycles, units::dims::none, Row::NoMinimum, Row::Count);
  gear("Z_B", &GearRating::ZBD, units::dims::none, Row::NoMinimum, Row::Plain, "Z_B, Z_D");
  method(mr.internal ? "1 (internal mesh)" : "M_1, M_2 by eps_beta");
  std::string curve = in.optimumLife ? "optimum" : "normal";
  gear("Z_NT", &GearRating::ZNT);
  method(fmt::format("method B, {} curve", curve));
  gear("Z_L", &GearRating::ZL);
  method("method B");
  gear("Z_v", &GearRating::Zv);
  method("method B");
  gear("Z_R", &GearRating::ZR);
  method("method B");
  gear("Z_W", &GearRating::ZW);
  method(r.gear[0].ZW != 1 || r.gear[1].ZW != 1 ? "1.2 - (HB - 130)/1700 against a surface-hardened mate, else 1"
                                                 : "1: no through-hardened gear against a surface-hardened one");
  gear("Z_X", &GearRating::ZX);
  method("1 (ISO 6336-2 for steels of this size)");
  gear("contact_stress", &GearRating::sigmaH, pressure);
  gear("permissible_contact_stress", &GearRating::sigmaHP, pressure);
  size_t contactRow = out.rows.size();
  gear("contact_safety", &GearRating::SH, units::dims::none, Row::Contact);
  const bool ringRoot = mr.internal && in.gear[1].cutterTeeth > 0 && r.rootError.empty();
  if (ringRoot) criticalSectionRows(r, out);
  gear("Y_F", &GearRating::YF);
  method(formFactorMethod(mr, out));
  gear("Y_S", &GearRating::YS);
  method("method B");
  gear("Y_beta", &GearRating::Ybeta);
  method("1 - eps_beta beta/120 deg");
  if (ringRoot) {
    gear("Y_B", &GearRating::YB);
    method(std::isfinite(in.gear[1].rimThickness) ? "rim factor, from the ring's rim_thickness" : "rim factor, 1: no rim_thickness");
  }
  gear("Y_NT", &GearRating::YNT);
  method(fmt::format("method B, {} curve", curve));
  gear("Y_deltarelT", &GearRating::YdeltarelT);
  method("method B");
  gear("Y_RrelT", &GearRating::YRrelT);
  method("method B");
  gear("Y_X", &GearRating::YX);
  method("method B, from m_n");
  gear("Y_M", &GearRating::YM);
  method("1 one flank loaded, 0.7 both (an idler, a planet)");
  gear("bending_stress", &GearRating::sigmaF, pressure);
  gear("permissible_bending_stress", &GearRating::sigmaFP, pressure);
  gear("bending_safety", &GearRating::SF, units::dims::none, Row::Bending);
  spectrumRows(r, contactRow, out);
  scuffingRows(mr, out);
  governs(out);
  modelNotes(mr, out);
  internalNotes(mr, out);
  warnings(mr, out);
  return out;
}

// What a bevel rating was given: tooth counts, shifts, the materials' limits and treatment,
// the life, the oil, the roughness and the basic crown gear.
void bevelInputRows(const rating::BevelInput& in, RatingReport& out) {
  const units::DisplayUnit plain{"", 1};
  GivenRows rows{out};
  rows.both("z", "z", plain, in.gear[0].z, in.gear[1].z);
  rows.whole();
  rows.both("shift", "x_hm", plain, in.gear[0].xhm, in.gear[1].xhm, "mean profile shift coefficient");
  rows.materials({in.gear[0].sigmaHlim, in.gear[1].sigmaHlim}, {in.gear[0].sigmaFlim, in.gear[1].sigmaFlim}, treatments(in));
  rows.service(in.life, in.nu40, in.RzFlank, in.RzRoot);
  rows.one("basic_rack", "k_hap, k_hfp", plain, in.khap, fmt::format("basic crown gear; k_hfp {}", formatNumber(in.khfp)));
}

// The rating table of a bevel pair (ISO 10300 method B1): the cone, the virtual cylindrical
// gears, every factor and each safety against its minimum.
RatingReport bevelTable(const ir::Stage& st, const rating::BevelStageRating& br) {
  using rating::BevelGearRating;
  const rating::BevelRating& r = br.rating;
  const rating::BevelInput& in = br.input;
  RatingReport out;
  out.stage = st.name;
  out.standard = "ISO 10300";
  out.gears = {st.gears[0], st.gears[1]};
  out.minContact = in.SHmin;
  out.minBending = in.SFmin;
  out.kvRange = rangeName(r.kvRange);
  using Row = RatingReport::Row;
  using namespace units::dims;
  auto mesh = [&](std::string key, double v, std::string method, const units::Dim& d = units::dims::none) {
    auto u = units::displayUnitFor(d);
    std::string label = key;
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, false, {v}, Row::Plain, Row::NoMinimum, std::move(method)});
  };
  auto gear = [&](std::string key, double BevelGearRating::*m, std::string method, const units::Dim& d = units::dims::none,
                  Row::Minimum min = Row::NoMinimum, Row::Format f = Row::Plain) {
    auto u = units::displayUnitFor(d);
    std::string label = key;
    out.rows.push_back({std::move(key), std::move(label), u.name, u.scale, true, {r.gear[0].*m, r.gear[1].*m}, f, min, std::move(method)});
  };
  bevelInputRows(in, out);
  mesh("outer_cone_distance", r.Re, std::isfinite(in.Re) ? "given" : "from the mean normal module", length);
  mesh("mean_cone_distance", r.Rm, "R_e - b/2", length);
  mesh("face_width", r.b, std::isfinite(in.b) ? "given" : "face_ratio R_e", length);
  mesh("effective_face_width", r.bEff, "contact_pattern b", length);
  mesh("mean_normal_module", r.mmn, "from the cone: d_m1 cos(beta_m) / z1", length);
  gear("cone_angle", &BevelGearRating::cone, "ISO 23509", angle);
  gear("mean_diameter", &BevelGearRating::dm, "2 R_m sin(delta)", length);
  gear("mean_addendum", &BevelGearRating::ham, "m_mn (k_hap + x_hm)", length);
  gear("mean_dedendum", &BevelGearRating::hfm, "m_mn (k_hfp - x_hm)", length);
  gear("virtual_diameter", &BevelGearRating::dv, "d_m / cos(delta)", length);
  gear("virtual_tip_diameter", &BevelGearRating::dva, "d_v + 2 h_am", length);
  gear("virtual_z", &BevelGearRating::zv, "z / cos(delta)");
  gear("virtual_z_normal", &BevelGearRating::zvn, "z_v / (cos^2(beta_vb) cos(beta_m))");
  mesh("virtual_eps_alpha", r.epsVa, "virtual cylindrical gears");
  mesh("virtual_eps_beta", r.epsVb, "b_eff sin(beta_m) / (pi m_mn)");
  mesh("virtual_contact_ratio", r.epsVg, "eps_valpha + eps_vbeta");
  mesh("relative_curvature_radius", r.rhoRel, "at the pitch point, normal to the contact line", length);
  mesh("middle_contact_line", r.lbm, "l_bm in the zone of action, reduced to the contact pattern", length);
  mesh("tangential_force", r.Ft, "F_mt at the mean diameter", force);
  mesh("pitch_line_velocity", r.v, "v_mt at the mean diameter", velocity);
  mesh("resonance_ratio", r.N, fmt::format("n1 / n_E1 (n_E1 {} rpm)", formatNumber(r.nE1)));
  mesh("K_A", in.KA, "application_factor");
  mesh("K_v", r.Kv, std::isfinite(in.KvGiven) ? std::string("given") : fmt::format("method B, {}", rangeName(r.kvRange)));
  static const char* mountings[] = {"both members straddle mounted", "one member cantilever mounted", "both members cantilever mounted"};
  mesh("K_Hbeta", r.KHbeta,
       std::isfinite(in.KHbetaGiven) ? std::string("given")
                                     : fmt::format("K_Hbeta-C = 1.5 K_Hbeta-be, {} ({})", formatNumber(r.KHbetaBe), mountings[static_cast<int>(in.mounting)]));
  mesh("K_Fbeta", r.KFbeta, fmt::format("K_Hbeta / K_F0, K_F0 {}", formatNumber(r.KF0)));
  std::string alpha = std::isfinite(in.KHalphaGiven) ? "given" : "method B";
  mesh("K_Halpha", r.KHalpha, alpha);
  mesh("K_Falpha", r.KFalpha, alpha);
  mesh("Z_MB", r.ZMB, "mid-zone factor");
  mesh("Z_LS", r.ZLS, "load sharing over the tip, middle and root contact lines");
  mesh("Z_E", r.ZE, "from E, nu of both gears");
  mesh("Z_beta", r.Zbeta, "method B1: the spiral angle is in the contact lines");
  mesh("Z_K", r.ZK, "bevel gear factor on the permissible stress (ISO 10300-2:2023)");
  mesh("nominal_contact_stress", r.sigmaH0, "sqrt(F_n / (l_bm rho_rel)) Z_MB Z_LS Z_E", pressure);
  gear("load_cycles", &BevelGearRating::cycles, "over the life", units::dims::none, Row::NoMinimum, Row::Count);
  std::string curve = in.optimumLife ? "optimum" : "normal";
  gear("Z_NT", &BevelGearRating::ZNT, fmt::format("{} curve", curve));
  gear("Z_L", &BevelGearRating::ZL, "as ISO 6336-2");
  gear("Z_v", &BevelGearRating::Zv, "as ISO 6336-2, at v_mt");
  gear("Z_R", &BevelGearRating::ZR, "as ISO 6336-2, at rho_rel");
  gear("Z_W", &BevelGearRating::ZW, "work hardening");
  gear("Z_X", &BevelGearRating::ZX, "1");
  gear("contact_stress", &BevelGearRating::sigmaH, "sigma_H0 sqrt(K_A K_v K_Hbeta K_Halpha)", pressure);
  gear("permissible_contact_stress", &BevelGearRating::sigmaHP, "sigma_Hlim Z_NT Z_X Z_L Z_v Z_R Z_W Z_K / S_Hmin", pressure);
  gear("contact_safety", &BevelGearRating::SH,
       fmt::format("sigma_HP S_Hmin / sigma_H; ISO 10300-2:2014 (no Z_K): {}, {}", formatNumber(r.gear[0].SH / r.ZK),
                   formatNumber(r.gear[1].SH / r.ZK)),
       units::dims::none, Row::Contact);
  gear("Y_Fa", &BevelGearRating::YFa, "method B1, 30 deg tangent, load at the tip");
  gear("Y_Sa", &BevelGearRating::YSa, "method B1");
  mesh("Y_eps", r.Yeps, "from eps_valpha, eps_vbeta");
  mesh("Y_LS", r.YLS, "Z_LS^2");
  mesh("Y_BS", r.YBS, "bevel spiral angle factor");
  gear("Y_NT", &BevelGearRating::YNT, fmt::format("{} curve", curve));
  gear("Y_deltarelT", &BevelGearRating::YdeltarelT, "as ISO 6336-3 method B");
  gear("Y_RrelT", &BevelGearRating::YRrelT, "as ISO 6336-3 method B");
  gear("Y_X", &BevelGearRating::YX, "as ISO 6336-3, from m_mn");
  gear("bending_stress", &BevelGearRating::sigmaF, "F_mt/(b m_mn) Y_Fa Y_Sa Y_eps Y_BS Y_LS K_A K_v K_Fbeta K_Falpha", pressure);
  gear("permissible_bending_stress", &BevelGearRating::sigmaFP, "2 sigma_Flim Y_NT Y_deltarelT Y_RrelT Y_X / S_Fmin", pressure);
  gear("bending_safety", &BevelGearRating::SF, "sigma_FP S_Fmin / sigma_F", units::dims::none, Row::Bending);
  governs(out);
  out.model.push_back(fmt::format("K_v method B: c_gamma {} N/(mm um), reduced mass at the mean point {} kg/mm, f_pt {} um less running-in "
                                  "{} um",
                                  formatNumber(r.cgamma), formatNumber(r.mred), formatNumber(std::max(in.gear[0].fpt, in.gear[1].fpt) * 1e6),
                                  formatNumber(r.yAlpha)));
  if (r.epsVa < 1.1)
    out.warnings.push_back(fmt::format("eps_valpha = {}: little transverse overlap of the virtual gears", formatNumber(r.epsVa)));
  // ISO 23509's usual proportions: b up to R_e/3 and 10 outer transverse modules.
  double met = r.mmt * r.Re / r.Rm;
  if (r.b > r.Re / 3 * 1.0001 || r.b > 10 * met)
    out.warnings.push_back(fmt::format("face width {} mm is beyond the usual R_e/3 ({} mm) or 10 outer modules ({} mm): the contact pattern "
                                       "and the factors fitted to usual proportions (Y_BS) are less certain",
                                       formatNumber(r.b * 1e3), formatNumber(r.Re / 3 * 1e3), formatNumber(10 * met * 1e3)));
  for (size_t g = 0; g < 2; ++g)
    if (r.gear[g].sAn < 0.2 * r.mmn)
      out.warnings.push_back(fmt::format("the {}'s normal tooth thickness at the tip is {} mm, below 0.2 m_mn: a tip this thin chips and "
                                         "wears",
                                         out.gears[g], formatNumber(r.gear[g].sAn * 1e3)));
  return out;
}

// The planet bearings, in the sun-planet mesh's table, where the planet gives them; the
// modified life where its pitch diameter and the oil's viscosity line are given.
void planetBearingRows(const KindContext& c, RatingReport& out) {
  const Model& m = c.ev.model();
  if (!m.attribute(c.stage, cat::gear::Planet, Q::PlanetBearingKind)) return;
  const units::DisplayUnit h{"h", 3600};
  std::vector<std::string> missing;
  auto row = [&](const char* key, Q q, const units::DisplayUnit& u, const char* method, std::string why) {
    Value v = c.derived(cat::gear::Planet, q);
    if (!v.isNumber()) return missing.push_back(fmt::format("`{}` is not computed: {}", key, why));
    out.rows.push_back({key, key, u.name, u.scale, false, {v.mid()}});
    out.rows.back().method = method;
  };
  row("planet_bearing_load", Q::BearingLoad, units::displayUnitFor(units::dims::force),
      "each bearing: the planet's two mesh forces summed, times K_gamma, over its bearings",
      "the meshes are not rated at this design");
  row("planet_bearing_life", Q::BearingLife, h, "ISO 281 L10h at the planet's speed relative to the carrier",
      "ISO 281 refuses the bearing's load or rating");
  bool modifiable = m.attribute(c.stage, cat::gear::Planet, Q::PlanetBearingPitchDiameter) &&
                    m.attribute(c.stage, Q::RatingViscosity100) && m.attribute(c.stage, Q::RatingOilTemperature);
  row("planet_bearing_modified_life", Q::BearingModifiedLife, h,
      "ISO 281 a1 a_ISO L10h, kappa from the rating's lubricant",
      modifiable ? "ISO 281 refuses the bearing's load or rating"
                 : "it needs the bearing's `pitch_diameter` and the lubricant's `viscosity_100` and `oil_temperature`");
  if (!missing.empty())
    out.note +=
        std::string(out.note.empty() ? "" : "; ") + fmt::format("planet bearings: {}", fmt::join(missing, "; "));
}

} // namespace

Ratings ratings(const Model& m, const Assignment& best) {
  Ratings result;
  Evaluator ev(m);
  for (size_t s = 0; s < m.stages.size(); ++s) {
    const ir::Stage& st = *m.stages[s].ir;
    if (!m.attribute(static_cast<int>(s), Q::RatingLife)) continue;
    KindContext c{ev, static_cast<int>(s), best};
    std::string why;
    bool bevel = st.kind == ir::StageKind::Bevel;
    auto refused = [&] {
      RatingReport failed;
      failed.stage = st.name;
      if (bevel) failed.standard = "ISO 10300";
      failed.error = why;
      result.errors.push_back(fmt::format("stage `{}` cannot be rated: {}", st.name, why));
      result.ratings.push_back(std::move(failed));
    };
    // Every value is a number except an internal gear's root, which the note names; a freedom
    // still spanning an interval (not optimised) is rated at its middle, said so.
    auto keep = [&](RatingReport r, bool internalRoot) {
      for (const auto& row : r.rows)
        for (size_t g = 0; g < row.si.size(); ++g)
          if (std::isnan(row.si[g]) && !(internalRoot && g == 1))
            result.errors.push_back(fmt::format("stage `{}`: the rating's `{}` is not a number at design 1", st.name, row.key));
      for (int f : m.stages[s].freedoms)
        if (!m.freedoms[static_cast<size_t>(f)].shaft.setting &&
            best.box[static_cast<size_t>(f)].first != best.box[static_cast<size_t>(f)].second) {
          r.note += std::string(r.note.empty() ? "" : "; ") + "rated at the middle of each free attribute's interval";
          break;
        }
      result.ratings.push_back(std::move(r));
    };
    if (bevel) {
      auto br = rating::rateBevelStage(c, &why);
      if (br) keep(bevelTable(st, *br), false);
      else refused();
      continue;
    }
    auto meshes = rating::rateStage(c, &why);
    if (meshes.empty()) refused();
    auto minOf = [&](Q k) {
      Value v = c.at(k);
      return v.isNumber() ? v.mid() : 1.0;
    };
    for (size_t k = 0; k < meshes.size(); ++k) {
      const auto& mr = meshes[k];
      auto t = table(st, mr, meshes.size() > 1, minOf(Q::RatingMinContact), minOf(Q::RatingMinBending), mr.input.KA,
                     mr.input.Kgamma);
      if (k == 0 && st.kind == ir::StageKind::Planetary) planetBearingRows(c, t);
      keep(std::move(t), mr.internal);
    }
  }
  return result;
}

} // namespace gbx::rt::passes
