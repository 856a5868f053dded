#pragma once
// Pass 7, render: the reports of all gearboxes in one format, and their charts.
#include <string>
#include <vector>

#include "report/Charts.h"
#include "report/Formats.h"
#include "report/Report.h"

namespace gbx::rt::passes {

struct Rendered {
  std::string report;
  std::string reportFile;         // its name in the output folder
  std::vector<ChartFile> charts;  // drawn only when the options ask for charts
  std::vector<TableFile> tables;  // further files of the format (CSV tables), with charts
  // Without an output folder: the format's further tables that have rows and were not
  // written (stdout holds one table), for a note that names them.
  std::vector<std::string> unwritten;
  std::vector<GearboxReport> reports; // what was rendered, for an embedding program to keep
};

Rendered render(std::vector<GearboxReport> reports, const ReportFormat& format, const RenderOptions& options);

} // namespace gbx::rt::passes
