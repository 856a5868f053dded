#include "lsp/Json.h"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "diag/Diagnostic.h"

namespace gbx::lsp {

namespace {

const Json kNull;
const std::string kEmpty;

void dumpString(const std::string& s, std::string& out) {
  out += '"';
  out += diag::jsonEscape(s);
  out += '"';
}

class Parser {
public:
  explicit Parser(const std::string& t) : t_(t) {}

  std::optional<Json> document() {
    auto v = value(0);
    space();
    if (!v || i_ != t_.size()) return std::nullopt;
    return v;
  }

private:
  static constexpr int kDepth = 256;  // deeper nesting is refused, not recursed into

  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t' || t_[i_] == '\n' || t_[i_] == '\r')) ++i_;
  }
  bool take(char c) {
    space();
    if (i_ < t_.size() && t_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  bool word(const char* w) {
    size_t n = std::char_traits<char>::length(w);
    if (t_.compare(i_, n, w) != 0) return false;
    i_ += n;
    return true;
  }

  std::optional<Json> value(int depth) {
    if (depth > kDepth) return std::nullopt;
    space();
    if (i_ >= t_.size()) return std::nullopt;
    char c = t_[i_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') {
      auto s = str();
      if (!s) return std::nullopt;
      return Json(std::move(*s));
    }
    if (word("true")) return Json(true);
    if (word("false")) return Json(false);
    if (word("null")) return Json();
    return num();
  }

  std::optional<Json> object(int depth) {
    ++i_;
    Json::Object o;
    if (take('}')) return Json(std::move(o));
    do {
      space();
      if (i_ >= t_.size() || t_[i_] != '"') return std::nullopt;
      auto k = str();
      if (!k || !take(':')) return std::nullopt;
      auto v = value(depth + 1);
      if (!v) return std::nullopt;
      o[*k] = std::move(*v);
    } while (take(','));
    if (!take('}')) return std::nullopt;
    return Json(std::move(o));
  }

  std::optional<Json> array(int depth) {
    ++i_;
    Json::Array a;
    if (take(']')) return Json(std::move(a));
    do {
      auto v = value(depth + 1);
      if (!v) return std::nullopt;
      a.push_back(std::move(*v));
    } while (take(','));
    if (!take(']')) return std::nullopt;
    return Json(std::move(a));
  }

  static void utf8(unsigned cp, std::string& out) {
    if (cp < 0x80) out += static_cast<char>(cp);
    else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  std::optional<unsigned> hex4() {
    if (i_ + 4 > t_.size()) return std::nullopt;
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      char c = t_[i_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<unsigned>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<unsigned>(c - 'A' + 10);
      else return std::nullopt;
    }
    return v;
  }

  std::optional<std::string> str() {
    ++i_;  // the opening quote
    std::string s;
    while (i_ < t_.size()) {
      char c = t_[i_++];
      if (c == '"') return s;
      if (c != '\\') {
        s += c;
        continue;
      }
      if (i_ >= t_.size()) return std::nullopt;
      char e = t_[i_++];
      switch (e) {
      case '"': s += '"'; break;
      case '\\': s += '\\'; break;
      case '/': s += '/'; break;
      case 'b': s += '\b'; break;
      case 'f': s += '\f'; break;
      case 'n': s += '\n'; break;
      case 'r': s += '\r'; break;
      case 't': s += '\t'; break;
      case 'u': {
        auto cp = hex4();
        if (!cp) return std::nullopt;
        unsigned u = *cp;
        // A surrogate pair makes one code point; a lone surrogate becomes U+FFFD.
        if (u >= 0xD800 && u <= 0xDBFF && t_.compare(i_, 2, "\\u") == 0) {
          i_ += 2;
          auto lo = hex4();
          if (!lo) return std::nullopt;
          u = *lo >= 0xDC00 && *lo <= 0xDFFF ? 0x10000 + ((u - 0xD800) << 10) + (*lo - 0xDC00) : 0xFFFD;
        } else if (u >= 0xD800 && u <= 0xDFFF) {
          u = 0xFFFD;
        }
        utf8(u, s);
        break;
      }
      default: return std::nullopt;
      }
    }
    return std::nullopt;
  }

  std::optional<Json> num() {
    size_t start = i_;
    if (i_ < t_.size() && t_[i_] == '-') ++i_;
    while (i_ < t_.size() && (std::isdigit(static_cast<unsigned char>(t_[i_])) || t_[i_] == '.' || t_[i_] == 'e' ||
                              t_[i_] == 'E' || t_[i_] == '+' || t_[i_] == '-'))
      ++i_;
    if (i_ == start) return std::nullopt;
    std::string text = t_.substr(start, i_ - start);
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    if (!end || *end != '\0' || !std::isfinite(v)) return std::nullopt;
    return Json(v);
  }

  const std::string& t_;
  size_t i_ = 0;
};

} // namespace

const Json& Json::operator[](const std::string& key) const {
  if (!isObject()) return kNull;
  const auto& o = *std::get<std::shared_ptr<Object>>(v_);
  auto it = o.find(key);
  return it == o.end() ? kNull : it->second;
}

const Json& Json::at(size_t i) const {
  if (!isArray()) return kNull;
  const auto& a = *std::get<std::shared_ptr<Array>>(v_);
  return i < a.size() ? a[i] : kNull;
}

size_t Json::size() const {
  if (isArray()) return std::get<std::shared_ptr<Array>>(v_)->size();
  if (isObject()) return std::get<std::shared_ptr<Object>>(v_)->size();
  return 0;
}

const std::string& Json::string() const { return isString() ? std::get<std::string>(v_) : kEmpty; }

std::string Json::dump() const {
  std::string out;
  switch (v_.index()) {
  case 0: return "null";
  case 1: return std::get<bool>(v_) ? "true" : "false";
  case 2: {
    double d = std::get<double>(v_);
    if (!std::isfinite(d)) return "null";
    if (d == std::floor(d) && std::fabs(d) < 1e15) return fmt::format("{}", static_cast<long long>(d));
    return fmt::format("{}", d);
  }
  case 3: dumpString(std::get<std::string>(v_), out); return out;
  case 4: {
    out += '[';
    bool first = true;
    for (const auto& x : *std::get<std::shared_ptr<Array>>(v_)) {
      if (!first) out += ',';
      first = false;
      out += x.dump();
    }
    out += ']';
    return out;
  }
  default: {
    out += '{';
    bool first = true;
    for (const auto& [k, x] : *std::get<std::shared_ptr<Object>>(v_)) {
      if (!first) out += ',';
      first = false;
      dumpString(k, out);
      out += ':';
      out += x.dump();
    }
    out += '}';
    return out;
  }
  }
}

std::optional<Json> Json::parse(const std::string& text) { return Parser(text).document(); }

} // namespace gbx::lsp
