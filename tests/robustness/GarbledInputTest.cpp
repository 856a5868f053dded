// Truncated and garbled versions of every spec example: the front end must answer each
// with diagnostics (exit 1) where the text is certainly broken, and never crash or hang.
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "driver/Driver.h"

namespace fs = std::filesystem;
using namespace gbx;

namespace {

std::vector<std::pair<std::string, std::string>> examples() {
  std::vector<std::pair<std::string, std::string>> v;
  for (const auto& e : fs::directory_iterator(fs::path(GBX_SOURCE_DIR) / "specs"))
    if (e.path().extension() == ".gbx") {
      std::ifstream in(e.path(), std::ios::binary);
      std::stringstream ss;
      ss << in.rdbuf();
      v.emplace_back(e.path().filename().string(), ss.str());
    }
  std::sort(v.begin(), v.end());
  return v;
}

// For each byte: true when it is code (not inside a comment or string).
std::vector<bool> codeMask(const std::string& t) {
  std::vector<bool> m(t.size(), true);
  for (size_t i = 0; i < t.size(); ++i) {
    if (t.compare(i, 2, "//") == 0) {
      while (i < t.size() && t[i] != '\n') m[i++] = false;
    } else if (t.compare(i, 2, "/*") == 0) {
      size_t e = t.find("*/", i + 2);
      e = e == std::string::npos ? t.size() : e + 2;
      for (; i < e; ++i) m[i] = false;
      --i;
    } else if (t[i] == '"') {
      size_t e = t.find('"', i + 1);
      e = e == std::string::npos ? t.size() : e + 1;
      for (; i < e; ++i) m[i] = false;
      --i;
    }
  }
  return m;
}

int braceDepth(const std::string& t, size_t upTo, const std::vector<bool>& code) {
  int d = 0;
  for (size_t i = 0; i < upTo; ++i) {
    if (!code[i]) continue;
    if (t[i] == '{') ++d;
    if (t[i] == '}') --d;
  }
  return d;
}

void expectErrors(const std::string& text, const std::string& what) {
  auto c = driver::compileText("garbled.gbx", text);
  ASSERT_FALSE(c->ok()) << what << " was accepted:\n" << text;
  for (const auto& d : c->diags.all()) {
    EXPECT_EQ(d.code.size(), 5u) << what;
    EXPECT_FALSE(d.message.empty()) << what;
  }
  // Rendering must not crash either, whatever the spans are.
  EXPECT_FALSE(c->diags.renderText(c->sources).empty());
}

void expectNoCrash(const std::string& text) {
  auto c = driver::compileText("garbled.gbx", text);
  (void)c->diags.renderText(c->sources);
  (void)c->diags.renderJson(c->sources);
}

} // namespace

TEST(Robustness, TruncatedSpecExamples) {
  for (const auto& [name, text] : examples()) {
    auto code = codeMask(text);
    size_t step = std::max<size_t>(1, text.size() / 150);
    for (size_t cut = 1; cut < text.size(); cut += step) {
      std::string t = text.substr(0, cut);
      if (braceDepth(text, cut, code) > 0) expectErrors(t, name + " cut at " + std::to_string(cut));
      else expectNoCrash(t);
    }
  }
}

TEST(Robustness, StrayCharacterInCode) {
  std::mt19937 rng(20261122);
  for (const auto& [name, text] : examples()) {
    auto code = codeMask(text);
    for (int k = 0; k < 40; ++k) {
      size_t pos = rng() % text.size();
      while (!code[pos] || (pos > 0 && !code[pos - 1])) pos = (pos + 1) % text.size();
      std::string t = text;
      t.insert(pos, "$");
      expectErrors(t, name + " with `$` at " + std::to_string(pos));
    }
  }
}

TEST(Robustness, ClosingBraceRemoved) {
  for (const auto& [name, text] : examples()) {
    auto code = codeMask(text);
    for (size_t i = 0; i < text.size(); ++i)
      if (code[i] && text[i] == '}') expectErrors(text.substr(0, i) + text.substr(i + 1), name + " without brace " + std::to_string(i));
  }
}

TEST(Robustness, RandomBytesIncludingInvalidUtf8) {
  std::mt19937 rng(7);
  for (const auto& [name, text] : examples()) {
    for (int k = 0; k < 60; ++k) {
      std::string t = text;
      int edits = 1 + static_cast<int>(rng() % 6);
      for (int e = 0; e < edits; ++e) {
        size_t pos = rng() % t.size();
        switch (rng() % 3) {
        case 0: t[pos] = static_cast<char>(rng() % 256); break;
        case 1: t.erase(pos, 1 + rng() % 8); break;
        default: t.insert(pos, t.substr(rng() % t.size(), 1 + rng() % 12)); break;
        }
        if (t.empty()) t = "x";
      }
      expectNoCrash(t);
    }
  }
}

TEST(Robustness, InvalidUtf8IsADiagnostic) {
  expectErrors("gearbox G { stage s: spur { pinion.z = 14; wheel.z = 3\xff; } }", "invalid UTF-8");
  auto c = driver::compileText("bad.gbx", "const a = 1;\nconst b = \xc3;\n");
  ASSERT_FALSE(c->ok());
  EXPECT_EQ(c->diags.all()[0].code, "E0104");
  EXPECT_EQ(c->diags.all()[0].span.line, 2);
}

TEST(Robustness, EmptyAndWhitespaceFilesAreValid) {
  EXPECT_TRUE(driver::compileText("e.gbx", "")->ok());
  EXPECT_TRUE(driver::compileText("e.gbx", "  \n// nothing\n/* */\n")->ok());
}
