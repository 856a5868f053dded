#include "study/Sweep.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "report/Svg.h"
#include "model/Evaluator.h"
#include "units/Unit.h"

namespace gbx::rt {

namespace {
// Imbalances and other fractions read best in percent.
units::DisplayUnit unitFor(const ir::Expr& e) {
  if (e.op == ir::Op::Quantity && e.ref.key == cat::Q::Imbalance) return {"%", 0.01};
  return units::displayUnitFor(e.type.dim);
}
} // namespace

StudyReport sweep(const Model& m, const Assignment& a, const ir::Study& st, const std::string& outDir, const std::string& prefix) {
  StudyReport r;
  r.name = st.name;
  r.kind = "sweep";
  units::Dim dim = st.dim.value_or(units::Dim{});
  auto xu = units::displayUnitFor(dim);
  r.header.push_back(st.target + (xu.name.empty() ? "" : " [" + xu.name + "]"));
  std::vector<units::DisplayUnit> yu;
  for (size_t i = 0; i < st.outputs.size(); ++i) {
    yu.push_back(unitFor(*st.outputs[i]));
    r.header.push_back(st.outputTexts[i] + (yu.back().name.empty() ? "" : " [" + yu.back().name + "]"));
  }
  double lo = st.lo->toDouble(), hi = st.hi->toDouble(), step = st.step->toDouble();
  long n = static_cast<long>(std::floor((hi - lo) / step * (1 + 1e-12))) + 1;
  std::vector<SvgSeries> series(st.outputs.size());
  std::string points;
  for (long k = 0; k < n; ++k) {
    double x = lo + static_cast<double>(k) * step;
    Evaluator ev(m);
    ev.setOverride(st.swept, Value::number(x));
    std::vector<std::string> row = {fmt::format("{:.6g}", x / xu.scale)};
    std::string outs;
    for (size_t i = 0; i < st.outputs.size(); ++i) {
      Value v = ev.eval(*st.outputs[i], a);
      double y = v.isNumber() ? v.mid() : NAN;
      row.push_back(std::isfinite(y) ? formatNumber(y / yu[i].scale) : "n/a");
      outs += fmt::format("{}\"{}\": {}", i ? ", " : "", st.outputTexts[i], std::isfinite(y) ? fmt::format("{}", y) : "null");
      series[i].label = st.outputTexts[i];
      series[i].markers = true;
      series[i].x.push_back(x / xu.scale);
      series[i].y.push_back(y / yu[i].scale);
    }
    r.rows.push_back(row);
    points += fmt::format("{}{{\"x\": {}, \"outputs\": {{{}}}}}", k ? ", " : "", x, outs);
  }
  r.json = fmt::format("{{\"sweep\": \"{}\", \"unit\": \"SI\", \"points\": [{}]}}", st.target, points);
  if (st.plot && !outDir.empty()) {
    // One chart per output: outputs of different units do not share an axis.
    for (size_t i = 0; i < series.size(); ++i) {
      SvgChart c;
      c.title = fmt::format("{}: {} against {}", st.name, st.outputTexts[i], st.target);
      c.xLabel = r.header[0];
      c.yLabel = r.header[i + 1];
      c.series = {series[i]};
      std::string file = prefix + "." + st.name + (series.size() > 1 ? fmt::format(".{}", i + 1) : "") + ".svg";
      std::filesystem::create_directories(outDir);
      std::ofstream(std::filesystem::path(outDir) / file) << renderSvg(c);
      r.files.push_back(file);
    }
  }
  return r;
}

} // namespace gbx::rt
