// The faster meet-in-the-middle (mitm_fast.h) as a program of its own, for whole-process
// comparisons with `gbxc solve` (bench/run.sh):
//   mitm_program STAGES [MAX_TEETH] [TOP]
// prints the count and the best TOP designs as CSV (teeth of each stage, ratio).
#include <cstdio>
#include <cstdlib>

#include "mitm_fast.h"

int main(int argc, char** argv) {
  int stages = argc > 1 ? std::atoi(argv[1]) : 4, maxTeeth = argc > 2 ? std::atoi(argv[2]) : 100;
  size_t top = argc > 3 ? static_cast<size_t>(std::atol(argv[3])) : 100;
  if ((stages != 3 && stages != 4) || maxTeeth < 14 || maxTeeth > 300) {
    std::fprintf(stderr, "usage: mitm_program 3|4 [MAX_TEETH 14..300] [TOP]\n");
    return 2;
  }
  bench::FastResult r = bench::mitmFast(stages, maxTeeth, top);
  std::printf("designs,%llu\n", r.count);
  for (const auto& x : r.best) {
    const auto& P = r.pairs;
    std::printf("%d,%d,%d,%d,%d,%d", P[x.a].p, P[x.a].w, P[x.b].p, P[x.b].w, P[x.c].p, P[x.c].w);
    if (stages == 4) std::printf(",%d,%d", P[x.d].p, P[x.d].w);
    double r1 = static_cast<double>(P[x.a].w) / P[x.a].p * P[x.b].w / P[x.b].p * P[x.c].w / P[x.c].p;
    if (stages == 4) r1 = r1 * P[x.d].w / P[x.d].p;
    std::printf(",%.17g\n", r1);
  }
  return 0;
}
