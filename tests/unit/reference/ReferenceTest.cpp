// The documentation is the whole reference: every keyword, catalogue name, function, signal,
// method, diagnostic code and command-line option has an entry in docs/, the catalogue page
// is the catalogue's own text, every complete example compiles, and nothing in the
// repository points at a file outside it.
#include <gtest/gtest.h>

#include "ReadFile.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "catalogue/Effects.h"
#include "catalogue/Functions.h"
#include "catalogue/Keys.h"
#include "catalogue/Methods.h"
#include "catalogue/Settings.h"
#include "catalogue/Signals.h"
#include "catalogue/StageKinds.h"
#include "driver/Driver.h"
#include "reference/Catalogue.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

fs::path repoDir() { return fs::path(GBX_SOURCE_DIR); }
std::string doc(const std::string& page) { return readFile(repoDir() / "docs" / page); }

// An entry: the name in backticks, alone or as the head of a longer code span
// (`rms(acceleration)`, `pinion.z = 21;`).
bool hasEntry(const std::string& text, const std::string& name) {
  for (size_t at = text.find("`" + name); at != std::string::npos; at = text.find("`" + name, at + 1)) {
    char next = at + 1 + name.size() < text.size() ? text[at + 1 + name.size()] : '`';
    if (!std::isalnum(static_cast<unsigned char>(next)) && next != '_') return true;
  }
  return false;
}

template <class Names> std::vector<std::string> missing(const std::string& text, const Names& names) {
  std::vector<std::string> out;
  for (const auto& n : names)
    if (!hasEntry(text, std::string(n))) out.emplace_back(n);
  return out;
}

std::string list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v)
    s += (s.empty() ? "" : ", ") + x;
  return s;
}

// The grammar's keywords: `IMPORT : 'import' ;` rules of upper-case tokens.
std::vector<std::string> keywords() {
  std::vector<std::string> out;
  std::string g = readFile(repoDir() / "grammar" / "Gbx.g4");
  std::regex kw(R"(([A-Z]+) : '([a-z]+)' ;)");
  for (auto it = std::sregex_iterator(g.begin(), g.end(), kw); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[2]);
  return out;
}

// Every diagnostic code the sources can emit ("E0302", "W0501").
std::set<std::string> diagnosticCodes() {
  std::set<std::string> out;
  std::regex code(R"re("([EW][0-9]{4})")re");
  for (const char* dir : {"compiler", "runtime", "tools"})
    for (const auto& e : fs::recursive_directory_iterator(repoDir() / dir)) {
      auto ext = e.path().extension();
      if (ext != ".cpp" && ext != ".h") continue;
      std::string t = readFile(e.path());
      for (auto it = std::sregex_iterator(t.begin(), t.end(), code); it != std::sregex_iterator(); ++it)
        out.insert((*it)[1]);
    }
  return out;
}

} // namespace

TEST(Reference, CatalogueIsCurrent) {
  EXPECT_EQ(doc("catalogue.md"), reference::catalogueMarkdown())
      << "docs/catalogue.md is stale: run scripts/reference.sh and review the diff";
}

TEST(Reference, EveryKeyIsInTheCatalogue) {
  std::string text = doc("catalogue.md") + doc("language.md");
  std::vector<std::string> names;
  for (int i = 0; i < cat::kKeyCount; ++i) {
    std::string n(cat::keyName(static_cast<cat::Q>(i)));
    // A gear attribute's key is its name after the gear (`pinion.z` documents `z`).
    names.push_back(n);
  }
  auto gaps = missing(text, names);
  EXPECT_TRUE(gaps.empty()) << "no entry in docs/catalogue.md or docs/language.md: " << list(gaps);
}

TEST(Reference, EveryKeywordAndWordOfTheLanguageIsDocumented) {
  std::string text = doc("language.md");
  std::vector<std::string> words = keywords();
  EXPECT_GT(words.size(), 30u);
  for (const auto& f : cat::kFunctions)
    words.emplace_back(f.name);
  for (const auto& s : cat::sceneSignals())
    words.emplace_back(s.name);
  for (const auto& f : cat::kSignalFns)
    words.emplace_back(f.name);
  for (const auto& m : cat::kMethods)
    words.emplace_back(m.name);
  for (const auto& e : cat::effects())
    words.push_back(e.name);
  for (const auto* k : cat::stageKinds())
    words.push_back(k->name);
  for (const auto& t : cat::modificationTargets())
    words.push_back(t);
  for (const auto& b : cat::modifyBuiltins())
    words.push_back(b.name);
  auto gaps = missing(text, words);
  EXPECT_TRUE(gaps.empty()) << "no entry in docs/language.md: " << list(gaps);
}

TEST(Reference, EveryDiagnosticCodeIsDocumented) {
  std::string text = doc("diagnostics.md");
  auto codes = diagnosticCodes();
  EXPECT_GT(codes.size(), 50u);
  std::vector<std::string> gaps;
  for (const auto& c : codes)
    if (text.find("| " + c + " |") == std::string::npos) gaps.push_back(c);
  EXPECT_TRUE(gaps.empty()) << "no row in docs/diagnostics.md: " << list(gaps);
}

TEST(Reference, EveryCommandAndOptionIsDocumented) {
  std::string text = doc("cli.md");
  std::vector<std::string> gaps;
  for (const auto& o : driver::optionNames())
    if (text.find("**" + o + "**") == std::string::npos) gaps.push_back(o);
  for (const auto& c : driver::commandNames())
    if (text.find("**" + c + "**") == std::string::npos) gaps.push_back(c);
  EXPECT_TRUE(gaps.empty()) << "no entry in docs/cli.md: " << list(gaps);
}

// Every material, constant and preset of the standard library has an entry in docs/stdlib.md
// (an oil grade's three constants share the grade's row).
TEST(Reference, EveryStandardLibraryNameIsDocumented) {
  std::string text = doc("stdlib.md");
  std::regex decl(R"re((?:^|\n)\s*(?:material|const|preset)\s+(\w+))re");
  std::regex oil(R"re((iso_vg\d+)_(?:viscosity_40|viscosity_100|density))re");
  std::vector<std::string> gaps;
  int n = 0;
  for (const auto& e : fs::directory_iterator(repoDir() / "stdlib")) {
    std::string t = readFile(e.path());
    for (auto it = std::sregex_iterator(t.begin(), t.end(), decl); it != std::sregex_iterator(); ++it) {
      std::string name = (*it)[1];
      std::smatch m;
      if (std::regex_match(name, m, oil)) name = m[1];
      ++n;
      if (!hasEntry(text, name)) gaps.push_back(name);
    }
  }
  EXPECT_GT(n, 30);
  EXPECT_TRUE(gaps.empty()) << "no entry in docs/stdlib.md: " << list(gaps);
}

// A complete example (a ```gbx block) compiles without errors; fragments use plain ```.
TEST(Reference, EveryCompleteExampleCompiles) {
  int n = 0;
  std::vector<fs::path> pages = {repoDir() / "README.md"};
  for (const auto& e : fs::directory_iterator(repoDir() / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  for (const auto& page : pages) {
    std::string text = readFile(page);
    for (size_t at = text.find("```gbx\n"); at != std::string::npos; at = text.find("```gbx\n", at + 1)) {
      size_t end = text.find("```", at + 7);
      ASSERT_NE(end, std::string::npos) << page;
      std::string name = page.filename().string() + " example " + std::to_string(++n);
      auto c = driver::compileText(name, text.substr(at + 7, end - at - 7));
      ASSERT_TRUE(c);
      EXPECT_FALSE(c->diags.hasErrors()) << name << "\n" << c->diags.renderText(c->sources);
    }
  }
  EXPECT_GE(n, 5);
}

// Nothing in the repository names a file outside it (CI's own scripts excepted: they set
// up the folders beside the clone).
TEST(Reference, NothingPointsOutsideTheRepository) {
  std::regex outside(R"(\.\./shared|LANGUAGE\.md|DOMAIN\.md|DESIGN\.md|spec-examples|seeds/)");
  std::vector<std::string> hits;
  for (auto it = fs::recursive_directory_iterator(repoDir()); it != fs::recursive_directory_iterator(); ++it) {
    const auto& p = it->path();
    std::string name = p.filename().string();
    if (it->is_directory()) {
      if (name == ".git" || name == ".ci" || name == "node_modules" || name.rfind("build", 0) == 0)
        it.disable_recursion_pending();
      continue;
    }
    if (p.string().find("/tests/fuzz/corpus/") != std::string::npos) continue; // inputs, not text
    if (p.filename() == "ReferenceTest.cpp") continue;
    std::string t = readFile(p);
    if (t.find('\0') != std::string::npos) continue;
    std::smatch m;
    if (std::regex_search(t, m, outside)) hits.push_back(fs::relative(p, repoDir()).string() + ": " + m.str());
  }
  EXPECT_TRUE(hits.empty()) << list(hits);
}
