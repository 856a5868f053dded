#pragma once
// Reports of solved gearboxes: text tables, JSON (keys of LANGUAGE.md §10), CSV and
// Markdown. Numbers are printed in a fixed format so that reports are byte-stable.
#include <string>
#include <vector>

#include "search/Search.h"

namespace gbx::rt {

struct Cell {
  bool valid = false;
  double lo = 0, hi = 0;  // lo == hi for a number; over freedoms the attainable interval
  bool feasible = false;  // a rule bounds this quantity: [flo, fhi] is the part it allows
  double flo = 0, fhi = 0;
  std::string text;       // how the text report shows it
};

struct Column {
  std::string name;
  std::string unit;  // display unit
  double scale = 1;  // SI per display unit
  bool exact = true; // intervals are exact images (monotone catalogue quantities), else enclosures
};

struct DesignRow {
  int rank = 0;
  std::vector<std::pair<std::string, long long>> teeth;  // integer choices and tooth counts
  std::vector<std::pair<std::string, std::string>> choices;  // other chosen values, as text
  Rational ratio;
  bool undecided = false;
  std::vector<Cell> cells;
};

struct GearboxReport {
  std::string name;
  unsigned long long count = 0;
  unsigned long long undecided = 0;
  std::string window;
  std::vector<Column> columns;
  std::vector<DesignRow> rows;
  std::vector<FunnelStep> funnel;
  std::vector<std::string> notes;
};

std::string formatNumber(double v);
std::string renderText(const std::vector<GearboxReport>& r);
std::string renderJson(const std::vector<GearboxReport>& r);
std::string renderCsv(const std::vector<GearboxReport>& r);
std::string renderMarkdown(const std::vector<GearboxReport>& r, bool html);

} // namespace gbx::rt
