#include "parse/Parser.h"

#include "diag/Suggest.h"

#include <algorithm>
#include <cctype>
#include <set>

#include <antlr4-runtime.h>
#include <fmt/format.h>

#include "parse/Tree.h"

namespace gbx::parse {

using grammar::GbxLexer;
using grammar::GbxParser;
using source::Span;

namespace {

constexpr int kMaxNesting = 100;

} // namespace

Span tokenSpan(int file, antlr4::Token* t) {
  Span s;
  if (!t) return s;
  s.file = file;
  s.line = static_cast<int>(t->getLine());
  s.col = static_cast<int>(t->getCharPositionInLine()) + 1;
  s.endLine = s.line;
  int len = t->getType() == antlr4::Token::EOF ? 1 : std::max(1, source::codePoints(t->getText()));
  s.endCol = s.col + len - 1;
  return s;
}

namespace {

std::string describeToken(const antlr4::dfa::Vocabulary& voc, size_t type) {
  if (type == antlr4::Token::EOF) return "end of file";
  std::string lit = voc.getLiteralName(type);
  if (!lit.empty()) {
    if (lit.size() >= 2 && lit.front() == '\'') lit = lit.substr(1, lit.size() - 2);
    return "`" + lit + "`";
  }
  std::string sym = voc.getSymbolicName(type);
  if (sym == "ID") return "a name";
  if (sym == "NUMBER") return "a number";
  if (sym == "STRING") return "a string";
  if (sym == "PLUSMINUS") return "`+-`";
  if (sym == "DEGSIGN") return "`°`";
  return sym;
}

class ErrorCollector : public antlr4::BaseErrorListener {
public:
  ErrorCollector(int file, diag::DiagnosticEngine& diags, int cutoffLine) : file_(file), diags_(diags), cutoff_(cutoffLine) {}

  void syntaxError(antlr4::Recognizer* recognizer, antlr4::Token* offending, size_t line, size_t col,
                   const std::string& msg, std::exception_ptr) override {
    if (cutoff_ > 0 && static_cast<int>(line) >= cutoff_) return;
    auto* parser = dynamic_cast<antlr4::Parser*>(recognizer);
    Span span = tokenSpan(file_, offending);
    if (!offending) {
      span.file = file_;
      span.line = span.endLine = static_cast<int>(line);
      span.col = span.endCol = static_cast<int>(col) + 1;
    }
    std::string got = "end of file";
    if (offending && offending->getType() != antlr4::Token::EOF) got = "`" + offending->getText() + "`";
    std::string expected;
    bool wantsSemicolon = false, wantsStatement = false;
    std::vector<std::string> keywords;  // the words that could stand here
    if (parser) {
      auto set = parser->getExpectedTokens();
      const auto& voc = parser->getVocabulary();
      std::vector<std::string> names;
      bool wantsValue = false;
      for (auto t : set.toList()) {
        std::string sym = voc.getSymbolicName(t);
        if (sym == "NUMBER") wantsValue = true;
        if (sym == "STAGE" || sym == "REQUIRE") wantsStatement = true;
        if (voc.getLiteralName(t) == "';'") wantsSemicolon = true;
        std::string lit = voc.getLiteralName(t);
        if (lit.size() > 2 && std::isalpha(static_cast<unsigned char>(lit[1]))) keywords.push_back(lit.substr(1, lit.size() - 2));
        names.push_back(describeToken(voc, t));
      }
      std::sort(names.begin(), names.end());
      names.erase(std::unique(names.begin(), names.end()), names.end());
      if (!names.empty() && names.size() <= 6) {
        expected = "; expected ";
        for (size_t i = 0; i < names.size(); ++i)
          expected += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + names[i];
      } else if (wantsValue) {
        expected = "; expected an expression";
      } else if (wantsStatement) {
        expected = "; expected a statement";
      }
    }
    // A statement cut short at a line end: point at the end of that line, where `;` belongs.
    if (parser && wantsSemicolon && offending) {
      auto* prev = parser->getTokenStream()->LT(-1);
      if (prev && prev->getLine() < offending->getLine()) {
        Span at = tokenSpan(file_, prev);
        at.col = at.endCol + 1;
        at.endCol = at.col;
        diags_.error("E0102", at, fmt::format("syntax error: missing `;` after `{}`", prev->getText()));
        return;
      }
    }
    if (parser && offending && hint(*parser, *offending, span, keywords)) return;
    std::string text;
    if (msg.rfind("missing ", 0) == 0) {
      // "missing ';' at '}'": ANTLR inserted the token to recover.
      std::string what = msg.substr(8, msg.find(" at ") - 8);
      if (what.size() >= 2 && what.front() == '\'') what = "`" + what.substr(1, what.size() - 2) + "`";
      text = fmt::format("missing {} before {}", what, got);
    } else {
      text = fmt::format("unexpected {}{}", got, expected);
    }
    diags_.error("E0102", span, "syntax error: " + text);
  }

private:
  // Mistakes a newcomer makes, said in their words: `=` in a rule, a misspelt keyword.
  bool hint(antlr4::Parser& parser, antlr4::Token& offending, const Span& span, const std::vector<std::string>& keywords) {
    // The statement's tokens before the offending one, back to its start (the stream may
    // stand elsewhere after a failed prediction).
    std::vector<antlr4::Token*> stmt;
    auto* stream = parser.getTokenStream();
    for (size_t i = offending.getTokenIndex(); i-- > 0 && stmt.size() < 256;) {
      auto* t = stream->get(i);
      if (t->getChannel() != antlr4::Token::DEFAULT_CHANNEL) continue;
      std::string x = t->getText();
      if (x == ";" || x == "{" || x == "}") break;
      stmt.insert(stmt.begin(), t);
    }
    const auto& voc = parser.getVocabulary();
    if (offending.getText() == "=" && !stmt.empty() && voc.getSymbolicName(stmt.front()->getType()) == "REQUIRE") {
      diags_.error("E0102", span,
                   "syntax error: a rule compares values: write `==` for equal, or `>=`/`<=` for a bound (a minimum "
                   "safety: `>=`), not `=` (which sets a value)");
      return true;
    }
    // `shaft output {`: a keyword where a member's name belongs.
    std::string lit = voc.getLiteralName(offending.getType());
    if (stmt.size() == 1 && voc.getSymbolicName(stmt[0]->getType()) == "ID" && lit.size() > 2 &&
        std::isalpha(static_cast<unsigned char>(lit[1]))) {
      antlr4::Token* next = nullptr;
      for (size_t i = offending.getTokenIndex() + 1; i < stream->size() && !next; ++i)
        if (stream->get(i)->getChannel() == antlr4::Token::DEFAULT_CHANNEL) next = stream->get(i);
      if (next && next->getText() == "{") {
        diags_.error("E0102", span,
                     fmt::format("syntax error: `{}` is a word of the language and cannot name a {}; call it otherwise "
                                 "(`{}_{}`)",
                                 offending.getText(), stmt[0]->getText(), offending.getText(), stmt[0]->getText()));
        // The block read as statements makes no sense after it: say this one thing.
        cutoff_ = static_cast<int>(offending.getLine()) + 1;
        return true;
      }
    }
    // A word where a statement starts, then something no statement has after a name: a
    // keyword misspelt (`minimise`).
    // (A word that opens a statement of its own, `bin`, makes the parser stop at the first
    // word already: then the word after it is looked at.)
    if (stmt.empty() && voc.getSymbolicName(offending.getType()) == "ID") {
      for (size_t i = offending.getTokenIndex() + 1; i < stream->size(); ++i) {
        auto* t = stream->get(i);
        if (t->getChannel() != antlr4::Token::DEFAULT_CHANNEL) continue;
        if (voc.getSymbolicName(t->getType()) == "ID") stmt.push_back(&offending);
        break;
      }
      if (!stmt.empty()) return unknownStatement(voc, *stmt[0], keywords);
    }
    if (stmt.size() == 1 && voc.getSymbolicName(stmt[0]->getType()) == "ID" && voc.getSymbolicName(offending.getType()) == "ID")
      return unknownStatement(voc, *stmt[0], keywords);
    // `word a.b …` that is no placement (no `at`): taken as one up to its end, still a
    // misspelt statement word.
    if (stmt.size() >= 2 && voc.getSymbolicName(stmt[0]->getType()) == "ID" && voc.getSymbolicName(stmt[1]->getType()) == "ID" &&
        std::none_of(stmt.begin(), stmt.end(), [&](antlr4::Token* t) { return voc.getSymbolicName(t->getType()) == "AT"; }))
      return unknownStatement(voc, *stmt[0], keywords);
    return false;
  }

  bool unknownStatement(const antlr4::dfa::Vocabulary& voc, antlr4::Token& first, const std::vector<std::string>& keywords) {
    {
      std::vector<std::string> words = keywords;
      for (size_t t = 1; t <= voc.getMaxTokenType(); ++t) {
        std::string lit = voc.getLiteralName(t);
        if (lit.size() > 2 && std::isalpha(static_cast<unsigned char>(lit[1]))) words.push_back(lit.substr(1, lit.size() - 2));
      }
      std::string word = diag::closest(first.getText(), words);
      if (word.empty()) return false;
      diags_.error("E0102", tokenSpan(file_, &first),
                   fmt::format("syntax error: unknown statement `{}`; did you mean `{}`?", first.getText(), word));
      return true;
    }
  }

  int file_;
  diag::DiagnosticEngine& diags_;
  int cutoff_;
};

// Typed functions from parse-tree contexts to AST nodes.
class Builder {
public:
  Builder(int file, diag::DiagnosticEngine& diags, bool recovered = false)
      : file_(file), diags_(diags), recovered_(recovered) {}

  Span span(antlr4::ParserRuleContext* ctx) const {
    if (!ctx || !ctx->getStart()) return {};
    Span s = tokenSpan(file_, ctx->getStart());
    auto* stop = ctx->getStop();
    if (stop && stop->getTokenIndex() >= ctx->getStart()->getTokenIndex()) {
      Span e = tokenSpan(file_, stop);
      s.endLine = e.endLine;
      s.endCol = e.endCol;
    }
    return s;
  }
  Span span(antlr4::tree::TerminalNode* n) const { return n ? tokenSpan(file_, n->getSymbol()) : Span{}; }

  ast::File file(GbxParser::FileContext* ctx) {
    ast::File f;
    f.fileId = file_;
    for (auto* d : ctx->topDecl())
      if (auto s = topDecl(d)) f.decls.push_back(std::move(*s));
    return f;
  }

private:
  std::optional<ast::Stmt> topDecl(GbxParser::TopDeclContext* ctx) {
    ast::Stmt s;
    s.span = span(ctx);
    if (auto* c = dynamic_cast<GbxParser::ImportDeclContext*>(ctx)) {
      s.kind = ast::StmtKind::Import;
      if (c->STRING()) {
        std::string t = c->STRING()->getText();
        s.word = t.size() >= 2 ? t.substr(1, t.size() - 2) : t;
        s.importIsPath = true;
        s.wordSpan = span(c->STRING());
      } else if (c->ID()) {
        s.word = c->ID()->getText();
        s.wordSpan = span(c->ID());
      }
    } else if (auto* c = dynamic_cast<GbxParser::ConstDeclContext*>(ctx)) {
      s.kind = ast::StmtKind::Const;
      setName(s, c->ID());
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::PresetDeclContext*>(ctx)) {
      s.kind = ast::StmtKind::Preset;
      setName(s, c->ID(0));
      if (c->ID(1)) {
        s.word = c->ID(1)->getText();
        s.wordSpan = span(c->ID(1));
      }
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::GearboxDeclContext*>(ctx)) {
      s.kind = ast::StmtKind::Gearbox;
      setName(s, c->ID(0));
      if (c->EXTENDS() && c->ID(1)) {
        s.base = c->ID(1)->getText();
        s.baseSpan = span(c->ID(1));
      }
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::NamedDeclContext*>(ctx)) {
      s.kind = ast::StmtKind::Named;
      if (c->ID(0)) {
        s.word = c->ID(0)->getText();
        s.wordSpan = span(c->ID(0));
      }
      setName(s, c->ID(1));
      body(s, c->block());
      if (s.word != "material" && !recovered_) {
        diags_.error("E0111", s.wordSpan,
                     fmt::format("unknown declaration `{}`; a file holds import, const, material, preset and "
                                 "gearbox declarations",
                                 s.word));
      }
    } else {
      return std::nullopt;
    }
    return s;
  }

  void setName(ast::Stmt& s, antlr4::tree::TerminalNode* id) {
    if (!id) return;
    s.name = id->getText();
    s.nameSpan = span(id);
  }

  void body(ast::Stmt& s, GbxParser::BlockContext* b) {
    if (!b) return;
    s.hasBody = true;
    for (auto* st : b->stmt())
      if (auto x = stmt(st)) s.body.push_back(std::move(*x));
  }

  // The statements of a shaft: `segment a .. b { … }`, `WORD [path] at x …`, and the
  // gearbox member `shaft NAME { … }` itself.
  bool shaftStmt(ast::Stmt& s, GbxParser::StmtContext* ctx) {
    using K = ast::StmtKind;
    if (auto* c = dynamic_cast<GbxParser::SegmentStmtContext*>(ctx)) {
      s.kind = K::Segment;
      setName(s, c->ID());
      auto t = c->tolExpr();
      if (t.size() > 0) s.lo = tolExpr(t[0]);
      if (t.size() > 1) s.hi = tolExpr(t[1]);
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::PlacedStmtContext*>(ctx)) {
      s.kind = K::Placed;
      setName(s, c->ID());
      if (c->path()) s.path = path(c->path());
      s.value = expr(c->expr());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::MemberStmtContext*>(ctx)) {
      s.kind = K::Member;
      auto ids = c->ID();
      s.word = ids[0]->getText();
      s.wordSpan = span(ids[0]);
      if (ids.size() > 1) setName(s, ids[1]);
      body(s, c->block());
    } else {
      return false;
    }
    return true;
  }

  std::optional<ast::Stmt> stmt(GbxParser::StmtContext* ctx) {
    using K = ast::StmtKind;
    ast::Stmt s;
    s.span = span(ctx);
    if (auto* c = dynamic_cast<GbxParser::StageStmtContext*>(ctx)) {
      s.kind = K::Stage;
      auto ids = c->ID();
      if (!ids.empty()) setName(s, ids[0]);
      if (ids.size() > 1) {
        s.word = ids[1]->getText();
        s.wordSpan = span(ids[1]);
      }
      for (size_t i = 2; i < ids.size(); ++i) {
        s.with.push_back(ids[i]->getText());
        s.withSpans.push_back(span(ids[i]));
      }
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::LikeStmtContext*>(ctx)) {
      s.kind = K::Like;
      setName(s, c->ID());
      s.path = path(c->path());
    } else if (auto* c = dynamic_cast<GbxParser::LetStmtContext*>(ctx)) {
      s.kind = K::Let;
      setName(s, c->ID());
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::RequireStmtContext*>(ctx)) {
      s.kind = K::Require;
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::InterchangeableStmtContext*>(ctx)) {
      s.kind = K::Interchangeable;
      for (auto* p : c->path()) s.paths.push_back(path(p));
    } else if (auto* c = dynamic_cast<GbxParser::ObjectiveStmtContext*>(ctx)) {
      s.kind = c->MINIMIZE() ? K::Minimize : K::Maximize;
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::OperatingStmtContext*>(ctx)) {
      s.kind = K::Operating;
      s.name = "operating";
      s.nameSpan = span(c->OPERATING());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::SceneStmtContext*>(ctx)) {
      s.kind = K::Scene;
      setName(s, c->ID());
      s.path = path(c->path());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::EffectsStmtContext*>(ctx)) {
      s.kind = K::Effects;
      s.name = "effects";
      s.nameSpan = span(c->EFFECTS());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::ModifyStmtContext*>(ctx)) {
      s.kind = K::Modify;
      s.path = path(c->path());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::SplitStmtContext*>(ctx)) {
      s.kind = K::Split;
      setName(s, c->ID());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::StudyStmtContext*>(ctx)) {
      s.kind = K::Study;
      setName(s, c->ID());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::ReportStmtContext*>(ctx)) {
      s.kind = K::Report;
      s.name = "report";
      s.nameSpan = span(c->REPORT());
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::OutputStmtContext*>(ctx)) {
      s.kind = K::Output;
      for (auto* e : c->expr()) s.exprs.push_back(expr(e));
    } else if (auto* c = dynamic_cast<GbxParser::SweepStmtContext*>(ctx)) {
      s.kind = K::Sweep;
      s.path = path(c->path());
      auto t = c->tolExpr();
      if (t.size() > 0) s.lo = tolExpr(t[0]);
      if (t.size() > 1) s.hi = tolExpr(t[1]);
      if (t.size() > 2) s.step = tolExpr(t[2]);
    } else if (auto* c = dynamic_cast<GbxParser::OfStmtContext*>(ctx)) {
      s.kind = K::Of;
      setName(s, c->ID());
      s.path = path(c->path());
    } else if (auto* c = dynamic_cast<GbxParser::TopStmtContext*>(ctx)) {
      s.kind = K::Top;
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::SortStmtContext*>(ctx)) {
      s.kind = K::Sort;
      s.value = expr(c->expr());
    } else if (auto* c = dynamic_cast<GbxParser::ColumnsStmtContext*>(ctx)) {
      s.kind = K::Columns;
      for (auto* e : c->expr()) s.exprs.push_back(expr(e));
    } else if (auto* c = dynamic_cast<GbxParser::AssignStmtContext*>(ctx)) {
      assign(s, c);
    } else if (auto* c = dynamic_cast<GbxParser::DomainStmtContext*>(ctx)) {
      s.kind = K::Domain;
      s.path = path(c->path());
      domain(s, c->domain());
    } else if (auto* c = dynamic_cast<GbxParser::ScatterStmtContext*>(ctx)) {
      s.kind = K::Scatter;
      s.path = path(c->path());
      s.value = addExpr(c->addExpr());
    } else if (auto* c = dynamic_cast<GbxParser::BinStmtContext*>(ctx)) {
      bin(s, c);
    } else if (shaftStmt(s, ctx)) {
    } else if (auto* c = dynamic_cast<GbxParser::BlockStmtContext*>(ctx)) {
      // A gear's block (`ring.cutter { … }`) is named by its whole path.
      s.kind = K::Block;
      s.path = path(c->path());
      s.name = s.path.str();
      s.nameSpan = s.path.span;
      body(s, c->block());
    } else if (auto* c = dynamic_cast<GbxParser::FlagStmtContext*>(ctx)) {
      s.kind = K::Flag;
      setName(s, c->ID());
    } else {
      return std::nullopt;
    }
    return s;
  }

  // `x = value (when condition)?;` or `x = scene NAME;`.
  void assign(ast::Stmt& s, GbxParser::AssignStmtContext* c) {
    s.kind = ast::StmtKind::Assign;
    s.path = path(c->path());
    auto es = c->expr();
    size_t next = 0;
    if (c->SCENE() && c->ID()) {
      s.sceneRef = true;
      s.value = leaf(ast::ExprKind::Name, span(c->ID()), c->ID()->getText());
    } else if (!es.empty()) {
      s.value = expr(es[next++]);
    }
    if (es.size() > next) s.when = expr(es[next]);
  }

  // `bin LOAD [torque] for SHARE of life;` or `bin LOAD [torque] for N cycles;` (the unit
  // `cycles` marks a count of load cycles).
  void bin(ast::Stmt& s, GbxParser::BinStmtContext* c) {
    s.kind = ast::StmtKind::Bin;
    auto ids = c->ID();
    setName(s, ids[0]);
    auto t = c->tolExpr();
    if (!t.empty()) s.value = tolExpr(t[0]);
    size_t words = ids.size() - (c->OF() ? 1 : 0);
    if (words > 1) {
      s.word = ids[1]->getText();
      s.wordSpan = span(ids[1]);
    }
    if (c->OF() && ids.size() > words) {
      s.base = ids.back()->getText();
      s.baseSpan = span(ids.back());
    }
    if (t.size() > 1) s.step = tolExpr(t[1]);
    if (s.step && s.step->kind == ast::ExprKind::Number && s.step->unit && s.step->unit->factors.size() == 1 &&
        s.step->unit->factors[0].atom == "cycles" && s.step->unit->factors[0].exponent == 1) {
      s.cycles = true;
      s.step->unit.reset();
    }
  }

  void domain(ast::Stmt& s, GbxParser::DomainContext* ctx) {
    if (auto* c = dynamic_cast<GbxParser::RangeDomainContext*>(ctx)) {
      s.domain = ast::DomainKind::Range;
      auto t = c->tolExpr();
      if (t.size() > 0) s.lo = tolExpr(t[0]);
      if (t.size() > 1) s.hi = tolExpr(t[1]);
    } else if (auto* c = dynamic_cast<GbxParser::SetDomainContext*>(ctx)) {
      s.domain = ast::DomainKind::Set;
      for (auto* e : c->expr()) s.exprs.push_back(expr(e));
    } else if (auto* c = dynamic_cast<GbxParser::NamedDomainContext*>(ctx)) {
      s.domain = ast::DomainKind::Named;
      ast::Path p = path(c->path());
      s.value = pathExpr(p);
    }
  }

  ast::Path path(GbxParser::PathContext* ctx) {
    ast::Path p;
    if (!ctx) return p;
    for (auto* id : ctx->ID()) {
      p.parts.push_back(id->getText());
      p.spans.push_back(span(id));
    }
    p.span = span(ctx);
    return p;
  }

  ast::ExprPtr pathExpr(const ast::Path& p) {
    if (p.parts.empty()) return nullptr;
    auto e = leaf(ast::ExprKind::Name, p.spans[0], p.parts[0]);
    for (size_t i = 1; i < p.parts.size(); ++i) {
      auto m = leaf(ast::ExprKind::Member, source::cover(e->span, p.spans[i]), p.parts[i]);
      m->args.push_back(std::move(e));
      e = std::move(m);
    }
    return e;
  }

  static ast::ExprPtr leaf(ast::ExprKind k, Span sp, std::string text) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = k;
    e->span = sp;
    e->text = std::move(text);
    return e;
  }

  static ast::ExprPtr node(ast::ExprKind k, Span sp, std::vector<ast::ExprPtr> args) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = k;
    e->span = sp;
    e->args = std::move(args);
    return e;
  }

  template <class... A>
  static std::vector<ast::ExprPtr> list(A&&... a) {
    std::vector<ast::ExprPtr> v;
    (v.push_back(std::forward<A>(a)), ...);
    return v;
  }

  ast::ExprPtr expr(GbxParser::ExprContext* ctx) {
    if (!ctx) return nullptr;
    if (auto* c = dynamic_cast<GbxParser::ForallExprContext*>(ctx)) {
      auto e = node(ast::ExprKind::Forall, span(ctx), list(orExpr(c->orExpr()), expr(c->expr())));
      if (c->ID()) e->text = c->ID()->getText();
      return e;
    }
    if (auto* c = dynamic_cast<GbxParser::PlainExprContext*>(ctx)) return orExpr(c->orExpr());
    return nullptr;
  }

  // Folds `a op b op c` left to right over a context's alternating children.
  template <class Ctx, class Sub, class F>
  ast::ExprPtr leftFold(Ctx* ctx, const std::vector<Sub*>& subs, F build) {
    if (!ctx || subs.empty()) return nullptr;
    auto acc = build(subs[0]);
    size_t k = 1;
    for (auto* child : ctx->children) {
      auto* term = dynamic_cast<antlr4::tree::TerminalNode*>(child);
      if (!term || k >= subs.size()) continue;
      std::string op = term->getText();
      auto rhs = build(subs[k++]);
      auto e = std::make_unique<ast::Expr>();
      e->kind = ast::ExprKind::Binary;
      e->binOp = op == "+" ? ast::BinOp::Add
                 : op == "-" ? ast::BinOp::Sub
                 : op == "*" ? ast::BinOp::Mul
                 : op == "/" ? ast::BinOp::Div
                 : op == "and" ? ast::BinOp::And
                               : ast::BinOp::Or;
      Span sp = acc ? acc->span : span(ctx);
      if (rhs) sp = source::cover(sp, rhs->span);
      e->span = sp;
      e->args = list(std::move(acc), std::move(rhs));
      acc = std::move(e);
    }
    return acc;
  }

  ast::ExprPtr orExpr(GbxParser::OrExprContext* ctx) {
    return leftFold(ctx, ctx ? ctx->andExpr() : std::vector<GbxParser::AndExprContext*>{},
                    [&](auto* c) { return andExpr(c); });
  }
  ast::ExprPtr andExpr(GbxParser::AndExprContext* ctx) {
    return leftFold(ctx, ctx ? ctx->notExpr() : std::vector<GbxParser::NotExprContext*>{},
                    [&](auto* c) { return notExpr(c); });
  }
  ast::ExprPtr notExpr(GbxParser::NotExprContext* ctx) {
    if (!ctx) return nullptr;
    if (ctx->NOT()) return node(ast::ExprKind::Not, span(ctx), list(notExpr(ctx->notExpr())));
    return cmpExpr(ctx->cmpExpr());
  }
  ast::ExprPtr cmpExpr(GbxParser::CmpExprContext* ctx) {
    if (!ctx) return nullptr;
    auto t = ctx->tolExpr();
    if (t.empty()) return nullptr;
    auto lhs = tolExpr(t[0]);
    if (ctx->cmpOp()) {
      auto e = node(ast::ExprKind::Compare, span(ctx), list(std::move(lhs), t.size() > 1 ? tolExpr(t[1]) : nullptr));
      std::string op = ctx->cmpOp()->getText();
      e->cmpOp = op == "==" ? ast::CmpOp::Eq
                 : op == "!=" ? ast::CmpOp::Ne
                 : op == "<" ? ast::CmpOp::Lt
                 : op == "<=" ? ast::CmpOp::Le
                 : op == ">" ? ast::CmpOp::Gt
                             : ast::CmpOp::Ge;
      return e;
    }
    if (ctx->IN() && ctx->setLit())
      return node(ast::ExprKind::InSet, span(ctx), list(std::move(lhs), setLit(ctx->setLit())));
    if (ctx->IN())
      return node(ast::ExprKind::InRange, span(ctx),
                  list(std::move(lhs), t.size() > 1 ? tolExpr(t[1]) : nullptr, t.size() > 2 ? tolExpr(t[2]) : nullptr));
    return lhs;
  }
  ast::ExprPtr tolExpr(GbxParser::TolExprContext* ctx) {
    if (!ctx) return nullptr;
    auto a = ctx->addExpr();
    if (a.empty()) return nullptr;
    if (ctx->PLUSMINUS())
      return node(ast::ExprKind::Tolerance, span(ctx), list(addExpr(a[0]), a.size() > 1 ? addExpr(a[1]) : nullptr));
    return addExpr(a[0]);
  }
  ast::ExprPtr addExpr(GbxParser::AddExprContext* ctx) {
    return leftFold(ctx, ctx ? ctx->mulExpr() : std::vector<GbxParser::MulExprContext*>{},
                    [&](auto* c) { return mulExpr(c); });
  }
  ast::ExprPtr mulExpr(GbxParser::MulExprContext* ctx) {
    return leftFold(ctx, ctx ? ctx->unaryExpr() : std::vector<GbxParser::UnaryExprContext*>{},
                    [&](auto* c) { return unaryExpr(c); });
  }
  ast::ExprPtr unaryExpr(GbxParser::UnaryExprContext* ctx) {
    if (!ctx) return nullptr;
    if (ctx->unaryExpr()) return node(ast::ExprKind::Neg, span(ctx), list(unaryExpr(ctx->unaryExpr())));
    return powExpr(ctx->powExpr());
  }
  ast::ExprPtr powExpr(GbxParser::PowExprContext* ctx) {
    if (!ctx) return nullptr;
    auto base = postfix(ctx->postfixExpr());
    if (!ctx->unaryExpr()) return base;
    auto e = node(ast::ExprKind::Binary, span(ctx), list(std::move(base), unaryExpr(ctx->unaryExpr())));
    e->binOp = ast::BinOp::Pow;
    return e;
  }
  ast::ExprPtr postfix(GbxParser::PostfixExprContext* ctx) {
    if (!ctx) return nullptr;
    auto e = primary(ctx->primary());
    for (auto* op : ctx->postfixOp()) {
      Span sp = e ? source::cover(e->span, span(op)) : span(op);
      if (op->ID()) {
        auto m = leaf(ast::ExprKind::Member, sp, op->ID()->getText());
        m->args.push_back(std::move(e));
        e = std::move(m);
      } else {
        auto c = node(ast::ExprKind::Call, sp, list(std::move(e)));
        for (auto* a : op->expr()) c->args.push_back(expr(a));
        e = std::move(c);
      }
    }
    return e;
  }
  ast::ExprPtr setLit(GbxParser::SetLitContext* ctx) {
    if (!ctx) return nullptr;
    auto e = node(ast::ExprKind::Set, span(ctx), {});
    for (auto* a : ctx->expr()) e->args.push_back(expr(a));
    return e;
  }
  ast::ExprPtr primary(GbxParser::PrimaryContext* ctx) {
    if (!ctx) return nullptr;
    if (ctx->quantity()) return quantity(ctx->quantity());
    if (ctx->ID()) return leaf(ast::ExprKind::Name, span(ctx), ctx->ID()->getText());
    if (ctx->STRING()) {
      std::string t = ctx->STRING()->getText();
      return leaf(ast::ExprKind::String, span(ctx), t.size() >= 2 ? t.substr(1, t.size() - 2) : t);
    }
    if (ctx->TRUE() || ctx->FALSE()) {
      auto e = leaf(ast::ExprKind::Bool, span(ctx), ctx->getText());
      e->boolValue = ctx->TRUE() != nullptr;
      return e;
    }
    if (ctx->setLit()) return setLit(ctx->setLit());
    if (ctx->expr()) {
      auto e = expr(ctx->expr());
      if (e) e->span = span(ctx);
      return e;
    }
    return nullptr;
  }
  ast::ExprPtr quantity(GbxParser::QuantityContext* ctx) {
    auto e = leaf(ast::ExprKind::Number, span(ctx), ctx->NUMBER() ? ctx->NUMBER()->getText() : "0");
    if (auto* u = ctx->unit()) {
      ast::UnitExpr ue;
      ue.text = u->getText();
      ue.span = span(u);
      flatten(u, 1, ue.factors);
      e->unit = std::move(ue);
    }
    return e;
  }
  void flatten(GbxParser::UnitContext* ctx, int sign, std::vector<ast::UnitFactor>& out) {
    if (!ctx) return;
    int cur = sign;
    auto factors = ctx->unitFactor();
    size_t k = 0;
    for (auto* child : ctx->children) {
      if (auto* term = dynamic_cast<antlr4::tree::TerminalNode*>(child)) {
        cur = term->getText() == "/" ? -sign : sign;
        continue;
      }
      if (k < factors.size() && child == factors[k]) factor(factors[k++], cur, out);
    }
  }
  void factor(GbxParser::UnitFactorContext* ctx, int sign, std::vector<ast::UnitFactor>& out) {
    int e = 1;
    if (auto* n = ctx->NUMBER()) {
      auto r = units_exponent(n->getText());
      if (!r) {
        diags_.error("E0304", span(n), fmt::format("a unit exponent must be a whole number, not `{}`", n->getText()));
      } else {
        e = *r;
      }
      for (auto* child : ctx->children)
        if (child->getText() == "-") e = -e;
    }
    auto* atom = ctx->unitAtom();
    if (!atom) return;
    if (atom->unit()) {
      std::vector<ast::UnitFactor> inner;
      flatten(atom->unit(), 1, inner);
      for (auto& f : inner) {
        f.exponent *= e * sign;
        out.push_back(f);
      }
      return;
    }
    out.push_back({atom->getText(), e * sign, span(atom)});
  }
  static std::optional<int> units_exponent(const std::string& t) {
    if (t.empty() || t.size() > 2) return std::nullopt;
    for (char c : t)
      if (c < '0' || c > '9') return std::nullopt;
    return std::stoi(t);
  }

  int file_;
  diag::DiagnosticEngine& diags_;
  bool recovered_ = false; // the parse recovered from a syntax error
};

// A cheap bound on parser recursion: brackets and prefix operators nest rule calls.
bool tooDeep(const std::vector<antlr4::Token*>& tokens, int file, diag::DiagnosticEngine& diags) {
  int depth = 0, run = 0;
  for (auto* t : tokens) {
    if (t->getChannel() != antlr4::Token::DEFAULT_CHANNEL) continue;
    std::string x = t->getText();
    if (x == "(" || x == "{") ++depth;
    if (x == ")" || x == "}") depth = std::max(0, depth - 1);
    if (x == "-" || x == "not" || x == "^" || x == "forall") ++run;
    else if (x == ";") run = 0;
    if (depth + run > kMaxNesting) {
      diags.error("E0105", tokenSpan(file, t),
                  fmt::format("expression nested too deeply (more than {} levels)", kMaxNesting));
      return true;
    }
  }
  return false;
}

} // namespace

// The runtime's UTF-8 decoder throws on malformed input: find the first bad byte first.
bool validUtf8(const std::string& t, int file, diag::DiagnosticEngine& diags) {
  int line = 1, col = 1;
  for (size_t i = 0; i < t.size();) {
    auto c = static_cast<unsigned char>(t[i]);
    size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool ok = n > 0 && i + n <= t.size();
    for (size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(t[i + k]) & 0xC0) == 0x80;
    if (ok && n == 2) ok = c >= 0xC2;
    if (ok && n == 3) {
      unsigned cp = ((c & 0x0Fu) << 12) | ((static_cast<unsigned char>(t[i + 1]) & 0x3Fu) << 6) | (static_cast<unsigned char>(t[i + 2]) & 0x3Fu);
      ok = cp >= 0x800 && (cp < 0xD800 || cp > 0xDFFF);
    }
    if (ok && n == 4) {
      unsigned cp = ((c & 0x07u) << 18) | ((static_cast<unsigned char>(t[i + 1]) & 0x3Fu) << 12);
      ok = cp >= 0x10000 && cp <= 0x10FFFF;
    }
    if (!ok) {
      Span s;
      s.file = file;
      s.line = s.endLine = line;
      s.col = s.endCol = col;
      diags.error("E0104", s, fmt::format("the file is not valid UTF-8 (byte 0x{:02x})", c));
      return false;
    }
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
    i += n;
  }
  return true;
}

ParsedTree parseTree(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags) {
  ParsedTree p;
  const auto& src = sm.get(fileId);
  if (!validUtf8(src.text(), fileId, diags)) return p;
  p.input = std::make_unique<antlr4::ANTLRInputStream>(src.text());
  p.lexer = std::make_unique<GbxLexer>(p.input.get());
  p.lexer->removeErrorListeners();
  p.tokens = std::make_unique<antlr4::CommonTokenStream>(p.lexer.get());
  p.tokens->fill();

  int cutoff = 0;
  for (auto* t : p.tokens->getTokens()) {
    switch (t->getType()) {
    case GbxLexer::BAD_CHAR:
      diags.error("E0101", tokenSpan(fileId, t), fmt::format("unexpected character `{}`", t->getText()));
      break;
    case GbxLexer::UNTERMINATED_STRING:
      diags.error("E0103", tokenSpan(fileId, t), "unterminated string: a `\"` is missing before the end of the line");
      break;
    case GbxLexer::UNTERMINATED_COMMENT: {
      Span sp = tokenSpan(fileId, t);
      sp.endCol = sp.col + 1;
      diags.error("E0103", sp, "unterminated comment: `/*` is never closed by `*/`");
      cutoff = static_cast<int>(t->getLine());
      break;
    }
    default: break;
    }
  }
  if (tooDeep(p.tokens->getTokens(), fileId, diags)) return p;

  p.parser = std::make_unique<GbxParser>(p.tokens.get());
  auto& parser = *p.parser;
  parser.removeErrorListeners();
  ErrorCollector collector(fileId, diags, cutoff);
  // Two stages: SLL prediction, bailing out at the first error, parses a valid file at a
  // fraction of full LL's cost; a file it cannot parse is parsed again with LL, error
  // recovery and the diagnostics.
  auto* atn = parser.getInterpreter<antlr4::atn::ParserATNSimulator>();
  atn->setPredictionMode(antlr4::atn::PredictionMode::SLL);
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  try {
    p.tree = parser.file();
  } catch (const antlr4::ParseCancellationException&) {
    p.tokens->seek(0);
    parser.reset();
    atn->setPredictionMode(antlr4::atn::PredictionMode::LL);
    parser.setErrorHandler(std::make_shared<antlr4::DefaultErrorStrategy>());
    parser.addErrorListener(&collector);
    p.tree = parser.file();
    parser.removeErrorListeners();  // the collector goes out of scope here
  }
  return p;
}

ast::File parseFile(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags) {
  const int before = diags.errorCount();
  ParsedTree p = parseTree(sm, fileId, diags);
  if (!p.tree) {
    ast::File empty;
    empty.fileId = fileId;
    return empty;
  }
  // After a syntax error the parser's recovery reads the rest of a block as declarations:
  // one error for the mistake, not one per word after it.
  Builder builder(fileId, diags, diags.errorCount() > before);
  return builder.file(p.tree);
}

} // namespace gbx::parse
