// Every design of the benchmark's spur case as CSV, the way a program written for this one
// listing would do it, for whole-process comparisons with `gbxc solve SPEC --format csv`
// (bench/listing.sh):
//   listing_program STAGES [MAX_TEETH]
// Stages 3 or 4 of coprime pairs, pinion 12..MAX_TEETH below the wheel, interchangeable (one
// design per orbit: pair indices non-decreasing in ratio order), overall ratio within 1e-6
// of 13.36838, exactly: the meet-in-the-middle of mitm_fast.h. Ranked by |ratio - 13.36838|
// to 12 significant digits, then by the stages' ratios; written with std::to_chars, a
// megabyte at a time. Nothing here is shared with gbxc.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <vector>

#include "mitm_fast.h"

namespace {

__extension__ using i128 = __int128;

struct Row {
  double key;
  std::uint16_t at[4];
  std::uint64_t num, den;
};

// 12 significant digits, so that values equal but for their last bits tie.
double snapped(double v) {
  if (v == 0) return v;
  int e = static_cast<int>(std::floor(std::log10(std::fabs(v))));
  double scale = std::pow(10.0, 11 - e);
  return std::round(v * scale) / scale;
}

class Out {
public:
  ~Out() { flush(); }
  void text(const char* s) {
    while (*s)
      buf_[n_++] = *s++;
  }
  void ch(char c) { buf_[n_++] = c; }
  // Room for one more row; flushed before it could run short.
  template <class T> void num(T v) {
    n_ = static_cast<size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  void row() {
    if (n_ > buf_.size() - 512) flush();
  }
  void flush() {
    std::fwrite(buf_.data(), 1, n_, stdout);
    n_ = 0;
  }

private:
  std::vector<char> buf_ = std::vector<char>(size_t{1} << 20);
  size_t n_ = 0;
};

} // namespace

int main(int argc, char** argv) {
  const int stages = argc > 1 ? std::atoi(argv[1]) : 4, maxTeeth = argc > 2 ? std::atoi(argv[2]) : 100;
  if ((stages != 3 && stages != 4) || maxTeeth < 14 || maxTeeth > 300) {
    std::fprintf(stderr, "usage: listing_program 3|4 [MAX_TEETH 14..300]\n");
    return 2;
  }
  std::vector<bench::FastPair> pairs;
  const i128 tNum = 1336838, tDen = 100000; // 13.36838
  std::vector<Row> rows;
  mitmEach(stages, maxTeeth, pairs,
           [&](i128 num, i128 den, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
             i128 diff = num * tDen - tNum * den;
             if (diff < 0) diff = -diff;
             Row r{};
             r.key =
                 snapped(static_cast<double>(static_cast<long double>(diff) / static_cast<long double>(den * tDen)));
             r.at[0] = static_cast<std::uint16_t>(a);
             r.at[1] = static_cast<std::uint16_t>(b);
             r.at[2] = static_cast<std::uint16_t>(c);
             r.at[3] = static_cast<std::uint16_t>(d);
             auto g = std::gcd(static_cast<std::int64_t>(num), static_cast<std::int64_t>(den));
             r.num = static_cast<std::uint64_t>(num / g);
             r.den = static_cast<std::uint64_t>(den / g);
             rows.push_back(r);
           });
  std::sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) {
    if (x.key != y.key) return x.key < y.key;
    return std::lexicographical_compare(x.at, x.at + 4, y.at, y.at + 4);
  });
  Out out;
  out.text("gearbox,rank");
  for (int s = 0; s < stages; ++s) {
    char h[64];
    std::snprintf(h, sizeof h, ",s%d.pinion.z,s%d.wheel.z", s, s);
    out.text(h);
  }
  out.text(",ratio,abs((ratio - 13.36838)),ratio_exact\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    out.text("Bench,");
    out.num(i + 1);
    for (int s = 0; s < stages; ++s) {
      out.ch(',');
      out.num(pairs[r.at[s]].p);
      out.ch(',');
      out.num(pairs[r.at[s]].w);
    }
    out.ch(',');
    out.num(static_cast<double>(static_cast<long double>(r.num) / static_cast<long double>(r.den)));
    out.ch(',');
    i128 diff = static_cast<i128>(r.num) * tDen - tNum * static_cast<i128>(r.den);
    if (diff < 0) diff = -diff;
    out.num(static_cast<double>(static_cast<long double>(diff) /
                                static_cast<long double>(static_cast<i128>(r.den) * tDen)));
    out.ch(',');
    out.num(r.num);
    out.ch('/');
    out.num(r.den);
    out.ch('\n');
    out.row();
  }
  return 0;
}
