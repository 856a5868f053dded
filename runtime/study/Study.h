#pragma once
// What a study returns: plain data in SI. report/ turns it into tables, JSON and charts.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "units/Unit.h"

namespace gbx::rt {

// `sweep X in a..b step s`: every output at every value of X.
struct SweepStudy {
  std::string name;
  std::string target;                   // the swept quantity
  units::DisplayUnit unit{"", 1};       // how X is shown
  struct Output {
    std::string text;                   // as written in the spec
    units::DisplayUnit unit{"", 1};
  };
  std::vector<Output> outputs;
  // `Y in {…}` beside the sweep: the sweep once per value of Y, a line each.
  std::string seriesTarget; // "" without one
  units::DisplayUnit seriesUnit{"", 1};
  struct Point {
    double x = 0;
    std::vector<double> y;              // one per output; NaN where it has no value
    // Sweeps of a scene: the periodic response's stability (largest Floquet multiplier
    // modulus) and, with continuation, the branch (parts between turning points).
    double stability = NAN;
    int branch = 0;
    double error = NAN;                 // the scene's error estimate at this point
    std::vector<bool> unstable;         // per output: it reads a scene whose orbit is unstable here
    bool afterGap = false;              // continuation: the first point after a stretch not followed
    double series = NAN;                // the series' value (SI) of the line it lies on; NaN without one
  };
  std::vector<Point> points;
  bool plot = false;                    // `plot;`: one chart per output
  bool scene = false;                   // the outputs include a scene's
  std::string stabilityScene;           // whose stability the points carry (the first scene read)
  std::string continuation;             // "", "natural" or "arclength"
  std::vector<double> folds;            // turning points of the continuation, in SI of X
  double nominal = NAN;                 // X at the design as specified (the operating point), SI
  std::vector<std::pair<double, double>> gaps;  // stretches the continuation could not follow, SI of X
  // Where an order of the mesh frequency meets the mesh's natural frequency (f_mesh = f_n / k),
  // in SI of X: the resonance speeds of a speed sweep.
  std::vector<std::pair<double, std::string>> marks;
  std::vector<std::string> notes;       // how the sweep was followed
  std::string failure;                  // a point that could not be solved (exit 3)
};

// `work_precision of SCENE`: the error of the scene's first numeric output against a
// reference, for every harmonics setting, method and tolerance.
struct WorkPrecisionStudy {
  std::string name, scene;
  struct Reference {
    int harmonics = 0;                  // 0: the scene's own model
    bool ok = false;
    std::string failure;                // why there is none, when !ok
    std::string output;                 // the output compared
    double rtol = 0, value = 0;         // the reference run (rk8pd)
    std::string steady;                 // how it reached its steady state
    double checkRtol = 0, difference = 0;  // a still tighter run, and the relative difference to it
  };
  std::vector<Reference> references;
  struct Run {
    double rtol = 0;
    bool ok = false;
    double error = 0;                   // relative, against the reference
    long steps = 0, rhsEvaluations = 0;
    double cpuSeconds = 0;
  };
  // One per harmonics setting with a reference and method, its runs from loose to tight.
  struct Curve {
    int harmonics = 0;
    std::string method;
    std::string steady;                 // "periodic" or "settle N"
    std::vector<Run> runs;
  };
  std::vector<Curve> curves;
};

} // namespace gbx::rt
