#include "format/Formatter.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "parse/Layout.h"

namespace gbx::format {

namespace {

using parse::LayoutToken;
using Kind = LayoutToken::Kind;

std::string lf(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i)
    if (!(s[i] == '\r' && i + 1 < s.size() && s[i + 1] == '\n')) out += s[i];
  return out;
}

std::string rtrim(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.pop_back();
  return s;
}

// Code points after the last line break: where the next character lands.
int widthAfterBreak(const std::string& s) {
  size_t nl = s.rfind('\n');
  return source::codePoints(nl == std::string::npos ? s : s.substr(nl + 1));
}

struct Line {
  std::vector<int> toks;
  bool blankBefore = false;
  bool opensBlock = false;  // ends with the `{` of a block that spans lines
  std::string code;         // indentation and code, without a trailing line comment
  std::string comment;      // the trailing line comment
  bool commentOnly = false; // nothing but a line comment
  int depth = 0;
  bool alignable = false; // one whole `x = …;` or `x in …;` statement
  size_t opOffset = 0;    // where its `=` or `in` starts in `code`
  int opCol = 0;
};

class Formatter {
public:
  explicit Formatter(const std::vector<LayoutToken>& t) : t_(t) {}

  std::string run() {
    split();
    emit();
    alignOperators();
    alignComments();
    std::string out;
    for (size_t i = 0; i < lines_.size(); ++i) {
      if (i > 0 && lines_[i].blankBefore) out += '\n';
      out += rtrim(lines_[i].code + lines_[i].comment);
      out += '\n';
    }
    return out;
  }

private:
  const LayoutToken& at(int i) const { return t_[static_cast<size_t>(i)]; }
  bool isOpen(int i) const { return at(i).blockBrace && at(i).text == "{"; }
  bool isClose(int i) const { return at(i).blockBrace && at(i).text == "}"; }
  // A block whose braces stand on different lines keeps its statements on lines of their own.
  bool spansLines(int i) const {
    const LayoutToken& x = at(i);
    return x.blockBrace && x.match >= 0 && x.line != at(x.match).line;
  }

  // Lines as written, with the breaks a block spanning lines needs, at most one blank line
  // in a row, and none just inside braces.
  void split() {
    int prevCode = -1;
    size_t prevCodeLine = 0;
    for (int i = 0; i < static_cast<int>(t_.size()); ++i) {
      const LayoutToken& x = at(i);
      bool brk = i == 0, blank = false;
      if (i > 0) {
        const LayoutToken& p = at(i - 1);
        if (x.line > p.endLine) {
          brk = true;
          blank = x.line - p.endLine >= 2;
        } else if (p.kind == Kind::LineComment) {
          brk = true; // a line comment ends its line, whatever ends lines in the file
        } else if (!x.comment()) {
          brk = (isClose(i) && spansLines(i)) ||
                (prevCode >= 0 && prevCodeLine + 1 == lines_.size() && spansLines(prevCode));
        }
      }
      if (brk) {
        Line l;
        l.blankBefore = blank && !lines_.empty() && !lines_.back().opensBlock && !(isClose(i) && spansLines(i));
        lines_.push_back(std::move(l));
      }
      lines_.back().toks.push_back(i);
      if (!x.comment()) {
        prevCode = i;
        prevCodeLine = lines_.size() - 1;
        lines_.back().opensBlock = isOpen(i) && spansLines(i);
      }
    }
  }

  // Blanks between two tokens on one line. `inBlock`: inside braces opened on this line.
  int space(int a, int b, bool inBlock) const {
    const LayoutToken &A = at(a), &B = at(b);
    if (A.comment() || B.comment()) return 1;
    if (A.stmtEnd && B.stmtStart) return inBlock ? 1 : 2;
    if (isOpen(a) && isClose(b)) return 0;
    if (B.kind == Kind::Punct && (B.text == ";" || B.text == "," || B.text == ":" || B.text == ")")) return 0;
    if (A.kind == Kind::Punct && A.text == "(") return 0;
    if (A.kind == Kind::Punct && A.text == "{" && !A.blockBrace) return 0;
    if (B.kind == Kind::Punct && B.text == "}" && !B.blockBrace) return 0;
    if (A.text == "." || B.text == "." || A.text == ".." || B.text == "..") return 0;
    if (B.call) return 0;
    if (B.unit) return B.unitStart && B.text != "%" && B.text != "\u00B0" ? 1 : 0;
    if (A.prefix) return 0;
    // `x^2`, but `2 mm ^ 2`: glued to a unit, the power would join the unit.
    if (B.power) return afterUnit(b) ? 1 : 0;
    if (A.power) return afterUnit(a) ? 1 : 0;
    return 1;
  }

  // Whether the code token before token i is part of a unit.
  bool afterUnit(int i) const {
    for (int k = i - 1; k >= 0; --k)
      if (!at(k).comment()) return at(k).unit;
    return false;
  }

  void emit() {
    int depth = 0;
    std::vector<int> brackets; // output columns of the open `(` and set `{`
    int stmtTok = -1, stmtCol = 0, prevCode = -1;
    for (Line& l : lines_) {
      const int first = l.toks.front();
      // A block's `{` on a line of its own stands where its statement does.
      const bool cont = prevCode >= 0 && !at(prevCode).stmtEnd && !isOpen(prevCode) && !isOpen(first);
      l.depth = isClose(first) && spansLines(first) ? depth - 1 : depth;
      int indent = 2 * l.depth;
      if (cont) {
        // Inside brackets: under the first thing after the innermost open one; otherwise
        // under what follows the statement's keyword (`output a,` / `       b;`).
        if (!brackets.empty())
          indent = brackets.back() + 1;
        else if (stmtTok >= 0)
          indent = stmtCol + (at(stmtTok).kind == Kind::Keyword ? source::codePoints(at(stmtTok).text) + 1 : 4);
      }
      l.code.assign(static_cast<size_t>(indent), ' ');
      int col = indent, inBlock = 0, starts = 0, opAt = -1;
      size_t opOffset = 0;
      for (size_t k = 0; k < l.toks.size(); ++k) {
        const int i = l.toks[k];
        const LayoutToken& x = at(i);
        if (x.kind == Kind::LineComment) {
          if (k == 0) {
            l.commentOnly = true;
            l.code += rtrim(x.text);
          } else {
            l.comment = rtrim(x.text);
          }
          break;
        }
        if (k > 0) {
          int n = space(l.toks[k - 1], i, inBlock > 0);
          l.code.append(static_cast<size_t>(n), ' ');
          col += n;
        }
        if (x.stmtStart) {
          stmtTok = i;
          stmtCol = col;
          if (inBlock == 0) ++starts;
        }
        if (x.aligned && inBlock == 0) {
          opAt = col;
          opOffset = l.code.size();
        }
        // `(` and a set's `{` (a block's braces and a comment's text are not brackets here).
        const bool bracket = x.kind == Kind::Punct && !x.blockBrace;
        if (bracket && (x.text == "(" || x.text == "{")) brackets.push_back(col);
        // A block comment's inner line ends are LF like the file's; its text is not code.
        l.code += x.kind == Kind::BlockComment ? lf(x.text) : x.text;
        col = x.text.find('\n') == std::string::npos ? col + source::codePoints(x.text) : widthAfterBreak(x.text);
        if (bracket && (x.text == ")" || x.text == "}") && !brackets.empty()) brackets.pop_back();
        if (isOpen(i)) spansLines(i) ? ++depth : ++inBlock;
        if (isClose(i)) spansLines(i) ? --depth : --inBlock;
        if (!x.comment()) prevCode = i;
      }
      // One statement, whole on this line, that sets a value.
      l.alignable = !cont && !l.commentOnly && at(first).stmtStart && starts == 1 && opAt >= 0 && prevCode >= 0 &&
                    at(prevCode).stmtEnd && l.code.find('\n') == std::string::npos;
      l.opCol = opAt;
      l.opOffset = opOffset;
    }
  }

  // Each run of consecutive lines at one depth, with no blank line between, that all pass
  // `in`: given to `align` as [a, b).
  template <class In, class Align> void runs(In in, Align align) {
    for (size_t a = 0; a < lines_.size();) {
      if (!in(lines_[a])) {
        ++a;
        continue;
      }
      size_t b = a + 1;
      while (b < lines_.size() && in(lines_[b]) && !lines_[b].blankBefore && lines_[b].depth == lines_[a].depth)
        ++b;
      align(a, b);
      a = b;
    }
  }

  // Runs of such statements line their `=` and `in` up.
  void alignOperators() {
    runs([](const Line& l) { return l.alignable; },
         [&](size_t a, size_t b) {
           int col = 0;
           for (size_t k = a; k < b; ++k)
             col = std::max(col, lines_[k].opCol);
           for (size_t k = a; k < b; ++k)
             lines_[k].code.insert(lines_[k].opOffset, static_cast<size_t>(col - lines_[k].opCol), ' ');
         });
  }

  // Runs of lines with trailing comments start them in one column, two blanks after the
  // longest code.
  void alignComments() {
    runs([](const Line& l) { return !l.comment.empty(); },
         [&](size_t a, size_t b) {
           int col = 0;
           for (size_t k = a; k < b; ++k)
             col = std::max(col, widthAfterBreak(rtrim(lines_[k].code)));
           for (size_t k = a; k < b; ++k) {
             Line& l = lines_[k];
             l.code = rtrim(l.code);
             l.code.append(static_cast<size_t>(col + 2 - widthAfterBreak(l.code)), ' ');
           }
         });
  }

  const std::vector<LayoutToken>& t_;
  std::vector<Line> lines_;
};

// Formatting moves blanks only: the same tokens, read the same way.
bool sameReading(const std::vector<LayoutToken>& a, const std::vector<LayoutToken>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const LayoutToken &x = a[i], &y = b[i];
    auto text = [](const LayoutToken& t) {
      return t.kind == Kind::LineComment ? rtrim(t.text) : t.kind == Kind::BlockComment ? lf(t.text) : t.text;
    };
    std::string tx = text(x), ty = text(y);
    if (x.kind != y.kind || tx != ty || x.unit != y.unit || x.unitStart != y.unitStart || x.prefix != y.prefix ||
        x.call != y.call || x.power != y.power || x.blockBrace != y.blockBrace || x.stmtStart != y.stmtStart ||
        x.stmtEnd != y.stmtEnd || x.aligned != y.aligned || x.match != y.match)
      return false;
  }
  return true;
}

} // namespace

std::optional<std::string> formatFile(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags) {
  auto tokens = parse::layout(sm, fileId, diags);
  if (!tokens) return std::nullopt;
  std::string out = Formatter(*tokens).run();
  // The result must read as the input did; a difference is a defect of the formatter, and
  // the file is better left alone than changed.
  source::SourceManager check;
  diag::DiagnosticEngine ignored;
  int id = check.add(sm.get(fileId).displayPath(), "", out);
  auto again = parse::layout(check, id, ignored);
  if (!again || !sameReading(*tokens, *again))
    throw std::logic_error(
        fmt::format("formatting `{}` would change how it reads; it is left as it was", sm.get(fileId).displayPath()));
  return out;
}

std::optional<std::string> formatText(const std::string& displayPath, const std::string& text,
                                      source::SourceManager& sm, diag::DiagnosticEngine& diags) {
  int id = sm.add(displayPath, "", text);
  return formatFile(sm, id, diags);
}

} // namespace gbx::format
