#pragma once
// A JSON value, parser and writer: what the language server reads and writes. The parser
// takes any bytes: bad input is an error, never a crash (nesting is bounded).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gbx::lsp {

class Json {
public:
  using Array = std::vector<Json>;
  using Object = std::map<std::string, Json>;

  Json() = default;                                  // null
  Json(std::nullptr_t) {}
  Json(bool b) : v_(b) {}
  Json(int n) : v_(static_cast<double>(n)) {}
  Json(long n) : v_(static_cast<double>(n)) {}
  Json(double n) : v_(n) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}
  Json(Array a) : v_(std::make_shared<Array>(std::move(a))) {}
  Json(Object o) : v_(std::make_shared<Object>(std::move(o))) {}

  bool isNull() const { return v_.index() == 0; }
  bool isNumber() const { return std::holds_alternative<double>(v_); }
  bool isString() const { return std::holds_alternative<std::string>(v_); }
  bool isObject() const { return std::holds_alternative<std::shared_ptr<Object>>(v_); }
  bool isArray() const { return std::holds_alternative<std::shared_ptr<Array>>(v_); }

  // Lookups that never throw: a missing member or a wrong type reads as null, 0 or "".
  const Json& operator[](const std::string& key) const;
  const Json& at(size_t i) const;
  size_t size() const;
  double number() const { return isNumber() ? std::get<double>(v_) : 0; }
  const std::string& string() const;
  bool boolean() const { return std::holds_alternative<bool>(v_) && std::get<bool>(v_); }

  std::string dump() const;
  // nullopt on malformed text.
  static std::optional<Json> parse(const std::string& text);

private:
  std::variant<std::monostate, bool, double, std::string, std::shared_ptr<Array>, std::shared_ptr<Object>> v_;
};

} // namespace gbx::lsp
