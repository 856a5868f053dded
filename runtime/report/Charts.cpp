#include "report/Charts.h"

#include <algorithm>
#include <cmath>
#include <cctype>

#include <fmt/format.h>

#include "report/Svg.h"

namespace gbx::rt {

namespace {

std::string fileSafe(const std::string& k) {
  std::string o;
  for (char c : k) o += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.') ? c : '_';
  while (!o.empty() && o.back() == '_') o.pop_back();
  return o;
}

std::string withUnit(const std::string& label, const std::string& unit) { return label + (unit.empty() ? "" : " [" + unit + "]"); }

void add(std::vector<ChartFile>& out, std::vector<std::string>& files, std::string name, const SvgChart& chart) {
  files.push_back(name);
  out.push_back({std::move(name), renderSvg(chart)});
}

void paretoChart(const std::string& gearbox, OptimisationSummary& s, std::vector<ChartFile>& out) {
  if (s.termNames.size() != 2) return;
  SvgChart c;
  c.title = fmt::format("{}: objectives relative to {}", gearbox, s.baseline);
  c.xLabel = "relative " + s.termNames[0];
  c.yLabel = "relative " + s.termNames[1];
  SvgSeries cloud{"feasible evaluations", {}, {}, true, false}, front{"Pareto front", {}, {}, true}, base{"baseline", {1.0}, {1.0}, true},
      weighted{"weighted optimum", {}, {}, true};
  for (const auto& p : s.cloud) {
    cloud.x.push_back(p.first);
    cloud.y.push_back(p.second);
  }
  for (const auto& p : s.pareto) {
    front.x.push_back(p.first);
    front.y.push_back(p.second);
  }
  if (s.best && s.best->terms.size() == 2) {
    weighted.x.push_back(s.best->terms[0] / s.baselineTerms[0]);
    weighted.y.push_back(s.best->terms[1] / s.baselineTerms[1]);
  }
  c.series = {cloud, front, base, weighted};
  add(out, s.files, fileSafe(gearbox) + ".pareto.svg", c);
}

// An axis in an engineering prefix of its SI unit (ms, µs, kHz) where the values are small
// or large, so that ticks read `0, 0.5, 1, 1.5 ms`, not `0, 5.0e-04, 0.001`.
struct Prefixed {
  double scale = 1;  // SI per shown unit
  std::string unit;
};
Prefixed timeAxis(double top) {
  if (top < 1e-3) return {1e-6, "us"};
  if (top < 1) return {1e-3, "ms"};
  return {1, "s"};
}
Prefixed frequencyAxis(double top) { return top >= 1e4 ? Prefixed{1e3, "kHz"} : Prefixed{1, "Hz"}; }

// `mesh_force` as `mesh force`.
std::string words(std::string s) {
  for (auto& c : s)
    if (c == '_') c = ' ';
  return s;
}

void sceneCharts(const std::string& gearbox, SceneReport& sc, std::vector<ChartFile>& out) {
  for (const auto& p : sc.plots) {
    SvgChart chart;
    std::string where = sc.target.empty() ? "the gearbox" : "stage " + sc.target;
    chart.title = p.spectrum ? fmt::format("Spectrum of the {}, scene {} on {} ({})", words(p.signal), sc.name, where, gearbox)
                             : fmt::format("{} over time, scene {} on {} ({})", words(p.signal), sc.name, where, gearbox);
    if (!p.spectrum && !chart.title.empty()) chart.title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(chart.title[0])));
    double top = 0;
    for (double x : p.x) top = std::max(top, std::fabs(x));
    Prefixed axis = p.spectrum ? frequencyAxis(top) : timeAxis(top);
    std::vector<double> xs;
    for (double x : p.x) xs.push_back(x / axis.scale);
    chart.xLabel = fmt::format("{} [{}]", p.spectrum ? "frequency" : "time", axis.unit);
    chart.yLabel = withUnit(p.spectrum ? "amplitude" : words(p.signal), p.unit);
    SvgSeries series{"", xs, p.y};
    series.bars = p.spectrum;  // a spectrum is lines at its harmonics, not a curve between them
    chart.series.push_back(series);
    // A spectrum reads by mesh orders: ticks at 1x, 2x, … the mesh frequency.
    if (p.spectrum && p.meshFrequency > 0) {
      chart.xLabel = fmt::format("frequency [{}], ticks at mesh orders ({:.2f} Hz)", axis.unit, p.meshFrequency);
      // Every order up to the tenth; beyond it (a listed peak far up) every second, fifth, …
      double last = p.x.empty() ? 10.5 * p.meshFrequency : p.x.back();
      int orders = std::max(10, static_cast<int>(last / p.meshFrequency));
      int step = orders <= 12 ? 1 : orders <= 24 ? 2 : orders <= 60 ? 5 : 10;
      for (int k = step == 1 ? 1 : step; k <= orders; k += step)
        chart.xTicks.emplace_back(k * p.meshFrequency / axis.scale, fmt::format("{}x", k));
    }
    add(out, sc.files, fileSafe(gearbox + "." + sc.name + "." + p.key) + ".svg", chart);
  }
}

// A sweep with a set of lines (`Y in {…}`): one line of output i per value of Y, in order.
void seriesLines(const SweepStudy& s, size_t i, SvgChart& c) {
  for (size_t k = 0; k < s.points.size();) {
    SvgSeries line;
    line.colour = static_cast<int>(c.series.size());
    double at = s.points[k].series;
    line.label = fmt::format("{} = {:.6g}{}", s.seriesTarget, s.seriesUnit.shown(at),
                             s.seriesUnit.name.empty() ? "" : " " + s.seriesUnit.name);
    for (; k < s.points.size() && s.points[k].series == at; ++k) {
      line.x.push_back(s.unit.shown(s.points[k].x));
      line.y.push_back(s.outputs[i].unit.shown(s.points[k].y[i]));
    }
    c.series.push_back(std::move(line));
  }
}

void sweepCharts(const std::string& gearbox, const SweepStudy& s, std::vector<std::string>& files, std::vector<ChartFile>& out) {
  if (!s.plot) return;
  // One chart per output: outputs of different units do not share an axis.
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    SvgChart c;
    c.title = fmt::format("{}: {} against {}", s.name, s.outputs[i].text, s.target);
    c.xLabel = withUnit(s.target, s.unit.name);
    c.yLabel = withUnit(s.outputs[i].text, s.outputs[i].unit.name);
    if (!s.seriesTarget.empty()) {
      seriesLines(s, i, c);
      add(out, files,
          fileSafe(gearbox) + "." + s.name + (s.outputs.size() > 1 ? fmt::format(".{}", i + 1) : "") + ".svg", c);
      continue;
    }
    // A scene's response: stable parts solid, unstable parts dashed, one colour; each part
    // shares its end point with the next so the curve stays whole.
    bool labelledStable = false, labelledUnstable = false;
    for (size_t k = 0; k < s.points.size();) {
      // This output's own scene decides (a sweep may read several).
      auto unstable = [&](size_t j) {
        const auto& p = s.points[j];
        if (i < p.unstable.size()) return static_cast<bool>(p.unstable[i]);
        return std::isfinite(p.stability) && p.stability >= 1.0;
      };
      bool u = unstable(k);
      SvgSeries part;
      part.colour = 0;
      part.dashed = u;
      size_t j = k;
      // A part ends where the stability changes or a gap begins: no line is drawn across a
      // stretch the continuation did not follow.
      for (; j < s.points.size() && unstable(j) == u && (j == k || !s.points[j].afterGap); ++j) {
        part.x.push_back(s.unit.shown(s.points[j].x));
        part.y.push_back(s.outputs[i].unit.shown(s.points[j].y[i]));
      }
      if (j < s.points.size() && !s.points[j].afterGap) {
        part.x.push_back(s.unit.shown(s.points[j].x));
        part.y.push_back(s.outputs[i].unit.shown(s.points[j].y[i]));
      }
      if (s.scene && !u && !labelledStable) {
        part.label = s.outputs[i].text + ", stable";
        labelledStable = true;
      }
      if (u && !labelledUnstable) {
        part.label = "unstable (dashed)";
        labelledUnstable = true;
      }
      if (!s.scene) part.label = s.outputs[i].text;
      c.series.push_back(std::move(part));
      k = j;
    }
    for (const auto& [x, label] : s.marks) c.xMarks.emplace_back(s.unit.shown(x), label);
    for (double f : s.folds) c.xMarks.emplace_back(s.unit.shown(f), "jump");
    if (std::isfinite(s.nominal)) c.xMarks.emplace_back(s.unit.shown(s.nominal), "design");
    add(out, files, fileSafe(gearbox) + "." + s.name + (s.outputs.size() > 1 ? fmt::format(".{}", i + 1) : "") + ".svg", c);
  }
}

void workPrecisionChart(const std::string& gearbox, const WorkPrecisionStudy& s, std::vector<std::string>& files, std::vector<ChartFile>& out) {
  SvgChart chart;
  chart.title = fmt::format("work-precision of scene {}", s.scene);
  chart.xLabel = "CPU time [s]";
  chart.yLabel = "relative error";
  chart.logX = chart.logY = true;
  for (const auto& c : s.curves) {
    SvgSeries series;
    series.label = fmt::format("{}, {}{}", c.method, c.steady, c.harmonics > 0 ? fmt::format(", {} harmonics", c.harmonics) : "");
    series.markers = true;
    for (const auto& run : c.runs) {
      if (!run.ok) continue;
      series.x.push_back(std::max(run.cpuSeconds, 1e-6));
      series.y.push_back(std::max(run.error, 1e-16));
    }
    chart.series.push_back(series);
  }
  add(out, files, fileSafe(gearbox) + "." + s.name + ".svg", chart);
}

// A shaft's deflection line and bending-moment diagram (its bearings as a second series).
void shaftCharts(const std::string& gearbox, ShaftReport& sh, std::vector<ChartFile>& out) {
  if (sh.lineX.empty()) return;
  std::vector<double> x, d, m;
  for (size_t i = 0; i < sh.lineX.size(); ++i) {
    x.push_back(sh.lineX[i] * 1e3);
    d.push_back(sh.lineDeflection[i] * 1e6);
    m.push_back(sh.lineMoment[i]);
  }
  SvgSeries bearings{"bearings", {}, {}};
  bearings.markers = true;
  bearings.line = false;
  for (const auto& b : sh.bearings) {
    bearings.x.push_back(b.x * 1e3);
    bearings.y.push_back(0);
  }
  SvgChart c;
  c.title = fmt::format("{} — shaft {}: deflection along the shaft (design 1)", gearbox, sh.name);
  c.xLabel = "position from the left end [mm]";
  c.yLabel = "radial deflection [um]";
  c.series = {{"deflection", x, d}, bearings};
  add(out, sh.files, fileSafe(gearbox + "." + sh.name) + ".deflection.svg", c);
  SvgChart mc;
  mc.title = fmt::format("{} — shaft {}: bending moment along the shaft (design 1)", gearbox, sh.name);
  mc.xLabel = c.xLabel;
  mc.yLabel = "bending moment [N m]";
  mc.series = {{"bending moment", x, m}, bearings};
  add(out, sh.files, fileSafe(gearbox + "." + sh.name) + ".bending_moment.svg", mc);
}

// K_Hbeta by contact analysis: the line load across the face against its mean.
void faceLoadChart(const std::string& gearbox, RatingReport& r, std::vector<ChartFile>& out) {
  if (r.lineLoad.empty()) return;
  SvgChart c;
  std::string where = r.stage + (r.mesh.empty() ? "" : "." + r.mesh);
  c.title = fmt::format("{} — stage {}: line load across the face (contact analysis)", gearbox, where);
  c.xLabel = "position across the face from the coupling end [mm]";
  c.yLabel = "line load, mean over a mesh period [N/mm]";
  SvgSeries load{"line load", r.facePosition, r.lineLoad};
  SvgSeries mean{"mean F/b", {r.facePosition.front(), r.facePosition.back()}, {r.meanLineLoad, r.meanLineLoad}};
  c.series = {load, mean};
  add(out, r.files, fileSafe(gearbox + "." + where) + ".line_load.svg", c);
}

// Scuffing and micropitting: the contact temperature and the film thickness along the path
// of contact, A to E (Gamma 0 at the pitch point).
void pathCharts(const std::string& gearbox, RatingReport& r, std::vector<ChartFile>& out) {
  if (r.pathGamma.empty()) return;
  std::string where = r.stage + (r.mesh.empty() ? "" : "." + r.mesh);
  const double a = r.pathGamma.front(), e = r.pathGamma.back();
  SvgChart t;
  t.title = fmt::format("{} — stage {}: contact temperature along the path of contact", gearbox, where);
  t.xLabel = "Gamma on the path of contact (0: pitch point)";
  t.yLabel = "temperature [degC]";
  t.series = {{"contact temperature theta_B", r.pathGamma, r.contactTemperature},
              {"bulk temperature theta_M", {a, e}, {r.bulkTemperature, r.bulkTemperature}}};
  if (r.scuffing) t.series.push_back({"scuffing temperature theta_S", {a, e}, {r.scuffingTemperature, r.scuffingTemperature}});
  add(out, r.files, fileSafe(gearbox + "." + where) + ".contact_temperature.svg", t);
  if (r.filmThickness.empty()) return;
  SvgChart f;
  f.title = fmt::format("{} — stage {}: lubricant film thickness along the path of contact", gearbox, where);
  f.xLabel = t.xLabel;
  f.yLabel = "film thickness [um]";
  f.series = {{"film thickness h", r.pathGamma, r.filmThickness}};
  add(out, r.files, fileSafe(gearbox + "." + where) + ".film_thickness.svg", f);
}

// Each sampled quantity's histogram (the bins' outline), its mean and quantiles marked.
void monteCarloCharts(const std::string& gearbox, MonteCarloReport& r, std::vector<ChartFile>& out) {
  for (const auto& o : r.outputs) {
    if (o.counts.empty()) continue;
    SvgChart c;
    c.title = fmt::format("{}: {} over {} samples", gearbox, o.quantity, r.samples);
    c.xLabel = withUnit(o.quantity, o.unit.name);
    c.yLabel = "samples per bin";
    SvgSeries bars{"samples", {}, {}, false, true};
    bars.x.push_back(o.unit.shown(o.edges.front()));
    bars.y.push_back(0);
    for (size_t b = 0; b < o.counts.size(); ++b) {
      double y = static_cast<double>(o.counts[b]);
      for (double x : {o.edges[b], o.edges[b + 1]}) {
        bars.x.push_back(o.unit.shown(x));
        bars.y.push_back(y);
      }
    }
    bars.x.push_back(o.unit.shown(o.edges.back()));
    bars.y.push_back(0);
    c.series = {bars};
    c.xMarks.push_back({o.unit.shown(o.nominal), "nominal"});
    c.xMarks.push_back({o.unit.shown(o.mean), "mean"});
    for (const auto& q : o.quantiles) c.xMarks.push_back({o.unit.shown(q.value), q.p == 0.5 ? "median" : fmt::format("q {:g}", q.p)});
    add(out, r.files, fmt::format("{}.monte_carlo.{}.svg", fileSafe(gearbox), fileSafe(o.quantity)), c);
  }
}

} // namespace

std::vector<ChartFile> drawCharts(std::vector<GearboxReport>& reports) {
  std::vector<ChartFile> out;
  for (auto& g : reports) {
    if (g.optimisation) paretoChart(g.name, *g.optimisation, out);
    if (g.monteCarlo) monteCarloCharts(g.name, *g.monteCarlo, out);
    for (auto& sc : g.scenes) sceneCharts(g.name, sc, out);
    for (auto& r : g.ratings) {
      faceLoadChart(g.name, r, out);
      pathCharts(g.name, r, out);
    }
    for (auto& sh : g.shafts) shaftCharts(g.name, sh, out);
    for (auto& st : g.studies) {
      if (const auto* s = std::get_if<SweepStudy>(&st.study)) sweepCharts(g.name, *s, st.files, out);
      else workPrecisionChart(g.name, std::get<WorkPrecisionStudy>(st.study), st.files, out);
    }
  }
  return out;
}

} // namespace gbx::rt
