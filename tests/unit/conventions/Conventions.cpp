#include "conventions/Conventions.h"

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace gbx::test {

namespace {

// The line without its `//` comment and with each string literal's contents blanked (kept as
// `""`), so that what a literal or a comment says is never read as code.
std::string code(const std::string& line) {
  std::string out;
  bool inString = false;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (inString) {
      if (c == '\\') {
        ++i;
        continue;
      }
      if (c == '"') {
        inString = false;
        out += c;
      }
      continue;
    }
    if (c == '/' && i + 1 < line.size() && line[i + 1] == '/') break;
    if (c == '\'' && i + 2 < line.size()) {  // a character literal: '"' is not a string
      size_t close = line.find('\'', i + 1 + (line[i + 1] == '\\' ? 2 : 1));
      if (close != std::string::npos) {
        out += "' '";
        i = close;
        continue;
      }
    }
    if (c == '"') inString = true;
    out += c;
  }
  return out;
}

std::vector<fs::path> sources(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && (e.path().extension() == ".cpp" || e.path().extension() == ".h")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

template <class F>
void eachLine(const fs::path& file, F f) {
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) f(n, line);
}

} // namespace

size_t countLiteralComparisons(const std::string& line) {
  static const std::regex pattern(R"re((==|!=)\s*"|\.compare\([^;]*"|starts_with\("|ends_with\(")re");
  std::string c = code(line);
  return static_cast<size_t>(std::distance(std::sregex_iterator(c.begin(), c.end(), pattern), std::sregex_iterator()));
}

std::vector<Hit> literalComparisons(const fs::path& dir) {
  std::vector<Hit> hits;
  for (const auto& f : sources(dir))
    eachLine(f, [&](int n, const std::string& line) {
      for (size_t k = countLiteralComparisons(line); k > 0; --k)
        hits.push_back({fs::relative(f, dir.parent_path()).string() + ":" + std::to_string(n), line});
    });
  return hits;
}

std::vector<Hit> upwardIncludes(const fs::path& root) {
  // A header's layer: the first folder of its include path, or a file at the top of runtime/.
  auto namesIn = [&](const fs::path& layer) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(root / layer))
      if (e.is_directory() || e.path().extension() == ".h") names.insert(e.path().filename().string());
    return names;
  };
  std::set<std::string> runtime = namesIn("runtime"), tools = namesIn("tools");
  static const std::regex include(R"re(^\s*#\s*include\s*"([^"/]+)(/|"))re");
  std::vector<Hit> hits;
  auto scan = [&](const std::string& layer, const std::vector<const std::set<std::string>*>& above) {
    for (const auto& f : sources(root / layer))
      eachLine(f, [&](int n, const std::string& line) {
        std::smatch m;
        if (!std::regex_search(line, m, include)) return;
        for (const auto* names : above)
          if (names->count(m[1])) hits.push_back({fs::relative(f, root).string() + ":" + std::to_string(n), line});
      });
  };
  scan("compiler", {&runtime, &tools});
  scan("runtime", {&tools});
  return hits;
}

std::vector<Hit> sceneReadsOutsideThePlan(const fs::path& root) {
  static const std::set<std::string> allowed = {"runtime/model/ScenePlan.h", "runtime/model/ScenePlan.cpp", "runtime/dynamics/Scene.h",
                                                "runtime/dynamics/Scene.cpp"};
  static const std::regex read(R"re(\bir::Scene\b|gearbox\.scenes\b|\bir::Effect\b|findEffect\(|effectParam\(|\.accuracy\b.*findSetting)re");
  std::vector<Hit> hits;
  for (const auto& f : sources(root / "runtime")) {
    std::string rel = fs::relative(f, root).string();
    if (allowed.count(rel)) continue;
    eachLine(f, [&](int n, const std::string& line) {
      if (std::regex_search(line, read)) hits.push_back({rel + ":" + std::to_string(n), line});
    });
  }
  return hits;
}

std::vector<Hit> longFunctions(const std::string& ctagsOutput, int most) {
  std::vector<Hit> hits;
  std::istringstream in(ctagsOutput);
  std::string row;
  while (std::getline(in, row)) {
    std::vector<std::string> f;
    std::istringstream fields(row);
    for (std::string x; std::getline(fields, x, '\t');) f.push_back(x);
    if (f.size() < 4) continue;
    long line = 0, end = 0;
    for (size_t i = 3; i < f.size(); ++i) {
      if (f[i].rfind("line:", 0) == 0) line = std::stol(f[i].substr(5));
      if (f[i].rfind("end:", 0) == 0) end = std::stol(f[i].substr(4));
    }
    if (line > 0 && end >= line && end - line + 1 > most)
      hits.push_back({f[1] + ":" + std::to_string(line), f[0] + " (" + std::to_string(end - line + 1) + " lines)"});
  }
  return hits;
}

} // namespace gbx::test
