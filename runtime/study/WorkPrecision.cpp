#include "study/WorkPrecision.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "dynamics/Scene.h"
#include "report/Svg.h"

namespace gbx::rt {

StudyReport workPrecision(const Model& m, const Assignment& design, const ir::Study& study, const ir::Scene& scene,
                          const std::string& outDir, const std::string& filePrefix, bool timings) {
  StudyReport r;
  r.name = study.name;
  r.kind = "work_precision";
  std::vector<double> rtols;
  std::vector<int> harmonics;
  std::vector<cat::Method> methods;
  for (const auto& s : study.settings) {
    if (s.key == Q::Rtol)
      for (const auto& v : s.members) rtols.push_back(v.toDouble());
    if (s.key == Q::Harmonics && s.lo && s.hi)
      for (long h = static_cast<long>(s.lo->toDouble()); h <= static_cast<long>(s.hi->toDouble()); ++h) harmonics.push_back(static_cast<int>(h));
    if (s.key == Q::Harmonics)
      for (const auto& v : s.members) harmonics.push_back(static_cast<int>(v.toDouble()));
    if (s.key == Q::Methods)
      for (int c : s.choices) methods.push_back(cat::kMethods[static_cast<size_t>(c)].id);
  }
  if (rtols.empty()) rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::sort(rtols.begin(), rtols.end(), std::greater<>());
  bool varying = scene.findEffect(cat::Effect::VaryingStiffness);
  if (harmonics.empty() || !varying) harmonics = {0};
  if (methods.empty()) methods = {scene.method()};
  r.header = {"harmonics", "method", "rtol", "error", "steps", "RHS evaluations"};
  if (timings) r.header.push_back("CPU ms");
  std::string json = "{\"scene\": \"" + scene.name + "\", ";
  std::string key;
  SvgChart chart;
  chart.title = fmt::format("work-precision of scene {}", scene.name);
  chart.xLabel = "CPU time [s]";
  chart.yLabel = "relative error";
  chart.logX = chart.logY = true;
  std::string runs, refs;
  double tightest = rtols.back();
  for (int h : harmonics) {
    dyn::SceneOverrides base;
    base.estimateError = false;
    base.keepSeries = false;
    if (h > 0) base.harmonics = h;
    // The reference, and a still tighter run that says how far it can be trusted.
    auto refOv = base;
    refOv.method = cat::Method::Rk8pd;
    refOv.rtol = tightest / 100;
    auto ref = dyn::runScene(m, design, scene, refOv);
    refOv.rtol = tightest / 1000;
    auto check = dyn::runScene(m, design, scene, refOv);
    if (!ref.failure.empty() || ref.numbers.empty() || !check.failure.empty()) {
      r.notes.push_back(fmt::format("harmonics {}: no reference ({})", h, ref.failure.empty() ? check.failure : ref.failure));
      continue;
    }
    key = ref.numbers[0].key;
    double refValue = ref.numbers[0].value;
    double verified = std::fabs(refValue - check.numbers[0].value) / std::max(std::fabs(check.numbers[0].value), 1e-300);
    refs += fmt::format("{}{{\"harmonics\": {}, \"rtol\": {}, \"value\": {}, \"checked_against_rtol\": {}, \"difference\": {}}}",
                        refs.empty() ? "" : ", ", h, tightest / 100, refValue, tightest / 1000, verified);
    r.notes.push_back(fmt::format("harmonics {}: reference {} = {:.10g} at rtol {:.0e} (rk8pd), within {:.1e} of a run at rtol {:.0e}",
                                  h == 0 ? std::string("-") : std::to_string(h), key, refValue, tightest / 100, verified, tightest / 1000));
    for (cat::Method id : methods) {
      std::string method(cat::methodSpec(id).name);
      SvgSeries series;
      series.label = fmt::format("{}{}", method, h > 0 ? fmt::format(", {} harmonics", h) : "");
      series.markers = true;
      for (double rtol : rtols) {
        auto ov = base;
        ov.method = id;
        ov.rtol = rtol;
        auto run = dyn::runScene(m, design, scene, ov);
        std::vector<std::string> row = {h == 0 ? "-" : std::to_string(h), method, fmt::format("{:.0e}", rtol)};
        if (!run.failure.empty() || run.numbers.empty()) {
          row.push_back("failed");
          row.push_back("-");
          row.push_back("-");
          if (timings) row.push_back("-");
          r.rows.push_back(row);
          continue;
        }
        double err = std::fabs(run.numbers[0].value - refValue) / std::max(std::fabs(refValue), 1e-300);
        row.push_back(fmt::format("{:.2e}", err));
        row.push_back(std::to_string(run.stats.steps));
        row.push_back(std::to_string(run.stats.rhsEvaluations));
        if (timings) row.push_back(fmt::format("{:.2f}", run.stats.cpuSeconds * 1e3));
        r.rows.push_back(row);
        runs += fmt::format("{}{{\"harmonics\": {}, \"method\": \"{}\", \"rtol\": {}, \"error\": {}, \"steps\": {}, \"rhs_evaluations\": {}{}}}",
                            runs.empty() ? "" : ", ", h, method, rtol, err, run.stats.steps, run.stats.rhsEvaluations,
                            timings ? fmt::format(", \"cpu_seconds\": {}", run.stats.cpuSeconds) : "");
        series.x.push_back(std::max(run.stats.cpuSeconds, 1e-6));
        series.y.push_back(std::max(err, 1e-16));
      }
      chart.series.push_back(series);
    }
  }
  json += fmt::format("\"output\": \"{}\", \"references\": [{}], \"runs\": [{}]}}", key, refs, runs);
  r.json = json;
  if (!outDir.empty()) {
    std::filesystem::create_directories(outDir);
    std::string file = filePrefix + "." + study.name + ".svg";
    std::ofstream(std::filesystem::path(outDir) / file) << renderSvg(chart);
    r.files.push_back(file);
  }
  return r;
}

} // namespace gbx::rt
