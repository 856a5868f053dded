// Rules of the house that nothing else checks, kept as tests so they cannot erode:
// names never decide (literal string comparisons stay under a ceiling), and the layers
// include downwards only (compiler/ sees neither runtime/ nor tools/; runtime/ not tools/).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conventions/Conventions.h"

namespace fs = std::filesystem;
using namespace gbx::test;

namespace {

const fs::path kRoot = GBX_SOURCE_DIR;

std::string listed(const std::vector<Hit>& hits) {
  std::string s;
  for (const auto& h : hits) s += "  " + h.where + ": " + h.line + "\n";
  return s;
}

} // namespace

// The ceilings of docs/architecture.md's "names never decide": a name that decides behaviour is a
// catalogue row, an enum or a table entry, compared as such.
TEST(Conventions, LiteralStringComparisonsStayUnderTheirCeilings) {
  auto sema = literalComparisons(kRoot / "compiler" / "sema");
  EXPECT_LE(sema.size(), 15u) << "literal string comparisons in compiler/sema/:\n" << listed(sema);
  auto runtime = literalComparisons(kRoot / "runtime");
  EXPECT_LE(runtime.size(), 5u) << "literal string comparisons in runtime/:\n" << listed(runtime);
}

// The pattern counts each form the rule names, and nothing else.
TEST(Conventions, ThePatternFindsEachForm) {
  for (const char* line : {R"(if (name == "plot") x();)", R"(if (s != "stability") y();)", R"(a.compare(0, 3, "abc");)",
                           R"(if (w.starts_with("x")) z();)", R"(if (w.ends_with("y")) z();)"})
    EXPECT_EQ(countLiteralComparisons(line), 1u) << line;
  for (const char* line : {R"(if (name == kPlot) x();)", R"(out += "a == b";)", R"(// == "comment")", R"(f("x") == g;)"})
    EXPECT_EQ(countLiteralComparisons(line), 0u) << line;
}

// compiler/ is the front end: it builds and reads without runtime/ or tools/; runtime/ never
// reaches up into tools/.
TEST(Conventions, LayersIncludeDownwardsOnly) {
  auto up = upwardIncludes(kRoot);
  EXPECT_TRUE(up.empty()) << "includes that run up a layer:\n" << listed(up);
}

// A scene is resolved once into its plan (model/ScenePlan.h): the scene models, the passes
// and the studies read the plan, never the scene's settings or effects in the IR.
TEST(Conventions, ScenesAreReadThroughTheirPlan) {
  auto reads = sceneReadsOutsideThePlan(kRoot);
  EXPECT_TRUE(reads.empty()) << "scene reads outside model/ScenePlan:\n" << listed(reads);
}

// No function in compiler/ or runtime/ runs over 120 lines, as Universal Ctags measures them
// (its end line of each function definition): a function a newcomer must scroll through is
// split by what it does.
TEST(Conventions, NoFunctionOverAHundredAndTwentyLines) {
  ASSERT_EQ(std::system("command -v ctags-universal >/dev/null 2>&1"), 0) << "universal-ctags is missing: run scripts/setup.sh";
  std::string cmd = "cd '" + kRoot.string() + "' && ctags-universal --kinds-C++=f --fields=+ne -R --output-format=u-ctags -f - compiler runtime";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  ASSERT_EQ(pclose(pipe), 0);
  auto long_ = longFunctions(out, 120);
  EXPECT_GT(std::count(out.begin(), out.end(), '\n'), 500) << "ctags listed too few functions";
  EXPECT_TRUE(long_.empty()) << "functions over 120 lines:\n" << listed(long_);
}
