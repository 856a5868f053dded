#include <sstream>
#include <algorithm>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "report/Progress.h"
#include "report/Formats.h"
#include "report/Svg.h"

using namespace gbx;

TEST(ReportFormats, OneRowPerNameTextFirst) {
  auto formats = rt::reportFormats();
  ASSERT_FALSE(formats.empty());
  EXPECT_EQ(formats.front().name, "text");
  EXPECT_EQ(formats.front().extension, "txt");
  std::set<std::string_view> names;
  for (const auto& f : formats) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    EXPECT_NE(f.render, nullptr) << f.name;
    EXPECT_EQ(rt::findReportFormat(f.name), &f);
  }
  EXPECT_EQ(rt::findReportFormat("yaml"), nullptr);
}

TEST(Svg, ASeriesWithoutALineDrawsItsPointsOnly) {
  rt::SvgChart c;
  c.series.push_back({"cloud", {1, 2, 3}, {3, 1, 2}, true, false});
  c.series.push_back({"front", {1, 2}, {1, 2}, true});
  std::string svg = rt::renderSvg(c);
  EXPECT_EQ(svg.find("<polyline fill=\"none\" stroke=\"#1f77b4\""), std::string::npos) << "the cloud has no line";
  EXPECT_NE(svg.find("<polyline fill=\"none\" stroke=\"#d62728\""), std::string::npos) << "the front keeps its line";
  EXPECT_NE(svg.find("<circle"), std::string::npos);
}

// The bar ends at 100 % with a newline, whether the work said 1.0 or stopped short.
TEST(Progress, EndsAtOneHundredPercentWithANewline) {
  std::ostringstream a;
  {
    rt::ProgressBar bar(a, "G");
    bar.update(0.1);
    bar.update(0.97);
  }  // the work stopped at 97 %: the bar still finishes
  std::string sa = a.str();
  EXPECT_EQ(sa.substr(sa.size() - 5), "100%\n") << sa;
  EXPECT_EQ(std::count(sa.begin(), sa.end(), '\n'), 1);

  std::ostringstream b;
  {
    rt::ProgressBar bar(b, "G");
    bar.update(0.5);
    bar.update(1.0);
    bar.update(0.7);  // after the end: nothing more
  }
  std::string sb = b.str();
  EXPECT_EQ(sb.substr(sb.size() - 5), "100%\n") << sb;
  EXPECT_EQ(std::count(sb.begin(), sb.end(), '\n'), 1);

  std::ostringstream c;
  { rt::ProgressBar bar(c, "G"); }  // never drawn: prints nothing
  EXPECT_TRUE(c.str().empty());
}

// Axes carry round ticks (1, 2 or 5 times a power of ten), and an amplitude axis starts at zero.
TEST(Svg, RoundTicksAndAnAxisFromZero) {
  rt::SvgChart c;
  c.title = "spectrum";
  c.series.push_back({"amplitude", {280, 840, 1400, 2800}, {1050, 5562, 8824, 10}, false});
  std::string svg = rt::renderSvg(c);
  for (const char* label : {">0<", ">2000<", ">4000<", ">6000<", ">8000<", ">1000<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label << "\n" << svg;
  EXPECT_EQ(svg.find("1504"), std::string::npos);
  EXPECT_EQ(svg.find(">-"), std::string::npos) << "no negative tick on an axis of amplitudes";
}

TEST(Svg, SpectrumTicksAtMeshOrders) {
  rt::SvgChart c;
  c.series.push_back({"", {280, 560, 840, 1400, 2800}, {1000, 1200, 5562, 8824, 10}, false});
  for (int k = 1; k <= 10; ++k) c.xTicks.emplace_back(280.0 * k, std::to_string(k) + "x");
  c.xTicks.emplace_back(280.0 * 20, "20x");  // outside the data: not drawn
  std::string svg = rt::renderSvg(c);
  for (const char* label : {">1x<", ">3x<", ">5x<", ">10x<"}) EXPECT_NE(svg.find(label), std::string::npos) << label;
  EXPECT_EQ(svg.find(">20x<"), std::string::npos);
  EXPECT_EQ(svg.find(">1000<"), std::string::npos) << "no round-value ticks beside the orders";
}
