#pragma once
// The only door to ANTLR: text in, AST and diagnostics out.
#include "ast/Ast.h"
#include "diag/Diagnostic.h"
#include "source/Source.h"

namespace gbx::parse {

// Parses one loaded file. Lexical and syntax errors are reported to `diags`; the
// returned tree holds whatever could be recovered and must not be analysed further
// when errors were reported for this file.
ast::File parseFile(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags);

} // namespace gbx::parse
