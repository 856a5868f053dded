// Every input in tests/fuzz/regressions/ once broke gbxc (a crash, a hang, memory without
// bound, a non-finite number in a report) or is a hostile size a budget must refuse. Each
// is solved in-process; its first lines say what must come back:
//   // expect-exit: 3                        the exit status (any of 0, 1, 3 when absent)
//   // expect-text: beyond the search budget  a phrase of the diagnostic or failure
//   // args: --time-limit 1                  further command-line options
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "../fuzz/FuzzSupport.h"
#include "driver/Driver.h"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> regressionFiles() {
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(fs::path(GBX_SOURCE_DIR) / "tests/fuzz/regressions"))
    if (e.is_regular_file()) v.push_back(e.path().filename().string());
  std::sort(v.begin(), v.end());
  return v;
}

struct Expectation {
  std::optional<int> exit;
  std::vector<std::string> texts;
  std::vector<std::string> args;
};

Expectation expectationOf(const std::string& text) {
  Expectation x;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line) && line.rfind("//", 0) == 0) {
    auto value = [&](const char* key) -> std::optional<std::string> {
      std::string k = std::string("// ") + key + ": ";
      if (line.rfind(k, 0) != 0) return std::nullopt;
      return line.substr(k.size());
    };
    if (auto v = value("expect-exit")) x.exit = std::stoi(*v);
    if (auto v = value("expect-text")) x.texts.push_back(*v);
    if (auto v = value("args")) {
      std::istringstream words(*v);
      for (std::string w; words >> w;) x.args.push_back(w);
    }
  }
  return x;
}

class Regression : public testing::TestWithParam<std::string> {};

} // namespace

TEST_P(Regression, AnswersWithADiagnosticOrABudgetFailure) {
  fs::path file = fs::path(GBX_SOURCE_DIR) / "tests/fuzz/regressions" / GetParam();
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  Expectation x = expectationOf(ss.str());
  std::vector<std::string> args = {"solve", file.string(), "--format", "json", "--quiet", "--no-timings"};
  args.insert(args.end(), x.args.begin(), x.args.end());
  std::ostringstream out, err;
  int status = gbx::driver::run(args, out, err);
  std::string all = out.str() + err.str();
  if (x.exit) {
    EXPECT_EQ(status, *x.exit) << all;
  } else {
    EXPECT_TRUE(status == 0 || status == 1 || status == 3) << status << "\n" << all;
  }
  for (const auto& t : x.texts) EXPECT_NE(all.find(t), std::string::npos) << "no `" << t << "` in:\n" << all;
  if (status != 0) {
    EXPECT_FALSE(all.empty()) << "a failure must say what failed";
  }
  EXPECT_FALSE(gbx::fuzz::jsonHasNonFinite(out.str())) << out.str();
}

INSTANTIATE_TEST_SUITE_P(Inputs, Regression, testing::ValuesIn(regressionFiles()),
                         [](const testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param.substr(0, i.param.rfind('.'));
                           for (auto& c : n)
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });
