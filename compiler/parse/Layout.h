#pragma once
// The formatter's view of a file: every token but blanks, comments included, each with
// what the parse tree says about the space around it. The formatter decides where spaces
// and line breaks go from this alone, so it never needs the grammar.
#include <optional>
#include <string>
#include <vector>

#include "diag/Diagnostic.h"
#include "source/Source.h"

namespace gbx::parse {

struct LayoutToken {
  enum class Kind : unsigned char { Keyword, Name, Number, String, Punct, LineComment, BlockComment };
  Kind kind = Kind::Punct;
  std::string text;
  int line = 0, endLine = 0; // source lines of the first and the last character
  bool unit = false;         // part of the unit after a number (its parts touch: `N*m`)
  bool unitStart = false;    // the unit's first token
  bool prefix = false;       // a prefix minus
  bool call = false;         // the `(` of a call
  bool power = false;        // the `^` of an expression (not of a unit)
  bool blockBrace = false;   // `{` or `}` of a statement's block (not of a set)
  bool stmtStart = false;    // the first token of a statement or a declaration
  bool stmtEnd = false;      // the `;` or `}` that ends one
  bool aligned = false;      // the `=` or `in` of `x = 1;`, `x in 1..5;`, `let`, `const`
  int match = -1;            // the index of the other bracket of a pair

  bool comment() const { return kind == Kind::LineComment || kind == Kind::BlockComment; }
};

// The tokens of a loaded file; nullopt, with the errors in `diags`, when it does not parse.
std::optional<std::vector<LayoutToken>> layout(const source::SourceManager& sm, int fileId,
                                               diag::DiagnosticEngine& diags);

// Every token of a text as the grammar's lexer makes it, whatever a parser would say of
// them: for readers of a half-typed file (completion). Offsets are bytes. Empty when the
// text is not UTF-8.
struct LexToken {
  enum class Kind : unsigned char { Word, Number, String, Punct, Comment, Unterminated };
  Kind kind = Kind::Punct; // Word: a name or keyword; Unterminated: a string or comment left open
  size_t begin = 0, end = 0;
  int line = 1; // as the parser counts lines (LF)
};
std::vector<LexToken> lex(const std::string& text);

} // namespace gbx::parse
