#include "diag/Diagnostic.h"

#include <algorithm>
#include <tuple>

#include <fmt/format.h>

namespace gbx::diag {

Diagnostic& DiagnosticEngine::error(std::string code, source::Span span, std::string message) {
  diags_.push_back({Severity::Error, std::move(code), span, std::move(message), {}});
  return diags_.back();
}

Diagnostic& DiagnosticEngine::warning(std::string code, source::Span span, std::string message) {
  diags_.push_back({Severity::Warning, std::move(code), span, std::move(message), {}});
  return diags_.back();
}

bool DiagnosticEngine::hasErrors() const { return errorCount() > 0; }

int DiagnosticEngine::errorCount() const {
  return static_cast<int>(std::count_if(diags_.begin(), diags_.end(),
                                        [](const Diagnostic& d) { return d.severity == Severity::Error; }));
}

int DiagnosticEngine::warningCount() const {
  return static_cast<int>(std::count_if(diags_.begin(), diags_.end(),
                                        [](const Diagnostic& d) { return d.severity == Severity::Warning; }));
}

std::vector<Diagnostic> DiagnosticEngine::sorted() const {
  std::vector<Diagnostic> v = diags_;
  auto key = [](const Diagnostic& d) {
    return std::make_tuple(d.span.file, d.span.line, d.span.col, d.code, d.message);
  };
  std::stable_sort(v.begin(), v.end(), [&](const Diagnostic& a, const Diagnostic& b) { return key(a) < key(b); });
  v.erase(std::unique(v.begin(), v.end(), [&](const Diagnostic& a, const Diagnostic& b) { return key(a) == key(b); }),
          v.end());
  return v;
}

namespace {

const char* severityName(Severity s) {
  switch (s) {
  case Severity::Error: return "error";
  case Severity::Warning: return "warning";
  case Severity::Note: return "note";
  }
  return "error";
}

// Source window: the line, then carets under the span (to the line's end if it spans lines).
// A long line (a generated file, a line of a thousand tolerances) is cut to a window around
// the span, marked with `…`, so a diagnostic's size never grows with the line's.
void renderWindow(std::string& out, const source::SourceManager& sm, const source::Span& span) {
  if (!span.valid() || span.file >= sm.size()) return;
  const auto& f = sm.get(span.file);
  std::string text = f.line(span.line);
  std::replace(text.begin(), text.end(), '\t', ' ');
  std::string num = std::to_string(span.line);
  std::string pad(num.size(), ' ');
  std::vector<size_t> starts;  // byte offset of each code point
  for (size_t i = 0; i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) starts.push_back(i);
  int lineLen = static_cast<int>(starts.size());
  int startCol = std::clamp(span.col, 1, lineLen + 1);
  int endCol = span.endLine == span.line ? span.endCol : lineLen;
  endCol = std::clamp(endCol, startCol, std::max(startCol, lineLen));
  constexpr int kWidth = 120, kBefore = 40;
  int first = 1, last = lineLen;
  if (lineLen > kWidth) {
    first = std::max(1, std::min(startCol - kBefore, lineLen - kWidth + 1));
    last = std::min(lineLen, first + kWidth - 1);
  }
  auto byteAt = [&](int col) { return col > lineLen ? text.size() : starts[static_cast<size_t>(col - 1)]; };
  std::string shown = text.substr(byteAt(first), byteAt(last + 1) - byteAt(first));
  std::string lead = first > 1 ? "… " : "";
  std::string tail = last < lineLen ? " …" : "";
  out += fmt::format("{} |\n{} | {}{}{}\n", pad, num, lead, shown, tail);
  int caretFrom = startCol - first + (first > 1 ? 2 : 0);
  int caretLen = std::max(1, std::min(endCol, last) - startCol + 1);
  out += fmt::format("{} | {}{}\n", pad, std::string(static_cast<size_t>(caretFrom), ' '),
                     std::string(static_cast<size_t>(caretLen), '^'));
}

} // namespace

std::string DiagnosticEngine::renderText(const source::SourceManager& sm) const {
  std::string out;
  for (const auto& d : sorted()) {
    out += fmt::format("{}[{}]: {}\n", severityName(d.severity), d.code, d.message);
    if (d.span.valid() && d.span.file < sm.size()) {
      out += fmt::format("  --> {}:{}:{}\n", sm.get(d.span.file).displayPath(), d.span.line, d.span.col);
      renderWindow(out, sm, d.span);
    }
    for (const auto& n : d.notes) {
      out += fmt::format("note: {}\n", n.message);
      if (n.span.valid() && n.span.file < sm.size()) {
        out += fmt::format("  --> {}:{}:{}\n", sm.get(n.span.file).displayPath(), n.span.line, n.span.col);
        renderWindow(out, sm, n.span);
      }
    }
    out += "\n";
  }
  int e = errorCount(), w = warningCount();
  if (e > 0 || w > 0)
    out += fmt::format("{} error{}, {} warning{}\n", e, e == 1 ? "" : "s", w, w == 1 ? "" : "s");
  return out;
}

std::string jsonEscape(const std::string& s) {
  std::string o;
  for (unsigned char c : s) {
    switch (c) {
    case '"': o += "\\\""; break;
    case '\\': o += "\\\\"; break;
    case '\n': o += "\\n"; break;
    case '\t': o += "\\t"; break;
    case '\r': o += "\\r"; break;
    default:
      if (c < 0x20)
        o += fmt::format("\\u{:04x}", c);
      else
        o += static_cast<char>(c);
    }
  }
  return o;
}

std::string DiagnosticEngine::renderJson(const source::SourceManager& sm) const {
  auto spanJson = [&](const source::Span& s) {
    if (!s.valid() || s.file >= sm.size()) return std::string("null");
    return fmt::format(R"({{"file": "{}", "line": {}, "column": {}, "end_line": {}, "end_column": {}}})",
                       jsonEscape(sm.get(s.file).displayPath()), s.line, s.col, s.endLine, s.endCol);
  };
  std::string out = "[";
  bool first = true;
  for (const auto& d : sorted()) {
    out += first ? "\n  " : ",\n  ";
    first = false;
    out += fmt::format(R"({{"severity": "{}", "code": "{}", "message": "{}", "span": {}, "notes": [)",
                       severityName(d.severity), d.code, jsonEscape(d.message), spanJson(d.span));
    for (size_t i = 0; i < d.notes.size(); ++i)
      out += fmt::format(R"({}{{"message": "{}", "span": {}}})", i ? ", " : "", jsonEscape(d.notes[i].message),
                         spanJson(d.notes[i].span));
    out += "]}";
  }
  out += first ? "]\n" : "\n]\n";
  return out;
}

} // namespace gbx::diag
