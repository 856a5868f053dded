#include "report/Ratings.h"

#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"
#include "report/Numbers.h"

namespace gbx::rt {

namespace {

std::string label(const RatingReport::Row& row) { return row.unit.empty() ? row.label : row.label + " [" + row.unit + "]"; }

std::string shown(const RatingReport::Row& row, double si) {
  if (std::isinf(si)) return "beyond static";  // a damage sum: a bin above the static strength
  if (!std::isfinite(si)) return "not rated";  // an internal gear's root (ISO 6336-3 internal gears)
  if (row.format == RatingReport::Row::Count) return fmt::format("{:.4e}", si);
  if (row.format == RatingReport::Row::Whole) return fmt::format("{:.0f}", si);
  return formatNumber((si - row.offset) / row.scale);
}

// Rating values in JSON: SI, every digit (the shortest form that reads back to the double).
std::string ratingNumber(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

} // namespace

std::vector<std::string> ratingHeader(const RatingReport& r) {
  std::vector<std::string> h = {r.standard};
  for (const auto& g : r.gears) h.push_back(g);
  h.push_back("minimum");
  h.push_back("method");
  return h;
}

std::vector<std::vector<std::string>> ratingRows(const RatingReport& r) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : r.rows) {
    std::vector<std::string> v = {label(row)};
    if (row.perGear)
      for (double x : row.si) v.push_back(shown(row, x));
    else {
      v.push_back(shown(row, row.si[0]));
      v.push_back("");
    }
    v.push_back(row.minimum == RatingReport::Row::NoMinimum ? "" : formatNumber(r.minimumOf(row.minimum)));
    v.push_back(row.method);
    rows.push_back(std::move(v));
  }
  return rows;
}

std::vector<std::string> ratingNotes(const RatingReport& r) {
  std::vector<std::string> notes;
  for (const auto& w : r.warnings) notes.push_back("warning: " + w);
  for (const auto& n : r.notRated) notes.push_back(fmt::format("not rated: the {}'s {}: {}", n.gear, n.what, n.reason));
  for (const auto& line : r.model) notes.push_back(line);
  return notes;
}

std::string ratingVerdict(const RatingReport& r) {
  if (!r.error.empty()) return "not rated: " + r.error;
  return fmt::format("governs: {}; K_v {}{}", r.governs, r.kvRange, r.note.empty() ? "" : "; " + r.note);
}

std::string ratingJson(const RatingReport& r) {
  if (!r.error.empty()) return fmt::format("{{\"error\": \"{}\"}}", diag::jsonEscape(r.error));
  std::string o = "{\"mesh\": {";
  bool first = true;
  for (const auto& row : r.rows)
    if (!row.perGear) {
      o += fmt::format("{}\"{}\": {}", first ? "" : ", ", diag::jsonEscape(row.key), ratingNumber(row.si[0]));
      first = false;
    }
  o += "}";
  for (size_t g = 0; g < r.gears.size(); ++g) {
    o += fmt::format(", \"{}\": {{", diag::jsonEscape(r.gears[g]));
    first = true;
    for (const auto& row : r.rows)
      if (row.perGear) {
        o += fmt::format("{}\"{}\": {}", first ? "" : ", ", diag::jsonEscape(row.key), ratingNumber(row.si[g]));
        first = false;
      }
    o += "}";
  }
  o += fmt::format(", \"min_safety\": {{\"contact\": {}, \"bending\": {}", ratingNumber(r.minContact), ratingNumber(r.minBending));
  if (r.scuffing) o += fmt::format(", \"scuffing\": {}, \"integral_scuffing\": {}", ratingNumber(r.minScuffing), ratingNumber(r.minIntegralScuffing));
  if (r.micropitting) o += fmt::format(", \"micropitting\": {}", ratingNumber(r.minMicropitting));
  o += "}";
  o += ", \"methods\": {";
  first = true;
  for (const auto& row : r.rows)
    if (!row.method.empty()) {
      o += fmt::format("{}\"{}\": \"{}\"", first ? "" : ", ", diag::jsonEscape(row.key), diag::jsonEscape(row.method));
      first = false;
    }
  o += "}";
  if (!r.warnings.empty()) {
    o += ", \"warnings\": [";
    for (size_t i = 0; i < r.warnings.size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", diag::jsonEscape(r.warnings[i]));
    o += "]";
  }
  if (!r.notRated.empty()) {
    o += ", \"not_rated\": [";
    for (size_t i = 0; i < r.notRated.size(); ++i)
      o += fmt::format("{}{{\"gear\": \"{}\", \"what\": \"{}\", \"reason\": \"{}\"}}", i ? ", " : "", diag::jsonEscape(r.notRated[i].gear),
                       diag::jsonEscape(r.notRated[i].what), diag::jsonEscape(r.notRated[i].reason));
    o += "]";
  }
  if (!r.model.empty()) {
    o += ", \"model\": [";
    for (size_t i = 0; i < r.model.size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", diag::jsonEscape(r.model[i]));
    o += "]";
  }
  o += fmt::format(", \"governs\": \"{}\", \"governing_ratio\": {}, \"K_v_range\": \"{}\", \"standard\": \"{}\"}}",
                   diag::jsonEscape(r.governs), ratingNumber(r.governingRatio), diag::jsonEscape(r.kvRange), diag::jsonEscape(r.standard));
  return o;
}

std::vector<std::vector<std::string>> ratingCsvRows(const std::string& gearbox, const RatingReport& r) {
  std::vector<std::vector<std::string>> out;
  for (const auto& row : r.rows) {
    auto value = [&](double si) { return csvNumber(si, row.unit, row.scale, row.offset); };
    // A value left out names its reason.
    auto note = [&](size_t g, double si) {
      if (std::isfinite(si)) return std::string();
      for (const auto& n : r.notRated)
        if (g < r.gears.size() && n.gear == r.gears[g]) return "not rated: " + n.reason;
      return std::string("not a number");
    };
    std::string stage = r.mesh.empty() ? r.stage : r.stage + "." + r.mesh;
    // A safety stands beside the minimum it is held against.
    std::string least = row.minimum == RatingReport::Row::NoMinimum ? "" : csvNumber(r.minimumOf(row.minimum));
    if (!row.perGear) out.push_back({gearbox, stage, "", row.key, row.unit, value(row.si[0]), least, row.method, note(0, row.si[0])});
    else
      for (size_t g = 0; g < r.gears.size(); ++g)
        out.push_back({gearbox, stage, r.gears[g], row.key, row.unit, value(row.si[g]), least, row.method, note(g, row.si[g])});
  }
  return out;
}

} // namespace gbx::rt
