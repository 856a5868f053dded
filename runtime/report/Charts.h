#pragma once
// The SVG charts that go beside a report: scene plots and spectra, study charts and the
// Pareto front of an optimisation.
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

// Draws every chart of the reports and records each file's name with the part it shows.
std::vector<ChartFile> drawCharts(std::vector<GearboxReport>& reports);

} // namespace gbx::rt
