// One test per golden file (output against `.expected`) and, for the bad-input corpus,
// one per file that asserts its diagnostic codes (`// CODES: E0201 …` on the first line).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "driver/Golden.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

bool updating() {
  const char* v = std::getenv("GBX_UPDATE_GOLDEN");
  return v && std::string(v) == "1";
}

class GoldenFileTest : public testing::Test {
public:
  explicit GoldenFileTest(driver::GoldenCase c) : c_(std::move(c)) {}
  void TestBody() override {
    auto r = driver::runGolden(c_, driver::GoldenOptions{updating(), false});
    switch (r.status) {
    case driver::GoldenOutcome::Pass:
    case driver::GoldenOutcome::Updated: break;
    case driver::GoldenOutcome::Missing:
      FAIL() << "no " << c_.expected << ": run `GBX_UPDATE_GOLDEN=1 ctest -L golden`, then review `git diff`";
    case driver::GoldenOutcome::Fail: FAIL() << "output differs from " << c_.expected << ":\n" << r.diff;
    }
  }

private:
  driver::GoldenCase c_;
};

std::string firstLine(const std::string& path) {
  std::ifstream in(path);
  std::string l;
  std::getline(in, l);
  return l;
}

class CodesTest : public testing::Test {
public:
  CodesTest(std::string path, std::vector<std::string> want) : path_(std::move(path)), want_(std::move(want)) {}
  void TestBody() override {
    fs::path cwd = fs::current_path();
    fs::current_path(fs::path(path_).parent_path());
    auto c = driver::compile(fs::path(path_).filename().string());
    fs::current_path(cwd);
    std::vector<std::string> got;
    for (const auto& d : c->diags.sorted()) got.push_back(d.code);
    auto want = want_;
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(want, got) << path_;
    bool onlyWarnings = std::all_of(want.begin(), want.end(), [](const std::string& s) { return s[0] == 'W'; });
    EXPECT_EQ(onlyWarnings, c->ok()) << "a spec with errors must fail, one with only warnings must pass";
  }

private:
  std::string path_;
  std::vector<std::string> want_;
};

} // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  std::vector<std::string> problems;
  auto cases = driver::discoverGolden({GBX_GOLDEN_DIR}, problems);
  for (const auto& c : cases) {
    // A `-` in a name would read as gtest's negative filter when ctest runs the test alone
    // (`golden/solve-json.x` matched nothing, so it passed without running): `_` instead.
    auto gtestName = [](std::string s) {
      std::replace(s.begin(), s.end(), '-', '_');
      return s;
    };
    std::string suite = gtestName("golden/" + fs::path(c.gbx).parent_path().filename().string());
    testing::RegisterTest(suite.c_str(), gtestName(fs::path(c.gbx).stem().string()).c_str(), nullptr, nullptr, c.gbx.c_str(), 1,
                          [c]() -> testing::Test* { return new GoldenFileTest(c); });
    std::string first = firstLine(c.gbx);
    const std::string tag = "// CODES:";
    if (first.rfind(tag, 0) == 0) {
      std::istringstream in(first.substr(tag.size()));
      std::vector<std::string> codes;
      std::string code;
      while (in >> code) codes.push_back(code);
      testing::RegisterTest("codes", gtestName(fs::path(c.gbx).stem().string()).c_str(), nullptr, nullptr, c.gbx.c_str(), 1,
                            [p = c.gbx, codes]() -> testing::Test* { return new CodesTest(p, codes); });
    }
  }
  for (const auto& p : problems) std::cerr << p << "\n";
  return RUN_ALL_TESTS();
}
