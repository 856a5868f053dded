#include "catalogue/Attr.h"

namespace gbx::cat::rows {

using units::Number;
using units::Rational;

AttrSpec in(std::string n, Dim d, std::string meaning) {
  AttrSpec a;
  a.key = keyOf(n).value_or(Q::None);
  a.name = std::move(n);
  a.dim = d;
  a.meaning = std::move(meaning);
  return a;
}
AttrSpec pos(std::string n, Dim d, std::string meaning) {
  auto a = in(std::move(n), d, std::move(meaning));
  a.positive = true;
  return a;
}
AttrSpec whole(std::string n, std::string meaning) {
  auto a = in(std::move(n), units::dims::none, std::move(meaning));
  a.integer = true;
  return a;
}
AttrSpec count(std::string n, std::string meaning) {
  auto a = whole(std::move(n), std::move(meaning));
  a.positive = true;
  return a;
}
AttrSpec list(std::string n, Dim d, std::string meaning) {
  auto a = in(std::move(n), d, std::move(meaning));
  a.value = ValueKind::List;
  return a;
}
AttrSpec derived(std::string n, Dim d, std::string meaning, bool integer) {
  auto a = in(std::move(n), d, std::move(meaning));
  a.role = AttrRole::Derived;
  a.integer = integer;
  return a;
}
AttrSpec withDefault(AttrSpec a, Number v) {
  a.dflt = v;
  return a;
}
AttrSpec required(AttrSpec a) {
  a.required = true;
  return a;
}
AttrSpec symbol(std::string n, std::vector<std::string> words, std::string meaning) {
  auto a = in(std::move(n), units::dims::none, std::move(meaning));
  a.value = ValueKind::Symbol;
  a.symbols = std::move(words);
  return a;
}
AttrSpec keyed(AttrSpec a, Q key) {
  a.key = key;
  return a;
}
AttrSpec bounded(AttrSpec a, std::optional<Number> lo, std::optional<Number> hi) {
  a.atLeast = lo;
  a.atMost = hi;
  return a;
}
AttrSpec budgeted(AttrSpec a, std::int64_t most) {
  a.atMost = Number::exact(Rational(most));
  a.budget = true;
  return a;
}
Number deg(std::int64_t d) { return Number::exact(Rational::make(d, 180), 1); }
AttrSpec hinted(AttrSpec a, std::string unit) {
  a.unitHint = std::move(unit);
  return a;
}

Number num(std::int64_t n, std::int64_t d) { return Number::exact(Rational::make(n, d)); }

} // namespace gbx::cat::rows
