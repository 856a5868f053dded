#include "sema/Sema.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <fmt/format.h>

#include "catalogue/Budgets.h"
#include "sema/Catalogue.h"
#include "sema/ExprChecker.h"
#include "sema/Model.h"
#include "units/Unit.h"

namespace gbx::sema {

using ast::Stmt;
using ast::StmtKind;
using ir::Op;
using ir::Type;
using source::Span;
using units::Number;

namespace {

constexpr std::string_view kRatingBlock = "rating";

Span nameOr(const Stmt& s) { return s.nameSpan.valid() ? s.nameSpan : s.span; }

void walk(const ir::Expr& e, const std::function<void(const ir::Expr&)>& f) {
  f(e);
  for (const auto& a : e.args)
    if (a) walk(*a, f);
}

std::string lastPart(const std::string& p) {
  auto d = p.rfind('.');
  return d == std::string::npos ? p : p.substr(d + 1);
}

// Whether a written name is the catalogue's name of `key` (names are compared through the
// catalogue, never as literals).
bool isKey(std::string_view name, Q key) { return keyOf(name) == key; }

// Whether a scene output reads `signal`.
bool isSignal(const ir::SceneOutput& o, cat::Signal signal) {
  const auto* s = cat::findSignal(o.signal);
  return s && s->id == signal;
}

bool needsOperating(const std::string& path) {
  auto key = keyOf(lastPart(path));
  return key && dependsOnOperatingPoint(*key);
}

class Analyser {
public:
  Analyser(diag::DiagnosticEngine& d) : diags_(d), checker_(globals_, d) {}

  ir::Program run(const LoadedProgram& prog) {
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

private:
  // ---- declarations ------------------------------------------------------------------

  void declare(std::map<std::string, const Stmt*>& table, const Stmt& d) {
    for (auto* t : {&globals_.consts, &globals_.materials, &globals_.presets, &globals_.gearboxes}) {
      auto it = t->find(d.name);
      if (it == t->end()) continue;
      auto& diag = diags_.error("E0202", nameOr(d), fmt::format("duplicate declaration: `{}` is already declared", d.name));
      diag.notes.push_back({nameOr(*it->second), "first declared here"});
      return;
    }
    table[d.name] = &d;
  }

  void collect(const LoadedProgram& prog) {
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

  void checkConsts() {
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
  void flatten(const std::vector<Stmt>& body, const std::string& prefix, const std::string& owner,
               std::vector<std::pair<std::string, Binding>>& out, const std::set<std::string>& blocks) {
    for (const auto& st : body) {
      if (st.kind == StmtKind::Assign) {
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

  void notAllowed(const Stmt& st, const std::string& owner) {
    std::string what = st.kind == StmtKind::Flag     ? fmt::format("`{};`", st.name)
                       : st.kind == StmtKind::Domain ? fmt::format("a domain `{} in …`", st.path.str())
                       : st.kind == StmtKind::Block  ? fmt::format("a `{} {{ … }}` block", st.name)
                                                     : fmt::format("`{}`", ast::stmtKindName(st.kind));
    diags_.error("E0110", st.span,
                 fmt::format("{} is not allowed in {}{}", what, owner,
                             st.kind == StmtKind::Block && st.name == kRatingBlock ? " (a `rating` belongs inside the stage it rates)" : ""));
  }

  // Checks one value against its spec; returns the setting (value unset on error).
  ir::Setting setting(const std::string& name, const Binding& b, const AttrSpec& spec, const Scope& scope,
                      const std::string& owner) {
    ir::Setting out;
    out.name = name;
    out.key = spec.key != Q::None ? spec.key : cat::keyOf(lastPart(name)).value_or(Q::None);
    out.dim = spec.dim;
    out.integer = spec.integer;
    const Stmt& st = *b.stmt;
    out.span = st.span;
    if (st.when) diags_.error("E0408", st.when->span, "`x when condition` is only allowed in a `modify` block");
    if (st.kind == StmtKind::Domain) {
      diags_.error("E0110", st.span, fmt::format("`{}` of {} takes one value (`=`), not a domain", name, owner));
      return out;
    }
    const ast::Expr* v = st.value.get();
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

  std::vector<ir::Setting> settings(const std::vector<std::pair<std::string, Binding>>& items,
                                    const std::vector<AttrSpec>& specs, const Scope& scope, const std::string& owner,
                                    Span ownerSpan, const char* missingCode) {
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

  ir::Material material(const Stmt& d) {
    ir::Material m;
    m.name = d.name;
    m.span = d.span;
    std::vector<std::pair<std::string, Binding>> items;
    std::string owner = fmt::format("material `{}`", d.name);
    flatten(d.body, "", owner, items, {});
    m.properties = settings(items, materialProperties(), Scope{}, owner, nameOr(d), "E0225");
    return m;
  }

  void checkPreset(const Stmt& d) {
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

  void unknownKind(const std::string& word, Span span) {
    std::vector<std::string> names;
    for (const auto& k : stageKinds()) names.push_back(k.name);
    std::string hint = closest(word, names);
    diags_.error("E0210", span,
                 fmt::format("unknown stage kind `{}`{}", word,
                             hint.empty() ? fmt::format(" (kinds: {})", fmt::join(names, ", "))
                                          : fmt::format("; did you mean `{}`?", hint)));
  }

  // ---- gearbox models: extends, presets, like ------------------------------------------

  StageModel makeStage(const Stmt& st) {
    StageModel m;
    m.name = st.name;
    m.decl = &st;
    m.kind = findKind(st.word);
    if (!m.kind) unknownKind(st.word, st.wordSpan);
    for (size_t i = 0; i < st.with.size(); ++i) {
      const std::string& p = st.with[i];
      auto it = globals_.presets.find(p);
      if (it == globals_.presets.end()) {
        std::vector<std::string> names;
        for (const auto& [n, _] : globals_.presets) names.push_back(n);
        std::string hint = closest(p, names);
        diags_.error("E0208", st.withSpans[i],
                     fmt::format("unknown preset `{}`{}", p,
                                 hint.empty() ? (names.empty() ? fmt::format(" (did you forget `import {};`?)", p) : "")
                                              : fmt::format("; did you mean `{}`?", hint)));
        continue;
      }
      const Stmt& pre = *it->second;
      if (m.kind && pre.word != m.kind->name) {
        diags_.error("E0209", st.withSpans[i],
                     fmt::format("preset `{}` is for {} stages, but `{}` is a {} stage", p, pre.word, st.name, m.kind->name));
        continue;
      }
      m.presets.push_back(p);
      for (const auto& b : pre.body) {
        if (b.kind == StmtKind::Assign || b.kind == StmtKind::Domain) m.setAttr(b.path.str(), {&b, "preset " + p});
        else if (b.kind == StmtKind::Require) m.rules.push_back({&b, st.name});
      }
    }
    std::map<std::string, const Stmt*> seen;
    for (const auto& b : st.body) {
      switch (b.kind) {
      case StmtKind::Assign:
      case StmtKind::Domain: {
        std::string p = b.path.str();
        if (auto it = seen.find(p); it != seen.end()) {
          auto& d = diags_.error("E0202", b.path.span, fmt::format("duplicate declaration: `{}` is already given in stage `{}`", p, st.name));
          d.notes.push_back({it->second->path.span, "first given here"});
          break;
        }
        seen[p] = &b;
        m.setAttr(p, {&b, "stage"});
        break;
      }
      case StmtKind::Require: m.rules.push_back({&b, st.name}); break;
      case StmtKind::Block:
        if (b.name == kRatingBlock) ratingBlock(m, b, seen);
        else diags_.error("E0224", nameOr(b), fmt::format("stage `{}` has no block `{}` (a stage's one block is `{}`)", st.name, b.name, kRatingBlock));
        break;
      case StmtKind::Let:
        if (std::any_of(m.lets.begin(), m.lets.end(), [&](const Stmt* l) { return l->name == b.name; }))
          diags_.error("E0202", nameOr(b), fmt::format("duplicate declaration: `let {}` is already in stage `{}`", b.name, st.name));
        else
          m.lets.push_back(&b);
        break;
      default: notAllowed(b, fmt::format("stage `{}`", st.name));
      }
    }
    return m;
  }

  // `rating { … }`: its settings become the stage's `rating.…` attributes, so that a
  // variant overrides them (`hs.rating.life = …`) like any other attribute.
  void ratingBlock(StageModel& m, const Stmt& b, std::map<std::string, const Stmt*>& seen) {
    if (m.kind && !findAttr(*m.kind, "rating.life")) {
      diags_.error("E0235", nameOr(b),
                   fmt::format("{} {} stage has no load-capacity rating yet{}", m.kind->name[0] == 'i' ? "an" : "a", m.kind->name,
                               m.kind->kind == ir::StageKind::Bevel ? " (bevel gears are rated by ISO 10300, which gbxc does not implement)"
                                                                    : " (ISO 6336 rating covers spur, helical, idler and planetary stages)"));
      return;
    }
    if (m.rated) {
      diags_.error("E0202", nameOr(b), fmt::format("duplicate declaration: stage `{}` already has a `rating` block", m.name));
      return;
    }
    std::vector<std::pair<std::string, Binding>> items;
    flatten(b.body, std::string(kRatingBlock) + ".", fmt::format("the `rating` of stage `{}`", m.name), items,
            {"rating.lubricant", "rating.roughness", "rating.basic_rack", "rating.min_safety"});
    for (auto& [p, bind] : items) {
      if (auto it = seen.find(p); it != seen.end()) {
        auto& d = diags_.error("E0202", bind.stmt->path.span, fmt::format("duplicate declaration: `{}` is already given in stage `{}`", p, m.name));
        d.notes.push_back({it->second->path.span, "first given here"});
        continue;
      }
      seen[p] = bind.stmt;
      m.setAttr(p, {bind.stmt, "stage"});
    }
    m.rated = true;
  }

  template <class T, class Key>
  static void replaceOrAdd(std::vector<T>& v, T item, Key key) {
    for (auto& x : v)
      if (key(x) == key(item)) {
        x = std::move(item);
        return;
      }
    v.push_back(std::move(item));
  }

  // A value as the user wrote it (`0 um`), for messages; an expression by its value in the
  // display unit.
  static std::string asWritten(const ast::Expr* v, const ir::Expr& x) {
    if (v && v->kind == ast::ExprKind::Number) return ast::print(*v);
    if (v && v->kind == ast::ExprKind::Neg && !v->args.empty() && v->args[0] && v->args[0]->kind == ast::ExprKind::Number)
      return "-" + ast::print(*v->args[0]);
    return units::showQuantity(x.value, x.type.dim);
  }

  // A value beyond the limits the catalogue row sets (E0405); `v` as written, where known.
  bool outsideLimits(const AttrSpec& spec, const std::string& name, const ir::Expr& x, const ast::Expr* v) {
    if (!((spec.atLeast && x.value.compare(*spec.atLeast) < 0) || (spec.atMost && x.value.compare(*spec.atMost) > 0)))
      return false;
    std::string range = spec.atLeast && spec.atMost ? fmt::format("between {} and {}", units::showQuantity(*spec.atLeast, spec.dim),
                                                                  units::showQuantity(*spec.atMost, spec.dim))
                        : spec.atLeast ? fmt::format("at least {}", units::showQuantity(*spec.atLeast, spec.dim))
                                       : fmt::format("at most {}", units::showQuantity(*spec.atMost, spec.dim));
    diags_.error("E0405", x.span, fmt::format("`{}` must be {} ({}), got {}", name, range, spec.meaning, asWritten(v, x)));
    return true;
  }

  void dupInBlock(std::map<std::string, const Stmt*>& seen, const Stmt& st, const char* what) {
    auto key = std::string(what) + ":" + st.name;
    if (auto it = seen.find(key); it != seen.end()) {
      auto& d = diags_.error("E0202", nameOr(st), fmt::format("duplicate declaration: {} `{}` is already declared in this gearbox", what, st.name));
      d.notes.push_back({nameOr(*it->second), "first declared here"});
    }
    seen[key] = &st;
  }

  const GearboxModel* build(const std::string& name, std::vector<std::string>& stack) {
    if (auto it = models_.find(name); it != models_.end()) return it->second.get();
    auto dit = globals_.gearboxes.find(name);
    if (dit == globals_.gearboxes.end()) return nullptr;
    const Stmt& decl = *dit->second;
    if (std::find(stack.begin(), stack.end(), name) != stack.end()) {
      diags_.error("E0205", decl.baseSpan.valid() ? decl.baseSpan : nameOr(decl),
                   fmt::format("extends cycle: {} -> {}", fmt::join(stack, " -> "), name));
      return nullptr;
    }
    auto model = std::make_unique<GearboxModel>();
    if (!decl.base.empty()) {
      if (!globals_.gearboxes.count(decl.base)) {
        std::vector<std::string> names;
        for (const auto& [n, _] : globals_.gearboxes) names.push_back(n);
        std::string hint = closest(decl.base, names);
        diags_.error("E0206", decl.baseSpan,
                     fmt::format("`{}` extends unknown gearbox `{}`{}", name, decl.base,
                                 suggestion(hint)));
      } else {
        stack.push_back(name);
        const GearboxModel* base = build(decl.base, stack);
        stack.pop_back();
        if (!base) return nullptr;
        *model = *base;
        model->splitOverrides = base->splitOverrides;
      }
    }
    model->name = name;
    model->base = globals_.gearboxes.count(decl.base) ? decl.base : "";
    model->decl = &decl;
    std::string origin = "gearbox " + name;
    std::map<std::string, const Stmt*> seen;

    // Stages first (in place, so `like` and overrides find them), `like` copies after.
    std::vector<const Stmt*> likes = stagesOf(*model, decl, seen);
    std::set<std::string> resolving;
    for (const auto* l : likes) resolveLike(*model, *l, likes, resolving, name);
    statementsOf(*model, decl, seen, name, origin);
    auto* raw = model.get();
    models_[name] = std::move(model);
    return raw;
  }

  // A gearbox's own stages and `like` placeholders, in declaration order; the `like` statements.
  std::vector<const Stmt*> stagesOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen) {
    std::vector<const Stmt*> likes;
    for (const auto& st : decl.body) {
      if (st.kind == StmtKind::Stage) {
        dupInBlock(seen, st, "stage");
        replaceOrAdd(model.stages, makeStage(st), [](const StageModel& s) { return s.name; });
      } else if (st.kind == StmtKind::Like) {
        dupInBlock(seen, st, "stage");
        StageModel placeholder;
        placeholder.name = st.name;
        placeholder.decl = &st;
        placeholder.likePending = true;
        replaceOrAdd(model.stages, std::move(placeholder), [](const StageModel& s) { return s.name; });
        likes.push_back(&st);
      }
    }
    return likes;
  }

  // `stage b like a;`: b becomes a copy of a (resolving a first where it is a `like` too).
  void resolveLike(GearboxModel& model, const Stmt& st, const std::vector<const Stmt*>& likes, std::set<std::string>& resolving,
                   const std::string& name) {
    StageModel* target = model.findStage(st.name);
    if (!target || !target->likePending) return;
    std::string src = st.path.str();
    StageModel* source = model.findStage(src);
    if (!source || st.path.parts.size() != 1) {
      std::vector<std::string> names;
      for (const auto& s : model.stages) names.push_back(s.name);
      std::string hint = closest(src, names);
      diags_.error("E0207", st.path.span,
                   fmt::format("stage `{}` is like `{}`, but gearbox `{}` has no stage `{}`{}", st.name, src, name, src,
                               suggestion(hint)));
      target->likePending = false;
      return;
    }
    if (source->likePending) {
      if (resolving.count(src)) {
        diags_.error("E0223", st.path.span, fmt::format("`like` cycle: stage `{}` is, in the end, like itself", st.name));
        target->likePending = false;
        return;
      }
      resolving.insert(st.name);
      for (const auto* l : likes)
        if (l->name == src) resolveLike(model, *l, likes, resolving, name);
      resolving.erase(st.name);
      source = model.findStage(src);
      target = model.findStage(st.name);
    }
    if (source->likePending || (source->likeOf.empty() && !source->kind && source->decl && source->decl->kind == StmtKind::Like)) {
      target->likePending = false;
      return;
    }
    StageModel copy = *source;
    copy.name = st.name;
    copy.decl = &st;
    copy.likeOf = src;
    for (auto& [p, b] : copy.attrs) b.origin = "like " + src;
    for (auto& r : copy.rules) r.scope = st.name;
    *target = std::move(copy);
  }

  // Everything else a gearbox declares, onto its model (a variant's replaces its baseline's).
  void statementsOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen, const std::string& name,
                    const std::string& origin) {
    bool ownObjectives = false;
    for (const auto& st : decl.body) {
      switch (st.kind) {
      case StmtKind::Stage:
      case StmtKind::Like: break;
      case StmtKind::Let:
        dupInBlock(seen, st, "let");
        replaceOrAdd(model.lets, &st, [](const Stmt* s) { return s->name; });
        break;
      case StmtKind::Require: model.rules.push_back({&st, ""}); break;
      case StmtKind::Interchangeable: model.interchangeables.push_back(&st); break;
      case StmtKind::Minimize:
      case StmtKind::Maximize:
        // A variant that states its own objectives replaces the baseline's.
        if (!ownObjectives) model.objectives.clear();
        ownObjectives = true;
        model.objectives.push_back(&st);
        break;
      case StmtKind::Operating:
        if (seen.count("operating")) {
          diags_.error("E0202", st.span, "duplicate declaration: this gearbox already has an `operating` block");
          break;
        }
        seen["operating"] = &st;
        model.hasOperating = true;
        for (const auto& a : st.body) {
          if (a.kind != StmtKind::Assign) {
            notAllowed(a, "`operating`");
            continue;
          }
          replaceOrAdd(model.operating, std::make_pair(a.path.str(), Binding{&a, origin}),
                       [](const auto& p) { return p.first; });
        }
        break;
      case StmtKind::Scene:
        dupInBlock(seen, st, "scene");
        replaceOrAdd(model.scenes, &st, [](const Stmt* s) { return s->name; });
        break;
      case StmtKind::Split:
        dupInBlock(seen, st, "split");
        replaceOrAdd(model.splits, &st, [](const Stmt* s) { return s->name; });
        model.splitOverrides.erase(st.name);
        break;
      case StmtKind::Study:
        dupInBlock(seen, st, "study");
        replaceOrAdd(model.studies, &st, [](const Stmt* s) { return s->name; });
        break;
      case StmtKind::Modify: {
        // One block per stage in a gearbox; a variant's block adds to or replaces the rules
        // of its baseline's (merged where the rules are built).
        auto key = "modify:" + st.path.str();
        if (auto it = seen.find(key); it != seen.end()) {
          auto& d = diags_.error("E0202", st.path.span,
                                 fmt::format("duplicate declaration: gearbox `{}` already has a `modify {}` block; put its rules in one block",
                                             name, st.path.str()));
          d.notes.push_back({it->second->path.span, "first declared here"});
        }
        seen[key] = &st;
        model.modifies.push_back(&st);
        break;
      }
      case StmtKind::Report:
        if (seen.count("report")) diags_.error("E0202", st.span, "duplicate declaration: this gearbox already has a `report` block");
        seen["report"] = &st;
        model.report = &st;
        break;
      case StmtKind::Assign:
      case StmtKind::Domain: override(model, st, origin); break;
      case StmtKind::Block:
        if (cat::blockOf(st.name) != cat::Block::Tolerances) {
          notAllowed(st, fmt::format("gearbox `{}`", name));
          break;
        }
        if (seen.count("tolerances")) diags_.error("E0202", st.span, "duplicate declaration: this gearbox already has a `tolerances` block");
        seen["tolerances"] = &st;
        // A variant's line replaces the baseline's line for the same quantity.
        for (const auto& t : st.body) {
          if (t.kind != StmtKind::Scatter) {
            notAllowed(t, "`tolerances` (it lists `stage.attribute +- amount;`)");
            continue;
          }
          replaceOrAdd(model.tolerances, &t, [](const Stmt* x) { return x->path.str(); });
        }
        break;
      default: notAllowed(st, fmt::format("gearbox `{}`", name));
      }
    }
  }

  void override(GearboxModel& m, const Stmt& st, const std::string& origin) {
    const auto& parts = st.path.parts;
    if (parts.empty()) return;
    if (StageModel* stage = m.findStage(parts[0])) {
      if (parts.size() == 1) {
        diags_.error("E0211", st.path.span, fmt::format("`{}` is a stage; set one of its attributes, as in `{}.face_width = …`", parts[0], parts[0]));
        return;
      }
      std::string rest = st.path.str().substr(parts[0].size() + 1);
      stage->setAttr(rest, {&st, origin});
      return;
    }
    if (parts.size() > 1 && m.findSplit(parts[0])) {
      std::string rest = st.path.str().substr(parts[0].size() + 1);
      replaceOrAdd(m.splitOverrides[parts[0]], std::make_pair(rest, Binding{&st, origin}), [](const auto& p) { return p.first; });
      return;
    }
    if (parts.size() == 1) {
      diags_.error("E0211", st.path.span,
                   fmt::format("gearbox `{}` has no attribute `{}` to set: attributes belong to stages (`stage.{}`); "
                               "name a derived value with `let`",
                               m.name, parts[0], parts[0]));
      return;
    }
    std::vector<std::string> names;
    for (const auto& s : m.stages) names.push_back(s.name);
    for (const auto* s : m.splits) names.push_back(s->name);
    std::string hint = closest(parts[0], names);
    diags_.error("E0219", st.path.spans[0],
                 fmt::format("`{}` is not a stage or split of gearbox `{}`{}", parts[0], m.name,
                             suggestion(hint)));
  }

  // ---- from models to IR ---------------------------------------------------------------

  // E0211: no such attribute of the stage's kind, with the name it was likely meant to be.
  void unknownAttribute(const StageModel& st, const std::string& path, Span where) {
    std::vector<std::string> names;
    for (const auto& x : st.kind->stage) names.push_back(x.name);
    for (const auto& g : st.kind->gears)
      for (const auto& x : st.kind->gear) names.push_back(g + "." + x.name);
    std::string hint = closest(path, names);
    std::string extra;
    if (isKey(path, Q::Module) && (st.kind->kind == ir::StageKind::Spur || st.kind->kind == ir::StageKind::Helical))
      hint = "normal_module";
    if (isKey(path, Q::HelixAngle) && st.kind->kind == ir::StageKind::Spur) extra = " (a spur stage has no helix; use a helical stage)";
    diags_.error("E0211", where,
                 fmt::format("`{}` is not an attribute of a {} stage{}{}", path, st.kind->name, extra,
                             suggestion(hint)));
    // The attribute it was meant to be is then not "missing": one error, not two.
    if (!hint.empty()) misspelt_.insert({st.name, hint});
  }

  // A bound of a domain of `path`: a constant number in the attribute's unit, whole where it
  // counts, positive and within its row's limits and budgets.
  std::optional<Number> boundOf(const AttrSpec& spec, const std::string& path, bool tooth, ir::ExprPtr x) {
    if (x->type.isError()) return std::nullopt;
    if (!x->type.isNumber()) {
      diags_.error("E0306", x->span, fmt::format("a bound of `{}` must be a number, but this is {}", path, describe(x->type)));
      return std::nullopt;
    }
    if (!x->isConst()) {
      diags_.error("E0410", x->span, fmt::format("a bound of `{}` must be a constant", path));
      return std::nullopt;
    }
    if (x->type.dim != spec.dim) {
      diags_.error("E0302", x->span,
                   fmt::format("unit mismatch: `{}` needs {}, got {}", path, spec.dim.describe(), describe(x->type)));
      return std::nullopt;
    }
    if (spec.integer && !(x->value.isRational() && x->value.rational().isInteger())) {
      diags_.error("E0403", x->span, fmt::format("`{}` takes whole numbers, got {}", path, x->value.str()));
      return std::nullopt;
    }
    if (spec.positive && x->value.sign() <= 0) {
      diags_.error(tooth ? "E0402" : "E0405", x->span,
                   tooth ? fmt::format("a tooth count must be positive, got {}", x->value.str())
                         : fmt::format("`{}` must be positive, got {}", path, units::showQuantity(x->value, x->type.dim)));
      return std::nullopt;
    }
    if (beyondBudget(spec, path, *x)) return std::nullopt;
    if (!spec.budget && outsideLimits(spec, path, *x, nullptr)) return std::nullopt;
    if (spec.integer && (x->value.sign() < 0 ? x->value.neg() : x->value).compare(units::Number::exact(units::Rational(cat::budget::kWholeNumber))) > 0) {
      diags_.error("E0411", x->span,
                   fmt::format("`{}` = {} is beyond the budget of {} for a whole number", path, x->value.str(), cat::budget::kWholeNumber));
      return std::nullopt;
    }
    return x->value;
  }

  ir::Attribute attribute(const StageModel& st, const std::string& path, const Binding& b, const Scope& scope) {
    ir::Attribute a;
    a.name = path;
    a.origin = b.origin;
    a.span = b.stmt->span;
    const Stmt& s = *b.stmt;
    const AttrSpec* spec = findAttr(*st.kind, path);
    Span where = s.path.span;
    if (!spec) {
      unknownAttribute(st, path, where);
      a.role = ir::Attribute::Fixed;
      return a;
    }
    a.dim = spec->dim;
    a.integer = spec->integer;
    if (spec->role == AttrRole::Derived) {
      diags_.error("E0212", where, fmt::format("`{}` is derived ({}) and cannot be set; constrain it with `require`", path, spec->meaning));
      return a;
    }
    bool tooth = isKey(lastPart(path), Q::Z);
    if (s.kind == StmtKind::Assign) {
      a.role = ir::Attribute::Fixed;
      ir::Setting v = setting(path, b, *spec, scope, fmt::format("stage `{}`", st.name));
      a.value = std::move(v.expr);
      a.symbol = v.symbol;
      return a;
    }
    // A domain: bounds are constants in the attribute's unit.
    if (spec->value != ValueKind::Number) {
      diags_.error("E0110", where, fmt::format("`{}` takes one value (`=`), not a domain", path));
      return a;
    }
    a.role = spec->integer ? ir::Attribute::Decision : ir::Attribute::Freedom;
    auto checkBound = [&](ir::ExprPtr x) { return boundOf(*spec, path, tooth, std::move(x)); };
    if (s.domain == ast::DomainKind::Range) {
      auto [lo, hi] = checker_.checkRange(s.lo.get(), s.hi.get(), scope);
      Span span = source::cover(lo->span, hi->span);
      a.lo = checkBound(std::move(lo));
      a.hi = checkBound(std::move(hi));
      if (a.lo && a.hi && a.lo->compare(*a.hi) > 0) {
        diags_.error("E0401", span, fmt::format("empty range for `{}`: {} is above {}", path, units::showQuantity(*a.lo, a.dim),
                                                units::showQuantity(*a.hi, a.dim)));
      } else if (a.lo && a.hi && spec->integer) {
        // Every value of a decision range is listed: its size is a budget (counted exactly:
        // bounds near 2^80 are one double apart).
        units::Number width = a.hi->sub(*a.lo);
        double values = width.toDouble() + 1;
        if (width.compare(units::Number::exact(units::Rational(cat::budget::kDomainValues - 1))) > 0) {
          diags_.error("E0411", span,
                       fmt::format("`{}` in {}..{} holds {:.0f} values, beyond the budget of {} a search lists per decision; "
                                   "narrow the range",
                                   path, a.lo->str(), a.hi->str(), values, cat::budget::kDomainValues));
        }
      }
      return a;
    }
    std::vector<ir::ExprPtr> members;
    std::vector<std::string> texts;  // literals as written, for reports
    Span span = s.span;
    if (s.domain == ast::DomainKind::Named) {
      auto v = checker_.check(s.value.get(), scope);
      if (v->type.isError()) return a;
      if (v->op != Op::Set) {
        diags_.error("E0306", v->span, fmt::format("`{}` must be a set `{{…}}` to serve as a domain", ast::print(*s.value)));
        return a;
      }
      span = v->span;
      members = std::move(v->args);
    } else {
      for (const auto& m : s.exprs) {
        members.push_back(checker_.check(m.get(), scope));
        texts.push_back(m && m->kind == ast::ExprKind::Number ? ast::print(*m) : std::string());
      }
    }
    if (members.empty()) diags_.error("E0404", span, fmt::format("empty set: `{}` has no value to take", path));
    std::vector<std::pair<Number, std::string>> checked;
    for (size_t i = 0; i < members.size(); ++i)
      if (auto v = checkBound(std::move(members[i]))) checked.emplace_back(*v, i < texts.size() ? texts[i] : std::string());
    std::stable_sort(checked.begin(), checked.end(), [](const auto& x, const auto& y) { return x.first.compare(y.first) < 0; });
    bool written = !checked.empty();
    for (const auto& [v, t] : checked) {
      a.members.push_back(v);
      written = written && !t.empty();
    }
    if (written)
      for (const auto& [v, t] : checked) a.memberTexts.push_back(t);
    return a;
  }

  ir::Stage stage(const StageModel& st, const Scope& gbScope) {
    ir::Stage out;
    out.name = st.name;
    out.span = st.decl ? st.decl->span : Span{};
    out.presets = st.presets;
    out.likeOf = st.likeOf;
    if (!st.kind) return out;
    out.kind = st.kind->kind;
    out.gears = st.kind->gears;
    Scope s = gbScope;
    s.stage = &st;
    for (const auto& [path, b] : st.attrs) out.attributes.push_back(attribute(st, path, b, s));
    Span where = st.decl ? nameOr(*st.decl) : Span{};
    for (const auto& a : st.kind->stage)
      if (a.required && !st.findAttr(a.name) && !misspelt_.count({st.name, a.name}))
        diags_.error("E0225", where, fmt::format("stage `{}` does not give `{}` ({})", st.name, a.name, a.meaning));
    for (const auto& g : st.kind->gears)
      for (const auto& a : st.kind->gear)
        if (a.required && !st.findAttr(g + "." + a.name) && !misspelt_.count({st.name, g + "." + a.name}))
          diags_.error("E0225", where, fmt::format("stage `{}` does not give `{}.{}` ({})", st.name, g, a.name, a.meaning));
    if (st.rated) ratingInputs(st, where);
    return out;
  }

  // A rated stage needs its service life and a material with the ISO 6336-5 numbers.
  void ratingInputs(const StageModel& st, Span where) {
    for (const char* need : {"rating.life", "rating.lubricant.viscosity_40", "rating.roughness.flank", "rating.roughness.root"}) {
      std::string rz = std::string(need) + "_rz";
      if (!st.findAttr(need) && !st.findAttr(rz))
        diags_.error("E0225", where,
                     fmt::format("the `rating` of stage `{}` does not give `{}` ({})", st.name, std::string(need).substr(7),
                                 findAttr(*st.kind, need)->meaning));
    }
    bool plainModule = st.kind->kind == ir::StageKind::Idler || st.kind->kind == ir::StageKind::Planetary;
    for (const char* need : {plainModule ? "module" : "normal_module", "face_width"})
      if (!st.findAttr(need))
        diags_.error("E0225", where, fmt::format("stage `{}` is rated but does not give `{}` ({})", st.name, need, findAttr(*st.kind, need)->meaning));
    if (!st.findAttr("accuracy")) {
      std::vector<std::string> missing;
      for (const auto& g : st.kind->gears)
        for (const char* dev : {"pitch_deviation", "profile_form_deviation", "helix_slope_deviation"})
          if (!st.findAttr(g + "." + dev)) missing.push_back("`" + g + "." + dev + "`");
      if (!missing.empty())
        diags_.error("E0225", where,
                     fmt::format("stage `{}` is rated but gives no `accuracy` (ISO 1328-1 grade) from which to take {}", st.name,
                                 fmt::join(missing, ", ")));
    }
    for (const auto& g : st.kind->gears)
      if (st.findAttr(g + ".web_thickness") && !st.findAttr(g + ".rim_thickness"))
        diags_.error("E0225", where, fmt::format("`{}.web_thickness` needs `{}.rim_thickness` (C_R of a webbed blank)", g, g));
    const Binding* mat = st.findAttr(std::string(keyName(Q::Material)));
    if (!mat) {
      diags_.error("E0233", where, fmt::format("stage `{}` is rated but names no `material` (the rating needs its E, nu, sigma_hlim, sigma_flim and treatment)", st.name));
      return;
    }
    const ast::Expr* v = mat->stmt->value.get();
    if (!v || v->kind != ast::ExprKind::Name) return;
    auto it = globals_.materials.find(v->text);
    if (it == globals_.materials.end()) return;  // reported as an unknown material
    std::vector<std::string> missing;
    for (Q need : {Q::SigmaHlim, Q::SigmaFlim, Q::Treatment}) {
      std::string n(keyName(need));
      if (std::none_of(it->second->body.begin(), it->second->body.end(), [&](const Stmt& b) { return b.path.str() == n; }))
        missing.push_back("`" + n + "`");
    }
    if (!missing.empty())
      diags_.error("E0233", mat->stmt->value->span,
                   fmt::format("stage `{}` is rated, but material `{}` does not give {}", st.name, v->text, fmt::join(missing, ", ")));
  }

  ir::Rule rule(const Stmt& st, const Scope& s, const std::string& scopeName) {
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

  // Which end of the tolerance box is the worst for each `worst(q)`: where q is minimised or
  // bounded from above its largest value, where maximised or bounded from below its smallest;
  // a minus sign, a divisor or a `not` turns it round. `sense` 0: not known here (a report
  // column, where q's own better direction decides). In a rule, a two-sided bound on a
  // `worst` (`in a..b`, `== c +- t`) holds when both ends of q hold it, so it is checked at
  // both: the comparison is kept twice, once at each end; and a `let` that reads `worst` is
  // read in place, so that it takes the rule's direction.
  // Whether an expression reads `worst` or `mean` over the tolerances, itself or through lets.
  bool readsWorst(const ir::Expr& e, int depth = 0) const {
    if (e.op == Op::Scatter) return true;
    if (depth > 64) return false;
    if (e.op == Op::Let && lets_)
      if (auto it = lets_->find(e.name); it != lets_->end() && it->second && readsWorst(*it->second, depth + 1)) return true;
    for (const auto& x : e.args)
      if (x && readsWorst(*x, depth + 1)) return true;
    return false;
  }

  void worstSense(ir::Expr& e, int sense, bool condition = false, bool negated = false) {
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
  std::vector<ir::Tolerance> tolerances(const GearboxModel& m, const Scope& gs) {
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
    if (out.size() > 6 && !m.tolerances.empty())
      diags_.error("E0237", m.tolerances[6]->span,
                   fmt::format("gearbox `{}` lists {} tolerances; `worst` and `mean` visit every corner of their box, so at most 6 "
                               "(64 corners) are taken",
                               m.name, out.size()));
    return out;
  }

  // Attributes given by expressions that need themselves, through one another
  // (`face_width = face_width + 1 mm`, or `a = b` and `b = a`): no value can come of them.
  // One through a computed quantity (`face_width = 0.1 * mass`) is the runtime's to find.
  void selfDefined(const ir::Gearbox& g) {
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

  ir::Objective objective(const Stmt& st, const Scope& gs) {
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

  // A stage's rules from its baseline's block and its own, one rule per target: a later rule
  // for a target replaces the earlier one (as a `tolerances` line does).
  static void mergeModify(std::vector<ir::Modify>& modifies, ir::Modify built) {
    auto same = std::find_if(modifies.begin(), modifies.end(), [&](const ir::Modify& x) { return x.stage == built.stage; });
    if (same == modifies.end()) {
      modifies.push_back(std::move(built));
      return;
    }
    for (auto& r : built.rules) {
      auto old = std::find_if(same->rules.begin(), same->rules.end(), [&](const ir::ModRule& x) { return x.target == r.target; });
      if (old != same->rules.end()) *old = std::move(r);
      else same->rules.push_back(std::move(r));
    }
  }

  ir::Gearbox lowerGearbox(const GearboxModel& m) {
    ir::Gearbox g;
    g.name = m.name;
    g.baseline = m.base;
    g.span = m.decl->span;
    Scope gs;
    gs.gearbox = &m;
    gs.hasBaseline = !m.base.empty();
    gs.hasTolerances = !m.tolerances.empty();
    g.tolerances = tolerances(m, gs);

    std::map<std::string, Type> letTypes;
    std::set<std::string> letBusy;
    std::map<std::string, ir::ExprPtr> letExprs;
    lets_ = &letExprs;
    struct ForgetLets {
      const std::map<std::string, ir::ExprPtr>*& p;
      ~ForgetLets() { p = nullptr; }
    } forgetLets{lets_};
    checker_.setLetResolver([&](const std::string& n, const StageModel* st) -> Type {
      std::string key = st ? st->name + "." + n : n;
      if (auto it = letTypes.find(key); it != letTypes.end()) return it->second;
      const Stmt* decl = nullptr;
      if (st) {
        for (const auto* l : st->lets)
          if (l->name == n) decl = l;
      } else {
        decl = m.findLet(n);
      }
      if (!decl) return Type::error();
      if (letBusy.count(key)) {
        diags_.error("E0228", nameOr(*decl), fmt::format("`let {}` is defined in terms of itself", n));
        letTypes[key] = Type::error();
        return Type::error();
      }
      letBusy.insert(key);
      Scope s = gs;
      s.stage = st;
      auto e = checker_.check(decl->value.get(), s);
      letBusy.erase(key);
      Type t = e->type;
      letTypes[key] = t;
      letExprs[key] = std::move(e);
      return t;
    });

    for (const auto& st : m.stages) g.stages.push_back(stage(st, gs));
    selfDefined(g);
    for (const auto& st : m.stages) {
      Scope s = gs;
      s.stage = &st;
      for (const auto& r : st.rules) g.rules.push_back(rule(*r.stmt, s, r.scope));
    }
    // Lets: resolve every one (also the unused), in declaration order.
    auto resolveLets = [&](const StageModel* st, const std::vector<const Stmt*>& lets) {
      for (const auto* l : lets) {
        Scope s = gs;
        s.stage = st;
        ast::Expr probe;
        probe.kind = ast::ExprKind::Name;
        probe.text = l->name;
        probe.span = l->nameSpan;
        checker_.check(&probe, s);
        std::string key = st ? st->name + "." + l->name : l->name;
        ir::Let out;
        out.name = key;
        out.span = l->span;
        if (auto it = letExprs.find(key); it != letExprs.end() && it->second) out.expr = it->second->clone();
        else out.expr = ir::makeConst(Number::exact(0), {}, false);
        g.lets.push_back(std::move(out));
      }
    };
    for (const auto& st : m.stages) resolveLets(&st, st.lets);
    resolveLets(nullptr, m.lets);
    for (const auto& r : m.rules) g.rules.push_back(rule(*r.stmt, gs, ""));

    for (const auto* st : m.interchangeables) g.interchangeable.push_back(interchangeable(*st, m));
    for (const auto* st : m.objectives) g.objectives.push_back(objective(*st, gs));
    // A let read in one direction by the rules and objectives takes it where it stands alone
    // too (a report column of it reads the same number as the rule).
    for (auto& l : g.lets)
      if (auto it = letSense_.find(l.name); it != letSense_.end() && it->second != 0 && l.expr) worstSense(*l.expr, it->second);
    letSense_.clear();
    if (m.hasOperating) {
      const Stmt* opDecl = nullptr;
      for (const auto& [n, b] : m.operating) opDecl = b.stmt;
      g.operating = settings(m.operating, operatingSettings(), gs, "`operating`", m.decl ? nameOr(*m.decl) : Span{}, "E0226");
      checkOperating(m, g.operating, opDecl);
    }
    for (const auto* sc : m.scenes) g.scenes.push_back(scene(*sc, m, gs));
    for (const auto* md : m.modifies) mergeModify(g.modifies, modify(*md, m, gs));
    for (const auto* sp : m.splits) g.splits.push_back(split(*sp, m, gs));
    for (const auto* sd : m.studies) g.studies.push_back(study(*sd, m, gs));
    if (m.report) g.report = report(*m.report, gs);

    if (!m.hasOperating) requireOperating(g);
    requireMaterial(g, m);
    requireRating(g, m);
    if (!m.hasOperating)
      for (const auto& st : m.stages)
        if (st.rated)
          diags_.error("E0231", st.decl ? nameOr(*st.decl) : Span{},
                       fmt::format("stage `{}` is rated, but gearbox `{}` has no `operating` block (the rating needs the load and speed)", st.name, g.name));
    return g;
  }

  // A gear pair's mass needs its material's density: say so at check time, not as `n/a`.
  void requireMaterial(const ir::Gearbox& g, const GearboxModel& m) {
    std::set<std::pair<int, int>> reported;
    auto visit = [&](const ir::Expr* e, const char* where) {
      if (!e) return;
      walk(*e, [&](const ir::Expr& x) {
        if (x.op != Op::Quantity || !x.type.isNumber() || keyOf(lastPart(x.name)) != Q::Mass) return;
        auto dot = x.name.find('.');
        const StageModel* st = dot == std::string::npos ? nullptr : m.findStage(x.name.substr(0, dot));
        if (!st || !st->kind || st->findAttr(std::string(keyName(Q::Material))) || x.name.find('.', dot + 1) != std::string::npos) return;
        if (!reported.insert({x.span.line, x.span.col}).second) return;
        diags_.error("E0233", x.span,
                     fmt::format("`{}` needs the density of the stage's material, but stage `{}` names no `material` ({})", x.name,
                                 st->name, where));
      });
    };
    for (const auto& o : g.objectives) visit(o.expr.get(), "used in an objective");
    for (const auto& r : g.rules) visit(r.expr.get(), "used in a rule");
    if (g.report)
      for (const auto& c : g.report->columns) visit(c.get(), "reported");
  }

  // A safety or an influence factor needs the stage's `rating` inputs.
  void requireRating(const ir::Gearbox& g, const GearboxModel& m) {
    std::set<std::pair<int, int>> reported;
    auto visit = [&](const ir::Expr* e, const char* where) {
      if (!e) return;
      walk(*e, [&](const ir::Expr& x) {
        if (x.op != Op::Quantity || !x.type.isNumber()) return;
        auto k = keyOf(lastPart(x.name));
        if (!k || !isRatingQuantity(*k)) return;
        auto dot = x.name.find('.');
        const StageModel* st = dot == std::string::npos ? nullptr : m.findStage(x.name.substr(0, dot));
        if (!st || !st->kind) return;
        if (st->rated) {
          // An internal gear's tooth root: ISO 6336-3 for internal gears is not implemented.
          static const std::set<Q> root = {Q::BendingSafety, Q::BendingStress, Q::PermissibleBendingStress, Q::YF, Q::YS, Q::Ybeta,
                                           Q::YNT, Q::YdeltarelT, Q::YRrelT, Q::YX};
          bool ring = st->kind->kind == ir::StageKind::Planetary && x.name.find("." + st->kind->gears[2] + ".") != std::string::npos;
          if (ring && root.count(*k) && reported.insert({x.span.line, x.span.col}).second)
            diags_.error("E0235", x.span,
                         fmt::format("`{}`: the tooth root of an internal gear is not rated (ISO 6336-3 for internal gears is not "
                                     "implemented; its contact is rated) ({})",
                                     x.name, where));
          return;
        }
        if (!reported.insert({x.span.line, x.span.col}).second) return;
        diags_.error("E0236", x.span,
                     fmt::format("`{}` is a load-capacity result, but stage `{}` has no `rating {{ … }}` block with its inputs ({})",
                                 x.name, st->name, where));
      });
    };
    for (const auto& r : g.rules) visit(r.expr.get(), "used in a rule");
    for (const auto& o : g.objectives) visit(o.expr.get(), "used in an objective");
    for (const auto& l : g.lets) visit(l.expr.get(), "used in a let");
    if (g.report) {
      for (const auto& c : g.report->columns) visit(c.get(), "reported");
      visit(g.report->sortBy.get(), "used to sort");
    }
    for (const auto& st : g.studies)
      for (const auto& o : st.outputs) visit(o.get(), "output of a study");
  }

  void requireOperating(const ir::Gearbox& g) {
    std::set<std::pair<int, int>> reported;
    auto visit = [&](const ir::Expr* e, const char* where) {
      if (!e) return;
      walk(*e, [&](const ir::Expr& x) {
        if (x.op != Op::Quantity || !x.type.isNumber() || !needsOperating(x.name)) return;
        if (!reported.insert({x.span.line, x.span.col}).second) return;
        diags_.error("E0231", x.span,
                     fmt::format("`{}` depends on the operating point, but gearbox `{}` has no `operating` block ({})",
                                 x.name, g.name, where));
      });
    };
    for (const auto& r : g.rules) visit(r.expr.get(), "used in a rule");
    for (const auto& o : g.objectives) visit(o.expr.get(), "used in an objective");
    for (const auto& l : g.lets) visit(l.expr.get(), "used in a let");
    if (g.report) {
      for (const auto& c : g.report->columns) visit(c.get(), "reported");
      visit(g.report->sortBy.get(), "used to sort");
    }
    for (const auto& md : g.modifies)
      for (const auto& r : md.rules) visit(r.value.get(), "used in a modification rule");
    for (const auto& st : g.studies)
      for (const auto& o : st.outputs) visit(o.get(), "output of a study");
  }

  void checkOperating(const GearboxModel& m, const std::vector<ir::Setting>& op, const Stmt* decl) {
    auto has = [&](const char* n) { return ir::findSetting(op, n) != nullptr; };
    Span where = decl ? decl->span : nameOr(*m.decl);
    if (!has("input_speed") && !has("output_speed"))
      diags_.error("E0226", where, "`operating` needs a speed: `input_speed` or `output_speed`");
    if (has("input_speed") && has("output_speed"))
      diags_.error("E0226", where, "`operating` gives both `input_speed` and `output_speed`; the ratio fixes one from the other");
    int loads = has("input_torque") + has("output_torque") + has("power");
    if (loads > 1)
      diags_.error("E0226", where, "`operating` gives more than one of `input_torque`, `output_torque` and `power`; give one");
  }

  std::vector<std::string> interchangeable(const Stmt& st, const GearboxModel& m) {
    std::vector<std::string> out;
    std::string kind;
    for (const auto& p : st.paths) {
      const StageModel* s = p.parts.empty() ? nullptr : m.findStage(p.parts[0]);
      if (!s) {
        diags_.error("E0219", p.span, fmt::format("`{}` is not a stage of gearbox `{}`", p.parts.empty() ? "" : p.parts[0], m.name));
        continue;
      }
      std::string k;
      if (p.parts.size() == 1) k = "stage " + std::string(s->kind ? s->kind->name : "?");
      else if (p.parts.size() == 2 && s->kind && isGear(*s->kind, p.parts[1])) k = "gear " + p.parts[1];
      else {
        diags_.error("E0219", p.span, fmt::format("`{}` is neither a stage nor a gear of one", p.str()));
        continue;
      }
      if (!kind.empty() && k != kind) {
        diags_.error("E0306", p.span, fmt::format("interchangeable members must be alike: `{}` is a {}, the first a {}", p.str(), k, kind));
        continue;
      }
      kind = k;
      out.push_back(p.str());
    }
    return out;
  }

  ir::Scene scene(const Stmt& st, const GearboxModel& m, const Scope& gs) {
    ir::Scene out;
    out.name = st.name;
    out.span = st.span;
    std::string owner = fmt::format("scene `{}`", st.name);
    std::string target = st.path.str();
    const StageModel* stage = m.findStage(target);
    if (stage) out.target = target;
    else if (target != m.name) {
      std::vector<std::string> names;
      for (const auto& x : m.stages) names.push_back(x.name);
      std::string hint = closest(target, names);
      diags_.error("E0232", st.path.span,
                   fmt::format("a scene runs on a stage of gearbox `{}` or on the gearbox itself (`on {}`); `{}` is neither{} (stages: {})",
                               m.name, m.name, target, suggestion(hint), fmt::join(names, ", ")));
    }
    if (!m.hasOperating)
      diags_.error("E0231", nameOr(st), fmt::format("{} needs an operating point, but gearbox `{}` has no `operating` block", owner, m.name));
    std::vector<std::pair<std::string, Binding>> items, acc;
    bool sawEffects = false;
    for (const auto& b : st.body) {
      switch (b.kind) {
      case StmtKind::Effects:
        if (sawEffects) diags_.error("E0202", b.span, fmt::format("duplicate declaration: {} already has an `effects` block", owner));
        sawEffects = true;
        effects(b, out, gs);
        break;
      case StmtKind::Assign: flattenOne(b, items, owner); break;
      case StmtKind::Block:
        if (cat::blockOf(b.name) == cat::Block::Accuracy) flatten(b.body, "", owner + " accuracy", acc, {});
        else diags_.error("E0224", nameOr(b), fmt::format("{} has no block `{}` (it takes `effects` and `accuracy`)", owner, b.name));
        break;
      case StmtKind::Output:
        for (const auto& e : b.exprs) sceneOutput(e.get(), out, stage, m, !stage && target == m.name);
        break;
      default: notAllowed(b, owner);
      }
    }
    out.settings = settings(items, sceneSettings(), gs, owner, nameOr(st), "E0225");
    out.accuracy = settings(acc, accuracySettings(), gs, owner + " accuracy", nameOr(st), "E0225");
    sceneBudgets(out, owner);
    if (ir::findSetting(out.settings, "steady_state")) {
      for (const char* other : {"settle", "duration", "ramp"})
        if (const auto* s = ir::findSetting(out.settings, other))
          diags_.error("E0202", s->span,
                       fmt::format("{} asks for the periodic steady state (`steady_state = periodic`), which has no `{}`: the periodic "
                                   "response is found directly; drop one of the two",
                                   owner, other));
      if (!ir::findSetting(out.settings, "record"))
        diags_.error("E0225", nameOr(st), fmt::format("{} needs `record` (the steady-state window) with `steady_state = periodic`", owner));
      if (!stage)
        diags_.error("E0232", nameOr(st), fmt::format("{}: `steady_state = periodic` needs a scene on a stage; a whole-gearbox scene runs "
                                                     "from rest (`duration`) or settles (`settle`)", owner));
    }
    if (!ir::findSetting(out.settings, "duration") && !ir::findSetting(out.settings, "record"))
      diags_.error("E0225", nameOr(st), fmt::format("{} needs `duration` (a run from rest) or `record` (a steady-state window)", owner));
    for (const auto& o : out.outputs)
      if (isSignal(o, cat::Signal::Stability) && !ir::findSetting(out.settings, Q::SteadyState))  // else E0202 already says it
        for (const char* transient : {"settle", "duration"})
          if (ir::findSetting(out.settings, transient))
            diags_.error("E0232", o.span,
                         fmt::format("{}: `stability` is the largest Floquet multiplier of the periodic steady state, which a scene with "
                                     "`{}` does not compute; write `steady_state = periodic` instead of `{}`",
                                     owner, transient, transient));
    if (const ir::Effect* lm = out.findEffect(Effect::LoadedMesh)) {
      for (const char* other : {"varying_stiffness", "transmission_error", "hertz_contact"})
        if (out.hasEffect(other))
          diags_.error("E0214", lm->span,
                       fmt::format("{}: `loaded_mesh` computes the mesh stiffness and the transmission error from the flank geometry, so "
                                   "it replaces `{}`: list one of the two",
                                   owner, other));
      if (stage && stage->kind && stage->kind->kind != ir::StageKind::Spur && stage->kind->kind != ir::StageKind::Helical)
        diags_.error("E0232", lm->span, fmt::format("{}: `loaded_mesh` models a spur or helical pair; `{}` is {}", owner, target, stage->kind->name));
      else if (!stage && target == m.name)
        for (const auto& x : m.stages)
          if (x.kind && x.kind->kind != ir::StageKind::Spur && x.kind->kind != ir::StageKind::Helical) {
            diags_.error("E0232", lm->span,
                         fmt::format("{}: `loaded_mesh` models spur and helical pairs, and stage `{}` of the gearbox is {}; run the scene "
                                     "on a spur or helical stage",
                                     owner, x.name, x.kind->name));
            break;
          }
    }
    if (!stage && target == m.name && out.hasEffect("transmission_error") &&
        std::any_of(out.outputs.begin(), out.outputs.end(), [](const ir::SceneOutput& o) { return !isSignal(o, cat::Signal::Modes); }))
      diags_.error("E0232", out.findEffect(Effect::TransmissionError)->span,
                   fmt::format("{}: a whole-gearbox scene does not model `transmission_error`; list `loaded_mesh` (spur and helical "
                               "gearboxes), or run the scene on a stage",
                               owner));
    if (out.hasEffect("transmission_error") && !out.hasEffect("varying_stiffness"))
      diags_.warning("W0501", nameOr(st),
                     fmt::format("{}: `transmission_error` acts through F = dk(t)·e(t) and does nothing without `varying_stiffness`", owner));
    return out;
  }

  void flattenOne(const Stmt& b, std::vector<std::pair<std::string, Binding>>& items, const std::string& owner) {
    std::string p = b.path.str();
    for (const auto& [q, x] : items)
      if (q == p) {
        auto& d = diags_.error("E0202", b.path.span, fmt::format("duplicate declaration: `{}` is already set in {}", p, owner));
        d.notes.push_back({x.stmt->path.span, "first set here"});
        return;
      }
    items.emplace_back(p, Binding{&b, owner});
  }

  void effects(const Stmt& block, ir::Scene& out, const Scope& gs) {
    for (const auto& e : block.body) {
      if (e.kind != StmtKind::Block && e.kind != StmtKind::Flag) {
        notAllowed(e, "`effects` (it lists effects, as in `damping { ratio = 0.07; }`)");
        continue;
      }
      const EffectSpec* spec = findEffect(e.name);
      if (!spec) {
        std::vector<std::string> names;
        for (const auto& x : sema::effects()) names.push_back(x.name);
        std::string hint = closest(e.name, names);
        diags_.error("E0213", nameOr(e),
                     fmt::format("unknown effect `{}`{}", e.name,
                                 hint.empty() ? fmt::format(" (effects: {})", fmt::join(names, ", "))
                                              : fmt::format("; did you mean `{}`?", hint)));
        continue;
      }
      if (out.hasEffect(e.name)) {
        diags_.error("E0222", nameOr(e), fmt::format("effect `{}` is listed twice in scene `{}`", e.name, out.name));
        continue;
      }
      ir::Effect fx;
      fx.name = e.name;
      fx.kind = spec->id;
      fx.span = e.span;
      std::vector<std::pair<std::string, Binding>> items;
      std::string owner = fmt::format("effect `{}`", e.name);
      flatten(e.body, "", owner, items, {});
      Scope s = gs;
      s.context = Scope::EffectParam;
      s.effectLocals = spec->locals;
      fx.params = settings(items, spec->params, s, owner, nameOr(e), "E0215");
      if (spec->id == Effect::Damping) {
        bool r = ir::findSetting(fx.params, "ratio"), c = ir::findSetting(fx.params, "coefficient");
        if (!r && !c) diags_.error("E0215", nameOr(e), "effect `damping` needs `ratio` (zeta) or `coefficient` (c)");
        if (r && c) diags_.error("E0214", nameOr(e), "effect `damping` takes `ratio` or `coefficient`, not both");
      }
      out.effects.push_back(std::move(fx));
    }
  }

  // `a.b.c` of a name or member chain; "" for anything else.
  static std::string dotted(const ast::Expr* e) {
    if (!e) return "";
    if (e->kind == ast::ExprKind::Name) return e->text;
    if (e->kind == ast::ExprKind::Member && !e->args.empty()) {
      std::string head = dotted(e->args[0].get());
      return head.empty() ? "" : head + "." + e->text;
    }
    return "";
  }

  // The meshes a whole-gearbox scene names by stage (LANGUAGE.md §14).
  static std::vector<std::string> meshNames(const StageModel& st) {
    if (!st.kind) return {};
    switch (st.kind->kind) {
    case ir::StageKind::Planetary: return {st.name + ".sun_planet", st.name + ".ring_planet"};
    case ir::StageKind::Idler: return {st.name + ".driver_idler", st.name + ".idler_driven"};
    case ir::StageKind::Spur:
    case ir::StageKind::Helical: return {st.name};
    default: return {};
    }
  }

  void sceneOutput(const ast::Expr* e, ir::Scene& out, const StageModel* stage, const GearboxModel& m, bool whole) {
    if (!e) return;
    ir::SceneOutput o;
    o.span = e->span;
    const ast::Expr* inner = e->kind == ast::ExprKind::Call && e->args.size() == 2 ? e->args[1].get() : nullptr;
    if (e->kind == ast::ExprKind::Name) {
      o.signal = e->text;
    } else if (inner && e->args[0] && e->args[0]->kind == ast::ExprKind::Name && inner->kind == ast::ExprKind::Call &&
               inner->args.size() == 2 && inner->args[0] && inner->args[0]->kind == ast::ExprKind::Name) {
      // `peak(contact_force(planet_stage.sun_planet))`: a signal of one mesh of the gearbox.
      o.function = e->args[0]->text;
      o.signal = inner->args[0]->text;
      o.mesh = dotted(inner->args[1].get());
      if (!findSignalFn(o.function)) {
        diags_.error("E0220", e->args[0]->span, fmt::format("`{}` is not a scene result function ({})", o.function, signalFnList()));
        return;
      }
      if (o.mesh.empty()) {
        diags_.error("E0306", inner->args[1]->span, "a mesh is named by its stage, and its mesh on a planetary or idler stage, as in `transfer.driver_idler`");
        return;
      }
      if (!whole) {
        if (!stage) return;  // the scene's target is already an error
        diags_.error("E0232", inner->span,
                     fmt::format("scene `{}` runs on stage `{}`, whose signals are its own mesh's (a planetary stage's first planet): write "
                                 "`{}({})`, or run the scene on the gearbox to name a mesh",
                                 out.name, stage->name, o.function, o.signal));
        return;
      }
      if (!isSignal(o, cat::Signal::ContactForce) && !isSignal(o, cat::Signal::MeshForce)) {
        diags_.error("E0232", inner->args[0]->span,
                     fmt::format("a mesh of the gearbox has `contact_force` and `mesh_force`; `{}` is not a signal of one mesh", o.signal));
        return;
      }
      std::vector<std::string> names;
      for (const auto& st : m.stages)
        for (const auto& n : meshNames(st)) names.push_back(n);
      if (std::find(names.begin(), names.end(), o.mesh) == names.end()) {
        std::string hint = closest(o.mesh, names);
        diags_.error("E0219", inner->args[1]->span,
                     fmt::format("gearbox `{}` has no mesh `{}`{} (meshes: {})", m.name, o.mesh, suggestion(hint), fmt::join(names, ", ")));
        return;
      }
    } else if (e->kind == ast::ExprKind::Call && e->args.size() == 2 && e->args[0] &&
               e->args[0]->kind == ast::ExprKind::Name && e->args[1] && e->args[1]->kind == ast::ExprKind::Name) {
      o.function = e->args[0]->text;
      o.signal = e->args[1]->text;
      if (!findSignalFn(o.function)) {
        diags_.error("E0220", e->args[0]->span,
                     fmt::format("`{}` is not a scene result function ({})", o.function, signalFnList()));
        return;
      }
    } else {
      diags_.error("E0306", e->span, "a scene output is a function of a signal, as in `rms(acceleration)`, or `modes`");
      return;
    }
    const SignalSpec* sig = findSignal(o.signal);
    if (!sig) {
      std::vector<std::string> names;
      for (const auto& s : sceneSignals()) names.emplace_back(s.name);
      std::string hint = closest(o.signal, names);
      diags_.error("E0218", e->kind == ast::ExprKind::Name ? e->span : e->args[1]->span,
                   fmt::format("scenes have no signal `{}`{}", o.signal,
                               hint.empty() ? fmt::format(" (signals: {})", fmt::join(names, ", "))
                                            : fmt::format("; did you mean `{}`?", hint)));
      return;
    }
    if (sig->scalar != o.function.empty()) {
      diags_.error("E0306", e->span,
                   sig->scalar ? fmt::format("`{}` is a single result; write it bare, as `output {};`", o.signal, o.signal)
                               : fmt::format("`{}` is a time signal; say what to take of it, as in `rms({})`", o.signal, o.signal));
      return;
    }
    if (whole && o.mesh.empty() && (sig->id == Signal::MeshForce || sig->id == Signal::ContactForce))
      diags_.error("E0232", e->span,
                   fmt::format("scene `{}` runs on the whole gearbox: say which mesh, as in `{}({}({}))`", out.name,
                               o.function.empty() ? "peak" : o.function, o.signal,
                               [&] {
                                 for (const auto& st : m.stages)
                                   if (!meshNames(st).empty()) return meshNames(st)[0];
                                 return std::string("stage");
                               }()));
    else if (whole && sig->id != Signal::Modes && sig->id != Signal::MeshForce && sig->id != Signal::ContactForce && sig->id != Signal::OutputSpeed &&
             sig->id != Signal::InputSpeed)
      diags_.error("E0232", e->span,
                   fmt::format("scene `{}` runs on the whole gearbox, whose signals are `contact_force` and `mesh_force` of a mesh, "
                               "`input_speed`, `output_speed` and `modes`; `{}` belongs to a scene on one stage",
                               out.name, o.signal));
    if (sig->id == Signal::Modes && stage && stage->kind && stage->kind->kind != ir::StageKind::Planetary)
      diags_.error("E0232", e->span, "`modes` needs a lumped model: a scene on a planetary stage or on the whole gearbox");
    if (!sig->needsAnyEffect.empty() &&
        std::none_of(sig->needsAnyEffect.begin(), sig->needsAnyEffect.end(), [&](Effect x) { return out.findEffect(x); })) {
      std::vector<std::string> names;
      for (Effect x : sig->needsAnyEffect) names.push_back(effectSpec(x).name);
      diags_.error("E0218", e->span,
                   fmt::format("`{}` exists only with the effect{} {}; scene `{}` does not list {}", o.signal,
                               names.size() > 1 ? "s" : "", fmt::join(names, " or "), out.name, names.size() > 1 ? "either" : "it"));
    }
    for (const auto& x : out.outputs)
      if (x.key() == o.key()) return;
    out.outputs.push_back(o);
  }

  ir::Modify modify(const Stmt& st, const GearboxModel& m, const Scope& gs) {
    ir::Modify out;
    out.stage = st.path.str();
    out.span = st.span;
    const StageModel* stage = m.findStage(out.stage);
    if (!stage) {
      diags_.error("E0232", st.path.span, fmt::format("`modify {}`: gearbox `{}` has no stage `{}`", out.stage, m.name, out.stage));
      return out;
    }
    if (stage->kind && stage->kind->kind != ir::StageKind::Spur && stage->kind->kind != ir::StageKind::Helical) {
      diags_.error("E0232", st.path.span, fmt::format("tooth modification rules apply to spur and helical stages; `{}` is {}", out.stage, stage->kind->name));
      return out;
    }
    std::set<std::string> seen;
    for (const auto& b : st.body) {
      if (b.kind != StmtKind::Assign) {
        notAllowed(b, fmt::format("`modify {}`", out.stage));
        continue;
      }
      ir::ModRule r;
      r.target = b.path.str();
      r.span = b.span;
      r.text = b.value ? ast::print(*b.value) : "";
      std::string gear, what = r.target;
      if (b.path.parts.size() == 2) {
        gear = b.path.parts[0];
        what = b.path.parts[1];
      }
      const auto& targets = modificationTargets();
      bool gearOk = gear.empty() || (stage->kind && isGear(*stage->kind, gear));
      if (b.path.parts.size() > 2 || !gearOk || std::find(targets.begin(), targets.end(), what) == targets.end()) {
        std::string hint = closest(what, targets);
        diags_.error("E0211", b.path.span,
                     fmt::format("`{}` is not a tooth modification{}", r.target,
                                 hint.empty() ? fmt::format(" (modifications: {})", fmt::join(targets, ", "))
                                              : fmt::format("; did you mean `{}`?", hint)));
        continue;
      }
      if (!seen.insert(r.target).second) {
        diags_.error("E0202", b.path.span, fmt::format("duplicate declaration: `{}` already has a rule", r.target));
        continue;
      }
      Scope s = gs;
      s.stage = stage;
      s.context = Scope::Modify;
      s.modifyGear = gear;
      r.value = checker_.check(b.value.get(), s);
      if (r.value->type.kind == Type::PerGear)
        diags_.error("E0306", r.value->span,
                     fmt::format("this value differs between the gears; reduce it with `mean(…)`, `max(…)`, or name the gear "
                                 "(`pinion.…`), or set `pinion.{}` and `wheel.{}` separately",
                                 what, what));
      else if (!r.value->type.isError() && (!r.value->type.isNumber() || r.value->type.dim != units::dims::length))
        diags_.error("E0302", r.value->span,
                     fmt::format("unit mismatch: `{}` is a length (µm or mm), got {}", r.target, describe(r.value->type)));
      missingInputs(*stage, r, b);
      if (b.when) {
        r.when = checker_.check(b.when.get(), s);
        if (!r.when->type.isError() && r.when->type.kind != Type::Bool)
          diags_.error("E0305", r.when->span, fmt::format("`when` needs a condition, but this is {}", describe(r.when->type)));
      }
      // The rating reads the modification (tip relief, crowning): a rule cannot read the rating.
      for (const ir::Expr* e : {r.value.get(), r.when.get()})
        if (e)
          walk(*e, [&](const ir::Expr& x) {
            auto k = x.op == Op::Quantity ? keyOf(lastPart(x.name)) : std::nullopt;
            if (k && isRatingQuantity(*k))
              diags_.error("E0228", x.span,
                           fmt::format("a `modify` rule cannot read `{}`: the rating is computed from the stage's modification, "
                                       "so the rule would be defined in terms of itself",
                                       x.name));
          });
      out.rules.push_back(std::move(r));
    }
    return out;
  }

  // A built-in quantity a rule reads must be given or computable from what the stage
  // gives; say which inputs are missing at check time rather than fail at run time.
  void missingInputs(const StageModel& stage, const ir::ModRule& r, const Stmt& b) {
    if (!r.value || !stage.kind || !r.value->type.isNumber()) return;  // a rule already in error says enough
    auto has = [&](const std::string& a) { return stage.findAttr(a) != nullptr; };
    std::set<std::string> reported;
    walk(*r.value, [&](const ir::Expr& e) {
      if (e.op != Op::Quantity) return;
      std::string rest = e.name.substr(e.name.find('.') + 1);
      std::vector<std::string> names;
      if (e.type.kind == Type::PerGear)
        for (const auto& g : stage.kind->gears) names.push_back(g + "." + rest);
      else
        names.push_back(rest);
      for (const auto& n : names) {
        auto dot = n.find('.');
        std::string gear = dot == std::string::npos ? "" : n.substr(0, dot), q = dot == std::string::npos ? n : n.substr(dot + 1);
        std::string need;
        if (isKey(q, Q::BendingDeflection) && !has(n) && !(has(gear + ".bearing_span") && has(gear + ".shaft_diameter")))
          need = fmt::format("give `{}`, or `{}.bearing_span` and `{}.shaft_diameter` for the beam model", n, gear, gear);
        else if ((isKey(q, Q::PitchDeviation) || isKey(q, Q::ProfileDeviation)) && !gear.empty() && !has(n) && !has("accuracy"))
          need = fmt::format("give `{}`, or the stage's `accuracy` grade for the ISO 1328-1 tolerance", n);
        else if ((isKey(q, Q::TorsionDeflection) || isKey(q, Q::LoadDeflection)) && !has(n) && !has("face_width"))
          need = fmt::format("the stage gives no `face_width`");
        if (need.empty() || !reported.insert(n).second) continue;
        diags_.error("E0233", b.value ? b.value->span : b.span,
                     fmt::format("`{}` needs `{}`, which cannot be computed: {}", r.target, n, need));
      }
    });
  }

  ir::Split split(const Stmt& st, const GearboxModel& m, const Scope& gs) {
    ir::Split out;
    out.name = st.name;
    out.span = st.span;
    std::string owner = fmt::format("split `{}`", st.name);
    std::vector<std::pair<std::string, Binding>> items;
    flatten(st.body, "", owner, items, {"torsion_shaft"});
    if (auto it = m.splitOverrides.find(st.name); it != m.splitOverrides.end())
      for (const auto& [p, b] : it->second)
        replaceOrAdd(items, std::make_pair(p, b), [](const auto& x) { return x.first; });
    out.settings = settings(items, splitSettings(), gs, owner, nameOr(st), "E0225");
    const ir::Setting* install = ir::findSetting(out.settings, Q::Install);
    if (install && install->choice == cat::install::Preloaded && !ir::findSetting(out.settings, Q::PreloadTorque))
      diags_.error("E0225", nameOr(st), fmt::format("{} is installed `preloaded` but gives no `preload_torque`", owner));
    if (!m.hasOperating)
      diags_.error("E0231", nameOr(st), fmt::format("{} needs an operating point, but gearbox `{}` has no `operating` block", owner, m.name));
    return out;
  }

  ir::Study study(const Stmt& st, const GearboxModel& m, const Scope& gs) {
    ir::Study out;
    out.name = st.name;
    out.span = st.span;
    std::string owner = fmt::format("study `{}`", st.name);
    bool sweep = false, wp = false;
    std::vector<std::pair<std::string, const Stmt*>> domains;
    std::vector<std::pair<std::string, Binding>> items;
    for (const auto& b : st.body) {
      switch (b.kind) {
      case StmtKind::Sweep: {
        if (sweep || wp) {
          diags_.error("E0202", b.span, fmt::format("{} already says what it varies; a study has one sweep", owner));
          break;
        }
        sweep = true;
        sweepOf(b, m, gs, owner, out);
        break;
      }
      case StmtKind::Of: {
        if (sweep || wp) {
          diags_.error("E0202", b.span, fmt::format("{} already says what it varies", owner));
          break;
        }
        if (cat::blockOf(b.name) != cat::Block::WorkPrecision) {
          diags_.error("E0224", nameOr(b), fmt::format("unknown study `{} of …`; a study is a `sweep` or `work_precision of SCENE`", b.name));
          break;
        }
        wp = true;
        out.kind = ir::Study::WorkPrecision;
        out.target = b.path.str();
        if (!m.findScene(out.target)) {
          std::vector<std::string> names;
          for (const auto* s : m.scenes) names.push_back(s->name);
          std::string hint = closest(out.target, names);
          diags_.error("E0217", b.path.span,
                       fmt::format("unknown scene `{}`{}", out.target, suggestion(hint)));
        }
        break;
      }
      case StmtKind::Domain: domains.emplace_back(b.path.str(), &b); break;
      case StmtKind::Assign: flattenOne(b, items, owner); break;
      case StmtKind::Output:
        for (const auto& e : b.exprs) {
          auto x = checker_.check(e.get(), gs);
          if (!x->type.isError() && !x->type.isNumber())
            diags_.error("E0306", x->span, fmt::format("a study output must be a number, but this is {}", describe(x->type)));
          out.outputTexts.push_back(e ? ast::print(*e) : "");
          out.outputs.push_back(std::move(x));
        }
        break;
      case StmtKind::Flag:
        if (const auto* f = cat::findFlag(b.name); f && f->id == cat::Flag::Plot) out.plot = true;
        else diags_.error("E0224", nameOr(b), fmt::format("{} has no option `{}` (it takes `plot;`)", owner, b.name));
        break;
      default: notAllowed(b, owner);
      }
    }
    if (!sweep && !wp) diags_.error("E0225", nameOr(st), fmt::format("{} needs `sweep X in a..b step s;` or `work_precision of SCENE;`", owner));
    if (sweep && out.outputs.empty()) diags_.error("E0225", nameOr(st), fmt::format("{} sweeps but has no `output`", owner));
    if (!items.empty()) {
      if (wp)
        for (const auto& [name, b] : items)
          diags_.error("E0214", b.stmt->path.span,
                       fmt::format("`{}` is not a setting of a work-precision study (rtol, harmonics, methods)", name));
      else
        out.settings = settings(items, sweepSettings(), gs, owner, nameOr(st), "E0225");
    }
    checkContinuation(out, owner);
    for (const auto& [name, b] : domains) {
      if (!wp) {
        diags_.error("E0110", b->span, fmt::format("`{} in …` belongs in a work-precision study", name));
        continue;
      }
      const AttrSpec* spec = nullptr;
      for (const auto& s : workPrecisionSettings())
        if (s.name == name) spec = &s;
      if (!spec) {
        diags_.error("E0214", b->path.span, fmt::format("`{}` is not a setting of a work-precision study (rtol, harmonics, methods)", name));
        continue;
      }
      out.settings.push_back(domainSetting(*b, *spec, gs));
    }
    if (wp) checkRuns(out, st, owner);
    return out;
  }

  // `sweep X in a..b step s;`: what is swept and its start, end and step.
  void sweepOf(const Stmt& b, const GearboxModel& m, const Scope& gs, const std::string& owner, ir::Study& out) {
    out.kind = ir::Study::Sweep;
    out.target = b.path.str();
    const AttrSpec* swept = nullptr;
    out.dim = sweepTarget(b.path, m, &swept);
    auto [lo, hi] = checker_.checkRange(b.lo.get(), b.hi.get(), gs);
    auto step = b.step && b.step->kind == ast::ExprKind::Number && !b.step->unit && b.hi && b.hi->unit
                    ? checker_.literal(*b.step, &*b.hi->unit)
                    : checker_.check(b.step.get(), gs);
    // `limit`: a start or an end, which take the swept attribute's limits (a step does not).
    auto bound = [&](ir::ExprPtr x, const char* what, bool limit) -> std::optional<Number> {
      if (x->type.isError()) return std::nullopt;
      if (!x->isConst()) {
        diags_.error("E0410", x->span, fmt::format("the sweep's {} must be a constant", what));
        return std::nullopt;
      }
      if (out.dim && x->type.dim != *out.dim) {
        diags_.error("E0302", x->span,
                     fmt::format("unit mismatch: `{}` is {}, but the sweep's {} is {}", out.target, out.dim->describe(), what,
                                 describe(x->type)));
        return std::nullopt;
      }
      // The values a sweep gives take the swept attribute's own limits (its step is its own).
      if (!limit) return x->value;
      if (swept && swept->positive && x->value.sign() <= 0) {
        diags_.error("E0405", x->span, fmt::format("`{}` must be positive, but the sweep's {} is {}", out.target, what,
                                                   units::showQuantity(x->value, x->type.dim)));
        return std::nullopt;
      }
      if (swept && swept->budget && swept->atMost && x->value.compare(*swept->atMost) > 0) {
        diags_.error("E0411", x->span, fmt::format("the sweep's {} {} is beyond the budget of {} for `{}` ({})", what, x->value.str(),
                                                   swept->atMost->str(), out.target, swept->meaning));
        return std::nullopt;
      }
      return x->value;
    };
    out.lo = bound(std::move(lo), "start", true);
    out.hi = bound(std::move(hi), "end", true);
    out.step = bound(std::move(step), "step", false);
    // A sweep may run downwards (a down-sweep follows the upper branch of a jump).
    if (out.lo && out.hi && out.lo->compare(*out.hi) == 0)
      diags_.error("E0401", b.span, fmt::format("empty sweep: it starts and ends at {}", units::showQuantity(*out.lo, *out.dim)));
    if (out.step && out.step->sign() <= 0) diags_.error("E0407", b.step->span, "the sweep's step must be positive");
    else if (out.lo && out.hi && out.step) {
      double points = std::fabs(out.hi->toDouble() - out.lo->toDouble()) / out.step->toDouble() + 1;
      if (!(points <= static_cast<double>(cat::budget::kSweepPoints)))
        diags_.error("E0411", b.step->span,
                     fmt::format("{}: the sweep from {} to {} in steps of {} is {:.3g} points, beyond the budget of {} points "
                                 "per sweep; take a larger step",
                                 owner, units::showQuantity(*out.lo, *out.dim), units::showQuantity(*out.hi, *out.dim),
                                 units::showQuantity(*out.step, *out.dim), points, cat::budget::kSweepPoints));
    }
  }

  // Arclength continuation follows one scene's orbit: its outputs must read exactly one.
  void checkContinuation(const ir::Study& out, const std::string& owner) {
    if (const auto* c = ir::findSetting(out.settings, Q::Continuation); c && c->choice == cat::continuation::Arclength) {
      std::set<std::string> scenes;
      std::function<void(const ir::Expr&)> visit = [&](const ir::Expr& e) {
        if (e.op == ir::Op::SceneOutput) scenes.insert(e.name.substr(0, e.name.find('.')));
        for (const auto& a : e.args)
          if (a) visit(*a);
      };
      for (const auto& o : out.outputs)
        if (o) visit(*o);
      if (scenes.size() != 1)
        diags_.error("E0225", c->span,
                     scenes.empty() ? fmt::format("{}: `continuation = arclength` follows a scene's periodic response, but no output reads a scene", owner)
                                    : fmt::format("{}: `continuation = arclength` follows one scene's periodic response; the outputs read {} "
                                                  "scenes ({}): give each its own study",
                                                  owner, scenes.size(), fmt::join(scenes, ", ")));
    }
  }

  // The runs a work-precision study makes against their budget.
  void checkRuns(const ir::Study& out, const Stmt& st, const std::string& owner) {
    // Runs as the study makes them: per harmonic count, a reference and its check, then
    // every method at every tolerance (8 tolerances when none are listed).
    double harmonics = 1, methods = 1, rtols = 8;
    for (const auto& set : out.settings) {
      double n = !set.symbol.empty() ? static_cast<double>(std::count(set.symbol.begin(), set.symbol.end(), ',') + 1)
                 : !set.members.empty() ? static_cast<double>(set.members.size())
                 : set.lo && set.hi ? std::max(1.0, std::floor(set.hi->toDouble() - set.lo->toDouble()) + 1)
                                    : 1;
      (set.key == Q::Harmonics ? harmonics : set.key == Q::Methods ? methods : rtols) = n;
    }
    double runs = harmonics * (2 + methods * rtols);
    if (!(runs <= static_cast<double>(cat::budget::kWorkPrecisionRuns)))
      diags_.error("E0411", nameOr(st),
                   fmt::format("{} asks for {:.0f} runs of its scene, beyond the budget of {} runs per work-precision study; "
                               "list fewer tolerances, harmonic counts or methods",
                               owner, runs, cat::budget::kWorkPrecisionRuns));
  }

  // E0411 when a constant is beyond its row's size budget (catalogue/Budgets.h).
  bool beyondBudget(const AttrSpec& spec, const std::string& name, const ir::Expr& x) {
    if (!spec.budget || !spec.atMost || x.value.compare(*spec.atMost) <= 0) return false;
    diags_.error("E0411", x.span,
                 fmt::format("`{}` = {} is beyond its budget of {} ({}); a larger value cannot be answered in bounded time and memory",
                             name, x.value.str(), spec.atMost->str(), spec.meaning));
    return true;
  }

  // Times in mesh periods and the samples they record, against their budgets; times in
  // seconds are measured against a design's mesh period at run time.
  void sceneBudgets(const ir::Scene& sc, const std::string& owner) {
    const ir::Setting* samples = ir::findSetting(sc.settings, "samples");
    double perPeriod = samples && samples->value ? samples->value->toDouble() : 160;
    for (const char* name : {"settle", "record", "duration", "ramp"}) {
      const ir::Setting* t = ir::findSetting(sc.settings, name);
      if (!t || !t->value || !t->meshPeriods) continue;
      double periods = t->value->toDouble();
      if (!(periods <= static_cast<double>(cat::budget::kMeshPeriods))) {
        diags_.error("E0411", t->span,
                     fmt::format("{}: `{}` = {} mesh periods is beyond the budget of {} mesh periods", owner, name, t->value->str(),
                                 cat::budget::kMeshPeriods));
        continue;
      }
      bool recorded = isKey(name, Q::Record) || isKey(name, Q::Duration);
      if (recorded && !(periods * perPeriod <= static_cast<double>(cat::budget::kRecordedSamples)))
        diags_.error("E0411", t->span,
                     fmt::format("{}: recording {} mesh periods at {} samples each is {:.3g} samples, beyond the budget of {} "
                                 "recorded samples; record fewer periods or fewer samples",
                                 owner, t->value->str(), perPeriod, periods * perPeriod, cat::budget::kRecordedSamples));
    }
  }

  ir::Setting domainSetting(const Stmt& b, const AttrSpec& spec, const Scope& gs) {
    ir::Setting s;
    s.name = spec.name;
    s.key = spec.key != Q::None ? spec.key : cat::keyOf(spec.name).value_or(Q::None);
    s.dim = spec.dim;
    s.integer = spec.integer;
    s.span = b.span;
    auto number = [&](ir::ExprPtr x) -> std::optional<Number> {
      if (x->type.isError()) return std::nullopt;
      if (!x->isConst() || !x->type.isNumber() || x->type.dim != spec.dim) {
        diags_.error("E0302", x->span, fmt::format("`{}` takes constants that are {}", spec.name, spec.dim.describe()));
        return std::nullopt;
      }
      if (spec.integer && !(x->value.isRational() && x->value.rational().isInteger())) {
        diags_.error("E0403", x->span, fmt::format("`{}` takes whole numbers", spec.name));
        return std::nullopt;
      }
      if (spec.positive && x->value.sign() <= 0) {
        diags_.error("E0405", x->span, fmt::format("`{}` must be positive", spec.name));
        return std::nullopt;
      }
      if (beyondBudget(spec, spec.name, *x)) return std::nullopt;
      return x->value;
    };
    if (spec.value == ValueKind::Symbol) {
      if (b.domain != ast::DomainKind::Set) {
        diags_.error("E0406", b.span, fmt::format("`{}` takes a set of words, as in `{{rk8pd, rkf45}}`", spec.name));
        return s;
      }
      for (const auto& e : b.exprs) {
        if (!e || e->kind != ast::ExprKind::Name ||
            std::find(spec.symbols.begin(), spec.symbols.end(), e->text) == spec.symbols.end()) {
          diags_.error("E0406", e ? e->span : b.span, fmt::format("`{}` takes {}", spec.name, fmt::join(spec.symbols, ", ")));
          continue;
        }
        s.symbol += (s.symbol.empty() ? "" : ",") + e->text;
      }
      return s;
    }
    if (b.domain == ast::DomainKind::Range) {
      auto [lo, hi] = checker_.checkRange(b.lo.get(), b.hi.get(), gs);
      s.lo = number(std::move(lo));
      s.hi = number(std::move(hi));
      if (s.lo && s.hi && s.lo->compare(*s.hi) > 0) diags_.error("E0401", b.span, fmt::format("empty range for `{}`", spec.name));
      return s;
    }
    if (b.domain == ast::DomainKind::Set)
      for (const auto& e : b.exprs)
        if (auto v = number(checker_.check(e.get(), gs))) s.members.push_back(*v);
    return s;
  }

  std::optional<units::Dim> sweepTarget(const ast::Path& p, const GearboxModel& m, const AttrSpec** spec = nullptr) {
    const auto& parts = p.parts;
    auto found = [&](const AttrSpec& a) {
      if (spec) *spec = &a;
      return std::optional<units::Dim>(a.dim);
    };
    if (parts.size() == 1) {
      for (const auto& o : operatingSettings())
        if (o.name == parts[0]) {
          if (!m.hasOperating)
            diags_.error("E0231", p.span, fmt::format("sweeping `{}` needs an `operating` block to vary", parts[0]));
          return found(o);
        }
    } else if (const StageModel* st = m.findStage(parts[0]); st && st->kind) {
      std::string rest = p.str().substr(parts[0].size() + 1);
      if (const auto* a = findAttr(*st->kind, rest); a && a->role != AttrRole::Derived && a->value == ValueKind::Number) return found(*a);
      // A tooth modification of a spur or helical stage (`hs.tip_relief`, `hs.pinion.lead_crowning`):
      // the sweep's value replaces what the stage's `modify` rules give.
      std::string what = parts.back();
      bool gearOk = parts.size() == 2 || (parts.size() == 3 && isGear(*st->kind, parts[1]));
      if (gearOk && (isKey(what, Q::TipRelief) || isKey(what, Q::TipReliefHeight) || isKey(what, Q::LeadCrowning)) &&
          (st->kind->kind == ir::StageKind::Spur || st->kind->kind == ir::StageKind::Helical))
        return units::dims::length;
    } else if (m.findSplit(parts[0])) {
      std::string rest = p.str().substr(parts[0].size() + 1);
      for (const auto& s : splitSettings())
        if (s.name == rest && s.value == ValueKind::Number) return found(s);
    } else if (const ast::Stmt* sc = m.findScene(parts[0]); sc && parts.size() == 3) {
      // An effect parameter of a scene: `vibration.damping.ratio`.
      bool listed = false;
      for (const auto& b : sc->body)
        if (b.kind == StmtKind::Effects)
          for (const auto& e : b.body) listed = listed || e.name == parts[1];
      const EffectSpec* fx = findEffect(parts[1]);
      if (fx && !listed) {
        diags_.error("E0219", p.span, fmt::format("scene `{}` does not list the effect `{}`, so it has no `{}` to sweep", parts[0], parts[1], parts[2]));
        return std::nullopt;
      }
      if (fx)
        for (const auto& prm : fx->params)
          if (prm.name == parts[2] && prm.value == ValueKind::Number) return found(prm);
    }
    diags_.error("E0219", p.span,
                 fmt::format("cannot sweep `{}`: a sweep varies an operating value, a stage attribute or a split setting",
                             p.str()));
    return std::nullopt;
  }

  ir::Report report(const Stmt& st, const Scope& gs) {
    ir::Report r;
    r.span = st.span;
    for (const auto& b : st.body) {
      switch (b.kind) {
      case StmtKind::Top: {
        auto x = checker_.check(b.value.get(), gs);
        if (x->type.isError()) break;
        if (!x->isConst() || !x->type.dim.dimensionless() || !x->value.isRational() || !x->value.rational().isInteger() ||
            x->value.sign() <= 0)
          diags_.error("E0403", x->span, "`top` takes a positive whole number");
        else
          r.top = static_cast<long long>(x->value.rational().num());
        break;
      }
      case StmtKind::Sort: {
        auto x = checker_.check(b.value.get(), gs);
        if (!x->type.isError() && !x->type.isNumber())
          diags_.error("E0306", x->span, fmt::format("`sort by` needs a number, but this is {}", describe(x->type)));
        r.sortBy = std::move(x);
        break;
      }
      case StmtKind::Flag:
        if (const auto* f = cat::findFlag(b.name); f && f->id == cat::Flag::Ranges) r.ranges = true;
        else diags_.error("E0224", nameOr(b), fmt::format("`report` has no option `{}` (it takes `ranges;`)", b.name));
        break;
      case StmtKind::Columns:
        for (const auto& e : b.exprs) {
          auto x = checker_.check(e.get(), gs);
          if (!x->type.isError() && !x->type.isNumber() && x->type.kind != Type::Interval)
            diags_.error("E0306", x->span, fmt::format("a report column must be a number, but this is {}", describe(x->type)));
          r.columnTexts.push_back(e ? ast::print(*e) : "");
          r.columns.push_back(std::move(x));
        }
        break;
      default: notAllowed(b, "`report`");
      }
    }
    return r;
  }

  const std::map<std::string, ir::ExprPtr>* lets_ = nullptr;  // the lets being built, by key
  std::map<std::string, int> letSense_;  // the direction each let reading `worst` was used in (0: both)
  std::set<std::pair<std::string, std::string>> misspelt_;  // (stage, attribute) a reported misspelling meant
  diag::DiagnosticEngine& diags_;
  Globals globals_;
  ExprChecker checker_;
  std::map<std::string, std::unique_ptr<GearboxModel>> models_;
};

} // namespace

ir::Program analyse(const LoadedProgram& program, diag::DiagnosticEngine& diags) {
  Analyser a(diags);
  return a.run(program);
}

} // namespace gbx::sema
