#pragma once
// Reports of solved gearboxes: text tables, JSON (keys of docs/cli.md), CSV,
// Markdown and HTML. Numbers are printed in a fixed format so that reports are byte-stable.
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "search/Search.h"
#include "study/Study.h"
#include "units/Unit.h"

namespace gbx::rt {

struct Cell {
  bool valid = false;
  double lo = 0, hi = 0;  // lo == hi for a number; over freedoms the attainable interval
  // `report { ranges; }`: [rlo, rhi] is the value over the design's whole box of freedoms,
  // beside the value at its decided point.
  bool ranged = false;
  double rlo = 0, rhi = 0;
  bool feasible = false;  // a rule bounds this quantity: [flo, fhi] is the part of the range it allows
  double flo = 0, fhi = 0;
  std::string text;       // how the text report shows it
};

struct Column {
  std::string name;
  std::string unit;  // display unit
  double scale = 1;  // SI per display unit
  bool exact = true; // intervals are exact images (monotone catalogue quantities), else enclosures
  double offset = 0; // SI value of the display unit's zero (degC)
  std::string siUnit; // the SI unit of its values in JSON (`m`, `rad`, `1` for a plain number)
};

struct DesignRow {
  int rank = 0;
  std::vector<std::pair<std::string, long long>> teeth;  // integer choices and tooth counts
  std::vector<std::pair<std::string, std::string>> choices;  // other chosen values, as text
  struct Value {
    double shown = 0;  // in `unit`
    std::string unit;
    double si = 0, scale = 1;  // the value in SI, and SI per `unit`
    std::string siUnit;        // the SI unit of `si`
  };
  std::vector<Value> choiceValues;  // the same, as numbers in their display unit
  // The design as the search model has it, for passes that evaluate more of it.
  std::vector<int> choice;
  std::vector<std::pair<double, double>> box;
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
  bool eigen = false;  // modes of a lumped model: no integrator, no error estimate
  double rtol = 0, atol = 0;
  long steps = 0, rejected = 0, rhs = 0, jacobians = 0, events = 0;
  double cpu = 0, referenceCpu = 0;
  double errorEstimate = -1;
  std::string errorMethod;
  std::vector<std::pair<std::string, double>> errorParts;  // integration, stiffness series, Newton residual
  std::string stepRule;     // the maximum step and its rule
  std::string steady;       // "periodic", "settle", "from rest", "static"
  bool integrated = true;   // false: every output read the loaded mesh's table (steady "static")
  struct Output {
    std::string key, unit;
    double si = 0, shown = 0;
    double error = NAN;  // its own error estimate, relative to its scale (docs/language.md)
  };
  // Whether an output's own estimate is worth printing beside the scene's: it differs by
  // more than the two digits the scene's is printed with.
  static bool ownError(const Output& o, double scene) {
    return std::isfinite(o.error) && scene >= 0 && std::fabs(o.error - scene) > 0.05 * std::max(scene, 1e-300);
  }
  std::vector<Output> outputs;
  struct SpectrumRow {
    std::string key, unit;
    double scale = 1;
    std::vector<ScenePeakRow> peaks;
  };
  std::vector<SpectrumRow> spectra;
  // The scene's `plot(…)` and `spectrum(…)` outputs as drawn: x in s or Hz, y in `unit`.
  struct Plot {
    std::string key, signal, unit;
    bool spectrum = false;
    double meshFrequency = 0;  // spectra: ticked at its orders, Hz
    std::vector<double> x, y;
  };
  std::vector<Plot> plots;
  std::vector<std::string> model;
  std::vector<std::string> warnings;
  std::vector<std::string> files;  // charts written, set by the render step
  std::string failure;
};

struct StudyReport {
  std::variant<SweepStudy, WorkPrecisionStudy> study;
  std::vector<std::string> files;  // charts written, set by the render step
};

// What the optimiser did for a gearbox whose objectives need scenes or a baseline.
struct OptimisationSummary {
  size_t candidates = 0, infeasible = 0;  // candidates optimised; of them, with no feasible freedoms
  long evaluations = 0;
  double sceneRtol = 0;                   // of the scenes inside the objective
  std::string baseline;                   // the gearbox `relative(…)` compares with
  std::vector<std::string> termNames;     // the quantities under `relative(…)`
  std::vector<double> baselineTerms;      // their baseline values
  struct FreedomValue {
    std::string path;
    double value = 0;                     // SI
    units::DisplayUnit unit{"", 1};
  };
  struct Optimum {
    // Declared, so `std::optional<Optimum>` below sees a default constructor while the
    // enclosing struct is still incomplete (clang asks before the member initializers).
    Optimum() {}
    Rational ratio;
    std::vector<FreedomValue> freedoms;
    double objective = 0;
    std::vector<double> terms;            // absolute, in termNames order
    struct Margin {
      std::string rule;                   // `q >= bound` as written
      double value = 0, bound = 0;        // q and its bound, in the display unit
      std::string unit;
      double margin = 0;                  // (q - bound) / |bound|, positive on the allowed side
    };
    std::vector<Margin> margins;          // the inequality rules at the optimum, nearest first
    // Each objective at the optimum over the gearbox's `tolerances` (`worst`/`mean` read at the
    // nominal design here): one tolerance at a time, then the whole box.
    struct Sensitivity {
      std::string objective;              // as written
      double nominal = 0, lo = 0, hi = 0; // at the nominal design; least and largest over the box's corners
      struct Line {
        std::string target;               // "main.face_width"
        double amount = 0;                // in the display unit
        std::string unit;
        double minus = 0, plus = 0;       // the objective at -amount and +amount
      };
      std::vector<Line> lines;
      std::string unit;                   // the values are in this display unit
      int failed = 0;                     // evaluations that gave no number (a failed scene)
      bool singular() const { return std::isfinite(nominal) && hi - lo > std::fabs(nominal); }
    };
    std::vector<Sensitivity> sensitivity;
  };
  std::optional<Optimum> best;
  std::string rankCheck;
  std::vector<std::pair<double, double>> cloud, pareto;  // relative terms of feasible evaluations; the non-dominated ones
  double wallSeconds = 0;                 // not part of golden output
  int jobs = 1;
  std::vector<std::string> files;         // the Pareto chart, set by the render step
};

struct ModRow {
  std::string target, text, condition;
  bool present = true, valid = false;
  double si = 0;
  units::DisplayUnit unit{"mm", 1e-3}; // its display unit: um for an amount, mm for a height or width
  std::string shown;                   // value in its display unit
  std::vector<std::string> inputs;     // "hs.load_deflection 19.04 um"
  std::vector<std::pair<std::string, double>> inputsSI;
  std::string error;
};

struct ModifyReport {
  std::string stage;
  std::vector<ModRow> rows;
};

// A stage's load-capacity rating at design 1: each factor per gear (or of the mesh), the
// safeties against their minimums, and which one governs.
// A shaft at design 1 (docs/language.md, "Shafts and bearings"): its bearings, the gears' forces on it, its speed,
// critical speed, largest deflection and mass. SI throughout.
struct ShaftReport {
  std::string name;
  std::string error;  // why the shaft could not be solved
  struct Bearing {
    std::string name, kind, method;
    double x = 0, Fr = 0, Fa = 0, P = 0, L10h = 0, Lnmh = 0, s0 = 0;  // m, N, h, -
  };
  struct Gear {
    std::string name;
    double x = 0, Ft = 0, Fr = 0, Fa = 0;
  };
  // A notch rated to DIN 743: its geometry, its safeties and every factor of the sequence
  // (one value per load type: tension, bending, torsion).
  struct Notch {
    std::string kind;
    double x = 0, d = 0, D = 0, radius = 0;  // m
    double bending = 0, torque = 0, axial = 0;  // the section's loads: N m, N m, N (tension positive)
    double SD = 0, SF = 0;
    struct Factor {
      std::string key, label, unit;  // `beta`, `beta`, ``; `sigma_WK`, `sigma_WK`, `N/mm^2`
      double scale = 1;              // SI per display unit
      double si[3] = {0, 0, 0};      // NaN: not defined for that load type
    };
    std::vector<Factor> factors;
    struct Common {
      std::string key, label, unit;
      double scale = 1, si = 0;
    };
    std::vector<Common> common;  // K1B, K1S, sigma_B(d_eff), sigma_S(d_eff), phi, sigma_mv
  };
  std::vector<Bearing> bearings;
  std::vector<Gear> gears;
  std::vector<Notch> notches;
  int loadCase = 2;
  double peakFactor = 1, minFatigue = 1.2, minStatic = 1.2;
  double fatigueSafety = 0, staticSafety = 0;  // the least over the notches
  double speed = 0, criticalSpeed = 0, deflection = 0, deflectionAt = 0, mass = 0;  // rad/s, m, kg
  std::vector<std::string> warnings;
  std::vector<double> lineX, lineDeflection, lineMoment;  // along the shaft: m, m, N m (the bending moment's magnitude)
  std::vector<std::string> files;                         // charts written with -o DIR
};

struct RatingReport {
  std::string stage;
  std::string standard = "ISO 6336";  // ISO 10300 for a bevel pair
  std::string mesh;       // "driver-idler" when the stage has several meshes, else ""
  std::vector<std::string> gears;
  struct Row {
    enum Format { Plain, Count, Whole };      // a count (load cycles) prints in exponent form, a whole number (z) bare
    enum Minimum { NoMinimum, Contact, Bending, Scuffing, IntegralScuffing, Micropitting };  // a safety: its minimum goes beside it
    std::string key;     // the quantity's name (`K_v`, `contact_safety`) or a geometry term
    std::string label;   // as the table heads it (`Z_B, Z_D`)
    std::string unit;    // display unit
    double scale = 1;    // SI per display unit
    bool perGear = false;
    std::vector<double> si;  // one value, or one per gear; NaN: not rated (an internal gear's root)
    Format format = Plain;
    Minimum minimum = NoMinimum;
    std::string method = {};  // how the factor was found (`method B, subcritical`, `method A, scene vib`)
    double offset = 0;        // SI value of the display unit's zero (degC)
  };
  std::vector<Row> rows;
  double minContact = 1, minBending = 1;
  double minScuffing = 1.5, minIntegralScuffing = 1.8, minMicropitting = 1;
  bool scuffing = false, micropitting = false;  // rated for them (their minima go in the JSON)
  // The minimum a safety row stands against (1 for a row that has none).
  double minimumOf(Row::Minimum m) const {
    switch (m) {
    case Row::Contact: return minContact;
    case Row::Bending: return minBending;
    case Row::Scuffing: return minScuffing;
    case Row::IntegralScuffing: return minIntegralScuffing;
    case Row::Micropitting: return minMicropitting;
    case Row::NoMinimum: break;
    }
    return 1;
  }
  std::string kvRange;    // the K_v range (subcritical, …) or "given"
  std::string governs;    // "bending of the wheel: S_F 1.48 against 1.56 (below the minimum)"
  double governingRatio = 0;  // the smallest safety over its minimum
  std::string error;      // why the stage could not be rated
  std::string note;       // how the design was rated, when not at a point
  std::vector<std::string> model;   // how a factor from the models was found (contact analysis, scene)
  std::vector<std::string> warnings;  // what a rating engineer would want said (docs/rating.md)
  // Values the rating leaves out, each with its reason (an internal gear's tooth root).
  struct NotRated {
    std::string gear, what, reason;
    bool inNote = false;  // the verdict's note already says it (text)
  };
  std::vector<NotRated> notRated;
  // K_Hbeta by contact analysis: the line load across the face (the plot with -o).
  std::vector<double> facePosition, lineLoad;  // mm from the coupling end, N/mm
  double meanLineLoad = 0;                     // N/mm
  // Scuffing and micropitting along the path of contact (the plots with -o).
  std::vector<double> pathGamma, contactTemperature, filmThickness;  // Gamma, degC, um
  double bulkTemperature = 0, scuffingTemperature = 0;               // degC
  std::vector<std::string> files;              // its chart, with -o DIR
};

// Monte Carlo over the tolerances at design 1 (docs/optimisation.md): each quantity that a
// `worst`, `mean` or `quantile` reads, at every sample, and its statistics.
struct MonteCarloReport {
  long samples = 0;
  std::string distribution;  // "normal" (the amount is 3 sigma) or "uniform"
  bool uniform = false;      // the deviations drawn uniformly between the bounds
  unsigned long long seed = 1;
  struct Tolerance {
    std::string target;
    double amount = 0;  // in the display unit
    std::string unit;
    double si = 0;
    double scale = 1;   // SI per display unit (of a difference)
  };
  std::vector<Tolerance> tolerances;
  std::vector<std::vector<double>> deviations;  // per sample, each tolerance's, SI
  struct Quantile {
    double p = 0, value = 0, error = 0;  // value and its standard error, SI
  };
  struct Output {
    std::string quantity;  // as written inside `worst(…)`, `mean(…)`, `quantile(…)`
    units::DisplayUnit unit{"", 1};
    std::vector<double> values;    // SI, in sample order
    double nominal = 0;            // at the nominal design, SI
    double mean = 0, meanError = 0, stdDev = 0, min = 0, max = 0;
    std::vector<Quantile> quantiles;  // the spec's, and the 5 %, 50 % and 95 % ones, by p
    int sense = 0;          // +1: larger is worse, -1: smaller is worse, 0: not known
    long worstSample = -1;  // 0-based; -1 where sense is 0
    std::vector<double> edges;  // histogram bin edges, SI
    std::vector<long> counts;
  };
  std::vector<Output> outputs;
  std::string failure;  // why the samples gave no numbers (a scene that failed at a sample)
  std::vector<std::string> warnings;  // samples beyond an attribute's range, …
  std::vector<std::string> files;  // histograms written, set by the render step
};

// Design rows made one at a time: a listing of a million designs is written as it is made
// instead of being held.
class RowSource {
public:
  virtual ~RowSource() = default;
  virtual size_t size() const = 0;
  // Row i into `out` (its vectors reused); text: the cells' text for the text report too.
  virtual void row(size_t i, DesignRow& out, bool text) const = 0;
  // Whether row i has a value in column c (without making the rest of the row).
  virtual bool valid(size_t i, size_t c) const = 0;
};

struct GearboxReport {
  std::string name;
  // The operating point and the inputs that decide the answer, for the summary.
  struct Input {
    std::string label, value;
    bool stage = false;  // a stage's inputs, else the operating point's
  };
  std::vector<Input> inputs;
  unsigned long long count = 0;
  unsigned long long undecided = 0;
  std::string window;
  std::vector<Column> columns;
  // The listed designs. With a `source` (a CSV listing), `rows` holds the first only (for
  // headers and the best design's scene columns) and every row, the first included, is
  // made by the source; its values are points (no freedoms), so no column is an interval.
  std::vector<DesignRow> rows;
  std::shared_ptr<const RowSource> source;
  std::vector<FunnelStep> funnel;
  std::vector<std::string> notes;     // about the design list (where a `worst` was found, …)
  bool partial = false;               // the time limit stopped the search: a note says how far it got
  std::vector<std::string> warnings;  // what the numbers do not cover (eps_alpha below 1, …)
  std::vector<SceneReport> scenes;
  std::vector<StudyReport> studies;
  std::vector<ModifyReport> modifications;
  std::vector<RatingReport> ratings;
  std::vector<ShaftReport> shafts;
  std::optional<OptimisationSummary> optimisation;
  std::optional<MonteCarloReport> monteCarlo;
};

struct ChartFile {
  std::string name;  // relative to the output folder
  std::string svg;
};

struct RenderOptions {
  bool timings = true;  // CPU times: off for golden files
  // The document's header: the spec's file name, gbxc's version, and the date (left out
  // with the timings, so golden files stay the same from day to day).
  std::string title, version, date;
  bool charts = false;  // SVG charts beside the report (an output folder is given)
  // Charts to draw inside the report itself (HTML: one file that travels alone).
  const std::vector<ChartFile>* inlineCharts = nullptr;
};

// Every listed row, held or made on demand (made rows carry numbers, not cell text).
template <class F>
void forEachRow(const GearboxReport& g, F&& f) {
  if (!g.source) {
    for (const auto& r : g.rows) f(r);
    return;
  }
  DesignRow r;
  for (size_t i = 0; i < g.source->size(); ++i) {
    g.source->row(i, r, false);
    f(static_cast<const DesignRow&>(r));
  }
}

// The version of docs/report.schema.json the JSON report follows (its top-level "schema").
inline constexpr const char* kReportSchemaVersion = "1.7";

std::string formatNumber(double v);
// A JSON number, shortest round-trip; null where the value is not finite (never nan or inf).
std::string jsonNumber(double v);
// A length as a gear engineer reads it: um below a millimetre, mm above.
std::string formatLength(double metres);
std::string renderText(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderJson(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderCsv(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
// The same design table, given to `sink` a piece at a time as its rows are made (a listing
// of a million designs is never held whole); the bytes are renderCsv's.
using CsvSink = std::function<void(const std::string&)>;
void streamCsv(const std::vector<GearboxReport>& r, const CsvSink& sink);
// With -o DIR: one tidy CSV per kind of result (designs, scenes, spectra, sweeps,
// work-precision runs, modifications), those that have rows.
struct TableFile {
  std::string name, text;
};
std::vector<TableFile> csvTables(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
// The names of those tables, other than the design table, that have rows.
std::vector<std::string> csvOtherTables(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderMarkdown(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
std::string renderHtml(const std::vector<GearboxReport>& r, const RenderOptions& o = {});
// The HTML report's summary section alone, with its style (a notebook's view of a report).
std::string renderHtmlSummary(const std::vector<GearboxReport>& r, const RenderOptions& o = {});

} // namespace gbx::rt
