#pragma once
// The optimisation summary as reports show it: text lines and a JSON value.
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

// `files`: name the chart files written beside the report.
std::vector<std::string> optimisationLines(const OptimisationSummary& s, bool files = true);
std::string optimisationTiming(const OptimisationSummary& s);
std::string optimisationJson(const OptimisationSummary& s);

} // namespace gbx::rt
