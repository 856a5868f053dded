// Rules of the house that nothing else checks, kept as tests so they cannot erode:
// names never decide (literal string comparisons stay under a ceiling), and the layers
// include downwards only (compiler/ sees neither runtime/ nor tools/; runtime/ not tools/).
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

// The ceilings of LANGUAGE.md's "names never decide": a name that decides behaviour is a
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
