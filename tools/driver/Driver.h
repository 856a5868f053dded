#pragma once
// The pipeline, composed in one visible list of passes, and the command line.
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "ast/Ast.h"
#include "diag/Diagnostic.h"
#include "ir/Ir.h"
#include "sema/Loader.h"
#include "source/Source.h"

namespace gbx::driver {

struct Compilation {
  source::SourceManager sources;
  diag::DiagnosticEngine diags;
  sema::LoadedProgram loaded;
  ir::Program program;
  bool analysed = false;  // sema and lower ran (no parse errors)
  bool ok() const { return !diags.hasErrors(); }
};

// load+parse → sema → lower. Stops before sema when any file failed to parse.
std::unique_ptr<Compilation> compile(const std::string& path);
std::unique_ptr<Compilation> compileText(const std::string& displayPath, const std::string& text);

// Every option and command `run` accepts (docs/cli.md documents each).
const std::vector<std::string>& optionNames();
const std::vector<std::string>& commandNames();

// The command line, runnable in-process (the golden engine uses it). Returns the exit
// status: 0 success, 1 the spec has errors, 2 usage, 3 runtime failure.
// What only tests set: they cut work that another test of the same suite does in full.
struct TestSettings {
  int optimiserIterations = 0;  // Nelder-Mead iterations per candidate; 0: the optimiser's own
};
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, const TestSettings& test = {});

} // namespace gbx::driver
