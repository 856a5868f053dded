#include <sstream>
#include <algorithm>
#include <set>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "report/Progress.h"
#include "report/Formats.h"
#include "report/Svg.h"
#include "report/Symbols.h"

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

  // Work that grows (more designs to decide) never sends the bar back: 99 % stays.
  std::ostringstream d;
  {
    rt::ProgressBar bar(d, "G");
    bar.update(0.99);
    bar.update(0.02);
    bar.update(0.5);
  }
  std::string sd = d.str();
  EXPECT_EQ(sd.find("  2%"), std::string::npos) << sd;
  EXPECT_EQ(sd.find(" 50%"), std::string::npos) << sd;
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

namespace {

struct Label {
  double left, right, top, bottom;
  std::string text;
};

// Every horizontal text of an SVG with its box, from its anchor and 7.8 px a character
// (12 px type; 14 px for the title); rotated text (the y label) is left out.
std::vector<Label> labels(const std::string& svg) {
  std::vector<Label> out;
  for (size_t at = svg.find("<text "); at != std::string::npos; at = svg.find("<text ", at + 1)) {
    size_t close = svg.find('>', at), end = svg.find("</text>", at);
    std::string tag = svg.substr(at, close - at), text = svg.substr(close + 1, end - close - 1);
    if (tag.find("rotate") != std::string::npos) continue;
    auto attr = [&](const char* name) {
      size_t p = tag.find(std::string(" ") + name + "=\"");
      return p == std::string::npos ? 0.0 : std::stod(tag.substr(p + std::char_traits<char>::length(name) + 3));
    };
    double x = attr("x"), y = attr("y"), size = tag.find(" font-size=\"") != std::string::npos ? attr("font-size") : 12;
    double w = 0.65 * size * static_cast<double>(text.size());  // as wide as Chromium draws it
    double left = tag.find("\"middle\"") != std::string::npos ? x - w / 2 : tag.find("\"end\"") != std::string::npos ? x - w : x;
    out.push_back({left, left + w, y - size * 0.8, y + size * 0.2, text});
  }
  return out;
}

} // namespace

// A sweep's marks close together (two jumps and a resonance within a few percent of the axis)
// and a legend of long entries: no label lies on another, on the legend, or off the picture.
TEST(Svg, LabelsNeverOverlapEachOtherOrTheLegend) {
  rt::SvgChart c;
  // A title as long as a whole-gearbox scene's: made smaller to fit, not cut at both ends.
  c.title = "ElectricCylinderBuilt: scene mechanism_fluctuating: spectrum(contact_force(planet_stage.sun_planet)) against speed";
  c.xLabel = "input_speed [rpm]";
  c.yLabel = "mesh.dynamic_factor";
  c.series.push_back({"mesh.dynamic_factor, stable", {9000, 12000, 13100, 18000}, {1.9, 2.1, 3.3, 1.9}});
  c.series.push_back({"unstable (dashed)", {11300, 13100}, {3.3, 2.1}, false, true, true});
  c.series.push_back({"a third entry whose label is rather long to force a second legend row", {9000, 18000}, {2, 2}});
  c.xMarks = {{13106, "jump"}, {11281, "jump"}, {13846, "f_mesh = f_n"}, {13500, "f_mesh = 2 f_n (parametric)"}};
  std::string svg = rt::renderSvg(c);
  auto ls = labels(svg);
  ASSERT_GE(ls.size(), 10u);
  double width = 720;
  for (size_t i = 0; i < ls.size(); ++i) {
    EXPECT_GE(ls[i].left, 0) << ls[i].text;
    EXPECT_LE(ls[i].right, width) << ls[i].text;
    for (size_t j = i + 1; j < ls.size(); ++j) {
      bool apart = ls[i].right <= ls[j].left || ls[j].right <= ls[i].left || ls[i].bottom <= ls[j].top || ls[j].bottom <= ls[i].top;
      EXPECT_TRUE(apart) << "`" << ls[i].text << "` overlaps `" << ls[j].text << "`";
    }
  }
}

// A curve flat to a few ulps (a steady speed) gets its ends as ticks, at once: no endless
// loop of steps too small to move the value.
TEST(Svg, AFlatCurveEndsAtOnce) {
  rt::SvgChart c;
  c.series.push_back({"flat", {0, 1, 2}, {1000.0, 1000.0000000000001, 1000.0}});
  c.series.push_back({"not a number", {0, std::numeric_limits<double>::infinity()}, {1, 2}});
  std::string svg = rt::renderSvg(c);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

// HTML and Markdown write symbols and units as engineers do; words with an underscore stay.
TEST(Symbols, SubscriptsGreekLettersAndUnits) {
  EXPECT_EQ(rt::symbolHtml("K_Hbeta"), "K<sub>Hβ</sub>");
  EXPECT_EQ(rt::symbolHtml("Z_eps"), "Z<sub>ε</sub>");
  EXPECT_EQ(rt::symbolHtml("Z_B, Z_D"), "Z<sub>B</sub>, Z<sub>D</sub>");
  EXPECT_EQ(rt::symbolHtml("sigma_Hlim [MPa]"), "σ<sub>Hlim</sub> [MPa]");
  EXPECT_EQ(rt::symbolHtml("Y_deltarelT"), "Y<sub>δrelT</sub>");
  EXPECT_EQ(rt::symbolHtml("X_alphabeta"), "X<sub>αβ</sub>");
  EXPECT_EQ(rt::symbolHtml("h_aP*, h_fP*"), "h<sub>aP</sub>*, h<sub>fP</sub>*");
  EXPECT_EQ(rt::symbolHtml("nu_40 [mm^2/s]"), "ν<sub>40</sub> [mm²/s]");
  EXPECT_EQ(rt::symbolHtml("contact_stress [MPa]"), "contact_stress [MPa]");
  EXPECT_EQ(rt::symbolHtml("load_cycles"), "load_cycles");
  EXPECT_EQ(rt::symbolHtml("Rz flank [um]"), "Rz flank [µm]");
  EXPECT_EQ(rt::unitHtml("N*m"), "N·m");
  EXPECT_EQ(rt::unitHtml("kg/m^3"), "kg/m³");
  EXPECT_EQ(rt::unitHtml("degC"), "°C");
  EXPECT_EQ(rt::unitHtml("viscosity_40 150 mm^2/s, 12 um"), "viscosity_40 150 mm²/s, 12 µm");
  EXPECT_EQ(rt::unitHtml("a <b>"), "a &lt;b&gt;");
}
