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

struct ScenePeakRow {
  double frequency = 0, amplitude = 0;
  int harmonic = 0;
};

struct SceneReport {
  std::string name, target, method;
  double rtol = 0, atol = 0;
  long steps = 0, rejected = 0, rhs = 0, jacobians = 0, events = 0;
  double cpu = 0, referenceCpu = 0;
  double errorEstimate = -1;
  std::string errorMethod;
  struct Output {
    std::string key, unit;
    double si = 0, shown = 0;
  };
  std::vector<Output> outputs;
  struct SpectrumRow {
    std::string key, unit;
    double scale = 1;
    std::vector<ScenePeakRow> peaks;
  };
  std::vector<SpectrumRow> spectra;
  std::vector<std::string> model, files;
  std::string failure;
};

struct StudyReport {
  std::string name, kind;  // "sweep" or "work_precision"
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // text cells
  std::string json;                            // the study as a JSON value
  std::vector<std::string> notes, files;
};

struct ModRow {
  std::string target, text, condition;
  bool present = true, valid = false;
  double si = 0;
  std::string shown;                   // value in its display unit
  std::vector<std::string> inputs;     // "hs.load_deflection 19.04 um"
  std::vector<std::pair<std::string, double>> inputsSI;
  std::string error;
};

struct ModifyReport {
  std::string stage;
  std::vector<ModRow> rows;
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
  std::vector<SceneReport> scenes;
  std::vector<StudyReport> studies;
  std::vector<ModifyReport> modifications;
  std::vector<std::string> optimisation;  // text lines of the optimisation summary
  std::string optimisationJson;           // its JSON value, "" when none
  std::vector<std::string> optimisationTimings;  // not part of golden output
};

struct RenderOptions {
  bool timings = true;  // CPU times: off for golden files
};

std::string formatNumber(double v);
// A length as a gear engineer reads it: um below a millimetre, mm above.
std::string formatLength(double metres);
std::string renderText(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderJson(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderCsv(const std::vector<GearboxReport>& r);
std::string renderMarkdown(const std::vector<GearboxReport>& r, bool html);

} // namespace gbx::rt
