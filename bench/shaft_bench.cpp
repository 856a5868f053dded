// Cost of the shaft model: a static solve of a shaft of 200 elements (199 stations: steps
// and loads), its first natural frequencies on 200 elements, and one ISO 6336 mesh rating
// in the same process as the yardstick a search already pays per design.
// Prints "static <us>", "modes <us>" (200 elements and the default mesh), "rating <us>" and the
// ratios to the rating.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ExamplePair.h"
#include "rating/Iso6336.h"
#include "shaft/Beam.h"

using namespace gbx::rt;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class F> double microseconds(F&& f, int reps) {
  std::vector<double> per;
  for (int r = 0; r < 7; ++r) {
    auto t0 = Clock::now();
    for (int i = 0; i < reps; ++i)
      f();
    per.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / reps);
  }
  return median(per);
}

shaft::Model shaft200() {
  shaft::Model m;
  const int n = 200;
  for (int i = 0; i < n; ++i)
    m.sections.push_back({i * 2e-3, (i + 1) * 2e-3, i % 2 ? 0.05 : 0.052, i % 3 ? 0.0 : 0.01});
  m.bearings = {{"A", 0.02}, {"B", 0.38, 5e8, true}};
  for (int i = 1; i < n; i += 2)
    m.loads.push_back({i * 2e-3, 10.0 * i, -5.0 * i, 1.0, 0, 0, i == 1 ? 100.0 : -100.0 / 99});
  m.elements = n;
  return m;
}

} // namespace

int main() {
  shaft::Model m = shaft200();
  double sink = 0;
  double st = microseconds([&] { sink += shaft::solve(m).v[7]; }, 200);
  double modes = microseconds([&] { sink += shaft::naturalFrequencies(m, 3)[0]; }, 3);
  shaft::Model coarse = m;
  coarse.elements = 40; // the default mesh of the natural frequencies
  double modes40 = microseconds([&] { sink += shaft::naturalFrequencies(coarse, 3)[0]; }, 10);
  rating::PairInput in = trExample1Pair();
  double rate = microseconds([&] { sink += rating::rate(in).gear[0].SH; }, 2000);
  std::printf("static %.1f us (%zu stations)\n", st, shaft::solve(m).x.size());
  std::printf("modes %.0f us (200 elements), %.0f us (%zu nodes, the default mesh)\n", modes, modes40,
              shaft::meshNodes(coarse, true).size());
  std::printf("rating %.2f us\nstatic/rating %.1f\nmodes/rating %.0f (200 elements), %.0f (default)\n", rate, st / rate,
              modes / rate, modes40 / rate);
  return sink == 42 ? 1 : 0;
}
