#include "dynamics/Statistics.h"

#include <algorithm>
#include <cmath>

namespace gbx::rt::dyn {

namespace {

using cat::SignalFn;
using W = std::vector<double>;

// A function-local table: ready whenever it is first asked for.
const std::vector<StatisticRow>& kRowsTable() {
  static const std::vector<StatisticRow> rows = {
    {SignalFn::Rms,
     [](const W& v) {
       double s = 0;
       for (double x : v) s += x * x;
       return std::sqrt(s / static_cast<double>(v.size()));
     }},
    {SignalFn::Peak,
     [](const W& v) {
       double s = 0;
       for (double x : v) s = std::max(s, std::fabs(x));
       return s;
     }},
    {SignalFn::Mean,
     [](const W& v) {
       double s = 0;
       for (double x : v) s += x;
       return s / static_cast<double>(v.size());
     }},
    {SignalFn::Min, [](const W& v) { return *std::min_element(v.begin(), v.end()); }},
    {SignalFn::Max, [](const W& v) { return *std::max_element(v.begin(), v.end()); }},
    // The full swing, max - min: what a fluctuating load or speed spans.
    {SignalFn::PeakToPeak,
     [](const W& v) {
       auto [lo, hi] = std::minmax_element(v.begin(), v.end());
       return *hi - *lo;
     }},
  };
  return rows;
}

} // namespace

const std::vector<StatisticRow>& statisticRows() { return kRowsTable(); }

Statistic statistic(cat::SignalFn id) {
  for (const auto& r : kRowsTable())
    if (r.id == id) return r.fn;
  return nullptr;
}

} // namespace gbx::rt::dyn
