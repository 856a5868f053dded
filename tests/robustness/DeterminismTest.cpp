// The same bytes for --jobs 1, 2 and 4: every spec of specs/ solved three times in JSON
// (no timings), compared whole. The optimiser runs a few iterations per candidate here (its
// full run is the marine spec's golden file): the threads still share out the candidates,
// the scenes and the baseline. Under the sanitizers (ten to twenty times slower) --jobs 1
// and 2 only, and the marine spec's optimised gearbox is left out (its baseline still runs).
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "driver/Driver.h"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> specFiles() {
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(fs::path(GBX_SOURCE_DIR) / "specs"))
    if (e.path().extension() == ".gbx") v.push_back(e.path().filename().string());
  std::sort(v.begin(), v.end());
  return v;
}

class Determinism : public testing::TestWithParam<std::string> {};

} // namespace

TEST_P(Determinism, SameBytesForOneTwoAndFourJobs) {
#ifdef GBX_MPI_DETERMINISM
  // Its every file for one and two threads and four ranks: Mpi.SameBytesForOneTwoJobsAndFourRanks.
  if (GetParam() == "marine_tolerances.gbx") GTEST_SKIP() << "compared by the MPI determinism test";
#endif
  std::string file = (fs::path(GBX_SOURCE_DIR) / "specs" / GetParam()).string();
  std::vector<std::string> extra;
  std::vector<const char*> jobsList = {"1", "2", "4"};
#ifdef GBX_SANITIZED
  if (GetParam() == "marine_reducer.gbx") extra = {"--gearbox", "MarineReducer"};
  jobsList = {"1", "2"};
#endif
  std::string first;
  for (const char* jobs : jobsList) {
    std::vector<std::string> args = {"solve", file, "--format", "json", "--quiet", "--no-timings", "--jobs", jobs};
    args.insert(args.end(), extra.begin(), extra.end());
    std::ostringstream out, err;
    gbx::driver::TestSettings cut;
    cut.optimiserIterations = 6;
    int status = gbx::driver::run(args, out, err, cut);
    ASSERT_EQ(status, 0) << "--jobs " << jobs << ":\n" << err.str();
    if (first.empty()) {
      first = out.str();
      ASSERT_FALSE(first.empty());
    } else {
      EXPECT_TRUE(out.str() == first) << "--jobs " << jobs << " gives other bytes than --jobs 1";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Specs, Determinism, testing::ValuesIn(specFiles()),
                         [](const testing::TestParamInfo<std::string>& i) { return i.param.substr(0, i.param.rfind('.')); });
