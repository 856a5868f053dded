// CSV: every number in the unit its header names (the display unit of the text report),
// an interval as `_lo` and `_hi` columns, one tidy table per kind of result.
#include <algorithm>
#include <cmath>
#include <functional>
#include <variant>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "report/MonteCarlo.h"
#include "report/Numbers.h"
#include "report/Ratings.h"
#include "report/Report.h"
#include "report/Shafts.h"

namespace gbx::rt {

namespace {

std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string number(double v) { return csvNumber(v); }

std::string withUnit(const std::string& name, const std::string& unit) { return unit.empty() ? name : name + " [" + unit + "]"; }

std::string row(const std::vector<std::string>& cells) {
  std::string o;
  for (size_t i = 0; i < cells.size(); ++i) o += (i ? "," : "") + field(cells[i]);
  return o + "\n";
}

// Columns that show an interval in some row get two CSV columns.
std::vector<bool> intervalColumns(const GearboxReport& g) {
  std::vector<bool> v(g.columns.size(), false);
  if (g.source) return v;  // made rows are points
  for (const auto& r : g.rows)
    for (size_t i = 0; i < r.cells.size() && i < v.size(); ++i) v[i] = v[i] || (r.cells[i].valid && r.cells[i].lo != r.cells[i].hi);
  return v;
}

// Columns with a range beside their value in some row (`report { ranges; }`): two more.
std::vector<bool> rangedColumns(const GearboxReport& g) {
  std::vector<bool> v(g.columns.size(), false);
  for (const auto& r : g.rows)
    for (size_t i = 0; i < r.cells.size() && i < v.size(); ++i) v[i] = v[i] || r.cells[i].ranged;
  return v;
}

// A gearbox's design-table header: rank, its tooth counts and choices, the ratio, its columns.
std::vector<std::string> designHeader(const GearboxReport& g, const std::vector<bool>& wide, const std::vector<bool>& ranged) {
  std::vector<std::string> h = {"gearbox", "rank"};
  if (!g.rows.empty()) {
    for (const auto& [n, _] : g.rows[0].teeth) h.push_back(n);
    for (size_t i = 0; i < g.rows[0].choices.size(); ++i)
      h.push_back(withUnit(g.rows[0].choices[i].first, i < g.rows[0].choiceValues.size() ? g.rows[0].choiceValues[i].unit : ""));
  }
  h.push_back("ratio");
  for (size_t i = 0; i < g.columns.size(); ++i) {
    const auto& c = g.columns[i];
    if (wide[i]) {
      h.push_back(withUnit(c.name + "_lo", c.unit));
      h.push_back(withUnit(c.name + "_hi", c.unit));
    } else {
      h.push_back(withUnit(c.name, c.unit));
    }
    if (ranged[i]) {
      h.push_back(withUnit(c.name + "_lo", c.unit));
      h.push_back(withUnit(c.name + "_hi", c.unit));
    }
  }
  h.push_back("ratio_exact");
  return h;
}

// One gearbox's rows, appended to `o` in its own header's order.
void designRows(const GearboxReport& g, const std::vector<bool>& wide, const std::vector<bool>& ranged, std::string& o,
                const std::function<void(std::string&)>& rowDone, bool reserveAll = true) {
  const std::string name = field(g.name);
  auto num = [&](double v) {
    if (std::isfinite(v)) fmt::format_to(std::back_inserter(o), FMT_COMPILE("{}"), v);
  };
  // A plain number is written in place; one in a unit is the shortest that reads back.
  auto inUnit = [&](double si, const std::string& unit, double scale, double offset) {
    if (unit.empty() && scale == 1.0 && offset == 0.0)
      num(si);
    else
      o += csvNumber(si, unit, scale, offset);
  };
  auto integer = [&](long long v) {
    fmt::format_int f(v);
    o.append(f.data(), f.size());
  };
  auto exact = [&](const Rational& q) {
    const units::i128 lim = units::i128{1} << 62;
    if (q.num() >= lim || q.num() <= -lim || q.den() >= lim) {
      o += q.str();
      return;
    }
    integer(static_cast<long long>(q.num()));
    if (q.den() == 1) return;
    o += '/';
    integer(static_cast<long long>(q.den()));
  };
  size_t rowsStart = o.size();
  forEachRow(g, [&](const DesignRow& r) {
    // A long listing: room for all of it at the size of its first row, once.
    if (reserveAll && r.rank == 2 && g.source)
      o.reserve(o.size() + (o.size() - rowsStart) * (g.source->size() + 16) * 21 / 20);
    o += name;
    o += ',';
    integer(r.rank);
    for (const auto& [_, z] : r.teeth) {
      o += ',';
      integer(z);
    }
    for (const auto& c : r.choiceValues) {
      o += ',';
      if (std::isfinite(c.si)) inUnit(c.si, c.unit, c.scale, 0.0);
    }
    o += ',';
    num(r.ratio.toDouble());
    for (size_t i = 0; i < r.cells.size(); ++i) {
      const Cell& c = r.cells[i];
      const std::string& un = g.columns[i].unit;
      double sc = g.columns[i].scale, off = g.columns[i].offset;
      o += ',';
      if (c.valid) inUnit(c.lo, un, sc, off);
      if (wide[i]) {
        o += ',';
        if (c.valid) inUnit(c.hi, un, sc, off);
      }
      if (ranged[i]) {
        o += ',';
        if (c.ranged) inUnit(c.rlo, un, sc, off);
        o += ',';
        if (c.ranged) inUnit(c.rhi, un, sc, off);
      }
    }
    o += ',';
    exact(r.ratio);
    o += '\n';
    if (rowDone) rowDone(o);
  });
}

// One table for every gearbox: the union of their headers, in the order they first appear
// (the exact ratio last), with a gearbox's row empty in the columns it does not have.
// With `sink`, the table goes to it a piece at a time (about a megabyte), as its rows are
// made, and the string returned is empty: a listing of a million designs is never held whole.
std::string designs(const std::vector<GearboxReport>& reports, const CsvSink* sink = nullptr) {
  constexpr size_t piece = size_t{1} << 20;
  std::vector<std::vector<std::string>> heads;
  std::vector<std::string> all;
  for (const auto& g : reports) {
    heads.push_back(designHeader(g, intervalColumns(g), rangedColumns(g)));
    // Each header ends with the exact ratio, which goes last.
    for (auto h = heads.back().begin(); h + 1 < heads.back().end(); ++h)
      if (std::find(all.begin(), all.end(), *h) == all.end()) all.push_back(*h);
  }
  if (reports.empty()) return "";
  all.push_back(heads.back().back());
  std::string o = row(all);
  auto pour = [&](std::string& text) {
    if (sink && text.size() >= piece) {
      (*sink)(text);
      text.clear();
    }
  };
  for (size_t k = 0; k < reports.size(); ++k) {
    const auto& g = reports[k];
    auto wide = intervalColumns(g), ranged = rangedColumns(g);
    if (heads[k] == all) {
      if (sink)
        designRows(g, wide, ranged, o, pour, false);
      else
        designRows(g, wide, ranged, o, nullptr);
      continue;
    }
    // Each field to its place in the whole header (no field holds a comma: names are
    // identifiers, values numbers or a ratio).
    std::vector<size_t> at;
    for (const auto& h : heads[k]) at.push_back(static_cast<size_t>(std::find(all.begin(), all.end(), h) - all.begin()));
    std::string line;
    std::vector<std::string> cells(all.size());
    designRows(g, wide, ranged, line, [&](std::string& l) {
      for (auto& c : cells) c.clear();
      size_t from = 0;
      for (size_t f = 0; f < at.size(); ++f) {
        size_t to = l.find_first_of(",\n", from);
        cells[at[f]].assign(l, from, to - from);
        from = to + 1;
      }
      o += row(cells);
      l.clear();
      pour(o);
    });
  }
  if (sink) {
    (*sink)(o);
    o.clear();
  }
  return o;
}

std::string scenes(const std::vector<GearboxReport>& reports) {
  std::string o = row({"gearbox", "scene", "target", "output", "value", "unit", "method", "rtol", "error_estimate", "steady_state"});
  bool any = false;
  for (const auto& g : reports)
    for (const auto& s : g.scenes)
      for (const auto& x : s.outputs) {
        any = true;
        o += row({g.name, s.name, s.target, x.key, number(x.shown), x.unit, s.method, s.eigen ? "" : number(s.rtol),
                  s.errorEstimate >= 0 ? number(s.errorEstimate) : "", s.eigen ? "" : s.steady});
      }
  return any ? o : "";
}

std::string spectra(const std::vector<GearboxReport>& reports) {
  std::string o = row({"gearbox", "scene", "spectrum", "frequency [Hz]", "amplitude", "unit", "harmonic"});
  bool any = false;
  for (const auto& g : reports)
    for (const auto& s : g.scenes)
      for (const auto& sp : s.spectra)
        for (const auto& p : sp.peaks) {
          any = true;
          o += row({g.name, s.name, sp.key, number(p.frequency), csvNumber(p.amplitude, sp.unit, sp.scale), sp.unit,
                    p.harmonic > 0 ? std::to_string(p.harmonic) : ""});
        }
  return any ? o : "";
}

// Each scene's plotted outputs sample by sample: a signal over time (x in s) or a spectrum
// (x in Hz), its values in their display unit (what the charts draw).
std::string signals(const std::vector<GearboxReport>& reports) {
  std::string o = row({"gearbox", "scene", "output", "x", "x_unit", "value", "unit"});
  bool any = false;
  for (const auto& g : reports)
    for (const auto& s : g.scenes)
      for (const auto& p : s.plots)
        for (size_t i = 0; i < p.x.size() && i < p.y.size(); ++i) {
          any = true;
          o += row({g.name, s.name, p.key, number(p.x[i]), p.spectrum ? "Hz" : "s", number(p.y[i]), p.unit});
        }
  return any ? o : "";
}

std::string sweeps(const std::vector<GearboxReport>& reports) {
  std::string o = row({"gearbox", "study", "swept", "x", "x_unit", "output", "value", "unit", "stability", "branch",
                       "line", "line_value", "line_unit"});
  bool any = false;
  for (const auto& g : reports)
    for (const auto& st : g.studies)
      if (const auto* s = std::get_if<SweepStudy>(&st.study))
        for (const auto& p : s->points)
          for (size_t i = 0; i < s->outputs.size() && i < p.y.size(); ++i) {
            any = true;
            o += row({g.name, s->name, s->target, csvNumber(p.x, s->unit.name, s->unit.scale, s->unit.offset),
                      s->unit.name, s->outputs[i].text,
                      csvNumber(p.y[i], s->outputs[i].unit.name, s->outputs[i].unit.scale, s->outputs[i].unit.offset),
                      s->outputs[i].unit.name, number(p.stability),
                      s->continuation == "arclength" ? std::to_string(p.branch) : "", s->seriesTarget,
                      s->seriesTarget.empty()
                          ? ""
                          : csvNumber(p.series, s->seriesUnit.name, s->seriesUnit.scale, s->seriesUnit.offset),
                      s->seriesUnit.name});
          }
  return any ? o : "";
}

std::string workPrecision(const std::vector<GearboxReport>& reports, bool timings) {
  std::vector<std::string> h = {"gearbox", "study", "scene", "harmonics", "method", "steady_state", "rtol", "error", "steps", "rhs_evaluations"};
  if (timings) h.push_back("cpu [ms]");
  std::string o = row(h);
  bool any = false;
  for (const auto& g : reports)
    for (const auto& st : g.studies)
      if (const auto* w = std::get_if<WorkPrecisionStudy>(&st.study))
        for (const auto& c : w->curves)
          for (const auto& r : c.runs) {
            any = true;
            std::vector<std::string> v = {g.name, w->name, w->scene, c.harmonics > 0 ? std::to_string(c.harmonics) : "", c.method, c.steady,
                                          number(r.rtol), r.ok ? number(r.error) : "", r.ok ? std::to_string(r.steps) : "",
                                          r.ok ? std::to_string(r.rhsEvaluations) : ""};
            if (timings) v.push_back(r.ok ? number(r.cpuSeconds * 1e3) : "");
            o += row(v);
          }
  return any ? o : "";
}

std::string modifications(const std::vector<GearboxReport>& reports) {
  // Each row in its target's unit: um for an amount, mm for a height or a width.
  std::string o = row({"gearbox", "stage", "target", "present", "value", "unit", "rule", "condition", "error"});
  bool any = false;
  for (const auto& g : reports)
    for (const auto& m : g.modifications)
      for (const auto& r : m.rows) {
        any = true;
        o += row({g.name, m.stage, r.target, r.present ? "yes" : "no", r.valid ? csvNumber(r.si, r.unit.name, r.unit.scale, r.unit.offset) : "",
                    r.unit.name, r.text, r.condition, r.error});
      }
  return any ? o : "";
}

// A tidy table of every gearbox's rows under one header; empty when no gearbox has any.
template <class RowsOf>
std::string tidy(const std::vector<std::string>& header, const std::vector<GearboxReport>& reports, RowsOf rowsOf) {
  std::string o = row(header);
  bool any = false;
  for (const auto& g : reports)
    for (const auto& v : rowsOf(g)) {
      any = true;
      o += row(v);
    }
  return any ? o : "";
}

using Rows = std::vector<std::vector<std::string>>;

std::string ratings(const std::vector<GearboxReport>& reports) {
  return tidy({"gearbox", "stage", "gear", "quantity", "unit", "value", "minimum", "method", "note"}, reports, [](const GearboxReport& g) {
    Rows out;
    for (const auto& r : g.ratings)
      for (auto& v : ratingCsvRows(g.name, r)) out.push_back(std::move(v));
    return out;
  });
}

std::string shafts(const std::vector<GearboxReport>& reports) {
  return tidy({"gearbox", "shaft", "item", "quantity", "unit", "value", "method"}, reports, [](const GearboxReport& g) {
    Rows out;
    for (const auto& sh : g.shafts)
      for (auto& v : shaftCsvRows(g.name, sh)) out.push_back(std::move(v));
    return out;
  });
}

std::string monteCarlo(const std::vector<GearboxReport>& reports) {
  return tidy({"gearbox", "quantity", "unit", "statistic", "value", "standard_error", "sample"}, reports,
              [](const GearboxReport& g) { return g.monteCarlo ? monteCarloCsvRows(g.name, *g.monteCarlo) : Rows{}; });
}

// Every sample of each gearbox that has them: its deviations and each quantity's value.
std::string samples(const std::vector<GearboxReport>& reports) {
  std::string o;
  for (const auto& g : reports) {
    if (!g.monteCarlo || g.monteCarlo->outputs.empty()) continue;
    o += row(sampleCsvHeader(*g.monteCarlo));
    for (const auto& v : sampleCsvRows(g.name, *g.monteCarlo)) o += row(v);
  }
  return o;
}

} // namespace

std::string renderCsv(const std::vector<GearboxReport>& reports, const RenderOptions&) { return designs(reports); }

namespace {

// Every table but the design table (which a million-row listing makes as it is written).
std::vector<TableFile> otherTables(const std::vector<GearboxReport>& reports, const RenderOptions& o) {
  std::vector<TableFile> out;
  auto add = [&](const char* name, std::string text) {
    if (!text.empty()) out.push_back({name, std::move(text)});
  };
  add("scenes.csv", scenes(reports));
  add("spectra.csv", spectra(reports));
  add("signals.csv", signals(reports));
  add("sweeps.csv", sweeps(reports));
  add("work_precision.csv", workPrecision(reports, o.timings));
  add("modifications.csv", modifications(reports));
  add("ratings.csv", ratings(reports));
  add("shafts.csv", shafts(reports));
  add("monte_carlo.csv", monteCarlo(reports));
  add("samples.csv", samples(reports));
  return out;
}

} // namespace

std::vector<TableFile> csvTables(const std::vector<GearboxReport>& reports, const RenderOptions& o) {
  std::vector<TableFile> out;
  if (std::string d = designs(reports); !d.empty()) out.push_back({"designs.csv", std::move(d)});
  for (auto& t : otherTables(reports, o)) out.push_back(std::move(t));
  return out;
}

void streamCsv(const std::vector<GearboxReport>& reports, const CsvSink& sink) { designs(reports, &sink); }

std::vector<std::string> csvOtherTables(const std::vector<GearboxReport>& reports, const RenderOptions& o) {
  std::vector<std::string> names;
  for (const auto& t : otherTables(reports, o)) names.push_back(t.name);
  return names;
}

} // namespace gbx::rt
