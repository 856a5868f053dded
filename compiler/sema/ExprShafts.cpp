#include "sema/ExprChecker.h"

#include <algorithm>

#include <fmt/format.h>

#include "catalogue/Shafts.h"
#include "diag/Suggest.h"
#include "units/Unit.h"

// A shaft's results in expressions: its own, each bearing's, one notch's, and its line at one
// of its gears (`input.deflection`, `input.A.life`, `input.notch_at(60 mm).fatigue_safety`,
// `input.slope_at(hs.pinion)`).

namespace gbx::sema {

using diag::closest;
using diag::suggestion;
using ir::Op;
using ir::Type;

// `input.deflection`, or `input.A`: one of the shaft's results or one of its bearings.
ir::ExprPtr ExprChecker::shaftMember(const std::string& shaft, const std::string& m, const source::Span& span,
                                     const Scope& s) {
  std::vector<std::string> names;
  for (const auto& o : cat::shaftOutputs()) {
    if (o.name == m) return quantity(shaft + "." + m, o, span);
    names.push_back(o.name);
  }
  std::string outputs = fmt::format("{}", fmt::join(names, ", "));
  if (const ast::Stmt* sh = s.gearbox ? s.gearbox->findShaft(shaft) : nullptr)
    for (const auto& b : sh->body)
      if (b.kind == ast::StmtKind::Placed && b.name == "bearing" && b.path.parts.size() == 1) {
        if (b.path.parts[0] == m)
          return make(Op::Quantity, Type{Type::Bearing, {}, false, shaft}, span, shaft + "." + m);
        names.push_back(b.path.parts[0]);
      }
  diags_.error("E0219", span,
               fmt::format("shaft `{}` has no `{}` (it reports {}, and each bearing's values){}", shaft, m, outputs,
                           suggestion(closest(m, names))));
  return error(span);
}

// `input.A.life`: one of a bearing's results.
ir::ExprPtr ExprChecker::bearingMember(const std::string& bearing, const std::string& m, const source::Span& span) {
  std::vector<std::string> names;
  for (const auto& o : cat::bearingOutputs()) {
    if (o.name == m) return quantity(bearing + "." + m, o, span);
    names.push_back(o.name);
  }
  diags_.error("E0219", span, fmt::format("bearing `{}` has no `{}`{}", bearing, m, suggestion(closest(m, names))));
  return error(span);
}

// `input.deflection_at(hs.pinion)`: a shaft's line at one of its gears.
ir::ExprPtr ExprChecker::shaftAt(const ast::Expr& e, const ast::Expr& callee, const ir::Expr& obj,
                                 const std::vector<const ast::Expr*>& argAst, const Scope& s) {
  const std::string& fn = callee.text;
  if (fn == "notch_at") return notchAt(e, obj, argAst, s);
  const AttrSpec* spec = nullptr;
  std::vector<std::string> fns;
  for (const auto& f : cat::shaftFunctions()) {
    fns.push_back(f.name);
    if (f.name == fn) spec = &f;
  }
  if (!spec) {
    diags_.error("E0220", callee.span,
                 fmt::format("shaft `{}` has no function `{}` (it takes {}){}", obj.name, fn, fmt::join(fns, ", "),
                             suggestion(closest(fn, fns))));
    return error(e.span);
  }
  std::string gear = argAst.size() == 1 && argAst[0] ? ast::print(*argAst[0]) : "";
  std::vector<std::string> gears;
  if (const ast::Stmt* sh = s.gearbox ? s.gearbox->findShaft(obj.name) : nullptr)
    for (const auto& b : sh->body)
      if (b.kind == ast::StmtKind::Placed && b.name == "gear") gears.push_back(b.path.str());
  if (std::find(gears.begin(), gears.end(), gear) == gears.end()) {
    diags_.error("E0219", argAst.size() == 1 && argAst[0] ? argAst[0]->span : e.span,
                 fmt::format("`{}.{}` takes one gear that shaft `{}` carries ({}){}", obj.name, fn, obj.name,
                             gears.empty() ? std::string("it carries none") : fmt::format("{}", fmt::join(gears, ", ")),
                             suggestion(closest(gear, gears))));
    return error(e.span);
  }
  return quantity(fmt::format("{}.{}({})", obj.name, fn, gear), *spec, e.span);
}

// `input.notch_at(60 mm).fatigue_safety`: one notch's result.
ir::ExprPtr ExprChecker::notchMember(const std::string& notch, const std::string& m, const source::Span& span) {
  for (const auto& o : cat::notchOutputs())
    if (o.name == m) return quantity(notch + "." + m, o, span);
  diags_.error("E0219", span,
               fmt::format("a notch has no `{}` (it reports fatigue_safety and static_safety){}", m,
                           suggestion(closest(m, {"fatigue_safety", "static_safety"}))));
  return error(span);
}

// `input.notch_at(60 mm)`: the shaft's notch at that position.
ir::ExprPtr ExprChecker::notchAt(const ast::Expr& e, const ir::Expr& obj, const std::vector<const ast::Expr*>& argAst,
                                 const Scope& s) {
  ir::ExprPtr at = argAst.size() == 1 && argAst[0] ? check(argAst[0], s) : nullptr;
  if (at && at->type.isError()) return at;
  std::vector<std::string> where;
  std::optional<std::string> found;
  if (const ast::Stmt* sh = s.gearbox ? s.gearbox->findShaft(obj.name) : nullptr)
    for (const auto& b : sh->body) {
      if (b.kind != ast::StmtKind::Placed || b.name != "notch" || !b.value) continue;
      auto x = check(b.value.get(), s);
      if (!x->isConst() || !x->type.isNumber()) continue;
      std::string text = units::showQuantity(x->value, units::dims::length);
      where.push_back(text);
      if (at && at->isConst() && at->type.dim == units::dims::length && x->value.compare(at->value) == 0) found = text;
    }
  if (!found) {
    diags_.error("E0219", argAst.size() == 1 && argAst[0] ? argAst[0]->span : e.span,
                 fmt::format("`{}.notch_at` takes the position of one of its notches ({})", obj.name,
                             where.empty() ? std::string("it has none") : fmt::format("{}", fmt::join(where, ", "))));
    return error(e.span);
  }
  return make(Op::Quantity, Type{Type::Notch, {}, false, obj.name}, e.span,
              fmt::format("{}.notch_at({})", obj.name, *found));
}

} // namespace gbx::sema
