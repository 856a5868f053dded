#include "report/Numbers.h"

#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "units/Unit.h"

namespace gbx::rt {

namespace {

using units::Number;

// `mm^2/s`, `N*m`, `kg/m^3`: atoms joined by `*` and `/`, each with an optional `^n`.
std::optional<units::Unit> parseUnit(const std::string& name) {
  units::Unit u;
  bool divide = false;
  size_t at = 0;
  while (at < name.size()) {
    size_t end = name.find_first_of("*/", at);
    std::string factor = name.substr(at, end == std::string::npos ? std::string::npos : end - at);
    int exponent = 1;
    if (auto caret = factor.find('^'); caret != std::string::npos) {
      exponent = std::atoi(factor.c_str() + caret + 1);
      factor.erase(caret);
    }
    auto atom = units::lookupAtom(factor);
    if (!atom || exponent == 0) return std::nullopt;
    u = units::multiply(u, units::powerOf(*atom, divide ? -exponent : exponent));
    if (end == std::string::npos) break;
    divide = name[end] == '/';
    at = end + 1;
  }
  // A lone atom keeps its zero (`80 degC`), as a literal in it does.
  if (auto atom = units::lookupAtom(name)) u.offset = atom->offset;
  return u;
}

bool readsBack(const std::string& digits, double si, const std::optional<units::Unit>& u, double scale, double offset) {
  if (u) {
    // `-3 mm` is the negation of the literal `3 mm`, as a spec reads it.
    bool minus = !digits.empty() && digits[0] == '-';
    auto r = units::Rational::parseDecimal(minus ? digits.substr(1) : digits);
    if (r) {
      Number v = Number::exact(*r);
      if (minus) v = v.neg();
      return v.mul(u->scale).add(u->offset).toDouble() == si;
    }
  }
  return std::strtod(digits.c_str(), nullptr) * scale + offset == si;
}

} // namespace

std::string csvNumber(double si, const std::string& unit, double scale, double offset) {
  if (!std::isfinite(si)) return {};
  double shown = (si - offset) / scale;
  std::string plain = fmt::format("{}", shown); // the shortest that reads back to `shown`
  if (unit.empty() && scale == 1.0 && offset == 0.0) return plain;
  auto u = parseUnit(unit);
  for (int p = 1; p < 17; ++p) {
    // Rounded to p digits, written without an exponent where `{}` would (100, not 1e+02).
    std::string s = fmt::format("{}", std::strtod(fmt::format("{:.{}g}", shown, p).c_str(), nullptr));
    if (s.size() >= plain.size()) break;
    if (readsBack(s, si, u, scale, offset)) return s;
  }
  if (readsBack(plain, si, u, scale, offset)) return plain;
  // `shown` itself was rounded once (SI over the scale): a decimal a few units of its last
  // digit away may read back where its own does not (74.00799015338948 mm, not …947).
  if (shown != 0) {
    int e = static_cast<int>(std::floor(std::log10(std::fabs(shown))));
    for (int p = 16; p <= 17; ++p)
      for (int k : {1, -1, 2, -2, 3, -3}) {
        double step = std::pow(10.0, e - p + 1);
        std::string s = fmt::format("{:.{}g}", shown + k * step, p);
        if (s.find_first_of("eE") == std::string::npos && readsBack(s, si, u, scale, offset)) return s;
      }
  }
  return plain;
}

} // namespace gbx::rt
