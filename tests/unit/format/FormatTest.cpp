// gbxc fmt: the layout rules of docs/formatting.md, a fixed point, the same program before
// and after, on hand-written cases and on every .gbx file of the repository.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "ReadFile.h"

#include "driver/Driver.h"
#include "format/Formatter.h"
#include "ir/Ir.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

std::optional<std::string> fmtText(const std::string& text, std::string* diagnostics = nullptr) {
  source::SourceManager sm;
  diag::DiagnosticEngine diags;
  auto out = format::formatText("t.gbx", text, sm, diags);
  if (diagnostics) *diagnostics = diags.renderText(sm);
  return out;
}

struct Result {
  int status;
  std::string out, err;
};
Result gbxc(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  int s = driver::run(args, out, err);
  return {s, out.str(), err.str()};
}

// Every .gbx file the repository keeps laid out: specs/, stdlib/ and tests/golden/ but the
// bad-input corpus.
std::vector<fs::path> laidOutFiles() {
  std::vector<fs::path> files;
  fs::path src(GBX_SOURCE_DIR);
  for (const char* dir : {"specs", "stdlib", "tests/golden"})
    for (const auto& e : fs::recursive_directory_iterator(src / dir))
      if (e.path().extension() == ".gbx" && e.path().parent_path().filename() != "diagnostics")
        files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

} // namespace

TEST(Format, LaysOutASpec) {
  const std::string in = "// head\n\n\n"
                         "import   klingelnberg ;\n"
                         "gearbox G{\n"
                         "stage s : spur{ pinion.z in 11 .. 25; wheel.z=31 ;\n"
                         "  normal_module=3mm; face_width = 1.15*pinion.d ; }\n"
                         "\n"
                         "      require   abs( ratio-2 )<= 1 % ;   // tight\n"
                         "  require -s.pinion.z < 0;  minimize cos(s.helix_angle) ^ 3;\n"
                         "  operating{input_speed=1000 rpm;input_torque = 80 N * m;}\n"
                         "  report { columns s.center_distance,\n"
                         "   s.mass ; }\n"
                         "  study w { work_precision of v; rtol in { 1e-3 , 1e-4 }; }\n"
                         "\n"
                         "}\n\n";
  const std::string want = "// head\n"
                           "\n"
                           "import klingelnberg;\n"
                           "gearbox G {\n"
                           "  stage s: spur {\n"
                           "    pinion.z in 11..25;  wheel.z = 31;\n"
                           "    normal_module = 3 mm;  face_width = 1.15 * pinion.d;\n"
                           "  }\n"
                           "\n"
                           "  require abs(ratio - 2) <= 1%;  // tight\n"
                           "  require -s.pinion.z < 0;  minimize cos(s.helix_angle)^3;\n"
                           "  operating { input_speed = 1000 rpm; input_torque = 80 N * m; }\n"
                           "  report {\n"
                           "    columns s.center_distance,\n"
                           "            s.mass;\n"
                           "  }\n"
                           "  study w { work_precision of v; rtol in {1e-3, 1e-4}; }\n"
                           "}\n";
  // `80 N * m` is 80 N times a quantity m (not glued, not a unit): it keeps its blanks.
  std::string diags;
  auto out = fmtText(in, &diags);
  ASSERT_TRUE(out) << diags;
  EXPECT_EQ(*out, want);
  EXPECT_EQ(fmtText(*out).value_or(""), *out);
}

TEST(Format, KeepsWhatTouchingWouldChange) {
  // A power after a unit: glued it would join the unit (2 mm^2 is not (2 mm)^2).
  EXPECT_EQ(fmtText("const a = 2 mm ^ 2;\n").value_or(""), "const a = 2 mm ^ 2;\n");
  EXPECT_EQ(fmtText("const a = 2 mm^2;\n").value_or(""), "const a = 2 mm^2;\n");
  EXPECT_EQ(fmtText("const a = 2 mm /*c*/ ^ 2;\n").value_or(""), "const a = 2 mm /*c*/ ^ 2;\n");
  EXPECT_EQ(fmtText("const a = 2  kg/m^3;\n").value_or(""), "const a = 2 kg/m^3;\n");
  EXPECT_EQ(fmtText("const a = 22%  *  b;\n").value_or(""), "const a = 22% * b;\n");
  EXPECT_EQ(fmtText("const a = 22%*b;\n").value_or(""), "const a = 22%*b;\n"); // the unit `%*b`
  EXPECT_EQ(fmtText("const a = 1 - -2;\n").value_or(""), "const a = 1 - -2;\n");
  EXPECT_EQ(fmtText("const a = 5.8+-0.01;\n").value_or(""), "const a = 5.8 +- 0.01;\n");
  EXPECT_EQ(fmtText("const a = 20\u00B0;\n").value_or(""), "const a = 20\u00B0;\n");
  // A number at a line's end never takes the next line's word as its unit: breaks stay.
  EXPECT_EQ(fmtText("const a = 41\n  * b;\n").value_or(""), "const a = 41\n      * b;\n");
}

TEST(Format, CommentsStayWhereTheyWere) {
  const std::string in = "gearbox G {   // a gearbox\n"
                         "    /* one */ stage s: spur { pinion.z = 14; /* two */ wheel.z = 31; }\n"
                         "      // own line\n"
                         "  require ratio > 1;  // three\n"
                         "  require ratio < 9;            // four\n"
                         "  /* last */ }\n";
  const std::string want = "gearbox G {  // a gearbox\n"
                           "  /* one */ stage s: spur { pinion.z = 14; /* two */ wheel.z = 31; }\n"
                           "  // own line\n"
                           "  require ratio > 1;  // three\n"
                           "  require ratio < 9;  // four\n"
                           "  /* last */\n"
                           "}\n";
  auto out = fmtText(in);
  ASSERT_TRUE(out);
  EXPECT_EQ(*out, want);
  EXPECT_EQ(fmtText(*out).value_or(""), *out);
}

TEST(Format, BracesOnLinesOfTheirOwnAndCommentRunsByDepth) {
  const std::string in = "gearbox X\n{\nstage s: spur\n      {\n  pinion.z = 14;  // a\n wheel.z = 31;   // b\n  }\n"
                         "  require ratio > 1;                         // c\n}\n";
  const std::string want =
      "gearbox X\n{\n  stage s: spur\n  {\n    pinion.z = 14;  // a\n    wheel.z  = 31;  // b\n  }\n"
      "  require ratio > 1;  // c\n}\n";
  auto out = fmtText(in);
  ASSERT_TRUE(out);
  EXPECT_EQ(*out, want);
  EXPECT_EQ(fmtText(*out).value_or(""), *out);
}

TEST(Format, LineEndingsOfAnyKind) {
  // CRLF becomes LF; a lone CR does not end a line for the lexer, but a line comment stops
  // at it, so the code after it must start a line of its own.
  EXPECT_EQ(fmtText("const a = 1;\r\nconst bb = 2;\r\n").value_or(""), "const a  = 1;\nconst bb = 2;\n");
  auto out = fmtText("const a = 1; // c\rconst b = 2;\r");
  ASSERT_TRUE(out);
  EXPECT_EQ(*out, "const a = 1;  // c\nconst b = 2;\n");
  EXPECT_EQ(fmtText("/* a\r\n b */\r\nconst a = 1;\r\n").value_or(""), "/* a\n b */\nconst a = 1;\n");
  EXPECT_EQ(fmtText("").value_or("x"), "");
  EXPECT_EQ(fmtText("\n\n// only\n\n").value_or(""), "// only\n");
}

TEST(Format, RefusesWhatDoesNotParse) {
  std::string diags;
  EXPECT_FALSE(fmtText("gearbox G { require ratio = 2; }\n", &diags));
  EXPECT_NE(diags.find("E0102"), std::string::npos) << diags;
  EXPECT_FALSE(fmtText("gearbox G { # }\n", &diags));
  EXPECT_NE(diags.find("E0101"), std::string::npos) << diags;
  // A name or unit error is not the formatter's business.
  EXPECT_TRUE(fmtText("gearbox G { stage s: spurr { pinion.z = 14 parsecs; } }\n"));
}

// Every prefix of every spec: formatted, or refused with a diagnostic; never a throw, and
// what is formatted is a fixed point.
TEST(Format, SurvivesEveryTruncatedSpec) {
  int formatted = 0, refused = 0;
  for (const auto& p : laidOutFiles()) {
    if (p.parent_path().filename() != "specs") continue;
    std::string text = readFile(p);
    for (size_t k = 1; k <= 60; ++k) {
      std::string cut = text.substr(0, text.size() * k / 60);
      std::optional<std::string> out;
      ASSERT_NO_THROW(out = fmtText(cut)) << p << " cut at " << cut.size();
      if (!out) {
        ++refused;
        continue;
      }
      ++formatted;
      EXPECT_EQ(fmtText(*out).value_or(""), *out) << p << " cut at " << cut.size();
    }
  }
  EXPECT_GT(formatted, 8);
  EXPECT_GT(refused, 100);
}

// `fmt --check` on the repository: every file laid out, and a fixed point. The rest of
// the suite runs on these files as they are, so their meaning is checked there too.
TEST(Format, RepositoryIsLaidOut) {
  std::vector<std::string> args{"fmt", "--check"};
  auto files = laidOutFiles();
  ASSERT_GT(files.size(), 30u);
  for (const auto& p : files)
    args.push_back(p.string());
  Result r = gbxc(args);
  EXPECT_EQ(r.status, 0) << r.out << r.err << "\nlay them out with `gbxc fmt FILE`";
}

// The same program before and after, and one layout whatever the blanks were: each file
// with its lines indented anew and its runs of blanks made one.
TEST(Format, SameProgramWhateverTheBlanks) {
  int n = 0;
  for (const auto& p : laidOutFiles()) {
    std::string text = readFile(p), collapsed, messy;
    int line = 0;
    bool lineStart = true;
    for (char c : text) {
      if (c == ' ' && !collapsed.empty() && collapsed.back() == ' ') continue;
      if (lineStart && c == ' ') continue;
      if (lineStart) messy.append(static_cast<size_t>(line % 5), ' ');
      lineStart = c == '\n';
      line += lineStart;
      collapsed += c;
      messy += c;
    }
    auto want = fmtText(collapsed), out = fmtText(messy);
    ASSERT_TRUE(want && out) << p;
    EXPECT_EQ(*out, *want) << p;
    // The laid-out text under the file's own name (its imports resolve from its folder);
    // nothing is written into the tree, which other tests read at the same time.
    auto before = driver::compile(p.string()), after = driver::compileText(p.string(), *out);
    ASSERT_EQ(before->ok(), after->ok()) << p;
    if (!before->ok()) continue;
    ++n;
    EXPECT_EQ(ir::print(before->program), ir::print(after->program)) << p;
  }
  EXPECT_GT(n, 20);
}

TEST(Format, CommandLine) {
  fs::path d = fs::temp_directory_path() / ("gbx-fmt-" + std::to_string(::getpid()));
  fs::create_directories(d / "sub");
  const std::string messy = "gearbox G { stage s: spur { pinion.z=14; wheel.z = 31; } }\n";
  const std::string tidy = "gearbox G { stage s: spur { pinion.z = 14; wheel.z = 31; } }\n";
  { std::ofstream(d / "a.gbx") << messy; }
  { std::ofstream(d / "sub" / "b.gbx") << tidy; }
  { std::ofstream(d / "bad.gbx") << "gearbox G { require ratio = 2; }\n"; }
  fs::permissions(d / "a.gbx", fs::perms::owner_read | fs::perms::owner_write);

  Result check = gbxc({"fmt", "--check", (d / "a.gbx").string(), (d / "sub").string()});
  EXPECT_EQ(check.status, 1);
  EXPECT_NE(check.out.find("@@ -1,1 +1,1 @@\n-" + messy + "+" + tidy), std::string::npos) << check.out;
  EXPECT_EQ(readFile(d / "a.gbx"), messy); // --check changes nothing

  Result write = gbxc({"fmt", d.string()}); // a folder: every .gbx below it
  EXPECT_EQ(write.status, 1);               // bad.gbx does not parse ...
  EXPECT_NE(write.err.find("E0102"), std::string::npos) << write.err;
  EXPECT_EQ(readFile(d / "a.gbx"), tidy); // ... and the others are laid out all the same
  EXPECT_EQ(fs::status(d / "a.gbx").permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_NE(write.out.find("formatted "), std::string::npos);
  EXPECT_EQ(write.out.find("b.gbx"), std::string::npos) << write.out; // already laid out: untouched

  EXPECT_EQ(gbxc({"fmt", "--check", (d / "a.gbx").string()}).status, 0);
  // No line break at the end: the diff says so, as patch(1) reads it.
  { std::ofstream(d / "c.gbx") << "const a = 1;"; }
  Result last = gbxc({"fmt", "--check", (d / "c.gbx").string()});
  EXPECT_EQ(last.status, 1);
  EXPECT_NE(last.out.find("@@ -1,1 +1,1 @@\n-const a = 1;\n\\ No newline at end of file\n+const a = 1;\n"),
            std::string::npos)
      << last.out;
  // Through a symbolic link: the file it names is laid out, the link stays a link.
  { std::ofstream(d / "sub" / "real.gbx") << messy; }
  fs::create_symlink("sub/real.gbx", d / "link.gbx");
  EXPECT_EQ(gbxc({"fmt", (d / "link.gbx").string()}).status, 0);
  EXPECT_TRUE(fs::is_symlink(d / "link.gbx"));
  EXPECT_EQ(readFile(d / "sub" / "real.gbx"), tidy);
  EXPECT_EQ(gbxc({"fmt", (d / "missing.gbx").string()}).status, 3);
  EXPECT_EQ(gbxc({"fmt"}).status, 2);
  EXPECT_EQ(gbxc({"check", "--check", (d / "a.gbx").string()}).status, 2);
  EXPECT_EQ(gbxc({"fmt", "--format", "json", (d / "a.gbx").string()}).status, 2);
  fs::remove_all(d);
}
