// Cost of the ISO 6336 rating: one mesh rated (ISO/TR 6336-30 Example 1's pair), and a
// search with and without a strength rule on the same candidates, in one process.
// Prints: "mesh <ns per rating>" and "search <candidates rated> <s with> <s without>".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ExamplePair.h"
#include "driver/Driver.h"
#include "rating/Iso6336.h"
#include "search/Search.h"

using namespace gbx;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string spec(bool strength) {
  return std::string(R"(import materials;
gearbox G {
  stage s1: helical {
    pinion.z in 14..150; wheel.z in 40..600;
    normal_module = 3 mm; helix_angle = 12 deg; face_width = 40 mm;
    material = steel_18CrNiMo7_6; accuracy = 6;
    rating { life = 20000 h; lubricant { viscosity_40 = 220 mm^2/s; } roughness { flank = 0.8 um; root = 3 um; } }
    require ratio in 2.5..4.5;
)") + (strength ? "    require pinion.contact_safety >= 1.1;\n" : "") + R"(  }
  operating { input_speed = 1500 rpm; input_torque = 250 N*m; }
}
)";
}

} // namespace

int main() {
  rt::rating::PairInput in = trExample1Pair();
  std::vector<double> per;
  double sink = 0;
  for (int rep = 0; rep < 7; ++rep) {
    auto t0 = Clock::now();
    for (int i = 0; i < 20000; ++i) {
      in.torque1 = 9000 + i * 1e-3;
      sink += rt::rating::rate(in).gear[0].SH;
    }
    per.push_back(std::chrono::duration<double>(Clock::now() - t0).count() / 20000);
  }
  std::printf("mesh %.1f %g\n", median(per) * 1e9, sink > 0 ? 1.0 : 0.0);
  double times[2];
  size_t rated = 0;
  for (int strength = 1; strength >= 0; --strength) {
    auto c = driver::compileText("bench.gbx", spec(strength));
    if (!c->ok()) {
      std::fputs(c->diags.renderText(c->sources).c_str(), stderr);
      return 1;
    }
    rt::Model m(c->program, c->program.gearboxes[0]);
    std::vector<double> t;
    for (int rep = 0; rep < 5; ++rep) {
      auto t0 = Clock::now();
      auto r = rt::search(m, {});
      t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      for (const auto& f : r.funnel)
        if (strength && f.rule.find("contact_safety") != std::string::npos) rated = static_cast<size_t>(f.before);
    }
    times[strength] = median(t);
  }
  std::printf("search %zu %.6f %.6f\n", rated, times[1], times[0]);
  return 0;
}
