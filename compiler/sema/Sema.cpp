#include "sema/Sema.h"

#include "sema/Analyser.h"

// Declarations, constants, materials, presets and settings blocks; the entry point.

namespace gbx::sema {

ir::Program Analyser::run(const LoadedProgram& prog) {
  collect(prog);
  checkConsts();
  ir::Program out;
  for (const auto& [name, x] : globals_.constValues)
    if (x && !x->type.isError())
      out.consts.push_back({name, x->value, x->type.dim, x->op == ir::Op::Set});
  for (const auto& [name, decl] : globals_.materials) out.materials.push_back(material(*decl));
  for (const auto& [name, decl] : globals_.presets) checkPreset(*decl);
  // Gearboxes in declaration order of the main file, then of imports.
  for (const auto& f : prog.files)
    for (const auto& d : f.decls)
      if (d.kind == StmtKind::Gearbox && globals_.gearboxes[d.name] == &d) {
        std::vector<std::string> stack;
        const GearboxModel* m = build(d.name, stack);
        if (m) out.gearboxes.push_back(lowerGearbox(*m));
      }
  return out;
}

void Analyser::declare(std::map<std::string, const Stmt*>& table, const Stmt& d) {
  for (auto* t : {&globals_.consts, &globals_.materials, &globals_.presets, &globals_.gearboxes}) {
    auto it = t->find(d.name);
    if (it == t->end()) continue;
    auto& diag = diags_.error("E0202", nameOr(d), fmt::format("duplicate declaration: `{}` is already declared", d.name));
    diag.notes.push_back({nameOr(*it->second), "first declared here"});
    return;
  }
  table[d.name] = &d;
}

void Analyser::collect(const LoadedProgram& prog) {
  for (const auto& f : prog.files)
    for (const auto& d : f.decls) {
      switch (d.kind) {
      case StmtKind::Const: declare(globals_.consts, d); break;
      case StmtKind::Named:
        if (isKey(d.word, Q::Material)) declare(globals_.materials, d);
        break;
      case StmtKind::Preset: declare(globals_.presets, d); break;
      case StmtKind::Gearbox: declare(globals_.gearboxes, d); break;
      default: break;
      }
    }
}

void Analyser::checkConsts() {
  std::set<std::string> busy;
  std::function<void(const std::string&)> eval = [&](const std::string& n) {
    if (globals_.constValues.count(n) || !globals_.consts.count(n)) return;
    const Stmt* d = globals_.consts[n];
    if (busy.count(n)) {
      diags_.error("E0228", nameOr(*d), fmt::format("const `{}` is defined in terms of itself", n));
      return;
    }
    busy.insert(n);
    // Evaluate referenced consts first so the checker sees their values.
    std::function<void(const ast::Expr*)> deps = [&](const ast::Expr* e) {
      if (!e) return;
      if (e->kind == ast::ExprKind::Name && globals_.consts.count(e->text)) eval(e->text);
      for (const auto& a : e->args) deps(a.get());
    };
    deps(d->value.get());
    busy.erase(n);
    if (globals_.constValues.count(n)) return;  // set during a cycle report
    Scope s;
    s.context = Scope::ConstExpr;
    auto v = checker_.check(d->value.get(), s);
    if (v->type.isError()) return;
    if (v->op != Op::Const && v->op != Op::Set) {
      diags_.error("E0410", d->value->span, fmt::format("const `{}` must be a constant, not an expression over quantities", n));
      return;
    }
    if (v->op == Op::Set)
      for (const auto& m : v->args)
        if (!m->isConst()) {
          diags_.error("E0410", m->span, "a const set must hold constants");
          return;
        }
    globals_.constValues[n] = std::move(v);
  };
  for (const auto& [n, _] : globals_.consts) eval(n);
}

// Flattens assignments of a settings block (nested blocks become `a.b` paths).
void Analyser::flatten(const std::vector<Stmt>& body, const std::string& prefix, const std::string& owner, std::vector<std::pair<std::string, Binding>>& out, const std::set<std::string>& blocks, const std::set<std::string>& skip) {
  for (const auto& st : body) {
    if (st.kind == StmtKind::Block && skip.count(prefix + st.name)) continue;
    if (st.kind == StmtKind::Assign || (st.kind == StmtKind::Domain && shaftDomains_)) {
      std::string p = prefix + st.path.str();
      bool dup = false;
      for (auto& [q, b] : out)
        if (q == p) {
          auto& d = diags_.error("E0202", st.path.span, fmt::format("duplicate declaration: `{}` is already set in {}", p, owner));
          d.notes.push_back({b.stmt->path.span, "first set here"});
          dup = true;
        }
      if (!dup) out.emplace_back(p, Binding{&st, owner});
    } else if (st.kind == StmtKind::Block && blocks.count(prefix + st.name)) {
      flatten(st.body, prefix + st.name + ".", owner, out, blocks);
    } else if (st.kind == StmtKind::Block) {
      diags_.error("E0224", nameOr(st), fmt::format("{} has no block `{}`", owner, st.name));
    } else {
      notAllowed(st, owner);
    }
  }
}

void Analyser::notAllowed(const Stmt& st, const std::string& owner) {
  std::string what = st.kind == StmtKind::Flag     ? fmt::format("`{};`", st.name)
                     : st.kind == StmtKind::Domain ? fmt::format("a domain `{} in …`", st.path.str())
                     : st.kind == StmtKind::Block  ? fmt::format("a `{} {{ … }}` block", st.name)
                                                   : fmt::format("`{}`", ast::stmtKindName(st.kind));
  diags_.error("E0110", st.span,
               fmt::format("{} is not allowed in {}{}", what, owner,
                           st.kind == StmtKind::Block && st.name == kRatingBlock ? " (a `rating` belongs inside the stage it rates)" : ""));
}

// `x in lo..hi` or `x in {…}`: within a shaft, a number searched like an attribute; elsewhere
// refused.
ir::Setting Analyser::domainSetting(ir::Setting out, const Stmt& st, const AttrSpec& spec, const Scope& scope,
                                    const std::string& owner) {
  if (!shaftDomains_ || spec.value != ValueKind::Number) {
    diags_.error("E0110", st.span, fmt::format("`{}` of {} takes one value (`=`), not a domain", out.name, owner));
    return out;
  }
  Domain d = domain(spec, out.name, st, scope);
  out.lo = std::move(d.lo);
  out.hi = std::move(d.hi);
  out.members = std::move(d.members);
  out.memberTexts = std::move(d.memberTexts);
  return out;
}

// `name = {a, b, …}`: constant numbers of the row's dimension, kept in order.
ir::Setting Analyser::listSetting(ir::Setting out, const ast::Expr* v, const AttrSpec& spec, const Scope& scope) {
  if (!v || v->kind != ast::ExprKind::Set) {
    diags_.error("E0406", v ? v->span : out.span,
                 fmt::format("`{}` takes a list of {} in braces, as `{{0 {}, 2 {}, -1 {}}}`", out.name,
                             spec.dim.describe(), spec.unitHint, spec.unitHint, spec.unitHint));
    return out;
  }
  std::vector<units::Number> members;
  for (const auto& m : v->args) {
    auto x = checker_.check(m.get(), scope);
    if (x->type.isError()) return out;
    if (!x->isConst() || !x->type.isNumber()) {
      diags_.error("E0306", x->span, fmt::format("each member of `{}` is a constant number", out.name));
      return out;
    }
    if (x->type.dim != spec.dim) {
      diags_.error(
          "E0302", x->span,
          fmt::format("unit mismatch: `{}` lists {}, got {}", out.name, spec.dim.describe(), describe(x->type)));
      return out;
    }
    members.push_back(x->value);
  }
  out.members = std::move(members);
  return out;
}

ir::Setting Analyser::switchSetting(ir::Setting out, bool on) {
  out.symbol = on ? "true" : "false";
  out.choice = on ? 1 : 0;
  return out;
}

// Checks one value against its spec; returns the setting (value unset on error).
ir::Setting Analyser::setting(const std::string& name, const Binding& b, const AttrSpec& spec, const Scope& scope, const std::string& owner) {
  ir::Setting out;
  out.name = name;
  out.key = spec.key != Q::None ? spec.key : cat::keyOf(lastPart(name)).value_or(Q::None);
  out.dim = spec.dim;
  out.integer = spec.integer;
  const Stmt& st = *b.stmt;
  out.span = st.span;
  if (st.when) diags_.error("E0408", st.when->span, "`x when condition` is only allowed in a `modify` block");
  if (st.kind == StmtKind::Domain) return domainSetting(std::move(out), st, spec, scope, owner);
  const ast::Expr* v = st.value.get();
  if (spec.value == ValueKind::List) return listSetting(std::move(out), v, spec, scope);
  // A switch (`corner_contact = true`): its row's words are false and true.
  if (spec.value == ValueKind::Symbol && spec.symbols == std::vector<std::string>{"false", "true"} && v && v->kind == ast::ExprKind::Bool)
    return switchSetting(std::move(out), v->boolValue);
  if (spec.value == ValueKind::Symbol || spec.value == ValueKind::Stage || spec.value == ValueKind::Material) {
    if (!v || v->kind != ast::ExprKind::Name) {
      diags_.error("E0406", v ? v->span : st.span,
                   fmt::format("`{}` takes a name{}", name,
                               spec.symbols.empty() ? "" : fmt::format(" ({})", fmt::join(spec.symbols, ", "))));
      return out;
    }
    if (spec.value == ValueKind::Symbol &&
        std::find(spec.symbols.begin(), spec.symbols.end(), v->text) == spec.symbols.end()) {
      diags_.error("E0406", v->span,
                   fmt::format("`{}` is not a valid {}; use one of {}", v->text, name, fmt::join(spec.symbols, ", ")));
      return out;
    }
    if (spec.value == ValueKind::Stage && (!scope.gearbox || !scope.gearbox->findStage(v->text))) {
      diags_.error("E0232", v->span, fmt::format("`{}` is not a stage of this gearbox", v->text));
      return out;
    }
    if (spec.value == ValueKind::Material && !globals_.materials.count(v->text)) {
      std::vector<std::string> names;
      for (const auto& [m, _] : globals_.materials) names.push_back(m);
      std::string hint = closest(v->text, names);
      diags_.error("E0216", v->span,
                   fmt::format("unknown material `{}`{}{}", v->text,
                               suggestion(hint),
                               names.empty() ? " (did you forget `import materials;`?)" : ""));
      return out;
    }
    out.symbol = v->text;
    if (auto w = std::find(spec.symbols.begin(), spec.symbols.end(), v->text); w != spec.symbols.end())
      out.choice = static_cast<int>(w - spec.symbols.begin());
    return out;
  }
  // A number that may instead be a scene (`dynamic_factor = scene vib`) or one of its row's
  // words (`face_load_factor = contact_analysis`).
  if (st.sceneRef) {
    if (!spec.sceneRef) {
      diags_.error("E0406", v ? v->span : st.span, fmt::format("`{}` takes {}, not a scene", name, spec.dim.describe()));
      return out;
    }
    if (!scope.gearbox || !scope.gearbox->findScene(v->text)) {
      diags_.error("E0217", v->span, fmt::format("unknown scene `{}`: `{}` names a scene of this gearbox", v->text, name));
      return out;
    }
    out.symbol = v->text;
    out.sceneRef = true;
    return out;
  }
  if (!spec.symbols.empty() && v && v->kind == ast::ExprKind::Name)
    if (auto w = std::find(spec.symbols.begin(), spec.symbols.end(), v->text); w != spec.symbols.end()) {
      out.symbol = v->text;
      out.choice = static_cast<int>(w - spec.symbols.begin());
      return out;
    }
  Scope s = scope;
  s.meshPeriodsAllowed = spec.meshPeriods;
  auto x = checker_.check(v, s);
  if (x->type.isError()) return out;
  if (!x->type.isNumber()) {
    diags_.error("E0306", x->span, fmt::format("`{}` needs {}, but this is {}", name, spec.dim.describe(), describe(x->type)));
    return out;
  }
  if (x->type.dim != spec.dim && !(spec.altDim && x->type.dim == *spec.altDim)) {
    std::string written = v && v->kind == ast::ExprKind::Number && v->unit ? v->unit->text : "";
    // A bare number where a quantity with a unit belongs: show it with the usual unit.
    std::string fix;
    auto unit = units::displayUnitFor(spec.dim);
    if (v && v->kind == ast::ExprKind::Number && !v->unit && x->type.dim.dimensionless() && !unit.name.empty())
      fix = fmt::format("; write it with a unit, as `{} {}`", v->text, spec.unitHint.empty() ? unit.name : spec.unitHint);
    // A number in a unit of another dimension (`life = 20000 kW`): the unit it reads in.
    else if (v && v->kind == ast::ExprKind::Number && v->unit && !unit.name.empty())
      fix = fmt::format("; write it in {} (or any unit of {})", spec.unitHint.empty() ? unit.name : spec.unitHint,
                        spec.dim.describe());
    // A frequency where a speed belongs: the same number of turns per second, in rpm.
    if (spec.dim == units::dims::angularSpeed && x->type.dim == units::dims::frequency && x->isConst())
      fix = fmt::format("; a speed of {} turns a second is `{} rpm`", units::formatDouble(x->value.toDouble()),
                        units::formatDouble(x->value.toDouble() * 60));
    diags_.error("E0302", x->span,
                 fmt::format("unit mismatch: `{}` needs {}{}, got {}{}", name, spec.dim.describe(),
                             spec.altDim ? " or " + spec.altDim->describe() : "", describe(x->type, written), fix));
    return out;
  }
  out.meshPeriods = x->marker == ir::Marker::MeshPeriods;
  if (x->isConst()) {
    if (spec.integer && !(x->value.isRational() && x->value.rational().isInteger())) {
      diags_.error("E0403", x->span, fmt::format("`{}` must be a whole number, got {}", name, x->value.str()));
      return out;
    }
    if (spec.positive && x->value.sign() <= 0) {
      diags_.error(isKey(lastPart(name), Q::Z) ? "E0402" : "E0405", x->span,
                   fmt::format("`{}` must be positive, got {}", name, asWritten(v, *x)));
      return out;
    }
    if (beyondBudget(spec, name, *x)) return out;
    if (outsideLimits(spec, name, *x, v)) return out;
    out.value = x->value;
    // The alternative dimension is kept (a fluctuation's frequency in Hz is 2 pi rad/s
    // a hertz; the runtime converts by the setting's own dimension).
    if (spec.altDim && x->type.dim == *spec.altDim) out.dim = x->type.dim;
  }
  out.expr = std::move(x);
  return out;
}

std::vector<ir::Setting> Analyser::settings(const std::vector<std::pair<std::string, Binding>>& items, const std::vector<AttrSpec>& specs, const Scope& scope, const std::string& owner, Span ownerSpan, const char* missingCode) {
  std::vector<ir::Setting> out;
  for (const auto& [name, b] : items) {
    const AttrSpec* spec = nullptr;
    for (const auto& s : specs)
      if (s.name == name) spec = &s;
    if (!spec) {
      std::vector<std::string> names;
      for (const auto& s : specs) names.push_back(s.name);
      std::string hint = closest(name, names);
      diags_.error("E0214", b.stmt->path.span,
                   fmt::format("`{}` is not a setting of {}{}", name, owner,
                               hint.empty() ? fmt::format(" (it takes {})", fmt::join(names, ", "))
                                            : fmt::format("; did you mean `{}`?", hint)));
      continue;
    }
    out.push_back(setting(name, b, *spec, scope, owner));
  }
  for (const auto& s : specs)
    if (s.required && std::none_of(items.begin(), items.end(), [&](const auto& i) { return i.first == s.name; }))
      diags_.error(missingCode, ownerSpan, fmt::format("{} needs `{}` ({})", owner, s.name, s.meaning));
  for (const auto& s : specs)
    if (s.dflt && std::none_of(items.begin(), items.end(), [&](const auto& i) { return i.first == s.name; })) {
      ir::Setting d;
      d.name = s.name;
      d.key = s.key != Q::None ? s.key : cat::keyOf(lastPart(s.name)).value_or(Q::None);
      d.dim = s.dim;
      d.integer = s.integer;
      d.value = s.dflt;
      out.push_back(std::move(d));
    }
  return out;
}

ir::Material Analyser::material(const Stmt& d) {
  ir::Material m;
  m.name = d.name;
  m.span = d.span;
  std::vector<std::pair<std::string, Binding>> items;
  std::string owner = fmt::format("material `{}`", d.name);
  flatten(d.body, "", owner, items, {});
  m.properties = settings(items, materialProperties(), Scope{}, owner, nameOr(d), "E0225");
  return m;
}

void Analyser::checkPreset(const Stmt& d) {
  const KindSpec* k = findKind(d.word);
  if (!k) {
    unknownKind(d.word, d.wordSpan);
    return;
  }
  for (const auto& st : d.body) {
    if (st.kind == StmtKind::Assign || st.kind == StmtKind::Domain || st.kind == StmtKind::Require) continue;
    notAllowed(st, fmt::format("preset `{}`", d.name));
  }
}

void Analyser::unknownKind(const std::string& word, Span span) {
  std::vector<std::string> names;
  for (const auto* k : stageKinds())
    names.push_back(k->name);
  std::string hint = closest(word, names);
  diags_.error("E0210", span,
               fmt::format("unknown stage kind `{}`{}", word,
                           hint.empty() ? fmt::format(" (kinds: {})", fmt::join(names, ", "))
                                        : fmt::format("; did you mean `{}`?", hint)));
}

ir::Program analyse(const LoadedProgram& program, diag::DiagnosticEngine& diags) {
  Analyser a(diags);
  return a.run(program);
}

} // namespace gbx::sema
