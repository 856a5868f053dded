#include "report/Summary.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace gbx::rt {

std::vector<std::string> designHeader(const GearboxReport& g) {
  std::vector<std::string> h = {"rank"};
  if (!g.rows.empty()) {
    for (const auto& [n, _] : g.rows[0].teeth) h.push_back(n);
    for (const auto& [n, _] : g.rows[0].choices) h.push_back(n);
  }
  h.push_back("ratio");
  for (const auto& c : g.columns) h.push_back(c.unit.empty() ? c.name : c.name + " [" + c.unit + "]");
  return h;
}

std::vector<std::string> designCells(const DesignRow& r) {
  std::vector<std::string> v = {std::to_string(r.rank) + (r.undecided ? "?" : "")};
  for (const auto& [_, z] : r.teeth) v.push_back(std::to_string(z));
  for (const auto& [_, c] : r.choices) v.push_back(c);
  v.push_back(formatNumber(r.ratio.toDouble()) + " (" + r.ratio.str() + ")");
  for (const auto& c : r.cells) v.push_back(c.text);
  return v;
}

std::vector<std::string> modificationHeader() { return {"target", "value", "rule", "when", "inputs"}; }

std::vector<std::vector<std::string>> modificationRows(const ModifyReport& md) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : md.rows) {
    std::string inputs;
    for (const auto& in : r.inputs) inputs += (inputs.empty() ? "" : "; ") + in;
    rows.push_back({r.target, !r.error.empty() ? "not computed: " + r.error : r.present ? r.shown : "absent", r.text, r.condition, inputs});
  }
  return rows;
}

namespace {

void sceneResults(const GearboxReport& g, GearboxSummary& s) {
  for (const auto& sc : g.scenes) {
    if (!sc.failure.empty()) {
      s.warnings.push_back(fmt::format("scene {} failed: {}", sc.name, sc.failure));
      continue;
    }
    // The first few outputs; the scene's own table has them all.
    constexpr size_t kMost = 4;
    std::vector<std::string> outs;
    for (const auto& out : sc.outputs)
      if (outs.size() < kMost)
        outs.push_back(std::isfinite(out.shown) ? fmt::format("{} = {}{}", out.key, formatNumber(out.shown), out.unit.empty() ? "" : " " + out.unit)
                                              : fmt::format("{} = none (no steady response)", out.key));
    std::string accuracy = sc.eigen ? "eigenvalues" : fmt::format("{} at rtol {:.0e}", sc.method, sc.rtol);
    if (sc.errorEstimate >= 0) accuracy += fmt::format(", error estimate {:.2e}", sc.errorEstimate);
    if (sc.outputs.size() > kMost) outs.push_back(fmt::format("{} more in its table", sc.outputs.size() - kMost));
    if (!outs.empty()) s.results.push_back(fmt::format("scene {}: {} ({})", sc.name, fmt::join(outs, "; "), accuracy));
    for (const auto& w : sc.warnings) s.warnings.push_back(fmt::format("scene {}: {}", sc.name, w));
  }
}

void studyResults(const GearboxReport& g, GearboxSummary& s) {
  for (const auto& st : g.studies) {
    const auto* sweep = std::get_if<SweepStudy>(&st.study);
    if (!sweep) continue;
    for (double f : sweep->folds)
      s.results.push_back(fmt::format("study {}: turning point (jump) at {} = {:.6g} {}", sweep->name, sweep->target, sweep->unit.shown(f),
                                      sweep->unit.name));
    for (const auto& [at, label] : sweep->marks)
      s.results.push_back(fmt::format("study {}: {} at {} = {:.6g} {}", sweep->name, label, sweep->target, sweep->unit.shown(at), sweep->unit.name));
    // Between two turning points several steady responses coexist: the scene found one of
    // them at the design's own point, and which one the gearbox runs on depends on its history.
    if (sweep->folds.size() >= 2 && std::isfinite(sweep->nominal)) {
      auto [lo, hi] = std::minmax_element(sweep->folds.begin(), sweep->folds.end());
      if (sweep->nominal > *lo && sweep->nominal < *hi)
        s.warnings.push_back(fmt::format("study {}: the design's {} = {:.6g} {} lies between the turning points at {:.6g} and {:.6g} {}: "
                                         "more than one steady response exists there (see the plot), and the scenes report only the "
                                         "one they reached",
                                         sweep->name, sweep->target, sweep->unit.shown(sweep->nominal), sweep->unit.name,
                                         sweep->unit.shown(*lo), sweep->unit.shown(*hi), sweep->unit.name));
    }
    for (const auto& [a, b] : sweep->gaps)
      s.warnings.push_back(fmt::format("study {}: the continuation did not follow {} from {:.6g} to {:.6g} {}", sweep->name, sweep->target,
                                       sweep->unit.shown(a), sweep->unit.shown(b), sweep->unit.name));
  }
}

void modificationResults(const GearboxReport& g, GearboxSummary& s) {
  for (const auto& md : g.modifications) {
    std::vector<std::string> parts;
    for (const auto& r : md.rows)
      if (r.present && r.valid) parts.push_back(r.target + " " + r.shown);
    if (!parts.empty()) s.results.push_back(fmt::format("modify {}: {}", md.stage, fmt::join(parts, ", ")));
  }
}

void ratingResults(const GearboxReport& g, GearboxSummary& s) {
  for (const auto& r : g.ratings) {
    std::string where = r.stage + (r.mesh.empty() ? "" : ", mesh " + r.mesh);
    if (!r.error.empty()) {
      s.warnings.push_back(fmt::format("rating {}: not rated: {}", where, r.error));
      continue;
    }
    s.results.push_back(fmt::format("rating {} ({}): governs {}", where, r.standard, r.governs));
    for (const auto& row : r.rows) {
      if (row.minimum == RatingReport::Row::NoMinimum) continue;
      for (size_t k = 0; k < row.si.size(); ++k) {
        std::string gear = row.perGear && k < r.gears.size() ? ", " + r.gears[k] : "";
        s.safeties.push_back({where + gear, row.label, row.si[k] / row.scale, r.minimumOf(row.minimum)});
      }
    }
    for (const auto& w : r.warnings) s.warnings.push_back(fmt::format("rating {}: {}", where, w));
  }
}

// Each shaft's bearings: their lives, and the shaft's critical speed against its speed.
void shaftResults(const GearboxReport& g, GearboxSummary& s) {
  for (const auto& sh : g.shafts) {
    if (!sh.error.empty()) {
      s.warnings.push_back(fmt::format("shaft {}: not solved: {}", sh.name, sh.error));
      continue;
    }
    std::vector<std::string> lives;
    for (const auto& b : sh.bearings) lives.push_back(fmt::format("{} L10h {:.0f} h, L_nmh {:.0f} h, s0 {:.2f}", b.name, b.L10h, b.Lnmh, b.s0));
    std::string strength;
    if (!sh.notches.empty()) {
      auto least = [&](double ShaftReport::Notch::*v) {
        return *std::min_element(sh.notches.begin(), sh.notches.end(), [&](const auto& a, const auto& b) { return a.*v < b.*v; });
      };
      const auto& d = least(&ShaftReport::Notch::SD);
      const auto& f = least(&ShaftReport::Notch::SF);
      strength = fmt::format("; S_D {:.2f} (min {:.2f}, {} at {:g} mm), S_F {:.2f} (min {:.2f}, {} at {:g} mm)", d.SD,
                             sh.minFatigue, d.kind, d.x * 1e3, f.SF, sh.minStatic, f.kind, f.x * 1e3);
      s.safeties.push_back({fmt::format("shaft {}, {} at {:g} mm", sh.name, d.kind, d.x * 1e3), "S_D", d.SD, sh.minFatigue});
      s.safeties.push_back({fmt::format("shaft {}, {} at {:g} mm", sh.name, f.kind, f.x * 1e3), "S_F", f.SF, sh.minStatic});
    }
    s.results.push_back(fmt::format("shaft {}: {}{}; critical speed {:.0f} rpm at {:.0f} rpm", sh.name, fmt::join(lives, "; "),
                                    strength, sh.criticalSpeed * 30 / 3.14159265358979323846,
                                    sh.speed * 30 / 3.14159265358979323846));
  }
}

} // namespace

GearboxSummary summarise(const GearboxReport& g) {
  GearboxSummary s;
  s.headline = fmt::format("{} design{}", g.count, g.count == 1 ? "" : "s");
  if (g.undecided) s.headline += fmt::format(" ({} undecided)", g.undecided);
  if (g.count > g.rows.size()) s.headline += fmt::format(", best {} shown", g.rows.size());
  if (g.partial) s.headline += " (partial: the time limit stopped the work)";
  if (!g.window.empty()) s.headline += "; ratio window " + g.window;
  s.inputs = g.inputs;
  if (!g.rows.empty()) {
    // Each value with its unit after it: `hs.contact_temperature 145.2128 degC`.
    const DesignRow& r = g.rows[0];
    for (const auto& [n, z] : r.teeth) s.design.emplace_back(n, std::to_string(z));
    for (const auto& [n, c] : r.choices) s.design.emplace_back(n, c);
    s.design.emplace_back("ratio", formatNumber(r.ratio.toDouble()) + " (" + r.ratio.str() + ")");
    for (size_t i = 0; i < g.columns.size() && i < r.cells.size(); ++i)
      // A column that is a decided freedom (`hs.face_width`) is already in the line.
      if (std::none_of(s.design.begin(), s.design.end(), [&](const auto& d) { return d.first == g.columns[i].name; }))
        s.design.emplace_back(g.columns[i].name, r.cells[i].text + (g.columns[i].unit.empty() ? "" : " " + g.columns[i].unit));
  }
  if (g.count == 0)
    s.warnings.push_back("no design satisfies every rule: the elimination funnel below shows what each rule removed");
  for (const auto& w : g.warnings) s.warnings.push_back(w);
  modificationResults(g, s);
  sceneResults(g, s);
  studyResults(g, s);
  ratingResults(g, s);
  shaftResults(g, s);
  return s;
}

std::vector<std::vector<size_t>> columnGroups(const std::vector<double>& widths, double limit) {
  std::vector<std::vector<size_t>> groups(1, {0});
  if (widths.empty()) return groups;
  double used = widths[0];
  for (size_t c = 1; c < widths.size(); ++c) {
    if (used + widths[c] > limit && groups.back().size() > 1) {
      groups.push_back({0});
      used = widths[0];
    }
    groups.back().push_back(c);
    used += widths[c];
  }
  return groups;
}

std::vector<std::string> cellsOf(const std::vector<std::string>& row, const std::vector<size_t>& columns) {
  std::vector<std::string> out;
  for (size_t c : columns) out.push_back(c < row.size() ? row[c] : "");
  return out;
}

} // namespace gbx::rt
