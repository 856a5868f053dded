#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "driver/Golden.h"
#include "format/Formatter.h"
#include "report/Formats.h"

using namespace gbx;
namespace fs = std::filesystem;

namespace {

struct Run {
  int status;
  std::string out, err;
};

Run gbxc(std::vector<std::string> args) {
  std::ostringstream out, err;
  int s = driver::run(args, out, err);
  return {s, out.str(), err.str()};
}

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("gbxc-test-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

} // namespace

TEST(Cli, ExitStatuses) {
  EXPECT_EQ(gbxc({"--help"}).status, 0);
  EXPECT_EQ(gbxc({"--version"}).out, "gbxc 0.1.0\n");
  EXPECT_EQ(gbxc({}).status, 2);
  EXPECT_EQ(gbxc({"frobnicate", "x.gbx"}).status, 2);
  EXPECT_EQ(gbxc({"check"}).status, 2);
  EXPECT_EQ(gbxc({"dump", "tokens", "x.gbx"}).status, 2);
  EXPECT_EQ(gbxc({"check", "x.gbx", "--format", "yaml"}).status, 2);
  EXPECT_EQ(gbxc({"check", "x.gbx", "--bogus"}).status, 2);
  EXPECT_EQ(gbxc({"solve", "x.gbx", "--jobs", "0"}).status, 2);
  auto missing = gbxc({"check", "/no/such/file.gbx"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("E0001"), std::string::npos);
}

// A mistyped flag, format or command is answered with the nearest one, and a format the
// command does not take with the ones it does.
TEST(Cli, MistypedFlagsFormatsAndCommandsSayWhatWasMeant) {
  auto flag = gbxc({"solve", "--frmat", "text", "x.gbx"});
  EXPECT_EQ(flag.status, 2);
  EXPECT_NE(flag.err.find("unknown option `--frmat`; did you mean `--format`?"), std::string::npos) << flag.err;
  auto format = gbxc({"solve", "x.gbx", "--format", "pdf"});
  EXPECT_EQ(format.status, 2);
  EXPECT_NE(format.err.find("(it takes text, json, csv, md, html)"), std::string::npos) << format.err;
  auto near = gbxc({"solve", "x.gbx", "--format", "jsn"});
  EXPECT_NE(near.err.find("did you mean `json`?"), std::string::npos) << near.err;
  auto check = gbxc({"check", "x.gbx", "--format", "html"});
  EXPECT_NE(check.err.find("(it takes text, json)"), std::string::npos) << check.err;
  auto command = gbxc({"slove", "x.gbx"});
  EXPECT_EQ(command.status, 2);
  EXPECT_NE(command.err.find("unknown command `slove`; did you mean `solve`?"), std::string::npos) << command.err;
}

// A module beside the spec is found first: `import shopstd;` reads shopstd.gbx in the spec's
// own folder, without GBX_PATH.
TEST(Cli, AModuleBesideTheSpecIsImported) {
  fs::path d = tempDir("beside");
  write(d / "shopstd.gbx", "const shop_ratio_tolerance = 1 %;\n");
  write(d / "main.gbx", "import shopstd;\ngearbox G {\n  stage s: spur { pinion.z in 17..19; wheel.z in 50..60; normal_module = 2 mm; }\n"
                        "  require s.ratio == 3 +- shop_ratio_tolerance;\n}\n");
  ::unsetenv("GBX_PATH");
  auto r = gbxc({"check", (d / "main.gbx").string()});
  EXPECT_EQ(r.status, 0) << r.err;
}

// Each command has its own usage: `gbxc help CMD` and `gbxc CMD --help` print it.
TEST(Cli, EachCommandHasItsOwnHelp) {
  for (const char* command : {"solve", "check", "dump", "test", "fmt", "lsp"}) {
    auto help = gbxc({"help", command}), flag = gbxc({command, "--help"});
    EXPECT_EQ(help.status, 0) << command;
    EXPECT_EQ(help.out.rfind(std::string("usage: gbxc ") + command, 0), 0u) << command << ": " << help.out;
    EXPECT_EQ(flag.out, help.out) << command;
  }
  EXPECT_EQ(gbxc({"help"}).out.rfind("usage: gbxc <command>", 0), 0u);
  auto unknown = gbxc({"help", "slove"});
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("did you mean `solve`?"), std::string::npos) << unknown.err;
}

// GBX_PATH names folders of modules that `import NAME` finds before the stdlib, as a compiler
// takes include paths; without it the same import is an error naming the modules there are.
TEST(Cli, GbxPathAddsModuleFolders) {
  fs::path d = tempDir("gbx-path");
  fs::create_directories(d / "shop");
  write(d / "shop" / "shopstd.gbx", "import materials;\nconst shop_ratio_tolerance = 1 %;\n");
  write(d / "main.gbx", "import shopstd;\ngearbox G {\n  stage s: spur { pinion.z in 17..19; wheel.z in 50..60; normal_module = 2 mm; }\n"
                        "  require s.ratio == 3 +- shop_ratio_tolerance;\n}\n");
  ::unsetenv("GBX_PATH");
  auto without = gbxc({"check", (d / "main.gbx").string()});
  EXPECT_EQ(without.status, 1);
  EXPECT_NE(without.err.find("cannot import `shopstd`: no module of that name beside the spec, in GBX_PATH or in the stdlib "
                             "(modules: gleason, klingelnberg"),
            std::string::npos)
      << without.err;
  ::setenv("GBX_PATH", ("/no/such/folder:" + (d / "shop").string()).c_str(), 1);
  auto with = gbxc({"check", (d / "main.gbx").string()});
  auto listed = gbxc({"solve", (d / "main.gbx").string(), "--no-timings"});
  // A folder of GBX_PATH comes before the stdlib: a module of the stdlib's name shadows it.
  write(d / "shop" / "materials.gbx", "const shadowed = 1;\n");
  write(d / "uses.gbx", "import materials;\nconst x = shadowed;\n");
  auto shadow = gbxc({"check", (d / "uses.gbx").string()});
  // A relative folder is taken from the working folder, as a compiler takes -I.
  fs::path here = fs::current_path();
  fs::current_path(d);
  ::setenv("GBX_PATH", "shop", 1);
  auto relative = gbxc({"check", (d / "main.gbx").string()});
  fs::current_path(here);
  ::unsetenv("GBX_PATH");
  EXPECT_EQ(shadow.status, 0) << shadow.err;
  EXPECT_EQ(relative.status, 0) << relative.err;
  EXPECT_EQ(with.status, 0) << with.err;
  EXPECT_EQ(listed.status, 0) << listed.err;
  EXPECT_NE(listed.out.find("gearbox G:"), std::string::npos) << listed.out;
}

// CSV on stdout is the design table alone; a note on stderr names the tables it leaves out
// and how to get them (README, "Reports"). With -o DIR they are files, and no note is given.
TEST(Cli, CsvOnStdoutIsTheDesignTableAndSaysWhatElseThereIs) {
  std::string spec = std::string(GBX_SOURCE_DIR) + "/specs/spur_resonance.gbx";
  auto r = gbxc({"solve", spec, "--format", "csv", "--no-timings"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("gearbox,rank,", 0), 0u) << r.out;
  EXPECT_EQ(r.out.find("# table"), std::string::npos);
  EXPECT_NE(r.err.find("note: stdout holds the design table only; scenes.csv, sweeps.csv are written with -o DIR"), std::string::npos)
      << r.err;
  auto quiet = gbxc({"solve", spec, "--format", "csv", "--no-timings", "--quiet"});
  EXPECT_EQ(quiet.err, "");
  fs::path d = tempDir("csv-out");
  auto files = gbxc({"solve", spec, "--format", "csv", "--no-timings", "-o", d.string()});
  EXPECT_EQ(files.err, "");
  EXPECT_TRUE(fs::exists(d / "scenes.csv"));
  EXPECT_TRUE(fs::exists(d / "sweeps.csv"));
  // A spec with nothing but designs: no note.
  auto plain = gbxc({"solve", std::string(GBX_SOURCE_DIR) + "/specs/thruster_one_stage.gbx", "--format", "csv"});
  EXPECT_EQ(plain.err, "");
}

// A file with no gearbox is solved to nothing, and `solve` says so.
TEST(Cli, SolvingAFileWithoutAGearboxSaysSo) {
  fs::path d = tempDir("no-gearbox");
  write(d / "empty.gbx", "");
  auto r = gbxc({"solve", (d / "empty.gbx").string()});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.err.find("declares no gearbox"), std::string::npos) << r.err;
  fs::remove_all(d);
}

TEST(Cli, CheckAndDumpOfASpecExample) {
  fs::path spec = fs::path(GBX_SOURCE_DIR) / "specs" / "thruster_one_stage.gbx";
  auto r = gbxc({"check", spec.string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("ok, 3 gearboxes"), std::string::npos);
  auto j = gbxc({"check", "--format", "json", spec.string()});
  EXPECT_EQ(j.status, 0);
  EXPECT_NE(j.out.find("\"ok\": true"), std::string::npos);
  auto ir = gbxc({"dump", "ir", spec.string()});
  EXPECT_EQ(ir.status, 0);
  EXPECT_NE(ir.out.find("gearbox ThrusterOneStagePinned extends ThrusterOneStageWindow"), std::string::npos);
}

TEST(Cli, EveryReportFormatOfTheTable) {
  fs::path spec = fs::path(GBX_SOURCE_DIR) / "specs" / "thruster_one_stage.gbx";
  for (const auto& f : rt::reportFormats()) {
    std::string name(f.name);
    fs::path d = tempDir("format-" + name);
    auto r = gbxc({"solve", spec.string(), "--no-timings", "--format", name, "-o", d.string()});
    EXPECT_EQ(r.status, 0) << name << r.err;
    // A format written as tables (CSV) has its design table as designs.csv, and no report.csv.
    bool tables = f.tables != nullptr;
    EXPECT_EQ(fs::exists(d / ("report." + std::string(f.extension))), !tables) << name;
    std::ifstream in(d / (tables ? std::string("designs.csv") : "report." + std::string(f.extension)), std::ios::binary);
    std::stringstream file;
    file << in.rdbuf();
    EXPECT_EQ(file.str(), r.out) << name;
    EXPECT_EQ(gbxc({"check", spec.string(), "--format", name}).status, f.diagnostics ? 0 : 2) << name;
  }
  EXPECT_EQ(gbxc({"solve", spec.string(), "--format", "yaml"}).status, 2);
}

TEST(Golden, UnifiedDiffShowsChangedLines) {
  std::string d = driver::unifiedDiff("a\nb\nc\n", "a\nB\nc\n", "exp", "act");
  EXPECT_NE(d.find("-b\n"), std::string::npos);
  EXPECT_NE(d.find("+B\n"), std::string::npos);
  EXPECT_EQ(driver::unifiedDiff("x\n", "x\n", "e", "a").find("@@"), std::string::npos);
}

TEST(Golden, UpdateThenPassThenFailWithDiff) {
  fs::path d = tempDir("golden");
  write(d / "one.gbx", "// ARGS: check\ngearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } }\n");
  auto first = gbxc({"test", d.string()});
  EXPECT_EQ(first.status, 1) << "a missing expected file fails";
  EXPECT_NE(first.out.find("no "), std::string::npos);
  EXPECT_EQ(gbxc({"test", d.string(), "--update"}).status, 0);
  std::ifstream in(d / "one.expected");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "one.gbx: ok, 1 gearbox (G)\n[exit 0]\n");
  EXPECT_EQ(gbxc({"test", d.string()}).status, 0);
  write(d / "one.gbx", "// ARGS: check\ngearbox G { stage s: spur { pinion.z = 0; wheel.z = 31; } }\n");
  auto fail = gbxc({"test", d.string()});
  EXPECT_EQ(fail.status, 1);
  EXPECT_NE(fail.out.find("-one.gbx: ok"), std::string::npos);
  EXPECT_NE(fail.out.find("+[exit 1]"), std::string::npos);
  EXPECT_NE(fail.out.find("0 passed, 1 failed"), std::string::npos);
  fs::remove_all(d);
}

TEST(Golden, FolderArgumentsApplyWithoutAnArgsLine) {
  fs::path d = tempDir("golden-args");
  write(d / "golden.args", "dump ir\n");
  write(d / "g.gbx", "gearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } }\n");
  std::vector<std::string> problems;
  auto cases = driver::discoverGolden({d.string()}, problems);
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_EQ(cases[0].args, (std::vector<std::string>{"dump", "ir"}));
  EXPECT_NE(driver::captureGolden(cases[0]).find("stage s: spur"), std::string::npos);
  fs::remove_all(d);
}

// A spec with a scene: its expected output holds no CPU times, so an unchanged rerun passes.
TEST(Golden, SceneSpecPassesTwiceInARowUnchanged) {
  fs::path d = tempDir("golden-scene");
  write(d / "mesh.gbx", R"(gearbox G {
  stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
  operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
  scene v on s {
    effects { varying_stiffness { harmonics = 3; } damping { ratio = 0.05; } }
    settle = 20 mesh_periods; record = 2 mesh_periods;
    output rms(acceleration);
  }
}
)");
  EXPECT_EQ(gbxc({"test", d.string(), "--update"}).status, 0);
  std::ifstream in(d / "mesh.expected");
  std::string expected((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(expected.find("CPU"), std::string::npos) << expected;
  for (int run = 0; run < 2; ++run) {
    auto r = gbxc({"test", d.string()});
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("1 passed, 0 failed"), std::string::npos);
  }
  // A person who wants the times asks for them; then they are compared (and differ).
  EXPECT_EQ(gbxc({"test", d.string(), "--timings"}).status, 1);
  EXPECT_EQ(gbxc({"solve", "--timings", (d / "mesh.gbx").string()}).status, 2);
  fs::remove_all(d);
}

TEST(Golden, DiffShowsExpectedBeforeActual) {
  std::string diff = driver::unifiedDiff("a\nold\nc\n", "a\nnew\nc\n", "x.expected", "actual");
  auto minus = diff.find("-old"), plus = diff.find("+new");
  ASSERT_NE(minus, std::string::npos);
  ASSERT_NE(plus, std::string::npos);
  EXPECT_LT(minus, plus) << diff;
}

TEST(Golden, ToleranceComparesNumbersRelativelyAndTextExactly) {
  EXPECT_TRUE(driver::equalWithin("rms = 50.5300 m/s^2\n", "rms = 50.5300 m/s^2\n", 0));
  EXPECT_FALSE(driver::equalWithin("rms = 50.5300 m/s^2\n", "rms = 50.5301 m/s^2\n", 0));
  EXPECT_TRUE(driver::equalWithin("rms = 50.5300 m/s^2\n", "rms = 50.5301 m/s^2\n", 1e-5));
  EXPECT_FALSE(driver::equalWithin("rms = 50.5300 m/s^2\n", "rms = 50.6300 m/s^2\n", 1e-5));
  EXPECT_FALSE(driver::equalWithin("rms = 50.53 m/s^2\n", "rms = 50.53 m/s\n", 1e-3));  // text differs
  EXPECT_FALSE(driver::equalWithin("steps 6558\n", "steps 6558\nextra\n", 1e-3));      // a line more
  EXPECT_TRUE(driver::equalWithin("error[E0201] at 3:5, -1.5e-3\n", "error[E0201] at 3:5, -1.5000001e-3\n", 1e-6));
  EXPECT_FALSE(driver::equalWithin("error[E0201]\n", "error[E0202]\n", 0.5));  // codes are words, not numbers

  fs::path d = tempDir("golden-tol");
  write(d / "g.gbx", "// ARGS: check\n// TOLERANCE: 1e-9\ngearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } }\n");
  std::vector<std::string> problems;
  auto cases = driver::discoverGolden({d.string()}, problems);
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_EQ(cases[0].args, (std::vector<std::string>{"check"}));
  EXPECT_DOUBLE_EQ(cases[0].tolerance, 1e-9);
  fs::remove_all(d);
}

// The acceptance corpus is kept as the IR golden inputs, laid out by `gbxc fmt` and
// otherwise unchanged but for the comments' references, which name the product's own docs
// (docs/sources.md, docs/language.md) instead of files outside the repository: the code of
// every line and every comment's line stay; specs/ holds the project's versions, which may
// add to an example (a rating, a variant) but keep every gearbox it names.
namespace {
std::string withoutComments(const std::string& text) {
  std::stringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    auto c = line.find("//");
    if (c != std::string::npos) line.erase(c);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}
} // namespace

TEST(Specs, KeepTheSharedAcceptanceCorpus) {
  // The corpus lives outside the repository: GBX_ACCEPTANCE_DIR names it (.ci/run sets it).
  fs::path shared(GBX_ACCEPTANCE_DIR);
  if (shared.empty() || !fs::exists(shared)) GTEST_SKIP() << "GBX_ACCEPTANCE_DIR names no folder";
  int n = 0;
  auto read = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  for (const auto& e : fs::directory_iterator(shared)) {
    if (e.path().extension() != ".gbx") continue;
    ++n;
    fs::path golden = fs::path(GBX_GOLDEN_DIR) / "ir" / e.path().filename();
    source::SourceManager sm;
    diag::DiagnosticEngine diags;
    auto laidOut = format::formatText(e.path().string(), read(e.path()), sm, diags);
    ASSERT_TRUE(laidOut) << diags.renderText(sm);
    EXPECT_EQ(withoutComments(read(golden)), withoutComments(*laidOut)) << golden;
    fs::path mine = fs::path(GBX_SOURCE_DIR) / "specs" / e.path().filename();
    ASSERT_TRUE(fs::exists(mine)) << mine;
    std::string text = read(mine), theirs = read(e.path());
    for (size_t at = theirs.find("gearbox "); at != std::string::npos; at = theirs.find("gearbox ", at + 1)) {
      size_t end = theirs.find_first_of(" {", at + 8);
      std::string name = theirs.substr(at + 8, end - at - 8);
      EXPECT_NE(text.find("gearbox " + name + " "), std::string::npos) << mine << " lost gearbox " << name;
    }
  }
  EXPECT_GE(n, 6);
}

// CSV numbers are in the unit their header names; intervals are two columns.
TEST(Csv, NumbersInTheHeadersUnitIntervalsAsLoHi) {
  auto csv = gbxc({"solve", "--format", "csv", "--no-timings", "--gearbox", "MarineReducer",
                   std::string(GBX_SOURCE_DIR) + "/specs/marine_reducer.gbx"});
  ASSERT_EQ(csv.status, 0) << csv.err;
  std::istringstream in(csv.out);
  std::string head, row;
  std::getline(in, head);
  std::getline(in, row);
  auto cell = [](const std::string& line, size_t k) {
    std::istringstream s(line);
    std::string c;
    for (size_t i = 0; i <= k; ++i) std::getline(s, c, ',');
    return c;
  };
  ASSERT_EQ(cell(head, 5), "main.center_distance [mm]");
  EXPECT_NEAR(std::stod(cell(row, 5)), 855.0, 0.01);  // not 0.855 (m)
  EXPECT_EQ(cell(head, 6), "main.mass [kg]");
  EXPECT_NEAR(std::stod(cell(row, 6)), 4603.4, 0.1);

  auto bevel = gbxc({"solve", "--format", "csv", std::string(GBX_SOURCE_DIR) + "/specs/thruster_one_stage.gbx"});
  EXPECT_NE(bevel.out.find("main.mmn_b_lo,main.mmn_b_hi"), std::string::npos) << bevel.out;
  EXPECT_EQ(bevel.out.find("\"["), std::string::npos) << "no quoted interval strings";

  fs::path d = tempDir("csv-tables");
  auto tables = gbxc({"solve", "--format", "csv", "--no-timings", "-o", d.string(), std::string(GBX_SOURCE_DIR) + "/specs/turbine_modification.gbx"});
  ASSERT_EQ(tables.status, 0) << tables.err;
  EXPECT_TRUE(fs::exists(d / "designs.csv"));
  std::ifstream mods(d / "modifications.csv");
  std::string mhead, first;
  std::getline(mods, mhead);
  std::getline(mods, first);
  EXPECT_EQ(mhead, "gearbox,stage,target,present,value,unit,rule,condition,error");
  EXPECT_NE(first.find("tip_relief,yes,30,um,"), std::string::npos) << first;
  // A height reads in mm, as in every other format (docs/reports.md), not as 3217.5 um.
  std::string second;
  std::getline(mods, second);
  EXPECT_NE(second.find("tip_relief_height,yes,3.2175,mm,"), std::string::npos) << second;
  fs::remove_all(d);
}

// An objective with no value for a design is a run-time error naming the design, not a
// ranking on nothing.
TEST(Solve, ObjectiveWithoutAValueFailsNamingTheDesign) {
  fs::path d = tempDir("no-value");
  write(d / "g.gbx", R"(gearbox G {
  stage s1: spur { pinion.z in 20..21; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
  operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
  minimize s1.pinion.bending_deflection;
}
)");
  auto r = gbxc({"solve", (d / "g.gbx").string()});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("objective `s1.pinion.bending_deflection` has no value for design 1 (s1.pinion.z = 21, s1.wheel.z = 60)"),
            std::string::npos)
      << r.err;
  fs::remove_all(d);
}

TEST(Cli, SolveHelpShowsSolveOptionsAndDumpRefusesJson) {
  auto help = gbxc({"solve", "--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("usage: gbxc solve FILE", 0), 0u) << help.out;
  EXPECT_NE(help.out.find("--format FORMAT"), std::string::npos);
  auto dump = gbxc({"dump", "ir", "--format", "json", std::string(GBX_SOURCE_DIR) + "/specs/thruster_one_stage.gbx"});
  EXPECT_EQ(dump.status, 2);
  EXPECT_TRUE(dump.out.empty()) << "no half-JSON, half-text output";
  EXPECT_NE(dump.err.find("`dump` prints text only"), std::string::npos) << dump.err;
}

// The HTML report travels alone: its plots are inline SVG, not links to files beside it,
// and it carries what the text report has (spectrum peaks, model lines).
TEST(Html, OneSelfContainedFile) {
  fs::path d = tempDir("html");
  write(d / "g.gbx", R"(gearbox G {
  stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
  operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
  scene v on s {
    effects { varying_stiffness { harmonics = 3; } damping { ratio = 0.05; } }
    settle = 20 mesh_periods; record = 8 mesh_periods;
    output rms(acceleration), spectrum(mesh_force), plot(acceleration);
  }
}
)");
  auto r = gbxc({"solve", "--format", "html", "--no-timings", (d / "g.gbx").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  size_t svgs = 0;
  for (size_t at = r.out.find("<svg"); at != std::string::npos; at = r.out.find("<svg", at + 1)) ++svgs;
  EXPECT_EQ(svgs, 2u);
  EXPECT_EQ(r.out.find("<img"), std::string::npos);
  EXPECT_NE(r.out.find("spectrum(mesh_force) peaks: "), std::string::npos);
  EXPECT_NE(r.out.find("(1x mesh)"), std::string::npos);
  EXPECT_EQ(r.out.find("wrote "), std::string::npos);
  fs::remove_all(d);
}

// One spec in all five formats: every design-table number agrees (text, Markdown and HTML
// show 4 decimals in the display unit, CSV the full value in that unit, JSON SI).
TEST(Formats, AllFiveAgreeOnEveryNumber) {
  fs::path d = tempDir("formats");
  write(d / "g.gbx", R"(import materials;
gearbox G {
  stage s: helical { pinion.z in 18..20; wheel.z = 61; normal_module = 2.5 mm; helix_angle = 12 deg;
                     face_width = 30 mm; material = steel_20CrMnMo; }
  operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
  minimize s.mass;
  report { columns s.center_distance, s.mass, s.eps_alpha; }
}
)");
  auto run = [&](const char* f) {
    auto r = gbxc({"solve", "--format", f, "--no-timings", (d / "g.gbx").string()});
    EXPECT_EQ(r.status, 0) << f << ": " << r.err;
    return r.out;
  };
  std::string text = run("text"), json = run("json"), csv = run("csv"), md = run("md"), html = run("html");
  auto split = [](const std::string& s, char sep) {
    std::vector<std::string> v;
    std::string x;
    std::istringstream in(s);
    while (std::getline(in, x, sep)) v.push_back(x);
    return v;
  };
  // CSV is the reference here: rows of (rank, teeth…, ratio, centre distance, mass, eps_alpha, exact ratio).
  auto lines = split(csv, '\n');
  ASSERT_EQ(lines.size(), 4u) << csv;
  EXPECT_EQ(lines[0], "gearbox,rank,s.pinion.z,s.wheel.z,ratio,s.center_distance [mm],s.mass [kg],s.eps_alpha,ratio_exact");
  std::vector<std::vector<double>> want;  // per design: centre distance mm, mass kg, eps_alpha
  for (size_t i = 1; i < lines.size(); ++i) {
    auto c = split(lines[i], ',');
    want.push_back({std::stod(c[5]), std::stod(c[6]), std::stod(c[7])});
  }
  auto shown = [](double v) { return fmt::format("{:.4f}", v); };
  // Text, Markdown and HTML: each design's row holds the same numbers, rounded.
  for (const auto& w : want) {
    for (double v : w) {
      EXPECT_NE(text.find(shown(v)), std::string::npos) << shown(v) << " not in the text report";
      EXPECT_NE(md.find("| " + shown(v) + " |"), std::string::npos) << shown(v) << " not in the Markdown report";
      EXPECT_NE(html.find("<td>" + shown(v) + "</td>"), std::string::npos) << shown(v) << " not in the HTML report";
    }
  }
  // JSON: SI, the centre distance in metres.
  size_t at = 0;
  for (const auto& w : want) {
    at = json.find("\"values\": {", at);
    ASSERT_NE(at, std::string::npos) << json;
    auto value = [&](const std::string& key) {
      size_t k = json.find("\"" + key + "\": ", at);
      return std::stod(json.substr(k + key.size() + 4));
    };
    EXPECT_NEAR(value("s.center_distance") * 1e3, w[0], 1e-9 * w[0]);
    EXPECT_NEAR(value("s.mass"), w[1], 1e-9 * w[1]);
    EXPECT_NEAR(value("s.eps_alpha"), w[2], 1e-12);
    ++at;
  }
  fs::remove_all(d);
}

// A CSV listing on stdout makes its rows as it writes them; with -o DIR every row is
// held. Both give the same bytes, and a column without a value is reported the same way.
TEST(Cli, CsvListingMadeOnDemandEqualsTheHeldTable) {
  fs::path d = tempDir("csv-listing");
  write(d / "l.gbx", "gearbox L {\n  stage a: spur { pinion.z in 12..40; wheel.z in 30..90; }\n"
                     "  stage b: spur { pinion.z in 12..40; wheel.z in 30..90; }\n"
                     "  require ratio == 9 +- 2%;\n  minimize abs(ratio - 9);\n"
                     "  report { columns a.ratio, 1 / (ratio - 9), abs(ratio - 9); top 100000; }\n}\n");
  auto streamed = gbxc({"solve", (d / "l.gbx").string(), "--format", "csv", "--no-timings"});
  auto held = gbxc({"solve", (d / "l.gbx").string(), "--format", "csv", "--no-timings", "-o", (d / "out").string()});
  std::ifstream in(d / "out" / "designs.csv", std::ios::binary);
  std::stringstream file;
  file << in.rdbuf();
  EXPECT_GT(std::count(streamed.out.begin(), streamed.out.end(), '\n'), 1000);
  EXPECT_EQ(streamed.out, file.str());
  // `1 / (ratio - 9)` has no value where the ratio is exactly 9: the same message, exit 3.
  EXPECT_EQ(streamed.status, held.status);
  EXPECT_EQ(streamed.err, held.err);
  EXPECT_NE(streamed.err.find("has no value for design"), std::string::npos) << streamed.err;
}

// Files in -o DIR are written whole (a temporary file renamed over the old one): no
// temporary is left, a second run replaces them, and a folder that cannot be written is
// a clear error with exit 3.
TEST(Cli, OutputFolderIsWrittenWholeOrNotAtAll) {
  fs::path spec = fs::path(GBX_SOURCE_DIR) / "specs" / "thruster_one_stage.gbx";
  fs::path d = tempDir("atomic");
  for (int run = 0; run < 2; ++run) {
    auto r = gbxc({"solve", spec.string(), "--no-timings", "--format", "html", "-o", (d / "out").string()});
    EXPECT_EQ(r.status, 0) << r.err;
  }
  int files = 0;
  for (const auto& e : fs::directory_iterator(d / "out")) {
    ++files;
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  }
  EXPECT_GT(files, 0);
  EXPECT_TRUE(fs::exists(d / "out" / "report.html"));
  // Under a regular file no folder can be made.
  write(d / "plain", "x");
  auto bad = gbxc({"solve", spec.string(), "-o", (d / "plain" / "out").string()});
  EXPECT_EQ(bad.status, 3);
  EXPECT_NE(bad.err.find("cannot create the output folder"), std::string::npos) << bad.err;
  // The report's name taken by a folder: the report cannot replace it.
  fs::create_directories(d / "taken" / "report.txt");
  auto taken = gbxc({"solve", spec.string(), "-o", (d / "taken").string()});
  EXPECT_EQ(taken.status, 3);
  EXPECT_NE(taken.err.find("cannot write"), std::string::npos) << taken.err;
  for (const auto& e : fs::directory_iterator(d / "taken")) EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

namespace {

// Starts the gbxc executable with its output thrown away; returns its pid.
pid_t startGbxc(const std::vector<std::string>& args) {
  std::vector<std::string> all = {GBX_GBXC};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  // SIGINT at its default action even when the test runs where it is ignored (a background job).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t dflt;
  sigemptyset(&dflt);
  sigaddset(&dflt, SIGINT);
  posix_spawnattr_setsigdefault(&attr, &dflt);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  int rc = posix_spawn(&pid, GBX_GBXC, &fa, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  return rc == 0 ? pid : -1;
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

} // namespace

// Two processes writing one folder, and Ctrl-C in the middle of a long solve (while it
// integrates, before anything is written): the folder holds the whole report, byte for
// byte, and no temporary file. (Ctrl-C within the few milliseconds a report is being
// written is left to the signal handler in runtime/Solve.cpp, which no test times.)
TEST(Cli, ConcurrentWritersAndCtrlCLeaveWholeFiles) {
  fs::path spec = fs::path(GBX_SOURCE_DIR) / "specs" / "thruster_one_stage.gbx";
  fs::path d = tempDir("concurrent");
  std::vector<std::string> args = {"solve", spec.string(), "--no-timings", "--quiet", "--format", "json", "-o", (d / "out").string()};
  auto first = gbxc(args);
  ASSERT_EQ(first.status, 0) << first.err;
  const std::string report = readAll(d / "out" / "report.json");
  ASSERT_FALSE(report.empty());
  pid_t a = startGbxc(args), b = startGbxc(args);
  ASSERT_GT(a, 0);
  ASSERT_GT(b, 0);
  for (pid_t p : {a, b}) {
    int st = 0;
    waitpid(p, &st, 0);
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  }
  EXPECT_EQ(readAll(d / "out" / "report.json"), report);
  // A long scene, stopped by SIGINT while it integrates.
  write(d / "long.gbx", readAll(fs::path(GBX_SOURCE_DIR) / "tests/fuzz/regressions/scene_time_limit.gbx"));
  pid_t c = startGbxc({"solve", (d / "long.gbx").string(), "--quiet", "--format", "json", "-o", (d / "out").string()});
  ASSERT_GT(c, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(c, SIGINT);
  int st = 0;
  waitpid(c, &st, 0);
  EXPECT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT) << st;
  EXPECT_EQ(readAll(d / "out" / "report.json"), report);
  for (const auto& e : fs::directory_iterator(d / "out")) EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

// A freedom decided at an end of its range while an objective ranks the designs is said:
// the lightest face width here is the range's lower end, and the optimum may lie below it.
TEST(Cli, AFreedomAtTheEndOfItsRangeIsAWarning) {
  fs::path d = tempDir("freedom-bound");
  write(d / "b.gbx", "import materials;\ngearbox B {\n  stage s: helical { pinion.z = 21; wheel.z = 80; normal_module = 3 mm; helix_angle = 12 deg;\n"
                     "    face_width in 30..90 mm; material = steel_18CrNiMo7_6; }\n  minimize s.mass;\n}\n"
                     "gearbox C extends B { s.face_width = 40 mm; }\n");
  auto r = gbxc({"solve", (d / "b.gbx").string(), "--no-timings"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("design 1's `s.face_width` is decided at the lower end of its range (30.0000 mm)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("warning", r.out.find("gearbox C")), std::string::npos) << "a fixed face width has no range";
}
