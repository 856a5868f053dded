#include "ast/Ast.h"

#include <fmt/format.h>

namespace gbx::ast {

const char* binOpText(BinOp op) {
  switch (op) {
  case BinOp::Add: return "+";
  case BinOp::Sub: return "-";
  case BinOp::Mul: return "*";
  case BinOp::Div: return "/";
  case BinOp::Pow: return "^";
  case BinOp::And: return "and";
  case BinOp::Or: return "or";
  }
  return "?";
}

const char* cmpOpText(CmpOp op) {
  switch (op) {
  case CmpOp::Eq: return "==";
  case CmpOp::Ne: return "!=";
  case CmpOp::Lt: return "<";
  case CmpOp::Le: return "<=";
  case CmpOp::Gt: return ">";
  case CmpOp::Ge: return ">=";
  }
  return "?";
}

const char* stmtKindName(StmtKind k) {
  switch (k) {
  case StmtKind::Import: return "import";
  case StmtKind::Const: return "const";
  case StmtKind::Preset: return "preset";
  case StmtKind::Gearbox: return "gearbox";
  case StmtKind::Named: return "declaration";
  case StmtKind::Stage: return "stage";
  case StmtKind::Like: return "stage like";
  case StmtKind::Let: return "let";
  case StmtKind::Require: return "require";
  case StmtKind::Interchangeable: return "interchangeable";
  case StmtKind::Minimize: return "minimize";
  case StmtKind::Maximize: return "maximize";
  case StmtKind::Operating: return "operating";
  case StmtKind::Scene: return "scene";
  case StmtKind::Effects: return "effects";
  case StmtKind::Modify: return "modify";
  case StmtKind::Split: return "split";
  case StmtKind::Study: return "study";
  case StmtKind::Report: return "report";
  case StmtKind::Output: return "output";
  case StmtKind::Sweep: return "sweep";
  case StmtKind::Of: return "of";
  case StmtKind::Top: return "top";
  case StmtKind::Sort: return "sort by";
  case StmtKind::Columns: return "columns";
  case StmtKind::Assign: return "assignment";
  case StmtKind::Domain: return "domain";
  case StmtKind::Member: return "member";
  case StmtKind::Segment: return "segment";
  case StmtKind::Placed: return "placement";
  case StmtKind::Scatter: return "tolerance";
  case StmtKind::Bin: return "spectrum bin";
  case StmtKind::Block: return "block";
  case StmtKind::Flag: return "flag";
  }
  return "?";
}

ExprPtr Expr::clone() const {
  auto e = std::make_unique<Expr>();
  e->kind = kind;
  e->span = span;
  e->text = text;
  e->unit = unit;
  e->binOp = binOp;
  e->cmpOp = cmpOp;
  e->boolValue = boolValue;
  for (const auto& a : args) e->args.push_back(a ? a->clone() : nullptr);
  return e;
}

std::string Path::str() const {
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? "." : "") + parts[i];
  return s;
}

namespace {
ExprPtr cloneOpt(const ExprPtr& e) { return e ? e->clone() : nullptr; }
} // namespace

Stmt Stmt::clone() const {
  Stmt s;
  s.kind = kind;
  s.span = span;
  s.name = name;
  s.nameSpan = nameSpan;
  s.word = word;
  s.wordSpan = wordSpan;
  s.importIsPath = importIsPath;
  s.sceneRef = sceneRef;
  s.cycles = cycles;
  s.with = with;
  s.withSpans = withSpans;
  s.base = base;
  s.baseSpan = baseSpan;
  s.path = path;
  s.value = cloneOpt(value);
  s.when = cloneOpt(when);
  s.lo = cloneOpt(lo);
  s.hi = cloneOpt(hi);
  s.step = cloneOpt(step);
  s.domain = domain;
  for (const auto& e : exprs) s.exprs.push_back(cloneOpt(e));
  s.paths = paths;
  for (const auto& b : body) s.body.push_back(b.clone());
  s.hasBody = hasBody;
  return s;
}

std::string print(const Expr& e) {
  auto a = [&](size_t i) { return i < e.args.size() && e.args[i] ? print(*e.args[i]) : std::string("<missing>"); };
  switch (e.kind) {
  case ExprKind::Number: return e.unit ? e.text + " " + e.unit->text : e.text;
  case ExprKind::Name: return e.text;
  case ExprKind::String: return "\"" + e.text + "\"";
  case ExprKind::Bool: return e.boolValue ? "true" : "false";
  case ExprKind::Neg: return "(-" + a(0) + ")";
  case ExprKind::Not: return "(not " + a(0) + ")";
  case ExprKind::Binary: return "(" + a(0) + " " + binOpText(e.binOp) + " " + a(1) + ")";
  case ExprKind::Compare: return "(" + a(0) + " " + cmpOpText(e.cmpOp) + " " + a(1) + ")";
  case ExprKind::Tolerance: return "(" + a(0) + " +- " + a(1) + ")";
  case ExprKind::InRange: return "(" + a(0) + " in " + a(1) + ".." + a(2) + ")";
  case ExprKind::InSet: return "(" + a(0) + " in " + a(1) + ")";
  case ExprKind::Set: {
    std::string s = "{";
    for (size_t i = 0; i < e.args.size(); ++i) s += (i ? ", " : "") + a(i);
    return s + "}";
  }
  case ExprKind::Call: {
    std::string s = a(0) + "(";
    for (size_t i = 1; i < e.args.size(); ++i) s += (i > 1 ? ", " : "") + a(i);
    return s + ")";
  }
  case ExprKind::Member: return a(0) + "." + e.text;
  case ExprKind::Forall: return "(forall " + e.text + " in " + a(0) + ": " + a(1) + ")";
  }
  return "?";
}

namespace {

void printStmt(std::string& out, const Stmt& s, int depth) {
  std::string ind(static_cast<size_t>(depth * 2), ' ');
  std::string head = fmt::format("{}{} @{}:{}", ind, stmtKindName(s.kind), s.span.line, s.span.col);
  auto opt = [](const ExprPtr& e) { return e ? print(*e) : std::string("<missing>"); };
  switch (s.kind) {
  case StmtKind::Import: head += fmt::format(" {}{}", s.importIsPath ? "path " : "module ", s.word); break;
  case StmtKind::Const:
  case StmtKind::Let: head += fmt::format(" {} = {}", s.name, opt(s.value)); break;
  case StmtKind::Preset: head += fmt::format(" {} for {}", s.name, s.word); break;
  case StmtKind::Gearbox: head += " " + s.name + (s.base.empty() ? "" : " extends " + s.base); break;
  case StmtKind::Named: head += fmt::format(" {} {}", s.word, s.name); break;
  case StmtKind::Stage:
    head += fmt::format(" {}: {}", s.name, s.word);
    for (size_t i = 0; i < s.with.size(); ++i) head += (i ? ", " : " with ") + s.with[i];
    break;
  case StmtKind::Like: head += fmt::format(" {} like {}", s.name, s.path.str()); break;
  case StmtKind::Require:
  case StmtKind::Minimize:
  case StmtKind::Maximize:
  case StmtKind::Top:
  case StmtKind::Sort: head += " " + opt(s.value); break;
  case StmtKind::Interchangeable:
    for (size_t i = 0; i < s.paths.size(); ++i) head += (i ? ", " : " ") + s.paths[i].str();
    break;
  case StmtKind::Scene: head += fmt::format(" {} on {}", s.name, s.path.str()); break;
  case StmtKind::Modify: head += " " + s.path.str(); break;
  case StmtKind::Split:
  case StmtKind::Study:
  case StmtKind::Block:
  case StmtKind::Flag: head += " " + s.name; break;
  case StmtKind::Output:
  case StmtKind::Columns:
    for (size_t i = 0; i < s.exprs.size(); ++i) head += (i ? ", " : " ") + opt(s.exprs[i]);
    break;
  case StmtKind::Sweep:
    head += fmt::format(" {} in {}..{} step {}", s.path.str(), opt(s.lo), opt(s.hi), opt(s.step));
    break;
  case StmtKind::Of: head += fmt::format(" {} of {}", s.name, s.path.str()); break;
  case StmtKind::Assign:
    head += fmt::format(" {} = {}{}", s.path.str(), s.sceneRef ? "scene " : "", opt(s.value));
    if (s.when) head += " when " + opt(s.when);
    break;
  case StmtKind::Scatter: head += fmt::format(" {} +- {}", s.path.str(), opt(s.value)); break;
  case StmtKind::Member: head += fmt::format(" {} {}", s.word, s.name); break;
  case StmtKind::Segment: head += fmt::format(" {}..{}", opt(s.lo), opt(s.hi)); break;
  case StmtKind::Placed: head += fmt::format(" {}{} at {}", s.name, s.path.parts.empty() ? "" : " " + s.path.str(), opt(s.value)); break;
  case StmtKind::Bin:
    head += fmt::format(" {}{} for {}{}", opt(s.value), s.word.empty() ? "" : " " + s.word, opt(s.step),
                        s.cycles ? " cycles" : s.base.empty() ? "" : " of " + s.base);
    break;
  case StmtKind::Domain:
    if (s.domain == DomainKind::Range)
      head += fmt::format(" {} in {}..{}", s.path.str(), opt(s.lo), opt(s.hi));
    else if (s.domain == DomainKind::Named)
      head += fmt::format(" {} in {}", s.path.str(), opt(s.value));
    else {
      head += " " + s.path.str() + " in {";
      for (size_t i = 0; i < s.exprs.size(); ++i) head += (i ? ", " : "") + opt(s.exprs[i]);
      head += "}";
    }
    break;
  default: break;
  }
  out += head + "\n";
  for (const auto& b : s.body) printStmt(out, b, depth + 1);
}

} // namespace

std::string print(const File& f) {
  std::string out;
  for (const auto& d : f.decls) printStmt(out, d, 0);
  return out;
}

} // namespace gbx::ast
