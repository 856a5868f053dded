// The join's half list: every canonical tuple once, in order of its ratio product, and its
// bounds the same as a scan's; also where ratios are equal or a few units of the last place
// apart (one run, one bucket), and with a reach that leaves entries out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "search/HalfList.h"

using gbx::rt::HalfList;

namespace {

using Ratios = std::vector<std::vector<double>>;

// The tuples a list must hold: products of stages [from, to), canonical where `ordered` asks.
std::multiset<double> tuples(const Ratios& r, const std::vector<std::pair<int, int>>& ordered, int from, int to,
                             const std::vector<std::pair<double, double>>* reach = nullptr) {
  std::multiset<double> out;
  std::vector<size_t> at(static_cast<size_t>(to - from), 0);
  for (;;) {
    bool canon = true;
    for (const auto& [a, b] : ordered)
      if (a >= from && b < to && at[static_cast<size_t>(a - from)] > at[static_cast<size_t>(b - from)]) canon = false;
    double p = 1;
    for (int s = from; s < to; ++s)
      p *= r[static_cast<size_t>(s)][at[static_cast<size_t>(s - from)]];
    if (canon && reach && at[0] < reach->size()) canon = p >= (*reach)[at[0]].first && p <= (*reach)[at[0]].second;
    if (canon) out.insert(p);
    int s = to - from - 1;
    for (; s >= 0; --s)
      if (++at[static_cast<size_t>(s)] < r[static_cast<size_t>(from + s)].size()) break;
    if (s < 0) return out;
    for (size_t t = static_cast<size_t>(s) + 1; t < at.size(); ++t)
      at[t] = 0;
  }
}

void expectWhole(const HalfList& h, const std::multiset<double>& want) {
  ASSERT_TRUE(h.error().empty()) << h.error();
  ASSERT_EQ(h.size(), want.size());
  std::vector<double> got;
  for (size_t e = 0; e < h.size(); ++e)
    got.push_back(h.ratio(e));
  for (size_t e = 1; e < got.size(); ++e)
    ASSERT_LE(got[e - 1], got[e]) << "entry " << e;
  EXPECT_EQ(std::multiset<double>(got.begin(), got.end()), want);
  // Bounds against a scan, at every entry's ratio and between them.
  std::vector<double> probes(got.begin(), got.end());
  for (size_t e = 0; e + 1 < got.size(); e += 7)
    probes.push_back(0.5 * (got[e] + got[e + 1]));
  probes.push_back(got.front() / 2);
  probes.push_back(got.back() * 2);
  for (double v : probes) {
    size_t lo = static_cast<size_t>(std::lower_bound(got.begin(), got.end(), v) - got.begin());
    size_t hi = static_cast<size_t>(std::upper_bound(got.begin(), got.end(), v) - got.begin());
    ASSERT_EQ(h.lowerBound(v), lo) << v;
    ASSERT_EQ(h.upperBound(v), hi) << v;
  }
}

} // namespace

TEST(HalfList, HoldsEveryCanonicalPairInOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(1.05, 8.0);
  Ratios r(2);
  for (auto& list : r) {
    for (int i = 0; i < 300; ++i)
      list.push_back(u(rng));
    std::sort(list.begin(), list.end());
  }
  r[1] = r[0]; // equal stages, enumerated once: many equal products
  std::vector<std::pair<int, int>> ordered = {{0, 1}};
  expectWhole(HalfList::build(r, ordered, 0, 2), tuples(r, ordered, 0, 2));
  // Three stages, not canonical: a longer list of products in another code layout.
  Ratios three = {std::vector<double>(r[0].begin(), r[0].begin() + 40),
                  std::vector<double>(r[0].begin() + 40, r[0].begin() + 80),
                  std::vector<double>(r[0].begin() + 80, r[0].begin() + 120)};
  expectWhole(HalfList::build(three, {}, 0, 3), tuples(three, {}, 0, 3));
}

TEST(HalfList, NearlyEqualRatiosFallInOneRunAndStayInOrder) {
  // Products a few units of the last place apart: their keys span less than the runs the
  // count asks for, so the list is one run with one bucket (no shift below zero).
  Ratios r(2);
  for (int i = 0; i < 120; ++i) {
    double x = 1.5;
    for (int k = 0; k < i % 3; ++k)
      x = std::nextafter(x, 2.0);
    r[0].push_back(x);
    r[1].push_back(x);
  }
  std::sort(r[0].begin(), r[0].end());
  std::sort(r[1].begin(), r[1].end());
  expectWhole(HalfList::build(r, {}, 0, 2), tuples(r, {}, 0, 2));
  // With a reach that ends inside them: entries past it are left out, and one that rounds
  // onto the bound is kept.
  const double mid = r[0][60] * r[1][60];
  std::vector<std::pair<double, double>> reach(r[0].size(), {0.0, mid});
  expectWhole(HalfList::build(r, {}, 0, 2, &reach), tuples(r, {}, 0, 2, &reach));
}
