// Every example spec's HTML report in a real browser (headless Chromium): the page is
// not blank, and the browser's DOM holds each gearbox's section, its tables and every plot.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "ReadFile.h"

#include "driver/Driver.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
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
    std::string page = out.str(), parsed = readFile(dom);
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

namespace {

// Pages of a PDF: its page objects.
int pdfPages(const std::string& pdf) {
  int n = 0;
  for (size_t at = pdf.find("/Type"); at != std::string::npos; at = pdf.find("/Type", at + 1)) {
    size_t p = at + 5;
    while (p < pdf.size() && (pdf[p] == ' ' || pdf[p] == '\n' || pdf[p] == '\r')) ++p;
    if (pdf.compare(p, 5, "/Page") == 0 && (p + 5 >= pdf.size() || pdf[p + 5] != 's')) ++n;
  }
  return n;
}

// The measurement a test adds to a copy of a report: the right edge of the widest element
// that is not inside a scrolling box, at a 1280 px window.
const char* kMeasure = R"(<script>
(function(){var w=0;document.querySelectorAll('body *').forEach(function(e){if(e.parentElement&&e.parentElement.closest('.scroll'))return;
var r=e.getBoundingClientRect();if(r.width>0)w=Math.max(w,r.right);});
document.body.setAttribute('data-widest',String(Math.ceil(w)));
document.body.setAttribute('data-page-width',String(document.documentElement.scrollWidth));})();
</script>)";

int attribute(const std::string& dom, const std::string& name) {
  size_t at = dom.find(name + "=\"");
  return at == std::string::npos ? -1 : std::stoi(dom.substr(at + name.size() + 2));
}

} // namespace

// docs/reports.md in a browser, for the reports the README shows: the body opens with the
// summary; in each gearbox's part its plots come before its tables; nothing is wider than a
// 1280 px window (wide tables scroll inside their box); printed to PDF (A4) the report takes a
// bounded number of pages.
TEST(Browser, ReportsReadAsDocumentsOnScreenAndOnPaper) {
  ASSERT_EQ(std::system("command -v chromium >/dev/null 2>&1"), 0) << "chromium is missing: run scripts/setup.sh";
  fs::path d = fs::temp_directory_path() / ("gbxc-document-" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  // Spec, and the pages its print layout may take (fonts differ between machines).
  const std::vector<std::tuple<std::string, int, int>> specs = {
      {"spur_resonance", 5, 12}, {"turbine_modification", 24, 52}, {"electric_cylinder", 8, 18}};
  for (const auto& [name, fewest, most] : specs) {
    std::ostringstream out, err;
    int status = driver::run({"solve", "--format", "html", "--no-timings", "--quiet", std::string(GBX_SOURCE_DIR) + "/specs/" + name + ".gbx"},
                             out, err);
    ASSERT_EQ(status, 0) << name << ": " << err.str();
    std::string page = out.str();
    // The summary first, then each gearbox's plots before its tables.
    size_t body = page.find("<body>");
    ASSERT_NE(body, std::string::npos);
    const std::string opening = "<body>\n<section class=\"summary\">";
    EXPECT_EQ(page.compare(body, opening.size(), opening), 0) << name << ": the body does not open with the summary";
    size_t summaryEnd = page.find("</section>", body);
    for (size_t at = page.find("<section class=\"gearbox\"", summaryEnd); at != std::string::npos;
         at = page.find("<section class=\"gearbox\"", at + 1)) {
      size_t end = page.find("</section>", at);
      std::string part = page.substr(at, end - at);
      size_t svg = part.find("<svg"), table = part.find("<table");
      if (svg != std::string::npos && table != std::string::npos) {
        EXPECT_LT(svg, table) << name << ": a table comes before a plot";
      }
    }
    // A folded table is whole on paper: its print copy holds every row.
    if (page.find("<details><summary>all ") != std::string::npos) {
      size_t print = page.find("<div class=\"print\">");
      ASSERT_NE(print, std::string::npos) << name << ": a folded table has no copy for print";
      size_t rows = count(page.substr(print, page.find("</div>", print) - print), "<tr>");
      EXPECT_GT(rows, 31u) << name << ": the printed table is cut";
    }
    // Nothing wider than the window.
    fs::path html = d / (name + ".html"), measured = d / (name + ".measured.html"), dom = d / (name + ".dom"), pdf = d / (name + ".pdf");
    std::ofstream(html, std::ios::binary) << page;
    std::string copy = page;
    copy.insert(copy.rfind("</body>"), kMeasure);
    std::ofstream(measured, std::ios::binary) << copy;
    ASSERT_EQ(chromium("--window-size=1280,1000 --dump-dom file://" + measured.string() + " > " + dom.string() + " 2>/dev/null; true"), 0);
    std::string parsed = readFile(dom);
    int widest = attribute(parsed, "data-widest"), pageWidth = attribute(parsed, "data-page-width");
    ASSERT_GT(widest, 0) << name << ": the measurement did not run";
    EXPECT_LE(widest, 1280) << name << ": an element reaches past the window's right edge";
    EXPECT_LE(pageWidth, 1280) << name << ": the page scrolls sideways";
    // On paper.
    ASSERT_EQ(chromium("--no-pdf-header-footer --print-to-pdf=" + pdf.string() + " file://" + html.string()), 0) << name;
    int pages = pdfPages(readFile(pdf));
    EXPECT_GE(pages, fewest) << name;
    EXPECT_LE(pages, most) << name;
  }
  fs::remove_all(d);
}

namespace {

// Counts, at a 1280 px window, the safety cells (a column headed `…safety…` of a design
// table, a `…safety…` row of a rating's results, the summary's safeties) and those whose
// right edge lies past the window or past the visible part of their scrolling box.
const char* kSafeties = R"(<script>
(function(){var n=0,hidden=0;
function check(td){n++;var r=td.getBoundingClientRect(),box=td.closest('.scroll'),right=window.innerWidth;
if(box)right=Math.min(right,box.getBoundingClientRect().right);if(r.right>right+1||r.width<=0)hidden++;}
document.querySelectorAll('table').forEach(function(t){var heads=t.querySelectorAll('thead th');
t.querySelectorAll('tbody tr, tr').forEach(function(tr){var cells=tr.querySelectorAll('td');if(!cells.length)return;
cells.forEach(function(td,i){var h=heads[i]?heads[i].textContent:'';var first=cells[0].textContent;
if(/safety/.test(h)||(i>0&&i<3&&/safety/.test(first)&&td.textContent.trim()!==''))check(td);});});});
document.body.setAttribute('data-safeties',String(n));document.body.setAttribute('data-hidden',String(hidden));})();
</script>)";

// A two-stage reducer sized by both stages' safeties, with the safeties and the objective as
// columns: its design table is wider than a 1280 px window.
const char* kReducer = R"(import materials;
gearbox Reducer {
  stage hs: helical {
    pinion.z in 23..28;  wheel.z in 130..140;  normal_module in {2.5 mm, 3 mm};  helix_angle = 12 deg;
    face_width in 30..90 mm;  material = steel_18CrNiMo7_6;  accuracy = 6;
    rating { application_factor = 1.25; life = 20000 h; lubricant { viscosity_40 = 150 mm^2/s; }
             roughness { flank = 0.6 um; root = 3.0 um; } min_safety { contact = 1.2; bending = 1.5; } }
  }
  stage ls: helical {
    pinion.z in 28..30;  wheel.z in 100..128;  normal_module = 4 mm;  helix_angle = 10 deg;
    face_width in 50..140 mm;  material = steel_18CrNiMo7_6;  accuracy = 6;
    rating { application_factor = 1.25; life = 20000 h; lubricant { viscosity_40 = 150 mm^2/s; }
             roughness { flank = 0.6 um; root = 3.0 um; } min_safety { contact = 1.2; bending = 1.5; } }
  }
  operating { input_speed = 1480 rpm; power = 55 kW; }
  require ratio == 22 +- 2%;
  require forall s in stages: s.pinion.contact_safety >= 1.2 and s.wheel.contact_safety >= 1.2;
  require forall s in stages: s.pinion.bending_safety >= 1.5 and s.wheel.bending_safety >= 1.5;
  minimize hs.mass + ls.mass;
  report { top 8; columns hs.pinion.contact_safety, hs.wheel.contact_safety, hs.pinion.bending_safety, hs.wheel.bending_safety,
                   ls.pinion.contact_safety, ls.wheel.contact_safety, ls.pinion.bending_safety, ls.wheel.bending_safety; }
}
)";

} // namespace

// At a 1280 px window every safety of the report is in view without scrolling inside a
// table (a wide design table is cut into groups of columns); printed, every page carries its
// number and the spec's name, and the folded influence factors are on paper.
TEST(Browser, EverySafetyInViewAt1280AndPagesNumbered) {
  ASSERT_EQ(std::system("command -v chromium >/dev/null 2>&1"), 0) << "chromium is missing: run scripts/setup.sh";
  ASSERT_EQ(std::system("command -v pdftotext >/dev/null 2>&1"), 0) << "pdftotext is missing: run scripts/setup.sh";
  fs::path d = fs::temp_directory_path() / ("gbxc-safeties-" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "reducer.gbx") << kReducer;
  const std::vector<fs::path> specs = {d / "reducer.gbx", fs::path(GBX_SOURCE_DIR) / "specs" / "nrel5mw_planetary_stage.gbx"};
  for (const auto& spec : specs) {
    std::string name = spec.stem().string();
    std::ostringstream out, err;
    ASSERT_EQ(driver::run({"solve", "--format", "html", "--no-timings", "--quiet", spec.string()}, out, err), 0) << name << err.str();
    std::string page = out.str();
    std::string copy = page;
    copy.insert(copy.rfind("</body>"), kSafeties);
    fs::path measured = d / (name + ".measured.html"), dom = d / (name + ".dom"), html = d / (name + ".html"), pdf = d / (name + ".pdf");
    std::ofstream(measured, std::ios::binary) << copy;
    std::ofstream(html, std::ios::binary) << page;
    ASSERT_EQ(chromium("--window-size=1280,1000 --dump-dom file://" + measured.string() + " > " + dom.string() + " 2>/dev/null; true"), 0);
    std::string parsed = readFile(dom);
    EXPECT_GE(attribute(parsed, "data-safeties"), 8) << name << ": the measurement found too few safeties";
    EXPECT_EQ(attribute(parsed, "data-hidden"), 0) << name << ": a safety is out of view at 1280 px";
    ASSERT_EQ(chromium("--no-pdf-header-footer --print-to-pdf=" + pdf.string() + " file://" + html.string()), 0) << name;
    fs::path text = d / (name + ".txt");
    ASSERT_EQ(std::system(("pdftotext -layout " + pdf.string() + " " + text.string()).c_str()), 0);
    std::string paper = readFile(text);
    int pages = pdfPages(readFile(pdf));
    EXPECT_GE(pages, 2) << name;
    EXPECT_EQ(count(paper, " of " + std::to_string(pages)), static_cast<size_t>(pages)) << name << ": a page without its number\n" << paper;
    EXPECT_NE(paper.find("page 1 of " + std::to_string(pages)), std::string::npos) << name;
    EXPECT_GE(count(paper, name + ".gbx"), static_cast<size_t>(pages)) << name << ": a page without the title block";
    // Z_NT's method, a row of the folded influence factors.
    EXPECT_NE(paper.find("normal curve"), std::string::npos) << name << ": the folded factors are not on paper";
  }
  fs::remove_all(d);
}
