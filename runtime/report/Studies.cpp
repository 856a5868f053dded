#include "report/Studies.h"

#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"

namespace gbx::rt {

namespace {

StudyTable table(const SweepStudy& s) {
  StudyTable t;
  t.name = s.name;
  t.kind = "sweep";
  const bool lines = !s.seriesTarget.empty();
  if (lines) t.header.push_back(s.seriesTarget + (s.seriesUnit.name.empty() ? "" : " [" + s.seriesUnit.name + "]"));
  t.header.push_back(s.target + (s.unit.name.empty() ? "" : " [" + s.unit.name + "]"));
  for (const auto& out : s.outputs) t.header.push_back(out.text + (out.unit.name.empty() ? "" : " [" + out.unit.name + "]"));
  bool arclength = s.continuation == "arclength";
  if (s.scene) t.header.push_back("stability of " + s.stabilityScene);
  if (arclength) t.header.push_back("branch");
  for (const auto& p : s.points) {
    std::vector<std::string> row;
    if (lines) row.push_back(fmt::format("{:.6g}", s.seriesUnit.shown(p.series)));
    row.push_back(fmt::format("{:.6g}", s.unit.shown(p.x)));
    bool unstable = std::isfinite(p.stability) && p.stability >= 1.0;
    for (size_t i = 0; i < s.outputs.size() && i < p.y.size(); ++i) {
      bool u = i < p.unstable.size() ? p.unstable[i] : unstable;
      row.push_back(std::isfinite(p.y[i]) ? formatNumber(s.outputs[i].unit.shown(p.y[i])) : u ? "unstable" : "n/a");
    }
    if (s.scene) row.push_back(std::isfinite(p.stability) ? fmt::format("{:.4f}{}", p.stability, unstable ? " (unstable)" : "") : "-");
    if (arclength) row.push_back(std::to_string(p.branch));
    t.rows.push_back(std::move(row));
  }
  for (double f : s.folds) t.notes.push_back(fmt::format("turning point (jump) at {} = {:.6g} {}", s.target, s.unit.shown(f), s.unit.name));
  for (const auto& [from, to] : s.gaps)
    t.warnings.push_back(fmt::format("the continuation did not follow {} from {:.6g} to {:.6g} {} (a gap; no line is drawn across it)", s.target,
                                     s.unit.shown(from), s.unit.shown(to), s.unit.name));
  for (const auto& [x, label] : s.marks)
    t.notes.push_back(fmt::format("{}: {} = {:.6g} {}", label, s.target, s.unit.shown(x), s.unit.name));
  for (const auto& n : s.notes) t.notes.push_back(n);
  return t;
}

StudyTable table(const WorkPrecisionStudy& s, bool timings) {
  StudyTable t;
  t.name = s.name;
  t.kind = "work_precision";
  t.header = {"harmonics", "method", "steady state", "rtol", "error", "steps", "RHS evaluations"};
  if (timings) t.header.push_back("CPU ms");
  for (const auto& c : s.curves)
    for (const auto& run : c.runs) {
      std::vector<std::string> row = {c.harmonics == 0 ? "-" : std::to_string(c.harmonics), c.method, c.steady, fmt::format("{:.0e}", run.rtol)};
      if (!run.ok) {
        row.push_back("failed");
        row.push_back("-");
        row.push_back("-");
        if (timings) row.push_back("-");
      } else {
        row.push_back(fmt::format("{:.2e}", run.error));
        row.push_back(std::to_string(run.steps));
        row.push_back(std::to_string(run.rhsEvaluations));
        if (timings) row.push_back(fmt::format("{:.2f}", run.cpuSeconds * 1e3));
      }
      t.rows.push_back(std::move(row));
    }
  for (const auto& r : s.references) {
    if (!r.ok) {
      t.notes.push_back(fmt::format("harmonics {}: no reference ({})", r.harmonics, r.failure));
      continue;
    }
    t.notes.push_back(fmt::format("harmonics {}: reference {} = {:.10g} at rtol {:.0e} (rk8pd, {}), within {:.1e} of a run at rtol {:.0e}",
                                  r.harmonics == 0 ? std::string("-") : std::to_string(r.harmonics), r.output, r.value, r.rtol, r.steady,
                                  r.difference, r.checkRtol));
  }
  return t;
}

std::string json(const SweepStudy& s) {
  std::string points;
  for (size_t k = 0; k < s.points.size(); ++k) {
    const auto& p = s.points[k];
    std::string outs;
    for (size_t i = 0; i < s.outputs.size() && i < p.y.size(); ++i)
      outs += fmt::format("{}\"{}\": {}", i ? ", " : "", diag::jsonEscape(s.outputs[i].text), jsonNumber(p.y[i]));
    std::string extra;
    if (s.scene)
      extra += fmt::format(", \"stability\": {}", jsonNumber(p.stability));
    if (s.continuation == "arclength") extra += fmt::format(", \"branch\": {}", p.branch);
    if (s.scene) {
      std::string flags;
      for (size_t i = 0; i < s.outputs.size(); ++i)
        flags += fmt::format("{}{}", i ? ", " : "", i < p.unstable.size() && p.unstable[i] ? "true" : "false");
      extra += ", \"unstable\": [" + flags + "]";
    }
    // The line's quantity under its own name, SI.
    if (!s.seriesTarget.empty())
      extra += fmt::format(", \"{}\": {}", diag::jsonEscape(s.seriesTarget), jsonNumber(p.series));
    // The swept quantity under its own name too (docs/dynamics.md).
    points += fmt::format("{}{{\"x\": {}, \"{}\": {}{}, \"outputs\": {{{}}}}}", k ? ", " : "", jsonNumber(p.x), diag::jsonEscape(s.target), jsonNumber(p.x), extra, outs);
  }
  std::string folds, marks, notes, gaps;
  for (size_t i = 0; i < s.folds.size(); ++i) folds += fmt::format("{}{}", i ? ", " : "", jsonNumber(s.folds[i]));
  for (size_t i = 0; i < s.gaps.size(); ++i) gaps += fmt::format("{}[{}, {}]", i ? ", " : "", jsonNumber(s.gaps[i].first), jsonNumber(s.gaps[i].second));
  for (size_t i = 0; i < s.marks.size(); ++i)
    marks += fmt::format("{}{{\"at\": {}, \"label\": \"{}\"}}", i ? ", " : "", jsonNumber(s.marks[i].first), diag::jsonEscape(s.marks[i].second));
  for (size_t i = 0; i < s.notes.size(); ++i) notes += fmt::format("{}\"{}\"", i ? ", " : "", diag::jsonEscape(s.notes[i]));
  std::string series =
      s.seriesTarget.empty() ? "" : fmt::format(", \"lines\": \"{}\"", diag::jsonEscape(s.seriesTarget));
  return fmt::format(
      "{{\"sweep\": \"{}\"{}, \"unit\": \"SI\"{}, \"points\": [{}]}}", diag::jsonEscape(s.target), series,
      s.scene ? fmt::format(", \"continuation\": \"{}\", \"stability_of\": \"{}\", \"folds\": [{}], \"gaps\": [{}], "
                            "\"marks\": [{}], \"notes\": [{}]",
                            s.continuation, diag::jsonEscape(s.stabilityScene), folds, gaps, marks, notes)
              : "",
      points);
}

std::string json(const WorkPrecisionStudy& s, bool timings) {
  // The output named is that of the last reference.
  std::string key, refs, runs;
  for (const auto& r : s.references) {
    if (!r.ok) continue;
    key = r.output;
    refs += fmt::format("{}{{\"harmonics\": {}, \"rtol\": {}, \"value\": {}, \"checked_against_rtol\": {}, \"difference\": {}}}",
                        refs.empty() ? "" : ", ", r.harmonics, jsonNumber(r.rtol), jsonNumber(r.value), jsonNumber(r.checkRtol),
                        jsonNumber(r.difference));
  }
  for (const auto& c : s.curves)
    for (const auto& run : c.runs) {
      if (!run.ok) continue;
      runs += fmt::format("{}{{\"harmonics\": {}, \"method\": \"{}\", \"steady_state\": \"{}\", \"rtol\": {}, \"error\": {}, \"steps\": {}, \"rhs_evaluations\": {}{}}}",
                          runs.empty() ? "" : ", ", c.harmonics, diag::jsonEscape(c.method), diag::jsonEscape(c.steady), jsonNumber(run.rtol),
                          jsonNumber(run.error), run.steps, run.rhsEvaluations,
                          timings ? fmt::format(", \"cpu_seconds\": {}", jsonNumber(run.cpuSeconds)) : "");
    }
  return fmt::format("{{\"scene\": \"{}\", \"output\": \"{}\", \"references\": [{}], \"runs\": [{}]}}", diag::jsonEscape(s.scene), diag::jsonEscape(key), refs, runs);
}

} // namespace

std::string studyName(const StudyReport& st) {
  return std::visit([](const auto& s) { return s.name; }, st.study);
}

StudyTable studyTable(const StudyReport& st, const RenderOptions& o) {
  if (const auto* s = std::get_if<SweepStudy>(&st.study)) return table(*s);
  return table(std::get<WorkPrecisionStudy>(st.study), o.timings);
}

std::string studyJson(const StudyReport& st, const RenderOptions& o) {
  if (const auto* s = std::get_if<SweepStudy>(&st.study)) return json(*s);
  return json(std::get<WorkPrecisionStudy>(st.study), o.timings);
}

} // namespace gbx::rt
