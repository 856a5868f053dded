#include "sema/Analyser.h"

#include <set>

// Gearbox models (extends, presets, like) and their stages and attributes in the IR.

namespace gbx::sema {

StageModel Analyser::makeStage(const Stmt& st) {
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
      else if (b.path.parts.size() == 2 && m.kind && cat::gearIndex(*m.kind, b.path.parts[0]) >= 0)
        gearBlock(m, b, seen);
      else
        diags_.error(
            "E0224", nameOr(b),
            fmt::format("stage `{}` has no block `{}` (its blocks are `{}` and a gear's, as `ring.cutter {{ … }}`)",
                        st.name, b.name, kRatingBlock));
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

// A value as the user wrote it (`0 um`), for messages; an expression by its value in the
// display unit.
std::string Analyser::asWritten(const ast::Expr* v, const ir::Expr& x) {
  if (v && v->kind == ast::ExprKind::Number) return ast::print(*v);
  if (v && v->kind == ast::ExprKind::Neg && !v->args.empty() && v->args[0] && v->args[0]->kind == ast::ExprKind::Number)
    return "-" + ast::print(*v->args[0]);
  return units::showQuantity(x.value, x.type.dim);
}

// A value beyond the limits the catalogue row sets (E0405); `v` as written, where known.
bool Analyser::outsideLimits(const AttrSpec& spec, const std::string& name, const ir::Expr& x, const ast::Expr* v) {
  if (!((spec.atLeast && x.value.compare(*spec.atLeast) < 0) || (spec.atMost && x.value.compare(*spec.atMost) > 0)))
    return false;
  std::string range = spec.atLeast && spec.atMost && spec.atLeast->compare(*spec.atMost) == 0 ? units::showQuantity(*spec.atLeast, spec.dim)
                      : spec.atLeast && spec.atMost ? fmt::format("between {} and {}", units::showQuantity(*spec.atLeast, spec.dim),
                                                                units::showQuantity(*spec.atMost, spec.dim))
                      : spec.atLeast ? fmt::format("at least {}", units::showQuantity(*spec.atLeast, spec.dim))
                                     : fmt::format("at most {}", units::showQuantity(*spec.atMost, spec.dim));
  diags_.error("E0405", x.span, fmt::format("`{}` must be {} ({}), got {}", name, range, spec.meaning, asWritten(v, x)));
  return true;
}

void Analyser::dupInBlock(std::map<std::string, const Stmt*>& seen, const Stmt& st, const char* what) {
  auto key = std::string(what) + ":" + st.name;
  if (auto it = seen.find(key); it != seen.end()) {
    auto& d = diags_.error("E0202", nameOr(st), fmt::format("duplicate declaration: {} `{}` is already declared in this gearbox", what, st.name));
    d.notes.push_back({nameOr(*it->second), "first declared here"});
  }
  seen[key] = &st;
}

const GearboxModel* Analyser::build(const std::string& name, std::vector<std::string>& stack) {
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
std::vector<const Stmt*> Analyser::stagesOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen) {
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
void Analyser::resolveLike(GearboxModel& model, const Stmt& st, const std::vector<const Stmt*>& likes, std::set<std::string>& resolving, const std::string& name) {
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
void Analyser::statementsOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen, const std::string& name, const std::string& origin) {
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
    case StmtKind::Member:
      if (st.word != "shaft") {
        diags_.error("E0111", st.wordSpan, fmt::format("`{} {} {{ … }}` is not a gearbox member; a gearbox holds `shaft NAME {{ … }}`", st.word, st.name));
        break;
      }
      dupInBlock(seen, st, "shaft");
      replaceOrAdd(model.shafts, &st, [](const Stmt* s) { return s->name; });
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
    case StmtKind::Block: {
      if (cat::blockOf(st.name) != cat::Block::Tolerances) {
        notAllowed(st, fmt::format("gearbox `{}`", name));
        break;
      }
      if (seen.count("tolerances")) diags_.error("E0202", st.span, "duplicate declaration: this gearbox already has a `tolerances` block");
      seen["tolerances"] = &st;
      // A variant's line replaces the baseline's line for the same quantity; a setting given
      // twice in one block is an error.
      std::set<std::string> setHere;
      for (const auto& t : st.body) {
        if (t.kind == StmtKind::Assign && t.path.parts.size() == 1) {
          if (!setHere.insert(t.path.str()).second) {
            diags_.error("E0202", t.path.span,
                         fmt::format("duplicate declaration: `{}` is already set in this `tolerances` block", t.path.str()));
            continue;
          }
          replaceOrAdd(model.toleranceSettings, &t, [](const Stmt* x) { return x->path.str(); });
          continue;
        }
        if (t.kind != StmtKind::Scatter) {
          notAllowed(t, "`tolerances` (it lists `stage.attribute +- amount;`, and for Monte Carlo `samples = N;`)");
          continue;
        }
        replaceOrAdd(model.tolerances, &t, [](const Stmt* x) { return x->path.str(); });
      }
      break;
    }
    default: notAllowed(st, fmt::format("gearbox `{}`", name));
    }
  }
}

void Analyser::override(GearboxModel& m, const Stmt& st, const std::string& origin) {
  const auto& parts = st.path.parts;
  if (parts.empty()) return;
  if (StageModel* stage = m.findStage(parts[0])) {
    if (parts.size() == 1) {
      diags_.error("E0211", st.path.span, fmt::format("`{}` is a stage; set one of its attributes, as in `{}.face_width = …`", parts[0], parts[0]));
      return;
    }
    std::string rest = st.path.str().substr(parts[0].size() + 1);
    stage->setAttr(rest, {&st, origin});
    // A variant may rate a stage its base does not: `upper.rating.life = …` and the rest.
    if (parts.size() > 2 && parts[1] == kRatingBlock && stage->kind && rateable(*stage->kind)) stage->rated = true;
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

// E0211: no such attribute of the stage's kind, with the name it was likely meant to be.
void Analyser::unknownAttribute(const StageModel& st, const std::string& path, Span where) {
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
std::optional<Number> Analyser::boundOf(const AttrSpec& spec, const std::string& path, bool tooth, ir::ExprPtr x) {
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
    // A bare number: show it with the usual unit.
    auto unit = units::displayUnitFor(spec.dim);
    std::string fix = x->type.dim.dimensionless() && !unit.name.empty()
                          ? fmt::format("; write it with a unit, as `{} {}`", x->value.str(), spec.unitHint.empty() ? unit.name : spec.unitHint)
                          : "";
    diags_.error("E0302", x->span,
                 fmt::format("unit mismatch: `{}` needs {}, got {}{}", path, spec.dim.describe(), describe(x->type), fix));
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

// A domain's bounds (`in lo..hi`) or members (`in {…}`, a named set): constants in the
// setting's unit, checked against its limits; members sorted.
Analyser::Domain Analyser::domain(const AttrSpec& spec, const std::string& path, const Stmt& s, const Scope& scope,
                                  bool tooth) {
  Domain d;
  auto checkBound = [&](ir::ExprPtr x) { return boundOf(spec, path, tooth, std::move(x)); };
  if (s.domain == ast::DomainKind::Range) {
    auto [lo, hi] = checker_.checkRange(s.lo.get(), s.hi.get(), scope);
    Span span = source::cover(lo->span, hi->span);
    // Both bounds bare numbers where a quantity with a unit belongs: one error, with the fix.
    auto bare = [&](const ir::ExprPtr& x) { return x->isConst() && x->type.isNumber() && x->type.dim.dimensionless(); };
    if (!spec.dim.dimensionless() && bare(lo) && bare(hi)) {
      auto unit = units::displayUnitFor(spec.dim);
      diags_.error("E0302", span,
                   fmt::format("unit mismatch: `{}` needs {}, got plain numbers{}", path, spec.dim.describe(),
                               unit.name.empty()
                                   ? ""
                                   : fmt::format("; write the range with a unit, as `{}..{} {}`", lo->value.str(),
                                                 hi->value.str(), spec.unitHint.empty() ? unit.name : spec.unitHint)));
      return d;
    }
    d.lo = checkBound(std::move(lo));
    d.hi = checkBound(std::move(hi));
    if (d.lo && d.hi && d.lo->compare(*d.hi) > 0) {
      diags_.error("E0401", span,
                   fmt::format("empty range for `{}`: {} is above {}", path, units::showQuantity(*d.lo, spec.dim),
                               units::showQuantity(*d.hi, spec.dim)));
    } else if (d.lo && d.hi && spec.integer) {
      // Every value of a decision range is listed: its size is a budget (counted exactly:
      // bounds near 2^80 are one double apart).
      units::Number width = d.hi->sub(*d.lo);
      double values = width.toDouble() + 1;
      if (width.compare(units::Number::exact(units::Rational(cat::budget::kDomainValues - 1))) > 0) {
        diags_.error(
            "E0411", span,
            fmt::format("`{}` in {}..{} holds {:.0f} values, beyond the budget of {} a search lists per decision; "
                        "narrow the range",
                        path, d.lo->str(), d.hi->str(), values, cat::budget::kDomainValues));
      }
    }
    return d;
  }
  std::vector<ir::ExprPtr> members;
  std::vector<std::string> texts;  // literals as written, for reports
  Span span = s.span;
  if (s.domain == ast::DomainKind::Named) {
    auto v = checker_.check(s.value.get(), scope);
    if (v->type.isError()) return d;
    if (v->op != Op::Set) {
      diags_.error("E0306", v->span, fmt::format("`{}` must be a set `{{…}}` to serve as a domain", ast::print(*s.value)));
      return d;
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
    d.members.push_back(v);
    written = written && !t.empty();
  }
  if (written)
    for (const auto& [v, t] : checked)
      d.memberTexts.push_back(t);
  return d;
}

ir::Attribute Analyser::attribute(const StageModel& st, const std::string& path, const Binding& b, const Scope& scope) {
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
    diags_.error(
        "E0212", where,
        fmt::format("`{}` is derived ({}) and cannot be set; constrain it with `require`", path, spec->meaning));
    return a;
  }
  bool tooth = isKey(lastPart(path), Q::Z);
  if (s.kind == StmtKind::Assign) {
    a.role = ir::Attribute::Fixed;
    ir::Setting v = setting(path, b, *spec, scope, fmt::format("stage `{}`", st.name));
    a.value = std::move(v.expr);
    a.symbol = v.symbol;
    a.sceneRef = v.sceneRef;
    return a;
  }
  // A domain: bounds are constants in the attribute's unit.
  if (spec->value != ValueKind::Number) {
    diags_.error("E0110", where, fmt::format("`{}` takes one value (`=`), not a domain", path));
    return a;
  }
  a.role = spec->integer ? ir::Attribute::Decision : ir::Attribute::Freedom;
  Domain d = domain(*spec, path, s, scope, tooth);
  a.lo = std::move(d.lo);
  a.hi = std::move(d.hi);
  a.members = std::move(d.members);
  a.memberTexts = std::move(d.memberTexts);
  return a;
}

ir::Stage Analyser::stage(const StageModel& st, const Scope& gbScope) {
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
  // A shaft carrying one of its gears without its own `life.viscosity` reads the stage's oil.
  bool bearingsReadOil = false;
  if (gbScope.gearbox)
    for (const ast::Stmt* sh : gbScope.gearbox->shafts) {
      bool own = false, carries = false;
      for (const auto& b : sh->body) {
        if (b.kind == ast::StmtKind::Placed && b.name == "gear" && !b.path.parts.empty() && b.path.parts[0] == st.name)
          carries = true;
        if ((b.kind == ast::StmtKind::Block && b.name == "life" &&
             std::any_of(b.body.begin(), b.body.end(), [](const ast::Stmt& x) { return x.path.str() == "viscosity"; })) ||
            (b.kind == ast::StmtKind::Assign && b.path.str() == "life.viscosity"))
          own = true;
      }
      bearingsReadOil = bearingsReadOil || (carries && !own);
    }
  // A planet bearing's modified life reads the stage's oil too.
  if (st.kind->kind == ir::StageKind::Planetary &&
      st.findAttr(st.kind->gears[cat::gear::Planet] + ".bearing.pitch_diameter"))
    bearingsReadOil = true;
  if (st.rated) ratingInputs(st, where, bearingsReadOil);
  out.spectrum = spectrumBins(st);
  return out;
}

} // namespace gbx::sema
