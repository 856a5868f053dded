#pragma once
// Diagnostics are collected, never thrown; the engine sorts them by position so the
// output is the same whatever order the passes found them in.
#include <string>
#include <vector>

#include "source/Source.h"

namespace gbx::diag {

enum class Severity { Error, Warning, Note };

struct Note {
  source::Span span;
  std::string message;
};

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string code;  // stable: E0302, W0501, …
  source::Span span;
  std::string message;
  std::vector<Note> notes;
};

class DiagnosticEngine {
public:
  Diagnostic& error(std::string code, source::Span span, std::string message);
  Diagnostic& warning(std::string code, source::Span span, std::string message);
  bool hasErrors() const;
  int errorCount() const;
  int warningCount() const;
  const std::vector<Diagnostic>& all() const { return diags_; }
  // Sorted by file, position, code; exact duplicates dropped.
  std::vector<Diagnostic> sorted() const;

  // Render as text: code, place, the numbered source line with a caret, the sentence (docs/diagnostics.md).
  std::string renderText(const source::SourceManager& sm) const;
  // One JSON object per diagnostic, in a JSON array.
  std::string renderJson(const source::SourceManager& sm) const;

private:
  std::vector<Diagnostic> diags_;
};

std::string jsonEscape(const std::string& s);

} // namespace gbx::diag
