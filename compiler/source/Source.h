#pragma once
// Source files and positions. Columns count Unicode code points, 1-based, as the
// parser sees them, so a caret under `35°` lands where the reader expects.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace gbx::source {

struct Span {
  int file = -1;
  int line = 0, col = 0;        // first character
  int endLine = 0, endCol = 0;  // last character (inclusive)
  bool valid() const { return file >= 0 && line > 0; }
};

// Joins two spans into one covering both (same file assumed).
Span cover(const Span& a, const Span& b);

class SourceFile {
public:
  SourceFile(std::string displayPath, std::string absPath, std::string text);
  const std::string& displayPath() const { return displayPath_; }
  const std::string& absPath() const { return absPath_; }
  const std::string& text() const { return text_; }
  // Line n (1-based) without its newline; empty past the end.
  std::string line(int n) const;
  int lineCount() const { return static_cast<int>(lineStarts_.size()); }

private:
  std::string displayPath_, absPath_, text_;
  std::vector<size_t> lineStarts_;
};

class SourceManager {
public:
  int add(std::string displayPath, std::string absPath, std::string text);
  const SourceFile& get(int id) const { return *files_.at(static_cast<size_t>(id)); }
  int size() const { return static_cast<int>(files_.size()); }
  // Id of an already loaded file by absolute path, or -1.
  int find(const std::string& absPath) const;

private:
  std::vector<std::unique_ptr<SourceFile>> files_;
};

// Number of code points in a UTF-8 string.
int codePoints(const std::string& utf8);
// Bytes of the UTF-8 sequence a lead byte starts (1 for a stray continuation byte).
inline size_t utf8Length(unsigned char lead) {
  return lead < 0x80 ? 1 : (lead >> 5) == 6 ? 2 : (lead >> 4) == 14 ? 3 : (lead >> 3) == 30 ? 4 : 1;
}

} // namespace gbx::source
