#include "report/Optimisation.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"
#include <fmt/ranges.h>

namespace gbx::rt {

std::vector<std::string> optimisationLines(const OptimisationSummary& s, bool files) {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("optimisation: {} candidates, {} with no feasible freedoms; {} objective evaluations (scenes at rtol {:.0e})",
                              s.candidates, s.infeasible, s.evaluations, s.sceneRtol));
  lines.push_back("  method: Nelder-Mead (GSL nmsimplex2) over the freedoms of each candidate; bounds by x = lo + (hi - lo) sin^2(u);");
  lines.push_back("          rules by an exterior penalty (a violated rule costs 1000 (1 + relative violation)); best optimum kept");
  if (s.best) {
    const auto& best = *s.best;
    std::string vars;
    for (const auto& f : best.freedoms)
      vars += fmt::format("{}{} = {}{}", vars.empty() ? "" : ", ", f.path, formatNumber(f.value / f.unit.scale),
                          f.unit.name.empty() ? "" : " " + f.unit.name);
    lines.push_back(fmt::format("  optimum: ratio {}{}; objective {}", best.ratio.str(), vars.empty() ? "" : ", " + vars, formatNumber(best.objective)));
    for (size_t t = 0; t < s.termNames.size() && t < best.terms.size(); ++t) {
      double rel = best.terms[t] / s.baselineTerms[t];
      lines.push_back(fmt::format("  {}: {} against the baseline's {}: {:+.1f} %", s.termNames[t], formatNumber(best.terms[t]),
                                  formatNumber(s.baselineTerms[t]), (rel - 1) * 100));
    }
  }
  if (s.best && !s.best->margins.empty()) {
    // A rule binds when the optimum sits on its bound (within 0.1 %).
    std::vector<std::string> binds;
    for (const auto& mg : s.best->margins)
      if (mg.margin <= 1e-3) binds.push_back("`" + mg.rule + "`");
    lines.push_back(binds.empty() ? "  binding rules: none of the rules bounded by a constant sits on its bound; their margins:"
                                  : "  binding rules: " + fmt::format("{}", fmt::join(binds, ", ")) + "; margins of the rules bounded by a constant:");
    for (const auto& mg : s.best->margins)
      lines.push_back(fmt::format("    {}: {}{} against {}, margin {:+.1f} %", mg.rule, formatNumber(mg.value), mg.unit.empty() ? "" : " " + mg.unit,
                                  formatNumber(mg.bound), mg.margin * 100));
  }
  if (s.best)
    for (const auto& sv : s.best->sensitivity) {
      std::string u = sv.unit.empty() ? "" : " " + sv.unit;
      lines.push_back(fmt::format("  over the tolerances, `{}` (worst/mean read at the nominal design): {}{} at the optimum", sv.objective,
                                  formatNumber(sv.nominal), u));
      for (const auto& l : sv.lines)
        lines.push_back(fmt::format("    {} -{}{}: {}{}   +{}{}: {}{}", l.target, formatNumber(l.amount), l.unit.empty() ? "" : " " + l.unit,
                                    formatNumber(l.minus), u, formatNumber(l.amount), l.unit.empty() ? "" : " " + l.unit, formatNumber(l.plus), u));
      lines.push_back(fmt::format("    over the tolerance box: {} .. {}{} ({:.1f} % of the value at the optimum)", formatNumber(sv.lo),
                                  formatNumber(sv.hi), u, 100 * (sv.hi - sv.lo) / std::max(std::fabs(sv.nominal), 1e-300)));
      if (sv.failed > 0)
        lines.push_back(fmt::format("  warning: `{}` gave no number at {} of its evaluations over the box (a failed scene); the range "
                                    "covers the others",
                                    sv.objective, sv.failed));
      if (sv.singular())
        lines.push_back(fmt::format("  warning: `{}` changes by more than its own value over the tolerance box: the optimum sits on a "
                                    "singularity of the model, and a manufactured gearbox will not show it",
                                    sv.objective));
    }
  if (!s.rankCheck.empty()) lines.push_back("  ranking: " + s.rankCheck);
  if (s.termNames.size() == 2) {
    lines.push_back(fmt::format("  Pareto front of ({}, {}) relative to the baseline, {} points:", s.termNames[0], s.termNames[1], s.pareto.size()));
    size_t step = std::max<size_t>(1, s.pareto.size() / 12);
    for (size_t i = 0; i < s.pareto.size(); i += step) lines.push_back(fmt::format("    {:.4f}  {:.4f}", s.pareto[i].first, s.pareto[i].second));
  }
  if (files)
    for (const auto& f : s.files) lines.push_back("  wrote " + f);
  return lines;
}

std::string optimisationTiming(const OptimisationSummary& s) {
  return fmt::format("timing: optimisation {:.2f} s wall with --jobs {}", s.wallSeconds, s.jobs);
}

std::string optimisationJson(const OptimisationSummary& s) {
  std::string json = fmt::format(R"({{"candidates": {}, "infeasible": {}, "evaluations": {}, "scene_rtol": {}, )", s.candidates, s.infeasible,
                                 s.evaluations, jsonNumber(s.sceneRtol));
  if (s.best) {
    const auto& best = *s.best;
    json += fmt::format(R"("objective": {}, "terms": {{)", jsonNumber(best.objective));
    for (size_t t = 0; t < s.termNames.size() && t < best.terms.size(); ++t) {
      double rel = best.terms[t] / s.baselineTerms[t];
      json += fmt::format("{}\"{}\": {{\"value\": {}, \"baseline\": {}, \"relative\": {}}}", t ? ", " : "", diag::jsonEscape(s.termNames[t]),
                          jsonNumber(best.terms[t]), jsonNumber(s.baselineTerms[t]), jsonNumber(rel));
    }
    json += "}, \"margins\": [";
    for (size_t i = 0; i < best.margins.size(); ++i)
      json += fmt::format("{}{{\"rule\": \"{}\", \"margin\": {}, \"binds\": {}}}", i ? ", " : "", diag::jsonEscape(best.margins[i].rule),
                          jsonNumber(best.margins[i].margin),
                          best.margins[i].margin <= 1e-3 ? "true" : "false");
    json += "], \"sensitivity\": [";
    for (size_t i = 0; i < best.sensitivity.size(); ++i) {
      const auto& sv = best.sensitivity[i];
      auto num = jsonNumber;
      json += fmt::format("{}{{\"objective\": \"{}\", \"unit\": \"{}\", \"nominal\": {}, \"box\": [{}, {}], \"singular\": {}, \"failed\": {}, "
                          "\"tolerances\": [",
                          i ? ", " : "", diag::jsonEscape(sv.objective), diag::jsonEscape(sv.unit), num(sv.nominal), num(sv.lo), num(sv.hi), sv.singular() ? "true" : "false", sv.failed);
      for (size_t j = 0; j < sv.lines.size(); ++j)
        json += fmt::format("{}{{\"target\": \"{}\", \"amount\": {}, \"unit\": \"{}\", \"minus\": {}, \"plus\": {}}}", j ? ", " : "",
                            diag::jsonEscape(sv.lines[j].target), num(sv.lines[j].amount), diag::jsonEscape(sv.lines[j].unit), num(sv.lines[j].minus), num(sv.lines[j].plus));
      json += "]}";
    }
    json += "], ";
  }
  json += fmt::format(R"("rank_check": "{}", "pareto": [)", diag::jsonEscape(s.rankCheck));
  for (size_t i = 0; i < s.pareto.size(); ++i) json += fmt::format("{}[{}, {}]", i ? ", " : "", jsonNumber(s.pareto[i].first), jsonNumber(s.pareto[i].second));
  json += "]}";
  return json;
}

} // namespace gbx::rt
