// Every example spec's HTML report in a real browser (headless Chromium): the page is
// not blank, and the browser's DOM holds each gearbox's section, its tables and every plot.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "driver/Driver.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Chromium as the set-up script installs it; run as root in CI, hence --no-sandbox.
int chromium(const std::string& args) {
  return std::system(("timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars " + args + " >/dev/null 2>&1").c_str());
}

} // namespace

TEST(Browser, EverySpecsHtmlRendersWithItsSectionsAndPlots) {
  ASSERT_EQ(std::system("command -v chromium >/dev/null 2>&1"), 0) << "chromium is missing: run scripts/setup.sh";
  fs::path d = fs::temp_directory_path() / ("gbxc-browser-" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  // The reference: a blank page's screenshot, taken in the same run.
  std::ofstream(d / "blank.html") << "<!DOCTYPE html><html><body></body></html>\n";
  ASSERT_EQ(chromium("--window-size=1280,1600 --screenshot=" + (d / "blank.png").string() + " file://" + (d / "blank.html").string()), 0);
  auto blank = fs::file_size(d / "blank.png");
  int specs = 0;
  for (const auto& e : fs::directory_iterator(fs::path(GBX_SOURCE_DIR) / "specs")) {
    if (e.path().extension() != ".gbx") continue;
    ++specs;
    std::string name = e.path().stem().string();
    std::ostringstream out, err;
    // The optimiser cut to a few iterations per candidate: the page has the same sections
    // and plots, and the full run is the marine spec's golden file.
    driver::TestSettings cut;
    cut.optimiserIterations = 6;
    int status = driver::run({"solve", "--format", "html", "--no-timings", "--quiet", e.path().string()}, out, err, cut);
    ASSERT_EQ(status, 0) << name << ": " << err.str();
    fs::path html = d / (name + ".html"), png = d / (name + ".png"), dom = d / (name + ".dom");
    std::ofstream(html, std::ios::binary) << out.str();
    ASSERT_EQ(chromium("--window-size=1280,1600 --screenshot=" + png.string() + " file://" + html.string()), 0) << name;
    EXPECT_GT(fs::file_size(png), 3 * blank) << name << ": the screenshot is (nearly) blank";
    ASSERT_EQ(chromium("--dump-dom file://" + html.string() + " > " + dom.string() + " 2>/dev/null; true"), 0);
    std::string page = out.str(), parsed = read(dom);
    // The browser's DOM holds what the report wrote: each gearbox's heading, its tables,
    // every plot as an SVG element.
    EXPECT_GT(count(page, "<h2>"), 0u) << name;
    EXPECT_EQ(count(parsed, "<h2>"), count(page, "<h2>")) << name;
    EXPECT_EQ(count(parsed, "</table>"), count(page, "</table>")) << name;
    EXPECT_EQ(count(parsed, "<svg"), count(page, "<svg")) << name;
    EXPECT_EQ(count(parsed, "</svg>"), count(page, "<svg")) << name << ": a plot is not closed";
  }
  EXPECT_GE(specs, 6);
  fs::remove_all(d);
}
