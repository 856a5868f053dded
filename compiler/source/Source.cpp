#include "source/Source.h"

namespace gbx::source {

Span cover(const Span& a, const Span& b) {
  if (!a.valid()) return b;
  if (!b.valid()) return a;
  Span s = a;
  if (b.line < s.line || (b.line == s.line && b.col < s.col)) {
    s.line = b.line;
    s.col = b.col;
  }
  if (b.endLine > s.endLine || (b.endLine == s.endLine && b.endCol > s.endCol)) {
    s.endLine = b.endLine;
    s.endCol = b.endCol;
  }
  return s;
}

SourceFile::SourceFile(std::string displayPath, std::string absPath, std::string text)
    : displayPath_(std::move(displayPath)), absPath_(std::move(absPath)), text_(std::move(text)) {
  lineStarts_.push_back(0);
  for (size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') lineStarts_.push_back(i + 1);
}

std::string SourceFile::line(int n) const {
  if (n < 1 || n > lineCount()) return "";
  size_t b = lineStarts_[static_cast<size_t>(n - 1)];
  size_t e = text_.find('\n', b);
  if (e == std::string::npos) e = text_.size();
  std::string s = text_.substr(b, e - b);
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

int SourceManager::add(std::string displayPath, std::string absPath, std::string text) {
  files_.push_back(std::make_unique<SourceFile>(std::move(displayPath), std::move(absPath), std::move(text)));
  return static_cast<int>(files_.size()) - 1;
}

int SourceManager::find(const std::string& absPath) const {
  for (size_t i = 0; i < files_.size(); ++i)
    if (files_[i]->absPath() == absPath) return static_cast<int>(i);
  return -1;
}

int codePoints(const std::string& utf8) {
  int n = 0;
  for (unsigned char c : utf8)
    if ((c & 0xC0) != 0x80) ++n;
  return n;
}

} // namespace gbx::source
