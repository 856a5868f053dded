#include "sema/Analyser.h"

// A gearbox model lowered to the IR, part by part.

namespace gbx::sema {

// A stage's rules from its baseline's block and its own, one rule per target: a later rule
// for a target replaces the earlier one (as a `tolerances` line does).
void Analyser::mergeModify(std::vector<ir::Modify>& modifies, ir::Modify built) {
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

ir::Gearbox Analyser::lowerGearbox(const GearboxModel& m) {
  ir::Gearbox g;
  g.name = m.name;
  g.baseline = m.base;
  g.span = m.decl->span;
  Scope gs;
  gs.gearbox = &m;
  gs.hasBaseline = !m.base.empty();
  gs.hasTolerances = !m.tolerances.empty();
  auto sampling = toleranceSettings(m, gs);
  g.toleranceSettings = std::move(sampling.settings);
  // A misspelt setting (E0214 already) counts as the samples it meant: no cascade of
  // "add `samples`" errors after it.
  gs.hasSamples = gs.hasTolerances && (ir::findSetting(g.toleranceSettings, Q::Samples) || sampling.misspelt);
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
  for (const auto* sh : m.shafts) g.shafts.push_back(shaft(*sh, m, gs));
  for (const auto* sd : m.studies) g.studies.push_back(study(*sd, m, gs));
  if (m.report) g.report = report(*m.report, gs);

  if (!m.hasOperating) requireOperating(g);
  requireMaterial(g, m);
  requireRating(g, m);
  thicknessAllowances(g, m);
  sceneFactors(g);
  planetaryGears(g);
  if (!m.hasOperating)
    for (const auto& st : m.stages)
      if (st.rated)
        diags_.error("E0231", st.decl ? nameOr(*st.decl) : Span{},
                     fmt::format("stage `{}` is rated, but gearbox `{}` has no `operating` block (the rating needs the load and speed)", st.name, g.name));
  return g;
}

} // namespace gbx::sema
