#pragma once
// Golden regression tests: each `x.gbx` beside its `x.expected`. The arguments come from
// a line `// ARGS: …` among the spec's leading comments, else from `golden.args` in the
// folder, else `solve`. CPU times never enter the comparison unless asked for; a leading
// `// TOLERANCE: 1e-9` compares numbers within that relative tolerance.
#include <string>
#include <vector>

namespace gbx::driver {

struct GoldenCase {
  std::string gbx;       // path of the spec
  std::string expected;  // path of the expected output
  std::string name;      // folder/stem, for test names
  std::vector<std::string> args;
  double tolerance = 0;  // relative, for numbers; 0: byte-exact
};

struct GoldenOptions {
  bool update = false;
  bool timings = false;  // keep CPU times in the output (a person reading it; never for golden files)
};

// The .gbx files below a folder, in name order; a folder that cannot be read is named in
// `problem` (what was found before it is returned).
std::vector<std::string> gbxFilesBelow(const std::string& folder, std::string& problem);

std::vector<GoldenCase> discoverGolden(const std::vector<std::string>& paths, std::vector<std::string>& problems);

// Runs the case in-process from its own folder (so paths in the output are relative
// to it) and returns stdout, then stderr, then `[exit N]`.
std::string captureGolden(const GoldenCase& c, const GoldenOptions& o = {});

struct GoldenOutcome {
  enum Status { Pass, Fail, Missing, Updated } status = Pass;
  std::string diff;
};
GoldenOutcome runGolden(const GoldenCase& c, const GoldenOptions& o);

// Equal line by line, numbers within a relative tolerance and all other text exact.
bool equalWithin(const std::string& expected, const std::string& actual, double tolerance);

// Lines only in the expected output as `-`, before the lines only in the actual one as `+`.
std::string unifiedDiff(const std::string& expected, const std::string& actual, const std::string& expectedName,
                        const std::string& actualName);

} // namespace gbx::driver
