#pragma once
// The report formats of `gbxc solve --format F`, one row each. The driver validates
// --format against this table and solve renders with the row it names.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

struct ReportFormat {
  std::string_view name;       // the value of --format
  std::string_view extension;  // -o DIR writes DIR/report.<extension>
  std::string (*render)(const std::vector<GearboxReport>&, const RenderOptions&);
  bool diagnostics;            // check, dump and test print their diagnostics in it too
  // With -o DIR, further files beside the report (CSV: one table per kind of result).
  std::vector<TableFile> (*tables)(const std::vector<GearboxReport>&, const RenderOptions&) = nullptr;
  bool inlineCharts = false;   // the charts go inside the report, with or without -o DIR
  // Without -o DIR: the names of those further files that have rows (left out on stdout).
  std::vector<std::string> (*unwritten)(const std::vector<GearboxReport>&, const RenderOptions&) = nullptr;
};

// The first row, text, is the default.
std::span<const ReportFormat> reportFormats();
const ReportFormat* findReportFormat(std::string_view name);

} // namespace gbx::rt
