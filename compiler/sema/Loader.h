#pragma once
// Reads a file and everything it imports, each once, into the source manager and
// parses it. Imports name a stdlib module (`import materials;`) or a path relative to
// the importing file (`import "local/presets.gbx";`).
#include <string>
#include <vector>

#include "ast/Ast.h"
#include "diag/Diagnostic.h"
#include "source/Source.h"

namespace gbx::sema {

// An import that found its file: where it is written and what it loaded.
struct ResolvedImport {
  source::Span word;  // the module name or path, in the importing file
  int target = -1;    // the loaded file's id
};

struct LoadedProgram {
  std::vector<ast::File> files;  // the main file first, then imports in first-seen order
  std::vector<ResolvedImport> imports;
  bool parseErrors = false;
  bool mainMissing = false;
};

// Folders of modules named by $GBX_PATH (colon-separated), searched first.
std::vector<std::string> modulePath();
// Folders searched for stdlib modules: $GBX_STDLIB_PATH (colon-separated), then the stdlib
// installed beside the program (share/gbxc/stdlib next to or above its folder).
std::vector<std::string> stdlibSearchPath();
// Where the running program is, for a program that is not its process's executable (the
// Python module, a shared object in python3): the stdlib is looked for beside and above it.
// Set before the first compilation.
void setProgramLocation(const std::string& file);
// The modules found in all of them, by name, sorted.
std::vector<std::string> stdlibModules();

LoadedProgram load(const std::string& mainPath, source::SourceManager& sm, diag::DiagnosticEngine& diags);
// The same for text already in memory (tests).
LoadedProgram loadText(const std::string& displayPath, const std::string& text, source::SourceManager& sm,
                       diag::DiagnosticEngine& diags);

} // namespace gbx::sema
