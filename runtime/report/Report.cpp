#include "report/Report.h"
#include "report/Shafts.h"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"
#include "report/Optimisation.h"
#include "report/MonteCarlo.h"
#include "report/Ratings.h"
#include "report/Studies.h"
#include "report/Summary.h"
#include "report/Symbols.h"

namespace gbx::rt {

std::string formatNumber(double v) {
  if (!std::isfinite(v)) return "n/a";
  double a = std::fabs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e7)) return fmt::format("{:.4e}", v);
  std::string s = fmt::format("{:.4f}", v);
  return s == "-0.0000" ? "0.0000" : s;
}

std::string formatLength(double m) {
  if (!std::isfinite(m)) return "n/a";
  if (std::fabs(m) < 1e-3) return fmt::format("{:.2f} um", m * 1e6);
  return fmt::format("{:.2f} mm", m * 1e3);
}

namespace {

std::string count(double x) { return fmt::format("{:.0f}", x + 0.0); }  // + 0.0: a zero prints without its sign

std::vector<std::string> header(const GearboxReport& g) { return designHeader(g); }

std::vector<std::string> cells(const DesignRow& r) { return designCells(r); }

} // namespace

namespace {

// The text report's width: a longer line wraps, a wider table is cut into column groups.
constexpr size_t kTextWidth = 120;

// A line longer than the width, broken at blanks (after a comma or a semicolon where one is
// near), each continuation indented four more than the line.
std::string wrapLine(const std::string& line) {
  if (line.size() <= kTextWidth) return line;
  size_t lead = line.find_first_not_of(' ');
  std::string hang(std::min<size_t>(lead == std::string::npos ? 0 : lead, 40) + 4, ' ');
  std::string out, rest = line;
  bool first = true;
  while (rest.size() > kTextWidth) {
    size_t cut = rest.rfind(' ', kTextWidth);
    size_t start = first ? (lead == std::string::npos ? 0 : lead) : hang.size();
    if (cut == std::string::npos || cut <= start) break;  // one word longer than the line
    // Prefer a break after a list's comma or semicolon in the last third of the line.
    for (size_t c = cut; c > start + kTextWidth / 2; c = rest.rfind(' ', c - 1)) {
      if (rest[c - 1] == ',' || rest[c - 1] == ';') {
        cut = c;
        break;
      }
      if (c == 0) break;
    }
    out += rest.substr(0, cut) + "\n";
    rest = hang + rest.substr(rest.find_first_not_of(' ', cut));
    first = false;
  }
  return out + rest;
}

std::string wrapLines(const std::string& text) {
  std::string out;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    out += wrapLine(text.substr(at, end - at));
    if (end < text.size()) out += "\n";
    at = end + 1;
  }
  return out;
}

// A table's rows padded to their columns' widths, right-aligned, each line after `indent`.
std::string aligned(const std::vector<std::vector<std::string>>& table, const std::string& indent, size_t columns) {
  std::vector<size_t> w(columns, 0);
  for (const auto& row : table)
    for (size_t i = 0; i < row.size() && i < w.size(); ++i) w[i] = std::max(w[i], row[i].size());
  std::string o;
  for (const auto& row : table) {
    std::string line = indent;
    for (size_t i = 0; i < row.size() && i < w.size(); ++i) line += " " + fmt::format("{:>{}}", row[i], w[i]);
    o += line + "\n";
  }
  return o;
}

// The summary that opens a gearbox's part of the report: what it was solved for, design 1
// and its key results, each safety against its minimum, and every warning of the report.
std::string textSummary(const GearboxReport& g) {
  GearboxSummary s = summarise(g);
  std::string o;
  std::vector<std::string> operating;
  for (const auto& in : s.inputs) {
    if (in.stage) continue;
    operating.push_back(in.label + " " + in.value);
  }
  if (!operating.empty()) o += fmt::format("  operating point: {}\n", fmt::join(operating, ", "));
  for (const auto& in : s.inputs)
    if (in.stage) o += fmt::format("  {}: {}\n", in.label, in.value);
  if (!s.design.empty() && !s.results.empty()) {  // the table below lists it too; here beside its results
    std::vector<std::string> parts;
    for (const auto& [n, v] : s.design) parts.push_back(n + " " + v);
    o += fmt::format("  design 1: {}\n", fmt::join(parts, ", "));
  }
  for (const auto& r : s.results) o += "  result: " + r + "\n";
  for (const auto& sf : s.safeties)
    o += sf.computed() ? fmt::format("  safety: {} {} {} against {} ({})\n", sf.where, sf.label, formatNumber(sf.value),
                                     formatNumber(sf.minimum), sf.ok() ? "met" : "BELOW the minimum")
                       : fmt::format("  safety: {} {} not rated (the rating below says why)\n", sf.where, sf.label);
  for (const auto& w : s.warnings) o += "  warning: " + w + "\n";
  return o;
}

// The design list: its headline, table, funnel, notes, and the optimisation.
// A table wider than the text report: groups of columns that each fit, every group opening
// with the first column (the rank), one after the other.
std::string alignedToWidth(const std::vector<std::vector<std::string>>& table, const std::string& indent) {
  size_t columns = table.empty() ? 0 : table[0].size();
  // Each column takes its widest cell and the blank before it.
  std::vector<double> widths(columns, 1);
  for (const auto& row : table)
    for (size_t i = 0; i < row.size() && i < columns; ++i) widths[i] = std::max(widths[i], static_cast<double>(row[i].size()) + 1);
  auto groups = columnGroups(widths, static_cast<double>(kTextWidth - indent.size()));
  if (groups.size() == 1) return aligned(table, indent, columns);
  std::string o;
  for (const auto& cols : groups) {
    std::vector<std::vector<std::string>> part;
    for (const auto& row : table) part.push_back(cellsOf(row, cols));
    o += aligned(part, indent, cols.size());
  }
  return o;
}

std::string textDesigns(const GearboxReport& g, const RenderOptions& ro) {
  std::string o = fmt::format("gearbox {}: {} design{}", g.name, g.count, g.count == 1 ? "" : "s");
  if (g.undecided) o += fmt::format(" ({} undecided)", g.undecided);
  if (g.count > g.rows.size()) o += fmt::format(", best {} shown", g.rows.size());
  if (g.partial) o += " (partial: the time limit stopped the work; see the note)";
  o += "\n";
  if (!g.window.empty()) o += "  ratio window " + g.window + "\n";
  o += textSummary(g);
  if (!g.rows.empty()) {
    auto h = header(g);
    std::vector<std::vector<std::string>> table = {h};
    for (const auto& r : g.rows) table.push_back(cells(r));
    o += alignedToWidth(table, " ");
  }
  if (g.count == 0 || g.undecided) {
    o += "  elimination funnel:\n";
    for (const auto& f : g.funnel) {
      if (f.domain) {
        o += fmt::format("    stage {}: {} candidates\n", f.scope, count(-f.removed));
        continue;
      }
      o += fmt::format("    {}{}: {} of {} removed\n", f.scope.empty() ? "" : f.scope + ": ", f.rule, count(f.removed), count(f.before));
    }
  }
  for (const auto& c : g.columns)
    if (!c.exact) o += "  note: intervals of `" + c.name + "` are enclosures (interval arithmetic), not exact images\n";
  for (const auto& n : g.notes) o += "  note: " + n + "\n";
  if (g.undecided) o += "  ? = feasibility undecided at the freedom resolution (kept, not proven)\n";
  if (g.optimisation) {
    for (const auto& l : optimisationLines(*g.optimisation)) o += "  " + l + "\n";
    if (ro.timings) o += "  " + optimisationTiming(*g.optimisation) + "\n";
  }
  return o;
}

std::string textModification(const ModifyReport& md) {
  std::string o = fmt::format("  modify {} (design 1)\n", md.stage);
  for (const auto& r : md.rows) {
    if (!r.error.empty()) o += fmt::format("    {}: not computed: {}\n", r.target, r.error);
    else if (!r.present) o += fmt::format("    {}: absent (not {})\n", r.target, r.condition);
    else o += fmt::format("    {} = {}{}\n", r.target, r.shown, r.condition.empty() ? "" : fmt::format(" (as {})", r.condition));
    o += fmt::format("      rule: {}\n", r.text);
    for (const auto& in : r.inputs) o += "      input: " + in + "\n";
  }
  return o;
}

std::string textRating(const RatingReport& r) {
  std::string o = fmt::format("  rating {}{} (design 1), {}-1/-2/-3\n", r.stage, r.mesh.empty() ? "" : ", mesh " + r.mesh, r.standard);
  if (r.error.empty()) {
    auto rows = ratingRows(r);
    rows.insert(rows.begin(), ratingHeader(r));
    std::vector<size_t> w(rows[0].size(), 0);
    for (const auto& row : rows)
      for (size_t i = 0; i < row.size() && i < w.size(); ++i) w[i] = std::max(w[i], row[i].size());
    for (const auto& row : rows) {
      std::string line = fmt::format("    {:<{}}", row[0], w[0]);
      // Numbers align right; the method, last, reads left to right.
      for (size_t i = 1; i < row.size(); ++i) line += " " + (i + 1 == row.size() ? fmt::format("  {}", row[i]) : fmt::format("{:>{}}", row[i], w[i]));
      while (!line.empty() && line.back() == ' ') line.pop_back();
      o += line + "\n";
    }
  }
  o += "    " + ratingVerdict(r) + "\n";
  for (const auto& n : r.notRated)
    if (!n.inNote) o += fmt::format("    not rated: the {}'s {}: {}\n", n.gear, n.what, n.reason);
  for (const auto& w : r.warnings) o += "    warning: " + w + "\n";
  for (const auto& line : r.model) o += "    " + line + "\n";
  for (const auto& f : r.files) o += "    chart: " + f + "\n";
  return o;
}

std::string textScene(const SceneReport& sc, const GearboxReport& g, const RenderOptions& ro) {
  std::string o = fmt::format("  scene {} on {} (design 1)\n", sc.name, sc.target.empty() ? g.name : sc.target);
  if (!sc.failure.empty()) return o + "    failed: " + sc.failure + "\n";
  if (sc.eigen) o += "    accuracy: generalised eigenproblem (Eigen), double precision\n";
  else if (!sc.integrated)
    o += "    accuracy: nothing integrated, the outputs read the loaded mesh's table; steady state: static\n";
  else
    o += fmt::format("    accuracy: {}, rtol {:.0e}, atol {:.0e} (scaled){}; steady state: {}\n", sc.method, sc.rtol, sc.atol,
                     sc.stepRule.empty() ? "" : ", " + sc.stepRule, sc.steady);
  for (const auto& out : sc.outputs)
    o += std::isfinite(out.shown)
             ? fmt::format("    {} = {}{}{}\n", out.key, formatNumber(out.shown), out.unit.empty() ? "" : " " + out.unit,
                           SceneReport::ownError(out, sc.errorEstimate) ? fmt::format(" (error estimate {:.2e} of its scale)", out.error)
                                                                         : "")
             : fmt::format("    {} = none (no steady response)\n", out.key);
  if (sc.errorEstimate >= 0) o += fmt::format("    error estimate: {:.2e} relative = {}\n", sc.errorEstimate, sc.errorMethod);
  for (const auto& w : sc.warnings) o += "    warning: " + w + "\n";
  if (!sc.eigen)
    o += fmt::format("    cost: {} steps, {} rejected, {} RHS evaluations, {} Jacobians, {} events located\n", sc.steps, sc.rejected,
                     sc.rhs, sc.jacobians, sc.events);
  for (const auto& sp : sc.spectra) {
    o += fmt::format("    {} peaks:", sp.key);
    for (const auto& p : sp.peaks)
      o += fmt::format(" {:.2f} Hz{} {}{};", p.frequency, p.harmonic ? fmt::format(" ({}x mesh)", p.harmonic) : "",
                       formatNumber(p.amplitude / sp.scale), sp.unit.empty() ? "" : " " + sp.unit);
    o += "\n";
  }
  for (const auto& m : sc.model) o += "    model: " + m + "\n";
  for (const auto& f : sc.files) o += "    wrote " + f + "\n";
  if (ro.timings) o += fmt::format("    timing: {:.1f} ms CPU (error estimate run {:.1f} ms)\n", sc.cpu * 1e3, sc.referenceCpu * 1e3);
  return o;
}

std::string textStudy(const StudyReport& study, const RenderOptions& ro) {
  StudyTable st = studyTable(study, ro);
  std::string o = fmt::format("  study {} ({})\n", st.name, st.kind);
  std::vector<std::vector<std::string>> table = {st.header};
  for (const auto& r : st.rows) table.push_back(r);
  o += aligned(table, "   ", st.header.size());
  for (const auto& n : st.notes) o += "    note: " + n + "\n";
  for (const auto& w : st.warnings) o += "    warning: " + w + "\n";
  for (const auto& f : study.files) o += "    wrote " + f + "\n";
  return o;
}

// Monte Carlo over the tolerances: what was sampled, the statistics, how far to trust them.
std::string textMonteCarlo(const MonteCarloReport& r) {
  std::string o = "  monte carlo: " + monteCarloHeadline(r) + "\n    tolerances: " + monteCarloTolerances(r) + "\n";
  std::vector<std::vector<std::string>> t = {monteCarloHeader()};
  for (auto& row : monteCarloRows(r)) t.push_back(std::move(row));
  o += aligned(t, "   ", t.front().size());
  for (const auto& n : monteCarloNotes(r)) o += "    note: " + n + "\n";
  for (const auto& f : r.files) o += "    histogram: " + f + "\n";
  return o;
}

} // namespace

std::string renderText(const std::vector<GearboxReport>& reports, const RenderOptions& ro) {
  std::string o;
  for (const auto& g : reports) {
    o += textDesigns(g, ro);
    if (g.monteCarlo) o += textMonteCarlo(*g.monteCarlo);
    for (const auto& md : g.modifications) o += textModification(md);
    for (const auto& r : g.ratings) o += textRating(r);
    for (const auto& sh : g.shafts) o += textShaft(sh);
    for (const auto& sc : g.scenes) o += textScene(sc, g, ro);
    for (const auto& study : g.studies) o += textStudy(study, ro);
  }
  return wrapLines(o);
}

std::string jsonNumber(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("null"); }

namespace {

// One listed design: teeth, choices, ratio, column values and their feasible ranges.
std::string jsonCandidate(const GearboxReport& g, const DesignRow& r) {
  using diag::jsonEscape;
  auto num = jsonNumber;
  std::string o;
  o += fmt::format("{{\"rank\": {}, \"teeth\": {{", r.rank);
  for (size_t i = 0; i < r.teeth.size(); ++i)
    o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(r.teeth[i].first), r.teeth[i].second);
  o += "}";
  if (!r.choices.empty()) {
    o += ", \"choices\": {";
    for (size_t i = 0; i < r.choices.size(); ++i)
      o += fmt::format("{}\"{}\": \"{}\"", i ? ", " : "", jsonEscape(r.choices[i].first), jsonEscape(r.choices[i].second));
    o += "}";
  }
  // The same decisions as numbers in SI with their unit (schema 1.2).
  if (!r.choiceValues.empty() && r.choiceValues.size() == r.choices.size()) {
    o += ", \"choice_values\": {";
    for (size_t i = 0; i < r.choiceValues.size(); ++i)
      o += fmt::format("{}\"{}\": {{\"value\": {}, \"unit\": \"{}\"}}", i ? ", " : "", jsonEscape(r.choices[i].first),
                       num(r.choiceValues[i].si), jsonEscape(r.choiceValues[i].siUnit));
    o += "}";
  }
  o += fmt::format(", \"ratio\": {}, \"ratio_exact\": \"{}\", \"undecided\": {}, \"values\": {{", num(r.ratio.toDouble()),
                   r.ratio.str(), r.undecided ? "true" : "false");
  for (size_t i = 0; i < r.cells.size() && i < g.columns.size(); ++i) {
    const Cell& c = r.cells[i];
    std::string v = !c.valid || (std::isnan(c.lo) && std::isnan(c.hi)) ? "null" : c.lo == c.hi ? num(c.lo) : fmt::format("[{}, {}]", num(c.lo), num(c.hi));
    o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(g.columns[i].name), v);
  }
  o += "}";
  // The columns' intervals of one kind ("ranges", "feasible"), where some cell has one.
  auto intervals = [&](const char* key, bool Cell::*has, double Cell::*lo, double Cell::*hi) {
    bool first = true;
    for (size_t i = 0; i < r.cells.size() && i < g.columns.size(); ++i) {
      const Cell& c = r.cells[i];
      if (!(c.*has)) continue;
      o += fmt::format("{}\"{}\": [{}, {}]", first ? fmt::format(", \"{}\": {{", key) : ", ", jsonEscape(g.columns[i].name),
                       num(c.*lo), num(c.*hi));
      first = false;
    }
    if (!first) o += "}";
  };
  intervals("ranges", &Cell::ranged, &Cell::rlo, &Cell::rhi);
  intervals("feasible", &Cell::feasible, &Cell::flo, &Cell::fhi);
  o += "}";
  return o;
}

// One scene: its accuracy, cost, error estimate, outputs, spectra and model lines.
std::string jsonScene(const SceneReport& sc, const RenderOptions& ro) {
  using diag::jsonEscape;
  auto num = jsonNumber;
  std::string o;
  if (!sc.failure.empty()) {
    o += fmt::format("\"failure\": \"{}\"}}", jsonEscape(sc.failure));
    return o;
  }
  o += fmt::format("\"target\": \"{}\", \"method\": \"{}\", \"rtol\": {}, \"atol\": {}, \"steps\": {}, \"rejected\": {}, "
                   "\"rhs_evaluations\": {}, \"jacobian_evaluations\": {}, \"events\": {}, ",
                   jsonEscape(sc.target), jsonEscape(sc.method), num(sc.rtol), num(sc.atol), sc.steps, sc.rejected, sc.rhs, sc.jacobians, sc.events);
  if (ro.timings) o += fmt::format("\"cpu_seconds\": {}, ", num(sc.cpu));
  o += fmt::format("\"steady_state\": \"{}\", \"max_step_rule\": \"{}\", ", jsonEscape(sc.steady), jsonEscape(sc.stepRule));
  o += fmt::format("\"error_estimate\": {}, \"error_method\": \"{}\", \"error_parts\": {{", sc.errorEstimate >= 0 ? num(sc.errorEstimate) : "null",
                   jsonEscape(sc.errorMethod));
  for (size_t i = 0; i < sc.errorParts.size(); ++i)
    o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(sc.errorParts[i].first), num(sc.errorParts[i].second));
  o += "}, \"outputs\": {";
  for (size_t i = 0; i < sc.outputs.size(); ++i) o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(sc.outputs[i].key), num(sc.outputs[i].si));
  o += "}, \"output_errors\": {";
  bool firstError = true;
  for (const auto& out : sc.outputs)
    if (std::isfinite(out.error)) {
      o += fmt::format("{}\"{}\": {}", firstError ? "" : ", ", jsonEscape(out.key), num(out.error));
      firstError = false;
    }
  o += "}, \"spectra\": {";
  for (size_t i = 0; i < sc.spectra.size(); ++i) {
    o += fmt::format("{}\"{}\": [", i ? ", " : "", jsonEscape(sc.spectra[i].key));
    for (size_t k = 0; k < sc.spectra[i].peaks.size(); ++k) {
      const auto& p = sc.spectra[i].peaks[k];
      o += fmt::format("{}{{\"frequency\": {}, \"amplitude\": {}, \"harmonic\": {}}}", k ? ", " : "", num(p.frequency), num(p.amplitude), p.harmonic);
    }
    o += "]";
  }
  o += "}, \"model\": [";
  for (size_t i = 0; i < sc.model.size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", jsonEscape(sc.model[i]));
  o += "]";
  if (!sc.warnings.empty()) {
    o += ", \"warnings\": [";
    for (size_t i = 0; i < sc.warnings.size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", jsonEscape(sc.warnings[i]));
    o += "]";
  }
  o += "}";
  return o;
}

// One stage's modification rules, as lists of rows.
std::string jsonModification(const ModifyReport& md) {
  using diag::jsonEscape;
  auto num = jsonNumber;
  std::string o;
  for (size_t ri = 0; ri < md.rows.size(); ++ri) {
    const auto& r = md.rows[ri];
    o += fmt::format("{}\n      {{\"target\": \"{}\", \"present\": {}, \"value\": {}, \"rule\": \"{}\", \"inputs\": {{", ri ? "," : "",
                     jsonEscape(r.target), r.present ? "true" : "false", r.present && r.valid ? num(r.si) : "null", jsonEscape(r.text));
    for (size_t i = 0; i < r.inputsSI.size(); ++i)
      o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(r.inputsSI[i].first), num(r.inputsSI[i].second));
    o += "}";
    if (!r.error.empty()) o += fmt::format(", \"error\": \"{}\"", jsonEscape(r.error));
    o += "}";
  }
  o += "]";
  return o;
}

} // namespace

std::string renderJson(const std::vector<GearboxReport>& reports, const RenderOptions& ro) {
  using diag::jsonEscape;
  std::string o = fmt::format("{{\"schema\": \"{}\", \"gearboxes\": [", kReportSchemaVersion);
  for (size_t gi = 0; gi < reports.size(); ++gi) {
    const auto& g = reports[gi];
    o += gi ? ",\n" : "\n";
    o += fmt::format("  {{\"name\": \"{}\", \"count\": {}, \"undecided\": {}, \"window\": \"{}\",\n   \"candidates\": [",
                     jsonEscape(g.name), g.count, g.undecided, jsonEscape(g.window));
    for (size_t ri = 0; ri < g.rows.size(); ++ri) {
      o += ri ? ",\n    " : "\n    ";
      o += jsonCandidate(g, g.rows[ri]);
    }
    o += g.rows.empty() ? "],\n" : "\n   ],\n";
    o += "   \"columns\": [";
    for (size_t i = 0; i < g.columns.size(); ++i)
      o += fmt::format("{}{{\"name\": \"{}\", \"unit\": \"SI\", \"si_unit\": \"{}\", \"display_unit\": \"{}\", \"intervals\": \"{}\"}}",
                       i ? ", " : "", jsonEscape(g.columns[i].name), jsonEscape(g.columns[i].siUnit), jsonEscape(g.columns[i].unit),
                       g.columns[i].exact ? "exact" : "enclosure");
    o += "],\n   \"funnel\": [";
    for (size_t i = 0; i < g.funnel.size(); ++i) {
      const auto& f = g.funnel[i];
      if (f.domain)
        o += fmt::format("{}\n    {{\"scope\": \"{}\", \"rule\": \"domain\", \"candidates\": {}}}", i ? "," : "", jsonEscape(f.scope),
                         count(-f.removed));
      else
        o += fmt::format("{}\n    {{\"scope\": \"{}\", \"rule\": \"{}\", \"before\": {}, \"removed\": {}}}", i ? "," : "",
                         jsonEscape(f.scope), jsonEscape(f.rule), count(f.before), count(f.removed));
    }
    o += g.funnel.empty() ? "]," : "\n   ],";
    // Present where there are any.
    for (const auto& [key, lines] : {std::pair{"notes", &g.notes}, std::pair{"warnings", &g.warnings}}) {
      if (lines->empty()) continue;
      o += fmt::format("\n   \"{}\": [", key);
      for (size_t i = 0; i < lines->size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", jsonEscape((*lines)[i]));
      o += "],";
    }
    if (g.optimisation) o += "\n   \"optimisation\": " + optimisationJson(*g.optimisation) + ",";
    o += "\n   \"scenes\": {";
    for (size_t si = 0; si < g.scenes.size(); ++si) {
      const auto& sc = g.scenes[si];
      o += fmt::format("{}\n    \"{}\": {{", si ? "," : "", jsonEscape(sc.name));
      o += jsonScene(sc, ro);
    }
    o += g.scenes.empty() ? "}, " : "\n   }, ";
    o += "\"modifications\": {";
    for (size_t mi = 0; mi < g.modifications.size(); ++mi) {
      const auto& md = g.modifications[mi];
      o += fmt::format("{}\n    \"{}\": [", mi ? "," : "", jsonEscape(md.stage));
      o += jsonModification(md);
    }
    o += g.modifications.empty() ? "}, " : "\n   }, ";
    o += "\"ratings\": {";
    for (size_t ri = 0; ri < g.ratings.size(); ++ri)
      o += fmt::format("{}\n    \"{}\": {}", ri ? "," : "",
                       jsonEscape(g.ratings[ri].stage + (g.ratings[ri].mesh.empty() ? "" : "." + g.ratings[ri].mesh)), ratingJson(g.ratings[ri]));
    o += g.ratings.empty() ? "}, " : "\n   }, ";
    o += "\"shafts\": {";
    for (size_t si = 0; si < g.shafts.size(); ++si)
      o += fmt::format("{}\n    \"{}\": {}", si ? "," : "", jsonEscape(g.shafts[si].name), shaftJson(g.shafts[si]));
    o += g.shafts.empty() ? "}, " : "\n   }, ";
    if (g.monteCarlo) o += "\"monte_carlo\": " + monteCarloJson(*g.monteCarlo) + ", ";
    o += "\"studies\": {";
    for (size_t si = 0; si < g.studies.size(); ++si)
      o += fmt::format("{}\n    \"{}\": {}", si ? "," : "", jsonEscape(studyName(g.studies[si])), studyJson(g.studies[si], ro));
    o += g.studies.empty() ? "}}" : "\n   }}";
  }
  o += "\n]}\n";
  return o;
}

namespace {

// A scene's lines in the Markdown and HTML reports: outputs, method, error, cost, spectra, model.
std::vector<std::string> sceneItems(const SceneReport& sc) {
  std::vector<std::string> items;
  for (const auto& out : sc.outputs)
    items.push_back(std::isfinite(out.shown) ? fmt::format("{} = {}{}", out.key, formatNumber(out.shown), out.unit.empty() ? "" : " " + out.unit)
                                             : fmt::format("{} = none (no steady response)", out.key));
  if (!sc.eigen) items.push_back(fmt::format("steady state: {}{}", sc.steady, sc.stepRule.empty() ? "" : "; " + sc.stepRule));
  if (sc.errorEstimate >= 0) items.push_back(fmt::format("error estimate {:.2e} ({})", sc.errorEstimate, sc.errorMethod));
  for (const auto& w : sc.warnings) items.push_back("warning: " + w);
  if (!sc.eigen) items.push_back(fmt::format("{} at rtol {:.0e}: {} steps, {} RHS evaluations", sc.method, sc.rtol, sc.steps, sc.rhs));
  for (const auto& sp : sc.spectra) {
    std::string peaks;
    for (const auto& p : sp.peaks)
      peaks += fmt::format("{}{:.2f} Hz{} {}{}", peaks.empty() ? "" : "; ", p.frequency, p.harmonic ? fmt::format(" ({}x mesh)", p.harmonic) : "",
                           formatNumber(p.amplitude / sp.scale), sp.unit.empty() ? "" : " " + sp.unit);
    items.push_back(sp.key + " peaks: " + peaks);
  }
  for (const auto& m : sc.model) items.push_back(m);
  return items;
}

// Markdown's pieces: a table (numbers right-aligned), a heading, a list.
std::string mdTable(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  std::string o = "|";
  for (const auto& h : head) o += " " + h + " |";
  o += "\n|";
  // Numbers right-aligned; a column of words (safeties, methods, rules) left.
  for (size_t i = 0; i < head.size(); ++i) {
    bool words = false;
    for (const auto& r : rows)
      if (i < r.size() && !r[i].empty()) words = words || !(std::isdigit(static_cast<unsigned char>(r[i][0])) || r[i][0] == '-' || r[i][0] == '[');
    o += words ? " :--- |" : " ---: |";
  }
  o += "\n";
  for (const auto& r : rows) {
    o += "|";
    for (const auto& c : r) o += " " + c + " |";
    o += "\n";
  }
  return o + "\n";
}

std::string mdHeading(int level, const std::string& t) { return std::string(static_cast<size_t>(level), '#') + " " + t + "\n\n"; }

std::string mdList(const std::vector<std::string>& items) {
  std::string o;
  for (const auto& i : items) o += "- " + i + "\n";
  return o + "\n";
}

// Each shaft's bearings and gear forces, and its lines.
std::string markdownShafts(const GearboxReport& g) {
  std::string o;
  for (const auto& sh : g.shafts) {
    o += mdHeading(3, "Shaft " + sh.name + " (design 1)");
    for (const auto& t : shaftTables(sh)) o += (t.caption.empty() ? "" : t.caption + ":\n\n") + mdTable(t.header, t.rows);
    o += mdList(shaftNotes(sh));
  }
  return o;
}

std::string markdown(const std::vector<GearboxReport>& reports, const RenderOptions& ro) {
  const auto& table = mdTable;
  const auto& heading = mdHeading;
  const auto& list = mdList;
  auto para = [&](const std::string& t) { return t + "\n\n"; };
  auto image = [&](const std::string& f) { return fmt::format("![{}]({})\n\n", f, f); };
  std::string o;
  for (const auto& g : reports) {
    o += heading(2, g.name);
    GearboxSummary sum = summarise(g);
    o += para(sum.headline);
    // The summary first, as in every format.
    std::vector<std::string> solved;
    for (const auto& in : sum.inputs) solved.push_back(fmt::format("**{}**: {}", in.label, unitHtml(in.value)));
    if (!solved.empty()) o += list(solved);
    // Design 1 beside its results, as the text and HTML reports put it.
    if (!sum.design.empty() && !sum.results.empty()) {
      std::vector<std::string> parts;
      for (const auto& [n, v] : sum.design) parts.push_back(n + " " + v);
      o += para(fmt::format("**design 1**: {}", fmt::join(parts, ", ")));
    }
    for (const auto& r : sum.results) o += "- " + r + "\n";
    if (!sum.results.empty()) o += "\n";
    if (!sum.safeties.empty()) {
      std::vector<std::vector<std::string>> sr;
      for (const auto& sf : sum.safeties)
        sr.push_back({sf.where, sf.label, sf.computed() ? formatNumber(sf.value) : "not rated", formatNumber(sf.minimum),
                      !sf.computed() ? "see the rating" : sf.ok() ? "met" : "**below the minimum**"});
      o += table({"where", "safety", "value", "minimum", ""}, sr);
    }
    if (!sum.warnings.empty()) {
      std::vector<std::string> w;
      for (const auto& x : sum.warnings) w.push_back("**warning:** " + x);
      o += list(w);
    }
    std::vector<std::vector<std::string>> rows;
    for (const auto& r : g.rows) rows.push_back(cells(r));
    if (!rows.empty()) o += table(header(g), rows);
    if (!g.notes.empty()) o += list(g.notes);
    if (g.count == 0) {
      std::vector<std::string> f;
      for (const auto& x : g.funnel)
        f.push_back(x.domain ? fmt::format("stage {}: {} candidates", x.scope, count(-x.removed))
                                       : fmt::format("{}{}: {} of {} removed", x.scope.empty() ? "" : x.scope + ": ", x.rule, count(x.removed), count(x.before)));
      o += heading(3, "Elimination funnel") + list(f);
    }
    if (g.optimisation) {
      o += heading(3, "Optimisation") + list(optimisationLines(*g.optimisation, true));
      for (const auto& f : g.optimisation->files) o += image(f);
    }
    if (g.monteCarlo) {
      const auto& mc = *g.monteCarlo;
      o += heading(3, "Monte Carlo over the tolerances") + para(monteCarloHeadline(mc) + "; tolerances " + monteCarloTolerances(mc) + ".");
      o += table(monteCarloHeader(), monteCarloRows(mc)) + list(monteCarloNotes(mc));
      for (const auto& f : mc.files) o += image(f);
    }
    for (const auto& md : g.modifications) {
      o += heading(3, "Modification of " + md.stage) + table(modificationHeader(), modificationRows(md));
    }
    for (const auto& r : g.ratings) {
      o += heading(3, "Rating of " + r.stage + (r.mesh.empty() ? "" : ", mesh " + r.mesh) + " (" + r.standard + ")");
      if (r.error.empty()) {
        // Symbols and units as engineers write them (Markdown renders the HTML inline).
        auto rows = ratingRows(r);
        for (auto& row : rows) row[0] = symbolHtml(row[0]);
        o += table(ratingHeader(r), rows);
      }
      o += para(ratingVerdict(r));
      if (auto notes = ratingNotes(r); !notes.empty()) o += list(notes);
      for (const auto& f : r.files) o += image(f);
    }
    o += markdownShafts(g);
    for (const auto& sc : g.scenes) {
      o += heading(3, "Scene " + sc.name);
      if (!sc.failure.empty()) {
        o += para("failed: " + sc.failure);
        continue;
      }
      o += list(sceneItems(sc));
      for (const auto& f : sc.files) o += image(f);
    }
    for (const auto& study : g.studies) {
      StudyTable st = studyTable(study, ro);
      o += heading(3, "Study " + st.name);
      o += table(st.header, st.rows);
      if (!st.notes.empty()) o += list(st.notes);
      if (!st.warnings.empty()) {
        std::vector<std::string> w;
        for (const auto& x : st.warnings) w.push_back("warning: " + x);
        o += list(w);
      }
      for (const auto& f : study.files) o += image(f);
    }
  }
  return o;
}

} // namespace

std::string renderMarkdown(const std::vector<GearboxReport>& reports, const RenderOptions& o) { return markdown(reports, o); }


} // namespace gbx::rt
