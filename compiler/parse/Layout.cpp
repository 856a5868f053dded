#include "parse/Layout.h"

#include <cctype>
#include <unordered_map>

#include "parse/Tree.h"

namespace gbx::parse {

using grammar::GbxLexer;
using grammar::GbxParser;

namespace {

class LayoutWalk {
public:
  LayoutWalk(std::vector<LayoutToken>& out, const std::unordered_map<size_t, int>& index) : out_(out), index_(index) {}

  void walk(antlr4::tree::ParseTree* node) {
    auto* ctx = dynamic_cast<antlr4::ParserRuleContext*>(node);
    if (!ctx) return;
    if (dynamic_cast<GbxParser::TopDeclContext*>(ctx) || dynamic_cast<GbxParser::StmtContext*>(ctx)) {
      if (auto* t = at(ctx->getStart())) t->stmtStart = true;
      if (auto* t = at(ctx->getStop())) t->stmtEnd = true;
    }
    if (auto* b = dynamic_cast<GbxParser::BlockContext*>(ctx)) {
      if (auto* t = at(b->getStart())) t->blockBrace = true;
      if (auto* t = at(b->getStop())) t->blockBrace = true;
    } else if (dynamic_cast<GbxParser::AssignStmtContext*>(ctx) || dynamic_cast<GbxParser::LetStmtContext*>(ctx) ||
               dynamic_cast<GbxParser::ConstDeclContext*>(ctx)) {
      markTerminal(ctx, "=", &LayoutToken::aligned);
    } else if (dynamic_cast<GbxParser::DomainStmtContext*>(ctx)) {
      markTerminal(ctx, "in", &LayoutToken::aligned);
    } else if (auto* u = dynamic_cast<GbxParser::UnaryExprContext*>(ctx)) {
      markTerminal(u, "-", &LayoutToken::prefix);
    } else if (auto* p = dynamic_cast<GbxParser::PowExprContext*>(ctx)) {
      markTerminal(p, "^", &LayoutToken::power);
    } else if (auto* o = dynamic_cast<GbxParser::PostfixOpContext*>(ctx)) {
      markTerminal(o, "(", &LayoutToken::call);
    } else if (auto* q = dynamic_cast<GbxParser::QuantityContext*>(ctx); q && q->unit()) {
      // Every token of the unit, the hidden ones excepted (none can stand between glued parts).
      auto* unit = q->unit();
      bool first = true;
      for (size_t i = unit->getStart()->getTokenIndex(); i <= unit->getStop()->getTokenIndex(); ++i) {
        auto it = index_.find(i);
        if (it == index_.end()) continue;
        LayoutToken& t = out_[static_cast<size_t>(it->second)];
        if (t.comment()) continue;
        t.unit = true;
        t.unitStart = first;
        first = false;
      }
    }
    for (auto* child : ctx->children)
      walk(child);
  }

private:
  LayoutToken* at(antlr4::Token* t) {
    if (!t) return nullptr;
    auto it = index_.find(t->getTokenIndex());
    return it == index_.end() ? nullptr : &out_[static_cast<size_t>(it->second)];
  }
  // The direct child terminal `text` of a rule.
  void markTerminal(antlr4::ParserRuleContext* ctx, const char* text, bool LayoutToken::*flag) {
    for (auto* child : ctx->children)
      if (auto* term = dynamic_cast<antlr4::tree::TerminalNode*>(child); term && term->getText() == text)
        if (auto* t = at(term->getSymbol())) t->*flag = true;
  }

  std::vector<LayoutToken>& out_;
  const std::unordered_map<size_t, int>& index_;
};

} // namespace

std::optional<std::vector<LayoutToken>> layout(const source::SourceManager& sm, int fileId,
                                               diag::DiagnosticEngine& diags) {
  int errorsBefore = diags.errorCount();
  ParsedTree p = parseTree(sm, fileId, diags);
  if (!p.tree || diags.errorCount() != errorsBefore) return std::nullopt;

  std::vector<LayoutToken> out;
  std::unordered_map<size_t, int> index; // ANTLR token index -> position in `out`
  const auto& voc = p.parser->getVocabulary();
  std::vector<int> open; // brackets not yet closed
  for (auto* t : p.tokens->getTokens()) {
    size_t type = t->getType();
    if (type == antlr4::Token::EOF || type == GbxLexer::WS) continue;
    LayoutToken lt;
    lt.text = t->getText();
    lt.line = lt.endLine = static_cast<int>(t->getLine());
    for (char c : lt.text)
      lt.endLine += c == '\n';
    std::string literal = voc.getLiteralName(type);
    if (type == GbxLexer::LINE_COMMENT)
      lt.kind = LayoutToken::Kind::LineComment;
    else if (type == GbxLexer::BLOCK_COMMENT)
      lt.kind = LayoutToken::Kind::BlockComment;
    else if (type == GbxLexer::ID)
      lt.kind = LayoutToken::Kind::Name;
    else if (type == GbxLexer::NUMBER)
      lt.kind = LayoutToken::Kind::Number;
    else if (type == GbxLexer::STRING)
      lt.kind = LayoutToken::Kind::String;
    else if (literal.size() > 2 && std::isalpha(static_cast<unsigned char>(literal[1])))
      lt.kind = LayoutToken::Kind::Keyword;
    int here = static_cast<int>(out.size());
    if (!lt.comment() && (lt.text == "(" || lt.text == "{")) open.push_back(here);
    if (!lt.comment() && (lt.text == ")" || lt.text == "}") && !open.empty()) {
      lt.match = open.back();
      out[static_cast<size_t>(open.back())].match = here;
      open.pop_back();
    }
    index[t->getTokenIndex()] = here;
    out.push_back(std::move(lt));
  }
  LayoutWalk(out, index).walk(p.tree);
  return out;
}

std::vector<LexToken> lex(const std::string& text) {
  diag::DiagnosticEngine ignored;
  if (!validUtf8(text, 0, ignored)) return {};
  // The lexer counts code points; the reader wants bytes.
  std::vector<size_t> byteAt;
  for (size_t i = 0; i < text.size(); i += source::utf8Length(static_cast<unsigned char>(text[i])))
    byteAt.push_back(i);
  byteAt.push_back(text.size());
  antlr4::ANTLRInputStream input(text);
  GbxLexer lexer(&input);
  lexer.removeErrorListeners();
  std::vector<LexToken> out;
  for (auto t = lexer.nextToken(); t->getType() != antlr4::Token::EOF; t = lexer.nextToken()) {
    size_t type = t->getType();
    if (type == GbxLexer::WS) continue;
    LexToken k;
    k.begin = byteAt[std::min(t->getStartIndex(), byteAt.size() - 1)];
    k.end = byteAt[std::min(t->getStopIndex() + 1, byteAt.size() - 1)];
    k.line = static_cast<int>(t->getLine());
    switch (type) {
    case GbxLexer::ID: k.kind = LexToken::Kind::Word; break;
    case GbxLexer::NUMBER: k.kind = LexToken::Kind::Number; break;
    case GbxLexer::STRING: k.kind = LexToken::Kind::String; break;
    case GbxLexer::LINE_COMMENT:
    case GbxLexer::BLOCK_COMMENT: k.kind = LexToken::Kind::Comment; break;
    case GbxLexer::UNTERMINATED_STRING:
    case GbxLexer::UNTERMINATED_COMMENT: k.kind = LexToken::Kind::Unterminated; break;
    default: {
      std::string literal = lexer.getVocabulary().getLiteralName(type);
      k.kind = literal.size() > 2 && std::isalpha(static_cast<unsigned char>(literal[1])) ? LexToken::Kind::Word
                                                                                          : LexToken::Kind::Punct;
    }
    }
    out.push_back(k);
  }
  return out;
}

} // namespace gbx::parse
