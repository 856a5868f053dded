#include "sema/ExprChecker.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "units/Unit.h"

namespace gbx::sema {

using ir::Op;
using ir::Type;
using units::Number;

std::string describe(const Type& t, const std::string& written) {
  switch (t.kind) {
  case Type::Number: {
    std::string d = t.dim.describe();
    if (!written.empty()) d += " (" + written + ")";
    return d;
  }
  case Type::Bool: return "a condition";
  case Type::Interval: return "a tolerance interval";
  case Type::Set: return "a set";
  case Type::Stage: return "a stage";
  case Type::Gear: return "a gear";
  case Type::Collection: return "a collection";
  case Type::Signal: return "a plot or spectrum";
  case Type::Symbol: return "a word";
  case Type::Material: return "a material";
  case Type::Scene: return "a scene";
  case Type::Split: return "a split";
  case Type::Shaft: return "a shaft";
  case Type::Bearing: return "a bearing";
  case Type::Notch: return "a notch";
  case Type::PerGear: return "a per-gear quantity";
  case Type::Block: return "a settings block";
  case Type::Error: return "an erroneous expression";
  }
  return "?";
}

ir::ExprPtr make(Op op, Type t, source::Span span, std::string name) {
  auto e = std::make_unique<ir::Expr>();
  e->op = op;
  e->type = std::move(t);
  e->span = span;
  e->name = std::move(name);
  return e;
}

namespace {

std::string writtenUnit(const ast::Expr* e) {
  if (e && e->kind == ast::ExprKind::Number && e->unit) return e->unit->text;
  return "";
}

// `%` is the one unit written as a symbol: the lexer's token, not a catalogue name.
constexpr std::string_view kPercent = "%";

bool isPercentUnit(const ast::UnitExpr& u) {
  return u.factors.size() == 1 && u.factors[0].atom == kPercent && u.factors[0].exponent == 1;
}

bool isPercentLiteral(const ast::Expr* e) { return e && e->kind == ast::ExprKind::Number && e->unit && isPercentUnit(*e->unit); }

// The SI value of the zero of a literal's own unit (273.15 K for `20 degC`); 0 for any other
// expression or unit, a compound unit included.
Number literalZero(const ast::Expr* e) {
  Number none = Number::exact(units::Rational(0));
  if (!e || e->kind != ast::ExprKind::Number || !e->unit || e->unit->factors.size() != 1 || e->unit->factors[0].exponent != 1) return none;
  auto atom = units::lookupAtom(e->unit->factors[0].atom);
  return atom ? atom->offset : none;
}

// `-10 degC` is 10 degrees below the unit's zero, not the negated absolute temperature.
Number negated(const ast::Expr& operand, const Number& si) {
  Number zero = literalZero(&operand);
  return zero.isZero() ? si.neg() : si.neg().add(zero.add(zero));
}

} // namespace

ir::ExprPtr ExprChecker::error(const source::Span& span) { return make(Op::Const, Type::error(), span); }

bool ExprChecker::celsiusLiteral(const ast::Expr* e) { return !literalZero(e).isZero(); }

bool ExprChecker::refuseCelsiusDifference(const ast::Expr* e, const char* what) {
  if (!celsiusLiteral(e)) return false;
  diags_.error("E0302", e->span,
               fmt::format("{} is a temperature difference: write it in K (`{} K`), not `{} {}` (which is {} K above zero)", what, e->text,
                           e->text, e->unit->text, units::formatDouble(literal(*e)->value.toDouble())));
  return true;
}

ir::ExprPtr ExprChecker::literal(const ast::Expr& e, const ast::UnitExpr* unitOverride, bool difference) {
  auto r = units::Rational::parseDecimal(e.text);
  Number v = r ? Number::exact(*r) : Number::approx(std::strtod(e.text.c_str(), nullptr));
  const ast::UnitExpr* u = e.unit ? &*e.unit : unitOverride;
  units::Unit unit;
  Number zero = Number::exact(units::Rational(0));
  bool ok = true;
  if (u) {
    for (const auto& f : u->factors) {
      auto atom = units::lookupAtom(f.atom);
      if (!atom) {
        std::string hint = closest(f.atom, units::atomNames());
        diags_.error("E0301", f.span.valid() ? f.span : u->span,
                     fmt::format("unknown unit `{}`{}", f.atom, suggestion(hint)));
        ok = false;
        continue;
      }
      unit = units::multiply(unit, units::powerOf(*atom, f.exponent));
      if (u->factors.size() == 1 && f.exponent == 1 && !difference) zero = atom->offset;
    }
  }
  if (!ok) return error(e.span);
  bool integer = !u && r && r->isInteger();
  Number si = v.mul(unit.scale);
  // `80 degC` alone is an absolute temperature: its unit's zero is added.
  si = si.add(zero);
  if (!si.isRational()) {
    // Beyond a double either way, in SI: 1e400 is not infinity, 1e-400 (or 1e-320 um) not zero.
    double d = si.toDouble();
    std::string mantissa = e.text.substr(0, e.text.find_first_of("eE"));
    bool nonzero = mantissa.find_first_of("123456789") != std::string::npos;
    if (!std::isfinite(d) || (d == 0 && nonzero)) {
      diags_.error("E0306", e.span, fmt::format("`{}{}` is beyond the range of a double in SI units (magnitudes from about 1e-308 to 1e308)",
                                                e.text, u ? " " + u->text : ""));
      return error(e.span);
    }
  }
  auto c = ir::makeConst(si, unit.dim, integer, e.span);
  if (unit.meshPeriods) c->marker = ir::Marker::MeshPeriods;
  // A percentage stays marked through consts, so `+- tolerance` with `const tolerance = 1%` is relative.
  if (u && isPercentUnit(*u)) c->marker = ir::Marker::Percent;
  return c;
}

ir::ExprPtr ExprChecker::requireNumber(ir::ExprPtr x, const char* what) {
  if (x->type.isError() || x->type.isNumber()) return x;
  diags_.error("E0306", x->span, fmt::format("{} must be a number, but this is {}", what, describe(x->type)));
  return error(x->span);
}

bool ExprChecker::requireBool(const ir::Expr& x, const char* what) {
  if (x.type.isError() || x.type.kind == Type::Bool) return true;
  diags_.error("E0305", x.span, fmt::format("{} must be a condition (a comparison, `coprime(…)`, `and`/`or`), but this is {}",
                                            what, describe(x.type)));
  return false;
}

ir::ExprPtr ExprChecker::check(const ast::Expr* e, const Scope& s) {
  if (!e) return error({});
  switch (e->kind) {
  case ast::ExprKind::Number: {
    auto c = literal(*e);
    if (!c->type.isError() && c->marker == ir::Marker::MeshPeriods && !s.meshPeriodsAllowed) {
      diags_.error("E0301", e->unit ? e->unit->span : e->span,
                   "`mesh_period` is a unit only in a scene's time settings (settle, record, ramp, steps)");
      return error(e->span);
    }
    return c;
  }
  case ast::ExprKind::String:
    diags_.error("E0306", e->span, "a string is only allowed as an import path");
    return error(e->span);
  case ast::ExprKind::Bool: {
    auto b = make(Op::Const, Type::boolean(), e->span);
    b->value = Number::exact(units::Rational(e->boolValue ? 1 : 0));
    return b;
  }
  case ast::ExprKind::Name: return name(*e, s);
  case ast::ExprKind::Member: return member(*e, s);
  case ast::ExprKind::Call: return call(*e, s);
  case ast::ExprKind::Neg: {
    auto a = requireNumber(check(e->args[0].get(), s), "the operand of `-`");
    if (a->type.isError()) return a;
    if (a->isConst()) {
      a->value = negated(*e->args[0], a->value);
      a->span = e->span;
      return a;
    }
    auto n = make(Op::Neg, a->type, e->span);
    n->args.push_back(std::move(a));
    return n;
  }
  case ast::ExprKind::Not: {
    auto a = check(e->args[0].get(), s);
    if (a->type.isError() || !requireBool(*a, "the operand of `not`")) return error(e->span);
    auto n = make(Op::Not, Type::boolean(), e->span);
    n->args.push_back(std::move(a));
    return n;
  }
  case ast::ExprKind::Binary: return binary(*e, s);
  case ast::ExprKind::Compare: return compare(*e, s);
  case ast::ExprKind::Tolerance: {
    auto t = tolerance(*e, s);
    if (!t->type.isError())
      diags_.error("E0306", e->span, "a tolerance `a +- b` is only meaningful on the right of `==` or `!=`");
    return error(e->span);
  }
  case ast::ExprKind::InRange: {
    auto x = requireNumber(check(e->args[0].get(), s), "the value tested by `in`");
    auto [lo, hi] = checkRange(e->args[1].get(), e->args[2].get(), s);
    lo = requireNumber(std::move(lo), "a range bound");
    hi = requireNumber(std::move(hi), "a range bound");
    if (x->type.isError() || lo->type.isError() || hi->type.isError()) return error(e->span);
    for (const auto* b : {lo.get(), hi.get()})
      if (b->type.dim != x->type.dim) {
        diags_.error("E0303", b->span,
                     fmt::format("dimension mismatch: `in` tests {} against a range of {}", describe(x->type),
                                 describe(b->type)));
        return error(e->span);
      }
    if (lo->isConst() && hi->isConst() && lo->value.compare(hi->value) > 0) {
      diags_.error("E0401", source::cover(lo->span, hi->span), "inverted range: the lower bound is above the upper bound");
      return error(e->span);
    }
    auto n = make(Op::Within, Type::boolean(), e->span);
    n->args.push_back(std::move(x));
    n->args.push_back(std::move(lo));
    n->args.push_back(std::move(hi));
    return n;
  }
  case ast::ExprKind::InSet: {
    auto x = requireNumber(check(e->args[0].get(), s), "the value tested by `in`");
    auto n = make(Op::InSet, Type::boolean(), e->span);
    bool bad = x->type.isError();
    const ast::Expr* set = e->args[1].get();
    n->args.push_back(std::move(x));
    if (set)
      for (const auto& m : set->args) {
        auto v = requireNumber(check(m.get(), s), "a set member");
        if (!v->type.isError() && !n->args[0]->type.isError() && v->type.dim != n->args[0]->type.dim) {
          diags_.error("E0303", v->span,
                       fmt::format("dimension mismatch: `in` tests {} against a member that is {}",
                                   describe(n->args[0]->type), describe(v->type)));
          bad = true;
        }
        bad = bad || v->type.isError();
        n->args.push_back(std::move(v));
      }
    return bad ? error(e->span) : std::move(n);
  }
  case ast::ExprKind::Set: {
    auto n = make(Op::Set, Type{Type::Set, {}, true, {}}, e->span);
    bool bad = false;
    for (size_t i = 0; i < e->args.size(); ++i) {
      auto v = requireNumber(check(e->args[i].get(), s), "a set member");
      if (v->type.isError()) {
        bad = true;
        continue;
      }
      if (i == 0) n->type.dim = v->type.dim;
      else if (v->type.dim != n->type.dim) {
        diags_.error("E0303", v->span,
                     fmt::format("dimension mismatch: a set of {} cannot hold {}", n->type.dim.describe(), describe(v->type)));
        bad = true;
      }
      n->type.integer = n->type.integer && v->type.integer;
      n->args.push_back(std::move(v));
    }
    return bad ? error(e->span) : std::move(n);
  }
  case ast::ExprKind::Forall: return forall(*e, s);
  }
  return error(e->span);
}

std::pair<ir::ExprPtr, ir::ExprPtr> ExprChecker::checkRange(const ast::Expr* lo, const ast::Expr* hi, const Scope& s) {
  auto h = check(hi, s);
  ir::ExprPtr l;
  if (lo && hi && lo->kind == ast::ExprKind::Number && !lo->unit && hi->kind == ast::ExprKind::Number && hi->unit)
    l = literal(*lo, &*hi->unit);
  else
    l = check(lo, s);
  return {std::move(l), std::move(h)};
}

ir::ExprPtr ExprChecker::quantity(const std::string& path, const AttrSpec& spec, const source::Span& span) {
  if (spec.value == ValueKind::Material) return make(Op::Quantity, Type{Type::Material, {}, false, {}}, span, path);
  if (spec.value == ValueKind::Symbol || spec.value == ValueKind::Stage)
    return make(Op::Quantity, Type{Type::Symbol, {}, false, {}}, span, path);
  return make(Op::Quantity, Type::number(spec.dim, spec.integer), span, path);
}

ir::ExprPtr ExprChecker::stageMember(const StageModel& st, const std::string& m, const source::Span& span) {
  if (!st.kind) return error(span);
  if (isGear(*st.kind, m)) return make(Op::Quantity, Type{Type::Gear, {}, false, st.name + "." + m}, span, st.name + "." + m);
  if (keyOf(m) == Q::Teeth) return make(Op::Quantity, Type{Type::Collection, {}, false, "teeth"}, span, st.name + ".teeth");
  if (const auto* a = findAttr(*st.kind, m)) return quantity(st.name + "." + m, *a, span);
  std::vector<std::string> names = st.kind->gears;
  for (const auto& a : st.kind->stage) names.push_back(a.name);
  std::string hint = closest(m, names);
  diags_.error("E0219", span,
               fmt::format("`{}` is not an attribute of {} stage `{}`{}", m, st.kind->name, st.name,
                           suggestion(hint)));
  return error(span);
}

std::vector<std::string> ExprChecker::visibleNames(const Scope& s) const {
  std::vector<std::string> n;
  for (const auto& b : bound_) n.push_back(b.name);
  if (s.stage && s.stage->kind) {
    for (const auto& g : s.stage->kind->gears) n.push_back(g);
    for (const auto& a : s.stage->kind->stage) n.push_back(a.name);
  }
  if (s.context == Scope::Modify)
    for (const auto& b : modifyBuiltins()) n.push_back(b.name);
  if (s.gearbox) {
    for (const auto& st : s.gearbox->stages) n.push_back(st.name);
    for (const auto* l : s.gearbox->lets) n.push_back(l->name);
    for (const auto* sc : s.gearbox->scenes) n.push_back(sc->name);
    for (const auto* sp : s.gearbox->splits) n.push_back(sp->name);
    for (const auto& q : gearboxQuantities()) n.push_back(q.name);
  }
  for (const auto& [c, _] : globals_.consts) n.push_back(c);
  for (const auto& [m, _] : globals_.materials) n.push_back(m);
  return n;
}

ir::ExprPtr ExprChecker::name(const ast::Expr& e, const Scope& s) {
  const std::string& n = e.text;
  for (auto it = bound_.rbegin(); it != bound_.rend(); ++it) {
    if (it->name != n) continue;
    if (it->stage)
      return make(Op::Quantity, Type{Type::Stage, {}, false, it->stage->kind ? it->stage->kind->name : ""}, e.span,
                  it->stage->name);
    auto v = it->value->clone();
    v->span = e.span;
    return v;
  }
  if (s.context == Scope::EffectParam &&
      std::find(s.effectLocals.begin(), s.effectLocals.end(), n) != s.effectLocals.end())
    // ADAMS convention (docs/dynamics.md): C = 0.01·K takes K's SI magnitude as a damping coefficient.
    return make(Op::Symbol, Type::number(units::dims::dampingCoeff), e.span, n);
  if (s.context == Scope::Modify && s.stage) {
    for (const auto& b : modifyBuiltins()) {
      if (b.name != n) continue;
      if (b.perGear && !s.modifyGear.empty())
        return make(Op::Quantity, Type::number(b.dim), e.span, s.stage->name + "." + s.modifyGear + "." + n);
      if (b.perGear) return make(Op::Quantity, Type{Type::PerGear, b.dim, false, {}}, e.span, s.stage->name + "." + n);
      return make(Op::Quantity, Type::number(b.dim), e.span, s.stage->name + "." + n);
    }
  }
  // Inside a stage of unknown kind every name would be unknown: that was reported once.
  if (s.stage && !s.stage->kind) return error(e.span);
  if (s.stage) {
    for (const auto* l : s.stage->lets)
      if (l->name == n) {
        Type t = letResolver_ ? letResolver_(n, s.stage) : Type::error();
        return make(Op::Let, t, e.span, s.stage->name + "." + n);
      }
    if (s.stage->kind && (isGear(*s.stage->kind, n) || findAttr(*s.stage->kind, n) || keyOf(n) == Q::Teeth))
      return stageMember(*s.stage, n, e.span);
  }
  if (s.gearbox) {
    for (const auto* l : s.gearbox->lets)
      if (l->name == n) {
        Type t = letResolver_ ? letResolver_(n, nullptr) : Type::error();
        return make(Op::Let, t, e.span, n);
      }
    for (const auto& q : gearboxQuantities())
      if (q.name == n) return quantity(n, q, e.span);
    if (keyOf(n) == Q::Stages || keyOf(n) == Q::Teeth) return make(Op::Quantity, Type{Type::Collection, {}, false, n}, e.span, n);
    if (const auto* st = s.gearbox->findStage(n))
      return make(Op::Quantity, Type{Type::Stage, {}, false, st->kind ? st->kind->name : ""}, e.span, n);
    if (s.gearbox->findScene(n)) return make(Op::Quantity, Type{Type::Scene, {}, false, {}}, e.span, n);
    if (s.gearbox->findSplit(n)) return make(Op::Quantity, Type{Type::Split, {}, false, {}}, e.span, n);
    if (s.gearbox->findShaft(n)) return make(Op::Quantity, Type{Type::Shaft, {}, false, {}}, e.span, n);
  }
  if (auto it = globals_.constValues.find(n); it != globals_.constValues.end()) {
    auto v = it->second->clone();
    v->span = e.span;
    return v;
  }
  if (globals_.consts.count(n)) return error(e.span);  // const with an error, already reported
  if (globals_.materials.count(n)) return make(Op::Quantity, Type{Type::Material, {}, false, {}}, e.span, n);
  if (findFunction(n) || findSignalFn(n)) {
    diags_.error("E0306", e.span, fmt::format("`{}` is a function: call it, as in `{}(…)`", n, n));
    return error(e.span);
  }
  std::string hint = closest(n, visibleNames(s));
  diags_.error("E0201", e.span,
               fmt::format("unknown name `{}`{}", n, suggestion(hint)));
  return error(e.span);
}

ir::ExprPtr ExprChecker::member(const ast::Expr& e, const Scope& s) {
  auto obj = check(e.args[0].get(), s);
  const std::string& m = e.text;
  switch (obj->type.kind) {
  case Type::Error: return obj;
  case Type::Stage: {
    const StageModel* st = s.gearbox ? s.gearbox->findStage(obj->name) : nullptr;
    if (!st) return error(e.span);
    return stageMember(*st, m, e.span);
  }
  case Type::Gear: {
    std::string stageName = obj->name.substr(0, obj->name.find('.'));
    std::string gear = obj->name.substr(obj->name.find('.') + 1);
    const StageModel* st = s.gearbox ? s.gearbox->findStage(stageName) : nullptr;
    if (!st || !st->kind) return error(e.span);
    if (const auto* a = findAttr(*st->kind, gear + "." + m)) return quantity(obj->name + "." + m, *a, e.span);
    std::vector<std::string> names;
    for (const auto& a : st->kind->gear) names.push_back(a.name);
    std::string hint = closest(m, names);
    diags_.error("E0219", e.span,
                 fmt::format("`{}` is not an attribute of a gear{}", m,
                             suggestion(hint)));
    return error(e.span);
  }
  case Type::Split: {
    for (const auto& o : splitOutputs())
      if (o.name == m) return quantity(obj->name + "." + m, o, e.span);
    for (const auto& st : splitSettings()) {
      if (st.name == m) return quantity(obj->name + "." + m, st, e.span);
      if (st.name.rfind(m + ".", 0) == 0)
        return make(Op::Quantity, Type{Type::Block, {}, false, m}, e.span, obj->name + "." + m);
    }
    std::vector<std::string> names;
    for (const auto& o : splitOutputs()) names.push_back(o.name);
    std::string hint = closest(m, names);
    diags_.error("E0219", e.span,
                 fmt::format("split `{}` has no `{}` (it reports twist, displacement, imbalance, branch_torque){}",
                             obj->name, m, suggestion(hint)));
    return error(e.span);
  }
  case Type::Shaft: return shaftMember(obj->name, m, e.span, s);
  case Type::Notch: return notchMember(obj->name, m, e.span);
  case Type::Bearing: return bearingMember(obj->name, m, e.span);
  case Type::Block: {
    std::string split = obj->name.substr(0, obj->name.find('.'));
    std::string path = obj->type.detail + "." + m;
    for (const auto& st : splitSettings())
      if (st.name == path) return quantity(split + "." + path, st, e.span);
    diags_.error("E0219", e.span, fmt::format("`{}` has no setting `{}`", obj->type.detail, m));
    return error(e.span);
  }
  case Type::Material: {
    for (const auto& p : materialProperties())
      if (p.name == m) return quantity(obj->name + "." + m, p, e.span);
    diags_.error("E0219", e.span, fmt::format("a material has no property `{}`", m));
    return error(e.span);
  }
  case Type::Scene:
    // A single result of the scene: `vibration.dynamic_factor`, `vibration.stability`.
    if (const auto* sig = findSignal(m); sig && sig->scalar && sig->id != Signal::Modes) {
      const ast::Stmt* scene = s.gearbox->findScene(obj->name);
      // Every periodic scene has a stability; a settled or from-rest one has none.
      bool transient = false;
      for (const auto& st : scene->body)
        if (st.kind == ast::StmtKind::Assign && (keyOf(st.path.str()) == Q::Settle || keyOf(st.path.str()) == Q::Duration)) transient = true;
      if (sig->id == Signal::Stability && transient) {
        diags_.error("E0232", e.span,
                     fmt::format("scene `{}` settles a transient or runs from rest, so it has no `stability` (the largest Floquet "
                                 "multiplier of the periodic steady state); write `steady_state = periodic` in it",
                                 obj->name));
        return error(e.span);
      }
      bool declared = sig->id == Signal::Stability;
      for (const auto& st : scene->body)
        if (st.kind == ast::StmtKind::Output)
          for (const auto& o : st.exprs)
            if (o && o->kind == ast::ExprKind::Name && o->text == m) declared = true;
      if (!declared) {
        diags_.error("E0218", e.span, fmt::format("scene `{}` does not output `{}`; add it to the scene's `output` list", obj->name, m));
        return error(e.span);
      }
      return make(Op::SceneOutput, Type::number(sig->dim), e.span, obj->name + "." + m);
    }
    diags_.error("E0218", e.span,
                 fmt::format("a scene's results are read by a function of a signal, as in `{}.rms(acceleration)`",
                             obj->name));
    return error(e.span);
  default:
    diags_.error("E0219", e.span, fmt::format("{} has no members; `.{}` cannot be read from it", describe(obj->type), m));
    return error(e.span);
  }
}

ir::ExprPtr ExprChecker::binary(const ast::Expr& e, const Scope& s) {
  auto bop = e.binOp;
  if (bop == ast::BinOp::And || bop == ast::BinOp::Or) {
    auto a = check(e.args[0].get(), s);
    auto b = check(e.args[1].get(), s);
    // Both operands are checked, so that each wrong one is reported.
    bool okA = requireBool(*a, bop == ast::BinOp::And ? "an operand of `and`" : "an operand of `or`");
    bool okB = requireBool(*b, bop == ast::BinOp::And ? "an operand of `and`" : "an operand of `or`");
    bool ok = okA && okB;
    if (!ok || a->type.isError() || b->type.isError()) return error(e.span);
    auto n = make(bop == ast::BinOp::And ? Op::And : Op::Or, Type::boolean(), e.span);
    n->args.push_back(std::move(a));
    n->args.push_back(std::move(b));
    return n;
  }
  const char* sym = ast::binOpText(bop);
  auto a = check(e.args[0].get(), s);
  auto b = check(e.args[1].get(), s);
  if (a->type.isError() || b->type.isError()) return error(e.span);
  if (a->type.kind == Type::PerGear || b->type.kind == Type::PerGear) {
    // Per-gear quantities combine gear by gear; a reduction (mean/max/min) makes a number.
    if ((a->type.kind == Type::PerGear || a->type.isNumber()) && (b->type.kind == Type::PerGear || b->type.isNumber()) &&
        (bop == ast::BinOp::Add || bop == ast::BinOp::Sub) && a->type.dim == b->type.dim) {
      auto n = make(bop == ast::BinOp::Add ? Op::Add : Op::Sub, Type{Type::PerGear, a->type.dim, false, {}}, e.span);
      n->args.push_back(std::move(a));
      n->args.push_back(std::move(b));
      return n;
    }
  }
  // A Celsius temperature has its zero at 273.15 K: a sum, a multiple or a quotient of one
  // would carry that zero along.
  for (const auto* x : {e.args[0].get(), e.args[1].get()})
    if (bop != ast::BinOp::Sub && celsiusLiteral(x)) {
      diags_.error("E0302", x->span,
                   fmt::format("`{} {}` is a temperature on the Celsius scale (its zero is 273.15 K): it can be compared or subtracted, "
                               "not used in `{}`; write a temperature difference in K",
                               x->text, x->unit->text, sym));
      return error(e.span);
    }
  a = requireNumber(std::move(a), fmt::format("the left operand of `{}`", sym).c_str());
  b = requireNumber(std::move(b), fmt::format("the right operand of `{}`", sym).c_str());
  if (a->type.isError() || b->type.isError()) return error(e.span);
  Type t;
  Op op;
  switch (bop) {
  case ast::BinOp::Add:
  case ast::BinOp::Sub:
    if (a->type.dim != b->type.dim) {
      diags_.error("E0303", e.span,
                   fmt::format("dimension mismatch: cannot {} {} and {}", bop == ast::BinOp::Add ? "add" : "subtract",
                               describe(a->type, writtenUnit(e.args[0].get())),
                               describe(b->type, writtenUnit(e.args[1].get()))));
      return error(e.span);
    }
    t = Type::number(a->type.dim, a->type.integer && b->type.integer);
    op = bop == ast::BinOp::Add ? Op::Add : Op::Sub;
    break;
  case ast::BinOp::Mul:
    t = Type::number(a->type.dim * b->type.dim, a->type.integer && b->type.integer);
    op = Op::Mul;
    break;
  case ast::BinOp::Div:
    if (b->isConst() && b->value.isZero()) {
      diags_.error("E0306", b->span, "division by zero");
      return error(e.span);
    }
    t = Type::number(a->type.dim / b->type.dim, false);
    op = Op::Div;
    break;
  case ast::BinOp::Pow: {
    op = Op::Pow;
    if (!b->type.dim.dimensionless()) {
      diags_.error("E0303", b->span, fmt::format("an exponent must be a plain number, not {}", describe(b->type)));
      return error(e.span);
    }
    if (a->type.dim.dimensionless()) {
      t = Type::number(a->type.dim, a->type.integer && b->type.integer && b->isConst() && b->value.sign() >= 0);
      break;
    }
    if (!b->isConst() || !b->value.isRational() || !b->value.rational().isInteger() ||
        b->value.rational().abs() > units::Rational(16)) {
      diags_.error("E0304", b->span,
                   fmt::format("{} can only be raised to a small whole constant power", describe(a->type)));
      return error(e.span);
    }
    t = Type::number(a->type.dim.pow(static_cast<int>(b->value.rational().num())), false);
    break;
  }
  default: return error(e.span);
  }
  if (a->isConst() && b->isConst()) {
    Number v;
    switch (op) {
    case Op::Add: v = a->value.add(b->value); break;
    case Op::Sub: v = a->value.sub(b->value); break;
    case Op::Mul: v = a->value.mul(b->value); break;
    case Op::Div: v = a->value.div(b->value); break;
    default: {
      bool intExp = b->value.isRational() && b->value.rational().isInteger() && b->value.rational().abs() <= units::Rational(64);
      v = intExp ? a->value.pow(static_cast<int>(b->value.rational().num()))
                 : Number::approx(std::pow(a->value.toDouble(), b->value.toDouble()));
    }
    }
    if (!v.isRational() && !std::isfinite(v.toDouble())) {
      diags_.error("E0306", e.span, "this constant is not a finite number: it overflows a double (or is 0 times infinity)");
      return error(e.span);
    }
    auto c = ir::makeConst(v, t.dim, t.integer && v.isRational() && v.rational().isInteger(), e.span);
    // 2 * 1% is still a percentage; a sum of percentages is not obviously one and stays plain.
    bool pa = a->marker == ir::Marker::Percent, pb = b->marker == ir::Marker::Percent;
    if ((op == Op::Mul || op == Op::Div) && pa != pb && a->type.dim.dimensionless() && b->type.dim.dimensionless() &&
        (op == Op::Mul || pa))
      c->marker = ir::Marker::Percent;
    return c;
  }
  auto n = make(op, t, e.span);
  n->args.push_back(std::move(a));
  n->args.push_back(std::move(b));
  return n;
}

// The quantity a `worst`, `mean` or `quantile` reads over the tolerances, as written (the
// Monte Carlo report heads its statistics with it).
static std::string scatteredText(const ast::Expr& call) {
  return call.args.size() > 1 && call.args[1] ? ast::print(*call.args[1]) : std::string();
}

ir::ExprPtr ExprChecker::tolerance(const ast::Expr& e, const Scope& s) {
  auto centre = requireNumber(check(e.args[0].get(), s), "the target of a tolerance");
  auto tol = requireNumber(check(e.args[1].get(), s), "a tolerance");
  if (centre->type.isError() || tol->type.isError()) return error(e.span);
  if (refuseCelsiusDifference(e.args[1].get(), "a tolerance")) return error(e.span);
  bool relative = isPercentLiteral(e.args[1].get()) || (tol->isConst() && tol->marker == ir::Marker::Percent);
  if (!relative && tol->type.dim != centre->type.dim) {
    diags_.error("E0302", tol->span,
                 fmt::format("unit mismatch: the tolerance must be {} like its target, or a percentage; got {}",
                             centre->type.dim.describe(), describe(tol->type, writtenUnit(e.args[1].get()))));
    return error(e.span);
  }
  if (tol->isConst() && tol->value.sign() < 0) {
    diags_.error("E0409", tol->span, "a tolerance cannot be negative");
    return error(e.span);
  }
  auto n = make(Op::Tol, Type{Type::Interval, centre->type.dim, false, {}}, e.span);
  n->relative = relative;
  n->args.push_back(std::move(centre));
  n->args.push_back(std::move(tol));
  return n;
}

ir::ExprPtr ExprChecker::compare(const ast::Expr& e, const Scope& s) {
  static const Op ops[] = {Op::Eq, Op::Ne, Op::Lt, Op::Le, Op::Gt, Op::Ge};
  Op op = ops[static_cast<int>(e.cmpOp)];
  auto a = requireNumber(check(e.args[0].get(), s), "the left side of a comparison");
  const ast::Expr* rhs = e.args[1].get();
  ir::ExprPtr b;
  if (rhs && rhs->kind == ast::ExprKind::Tolerance) {
    if (op != Op::Eq && op != Op::Ne) {
      diags_.error("E0306", rhs->span, "a tolerance `a +- b` can only be compared with `==` or `!=`");
      return error(e.span);
    }
    b = tolerance(*rhs, s);
  } else {
    b = requireNumber(check(rhs, s), "the right side of a comparison");
  }
  if (a->type.isError() || b->type.isError()) return error(e.span);
  if (a->type.dim != b->type.dim) {
    // A bare number against a quantity with a unit: show it with the quantity's usual unit.
    auto unit = units::displayUnitFor(a->type.dim);
    std::string fix = rhs && rhs->kind == ast::ExprKind::Number && !rhs->unit && b->type.dim.dimensionless() && !unit.name.empty()
                          ? fmt::format("; write it with a unit, as `{} {}`", rhs->text, unit.name)
                          : "";
    diags_.error("E0303", e.span,
                 fmt::format("dimension mismatch: cannot compare {} with {}{}", describe(a->type, writtenUnit(e.args[0].get())),
                             b->type.kind == Type::Interval ? b->type.dim.describe()
                                                            : describe(b->type, writtenUnit(rhs)),
                             fix));
    return error(e.span);
  }
  auto n = make(op, Type::boolean(), e.span);
  n->args.push_back(std::move(a));
  n->args.push_back(std::move(b));
  return n;
}

ir::ExprPtr ExprChecker::forall(const ast::Expr& e, const Scope& s) {
  auto coll = check(e.args[0].get(), s);
  if (coll->type.isError()) return coll;
  std::vector<Bound> elements;
  std::string collName;
  if (coll->type.kind == Type::Collection && s.gearbox) {
    collName = coll->name;
    bool stages = keyOf(coll->type.detail) == Q::Stages;
    std::string onlyStage = coll->name.find('.') != std::string::npos ? coll->name.substr(0, coll->name.find('.')) : "";
    for (const auto& st : s.gearbox->stages) {
      if (!onlyStage.empty() && st.name != onlyStage) continue;
      if (stages) {
        elements.push_back({e.text, nullptr, &st});
        continue;
      }
      if (!st.kind) continue;
      for (const auto& g : st.kind->gears)
        elements.push_back({e.text, make(Op::Quantity, Type::number({}, true), e.span, st.name + "." + g + ".z"), nullptr});
    }
  } else if (coll->op == Op::Set) {
    collName = "set";
    for (auto& m : coll->args) elements.push_back({e.text, std::move(m), nullptr});
  } else {
    diags_.error("E0306", coll->span,
                 fmt::format("`forall` ranges over `teeth`, `stages` or a set `{{…}}`, not over {}", describe(coll->type)));
    return error(e.span);
  }
  auto n = make(Op::Forall, Type::boolean(), e.span, e.text);
  n->type.detail = collName;
  bool bad = false;
  for (auto& el : elements) {
    bound_.push_back(std::move(el));
    auto body = check(e.args[1].get(), s);
    bound_.pop_back();
    if (body->type.isError() || !requireBool(*body, "the body of `forall`")) {
      bad = true;
      break;  // the same mistake would be reported once per element
    }
    n->args.push_back(std::move(body));
  }
  if (bad) return error(e.span);
  return n;
}

ir::ExprPtr ExprChecker::call(const ast::Expr& e, const Scope& s) {
  const ast::Expr* callee = e.args[0].get();
  std::vector<const ast::Expr*> argAst;
  for (size_t i = 1; i < e.args.size(); ++i) argAst.push_back(e.args[i].get());
  if (callee && callee->kind == ast::ExprKind::Member) return sceneResult(e, *callee, argAst, s);
  if (!callee || callee->kind != ast::ExprKind::Name) {
    diags_.error("E0220", callee ? callee->span : e.span, "only a named function can be called");
    return error(e.span);
  }
  const std::string& fn = callee->text;
  const FunctionSpec* spec = findFunction(fn);
  if (!spec) {
    if (findSignalFn(fn)) {
      diags_.error("E0220", callee->span,
                   fmt::format("`{}` reads a scene's signal: write it in a scene's `output` list, or as `SCENE.{}(…)`", fn, fn));
      return error(e.span);
    }
    std::string hint = closest(fn, functionNames());
    diags_.error("E0220", callee->span,
                 fmt::format("unknown function `{}`{}", fn, suggestion(hint)));
    return error(e.span);
  }
  std::vector<ir::ExprPtr> args;
  bool bad = false;
  for (const auto* a : argAst) {
    args.push_back(check(a, s));
    bad = bad || args.back()->type.isError();
  }
  if (bad) return error(e.span);
  if (auto made = argumentsByRule(*spec, args, e, s)) return made;
  Type t;
  if (!resultType(*spec, args, t)) return error(e.span);
  auto n = make(Op::Call, std::move(t), e.span, fn);
  n->fn = spec->id;
  n->args = std::move(args);
  return n;
}

ir::ExprPtr ExprChecker::sceneResult(const ast::Expr& e, const ast::Expr& calleeRef, const std::vector<const ast::Expr*>& argAst,
                                     const Scope& s) {
  const ast::Expr* callee = &calleeRef;
  auto obj = check(callee->args[0].get(), s);
  if (obj->type.isError()) return obj;
  if (obj->type.kind != Type::Scene && obj->type.kind != Type::Shaft) {
    diags_.error("E0220", callee->span, fmt::format("`{}` is not a function", ast::print(*callee)));
    return error(e.span);
  }
  if (obj->type.kind == Type::Shaft) return shaftAt(e, *callee, *obj, argAst, s);
  const std::string& fn = callee->text;
  const SignalFnSpec* fnSpec = findSignalFn(fn);
  if (!fnSpec) {
    diags_.error("E0220", callee->span,
                 fmt::format("`{}` is not a scene result function ({})", fn, signalFnList()));
    return error(e.span);
  }
  if (argAst.size() == 1 && argAst[0] && argAst[0]->kind == ast::ExprKind::Call) {
    diags_.error("E0232", e.span,
                 fmt::format("`{}.{}({})`: a mesh's result of a whole-gearbox scene is reported, but cannot yet be read in an "
                             "expression; run a scene on that stage to use its result in a rule, an objective or a column",
                             obj->name, fn, ast::print(*argAst[0])));
    return error(e.span);
  }
  bool ordered = fnSpec->order != OrderArg::None;
  if (argAst.empty() || argAst.size() > (ordered ? 2u : 1u) || !argAst[0] || argAst[0]->kind != ast::ExprKind::Name ||
      (fnSpec->order == OrderArg::Required && argAst.size() != 2)) {
    diags_.error(
        "E0221", e.span,
        fnSpec->order == OrderArg::Required
            ? fmt::format("`{}` takes a signal and a mesh order, as in `{}.{}(mesh_force, 1)`", fn, obj->name, fn)
        : ordered ? fmt::format("`{}` takes a signal and, if one order, its number, as in `{}.{}(mesh_force, 1)`", fn,
                                obj->name, fn)
                  : fmt::format("`{}` takes one signal, as in `{}.{}(acceleration)`", fn, obj->name, fn));
    return error(e.span);
  }
  const std::string& sig = argAst[0]->text;
  const auto* spec = findSignal(sig);
  if (!spec) {
    diags_.error("E0218", argAst[0]->span, fmt::format("scenes have no signal `{}`", sig));
    return error(e.span);
  }
  const ast::Stmt* scene = s.gearbox->findScene(obj->name);
  std::string key =
      fn + "(" + sig + (argAst.size() == 2 && argAst[1] ? ", " + ast::print(*argAst[1]) : std::string()) + ")";
  bool declared = false;
  for (const auto& st : scene->body)
    if (st.kind == ast::StmtKind::Output)
      for (const auto& o : st.exprs)
        if (o && ast::print(*o) == key) declared = true;
  if (!declared) {
    diags_.error("E0218", e.span,
                 fmt::format("scene `{}` does not output `{}`; add it to the scene's `output` list", obj->name, key));
    return error(e.span);
  }
  Type t = fnSpec->decibels ? Type::number(units::dims::none)
           : fnSpec->number ? Type::number(spec->dim)
                            : Type{Type::Signal, spec->dim, false, {}};
  return make(Op::SceneOutput, t, e.span, obj->name + "." + key);
}

// `worst(q)` over the tolerances; `quantile(q, p)` over their Monte Carlo samples.
ir::ExprPtr ExprChecker::scatterCall(const FunctionSpec& spec, std::vector<ir::ExprPtr>& args, const ast::Expr& e, const Scope& s) {
  const std::string fn = e.args[0]->text;
  const bool sampled = spec.args == ArgRule::Sampled;
  if (!s.hasTolerances || (sampled && !s.hasSamples)) {
    std::string why =
        !sampled ? fmt::format("`{}(q)` evaluates q over the gearbox's manufacturing scatter, but this gearbox has no `tolerances` block", fn)
        : s.hasTolerances
            ? fmt::format("`{}(q, p)` reads q over Monte Carlo samples; add `samples = N;` to the `tolerances` block", fn)
            : fmt::format("`{}(q, p)` reads q over Monte Carlo samples of the gearbox's `tolerances`, but this gearbox has no "
                          "`tolerances` block",
                          fn);
    diags_.error("E0237", e.span, why);
    return error(e.span);
  }
  if (sampled) {
    const ir::Expr& p = *args[1];
    if (!p.isConst() || !p.type.dim.dimensionless() || !(p.value.toDouble() > 0 && p.value.toDouble() < 1)) {
      diags_.error("E0306", p.span, fmt::format("`{}(q, p)` takes a constant probability p between 0 and 1, as in `{}(q, 0.95)`", fn, fn));
      return error(e.span);
    }
  }
  auto n = make(Op::Scatter, sampled ? Type::number(args[0]->type.dim) : args[0]->type, e.span, fn);
  n->fn = spec.id;
  n->name = scatteredText(e);
  n->args = std::move(args);
  return n;
}

ir::ExprPtr ExprChecker::argumentsByRule(const FunctionSpec& specRef, std::vector<ir::ExprPtr>& args, const ast::Expr& e, const Scope& s) {
  const FunctionSpec* spec = &specRef;
  const std::string fn = e.args[0]->text;
  auto arity = [&]() {
    size_t lo = spec->minArgs, hi = spec->maxArgs;
    if (args.size() >= lo && args.size() <= hi) return true;
    diags_.error("E0221", e.span,
                 lo == hi ? fmt::format("`{}` takes {} argument{}, got {}", fn, lo, lo == 1 ? "" : "s", args.size())
                          : fmt::format("`{}` takes at least {} argument{}, got {}", fn, lo, lo == 1 ? "" : "s", args.size()));
    return false;
  };
  auto numbers = [&]() {
    for (auto& a : args)
      if (!a->type.isNumber()) {
        diags_.error("E0306", a->span, fmt::format("`{}` takes numbers, but this is {}", fn, describe(a->type)));
        return false;
      }
    return true;
  };
  auto sameDim = [&]() {
    for (size_t i = 1; i < args.size(); ++i)
      if (args[i]->type.dim != args[0]->type.dim) {
        diags_.error("E0303", args[i]->span,
                     fmt::format("dimension mismatch: `{}` mixes {} and {}", fn, describe(args[0]->type), describe(args[i]->type)));
        return false;
      }
    return true;
  };
  auto plain = [&](bool angleToo) {
    const auto& d = args[0]->type.dim;
    if (d.dimensionless() || (angleToo && d == units::dims::angle)) return true;
    diags_.error("E0302", args[0]->span,
                 fmt::format("unit mismatch: `{}` needs {}, got {}", fn, angleToo ? "an angle" : "a plain number", describe(args[0]->type)));
    return false;
  };
  switch (spec->args) {
  case ArgRule::WholePlain:
    if (!arity() || !numbers()) return error(e.span);
    for (auto& a : args)
      if (!a->type.integer || !a->type.dim.dimensionless()) {
        diags_.error("E0306", a->span, fmt::format("`{}` takes whole numbers such as tooth counts, but this is {}", fn, describe(a->type)));
        return error(e.span);
      }
    return nullptr;
  case ArgRule::Baseline: {
    if (!arity() || !numbers()) return error(e.span);
    if (!s.hasBaseline) {
      diags_.error("E0227", e.span,
                   "`relative(x)` divides by x of the baseline gearbox, but this gearbox extends none");
      return error(e.span);
    }
    // A ratio of absolute temperatures is one of kelvins: 10 K cooler at 150 degC reads 0.98.
    if (args[0]->type.dim == units::dims::temperature && args[0]->op != Op::Sub) {
      diags_.error("E0302", args[0]->span,
                   "`relative()` of a temperature would be a ratio of kelvins; take it of a temperature difference, such as the rise "
                   "above the oil (`relative(hs.contact_temperature - 80 degC)`)");
      return error(e.span);
    }
    auto n = make(Op::Relative, Type::number({}), e.span);
    n->args = std::move(args);
    return n;
  }
  case ArgRule::Scatter:
  case ArgRule::Sampled:
    if (!arity() || !numbers()) return error(e.span);
    return scatterCall(*spec, args, e, s);
  case ArgRule::Reduction: {
    if (!arity()) return error(e.span);
    // `mean(q)` of one number in a gearbox with `tolerances`: its mean over the tolerance box.
    if (spec->id == Fn::Mean && args.size() == 1 && args[0]->type.isNumber() && s.hasTolerances) {
      auto n = make(Op::Scatter, Type::number(args[0]->type.dim), e.span, fn);
      n->fn = Fn::Mean;
      n->name = scatteredText(e);
      n->args = std::move(args);
      return n;
    }
    if (args.size() == 1 && args[0]->type.kind == Type::PerGear) {
      auto n = make(Op::Call, Type::number(args[0]->type.dim), e.span, fn);
      n->fn = spec->id;
      n->args = std::move(args);
      return n;
    }
    for (auto& a : args)
      if (a->type.kind == Type::PerGear) {
        diags_.error("E0306", a->span,
                     fmt::format("`{}` of a per-gear quantity stands alone, as in `{}(pitch_deviation)`", fn, fn));
        return error(e.span);
      }
    if (args.size() < 2 && spec->result == ResultRule::Extreme) {
      diags_.error("E0221", e.span, fmt::format("`{}` takes two or more numbers, or one per-gear quantity", fn));
      return error(e.span);
    }
    if (!numbers() || !sameDim()) return error(e.span);
    return nullptr;
  }
  case ArgRule::Any:
    if (!numbers() || !arity()) return error(e.span);
    return nullptr;
  case ArgRule::SameDim:
    if (!numbers() || !arity() || !sameDim()) return error(e.span);
    return nullptr;
  case ArgRule::AngleOrPlain:
  case ArgRule::Plain:
    if (!numbers() || !arity() || !plain(spec->args == ArgRule::AngleOrPlain)) return error(e.span);
    return nullptr;
  }
  return nullptr;
}

bool ExprChecker::resultType(const FunctionSpec& specRef, const std::vector<ir::ExprPtr>& args, Type& t) {
  const FunctionSpec* spec = &specRef;
  switch (spec->result) {
  case ResultRule::Plain: t = Type::number({}); break;
  case ResultRule::Whole: t = Type::number({}, true); break;
  case ResultRule::Angle: t = Type::number(units::dims::angle); break;
  case ResultRule::Condition: t = Type::boolean(); break;
  case ResultRule::Like: t = args[0]->type; break;
  case ResultRule::Dim: t = Type::number(args[0]->type.dim); break;
  case ResultRule::Root: {
    units::Dim d;
    if (!args[0]->type.dim.sqrt(d)) {
      diags_.error("E0303", args[0]->span, fmt::format("the square root of {} has no unit", describe(args[0]->type)));
      return false;
    }
    t = Type::number(d);
    break;
  }
  case ResultRule::Extreme:
    t = Type::number(args[0]->type.dim, std::all_of(args.begin(), args.end(), [](auto& a) { return a->type.integer; }));
    break;
  }
  return true;
}

} // namespace gbx::sema
