// Search benchmark: gbxc's search against references in the same process.
//   search_bench CASE [jobs] [top]
// CASE: paper2 | spur3 | spur4 | spur3-40 | spur3-60 | spur4-30 | spur4-40
//   one line: case, jobs, designs, median search seconds, brute-force reference seconds
//   (or "-" when it is not run at that size), peak RSS in MiB.
// mitm3 | mitm4: gbxc's search (top 100) and the meet-in-the-middle reference
//   (mitm_reference.h), alternating in this process, both checked to give the same count
//   and the same best 100: case, designs, gbxc median s, reference median s.
// ref3 | ref4: the reference alone, for its peak memory: case, designs, seconds, MiB.
// list4: every design of the 4-stage case listed as CSV, `gbxc solve --format csv`
//   in-process against the reference writing its lines: case, designs, gbxc s, reference
//   s, gbxc bytes, reference bytes. list4-gbxc | list4-ref: one side alone, for memory.
// check: the front end of the paper's two-stage spec in-process, median seconds.
// helical: three helical stages, ratio 40 +- 0.5 %, pinions 17..30, wheels 65..120, three
//   modules, minimize the total mass, top 10: the pruned search against an exhaustive
//   one (every design keyed by the evaluator, `jobs` threads), same top 10 required:
//   case, designs, pruned s, exhaustive s, peak MiB.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <streambuf>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/Driver.h"
#include "mitm_reference.h"
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

double peakMiB();

std::string helicalSpec() {
  return "import materials;\n"
         "gearbox Helical3 {\n"
         "  stage s1: helical {\n"
         "    pinion.z in 17..30; wheel.z in 65..120;\n"
         "    normal_module in {2 mm, 2.5 mm, 3 mm};\n"
         "    helix_angle = 12 deg; pressure_angle = 20 deg; face_width = 40 mm;\n"
         "    material = steel_20CrMnMo;\n"
         "  }\n"
         "  stage s2 like s1;\n  stage s3 like s1;\n"
         "  require ratio == 40 +- 0.5%;\n"
         "  minimize s1.mass + s2.mass + s3.mass;\n"
         "  report { top 10; }\n}\n";
}

// Counts what a report writes, keeps none of it.
class CountingBuf : public std::streambuf {
public:
  size_t bytes = 0;

protected:
  int overflow(int c) override {
    ++bytes;
    return c;
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += static_cast<size_t>(n);
    return n;
  }
};

double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Compiled {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
};

Compiled compileSpec(const std::string& text, const std::string& gearbox) {
  Compiled out;
  out.c = driver::compileText("bench.gbx", text);
  if (!out.c->ok()) {
    std::fputs(out.c->diags.renderText(out.c->sources).c_str(), stderr);
    std::exit(1);
  }
  for (const auto& x : out.c->program.gearboxes)
    if (x.name == gearbox) out.model = std::make_unique<rt::Model>(out.c->program, x);
  return out;
}

// gbxc's search against the reference, alternating A B A B.
int mitm(int stages) {
  Compiled c = compileSpec(spurSpec(stages, 100), "Bench");
  rt::SearchOptions opt;
  opt.top = 100;
  std::vector<double> a, b;
  rt::SearchResult got;
  bench::MitmResult want;
  double budget = 0;
  for (int rep = 0; rep < 100 && (rep < 5 || budget < 4.0); ++rep) {
    auto t0 = Clock::now();
    got = rt::search(*c.model, opt);
    a.push_back(seconds(t0));
    t0 = Clock::now();
    want = bench::mitmReference(stages, 100, 100);
    b.push_back(seconds(t0));
    budget += a.back() + b.back();
  }
  if (got.count != want.count || got.designs.size() != want.best.size()) {
    std::fprintf(stderr, "MISMATCH: search %llu designs, reference %llu\n", got.count, want.count);
    return 1;
  }
  for (size_t i = 0; i < want.best.size(); ++i)
    if (std::fabs(got.designs[i].keys[0] - want.best[i]) > 1e-9 * (1 + want.best[i])) {
      std::fprintf(stderr, "MISMATCH at rank %zu: search %.17g, reference %.17g\n", i + 1, got.designs[i].keys[0], want.best[i]);
      return 1;
    }
  std::printf("mitm%d %llu %.6f %.6f\n", stages, got.count, median(a), median(b));
  return 0;
}

std::string writeTemp(const std::string& text) {
  char path[] = "/tmp/gbxc-bench-XXXXXX.gbx";
  int fd = mkstemps(path, 4);
  if (fd < 0) std::exit(1);
  ::close(fd);
  std::ofstream(path) << text;
  return path;
}

// Every design of the 4-stage case as CSV: gbxc solve in-process, the reference's lines.
int listing(const std::string& side) {
  std::string spec = spurSpec(4, 100);
  spec.replace(spec.find("top 100"), 7, "top 1000000");
  std::string path = writeTemp(spec);
  auto gbxc = [&](size_t& bytes) {
    CountingBuf buf;
    std::ostream out(&buf);
    std::ostringstream err;
    auto t0 = Clock::now();
    int rc = driver::run({"solve", path, "--format", "csv", "--no-timings", "--quiet"}, out, err);
    if (rc != 0) {
      std::fputs(err.str().c_str(), stderr);
      std::exit(1);
    }
    bytes = buf.bytes;
    return seconds(t0);
  };
  auto reference = [&](size_t& bytes, unsigned long long& count) {
    std::FILE* f = std::fopen("/dev/null", "w");
    auto t0 = Clock::now();
    auto r = bench::mitmReference(4, 100, 0, f);
    double dt = seconds(t0);
    count = r.count;
    bytes = r.written;
    std::fclose(f);
    return dt;
  };
  size_t gb = 0, rb = 0;
  unsigned long long count = 0;
  if (side == "gbxc") {
    double t = gbxc(gb);
    std::printf("list4-gbxc %.3f %zu %.1f\n", t, gb, peakMiB());
  } else if (side == "ref") {
    double t = reference(rb, count);
    std::printf("list4-ref %llu %.3f %zu %.1f\n", count, t, rb, peakMiB());
  } else {
    std::vector<double> a, b;
    for (int rep = 0; rep < 3; ++rep) {
      a.push_back(gbxc(gb));
      b.push_back(reference(rb, count));
    }
    std::printf("list4 %llu %.3f %.3f %zu %zu\n", count, median(a), median(b), gb, rb);
  }
  std::remove(path.c_str());
  return 0;
}

// The helical top 10: pruned against exhaustive.
int helical(int jobs) {
  Compiled c = compileSpec(helicalSpec(), "Helical3");
  rt::SearchOptions opt;
  opt.top = 10;
  std::vector<double> a;
  rt::SearchResult pruned;
  for (int rep = 0; rep < 3; ++rep) {
    auto t0 = Clock::now();
    pruned = rt::search(*c.model, opt);
    a.push_back(seconds(t0));
  }
  rt::SearchOptions all = opt;
  all.exhaustive = true;
  all.jobs = jobs;
  auto t0 = Clock::now();
  auto full = rt::search(*c.model, all);
  double te = seconds(t0);
  bool same = full.count == pruned.count && full.designs.size() == pruned.designs.size();
  for (size_t i = 0; same && i < full.designs.size(); ++i)
    same = full.designs[i].choice == pruned.designs[i].choice && full.designs[i].keys == pruned.designs[i].keys;
  if (!same) {
    std::fprintf(stderr, "MISMATCH: the pruned top 10 differs from the exhaustive one (%llu, %llu designs)\n", pruned.count, full.count);
    for (size_t i = 0; i < std::max(full.designs.size(), pruned.designs.size()); ++i) {
      auto show = [&](const rt::SearchResult& r) {
        std::string t;
        if (i < r.designs.size()) {
          for (int v : r.designs[i].choice) t += fmt::format("{} ", v);
          t += fmt::format("{:.17g}", r.designs[i].keys.empty() ? 0.0 : r.designs[i].keys[0]);
        }
        return t;
      };
      std::fprintf(stderr, "%2zu  %s  |  %s\n", i + 1, show(pruned).c_str(), show(full).c_str());
    }
    return 1;
  }
  std::printf("helical %llu %.3f %.3f %.1f\n", pruned.count, median(a), te, peakMiB());
  return 0;
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
  if (which == "mitm3" || which == "mitm4") return mitm(which[4] - '0');
  if (which == "ref3" || which == "ref4") {
    auto t0 = Clock::now();
    auto r = bench::mitmReference(which[3] - '0', 100, 100);
    std::printf("%s %llu %.4f %.1f\n", which.c_str(), r.count, seconds(t0), peakMiB());
    return 0;
  }
  if (which == "list4") return listing("both");
  if (which == "list4-gbxc") return listing("gbxc");
  if (which == "list4-ref") return listing("ref");
  if (which == "helical") return helical(jobs);
  if (which == "check") {
    // The front end alone, in-process: parse, check, lower the paper's two-stage spec.
    std::string spec = readSpec("thruster_two_stage.gbx");
    std::vector<double> t;
    for (int rep = 0; rep < 200; ++rep) {
      auto t0 = Clock::now();
      auto c = driver::compileText("thruster_two_stage.gbx", spec);
      t.push_back(seconds(t0));
      if (!c->ok()) return 1;
    }
    std::printf("check %.6f\n", median(t));
    return 0;
  }
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
  Compiled compiled = compileSpec(text, gearbox);
  const rt::Model& model = *compiled.model;
  rt::SearchOptions opt;
  opt.jobs = jobs;
  opt.top = argc > 3 ? std::atoll(argv[3]) : 100;  // a third argument: how many designs to keep
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
