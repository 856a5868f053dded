#include "passes/Ratings.h"

#include <cmath>

#include <fmt/format.h>

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

RatingReport table(const ir::Stage& st, const rating::MeshRating& mr, bool several, double minH, double minF, double ka, double kgamma) {
  const PairRating& r = mr.rating;
  RatingReport out;
  out.stage = st.name;
  out.gears = {st.gears[static_cast<size_t>(mr.driving)], st.gears[static_cast<size_t>(mr.driven)]};
  if (several) out.mesh = out.gears[0] + "-" + out.gears[1];
  out.minContact = minH;
  out.minBending = minF;
  out.kvRange = rangeName(r.kvRange);
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
  mesh("tangential_force", r.Ft, force);
  mesh("pitch_line_velocity", r.v, velocity);
  mesh("eps_alpha", r.epsAlpha);
  mesh("eps_beta", r.epsBeta);
  mesh("resonance_ratio", r.N);
  mesh("K_A", ka);
  mesh("K_gamma", kgamma);
  mesh("K_v", r.Kv);
  mesh("K_Hbeta", r.KHbeta);
  mesh("K_Fbeta", r.KFbeta);
  mesh("K_Halpha", r.KHalpha);
  mesh("K_Falpha", r.KFalpha);
  mesh("Z_H", r.ZH);
  mesh("Z_E", r.ZE);
  mesh("Z_eps", r.Zeps);
  mesh("Z_beta", r.Zbeta);
  gear("tip_diameter", &GearRating::tipDiameter, length);
  gear("load_cycles", &GearRating::cycles, units::dims::none, Row::NoMinimum, Row::Count);
  gear("Z_B", &GearRating::ZBD, units::dims::none, Row::NoMinimum, Row::Plain, "Z_B, Z_D");
  gear("Z_NT", &GearRating::ZNT);
  gear("Z_L", &GearRating::ZL);
  gear("Z_v", &GearRating::Zv);
  gear("Z_R", &GearRating::ZR);
  gear("Z_W", &GearRating::ZW);
  gear("Z_X", &GearRating::ZX);
  gear("contact_stress", &GearRating::sigmaH, pressure);
  gear("permissible_contact_stress", &GearRating::sigmaHP, pressure);
  gear("contact_safety", &GearRating::SH, units::dims::none, Row::Contact);
  gear("Y_F", &GearRating::YF);
  gear("Y_S", &GearRating::YS);
  gear("Y_beta", &GearRating::Ybeta);
  gear("Y_NT", &GearRating::YNT);
  gear("Y_deltarelT", &GearRating::YdeltarelT);
  gear("Y_RrelT", &GearRating::YRrelT);
  gear("Y_X", &GearRating::YX);
  gear("Y_M", &GearRating::YM);
  gear("bending_stress", &GearRating::sigmaF, pressure);
  gear("permissible_bending_stress", &GearRating::sigmaFP, pressure);
  gear("bending_safety", &GearRating::SF, units::dims::none, Row::Bending);
  // The governing side: the smallest safety relative to its minimum.
  double worst = 1e300;
  for (size_t g = 0; g < 2; ++g)
    for (bool contact : {true, false}) {
      double s = contact ? r.gear[g].SH : r.gear[g].SF, min = contact ? minH : minF;
      if (!std::isfinite(s)) continue;  // an internal gear's root: said below
      if (s / min < worst) {
        worst = s / min;
        out.governs = fmt::format("{} of the {}: {} {} against {}{}", contact ? "contact" : "bending", out.gears[g],
                                  contact ? "S_H" : "S_F", formatNumber(s), formatNumber(min), s < min ? " (below the minimum)" : "");
      }
    }
  out.governingRatio = worst;
  if (mr.internal) out.note = fmt::format("the {}'s tooth root is not rated (ISO 6336-3 for internal gears is not implemented)", out.gears[1]);
  return out;
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
    auto meshes = rating::rateStage(c, &why);
    if (meshes.empty()) {
      RatingReport failed;
      failed.stage = st.name;
      failed.error = why;
      result.errors.push_back(fmt::format("stage `{}` cannot be rated: {}", st.name, why));
      result.ratings.push_back(std::move(failed));
      continue;
    }
    auto minOf = [&](Q k) {
      Value v = c.at(k);
      return v.isNumber() ? v.mid() : 1.0;
    };
    for (const auto& mr : meshes) {
      result.ratings.push_back(table(st, mr, meshes.size() > 1, minOf(Q::RatingMinContact), minOf(Q::RatingMinBending), mr.input.KA,
                                     mr.input.Kgamma));
      // Every value is a number except an internal gear's root, which the note names.
      for (const auto& row : result.ratings.back().rows)
        for (size_t g = 0; g < row.si.size(); ++g)
          if (!std::isfinite(row.si[g]) && !(mr.internal && g == 1))
            result.errors.push_back(fmt::format("stage `{}`: the rating's `{}` is not a number at design 1", st.name, row.key));
      // A freedom still spanning an interval (not optimised): rated at its middle, said so.
      for (int f : m.stages[s].freedoms)
        if (best.box[static_cast<size_t>(f)].first != best.box[static_cast<size_t>(f)].second) {
          auto& note = result.ratings.back().note;
          note += std::string(note.empty() ? "" : "; ") + "rated at the middle of each free attribute's interval";
          break;
        }
    }
  }
  return result;
}

} // namespace gbx::rt::passes
