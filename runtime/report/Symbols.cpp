#include "report/Symbols.h"

#include <array>
#include <cctype>
#include <string_view>
#include <utility>

namespace gbx::rt {

namespace {

// Greek letters by the names the catalogue spells them with, longest first.
constexpr std::array<std::pair<const char*, const char*>, 12> kGreek = {{
    {"lambda", "λ"},
    {"alpha", "α"},
    {"gamma", "γ"},
    {"delta", "δ"},
    {"theta", "θ"},
    {"sigma", "σ"},
    {"beta", "β"},
    {"eps", "ε"},
    {"rho", "ρ"},
    {"nu", "ν"},
    {"mu", "μ"},
    {"zeta", "ζ"},
}};

std::string escaped(const std::string& x) {
  std::string o;
  for (char c : x)
    o += c == '<'   ? std::string("&lt;")
         : c == '>' ? std::string("&gt;")
         : c == '&' ? std::string("&amp;")
                    : std::string(1, c);
  return o;
}

// Every Greek name in `s` as its letter (`Hbeta` is Hβ, `alphabeta` αβ).
std::string greek(const std::string& s) {
  std::string o;
  for (size_t i = 0; i < s.size();) {
    bool hit = false;
    for (const auto& [name, letter] : kGreek) {
      std::string n(name);
      if (s.compare(i, n.size(), n) == 0) {
        o += letter;
        i += n.size();
        hit = true;
        break;
      }
    }
    if (!hit) o += s[i++];
  }
  return o;
}

bool isGreekName(const std::string& s) {
  for (const auto& [name, letter] : kGreek)
    if (s == name) return true;
  return false;
}

// One token: `K_Hbeta` as K<sub>Hβ</sub>; anything else (a word, `contact_stress`) escaped.
std::string token(const std::string& t) {
  size_t u = t.find('_');
  if (u == std::string::npos || u == 0) return escaped(t);
  std::string head = t.substr(0, u), sub = t.substr(u + 1), star;
  if (!sub.empty() && sub.back() == '*') {
    star = "*";
    sub.pop_back();
  }
  bool symbol = (head.size() == 1 && std::isalpha(static_cast<unsigned char>(head[0]))) || isGreekName(head);
  if (!symbol || sub.empty() || sub.size() > 10 || sub.find('_') != std::string::npos) return escaped(t);
  for (char c : sub)
    if (!std::isalnum(static_cast<unsigned char>(c))) return escaped(t);
  return greek(head) + "<sub>" + greek(sub) + "</sub>" + star;
}

} // namespace

// Spellings of units in a document, each replacing its ASCII form (`um` only where a word
// starts: `µm`, never inside `drum`).
struct UnitSpelling {
  std::string_view ascii;
  const char* shown;
  bool wordStart;
};
constexpr std::array<UnitSpelling, 5> kUnitSpellings = {{
    {"degC", "°C", false},
    {"um", "µm", true},
    {"^2", "²", false},
    {"^3", "³", false},
    {"*", "·", false},
}};

std::string unitHtml(const std::string& unit) {
  std::string o;
  for (size_t i = 0; i < unit.size();) {
    const UnitSpelling* hit = nullptr;
    for (const auto& sp : kUnitSpellings)
      if (unit.compare(i, sp.ascii.size(), sp.ascii) == 0 &&
          (!sp.wordStart || i == 0 || !std::isalpha(static_cast<unsigned char>(unit[i - 1]))))
        hit = &sp;
    if (hit) {
      o += hit->shown;
      i += hit->ascii.size();
    } else {
      o += escaped(std::string(1, unit[i++]));
    }
  }
  return o;
}

std::string symbolHtml(const std::string& label) {
  std::string name = label, unit;
  if (auto b = label.rfind(" ["); b != std::string::npos && label.back() == ']') {
    name = label.substr(0, b);
    unit = label.substr(b + 2, label.size() - b - 3);
  }
  std::string o;
  // Tokens split at blanks and commas, which stay.
  std::string t;
  auto flush = [&] {
    o += token(t);
    t.clear();
  };
  for (char c : name) {
    if (c == ' ' || c == ',') {
      flush();
      o += c;
    } else {
      t += c;
    }
  }
  flush();
  return unit.empty() ? o : o + " [" + unitHtml(unit) + "]";
}

} // namespace gbx::rt
