#pragma once
// Small, dependency-free SVG charts: line plots and point clouds with linear or logarithmic axes.
#include <string>
#include <vector>

namespace gbx::rt {

struct SvgSeries {
  std::string label;
  std::vector<double> x, y;
  bool markers = false;
  bool line = true;  // false: the points alone, e.g. a cloud whose order means nothing
  bool dashed = false;  // an unstable branch
  int colour = -1;      // a fixed colour index (parts of one curve), -1: by position
  bool bars = false;    // a vertical line from zero at each point (a spectrum), no curve
};

struct SvgChart {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;
  std::vector<SvgSeries> series;
  // Ticks of the x axis at these values with these labels (a spectrum's mesh orders);
  // empty: round values.
  std::vector<std::pair<double, std::string>> xTicks;
  // Vertical marks across the plot (resonance speeds), with a label at the top.
  std::vector<std::pair<double, std::string>> xMarks;
};

std::string renderSvg(const SvgChart& chart);

} // namespace gbx::rt
