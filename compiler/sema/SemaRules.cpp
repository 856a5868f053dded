#include "sema/Analyser.h"

// Rules, `worst` and its direction, tolerances and objectives.

namespace gbx::sema {

// Monte Carlo samples draw every tolerance at once, so the corners' limit of 6 does not
// hold; this one keeps a sample's deviations a short list.
constexpr size_t kMostSampledTolerances = 64;

ir::Rule Analyser::rule(const Stmt& st, const Scope& s, const std::string& scopeName) {
  ir::Rule r;
  r.expr = checker_.check(st.value.get(), s);
  if (!r.expr->type.isError() && r.expr->type.kind != Type::Bool) {
    diags_.error("E0305", r.expr->span,
                 fmt::format("a `require` needs a condition (a comparison, `coprime(…)`, `and`/`or`), but this is {}",
                             describe(r.expr->type)));
  }
  if (r.expr) worstSense(*r.expr, 0, true);
  r.text = st.value ? ast::print(*st.value) : "";
  r.scope = scopeName;
  r.span = st.span;
  return r;
}

// Whether an expression reads `worst` or `mean` over the tolerances, itself or through lets.
bool Analyser::readsWorst(const ir::Expr& e, int depth) const {
  if (e.op == Op::Scatter) return true;
  if (depth > 64) return false;
  if (e.op == Op::Let && lets_)
    if (auto it = lets_->find(e.name); it != lets_->end() && it->second && readsWorst(*it->second, depth + 1)) return true;
  for (const auto& x : e.args)
    if (x && readsWorst(*x, depth + 1)) return true;
  return false;
}

// Which end of the tolerance box is the worst for each `worst(q)`: where q is minimised or
// bounded from above its largest value, where maximised or bounded from below its smallest;
// a minus sign, a divisor or a `not` turns it round. `sense` 0: not known here (a report
// column, where q's own better direction decides). In a rule, a two-sided bound on a
// `worst` (`in a..b`, `== c +- t`) holds when both ends of q hold it, so it is checked at
// both: the comparison is kept twice, once at each end; and a `let` that reads `worst` is
// read in place, so that it takes the rule's direction.
void Analyser::worstSense(ir::Expr& e, int sense, bool condition, bool negated) {
  using ir::Op;
  if ((condition || sense != 0) && e.op == Op::Let && lets_)
    if (auto it = lets_->find(e.name); it != lets_->end() && it->second && readsWorst(*it->second)) {
      // The let takes this direction: its column then reads the same end (unless another
      // use gives it the other one).
      auto [dir, added] = letSense_.emplace(e.name, sense);
      if (!added && dir->second != sense) dir->second = 0;
      ir::ExprPtr inlined = it->second->clone();
      inlined->span = e.span;
      e = std::move(*inlined);
    }
  if (e.op == Op::Scatter) e.sense = static_cast<std::int8_t>(sense);
  auto arg = [&](size_t i, int sg) {
    if (i < e.args.size() && e.args[i]) worstSense(*e.args[i], sg, condition, negated);
  };
  int up = negated ? -1 : 1;  // `not (q < c)` bounds q from below
  switch (e.op) {
  case Op::Le:
  case Op::Lt: arg(0, condition ? up : 0); arg(1, condition ? -up : 0); return;
  case Op::Ge:
  case Op::Gt: arg(0, condition ? -up : 0); arg(1, condition ? up : 0); return;
  case Op::Not:
    if (!e.args.empty() && e.args[0]) worstSense(*e.args[0], 0, condition, !negated);
    return;
  case Op::Within:
  case Op::Eq:
  case Op::Ne:
    if (condition && !e.args.empty() && e.args[0] && ir::uses(e.args[0].get(), {Op::Scatter}) &&
        (e.op == Op::Within || (e.args.size() == 2 && e.args[1] && e.args[1]->op == Op::Tol))) {
      // q within bounds at both of its ends: (q at its largest) and (q at its smallest).
      auto high = std::make_unique<ir::Expr>();
      high->op = e.op;
      high->type = e.type;
      high->span = e.span;
      high->args = std::move(e.args);
      auto low = high->clone();
      worstSense(*high->args[0], 1, condition, negated);
      worstSense(*low->args[0], -1, condition, negated);
      for (size_t i = 1; i < high->args.size(); ++i) {
        worstSense(*high->args[i], 0, condition, negated);
        worstSense(*low->args[i], 0, condition, negated);
      }
      // Not every corner outside the bounds: both ends outside (Or under a `not`).
      e.op = negated ? Op::Or : Op::And;
      e.args.clear();
      e.args.push_back(std::move(high));
      e.args.push_back(std::move(low));
      return;
    }
    for (size_t i = 0; i < e.args.size(); ++i) arg(i, 0);
    return;
  case Op::And:
  case Op::Or:
  case Op::Forall:
    for (size_t i = 0; i < e.args.size(); ++i) arg(i, 0);
    return;
  case Op::Neg: arg(0, -sense); return;
  case Op::Sub: arg(0, sense); arg(1, -sense); return;
  case Op::Div: arg(0, sense); arg(1, -sense); return;
  case Op::Mul:
    // A constant factor's sign turns the sense round (`-2 * worst(q)`).
    for (size_t i = 0; i < e.args.size(); ++i) {
      int sg = sense;
      for (size_t j = 0; j < e.args.size(); ++j)
        if (j != i && e.args[j] && e.args[j]->isConst() && e.args[j]->type.isNumber() && e.args[j]->value.sign() < 0) sg = -sg;
      arg(i, sg);
    }
    return;
  case Op::Add:
  case Op::Relative:
  case Op::Scatter:
    for (size_t i = 0; i < e.args.size(); ++i) arg(i, sense);
    return;
  default:
    for (size_t i = 0; i < e.args.size(); ++i) arg(i, 0);
  }
}

// `tolerances { stage.attribute +- amount; }`: a number attribute of a stage, a constant
// non-negative amount of its unit.
std::vector<ir::Tolerance> Analyser::tolerances(const GearboxModel& m, const Scope& gs) {
  std::vector<ir::Tolerance> out;
  for (const Stmt* t : m.tolerances) {
    ir::Tolerance tol;
    tol.target = t->path.str();
    tol.span = t->span;
    const auto& parts = t->path.parts;
    const StageModel* st = parts.size() >= 2 ? m.findStage(parts[0]) : nullptr;
    const AttrSpec* a = st && st->kind ? findAttr(*st->kind, tol.target.substr(parts[0].size() + 1)) : nullptr;
    if (!a || a->role == AttrRole::Derived || a->value != ValueKind::Number || a->integer) {
      diags_.error("E0237", t->path.span,
                   fmt::format("`{}` cannot scatter: a tolerance belongs to a continuous attribute of a stage, as in "
                               "`{}.face_width +- 1 mm`",
                               tol.target, st ? st->name : (m.stages.empty() ? std::string("main") : m.stages[0].name)));
      continue;
    }
    tol.dim = a->dim;
    if (checker_.refuseCelsiusDifference(t->value.get(), "a tolerance")) continue;
    auto x = checker_.check(t->value.get(), gs);
    if (x->type.isError()) continue;
    if (!x->isConst() || !x->type.isNumber()) {
      diags_.error("E0410", x->span, "a tolerance must be a constant");
      continue;
    }
    if (x->type.dim != a->dim) {
      // A bare number for a quantity with a unit: show it with the attribute's usual unit.
      const ast::Expr* v = t->value.get();
      auto unit = units::displayUnitFor(a->dim);
      std::string fix = v && v->kind == ast::ExprKind::Number && !v->unit && x->type.dim.dimensionless() && !unit.name.empty()
                            ? fmt::format("; write it with a unit, as `{} {}`", v->text, unit.name)
                            : "";
      diags_.error("E0302", x->span,
                   fmt::format("unit mismatch: `{}` is {}, its tolerance is {}{}", tol.target, describe(Type::number(a->dim)),
                               describe(x->type), fix));
      continue;
    }
    if (x->value.sign() < 0) {
      diags_.error("E0409", x->span, "a tolerance cannot be negative");
      continue;
    }
    tol.amount = x->value.toDouble();
    out.push_back(std::move(tol));
  }
  if (gs.hasSamples) {
    if (out.size() > kMostSampledTolerances)
      diags_.error("E0237", m.tolerances[kMostSampledTolerances]->span,
                   fmt::format("gearbox `{}` lists {} tolerances; Monte Carlo samples draw at most {}", m.name, out.size(),
                               kMostSampledTolerances));
    return out;
  }
  if (out.size() > 6 && !m.tolerances.empty())
    diags_.error("E0237", m.tolerances[6]->span,
                 fmt::format("gearbox `{}` lists {} tolerances; `worst` and `mean` visit every corner of their box, so at most 6 "
                             "(64 corners) are taken; with `samples = N;` in the block they draw samples instead, for up to {} "
                             "tolerances",
                             m.name, out.size(), kMostSampledTolerances));
  return out;
}

// `samples = N; distribution = normal; seed = 1;` beside the tolerance lines: Monte Carlo
// samples instead of the box's corners (docs/optimisation.md).
Analyser::ToleranceSettings Analyser::toleranceSettings(const GearboxModel& m, const Scope& gs) {
  ToleranceSettings result;
  if (m.toleranceSettings.empty()) return result;
  const std::string owner = "the `tolerances` block";
  std::vector<std::pair<std::string, Binding>> items;
  for (const Stmt* t : m.toleranceSettings) flattenOne(*t, items, owner);
  result.misspelt = std::any_of(items.begin(), items.end(), [](const auto& i) {
    return std::none_of(cat::toleranceSettings().begin(), cat::toleranceSettings().end(), [&](const auto& spec) { return spec.name == i.first; });
  });
  result.settings = settings(items, cat::toleranceSettings(), gs, owner, m.toleranceSettings.front()->span, "E0237");
  const auto& out = result.settings;
  if (result.misspelt) return result;
  bool shaped = std::any_of(items.begin(), items.end(), [](const auto& i) {
    auto k = cat::keyOf(i.first);
    return k == Q::Distribution || k == Q::Seed;
  });
  if (shaped && !ir::findSetting(out, Q::Samples))
    diags_.error("E0237", m.toleranceSettings.front()->span,
                 "`distribution` and `seed` shape Monte Carlo samples; say how many with `samples = N;` (without it, "
                 "`worst` and `mean` visit the box's corners)");
  else if (ir::findSetting(out, Q::Samples) && m.tolerances.empty())
    diags_.error("E0237", m.toleranceSettings.front()->span,
                 "Monte Carlo samples scatter the tolerances, but this block lists none; add lines such as "
                 "`main.face_width +- 1 mm;`");
  return result;
}

// Attributes given by expressions that need themselves, through one another
// (`face_width = face_width + 1 mm`, or `a = b` and `b = a`): no value can come of them.
// One through a computed quantity (`face_width = 0.1 * mass`) is the runtime's to find.
void Analyser::selfDefined(const ir::Gearbox& g) {
  std::map<std::string, const ir::Attribute*> given;
  for (const auto& st : g.stages)
    for (const auto& a : st.attributes)
      if (a.role == ir::Attribute::Fixed && a.value && !a.value->isConst()) given[st.name + "." + a.name] = &a;
  std::map<std::string, int> state;  // 1 on the path being followed, 2 done
  std::set<std::string> reported;
  std::function<void(const std::string&)> visit = [&](const std::string& name) {
    state[name] = 1;
    walk(*given[name]->value, [&](const ir::Expr& e) {
      if (e.op != Op::Quantity || !given.count(e.name)) return;
      if (state[e.name] == 1) {
        if (reported.insert(e.name).second)
          diags_.error("E0228", given[e.name]->span, fmt::format("`{}` is defined in terms of itself", e.name));
      } else if (state[e.name] == 0) {
        visit(e.name);
      }
    });
    state[name] = 2;
  };
  for (const auto& [name, a] : given)
    if (state[name] == 0) visit(name);
}

ir::Objective Analyser::objective(const Stmt& st, const Scope& gs) {
  ir::Objective o;
  o.minimize = st.kind == StmtKind::Minimize;
  o.expr = checker_.check(st.value.get(), gs);
  worstSense(*o.expr, o.minimize ? 1 : -1);
  if (!o.expr->type.isError() && !o.expr->type.isNumber())
    diags_.error("E0306", o.expr->span,
                 fmt::format("an objective must be a number to {}, but this is {}", o.minimize ? "minimize" : "maximize",
                             describe(o.expr->type)));
  o.text = st.value ? ast::print(*st.value) : "";
  o.span = st.span;
  return o;
}

} // namespace gbx::sema
