#include "sema/Loader.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "parse/Parser.h"

namespace gbx::sema {

namespace fs = std::filesystem;

// A library folder's modules are its files with this extension.
constexpr std::string_view kSpecExtension = ".gbx";

namespace {

// A colon-separated list of folders from the environment, empty entries skipped.
std::vector<std::string> folderList(const char* variable) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv(variable)) {
    std::stringstream ss(env);
    std::string d;
    while (std::getline(ss, d, ':'))
      if (!d.empty()) dirs.push_back(d);
  }
  return dirs;
}

// The stdlib that travels with the running program: share/gbxc/stdlib in the folder of the
// executable or one above it. An installed gbxc (PREFIX/bin/gbxc) finds PREFIX/share/gbxc/stdlib,
// the build tree's (build/gbxc) build/share/gbxc/stdlib, a test program deeper in the build
// tree the same folder a few levels up. Nothing depends on where the sources were.
std::string& programLocation() {
  static std::string file;
  return file;
}

// The running program: the one set, else the process's executable.
fs::path programPath(std::error_code& ec) {
  return programLocation().empty() ? fs::read_symlink("/proc/self/exe", ec) : fs::path(programLocation());
}

std::string stdlibBesideProgram() {
  std::error_code ec;
  fs::path exe = programPath(ec);
#ifdef GBX_INSTALL_DATADIR
  // Without /proc (a bare container): where the installation put it.
  if (ec) return fs::is_directory(fs::path(GBX_INSTALL_DATADIR) / "gbxc" / "stdlib", ec) ? (fs::path(GBX_INSTALL_DATADIR) / "gbxc" / "stdlib").string() : "";
#endif
  if (ec) return {};
  fs::path dir = exe.parent_path();
  // Up to PREFIX from PREFIX/lib/python3/dist-packages/gbxc, the Python module's folder.
  for (int up = 0; up < 5 && !dir.empty(); ++up, dir = dir.parent_path()) {
    fs::path candidate = dir / "share" / "gbxc" / "stdlib";
    if (fs::is_directory(candidate, ec)) return candidate.string();
    if (dir == dir.parent_path()) break;
  }
  return {};
}

} // namespace

void setProgramLocation(const std::string& file) { programLocation() = file; }

std::vector<std::string> modulePath() { return folderList("GBX_PATH"); }

std::vector<std::string> stdlibSearchPath() {
  std::vector<std::string> dirs = folderList("GBX_STDLIB_PATH");
  static const std::string beside = stdlibBesideProgram();
  if (!beside.empty()) dirs.push_back(beside);
  return dirs;
}

std::vector<std::string> stdlibModules() {
  std::set<std::string> names;
  std::vector<std::string> dirs = modulePath();
  for (const auto& dir : stdlibSearchPath()) dirs.push_back(dir);
  for (const auto& dir : dirs) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->path().extension() == kSpecExtension) names.insert(it->path().stem().string());
  }
  return {names.begin(), names.end()};
}

namespace {

bool readFile(const fs::path& p, std::string& out) {
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return false;
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

std::string canonicalPath(const fs::path& p) {
  std::error_code ec;
  auto c = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal().string() : c.string();
}

class Loader {
public:
  Loader(source::SourceManager& sm, diag::DiagnosticEngine& diags) : sm_(sm), diags_(diags) {}

  void visit(int fileId) {
    state_[fileId] = 1;  // on the import stack
    int before = diags_.errorCount();
    auto file = parse::parseFile(sm_, fileId, diags_);
    bool broken = diags_.errorCount() > before;
    if (broken) result.parseErrors = true;
    result.files.push_back(std::move(file));
    // Resolve first, visit after: visiting grows `files`, so no reference into it is held.
    std::vector<std::pair<int, source::Span>> targets;
    // Imports recovered from a broken file are guesses: follow none of them.
    for (const auto& d : result.files.back().decls)
      if (!broken && d.kind == ast::StmtKind::Import)
        if (int t = resolve(d, fileId); t >= 0) {
          targets.emplace_back(t, d.span);
          result.imports.push_back({d.wordSpan.valid() ? d.wordSpan : d.span, t});
        }
    for (const auto& [target, span] : targets) {
      auto st = state_.find(target);
      if (st != state_.end() && st->second == 1) {
        diags_.error("E0204", span,
                     fmt::format("import cycle: `{}` imports `{}`, which is already being imported",
                                 sm_.get(fileId).displayPath(), sm_.get(target).displayPath()));
        continue;
      }
      if (st == state_.end()) visit(target);
    }
    state_[fileId] = 2;
  }

  int resolve(const ast::Stmt& d, int fromFile) {
    if (d.importIsPath) {
      fs::path base = fs::path(sm_.get(fromFile).absPath()).parent_path();
      fs::path target = base / d.word;
      fs::path display = fs::path(sm_.get(fromFile).displayPath()).parent_path() / d.word;
      std::string text;
      std::string abs = canonicalPath(target);
      if (int id = sm_.find(abs); id >= 0) return id;
      if (!readFile(target, text)) {
        diags_.error("E0203", d.wordSpan.valid() ? d.wordSpan : d.span,
                     fmt::format("cannot import \"{}\": no such file (looked for {})", d.word,
                                 display.lexically_normal().string()));
        return -1;
      }
      return sm_.add(display.lexically_normal().string(), abs, std::move(text));
    }
    // The importing file's own folder first (a shop's module beside its specs), then
    // GBX_PATH's folders, as a compiler searches its include paths before its own; a stdlib
    // module is shown as <stdlib>/NAME.gbx, one of a folder by its path.
    auto findIn = [&](const std::vector<std::string>& dirs, bool stdlib) {
      for (const auto& dir : dirs) {
        fs::path target = fs::path(dir) / (d.word + std::string(kSpecExtension));
        std::string abs = canonicalPath(target);
        if (int id = sm_.find(abs); id >= 0) return id;
        std::string text;
        if (readFile(target, text))
          return sm_.add(stdlib ? "<stdlib>/" + d.word + std::string(kSpecExtension) : target.lexically_normal().string(), abs, std::move(text));
      }
      return -1;
    };
    const fs::path own = fs::path(sm_.get(fromFile).absPath()).parent_path();
    std::error_code ec;
    if (!own.empty() && fs::is_directory(own, ec)) {
      fs::path target = own / (d.word + std::string(kSpecExtension));
      std::string abs = canonicalPath(target), text;
      if (int id = sm_.find(abs); id >= 0) return id;
      if (readFile(target, text)) {
        fs::path display = fs::path(sm_.get(fromFile).displayPath()).parent_path() / (d.word + std::string(kSpecExtension));
        return sm_.add(display.lexically_normal().string(), abs, std::move(text));
      }
    }
    std::vector<std::string> user = modulePath();
    if (int id = findIn(user, false); id >= 0) return id;
    if (int id = findIn(stdlibSearchPath(), true); id >= 0) return id;
    source::Span at = d.wordSpan.valid() ? d.wordSpan : d.span;
    std::vector<std::string> modules = stdlibModules();
    if (modules.empty()) {
      std::error_code ec;
      std::vector<std::string> missing;
      for (const auto& dir : user)
        if (!fs::is_directory(dir, ec)) missing.push_back(dir);
      diags_.error(
          "E0203", at,
          fmt::format(
              "cannot import `{}`: no folder of modules was found (no share/gbxc/stdlib beside {}{}); reinstall "
              "gbxc, or set GBX_PATH to folders of .gbx modules",
              d.word, programPath(ec).parent_path().string(),
              missing.empty() ? ""
                              : fmt::format("; GBX_PATH names {}, which {} not exist", fmt::join(missing, ", "),
                                            missing.size() == 1 ? "does" : "do")));
    } else
      diags_.error("E0203", at,
                   fmt::format("cannot import `{}`: no module of that name beside the spec, in GBX_PATH or in the stdlib (modules: {}; "
                               "GBX_PATH adds folders of your own)",
                               d.word,
                               fmt::join(modules, ", ")));
    return -1;
  }

  LoadedProgram result;

private:
  source::SourceManager& sm_;
  diag::DiagnosticEngine& diags_;
  std::map<int, int> state_;
};

} // namespace

LoadedProgram load(const std::string& mainPath, source::SourceManager& sm, diag::DiagnosticEngine& diags) {
  std::string text;
  if (!readFile(mainPath, text)) {
    diags.error("E0001", {}, fmt::format("cannot read `{}`: no such file", mainPath));
    LoadedProgram p;
    p.mainMissing = true;
    return p;
  }
  int id = sm.add(mainPath, canonicalPath(mainPath), std::move(text));
  Loader l(sm, diags);
  l.visit(id);
  return std::move(l.result);
}

LoadedProgram loadText(const std::string& displayPath, const std::string& text, source::SourceManager& sm,
                       diag::DiagnosticEngine& diags) {
  int id = sm.add(displayPath, canonicalPath(displayPath), text);
  Loader l(sm, diags);
  l.visit(id);
  return std::move(l.result);
}

} // namespace gbx::sema
