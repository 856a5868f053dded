#include "lsp/UnitCompletion.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "catalogue/Effects.h"
#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "parse/Layout.h"
#include "source/Source.h"
#include "units/Unit.h"

namespace gbx::lsp {

namespace {

constexpr size_t kMaxPath = 6;

// A token as the grammar's lexer makes it (grammar/Gbx.g4), with its byte range.
struct Tok {
  enum Kind { Number, Word, Symbol, Punct }; // Symbol: `%` or `°`, a unit atom that is no word
  Kind kind;
  size_t b, e;
  int line;
};

// The tokens of the whole text, as the grammar's lexer makes them; `hidden` is set when
// `offset` lies inside a comment or a string, where no unit is written.
std::vector<Tok> lex(const std::string& t, size_t offset, bool& hidden) {
  std::vector<Tok> out;
  for (const auto& k : parse::lex(t)) {
    using K = parse::LexToken::Kind;
    if (k.kind == K::Comment || k.kind == K::String || k.kind == K::Unterminated) {
      // Inside, or at the end of one that runs to the line's end (`// …|`, an open string).
      bool open = k.kind == K::Unterminated || t.compare(k.begin, 2, "//") == 0;
      if (k.begin < offset && (open ? offset <= k.end : offset < k.end)) hidden = true;
      continue;
    }
    Tok::Kind kind = k.kind == K::Word ? Tok::Word : k.kind == K::Number ? Tok::Number : Tok::Punct;
    // `%` and `°`: unit atoms that are no word.
    if (kind == Tok::Punct &&
        (t.compare(k.begin, k.end - k.begin, "%") == 0 || t.compare(k.begin, k.end - k.begin, "\u00B0") == 0))
      kind = Tok::Symbol;
    out.push_back({kind, k.begin, k.end, k.line});
  }
  return out;
}

struct Reader {
  const std::string& text;
  const std::vector<Tok>& toks;
  std::string str(long i) const {
    const Tok& k = toks[static_cast<size_t>(i)];
    return text.substr(k.b, k.e - k.b);
  }
  bool is(long i, const char* s) const {
    if (i < 0 || static_cast<size_t>(i) >= toks.size()) return false;
    const Tok& k = toks[static_cast<size_t>(i)];
    return text.compare(k.b, k.e - k.b, s) == 0;
  }
  bool glued(long left, long right) const {
    return toks[static_cast<size_t>(left)].e == toks[static_cast<size_t>(right)].b;
  }

  // The first token of the unit atom that ends at token i (`mm`, `°`, `m^2`, `s^-1`), or -1.
  long atomStart(long i) const {
    if (i < 0) return -1;
    const Tok& k = toks[static_cast<size_t>(i)];
    if (k.kind == Tok::Word || k.kind == Tok::Symbol) return i;
    if (k.kind != Tok::Number) return -1;
    long j = i - 1;
    if (is(j, "-") && glued(j, i)) --j;
    if (!is(j, "^") || !glued(j, j + 1) || j < 1) return -1;
    const Tok& a = toks[static_cast<size_t>(j - 1)];
    return (a.kind == Tok::Word || a.kind == Tok::Symbol) && glued(j - 1, j) ? j - 1 : -1;
  }
};

// What the statement at the cursor sets, as the catalogue describes it.
struct Target {
  const cat::AttrSpec* row = nullptr;
  bool found = false; // the block that owns the row was found (without the row: any unit)
};

const cat::AttrSpec* findRow(const std::vector<cat::AttrSpec>& rows, const std::string& name) {
  for (const auto& r : rows)
    if (r.name == name) return &r;
  return nullptr;
}

std::string joined(const std::vector<std::string>& parts, size_t from = 0) {
  std::string s;
  for (size_t i = from; i < parts.size(); ++i)
    s += (s.empty() ? "" : ".") + parts[i];
  return s;
}

// A second spelling (`μm` beside `µm`, `°` beside `deg`) is left out: an earlier atom means
// the same and is typed as easily.
bool alternativeSpelling(size_t i) {
  const auto& names = units::atomNames();
  if (std::all_of(names[i].begin(), names[i].end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; }))
    return false;
  auto u = units::lookupAtom(names[i]);
  for (size_t j = 0; j < i; ++j) {
    auto v = units::lookupAtom(names[j]);
    if (v && u && v->dim == u->dim && v->scale.toDouble() == u->scale.toDouble()) return true;
  }
  return false;
}

// The units of one dimension (and its alternative), the display unit first.
std::vector<UnitItem> unitsOf(const cat::AttrSpec& row) {
  std::vector<UnitItem> items;
  std::set<std::string> seen;
  auto add = [&](const std::string& label, const units::Dim& d, int rank, size_t order) {
    if (label.empty() || !seen.insert(label).second) return;
    items.push_back({label, d.describe(), fmt::format("{}{:03}", rank, order)});
  };
  add(units::displayUnitFor(row.dim).name, row.dim, 0, 0);
  if (!row.unitHint.empty()) add(row.unitHint, row.dim, 1, 0);
  const auto& names = units::atomNames();
  for (size_t i = 0; i < names.size(); ++i) {
    auto u = units::lookupAtom(names[i]);
    if (!u || (u->dim != row.dim && (!row.altDim || u->dim != *row.altDim)) || (u->meshPeriods && !row.meshPeriods) ||
        alternativeSpelling(i))
      continue;
    add(names[i], u->dim, 2, i);
  }
  return items;
}

std::vector<UnitItem> allUnits() {
  std::vector<UnitItem> items;
  const auto& names = units::atomNames();
  for (size_t i = 0; i < names.size(); ++i)
    if (auto u = units::lookupAtom(names[i]); u && !alternativeSpelling(i))
      items.push_back({names[i], u->dim.describe(), fmt::format("2{:03}", i)});
  return items;
}

} // namespace

std::optional<UnitCompletion> unitCompletion(const std::string& text, size_t offset, const StageKindOf& stageKindOf) {
  offset = std::min(offset, text.size());
  bool hidden = false;
  std::vector<Tok> toks = lex(text, offset, hidden);
  if (hidden) return std::nullopt;
  Reader rd{text, toks};
  long n = std::partition_point(toks.begin(), toks.end(), [&](const Tok& k) { return k.b < offset; }) - toks.begin();
  if (n == 0) return std::nullopt;
  UnitCompletion out;
  long i = n - 1;
  size_t glue = offset; // where the piece after token i starts
  const Tok& last = toks[static_cast<size_t>(i)];
  if (last.e >= offset && last.kind == Tok::Word) {
    out.typed = text.substr(last.b, offset - last.b); // a unit word being typed
    glue = last.b;
    --i;
  } else if (last.e > offset || (last.e == offset && last.kind == Tok::Symbol)) {
    return std::nullopt; // inside a number, or right after a written `%`
  }
  // Back over the unit written so far (`N*`, `kg/m^3*`) to the number it follows.
  bool compound = false;
  while (true) {
    if (i < 0) return std::nullopt;
    const Tok& k = toks[static_cast<size_t>(i)];
    if (k.kind == Tok::Number) break;
    if (!(rd.is(i, "*") || rd.is(i, "/")) || k.e != glue) return std::nullopt;
    long a = rd.atomStart(i - 1);
    if (a < 0 || !rd.glued(i - 1, i)) return std::nullopt;
    compound = true;
    glue = toks[static_cast<size_t>(a)].b;
    i = a - 1;
  }
  long base = i;
  // Not an exponent (`mm^2 |`), and on the cursor's line: a unit stands on its number's line.
  if ((rd.is(base - 1, "^") && rd.glued(base - 1, base)) ||
      (rd.is(base - 1, "-") && rd.is(base - 2, "^") && rd.glued(base - 2, base - 1)))
    return std::nullopt;
  int cursorLine = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
  if (toks[static_cast<size_t>(base)].line != cursorLine) return std::nullopt;
  if (compound) {
    out.items = allUnits();
    return out;
  }

  // The blocks around the statement and where the statement starts. A `{` after `in`, `=`,
  // `(` or `,` opens a set, not a block.
  struct Open {
    long tok, headerFrom;
    bool set;
  };
  std::vector<Open> stack;
  long boundary = -1;
  for (long j = 0; j < base; ++j) {
    if (rd.is(j, "{")) {
      const Tok* prev = j > 0 ? &toks[static_cast<size_t>(j - 1)] : nullptr;
      bool set =
          prev && ((prev->kind == Tok::Word && rd.is(j - 1, "in")) || (prev->kind == Tok::Punct && !rd.is(j - 1, ")")));
      stack.push_back({j, boundary, set});
      if (!set) boundary = j;
    } else if (rd.is(j, "}")) {
      bool set = !stack.empty() && stack.back().set;
      if (!stack.empty()) stack.pop_back();
      if (!set) boundary = j;
    } else if (rd.is(j, ";")) {
      boundary = j;
    }
  }
  std::vector<Open> blocks;
  for (const auto& o : stack)
    if (!o.set) blocks.push_back(o);
  // A statement being typed has no `;` yet: what follows it on a later line starts anew.
  auto lineStart = [&](long j) {
    return j > 0 && toks[static_cast<size_t>(j)].line > toks[static_cast<size_t>(j - 1)].line;
  };
  auto header = [&](const Open& o) {
    long from = o.headerFrom + 1;
    for (long j = from + 1; j < o.tok; ++j)
      if (lineStart(j)) from = j;
    std::vector<std::string> h;
    for (long j = from; j < o.tok; ++j)
      h.push_back(rd.str(j));
    return h;
  };

  // The statement's target: `path =`, `path in`, `path +-`, from the latest start that has one.
  std::vector<std::string> path;
  for (long from = base; from > boundary && path.empty(); --from) {
    if (from != boundary + 1 && !lineStart(from)) continue;
    long k = from;
    if (toks[static_cast<size_t>(k)].kind != Tok::Word) continue;
    path.push_back(rd.str(k++));
    // Paths are short (`rating.lubricant.viscosity_40`): a longer chain is no target.
    while (k + 1 < base && path.size() <= kMaxPath && rd.is(k, ".") &&
           toks[static_cast<size_t>(k + 1)].kind == Tok::Word) {
      path.push_back(rd.str(k + 1));
      k += 2;
    }
    if (k >= base || !(rd.is(k, "=") || rd.is(k, "in") || rd.is(k, "+-") || rd.is(k, "\u00B1"))) path.clear();
  }

  // The row it sets: from the innermost block that owns rows, through nested blocks
  // (`rating { lubricant { … } }`, `torsion_shaft { … }`) whose words prefix the name.
  Target target;
  std::vector<std::string> name = path;
  for (long r = static_cast<long>(blocks.size()) - 1; r >= 0 && !path.empty() && !target.found; --r) {
    std::vector<std::string> h = header(blocks[static_cast<size_t>(r)]);
    if (h.empty()) break;
    const std::string& w = h[0];
    auto inRows = [&](const std::vector<cat::AttrSpec>& list) { target = {findRow(list, joined(name)), true}; };
    if (w == "stage") {
      const cat::KindSpec* kind = h.size() >= 4 && h[2] == ":" ? cat::findKind(h[3]) : nullptr;
      target = {kind ? cat::findAttr(*kind, joined(name)) : nullptr, kind != nullptr};
    } else if (const cat::EffectSpec* fx = cat::findEffect(w);
               fx && h.size() == 1 && r > 0 &&
               header(blocks[static_cast<size_t>(r - 1)]) == std::vector<std::string>{"effects"}) {
      inRows(fx->params);
    } else if (w == "operating") {
      inRows(cat::operatingSettings());
    } else if (w == "scene") {
      inRows(cat::sceneSettings());
    } else if (w == "accuracy") {
      inRows(cat::accuracySettings());
    } else if (w == "split") {
      inRows(cat::splitSettings());
    } else if (w == "material") {
      inRows(cat::materialProperties());
    } else if ((w == "gearbox" || w == "tolerances") && name.size() >= 2 && name == path &&
               !header(blocks[0]).empty() && header(blocks[0])[0] == "gearbox") {
      // `main.helix_angle in 8..15 deg;`: the stage of that name in this gearbox.
      int depth = 0;
      for (size_t j = static_cast<size_t>(blocks[0].tok); j < toks.size(); ++j) {
        depth += rd.is(static_cast<long>(j), "{") - rd.is(static_cast<long>(j), "}");
        if (depth == 0) break;
        long s = static_cast<long>(j);
        if (rd.is(s, "stage") && rd.is(s + 1, path[0].c_str()) && rd.is(s + 2, ":") &&
            s + 3 < static_cast<long>(toks.size()))
          if (const cat::KindSpec* kind = cat::findKind(rd.str(s + 3))) {
            target = {cat::findAttr(*kind, joined(path, 1)), true};
            break;
          }
      }
      // Not declared here: a stage the gearbox inherits (`extends`), as the caller knows it.
      std::vector<std::string> g = header(blocks[0]);
      if (!target.found && stageKindOf && g.size() >= 2)
        if (const cat::KindSpec* kind = stageKindOf(g[1], path[0]))
          target = {cat::findAttr(*kind, joined(path, 1)), true};
      break;
    } else if (h.size() == 1 && toks[static_cast<size_t>(blocks[static_cast<size_t>(r)].tok - 1)].kind == Tok::Word) {
      name.insert(name.begin(), w);
    } else {
      break;
    }
  }

  if (!target.row) {
    out.items = allUnits();
  } else if (target.row->value == cat::ValueKind::Number && !target.row->integer) {
    out.items = unitsOf(*target.row);
  }
  // A count or a word takes no unit: nothing to offer.
  return out;
}

} // namespace gbx::lsp
