#pragma once
// The scans behind ConventionsTest.cpp, over the source tree.
#include <filesystem>
#include <string>
#include <vector>

namespace gbx::test {

struct Hit {
  std::string where;  // file:line
  std::string line;
};

// `== "…"`, `!= "…"`, `.compare(…"…")`, `starts_with("…")`, `ends_with("…")` in one line of
// code (a line comment's text and string contents are not code).
size_t countLiteralComparisons(const std::string& line);

// Every such comparison in the .cpp and .h files under `dir`.
std::vector<Hit> literalComparisons(const std::filesystem::path& dir);

// `#include "…"` lines that name a header of a higher layer: in compiler/, one of runtime/ or
// tools/; in runtime/, one of tools/.
std::vector<Hit> upwardIncludes(const std::filesystem::path& root);

// Lines of runtime/ that read a scene from the IR (`ir::Scene`, `gearbox.scenes`, an
// ir::Effect's parameters) outside the files allowed to: the planner (model/ScenePlan.*)
// and the two entries that plan a scene for a caller (dynamics/Scene.*).
std::vector<Hit> sceneReadsOutsideThePlan(const std::filesystem::path& root);

// The functions of a u-ctags listing (with `line:` and `end:` fields) longer than `most` lines.
std::vector<Hit> longFunctions(const std::string& ctagsOutput, int most);

} // namespace gbx::test
