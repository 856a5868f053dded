#include "passes/Render.h"

namespace gbx::rt::passes {

Rendered render(std::vector<GearboxReport> reports, const ReportFormat& format, const RenderOptions& o) {
  Rendered r;
  // Charts first: the report names the files it is drawn beside.
  if (o.charts || format.inlineCharts) r.charts = drawCharts(reports);
  RenderOptions ro = o;
  if (format.inlineCharts) ro.inlineCharts = &r.charts;
  r.report = format.render(reports, ro);
  r.reportFile = "report." + std::string(format.extension);
  // A format written as tables (CSV) writes those alone: its report is the first of them.
  if (o.charts && format.tables) {
    r.tables = format.tables(reports, o);
    r.reportFile.clear();
  }
  if (!o.charts && format.unwritten) r.unwritten = format.unwritten(reports, o);
  r.reports = std::move(reports);
  return r;
}

} // namespace gbx::rt::passes
