#pragma once
// `gbxc solve`: every gearbox of a checked program through the runtime's passes, then one report.
#include <iosfwd>
#include <string>

#include <vector>

#include "ir/Ir.h"

namespace gbx::rt {

struct GearboxReport;

struct SolveOptions {
  std::string gearbox;  // only this one, when set
  std::string format = "text";  // a name in report/Formats.h
  std::string outDir;
  int jobs = 1;
  bool quiet = false;
  bool timings = true;  // CPU times in reports (off for golden files)
  double maxDesigns = 1e9;  // the search budget (`--max-designs`)
  double timeLimit = 0;     // seconds of wall time (`--time-limit`); 0: none
  std::string title;    // the spec's file name, for the report's header
  std::string version;  // gbxc's
  int optimiserIterations = 0;  // a test setting: Nelder-Mead iterations per candidate; 0: its own
  // Where an embedding program keeps the reports once rendered (the Python module's arrays);
  // null: none kept.
  std::vector<GearboxReport>* keep = nullptr;
};

// Returns the exit status: 0 solved (an empty design list included), 3 a runtime failure.
int solve(const ir::Program& program, const SolveOptions& options, std::ostream& out, std::ostream& err);

} // namespace gbx::rt
