#pragma once
// Golden regression tests: each `x.gbx` beside its `x.expected`. The arguments come from
// a first line `// ARGS: …`, else from `golden.args` in the folder, else `solve`.
#include <string>
#include <vector>

namespace gbx::driver {

struct GoldenCase {
  std::string gbx;       // path of the spec
  std::string expected;  // path of the expected output
  std::string name;      // folder/stem, for test names
  std::vector<std::string> args;
};

std::vector<GoldenCase> discoverGolden(const std::vector<std::string>& paths, std::vector<std::string>& problems);

// Runs the case in-process from its own folder (so paths in the output are relative
// to it) and returns stdout, then stderr, then `[exit N]`.
std::string captureGolden(const GoldenCase& c);

struct GoldenOutcome {
  enum Status { Pass, Fail, Missing, Updated } status = Pass;
  std::string diff;
};
GoldenOutcome runGolden(const GoldenCase& c, bool update);

std::string unifiedDiff(const std::string& expected, const std::string& actual, const std::string& expectedName,
                        const std::string& actualName);

} // namespace gbx::driver
