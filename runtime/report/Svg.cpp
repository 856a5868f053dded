#include "report/Svg.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

namespace gbx::rt {

namespace {

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else o += c;
  }
  return o;
}

std::string tick(double v) {
  if (v == 0) return "0";
  double a = std::fabs(v);
  // Whole numbers below a million as they are (speeds in rpm, forces in N).
  if (a < 1e6 && a >= 1 && v == std::round(v)) return fmt::format("{:.0f}", v);
  if (a >= 1e4 || a < 1e-3) return fmt::format("{:.1e}", v);
  return fmt::format("{:.4g}", v);
}

constexpr double kCharWidth = 7.8;  // the widest Chromium gives a 12 px sans-serif character
double labelWidth(const std::string& s) { return kCharWidth * static_cast<double>(s.size()) + 8; }

// Ticks: round values in steps of 1, 2 or 5 times a power of ten on a linear axis (about
// five of them), the decades on a logarithmic one.
std::vector<double> axisTicks(double lo, double hi, bool log) {
  std::vector<double> t;
  // A range of a few ulps has no round steps to speak of: its ends alone.
  if (!(hi - lo > 1e-9 * std::max({std::fabs(lo), std::fabs(hi), 1e-300}))) return {lo, hi};
  if (log && hi - lo >= 1.0) {
    for (double d = std::ceil(lo); d <= hi + 1e-9; d += std::max(1.0, std::floor((hi - lo) / 6.0))) t.push_back(d);
    return t;
  }
  double raw = (hi - lo) / 5.0, p = std::pow(10.0, std::floor(std::log10(raw))), step = 10 * p;
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw * 0.999) {
      step = m * p;
      break;
    }
  double first = std::ceil(lo / step - 1e-9);
  for (int k = 0; k < 40; ++k) {  // about five; the bound guards against a step lost in rounding
    double v = (first + k) * step;
    if (v > hi + 1e-9 * step) break;
    t.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
  }
  return t;
}

// The legend's entries below the plot: each one's x and row, side by side until a row is full.
std::vector<std::pair<double, double>> legendLayout(const SvgChart& c, double W, double L, double R) {
  std::vector<std::pair<double, double>> at;
  double x = L, row = 0;
  for (const auto& s : c.series) {
    if (s.label.empty()) continue;
    double w = labelWidth(s.label) + 22;
    if (x + w > W - R && x > L) x = L, ++row;
    at.emplace_back(x, row);
    x += w;
  }
  return at;
}

struct MarkLabel {
  double x;  // the label's centre
  int row;   // 0: the top row of the band above the plot
  const std::string* text;
};

// The marks' labels, left to right, each in the first row where it clears the label before it.
std::vector<MarkLabel> markLayout(const SvgChart& c, double x0, double x1, double W, double L, double R) {
  std::vector<MarkLabel> out;
  if (c.logX) return out;
  std::vector<std::pair<double, const std::string*>> ms;
  for (const auto& [v, label] : c.xMarks)
    if (v >= x0 && v <= x1) ms.emplace_back(L + (v - x0) / (x1 - x0) * (W - L - R), &label);
  std::sort(ms.begin(), ms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> rowEnd;
  for (const auto& [X, label] : ms) {
    double w = labelWidth(*label);
    double left = std::max(2.0, std::min(X - w / 2, W - 2 - w));
    size_t row = 0;
    while (row < rowEnd.size() && rowEnd[row] > left) ++row;
    if (row == rowEnd.size()) rowEnd.push_back(0);
    rowEnd[row] = left + w + 4;
    out.push_back({left + w / 2, static_cast<int>(row), label});
  }
  return out;
}

} // namespace

std::string renderSvg(const SvgChart& c) {
  // Labels never overprint: the marks' labels sit in rows of a band above the plot, each row
  // taking a label only where it clears the one before it; the legend goes below the x axis,
  // its entries side by side in rows. The picture grows by what they need.
  const double W = 720, L = 80, R = 30, plotH = 300;
  std::vector<std::pair<double, double>> legendAt = legendLayout(c, W, L, R);
  double legendRows = legendAt.empty() ? 0 : legendAt.back().second + 1;
  auto tx = [&](double v) { return c.logX ? std::log10(v) : v; };
  auto ty = [&](double v) { return c.logY ? std::log10(v) : v; };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : c.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((c.logX && s.x[i] <= 0) || (c.logY && s.y[i] <= 0) || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, tx(s.x[i]));
      x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, ty(s.y[i]));
      y1 = std::max(y1, ty(s.y[i]));
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y0 -= 0.5, y1 += 0.5;
  // A linear y axis starts at zero unless the data sit far from it (a speed near its mean).
  bool fromZero = false, toZero = false;
  if (!c.logY && y0 > 0 && y0 <= y1 - y0) y0 = 0, fromZero = true;
  if (!c.logY && y1 < 0 && -y1 <= y1 - y0) y1 = 0, toZero = true;
  double pad = 0.05 * (y1 - y0);
  if (!fromZero) y0 -= pad;
  if (!toZero) y1 += pad;
  std::vector<MarkLabel> markLabels = markLayout(c, x0, x1, W, L, R);
  int markRows = 0;
  for (const auto& m : markLabels) markRows = std::max(markRows, m.row + 1);
  const double T = 40 + 15 * markRows, B = 60 + (legendRows > 0 ? 8 + 16 * legendRows : 0), H = T + plotH + B;
  auto px = [&](double v) { return L + (tx(v) - x0) / (x1 - x0) * (W - L - R); };
  auto py = [&](double v) { return H - B - (ty(v) - y0) / (y1 - y0) * (H - T - B); };
  std::string o = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" font-family=\"sans-serif\" "
      "font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      W, H, W, H);
  // The title in 14 px type, smaller where a long one would not fit the width.
  double titleSize = std::clamp((W - 20) / (0.65 * static_cast<double>(std::max<size_t>(c.title.size(), 1))), 8.0, 14.0);
  o += fmt::format("<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"{:.1f}\">{}</text>\n", W / 2, titleSize, esc(c.title));
  o += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n", L, T, W - L - R, H - T - B);
  std::vector<std::pair<double, std::string>> xt;
  if (!c.xTicks.empty() && !c.logX) {
    for (const auto& [v, label] : c.xTicks)
      if (v >= x0 - 1e-9 * (x1 - x0) && v <= x1 + 1e-9 * (x1 - x0)) xt.emplace_back(v, label);
  }
  if (xt.empty())
    for (double fx : axisTicks(x0, x1, c.logX)) xt.emplace_back(fx, tick(c.logX ? std::pow(10.0, fx) : fx));
  for (const auto& [fx, label] : xt) {
    double X = L + (fx - x0) / (x1 - x0) * (W - L - R);
    o += fmt::format("<line x1=\"{:.1f}\" y1=\"{}\" x2=\"{:.1f}\" y2=\"{}\" stroke=\"#ddd\"/>\n", X, T, X, H - B);
    o += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", X, H - B + 16, esc(label));
  }
  for (double fy : axisTicks(y0, y1, c.logY)) {
    double Y = H - B - (fy - y0) / (y1 - y0) * (H - T - B);
    o += fmt::format("<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>\n", L, Y, W - R, Y);
    o += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n", L - 6, Y + 4, tick(c.logY ? std::pow(10.0, fy) : fy));
  }
  o += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", (L + W - R) / 2, H - B + 36, esc(c.xLabel));
  o += fmt::format("<text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">{}</text>\n", (T + H - B) / 2,
                   (T + H - B) / 2, esc(c.yLabel));
  for (const auto& [v, label] : c.xMarks) {
    if (c.logX || v < x0 || v > x1) continue;
    double X = L + (v - x0) / (x1 - x0) * (W - L - R);
    o += fmt::format("<line x1=\"{:.1f}\" y1=\"{}\" x2=\"{:.1f}\" y2=\"{}\" stroke=\"#999\" stroke-dasharray=\"2,3\"/>\n", X, T, X, H - B);
  }
  for (const auto& m : markLabels)
    o += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\" fill=\"#555\">{}</text>\n", m.x, T - 5 - 15 * (markRows - 1 - m.row),
                     esc(*m.text));
  size_t legendRow = 0;
  for (size_t k = 0; k < c.series.size(); ++k) {
    const auto& s = c.series[k];
    const char* col = kColours[(s.colour >= 0 ? static_cast<size_t>(s.colour) : k) % 10];
    std::string pts;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((c.logX && s.x[i] <= 0) || (c.logY && s.y[i] <= 0) || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      pts += fmt::format("{:.2f},{:.2f} ", px(s.x[i]), py(s.y[i]));
      if (s.bars)
        o += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"3\"/>\n", px(s.x[i]),
                         py(std::max(0.0, y0)), px(s.x[i]), py(s.y[i]), col);
      // A series of one or two points is a marked design: draw it large.
      double radius = s.x.size() <= 2 ? 6.0 : 2.5;
      if (s.markers)
        o += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\" stroke=\"{}\"/>\n", px(s.x[i]), py(s.y[i]), radius,
                         col, radius > 3 ? "black" : col);
    }
    if (s.line && !s.bars)
      o += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{} points=\"{}\"/>\n", col, s.dashed ? "1.6" : "1.2",
                       s.dashed ? " stroke-dasharray=\"5,4\"" : "", pts);
    if (!s.label.empty()) {
      const auto& [lx, lrow] = legendAt[legendRow++];
      double ly = H - B + 52 + 16 * lrow;
      if (s.line)
        o += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-width=\"2\"{}/>\n", lx, ly - 4, lx + 16,
                         ly - 4, col, s.dashed ? " stroke-dasharray=\"5,4\"" : "");
      else
        o += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"/>\n", lx + 8, ly - 4, col);
      o += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"#333\">{}</text>\n", lx + 20, ly, esc(s.label));
    }
  }
  o += "</svg>\n";
  return o;
}

} // namespace gbx::rt
