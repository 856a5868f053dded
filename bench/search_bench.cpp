// Search benchmark: gbxc's search against a brute-force reference in the same process.
//   search_bench CASE [jobs]
// CASE: paper2 | spur3 | spur4 | spur3-40 | spur3-60 | spur4-30 | spur4-40
// Prints one line: case, jobs, designs, median search seconds, reference seconds (or
// "-" when the reference is not run at that size), peak RSS in MiB.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/Driver.h"
#include "search/Search.h"

using namespace gbx;
using Clock = std::chrono::steady_clock;

namespace {

std::string spurSpec(int stages, int maxTeeth) {
  std::string s = fmt::format("gearbox Bench {{\n  stage s0: spur {{ pinion.z in 12..{}; wheel.z in 12..{}; require coprime(pinion.z, wheel.z); }}\n",
                              maxTeeth, maxTeeth);
  std::string names = "s0";
  for (int i = 1; i < stages; ++i) {
    s += fmt::format("  stage s{} like s0;\n", i);
    names += fmt::format(", s{}", i);
  }
  s += "  interchangeable " + names + ";\n";
  s += "  require ratio == 13.36838 +- 0.0001%;\n  minimize abs(ratio - 13.36838);\n  report { top 100; }\n}\n";
  return s;
}

std::string readSpec(const std::string& name) {
  std::ifstream in(std::string(GBX_SOURCE_DIR) + "/specs/" + name);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The reference: every multiset of coprime reduction pairs, checked exactly. What a
// careful script would do; no pruning beyond the canonical order.
unsigned long long bruteForce(int stages, int maxTeeth) {
  struct Pair {
    long long p, w;
  };
  std::vector<Pair> pairs;
  for (long long p = 12; p <= maxTeeth; ++p)
    for (long long w = p + 1; w <= maxTeeth; ++w)
      if (std::gcd(p, w) == 1) pairs.push_back({p, w});
  // 13.36838 * (1 -+ 1e-6) as exact fractions: 1336838 * (1000000 -+ 1) / 10^11.
  const units::i128 lo_num = static_cast<units::i128>(1336838) * 999999, hi_num = static_cast<units::i128>(1336838) * 1000001;
  const units::i128 scale = static_cast<units::i128>(100000000000LL);
  unsigned long long count = 0;
  std::vector<size_t> idx(static_cast<size_t>(stages));
  std::function<void(int, size_t, units::i128, units::i128)> rec = [&](int s, size_t from, units::i128 num, units::i128 den) {
    if (s == stages) {
      // lo <= num/den <= hi  <=>  lo_num * den <= num * scale <= hi_num * den
      if (lo_num * den <= num * scale && num * scale <= hi_num * den) ++count;
      return;
    }
    for (size_t i = from; i < pairs.size(); ++i) rec(s + 1, i, num * pairs[i].w, den * pairs[i].p);
  };
  rec(0, 0, 1, 1);
  return count;
}

double peakMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: search_bench CASE [jobs]\n");
    return 2;
  }
  std::string which = argv[1];
  int jobs = argc > 2 ? std::atoi(argv[2]) : 1;
  std::string text, gearbox = "Bench";
  int stages = 0, teeth = 100;
  bool reference = false;
  if (which == "paper2") {
    text = readSpec("thruster_two_stage.gbx");
    gearbox = "ThrusterTwoStage";
  } else if (which.rfind("spur", 0) == 0) {
    stages = which[4] - '0';
    auto dash = which.find('-');
    if (dash != std::string::npos) {
      teeth = std::atoi(which.c_str() + dash + 1);
      reference = true;
    }
    text = spurSpec(stages, teeth);
  } else {
    std::fprintf(stderr, "unknown case %s\n", which.c_str());
    return 2;
  }
  auto c = driver::compileText("bench.gbx", text);
  if (!c->ok()) {
    std::fputs(c->diags.renderText(c->sources).c_str(), stderr);
    return 1;
  }
  const ir::Gearbox* g = nullptr;
  for (const auto& x : c->program.gearboxes)
    if (x.name == gearbox) g = &x;
  rt::Model model(c->program, *g);
  rt::SearchOptions opt;
  opt.jobs = jobs;
  opt.top = 100;
  // Repeat small cases enough to time them; report the median.
  std::vector<double> times;
  unsigned long long count = 0;
  double budget = 0;
  for (int rep = 0; rep < 200 && (rep < 5 || budget < 2.0); ++rep) {
    auto t0 = Clock::now();
    auto r = rt::search(model, opt);
    double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    times.push_back(dt);
    budget += dt;
    count = r.count;
  }
  std::sort(times.begin(), times.end());
  double median = times[times.size() / 2];
  std::string ref = "-";
  if (reference) {
    auto t0 = Clock::now();
    unsigned long long want = bruteForce(stages, teeth);
    double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    if (want != count) {
      std::fprintf(stderr, "MISMATCH: search %llu, reference %llu\n", count, want);
      return 1;
    }
    ref = fmt::format("{:.4f}", dt);
  }
  std::printf("%s %d %llu %.6f %s %.1f\n", which.c_str(), jobs, count, median, ref.c_str(), peakMiB());
  return 0;
}
