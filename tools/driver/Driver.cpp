#include "driver/Driver.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "catalogue/Budgets.h"
#include "diag/Suggest.h"
#include "driver/Golden.h"
#include "format/Formatter.h"
#include "lower/Lower.h"
#include "lsp/Server.h"
#include "report/Formats.h"
#include "sema/Sema.h"
#include "Solve.h"
#include "WriteWhole.h"

#ifndef GBX_VERSION
#define GBX_VERSION "0.0.0"
#endif

namespace gbx::driver {

namespace {

// Diagnostics about one statement alone (its attribute, units, values, functions): after a
// syntax error they are still true of the statements that parsed. Those that relate a
// statement to others (an unknown name, a missing input) may be the syntax error's doing
// (a declaration it cut off) and wait until the file parses.
bool aboutOneStatement(const std::string& code) {
  static const std::vector<std::string> codes = {"E0210", "E0211", "E0212", "E0213", "E0214", "E0215", "E0220", "E0221", "E0222",
                                                 "E0224", "E0301", "E0302", "E0303", "E0304", "E0305", "E0401", "E0402", "E0403",
                                                 "E0404", "E0405", "E0406", "E0407", "E0408", "E0409", "E0411", "W0501"};
  return std::find(codes.begin(), codes.end(), code) != codes.end();
}

void analyseAndLower(Compilation& c) {
  if (c.loaded.mainMissing) return;
  if (c.loaded.parseErrors) {
    // The parser resumed at the next statement: check what parsed, so that the file (and the
    // editor) shows every error of those statements beside the syntax errors.
    diag::DiagnosticEngine more;
    sema::analyse(c.loaded, more);
    // A statement on a syntax error's lines is what the parser made of broken text: its own
    // errors would only echo that one.
    const std::vector<diag::Diagnostic> syntax = c.diags.all();
    auto broken = [&](const source::Span& s) {
      for (const auto& e : syntax)
        if (e.span.file == s.file && s.line >= e.span.line && s.line <= std::max(e.span.line, e.span.endLine)) return true;
      return false;
    };
    for (const auto& d : more.all()) {
      if (!aboutOneStatement(d.code) || broken(d.span)) continue;
      auto& copy = d.severity == diag::Severity::Error ? c.diags.error(d.code, d.span, d.message) : c.diags.warning(d.code, d.span, d.message);
      copy.notes = d.notes;
    }
    return;
  }
  c.program = lower::lower(sema::analyse(c.loaded, c.diags));
  c.analysed = true;
}

} // namespace

std::unique_ptr<Compilation> compile(const std::string& path) {
  auto c = std::make_unique<Compilation>();
  c->loaded = sema::load(path, c->sources, c->diags);  // pass 1: load and parse
  analyseAndLower(*c);                                 // passes 2, 3: sema, lower
  return c;
}

std::unique_ptr<Compilation> compileText(const std::string& displayPath, const std::string& text) {
  auto c = std::make_unique<Compilation>();
  c->loaded = sema::loadText(displayPath, text, c->sources, c->diags);
  analyseAndLower(*c);
  return c;
}

namespace {

const char* kUsage = R"(usage: gbxc <command> [options]

commands:
  check FILE               check a spec: syntax, names, units (front end only)
  dump ast FILE            print the syntax tree
  dump ir FILE             print the checked, lowered program
  solve FILE               solve every gearbox of the spec (or --gearbox NAME)
  test PATH... [--update]  golden regression tests: each x.gbx against x.expected
  fmt PATH... [--check]    lay files out the one way (docs/formatting.md); - for stdin
  lsp                      a Language Server Protocol server on stdin/stdout (diagnostics)
  help [COMMAND]           a command's own usage (also `gbxc COMMAND --help`)

options:
  --format FORMAT          text or json (solve also: md, html, csv)
  --gearbox NAME           solve only this gearbox
  -o DIR                   write plots and reports into DIR
  --jobs N, -j N           worker threads (results do not depend on N)
  --max-designs N          (solve) the search budget (default 1e9)
  --time-limit S           (solve) stop with exit 3 after S seconds
  --quiet, -q              no progress output
  --no-timings             leave CPU times and the date out of reports (for golden files)
  --update                 (test) rewrite the expected files
  --timings                (test) compare CPU times too (left out by default: they vary)
  --check                  (fmt) change nothing: show a diff of each file not laid out
  --help                   this text
  --version                the version

exit status: 0 success, 1 the spec has errors, 2 usage, 3 runtime failure
)";

const char* kSolveUsage = R"(usage: gbxc solve FILE [options]

Solves every gearbox of the spec: the search, the optimiser, scenes, modifications and
studies, then one report.

options:
  --format FORMAT          text (default), json, csv, md or html
  --gearbox NAME           solve only this gearbox
  -o DIR                   write the report, plots (SVG) and, for csv, one table per result into DIR
  --jobs N, -j N           worker threads (results do not depend on N)
  --max-designs N          the search budget: candidates of a stage, and combinations the
                           join walks, counted before the work starts (default 1e9,
                           at most 4e9)
  --time-limit S           stop with exit 3 after S seconds of wall time, saying how far
                           the work got; stopped in the search or while deciding the
                           freedoms, the designs found or decided so far are listed,
                           marked partial (with how many of how many); stopped later
                           (optimisation, scenes, studies), no report is written
  --quiet, -q              no progress bar
  --no-timings             leave CPU times and the date out of reports

exit status: 0 solved (an empty design list too), 1 the spec has errors, 2 usage,
3 a runtime failure (a scene that fails, a value that cannot be computed, a budget reached)
)";

const char* kTestUsage = R"(usage: gbxc test PATH... [--update] [--timings]

Golden regression tests: each x.gbx below PATH against x.expected beside it.

options:
  --update                 write the expected files (review them with a diff)
  --timings                compare CPU times too (left out by default: they vary)

A leading `// ARGS: check` runs another command; `// TOLERANCE: 1e-9` compares numbers
within that relative tolerance.
)";

const char* kFmtUsage = R"(usage: gbxc fmt PATH... [--check]

Lays every .gbx file out the one way (docs/formatting.md): indentation, blanks around
operators and units, line breaks of blocks, aligned `=`/`in` and trailing comments.
Line breaks, comments and tokens stay as written. A folder means every .gbx file below
it; `-` reads standard input and writes the result to standard output.

options:
  --check                  change nothing; print a diff of each file that is not laid
                           out and exit 1 if any is not

exit status: 0 laid out (or, with --check, already laid out), 1 a file does not parse or
(--check) is not laid out, 2 usage, 3 a file cannot be read or written
)";

const char* kCheckUsage = R"(usage: gbxc check FILE [--format text|json]

Checks a spec without solving it: syntax, names, types and physical units, the rules of
each stage kind. Prints `FILE: ok, N gearboxes (NAMES)` or the diagnostics (code,
file:line:col, caret, a sentence and, where one is near, a "did you mean").

exit status: 0 no errors (warnings are printed), 1 the spec has errors, 2 usage
)";

const char* kDumpUsage = R"(usage: gbxc dump ast|ir FILE

Prints the syntax tree (`ast`) as parsed, or the checked and lowered program (`ir`): every
name resolved, every literal an exact rational in SI. Text only.

exit status: 0 printed, 1 the spec has errors, 2 usage
)";

const char* kLspUsage = R"(usage: gbxc lsp

A Language Server Protocol server on standard input and output, for an editor: diagnostics
as a document is typed, hover, completion, go to definition, document symbols and
formatting. It takes no file: it serves the editor's open documents.
)";

// The usage of one command, the general one for none; nullptr for an unknown command.
const char* usageOf(const std::string& command) {
  if (command.empty()) return kUsage;
  const std::pair<const char*, const char*> table[] = {{"solve", kSolveUsage}, {"test", kTestUsage}, {"fmt", kFmtUsage},
                                                       {"check", kCheckUsage}, {"dump", kDumpUsage}, {"lsp", kLspUsage}};
  for (const auto& [name, text] : table)
    if (command == name) return text;
  return nullptr;
}

struct Options {
  TestSettings test;
  std::string command;
  std::string sub;  // ast|ir for dump
  std::vector<std::string> files;
  std::string format = "text";
  std::string gearbox;
  std::string outDir;
  int jobs = 1;
  double maxDesigns = gbx::cat::budget::kDefaultMaxDesigns;
  double timeLimit = 0;  // seconds; 0: none
  bool quiet = false;
  bool update = false;
  bool timings = true;
  bool testTimings = false;  // test: keep CPU times in the compared output
  bool check = false;        // fmt: change nothing, show what would change
};

int usage(std::ostream& err, const std::string& msg) {
  err << "gbxc: " << msg << "\n(run `gbxc --help` for usage)\n";
  return 2;
}

// Prints diagnostics in the chosen form; returns the exit status of a front-end command.
int report(const Compilation& c, const Options& o, std::ostream& out, std::ostream& err) {
  if (o.format == "json") {
    out << "{\"diagnostics\": " << c.diags.renderJson(c.sources) << "}\n";
  } else if (!c.diags.all().empty()) {
    err << c.diags.renderText(c.sources);
  }
  return c.ok() ? 0 : 1;
}

int check(const Options& o, std::ostream& out, std::ostream& err) {
  auto c = compile(o.files[0]);
  if (o.format == "json") {
    out << fmt::format("{{\"file\": \"{}\", \"ok\": {}, \"gearboxes\": [", diag::jsonEscape(o.files[0]), c->ok() ? "true" : "false");
    for (size_t i = 0; c->ok() && i < c->program.gearboxes.size(); ++i)
      out << (i ? ", " : "") << "\"" << diag::jsonEscape(c->program.gearboxes[i].name) << "\"";
    out << "], \"diagnostics\": " << c->diags.renderJson(c->sources) << "}\n";
    return c->ok() ? 0 : 1;
  }
  int status = report(*c, o, out, err);
  if (status == 0) {
    std::vector<std::string> names;
    for (const auto& g : c->program.gearboxes) names.push_back(g.name);
    out << fmt::format("{}: ok, {} gearbox{}{}\n", o.files[0], names.size(), names.size() == 1 ? "" : "es",
                       names.empty() ? "" : fmt::format(" ({})", fmt::join(names, ", ")));
  }
  return status;
}

int dump(const Options& o, std::ostream& out, std::ostream& err) {
  auto c = compile(o.files[0]);
  if (o.sub == "ast") {
    // The syntax tree is printed even when sema finds errors: it is what was parsed.
    if (!c->loaded.files.empty() && !c->loaded.parseErrors) out << ast::print(c->loaded.files[0]);
    return report(*c, o, out, err);
  }
  int status = report(*c, o, out, err);
  if (status == 0) out << ir::print(c->program);
  return status;
}

int solve(const Options& o, std::ostream& out, std::ostream& err) {
  auto c = compile(o.files[0]);
  // The report owns stdout: diagnostics go there only when they stop the solve.
  if (!c->ok()) return report(*c, o, out, err);
  if (!c->diags.all().empty()) err << c->diags.renderText(c->sources);
  // A file of materials or presets alone has nothing to solve: said, not a silent empty report.
  if (c->program.gearboxes.empty() && !o.quiet)
    err << fmt::format("gbxc: `{}` declares no gearbox, so there is nothing to solve (`gbxc check` checks such a file)\n", o.files[0]);
  if (!o.gearbox.empty()) {
    bool found = false;
    for (const auto& g : c->program.gearboxes) found = found || g.name == o.gearbox;
    if (!found) return usage(err, fmt::format("`{}` declares no gearbox `{}`", o.files[0], o.gearbox));
  }
  rt::SolveOptions so;
  so.gearbox = o.gearbox;
  so.format = o.format;
  so.outDir = o.outDir;
  so.jobs = o.jobs;
  so.quiet = o.quiet;
  so.timings = o.timings;
  so.maxDesigns = o.maxDesigns;
  so.timeLimit = o.timeLimit;
  so.optimiserIterations = o.test.optimiserIterations;
  so.title = std::filesystem::path(o.files[0]).filename().string();
  so.version = GBX_VERSION;
  return rt::solve(c->program, so, out, err);
}

int test(const Options& o, std::ostream& out, std::ostream& err) {
  std::vector<std::string> problems;
  auto cases = discoverGolden(o.files, problems);
  for (const auto& p : problems) err << "gbxc test: " << p << "\n";
  int passed = 0, failed = 0;
  for (const auto& c : cases) {
    auto r = runGolden(c, GoldenOptions{o.update, o.testTimings});
    switch (r.status) {
    case GoldenOutcome::Pass: ++passed; break;
    case GoldenOutcome::Updated:
      ++passed;
      out << "updated " << c.expected << "\n";
      break;
    case GoldenOutcome::Missing:
      ++failed;
      out << "FAIL " << c.gbx << ": no " << c.expected << " (run `gbxc test --update` and review it)\n";
      break;
    case GoldenOutcome::Fail:
      ++failed;
      out << "FAIL " << c.gbx << "\n" << r.diff;
      break;
    }
  }
  out << fmt::format("{} passed, {} failed\n", passed, failed);
  if (!problems.empty()) return 2;
  return failed == 0 ? 0 : 1;
}

int formatFiles(const Options& o, std::ostream& out, std::ostream& err) {
  // Every file named first: a folder that cannot be read stops the run before any file
  // is changed.
  std::vector<std::string> files;
  for (const auto& arg : o.files) {
    std::string problem;
    std::error_code ec;
    bool folder = arg != "-" && std::filesystem::is_directory(arg, ec);
    for (auto& f : folder ? gbxFilesBelow(arg, problem) : std::vector<std::string>{arg}) files.push_back(std::move(f));
    if (!problem.empty()) {
      err << "gbxc fmt: " << problem << "; nothing was changed\n";
      return 3;
    }
  }
  int status = 0;
  auto raise = [&](int s) { status = std::max(status, s); };
  for (const auto& path : files) {
    std::string text;
    if (path == "-") {
      text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    } else {
      errno = 0;
      std::ifstream f(path, std::ios::binary);
      if (!f) {
        err << fmt::format("gbxc fmt: cannot read `{}`: {}\n", path, errno ? std::strerror(errno) : "unreadable");
        raise(3);
        continue;
      }
      text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    }
    source::SourceManager sm;
    diag::DiagnosticEngine diags;
    std::optional<std::string> formatted;
    try {
      formatted = format::formatText(path == "-" ? "<stdin>" : path, text, sm, diags);
    } catch (const std::logic_error& e) {
      err << "gbxc fmt: " << e.what() << "\n";
      raise(3);
      continue;
    }
    if (!formatted) {
      err << diags.renderText(sm);
      raise(1);
      continue;
    }
    const std::string name = path == "-" ? "<stdin>" : path;
    if (*formatted == text) {
      if (path == "-" && !o.check) out << *formatted;
    } else if (o.check) {
      out << unifiedDiff(text, *formatted, name, name + " (formatted)");
      raise(1);
    } else if (path == "-") {
      out << *formatted;
    } else if (::access(path.c_str(), W_OK) != 0) {
      // Renaming over a file the user may not write would change it all the same.
      err << fmt::format("gbxc fmt: `{}` is not laid out, but it is read-only: left as it was\n", path);
      raise(3);
    } else if (std::string e = rt::writeWhole(path, *formatted); !e.empty()) {
      err << "gbxc fmt: " << e << "\n";
      raise(3);
    } else {
      out << "formatted " << path << "\n";
    }
  }
  return status;
}

} // namespace

// The options and commands `run` knows, for "did you mean" (and the reference's test).
const std::vector<std::string> kOptions = {"--check",   "--format", "--gearbox",    "--help",       "--jobs",     "--max-designs",
                                           "--no-timings", "--quiet", "--time-limit", "--timings",   "--update",   "--version",
                                           "-h",        "-j",       "-o",           "-q"};
const std::vector<std::string> kCommands = {"solve", "check", "dump", "test", "fmt", "lsp"};
const std::vector<std::string>& optionNames() { return kOptions; }
const std::vector<std::string>& commandNames() { return kCommands; }

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, const TestSettings& testSettings) {
  Options o;
  o.test = testSettings;
  std::vector<std::string> positional;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    // The option's argument, consumed; nullptr when the line ends.
    auto value = [&]() -> const std::string* { return i + 1 < args.size() ? &args[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      // After a command, that command's options.
      const char* text = usageOf(positional.empty() ? "" : positional[0]);
      out << (text ? text : kUsage);
      return 0;
    }
    if (a == "--version") {
      out << "gbxc " << GBX_VERSION << "\n";
      return 0;
    }
    if (a == "--format") {
      auto v = value();
      if (!v) return usage(err, "--format needs a value");
      o.format = *v;
    } else if (a == "--gearbox") {
      auto v = value();
      if (!v) return usage(err, "--gearbox needs a name");
      o.gearbox = *v;
    } else if (a == "-o") {
      auto v = value();
      if (!v) return usage(err, "-o needs a directory");
      o.outDir = *v;
    } else if (a == "--jobs" || a == "-j") {
      auto v = value();
      int n = 0;
      if (!v || std::from_chars(v->data(), v->data() + v->size(), n).ec != std::errc{} || n < 1 || n > 256)
        return usage(err, "--jobs needs a whole number from 1 to 256");
      o.jobs = n;
    } else if (a == "--max-designs" || a == "--time-limit") {
      auto v = value();
      double x = 0;
      // A positive number; 1e12 is as good as 1000000000000.
      auto parsed = v ? std::from_chars(v->data(), v->data() + v->size(), x) : std::from_chars_result{};
      const double most = a == "--max-designs" ? gbx::cat::budget::kMostMaxDesigns : gbx::cat::budget::kMostTimeLimit;
      if (!v || parsed.ec != std::errc{} || parsed.ptr != v->data() + v->size() || !(x > 0) || !(x <= most))
        return usage(err, fmt::format("{} needs a positive number{} up to {:g}", a, a == "--time-limit" ? " of seconds" : "", most));
      (a == "--max-designs" ? o.maxDesigns : o.timeLimit) = x;
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else if (a == "--update") {
      o.update = true;
    } else if (a == "--no-timings") {
      o.timings = false;
    } else if (a == "--timings") {
      o.testTimings = true;
    } else if (a == "--check") {
      o.check = true;
    } else if (a.size() > 1 && a[0] == '-') {
      return usage(err, fmt::format("unknown option `{}`{}", a, diag::suggestion(diag::closest(a, kOptions))));
    } else {
      positional.push_back(a);
    }
  }
  if (positional.empty()) return usage(err, "no command given");
  // `gbxc help [COMMAND]`: that command's usage.
  if (positional[0] == "help") {
    const std::string command = positional.size() > 1 ? positional[1] : "";
    if (const char* text = usageOf(command)) {
      out << text;
      return 0;
    }
    return usage(err, fmt::format("no command `{}`{}", command, diag::suggestion(diag::closest(command, kCommands))));
  }
  o.command = positional[0];
  positional.erase(positional.begin());
  if (o.command == "dump") {
    if (positional.empty() || (positional[0] != "ast" && positional[0] != "ir"))
      return usage(err, "`dump` takes `ast` or `ir`, then a file");
    o.sub = positional[0];
    positional.erase(positional.begin());
  }
  o.files = positional;
  // --format names a row of the runtime's table of report formats; check, dump and test
  // print diagnostics, which come in fewer forms.
  const rt::ReportFormat* format = rt::findReportFormat(o.format);
  if (!format || (o.command != "solve" && !format->diagnostics)) {
    std::vector<std::string> names;
    for (const auto& f : rt::reportFormats())
      if (o.command == "solve" || f.diagnostics) names.emplace_back(f.name);
    return usage(err, fmt::format("unknown format `{}` for `{}`{} (it takes {})", o.format, o.command,
                                  diag::suggestion(diag::closest(o.format, names)), fmt::join(names, ", ")));
  }
  // A dump is the program as text; its diagnostics in JSON would make a file that is neither.
  if (o.command == "dump" && format != &rt::reportFormats().front())
    return usage(err, "`dump` prints text only; `check --format json` gives the diagnostics as JSON");
  if (o.command == "test") {
    if (o.files.empty()) return usage(err, "`test` needs at least one file or folder");
    return test(o, out, err);
  }
  if (o.check && o.command != "fmt") return usage(err, "--check goes with `fmt`");
  if (o.command == "fmt") {
    if (o.files.empty()) return usage(err, "`fmt` needs at least one file or folder (or - for standard input)");
    if (o.update || o.testTimings || !o.outDir.empty() || !o.gearbox.empty() || o.format != "text")
      return usage(err, "`fmt` takes only files, folders and --check");
    return formatFiles(o, out, err);
  }
  if (o.command == "lsp") {
    if (!o.files.empty()) return usage(err, "`lsp` takes no file: it serves the editor's documents on stdin/stdout");
    return lsp::serve(std::cin, out);
  }
  if (o.command != "check" && o.command != "dump" && o.command != "solve")
    return usage(err, fmt::format("unknown command `{}`{}", o.command, diag::suggestion(diag::closest(o.command, kCommands))));
  if (o.files.size() != 1) return usage(err, fmt::format("`{}` takes exactly one file", o.command));
  if (o.update) return usage(err, "--update goes with `test`");
  if (o.testTimings) return usage(err, "--timings goes with `test` (solve shows CPU times unless --no-timings)");
  if (o.command == "check") return check(o, out, err);
  if (o.command == "dump") return dump(o, out, err);
  return solve(o, out, err);
}

} // namespace gbx::driver
