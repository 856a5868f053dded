// CSV writes the shortest decimal that reads back, in its header's unit, to the value: every
// fixed input of a spec, listed as a column, reads back from the CSV as exactly the double
// the spec's own literal gives (71 mm as `71`, not `70.99999999999999`).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "driver/Driver.h"
#include "report/Numbers.h"

using namespace gbx;

namespace {

// What the compiler makes of `const c = TEXT;`: the value's double in SI.
double readAsSpec(const std::string& text) {
  auto c = driver::compileText("c.gbx", "const c = " + text + ";\n");
  EXPECT_FALSE(c->diags.hasErrors()) << text << "\n" << c->diags.renderText(c->sources);
  for (const auto& k : c->program.consts)
    if (k.name == "c") return k.value.toDouble();
  ADD_FAILURE() << "no const in " << text;
  return 0;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ','))
    out.push_back(cell);
  return out;
}

// `s.face_width [mm]` -> name and unit.
std::pair<std::string, std::string> header(const std::string& h) {
  auto b = h.find(" [");
  if (b == std::string::npos) return {h, ""};
  return {h.substr(0, b), h.substr(b + 2, h.size() - b - 3)};
}

} // namespace

TEST(CsvRoundTrip, EveryFixedInputReadsBackExactly) {
  // Literals chosen so that their value in the header's unit is not a short double
  // (71 mm is 70.99999999999999 mm after SI and back), with π in deg and rpm.
  const std::map<std::string, std::string> written = {
      {"s.face_width", "71 mm"},    {"s.helix_angle", "12.3 deg"}, {"s.pressure_angle", "0.3490658503988659 rad"},
      {"input_speed", "1480 rpm"},  {"power", "55.1 kW"},          {"s.center_distance", "0.154884 m"},
      {"t.face_width", "0.0333 m"}, {"t.normal_module", "3.7 mm"},
  };
  std::string spec = R"(gearbox G {
  stage s: helical { pinion.z = 21; wheel.z = 80; normal_module = 3.25 mm; helix_angle = 12.3 deg;
                     face_width = 71 mm; pressure_angle = 0.3490658503988659 rad; center_distance = 0.154884 m; }
  stage t: spur { pinion.z = 20; wheel.z = 41; normal_module in {3.7 mm, 4.1 mm}; face_width = 0.0333 m; }
  operating { input_speed = 1480 rpm; power = 55.1 kW; }
  report { columns s.face_width, s.helix_angle, s.pressure_angle, input_speed, power, s.center_distance,
                   t.face_width, t.normal_module; }
}
)";
  auto path = std::filesystem::temp_directory_path() / "gbx_csv_round_trip.gbx";
  std::ofstream(path) << spec;
  std::ostringstream out, err;
  ASSERT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, out, err), 0) << err.str();
  std::filesystem::remove(path);
  std::stringstream lines(out.str());
  std::string head, first;
  std::getline(lines, head);
  std::getline(lines, first);
  auto names = split(head), cells = split(first);
  ASSERT_EQ(names.size(), cells.size());
  int checked = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    auto [name, unit] = header(names[i]);
    auto w = written.find(name);
    if (w == written.end()) continue;
    ++checked;
    EXPECT_EQ(cells[i].find_first_of("eE"), std::string::npos) << names[i] << " = " << cells[i];
    EXPECT_LE(cells[i].size(), 12u) << names[i] << " = " << cells[i] << " is not the shortest decimal";
    EXPECT_EQ(readAsSpec(cells[i] + " " + unit), readAsSpec(w->second))
        << names[i] << ": the CSV's " << cells[i] << " " << unit << " is not the spec's " << w->second;
  }
  // Each column once, and the set choice t.normal_module also in its own column.
  EXPECT_GE(checked, static_cast<int>(written.size()));
}

// Negative values and computed values (whose value in the unit is not a short decimal) read
// back too: the exact reading of each written number is the value itself.
TEST(CsvRoundTrip, NegativeAndComputedValuesReadBack) {
  EXPECT_EQ(rt::csvNumber(-0.071, "mm", 1e-3), "-71");
  EXPECT_EQ(rt::csvNumber(readAsSpec("-50 degC"), "degC", 1, 273.15), "-50");
  EXPECT_EQ(rt::csvNumber(readAsSpec("12.3 deg"), "deg", 3.14159265358979323846 / 180), "12.3");
  EXPECT_EQ(rt::csvNumber(readAsSpec("-12.3 deg"), "deg", 3.14159265358979323846 / 180), "-12.3");
  for (double si : {0.07400799015338948, 0.0123456789012345, 1.2345678901234567e-5, -0.0987654321098765}) {
    std::string s = rt::csvNumber(si, "mm", 1e-3);
    EXPECT_EQ(readAsSpec(s + " mm"), si) << s;
  }
}

// Several gearboxes, different columns: one table, one header, every row as wide as it.
TEST(CsvRoundTrip, SeveralGearboxesMakeOneTidyTable) {
  const char* spec = R"(gearbox A {
  stage s: spur { pinion.z in 18..20; wheel.z in 40..41; normal_module = 3 mm; face_width = 30 mm; }
  report { columns s.center_distance; }
}
gearbox B {
  stage s: spur { pinion.z in 18..19; wheel.z = 50; normal_module in {2 mm, 3 mm}; face_width = 30 mm; }
  report { columns s.eps_alpha, s.center_distance; }
}
)";
  auto path = std::filesystem::temp_directory_path() / "gbx_csv_two_gearboxes.gbx";
  std::ofstream(path) << spec;
  std::stringstream csv, err;
  ASSERT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, csv, err), 0) << err.str();
  std::string line;
  std::getline(csv, line);
  auto head = split(line);
  EXPECT_EQ(head.front(), "gearbox");
  EXPECT_EQ(head.back(), "ratio_exact");
  auto column = [&](const std::string& n) { return std::find(head.begin(), head.end(), n) - head.begin(); };
  ASSERT_LT(column("s.eps_alpha"), static_cast<long>(head.size()));
  int a = 0, b = 0;
  while (std::getline(csv, line)) {
    auto cells = split(line);  // the last cell, the exact ratio, is never empty
    ASSERT_EQ(cells.size(), head.size()) << line;
    if (cells[0] == "A") {
      ++a;
      EXPECT_TRUE(cells[static_cast<size_t>(column("s.eps_alpha"))].empty()) << line;
    } else {
      ++b;
      EXPECT_FALSE(cells[static_cast<size_t>(column("s.eps_alpha"))].empty()) << line;
    }
  }
  EXPECT_EQ(a, 6);
  EXPECT_EQ(b, 4);
}

// A gearbox without stages has one design; the CSV listing on stdout (made a row at a time
// from the search's compact list) lists it as the text report does.
TEST(CsvRoundTrip, AGearboxWithoutStagesListsItsOneDesign) {
  auto path = std::filesystem::temp_directory_path() / "gbx_csv_no_stages.gbx";
  std::ofstream(path) << "gearbox Z { report { top 10; } }\n";
  std::ostringstream csv, err;
  ASSERT_EQ(driver::run({"solve", path.string(), "--format", "csv", "--quiet"}, csv, err), 0) << err.str();
  std::filesystem::remove(path);
  std::istringstream lines(csv.str());
  std::string header, row, more;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_EQ(header, "gearbox,rank,ratio,ratio_exact");
  EXPECT_EQ(row, "Z,1,1,1");
  EXPECT_FALSE(std::getline(lines, more)) << more;
}
