#include <set>
#include <string>

#include <gtest/gtest.h>

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
