#include "lsp/Server.h"

#include <algorithm>
#include <functional>
#include <istream>
#include <memory>
#include <map>
#include <optional>
#include <ostream>
#include <string>

#include <fmt/format.h>

#include "catalogue/Effects.h"
#include "catalogue/Settings.h"
#include "catalogue/Shafts.h"
#include "catalogue/StageKinds.h"
#include "driver/Driver.h"
#include "format/Formatter.h"
#include "lower/Lower.h"
#include "lsp/DesignValue.h"
#include "lsp/Json.h"
#include "lsp/UnitCompletion.h"
#include "units/Unit.h"

namespace gbx::lsp {

namespace {

constexpr size_t kMaxMessage = 64u << 20;  // a larger Content-Length is refused, not read

// One framed message; nullopt at the end of the stream. `bad` is set for a frame that
// cannot be read (no or an absurd Content-Length): the stream is then out of step.
std::optional<std::string> readMessage(std::istream& in, bool& bad) {
  size_t length = 0;
  bool sawLength = false;
  std::string line;
  while (true) {
    if (!std::getline(in, line)) return std::nullopt;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      if (sawLength) break;
      continue;  // blank lines between messages
    }
    const std::string key = "Content-Length:";
    if (line.size() > key.size() && line.compare(0, key.size(), key) == 0) {
      try {
        unsigned long long n = std::stoull(line.substr(key.size()));
        if (n > kMaxMessage) {
          bad = true;
          return std::nullopt;
        }
        length = static_cast<size_t>(n);
        sawLength = true;
      } catch (...) {
        bad = true;
        return std::nullopt;
      }
    }
  }
  std::string body(length, '\0');
  in.read(body.data(), static_cast<std::streamsize>(length));
  if (static_cast<size_t>(in.gcount()) != length) return std::nullopt;
  return body;
}

void send(std::ostream& out, const Json& message) {
  std::string body = message.dump();
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body << std::flush;
}

Json response(const Json& id, Json result) { return Json::Object{{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}}; }

Json error(const Json& id, int code, std::string message) {
  return Json::Object{{"jsonrpc", "2.0"}, {"id", id},
                      {"error", Json::Object{{"code", code}, {"message", std::move(message)}}}};
}

// file:///a/b%20c.gbx -> /a/b c.gbx (what imports resolve against and diagnostics name).
std::string pathOf(const std::string& uri) {
  std::string p = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
  std::string out;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] == '%' && i + 2 < p.size() && std::isxdigit(static_cast<unsigned char>(p[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(p[i + 2]))) {
      out += static_cast<char>(std::stoi(p.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += p[i];
    }
  }
  return out.empty() ? "untitled.gbx" : out;
}

// UTF-16 code units before the code point at `col` (1-based) of `line`: LSP's default
// position encoding.
int utf16Column(const std::string& line, int col) {
  int units = 0, points = 0;
  for (size_t i = 0; i < line.size() && points < col - 1;) {
    size_t len = source::utf8Length(static_cast<unsigned char>(line[i]));
    units += len == 4 ? 2 : 1;
    ++points;
    i += len;
  }
  return units + std::max(0, col - 1 - points);  // past the end: one unit a column
}

// The byte where the code point at `col` (1-based) of `line` starts (its size past the end).
size_t byteAtColumn(const std::string& line, int col) {
  size_t b = 0;
  for (int c = 1; b < line.size() && c < col; ++c) b += source::utf8Length(static_cast<unsigned char>(line[b]));
  return std::min(b, line.size());
}

// The code point column (1-based) of a UTF-16 `character` offset in `line`.
int codePointColumn(const std::string& line, int character) {
  int units = 0, col = 1;
  for (size_t i = 0; i < line.size() && units < character;) {
    size_t len = source::utf8Length(static_cast<unsigned char>(line[i]));
    units += len == 4 ? 2 : 1;
    ++col;
    i += len;
  }
  return col + std::max(0, character - units);
}

bool contains(const source::Span& s, int line, int col) {
  if (!s.valid()) return false;
  int endLine = s.endLine > 0 ? s.endLine : s.line, endCol = s.endLine > 0 ? s.endCol : s.col;
  return (line > s.line || (line == s.line && col >= s.col)) && (line < endLine || (line == endLine && col <= endCol + 1));
}

Json position(const source::SourceManager& sm, int file, int line, int col) {
  return Json::Object{{"line", line - 1}, {"character", utf16Column(sm.get(file).line(line), col)}};
}

Json rangeOf(const source::SourceManager& sm, const source::Span& s) {
  int endLine = s.endLine > 0 ? s.endLine : s.line, endCol = s.endLine > 0 ? s.endCol : s.col;
  return Json::Object{{"start", position(sm, s.file, s.line, s.col)}, {"end", position(sm, s.file, endLine, endCol + 1)}};
}

// A request's 0-based line or UTF-16 character: negative or absurd numbers are clamped.
int coordinate(const Json& n) { return static_cast<int>(std::clamp(n.number(), 0.0, 1e9)); }

// The byte offset of a 0-based line and UTF-16 character in `text`, within that line.
size_t byteOffset(const std::string& text, int line, int character) {
  size_t i = 0;
  for (int l = 0; l < line; ++l) {
    size_t nl = text.find('\n', i);
    if (nl == std::string::npos) return text.size();
    i = nl + 1;
  }
  for (int units = 0; i < text.size() && text[i] != '\n' && units < character;) {
    size_t len = source::utf8Length(static_cast<unsigned char>(text[i]));
    units += len == 4 ? 2 : 1;
    i += len;
  }
  return std::min(i, text.size());
}

std::string uriOf(const std::string& path) { return path.rfind("file://", 0) == 0 ? path : "file://" + path; }

// What an attribute is, for a hover: meaning, dimension and the unit reports use.
std::string describeAttr(const std::string& path, const cat::AttrSpec& a) {
  std::string unit = units::displayUnitFor(a.dim).name;
  return fmt::format("**{}** — {}\n\n{}{}{}", path, a.meaning, a.dim.describe(), unit.empty() ? "" : fmt::format(", in {}", unit),
                     a.role == cat::AttrRole::Derived ? " (computed)" : "");
}

// What the line says before the cursor, for completion. A name's characters:
bool nameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool nameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }

// Back from `end` over a partly typed name, then blanks: where they start.
size_t backOverName(const std::string& s, size_t end) {
  while (end > 0 && nameChar(s[end - 1])) --end;
  return end;
}
size_t backOverBlanks(const std::string& s, size_t end) {
  while (end > 0 && (s[end - 1] == ' ' || s[end - 1] == '\t')) --end;
  return end;
}

// `import ma|`
bool afterImport(const std::string& before) {
  size_t i = backOverName(before, before.size());
  size_t j = backOverBlanks(before, i);
  return j < i && j >= 6 && before.compare(j - 6, 6, "import") == 0 && backOverBlanks(before, j - 6) == 0;
}

// `stage main: he|`
bool afterStageColon(const std::string& before) {
  size_t i = backOverBlanks(before, backOverName(before, before.size()));
  if (i == 0 || before[i - 1] != ':') return false;
  size_t nameEnd = backOverBlanks(before, i - 1), nameBegin = backOverName(before, nameEnd);
  if (nameBegin == nameEnd || !nameStart(before[nameBegin])) return false;
  size_t k = backOverBlanks(before, nameBegin);
  return k < nameBegin && k >= 5 && before.compare(k - 5, 5, "stage") == 0 && (k == 5 || !nameChar(before[k - 6]));
}

// `main.pinion.|` or `main.pinion.s|`: the dotted name before the last dot ("" when none).
std::string dottedBefore(const std::string& before) {
  size_t i = backOverName(before, before.size());
  if (i == 0 || before[i - 1] != '.') return "";
  size_t end = i - 1, begin = end;
  while (true) {
    size_t b = backOverName(before, begin);
    if (b == begin || !nameStart(before[b])) return "";  // `1.` is a number, `..` a range
    begin = b;
    if (begin == 0 || before[begin - 1] != '.') break;
    --begin;
  }
  return before.substr(begin, end - begin);
}

class Server {
public:
  explicit Server(std::ostream& out) : out_(out) {}

  // Returns true when the server should stop (after `exit`).
  bool handle(const Json& msg) {
    const std::string& method = msg["method"].string();
    const Json& id = msg["id"];
    bool request = !id.isNull();
    const Json& params = msg["params"];
    if (method == "initialize") {
      Json::Object caps{{"textDocumentSync", Json::Object{{"openClose", true}, {"change", 1}}},
                        {"hoverProvider", true},
                        {"completionProvider", Json::Object{{"triggerCharacters", Json::Array{"."}}}},
                        {"definitionProvider", true},
                        {"documentSymbolProvider", true},
                        {"documentFormattingProvider", true}};
      send(out_, response(id, Json::Object{{"capabilities", caps},
                                           {"serverInfo", Json::Object{{"name", "gbxc"}, {"version", GBX_VERSION}}}}));
    } else if (method == "shutdown") {
      shutdown_ = true;
      send(out_, response(id, Json()));
    } else if (method == "exit") {
      return true;
    } else if (method == "textDocument/didOpen") {
      const Json& doc = params["textDocument"];
      docs_[doc["uri"].string()] = doc["text"].string();
      publish(doc["uri"].string());
    } else if (method == "textDocument/didChange") {
      const Json& changes = params["contentChanges"];
      // Full synchronisation: the last change holds the whole text.
      if (changes.size() > 0) {
        const std::string& uri = params["textDocument"]["uri"].string();
        docs_[uri] = changes.at(changes.size() - 1)["text"].string();
        publish(uri);
      }
    } else if (method == "textDocument/didClose") {
      const std::string& uri = params["textDocument"]["uri"].string();
      docs_.erase(uri);
      send(out_, notification("textDocument/publishDiagnostics", Json::Object{{"uri", uri}, {"diagnostics", Json::Array{}}}));
    } else if (method == "textDocument/hover") {
      send(out_, response(id, hover(params)));
    } else if (method == "textDocument/completion") {
      send(out_, response(id, completion(params)));
    } else if (method == "textDocument/definition") {
      send(out_, response(id, definition(params)));
    } else if (method == "textDocument/documentSymbol") {
      send(out_, response(id, symbols(params)));
    } else if (method == "textDocument/formatting") {
      send(out_, formatting(id, params));
    } else if (request) {
      send(out_, error(id, -32601, fmt::format("method `{}` is not served", method)));
    }
    return false;
  }

  bool shutdownRequested() const { return shutdown_; }

private:
  static Json notification(const char* method, Json params) {
    return Json::Object{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
  }

  // The front end on the document's text, its diagnostics in this file as LSP wants them.
  void publish(const std::string& uri) {
    const std::string path = pathOf(uri);
    auto c = driver::compileText(path, docs_[uri]);
    Json::Array list;
    for (const auto& d : c->diags.all()) {
      bool here = d.span.valid() && d.span.file < c->sources.size() && c->sources.get(d.span.file).displayPath() == path;
      // In an imported file, or with no place: shown at the top of this one.
      Json range = here ? rangeOf(c->sources, d.span)
                        : Json(Json::Object{{"start", Json::Object{{"line", 0}, {"character", 0}}},
                                            {"end", Json::Object{{"line", 0}, {"character", 0}}}});
      int severity = d.severity == diag::Severity::Error ? 1 : d.severity == diag::Severity::Warning ? 2 : 3;
      std::string message = d.message;
      if (!here && d.span.valid() && d.span.file < c->sources.size())
        message += fmt::format(" (in {}:{}:{})", c->sources.get(d.span.file).displayPath(), d.span.line, d.span.col);
      list.push_back(Json::Object{{"range", range}, {"severity", severity}, {"code", d.code}, {"source", "gbxc"}, {"message", message}});
    }
    send(out_, notification("textDocument/publishDiagnostics", Json::Object{{"uri", uri}, {"diagnostics", std::move(list)}}));
  }

  // The document compiled, and the 1-based line and code point column of a request's position.
  struct At {
    std::unique_ptr<driver::Compilation> c;
    int line = 0, col = 0;
  };
  At at(const Json& params) {
    At a;
    const std::string& uri = params["textDocument"]["uri"].string();
    a.c = driver::compileText(pathOf(uri), docs_[uri]);
    a.line = static_cast<int>(params["position"]["line"].number()) + 1;
    int character = static_cast<int>(params["position"]["character"].number());
    a.col = a.c->sources.size() > 0 ? codePointColumn(a.c->sources.get(0).line(a.line), character) : character + 1;
    return a;
  }

  // The identifier under the position ("" when none).
  static std::string wordAt(const At& a) {
    if (a.c->sources.size() == 0) return "";
    std::string line = a.c->sources.get(0).line(a.line);
    size_t b = byteAtColumn(line, a.col), e = b;
    while (b > 0 && nameChar(line[b - 1])) --b;
    while (e < line.size() && nameChar(line[e])) ++e;
    return line.substr(b, e - b);
  }

  // The statements from the outermost to the innermost that hold the position.
  static void chain(const std::vector<ast::Stmt>& body, int line, int col, std::vector<const ast::Stmt*>& out) {
    for (const auto& st : body)
      if (contains(st.span, line, col)) {
        out.push_back(&st);
        chain(st.body, line, col, out);
        return;
      }
  }

  // The kind of stage `stage` of gearbox `gearbox` as written: declared there, `like`
  // another, or inherited through `extends`.
  static const cat::KindSpec* stageKindIn(const std::vector<ast::File>& files, const std::string& gearbox, const std::string& stage,
                                          int depth = 0) {
    if (depth > 16) return nullptr;  // an `extends` cycle, reported elsewhere
    for (const auto& f : files)
      for (const auto& g : f.decls) {
        if (g.kind != ast::StmtKind::Gearbox || g.name != gearbox) continue;
        for (const auto& st : g.body) {
          if (st.kind == ast::StmtKind::Stage && st.name == stage) return cat::findKind(st.word);
          if (st.kind == ast::StmtKind::Like && st.name == stage) return stageKindIn(files, gearbox, st.path.str(), depth + 1);
        }
        if (!g.base.empty()) return stageKindIn(files, g.base, stage, depth + 1);
      }
    return nullptr;
  }

  static const cat::KindSpec* stageKind(const std::vector<const ast::Stmt*>& ch) {
    for (auto it = ch.rbegin(); it != ch.rend(); ++it)
      if ((*it)->kind == ast::StmtKind::Stage) return cat::findKind((*it)->word);
    return nullptr;
  }

  // The catalogue row an assignment, range or scatter sets, found through the blocks around
  // it: a stage's attribute (nested blocks prefix it: `rating { lubricant { … } }`), an
  // effect's parameter, an operating, scene, accuracy, split or material setting, or a
  // stage's attribute named from the gearbox (`main.helix_angle in 8..15 deg;`, also in
  // `tolerances`), the stage perhaps inherited. Returns the row and the name to show.
  static std::pair<const cat::AttrSpec*, std::string> targetRow(const At& a, const std::vector<const ast::Stmt*>& ch) {
    const ast::Stmt& st = *ch.back();
    std::string name = st.path.str();
    auto in = [&](const std::vector<cat::AttrSpec>& rows) -> const cat::AttrSpec* {
      for (const auto& r : rows)
        if (r.name == name) return &r;
      return nullptr;
    };
    for (size_t k = ch.size() - 1; k-- > 0;) {
      const ast::Stmt& b = *ch[k];
      switch (b.kind) {
      case ast::StmtKind::Stage:
        if (const cat::KindSpec* kind = cat::findKind(b.word)) return {cat::findAttr(*kind, name), name};
        return {nullptr, name};
      case ast::StmtKind::Operating: return {in(cat::operatingSettings()), "operating." + name};
      case ast::StmtKind::Scene: return {in(cat::sceneSettings()), name};
      case ast::StmtKind::Split: return {in(cat::splitSettings()), name};
      case ast::StmtKind::Study: return {in(cat::workPrecisionSettings()), name};
      case ast::StmtKind::Named: return {in(cat::materialProperties()), name};
      case ast::StmtKind::Block:
        if (b.name == "accuracy") return {in(cat::accuracySettings()), "accuracy." + name};
        if (const cat::EffectSpec* fx = cat::findEffect(b.name); fx && k > 0 && ch[k - 1]->kind == ast::StmtKind::Effects) {
          for (const auto& prm : fx->params)
            if (prm.name == name) return {&prm, fx->name + "." + prm.name};
          return {nullptr, name};
        }
        if (b.name == "tolerances") continue;
        name = b.name + "." + name;  // `rating`, `lubricant`, `torsion_shaft`: part of the name
        continue;
      case ast::StmtKind::Gearbox: {
        // `stage.attribute` from the gearbox, the stage perhaps inherited.
        size_t dot = name.find('.');
        const cat::KindSpec* kind = dot == std::string::npos ? nullptr : stageKindIn(a.c->loaded.files, b.name, name.substr(0, dot));
        return {kind ? cat::findAttr(*kind, name.substr(dot + 1)) : nullptr, name};
      }
      default: return {nullptr, name};
      }
    }
    return {nullptr, name};
  }

  // The source text of a span, as written.
  static std::string written(const source::SourceManager& sm, const source::Span& s) {
    if (!s.valid()) return "";
    const auto& f = sm.get(s.file);
    std::string out;
    int endLine = s.endLine > 0 ? s.endLine : s.line;
    for (int l = s.line; l <= endLine; ++l) {
      std::string line = f.line(l);
      size_t from = l == s.line ? byteAtColumn(line, s.col) : 0;
      size_t to = l == endLine ? byteAtColumn(line, s.endCol + 1) : line.size();
      out += (l == s.line ? "" : " ") + line.substr(from, to > from ? to - from : 0);
    }
    return out;
  }

  Json hover(const Json& params) {
    At a = at(params);
    if (a.c->loaded.files.empty()) return Json();
    std::vector<const ast::Stmt*> ch;
    chain(a.c->loaded.files[0].decls, a.line, a.col, ch);
    std::string text;
    const ast::Stmt* st = ch.empty() ? nullptr : ch.back();
    bool onTarget = st && (st->kind == ast::StmtKind::Assign || st->kind == ast::StmtKind::Domain || st->kind == ast::StmtKind::Scatter) &&
                    contains(st->path.span, a.line, a.col);
    if (onTarget) {
      auto [row, name] = targetRow(a, ch);
      if (row) text = describeAttr(name, *row);
    } else if (st && st->kind == ast::StmtKind::Stage && contains(st->wordSpan, a.line, a.col)) {
      if (const cat::KindSpec* k = cat::findKind(st->word))
        text = fmt::format("**{}** stage — gears: {}", k->name, fmt::join(k->gears, ", "));
    } else if (const cat::EffectSpec* fx = st ? cat::findEffect(st->name) : nullptr; fx && contains(st->nameSpan, a.line, a.col)) {
      text = fmt::format("**{}** — {}", fx->name, fx->meaning);
    }
    // A const, where it is declared or used: its value as written, and in SI.
    if (text.empty()) {
      std::string word = wordAt(a);
      for (const auto& k : a.c->program.consts)
        if (k.name == word && !k.isSet) {
          std::string asWritten;
          for (const auto& f : a.c->loaded.files)
            for (const auto& d : f.decls)
              if (d.kind == ast::StmtKind::Const && d.name == word && d.value) asWritten = written(a.c->sources, d.value->span);
          std::string si = k.value.str() + (k.dim.dimensionless() ? "" : " " + k.dim.siUnit());
          text = fmt::format("**const {}** = {}", k.name, asWritten.empty() ? si : asWritten);
          if (asWritten != si) text += fmt::format(" ({} in SI)", si);
        }
    }
    // A material, a stage or a scene, by its name wherever it stands: its definition.
    if (text.empty()) text = namedDefinition(a, ch, wordAt(a));
    // A quantity in an expression, and in a gearbox with one candidate design its value there.
    auto value = designValueAt(a, ch);
    if (text.empty() && value) text = value->first;
    else if (text.empty() && !onTarget && !ch.empty() && a.c->analysed) text = quantityDescription(a, ch);
    if (value) text += "\n\n" + value->second;
    if (text.empty()) return Json();
    return Json::Object{{"contents", Json::Object{{"kind", "markdown"}, {"value", text}}}};
  }

  // A setting as the spec wrote it: `sigma_hlim 1500 MPa`, `treatment case_hardened`.
  static std::string settingText(const ir::Setting& st) {
    if (!st.symbol.empty()) return st.name + " " + st.symbol;
    if (!st.value) return st.name;
    return st.name + " " + units::showQuantity(*st.value, st.dim);
  }

  // The definition behind a name: a material's properties, a stage's kind, gears and
  // bindings, a scene's target, effects and settings.
  static std::string namedDefinition(const At& a, const std::vector<const ast::Stmt*>& ch, const std::string& word) {
    if (word.empty()) return "";
    const ir::Program& program = a.c->program;
    for (const auto& m : program.materials)
      if (m.name == word) {
        std::vector<std::string> props;
        for (const auto& p : m.properties) props.push_back(settingText(p));
        return fmt::format("**material {}**\n\n{}", m.name, fmt::join(props, "; "));
      }
    const ir::Gearbox* g = nullptr;
    for (const auto& gb : program.gearboxes)
      if (!ch.empty() && ch.front()->kind == ast::StmtKind::Gearbox && gb.name == ch.front()->name) g = &gb;
    if (!g) return "";
    for (const auto& st : g->stages)
      if (st.name == word) {
        std::vector<std::string> binds;
        for (const auto& at : st.attributes) {
          if (at.role == ir::Attribute::Default) continue;
          if (at.role == ir::Attribute::Decision || at.role == ir::Attribute::Freedom) binds.push_back(at.name + " decided");
          else if (!at.symbol.empty()) binds.push_back(at.name + " " + at.symbol);
          else if (at.value && at.value->isConst()) binds.push_back(at.name + " " + units::showQuantity(at.value->value, at.dim));
        }
        return fmt::format("**stage {}**: {} — gears {}\n\n{}", st.name, cat::kindSpec(st.kind).name, fmt::join(st.gears, ", "),
                           fmt::join(binds, "; "));
      }
    for (const auto& sh : g->shafts)
      if (sh.name == word) {
        std::vector<std::string> parts;
        for (const auto& p : sh.placed)
          if (p.kind == ir::Shaft::Place::Gear || p.kind == ir::Shaft::Place::Bearing || p.kind == ir::Shaft::Place::Notch)
            parts.push_back(fmt::format("{} {} at {:g} mm",
                                        p.kind == ir::Shaft::Place::Gear      ? "gear"
                                        : p.kind == ir::Shaft::Place::Bearing ? "bearing"
                                                                              : "notch",
                                        p.name, p.at.toDouble() * 1e3));
        double length = sh.segments.empty() ? 0 : sh.segments.back().x1.toDouble();
        return fmt::format("**shaft {}**: {} segments over {:g} mm\n\n{}", sh.name, sh.segments.size(), length * 1e3, fmt::join(parts, "; "));
      }
    for (const auto& sc : g->scenes)
      if (sc.name == word) {
        std::vector<std::string> fx, set;
        for (const auto& e : sc.effects) fx.push_back(e.name);
        for (const auto& x : sc.settings) set.push_back(settingText(x));
        return fmt::format("**scene {}** on {}\n\neffects: {}\n\n{}", sc.name, sc.target.empty() ? "the gearbox" : sc.target,
                           fx.empty() ? "none" : fmt::format("{}", fmt::join(fx, ", ")), fmt::join(set, "; "));
      }
    return "";
  }

  // What the stage or gearbox quantity at the position is, from the checked program.
  static std::string quantityDescription(const At& a, const std::vector<const ast::Stmt*>& ch) {
    if (ch.front()->kind != ast::StmtKind::Gearbox) return "";
    for (const auto& g : a.c->program.gearboxes) {
      if (g.name != ch.front()->name) continue;
      const ir::Expr* e = quantityAt(g, [&](const source::Span& s) { return s.file == 0 && contains(s, a.line, a.col); });
      if (!e) return "";
      if (const cat::AttrSpec* spec = specOf(g, e->ref, e->name)) return describeAttr(e->name, *spec);
    }
    return "";
  }

  // The catalogue row of a resolved stage or gearbox quantity.
  static const cat::AttrSpec* specOf(const ir::Gearbox& g, const ir::QuantityRef& ref, const std::string& path) {
    if (ref.owner == ir::QuantityRef::Stage && ref.index >= 0 && static_cast<size_t>(ref.index) < g.stages.size()) {
      size_t dot = path.find('.');
      return cat::findAttr(cat::kindSpec(g.stages[static_cast<size_t>(ref.index)].kind), path.substr(dot + 1));
    }
    if (ref.owner == ir::QuantityRef::Gearbox)
      for (const auto& q : cat::gearboxQuantities())
        if (q.key == ref.key) return &q;
    if (ref.owner == ir::QuantityRef::Shaft)
      for (const auto& q : ref.gear < 0 ? cat::shaftOutputs() : cat::bearingOutputs())
        if (q.key == ref.key) return &q;
    return nullptr;
  }

  // The value, for the design of a gearbox whose design is fixed, of the quantity at the
  // position, with what the quantity is: an assignment's target in a stage or the gearbox
  // (where it is computed, not written as a number), or a quantity in an expression. Only an
  // error-free program is evaluated.
  static std::optional<std::pair<std::string, std::string>> designValueAt(const At& a, const std::vector<const ast::Stmt*>& ch) {
    if (!a.c->analysed || a.c->diags.hasErrors() || ch.empty() || ch.front()->kind != ast::StmtKind::Gearbox) return std::nullopt;
    const ir::Program& program = a.c->program;
    const ir::Gearbox* g = nullptr;
    for (const auto& gb : program.gearboxes)
      if (gb.name == ch.front()->name) g = &gb;
    if (!g) return std::nullopt;
    const ast::Stmt& st = *ch.back();
    ir::QuantityRef ref;
    units::Dim dim;
    std::string path;
    if ((st.kind == ast::StmtKind::Assign || st.kind == ast::StmtKind::Domain) && contains(st.path.span, a.line, a.col)) {
      const ast::Stmt* owner = ch.size() >= 2 ? ch[ch.size() - 2] : nullptr;
      if (owner && owner->kind == ast::StmtKind::Stage) path = owner->name + "." + st.path.str();
      else if (owner == ch.front()) path = st.path.str();
      else return std::nullopt;
      ref = lower::quantityRef(program, *g, path);
      if (ref.owner != ir::QuantityRef::Stage || ref.key == cat::Q::None) return std::nullopt;
      const ir::Attribute* attr = nullptr;
      for (const auto& x : g->stages[static_cast<size_t>(ref.index)].attributes)
        if (x.key == ref.key && x.gear == ref.gear) attr = &x;
      // A number as written needs no value beside it.
      if (!attr || attr->role != ir::Attribute::Fixed || !attr->value || attr->value->isConst()) return std::nullopt;
      dim = attr->dim;
    } else {
      const ir::Expr* e = quantityAt(*g, [&](const source::Span& s) { return s.file == 0 && contains(s, a.line, a.col); });
      if (!e) return std::nullopt;
      ref = e->ref;
      dim = e->type.dim;
      path = e->name;
    }
    auto value = designValue(program, *g, ref, dim);
    if (!value) return std::nullopt;
    const cat::AttrSpec* spec = specOf(*g, ref, path);
    return std::pair{spec ? describeAttr(path, *spec) : fmt::format("**{}**", path), *value};
  }

  Json completion(const Json& params) {
    // After a number: units, those of the dimension of what the statement sets first.
    const std::string& text = docs_[params["textDocument"]["uri"].string()];
    int line = coordinate(params["position"]["line"]), character = coordinate(params["position"]["character"]);
    // A stage the gearbox inherits, from the document as parsed (recovering from the
    // statement being typed), asked only when the text alone does not tell.
    std::unique_ptr<driver::Compilation> parsed;
    auto inherited = [&](const std::string& gearbox, const std::string& stage) -> const cat::KindSpec* {
      if (!parsed) parsed = driver::compileText(pathOf(params["textDocument"]["uri"].string()), text);
      return stageKindIn(parsed->loaded.files, gearbox, stage);
    };
    if (auto units = unitCompletion(text, byteOffset(text, line, character), inherited)) {
      // UTF-16 units of the unit word being typed, which an item replaces.
      int typed = utf16Column(units->typed, source::codePoints(units->typed) + 1);
      Json range = Json::Object{{"start", Json::Object{{"line", line}, {"character", std::max(0, character - typed)}}},
                                {"end", Json::Object{{"line", line}, {"character", character}}}};
      Json::Array items;
      for (const auto& u : units->items)
        items.push_back(Json::Object{{"label", u.label}, {"kind", 11}, {"detail", u.detail}, {"sortText", u.sortText},
                                     {"textEdit", Json::Object{{"range", range}, {"newText", u.label}}}});
      return Json::Object{{"isIncomplete", false}, {"items", std::move(items)}};
    }
    At a = at(params);
    Json::Array items;
    auto item = [&](const std::string& label, int kind, const std::string& detail) {
      items.push_back(Json::Object{{"label", label}, {"kind", kind}, {"detail", detail}});
    };
    std::vector<const ast::Stmt*> ch;
    if (!a.c->loaded.files.empty()) chain(a.c->loaded.files[0].decls, a.line, a.col, ch);
    // What the line says before the cursor narrows the choice: a module after `import`, a
    // kind after `stage x:`, what a dotted name holds after its dot.
    size_t offset = byteOffset(text, line, character);
    size_t lineStart = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
    lineStart = lineStart == std::string::npos ? 0 : lineStart + 1;
    size_t from = std::max(lineStart, offset > 200 ? offset - 200 : size_t{0});  // a long line: its end is enough
    std::string before = text.substr(from, offset - from);
    if (afterImport(before)) {
      for (const auto& mod : sema::stdlibModules()) item(mod, 9, "stdlib module");
      return Json::Object{{"isIncomplete", false}, {"items", std::move(items)}};
    }
    if (afterStageColon(before)) {
      for (const auto* k : cat::stageKinds())
        item(k->name, 7, fmt::format("stage kind — gears: {}", fmt::join(k->gears, ", ")));
      return Json::Object{{"isIncomplete", false}, {"items", std::move(items)}};
    }
    if (std::string dotted = dottedBefore(before); !dotted.empty()) {
      // Inside a stage the path starts at its attributes; elsewhere in a gearbox at a stage.
      std::string prefix = dotted;
      const cat::KindSpec* kind = stageKind(ch);
      if (!kind && !ch.empty() && ch.front()->kind == ast::StmtKind::Gearbox) {
        size_t dot = prefix.find('.');
        kind = stageKindIn(a.c->loaded.files, ch.front()->name, prefix.substr(0, dot));
        prefix = dot == std::string::npos ? "" : prefix.substr(dot + 1);
      }
      if (kind) {
        auto offer = [&](const std::string& name, const cat::AttrSpec& attr) {
          if (!prefix.empty() && name.rfind(prefix + ".", 0) != 0) return;
          item(prefix.empty() ? name : name.substr(prefix.size() + 1), 10,
               attr.meaning + (attr.role == cat::AttrRole::Derived ? " (computed)" : ""));
        };
        for (const auto& attr : kind->stage) offer(attr.name, attr);
        for (const auto& g : kind->gears)
          for (const auto& attr : kind->gear) offer(g + "." + attr.name, attr);
        return Json::Object{{"isIncomplete", false}, {"items", std::move(items)}};
      }
    }
    bool inEffects = false;
    for (const auto* st : ch) inEffects = inEffects || st->kind == ast::StmtKind::Effects;
    if (inEffects) {
      const cat::EffectSpec* fx = ch.back()->kind == ast::StmtKind::Effects ? nullptr : cat::findEffect(ch.back()->name);
      if (fx)
        for (const auto& prm : fx->params) item(prm.name, 10, prm.meaning);
      else
        for (const auto& e : cat::effects()) item(e.name, 3, e.meaning);
    } else if (const cat::KindSpec* k = stageKind(ch)) {
      for (const auto& attr : k->stage)
        if (attr.role != cat::AttrRole::Derived) item(attr.name, 10, attr.meaning);
      for (const auto& g : k->gears)
        for (const auto& attr : k->gear)
          if (attr.role != cat::AttrRole::Derived) item(g + "." + attr.name, 10, attr.meaning);
    } else {
      for (const char* kw : {"gearbox", "stage", "const", "let", "require", "minimize", "maximize", "operating", "scene",
                             "modify", "split", "study", "report", "import", "preset", "interchangeable", "tolerances"})
        item(kw, 14, "");
      for (const auto& m : sema::stdlibModules()) item(m, 9, "stdlib module");
      for (const auto* k : cat::stageKinds())
        item(k->name, 7, "stage kind");
    }
    return Json::Object{{"isIncomplete", false}, {"items", std::move(items)}};
  }

  Json definition(const Json& params) {
    At a = at(params);
    // An import's target: the file the loader loaded for it.
    for (const auto& imp : a.c->loaded.imports) {
      if (imp.word.file != 0 || !contains(imp.word, a.line, a.col)) continue;
      const auto& src = a.c->sources.get(imp.target);
      Json::Object start{{"line", 0}, {"character", 0}};
      return Json::Object{{"uri", uriOf(src.absPath().empty() ? src.displayPath() : src.absPath())},
                          {"range", Json::Object{{"start", start}, {"end", start}}}};
    }
    std::string word = wordAt(a);
    if (word.empty()) return Json();
    // Declarations with that name, in the main file first, then imports.
    std::function<const ast::Stmt*(const std::vector<ast::Stmt>&)> find = [&](const std::vector<ast::Stmt>& body) -> const ast::Stmt* {
      for (const auto& st : body) {
        bool declares = st.kind == ast::StmtKind::Gearbox || st.kind == ast::StmtKind::Stage || st.kind == ast::StmtKind::Const ||
                        st.kind == ast::StmtKind::Let || st.kind == ast::StmtKind::Scene || st.kind == ast::StmtKind::Study ||
                        st.kind == ast::StmtKind::Split || st.kind == ast::StmtKind::Preset || st.kind == ast::StmtKind::Named ||
                        st.kind == ast::StmtKind::Like;
        if (declares && st.name == word && st.nameSpan.valid() && !contains(st.nameSpan, a.line, a.col)) return &st;
        if (const auto* inner = find(st.body)) return inner;
      }
      return nullptr;
    };
    for (const auto& f : a.c->loaded.files)
      if (const ast::Stmt* st = find(f.decls)) {
        const auto& src = a.c->sources.get(st->nameSpan.file);
        std::string path = src.absPath().empty() ? src.displayPath() : src.absPath();
        return Json::Object{{"uri", st->nameSpan.file == 0 ? params["textDocument"]["uri"].string() : uriOf(path)},
                            {"range", rangeOf(a.c->sources, st->nameSpan)}};
      }
    return Json();
  }

  Json symbols(const Json& params) {
    const std::string& uri = params["textDocument"]["uri"].string();
    auto c = driver::compileText(pathOf(uri), docs_[uri]);
    std::function<Json::Array(const std::vector<ast::Stmt>&)> walk = [&](const std::vector<ast::Stmt>& body) {
      Json::Array out;
      for (const auto& st : body) {
        int kind = st.kind == ast::StmtKind::Gearbox   ? 5    // class
                   : st.kind == ast::StmtKind::Stage   ? 23   // struct
                   : st.kind == ast::StmtKind::Like    ? 23
                   : st.kind == ast::StmtKind::Scene   ? 24   // event
                   : st.kind == ast::StmtKind::Study   ? 12   // function
                   : st.kind == ast::StmtKind::Split   ? 12
                   : st.kind == ast::StmtKind::Const   ? 14   // constant
                   : st.kind == ast::StmtKind::Named   ? 19   // object (a material)
                   : st.kind == ast::StmtKind::Preset  ? 19
                                                       : 0;
        if (kind == 0 || st.name.empty() || !st.span.valid() || !st.nameSpan.valid()) continue;
        Json::Object sym{{"name", st.name}, {"kind", kind}, {"range", rangeOf(c->sources, st.span)},
                         {"selectionRange", rangeOf(c->sources, st.nameSpan)}};
        if (!st.word.empty()) sym["detail"] = st.word;
        Json::Array children = walk(st.body);
        if (!children.empty()) sym["children"] = std::move(children);
        out.push_back(std::move(sym));
      }
      return out;
    };
    if (c->loaded.files.empty()) return Json::Array{};
    return walk(c->loaded.files[0].decls);
  }

  // `gbxc fmt` on the document: one edit replacing the lines that change (the lines both
  // share at the start and the end are left alone, so the editor keeps its place); none when
  // it is laid out. A document that does not parse is left as it is: its diagnostics say why,
  // and the log says that formatting waits for them.
  Json formatting(const Json& id, const Json& params) {
    const std::string& uri = params["textDocument"]["uri"].string();
    const std::string& text = docs_[uri];
    source::SourceManager sm;
    diag::DiagnosticEngine diags;
    std::optional<std::string> laidOut;
    try {
      laidOut = format::formatText(pathOf(uri), text, sm, diags);
    } catch (const std::logic_error& e) {
      return error(id, -32603, e.what());
    }
    if (!laidOut) {
      send(out_, notification("window/logMessage",
                              Json::Object{{"type", 3}, {"message", fmt::format("{}: not formatted: it has syntax errors ({} in all)",
                                                                                pathOf(uri), diags.errorCount())}}));
      return response(id, Json());
    }
    // Lines as LSP counts them (LF, CRLF or a lone CR ends one), without their ends: a CRLF
    // document laid out already needs no edit, and the editor writes its own line ends.
    auto lines = [](const std::string& t) {
      std::vector<std::string> v;
      size_t from = 0;
      for (size_t i = 0; i < t.size(); ++i)
        if (t[i] == '\n' || t[i] == '\r') {
          v.push_back(t.substr(from, i - from));
          if (t[i] == '\r' && i + 1 < t.size() && t[i + 1] == '\n') ++i;
          from = i + 1;
        }
      v.push_back(t.substr(from));  // after the last line end (maybe empty)
      return v;
    };
    std::vector<std::string> a = lines(text), b = lines(*laidOut);
    if (a == b) return response(id, Json::Array{});
    size_t pre = 0, suf = 0;
    // A lone CR ends a line for the editor but not for the language: one edit over the
    // whole document then, as line numbers of the two need not agree.
    bool loneCr = false;
    for (size_t i = 0; i < text.size(); ++i) loneCr = loneCr || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
    if (!loneCr) {
      while (pre + 1 < a.size() && pre + 1 < b.size() && a[pre] == b[pre]) ++pre;
      while (suf + pre + 1 < a.size() && suf + pre + 1 < b.size() && a[a.size() - 1 - suf] == b[b.size() - 1 - suf]) ++suf;
    }
    std::string newText;
    for (size_t i = pre; i < b.size() - suf; ++i) newText += (i > pre ? "\n" : "") + b[i];
    if (suf > 0) newText += "\n";
    // From the start of the first changed line to the start of the first shared line after
    // them (or the end of the document). Built a member at a time: GCC 12 warns, falsely, of
    // nested initializer lists of variants.
    Json::Object start, end, range, edit;
    start["line"] = static_cast<double>(pre);
    start["character"] = 0;
    end["line"] = static_cast<double>(suf > 0 ? a.size() - suf : a.size() - 1);
    end["character"] = suf > 0 ? 0 : utf16Column(a.back(), source::codePoints(a.back()) + 1);
    range["start"] = Json(std::move(start));
    range["end"] = Json(std::move(end));
    edit["range"] = Json(std::move(range));
    edit["newText"] = newText;
    Json::Array edits;
    edits.push_back(Json(std::move(edit)));
    return response(id, Json(std::move(edits)));
  }

  std::ostream& out_;
  std::map<std::string, std::string> docs_;
  bool shutdown_ = false;
};

} // namespace

int serve(std::istream& in, std::ostream& out) {
  Server server(out);
  while (true) {
    bool bad = false;
    auto body = readMessage(in, bad);
    if (!body) return bad ? 1 : (server.shutdownRequested() ? 0 : 1);
    auto msg = Json::parse(*body);
    if (!msg || !msg->isObject()) {
      send(out, error(Json(), -32700, "the message is not a JSON object"));
      continue;
    }
    if (server.handle(*msg)) return server.shutdownRequested() ? 0 : 1;
  }
}

} // namespace gbx::lsp
