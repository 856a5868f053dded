#pragma once
// Inside parse/ only: the ANTLR objects of one parsed file, for the AST builder and the
// layout walk (the formatter's view of the tokens).
#include <memory>

#include <antlr4-runtime.h>

#include "GbxLexer.h"
#include "GbxParser.h"
#include "diag/Diagnostic.h"
#include "source/Source.h"

namespace gbx::parse {

struct ParsedTree {
  std::unique_ptr<antlr4::ANTLRInputStream> input;
  std::unique_ptr<grammar::GbxLexer> lexer;
  std::unique_ptr<antlr4::CommonTokenStream> tokens;
  std::unique_ptr<grammar::GbxParser> parser;
  grammar::GbxParser::FileContext* tree = nullptr; // null: invalid UTF-8 or nested too deeply
};

// Lexes and parses one loaded file, reporting lexical and syntax errors to `diags`.
ParsedTree parseTree(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags);

// Whether a text is UTF-8 (the runtime's decoder throws on anything else); the first bad
// byte is reported to `diags` as in file `file`.
bool validUtf8(const std::string& t, int file, diag::DiagnosticEngine& diags);

// The span of one token (columns in code points, 1-based).
source::Span tokenSpan(int file, antlr4::Token* t);

} // namespace gbx::parse
