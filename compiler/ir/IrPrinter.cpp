#include <fmt/format.h>

#include "ir/Ir.h"

// `dump ir`: one line per declaration, expressions fully parenthesised, constants in
// SI and exact where they are (`7/36*pi rad` for 35 deg).
namespace gbx::ir {

namespace {

std::string unitSuffix(const Dim& d) { return d.dimensionless() ? "" : " " + d.siUnit(); }

std::string join(const std::vector<ExprPtr>& v, size_t from, const char* sep) {
  std::string s;
  for (size_t i = from; i < v.size(); ++i) s += (i > from ? sep : "") + (v[i] ? print(*v[i]) : std::string("<error>"));
  return s;
}

const char* opText(Op op) {
  switch (op) {
  case Op::Add: return "+";
  case Op::Sub: return "-";
  case Op::Mul: return "*";
  case Op::Div: return "/";
  case Op::Pow: return "^";
  case Op::Eq: return "==";
  case Op::Ne: return "!=";
  case Op::Lt: return "<";
  case Op::Le: return "<=";
  case Op::Gt: return ">";
  case Op::Ge: return ">=";
  case Op::And: return "and";
  case Op::Or: return "or";
  default: return "?";
  }
}

std::string value(const std::optional<Number>& n, const Dim& d) { return n ? n->str() + unitSuffix(d) : "?"; }

std::string setting(const Setting& s) {
  std::string v;
  if (!s.symbol.empty()) v = s.symbol;
  else if (s.value) v = s.value->str() + (s.meshPeriods ? " mesh_periods" : unitSuffix(s.dim));
  else if (s.expr) v = print(*s.expr);
  else if (!s.members.empty()) {
    v = "{";
    for (size_t i = 0; i < s.members.size(); ++i) v += (i ? ", " : "") + s.members[i].str();
    v += "}" + unitSuffix(s.dim);
  } else if (s.lo || s.hi)
    v = (s.lo ? s.lo->str() : "?") + ".." + (s.hi ? s.hi->str() : "?") + unitSuffix(s.dim);
  else
    v = "<error>";
  std::string op = (!s.members.empty() || s.lo) ? " in " : " = ";
  return s.name + op + v;
}

const char* roleName(Attribute::Role r) {
  switch (r) {
  case Attribute::Fixed: return "fixed";
  case Attribute::Decision: return "decision";
  case Attribute::Freedom: return "freedom";
  case Attribute::Default: return "default";
  }
  return "?";
}

} // namespace

std::string print(const Expr& e) {
  auto a = [&](size_t i) { return i < e.args.size() && e.args[i] ? print(*e.args[i]) : std::string("<error>"); };
  switch (e.op) {
  case Op::Const:
    if (e.type.isError()) return "<error>";
    if (e.type.kind == Type::Bool) return e.value.isZero() ? "false" : "true";
    return e.value.str() + (e.marker == Marker::MeshPeriods ? " mesh_periods" : unitSuffix(e.type.dim));
  case Op::Quantity:
  case Op::Let:
  case Op::Symbol:
  case Op::SceneOutput: return e.name;
  case Op::Neg: return "(-" + a(0) + ")";
  case Op::Not: return "(not " + a(0) + ")";
  case Op::Within: return "(" + a(0) + " in " + a(1) + ".." + a(2) + ")";
  case Op::InSet: return "(" + a(0) + " in {" + join(e.args, 1, ", ") + "})";
  case Op::Set: return "{" + join(e.args, 0, ", ") + "}";
  case Op::Tol: return "(" + a(0) + " +- " + a(1) + (e.relative ? " relative" : "") + ")";
  case Op::Call: return e.name + "(" + join(e.args, 0, ", ") + ")";
  case Op::Relative: return "relative(" + a(0) + ")";
  case Op::Scatter:
    if (e.fn == cat::Fn::Quantile) return "quantile(" + join(e.args, 0, ", ") + ")";
    return std::string(e.fn == cat::Fn::Worst ? "worst(" : "mean(") + a(0) + ")";
  case Op::Forall: return "forall " + e.name + " in " + e.type.detail + " [" + join(e.args, 0, "; ") + "]";
  default: return "(" + a(0) + " " + opText(e.op) + " " + a(1) + ")";
  }
}

std::string print(const Program& p) {
  std::string o;
  for (const auto& m : p.materials) {
    o += fmt::format("material {}\n", m.name);
    for (const auto& s : m.properties) o += "  " + setting(s) + "\n";
  }
  for (const auto& g : p.gearboxes) {
    o += fmt::format("gearbox {}{}\n", g.name, g.baseline.empty() ? "" : " extends " + g.baseline);
    for (const auto& st : g.stages) {
      o += fmt::format("  stage {}: {}", st.name, stageKindName(st.kind));
      if (!st.presets.empty()) o += " with " + fmt::format("{}", fmt::join(st.presets, ", "));
      if (!st.likeOf.empty()) o += " like " + st.likeOf;
      o += "\n";
      for (const auto& a : st.attributes) {
        std::string type = a.integer ? "integer" : (a.symbol.empty() ? "real" : "name");
        std::string v;
        switch (a.role) {
        case Attribute::Fixed:
        case Attribute::Default:
          v = "= " + (!a.symbol.empty() ? (a.sceneRef ? "scene " : "") + a.symbol : (a.value ? print(*a.value) : std::string("<error>")));
          break;
        case Attribute::Decision:
        case Attribute::Freedom:
          if (!a.members.empty()) {
            v = "in {";
            for (size_t i = 0; i < a.members.size(); ++i) v += (i ? ", " : "") + a.members[i].str();
            v += "}" + unitSuffix(a.dim);
          } else {
            v = "in " + (a.lo ? a.lo->str() : "?") + ".." + (a.hi ? a.hi->str() : "?") + unitSuffix(a.dim);
          }
          break;
        }
        o += fmt::format("    {} {} {} {}  [{}]\n", roleName(a.role), type, a.name, v, a.origin);
      }
    }
    for (const auto& l : g.lets) o += fmt::format("  let {} = {}\n", l.name, l.expr ? print(*l.expr) : "<error>");
    for (const auto& r : g.rules)
      o += fmt::format("  rule{} {}\n", r.scope.empty() ? "" : " [" + r.scope + "]", r.expr ? print(*r.expr) : "<error>");
    for (const auto& i : g.interchangeable) o += fmt::format("  interchangeable {}\n", fmt::join(i, ", "));
    for (const auto& ob : g.objectives)
      o += fmt::format("  {} {}\n", ob.minimize ? "minimize" : "maximize", ob.expr ? print(*ob.expr) : "<error>");
    if (!g.operating.empty()) {
      o += "  operating\n";
      for (const auto& s : g.operating) o += "    " + setting(s) + "\n";
    }
    for (const auto& sc : g.scenes) {
      o += fmt::format("  scene {} on {}\n", sc.name, sc.target.empty() ? "gearbox" : sc.target);
      for (const auto& e : sc.effects) {
        o += fmt::format("    effect {}\n", e.name);
        for (const auto& s : e.params) o += "      " + setting(s) + "\n";
      }
      for (const auto& s : sc.settings) o += "    " + setting(s) + "\n";
      for (const auto& s : sc.accuracy) o += "    accuracy." + setting(s) + "\n";
      for (const auto& out : sc.outputs) o += "    output " + out.key() + "\n";
    }
    for (const auto& md : g.modifies) {
      o += fmt::format("  modify {}\n", md.stage);
      for (const auto& r : md.rules)
        o += fmt::format("    {} = {}{}\n", r.target, r.value ? print(*r.value) : "<error>",
                         r.when ? " when " + print(*r.when) : "");
    }
    for (const auto& sp : g.splits) {
      o += fmt::format("  split {}\n", sp.name);
      for (const auto& s : sp.settings) o += "    " + setting(s) + "\n";
    }
    for (const auto& st : g.studies) {
      if (st.kind == Study::Sweep)
        o += fmt::format("  study {}: sweep {} in {}..{} step {}{}\n", st.name, st.target, value(st.lo, st.dim.value_or(Dim{})),
                         value(st.hi, st.dim.value_or(Dim{})), value(st.step, st.dim.value_or(Dim{})), st.plot ? ", plot" : "");
      else
        o += fmt::format("  study {}: work_precision of {}\n", st.name, st.target);
      for (const auto& s : st.settings) o += "    " + setting(s) + "\n";
      for (const auto& out : st.outputs) o += "    output " + (out ? print(*out) : std::string("<error>")) + "\n";
    }
    for (const auto& t : g.tolerances) o += fmt::format("  tolerance {} +- {:.6g} (SI)\n", t.target, t.amount);
    if (g.report) {
      o += "  report\n";
      if (g.report->top) o += fmt::format("    top {}\n", *g.report->top);
      if (g.report->sortBy) o += "    sort by " + print(*g.report->sortBy) + "\n";
      for (const auto& c : g.report->columns) o += "    column " + (c ? print(*c) : std::string("<error>")) + "\n";
    }
  }
  return o;
}

} // namespace gbx::ir
