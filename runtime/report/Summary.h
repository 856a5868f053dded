#pragma once
// A gearbox's summary, as the text and HTML reports open with it: what it was solved for,
// the chosen design and its key results, each safety against its minimum, and every warning
// of the report in one place.
#include <cmath>
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

struct GearboxSummary {
  std::string headline;  // "31 designs, best 10 shown; ratio window [579/100, 581/100]"
  std::vector<GearboxReport::Input> inputs;
  std::vector<std::pair<std::string, std::string>> design;  // the chosen design: name, value as the table shows it
  std::vector<std::string> results;                         // "scene mesh: rms(acceleration) = 5081.4161 m/s^2"
  struct Safety {
    std::string where;  // "hs, pinion"
    std::string label;  // "contact_safety"
    double value = 0, minimum = 1;  // value NaN: it could not be computed
    // Met as the report shows the two, to four decimals.
    bool computed() const { return std::isfinite(value); }
    bool ok() const { return computed() && std::round(value * 1e4) >= std::round(minimum * 1e4); }
  };
  std::vector<Safety> safeties;
  std::vector<std::string> warnings;  // each with where it comes from
};

GearboxSummary summarise(const GearboxReport& g);

// A stage's modification rules as a table: target, value, rule, when, inputs.
std::vector<std::string> modificationHeader();
std::vector<std::vector<std::string>> modificationRows(const ModifyReport& md);

// The design table's header and a row's cells, as every table-shaped format shows them.
std::vector<std::string> designHeader(const GearboxReport& g);
std::vector<std::string> designCells(const DesignRow& r);

// A table too wide for its page, cut into groups of columns: each group opens with the first
// column (the rank) and takes the next columns while their widths (the first's included) fit
// within `limit`; one group when the whole table fits. Widths in any measure (characters, px).
std::vector<std::vector<size_t>> columnGroups(const std::vector<double>& widths, double limit);
// A row's cells in the given columns, a blank where the row is short.
std::vector<std::string> cellsOf(const std::vector<std::string>& row, const std::vector<size_t>& columns);

} // namespace gbx::rt
