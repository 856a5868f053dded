#pragma once
// The runtime side of the signal-function registry (compiler/catalogue/Signals.h): each
// number-valued function of a signal (`rms`, `peak`, …) as a statistic over the recorded
// window. Spectra and plots are series, made by the scene itself.
#include <vector>

#include "catalogue/Signals.h"

namespace gbx::rt::dyn {

using Statistic = double (*)(const std::vector<double>& window);

struct StatisticRow {
  cat::SignalFn id;
  Statistic fn;
};

const std::vector<StatisticRow>& statisticRows();
// The statistic of a number-valued function (nullptr for a spectrum or a plot).
Statistic statistic(cat::SignalFn id);

} // namespace gbx::rt::dyn
