#include "report/Report.h"

#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"

namespace gbx::rt {

std::string formatNumber(double v) {
  if (!std::isfinite(v)) return "n/a";
  double a = std::fabs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e7)) return fmt::format("{:.4e}", v);
  std::string s = fmt::format("{:.4f}", v);
  return s == "-0.0000" ? "0.0000" : s;
}

namespace {

std::string ratioText(const Rational& r) { return formatNumber(r.toDouble()) + " (" + r.str() + ")"; }

std::string count(double x) { return fmt::format("{:.0f}", x); }

std::vector<std::string> header(const GearboxReport& g) {
  std::vector<std::string> h = {"rank"};
  if (!g.rows.empty()) {
    for (const auto& [n, _] : g.rows[0].teeth) h.push_back(n);
    for (const auto& [n, _] : g.rows[0].choices) h.push_back(n);
  }
  h.push_back("ratio");
  for (const auto& c : g.columns) h.push_back(c.unit.empty() ? c.name : c.name + " [" + c.unit + "]");
  return h;
}

std::vector<std::string> cells(const GearboxReport& g, const DesignRow& r) {
  std::vector<std::string> v = {std::to_string(r.rank) + (r.undecided ? "?" : "")};
  for (const auto& [_, z] : r.teeth) v.push_back(std::to_string(z));
  for (const auto& [_, c] : r.choices) v.push_back(c);
  v.push_back(ratioText(r.ratio));
  for (const auto& c : r.cells) v.push_back(c.text);
  (void)g;
  return v;
}

} // namespace

std::string renderText(const std::vector<GearboxReport>& reports) {
  std::string o;
  for (const auto& g : reports) {
    o += fmt::format("gearbox {}: {} design{}", g.name, g.count, g.count == 1 ? "" : "s");
    if (g.undecided) o += fmt::format(" ({} undecided)", g.undecided);
    if (g.count > g.rows.size()) o += fmt::format(", best {} shown", g.rows.size());
    o += "\n";
    if (!g.window.empty()) o += "  ratio window " + g.window + "\n";
    if (!g.rows.empty()) {
      auto h = header(g);
      std::vector<std::vector<std::string>> table = {h};
      for (const auto& r : g.rows) table.push_back(cells(g, r));
      std::vector<size_t> w(h.size(), 0);
      for (const auto& row : table)
        for (size_t i = 0; i < row.size() && i < w.size(); ++i) w[i] = std::max(w[i], row[i].size());
      for (const auto& row : table) {
        std::string line = " ";
        for (size_t i = 0; i < row.size(); ++i) line += " " + fmt::format("{:>{}}", row[i], w[i]);
        o += line + "\n";
      }
    }
    if (g.count == 0 || g.undecided) {
      o += "  elimination funnel:\n";
      for (const auto& f : g.funnel) {
        if (f.rule == "domain") {
          o += fmt::format("    stage {}: {} candidates\n", f.scope, count(-f.removed));
          continue;
        }
        o += fmt::format("    {}{}: {} of {} removed\n", f.scope.empty() ? "" : f.scope + ": ", f.rule, count(f.removed),
                         count(f.before));
      }
    }
    for (const auto& c : g.columns)
      if (!c.exact) o += "  note: intervals of `" + c.name + "` are enclosures (interval arithmetic), not exact images\n";
    for (const auto& n : g.notes) o += "  note: " + n + "\n";
    if (g.undecided) o += "  ? = feasibility undecided at the freedom resolution (kept, not proven)\n";
  }
  return o;
}

std::string renderJson(const std::vector<GearboxReport>& reports) {
  using diag::jsonEscape;
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("null"); };
  std::string o = "{\"gearboxes\": [";
  for (size_t gi = 0; gi < reports.size(); ++gi) {
    const auto& g = reports[gi];
    o += gi ? ",\n" : "\n";
    o += fmt::format("  {{\"name\": \"{}\", \"count\": {}, \"undecided\": {}, \"window\": \"{}\",\n   \"candidates\": [",
                     jsonEscape(g.name), g.count, g.undecided, jsonEscape(g.window));
    for (size_t ri = 0; ri < g.rows.size(); ++ri) {
      const auto& r = g.rows[ri];
      o += ri ? ",\n    " : "\n    ";
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
      o += fmt::format(", \"ratio\": {}, \"ratio_exact\": \"{}\", \"undecided\": {}, \"values\": {{", num(r.ratio.toDouble()),
                       r.ratio.str(), r.undecided ? "true" : "false");
      for (size_t i = 0; i < r.cells.size() && i < g.columns.size(); ++i) {
        const Cell& c = r.cells[i];
        std::string v = !c.valid ? "null" : c.lo == c.hi ? num(c.lo) : fmt::format("[{}, {}]", num(c.lo), num(c.hi));
        o += fmt::format("{}\"{}\": {}", i ? ", " : "", jsonEscape(g.columns[i].name), v);
      }
      o += "}";
      bool anyFeasible = false;
      for (const auto& c : r.cells) anyFeasible = anyFeasible || c.feasible;
      if (anyFeasible) {
        o += ", \"feasible\": {";
        bool first = true;
        for (size_t i = 0; i < r.cells.size() && i < g.columns.size(); ++i) {
          if (!r.cells[i].feasible) continue;
          o += fmt::format("{}\"{}\": [{}, {}]", first ? "" : ", ", jsonEscape(g.columns[i].name), num(r.cells[i].flo), num(r.cells[i].fhi));
          first = false;
        }
        o += "}";
      }
      o += "}";
    }
    o += g.rows.empty() ? "],\n" : "\n   ],\n";
    o += "   \"columns\": [";
    for (size_t i = 0; i < g.columns.size(); ++i)
      o += fmt::format("{}{{\"name\": \"{}\", \"unit\": \"SI\", \"intervals\": \"{}\"}}", i ? ", " : "",
                       jsonEscape(g.columns[i].name), g.columns[i].exact ? "exact" : "enclosure");
    o += "],\n   \"funnel\": [";
    for (size_t i = 0; i < g.funnel.size(); ++i) {
      const auto& f = g.funnel[i];
      if (f.rule == "domain")
        o += fmt::format("{}\n    {{\"scope\": \"{}\", \"rule\": \"domain\", \"candidates\": {}}}", i ? "," : "", jsonEscape(f.scope),
                         count(-f.removed));
      else
        o += fmt::format("{}\n    {{\"scope\": \"{}\", \"rule\": \"{}\", \"before\": {}, \"removed\": {}}}", i ? "," : "",
                         jsonEscape(f.scope), jsonEscape(f.rule), count(f.before), count(f.removed));
    }
    o += g.funnel.empty() ? "]," : "\n   ],";
    o += "\n   \"scenes\": {}, \"modifications\": {}, \"studies\": {}}";
  }
  o += "\n]}\n";
  return o;
}

std::string renderCsv(const std::vector<GearboxReport>& reports) {
  std::string o;
  for (const auto& g : reports) {
    auto h = header(g);
    o += "gearbox";
    for (const auto& x : h) o += "," + x;
    o += ",ratio_exact\n";
    for (const auto& r : g.rows) {
      o += g.name + "," + std::to_string(r.rank);
      for (const auto& [_, z] : r.teeth) o += "," + std::to_string(z);
      for (const auto& [_, c] : r.choices) o += "," + c;
      o += "," + fmt::format("{}", r.ratio.toDouble());
      for (const auto& c : r.cells)
        o += "," + (!c.valid ? std::string() : c.lo == c.hi ? fmt::format("{}", c.lo) : fmt::format("\"[{}, {}]\"", c.lo, c.hi));
      o += "," + r.ratio.str() + "\n";
    }
  }
  return o;
}

std::string renderMarkdown(const std::vector<GearboxReport>& reports, bool html) {
  std::string o = html ? "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>gbxc report</title></head><body>\n" : "";
  for (const auto& g : reports) {
    auto h = header(g);
    if (html) {
      o += fmt::format("<h2>{}</h2>\n<p>{} design{}</p>\n<table>\n<tr>", g.name, g.count, g.count == 1 ? "" : "s");
      for (const auto& x : h) o += "<th>" + x + "</th>";
      o += "</tr>\n";
      for (const auto& r : g.rows) {
        o += "<tr>";
        for (const auto& c : cells(g, r)) o += "<td>" + c + "</td>";
        o += "</tr>\n";
      }
      o += "</table>\n";
    } else {
      o += fmt::format("## {}\n\n{} design{}\n\n|", g.name, g.count, g.count == 1 ? "" : "s");
      for (const auto& x : h) o += " " + x + " |";
      o += "\n|";
      for (size_t i = 0; i < h.size(); ++i) o += " ---: |";
      o += "\n";
      for (const auto& r : g.rows) {
        o += "|";
        for (const auto& c : cells(g, r)) o += " " + c + " |";
        o += "\n";
      }
      o += "\n";
    }
  }
  if (html) o += "</body></html>\n";
  return o;
}

} // namespace gbx::rt
