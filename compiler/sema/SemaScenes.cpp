#include "sema/Analyser.h"

// Scenes (effects, outputs, budgets), tooth modifications and power splits.

namespace gbx::sema {

std::vector<std::string> Analyser::interchangeable(const Stmt& st, const GearboxModel& m) {
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

// `steady_state` and `harmonics`: what the periodic steady state refuses beside it and needs.
void Analyser::steadyStateRules(const ir::Scene& out, const Stmt& st, const std::string& owner) {
  const ir::Setting* steady = ir::findSetting(out.settings, "steady_state");
  if (steady && steady->choice < 0) return; // a word the setting does not take: said already
  if (steady) {
    const std::string written = "steady_state = " + steady->symbol;
    for (const char* other : {"settle", "duration", "ramp"})
      if (const auto* s = ir::findSetting(out.settings, other))
        diags_.error("E0202", s->span,
                     fmt::format("{} asks for the periodic steady state (`{}`), which has no `{}`: the periodic "
                                 "response is found directly; drop one of the two",
                                 owner, written, other));
    if (!ir::findSetting(out.settings, "record"))
      diags_.error("E0225", nameOr(st),
                   fmt::format("{} needs `record` (the steady-state window) with `{}`", owner, written));
  }
  if (const ir::Setting* h = ir::findSetting(out.settings, "harmonics")) {
    if (!steady || steady->choice != cat::kSteadyHarmonicBalance)
      diags_.error(
          "E0225", h->span,
          fmt::format(
              "{}: `harmonics` is the harmonic-balance orbit's number of harmonics, which needs `steady_state = "
              "harmonic_balance` (a stiffness series' harmonics go in `varying_stiffness {{ harmonics = …; }}`)",
              owner));
  }
}

ir::Scene Analyser::scene(const Stmt& st, const GearboxModel& m, const Scope& gs) {
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
  steadyStateRules(out, st, owner);
  // A loaded mesh whose outputs all read its static transmission error or its stiffness runs no
  // dynamics.
  const bool staticOnly =
      stage && out.findEffect(Effect::LoadedMesh) && !out.outputs.empty() &&
      std::all_of(out.outputs.begin(), out.outputs.end(), [](const ir::SceneOutput& o) {
        return isSignal(o, cat::Signal::StaticTransmissionError) || isSignal(o, cat::Signal::Stiffness);
      });
  if (!staticOnly && !ir::findSetting(out.settings, "duration") && !ir::findSetting(out.settings, "record"))
    diags_.error("E0225", nameOr(st),
                 fmt::format("{} needs `duration` (a run from rest) or `record` (a steady-state window){}", owner,
                             out.findEffect(Effect::LoadedMesh)
                                 ? ", unless every output reads `static_transmission_error` or `stiffness`"
                                 : ""));
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

void Analyser::flattenOne(const Stmt& b, std::vector<std::pair<std::string, Binding>>& items, const std::string& owner) {
  std::string p = b.path.str();
  for (const auto& [q, x] : items)
    if (q == p) {
      auto& d = diags_.error("E0202", b.path.span, fmt::format("duplicate declaration: `{}` is already set in {}", p, owner));
      d.notes.push_back({x.stmt->path.span, "first set here"});
      return;
    }
  items.emplace_back(p, Binding{&b, owner});
}

void Analyser::effects(const Stmt& block, ir::Scene& out, const Scope& gs) {
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
    // A parameter is a number of the scene: a constant, or arithmetic over the effect's own
    // words (`damping = 0.01 * stiffness`); a quantity of the design has no value there.
    for (const auto& p : fx.params) {
      if (p.value || !p.expr) continue;
      const ir::Expr* other = nullptr;
      walk(*p.expr, [&](const ir::Expr& x) {
        bool arithmetic = x.op == Op::Const || x.op == Op::Symbol || x.op == Op::Neg || x.op == Op::Add || x.op == Op::Sub ||
                          x.op == Op::Mul || x.op == Op::Div;
        if (!arithmetic && !other) other = &x;
      });
      if (other)
        diags_.error("E0410", other->span,
                     fmt::format("{}: `{}` must be a constant{}; a quantity of the design has no value inside a scene's effect",
                                 owner, p.name,
                                 spec->locals.empty() ? std::string()
                                                      : fmt::format(" or arithmetic over `{}`", fmt::join(spec->locals, "`, `"))));
    }
    if (spec->id == Effect::Damping) {
      bool r = ir::findSetting(fx.params, "ratio"), c = ir::findSetting(fx.params, "coefficient");
      if (!r && !c) diags_.error("E0215", nameOr(e), "effect `damping` needs `ratio` (zeta) or `coefficient` (c)");
      if (r && c) diags_.error("E0214", nameOr(e), "effect `damping` takes `ratio` or `coefficient`, not both");
    }
    out.effects.push_back(std::move(fx));
  }
}

// `a.b.c` of a name or member chain; "" for anything else.
std::string Analyser::dotted(const ast::Expr* e) {
  if (!e) return "";
  if (e->kind == ast::ExprKind::Name) return e->text;
  if (e->kind == ast::ExprKind::Member && !e->args.empty()) {
    std::string head = dotted(e->args[0].get());
    return head.empty() ? "" : head + "." + e->text;
  }
  return "";
}

// The meshes a whole-gearbox scene names by stage (docs/dynamics.md).
std::vector<std::string> Analyser::meshNames(const StageModel& st) {
  if (!st.kind) return {};
  switch (st.kind->kind) {
  case ir::StageKind::Planetary: return {st.name + ".sun_planet", st.name + ".ring_planet"};
  case ir::StageKind::Idler: return {st.name + ".driver_idler", st.name + ".idler_driven"};
  case ir::StageKind::Spur:
  case ir::StageKind::Helical: return {st.name};
  default: return {};
  }
}

// The mesh order of `harmonic(x, k)` and `level(x, k)`: a whole constant from 1, where the
// function takes one; 0 where it takes none or leaves it out. Empty after an error.
std::optional<int> Analyser::orderArgument(const SignalFnSpec& fn, const ast::Expr* k, Span span,
                                           const std::string& signal) {
  if (!k) {
    if (fn.order != OrderArg::Required) return 0;
    diags_.error("E0221", span,
                 fmt::format("`{}` takes a signal and a mesh order, as in `{}({}, 1)`", fn.name, fn.name, signal));
    return std::nullopt;
  }
  if (fn.order == OrderArg::None) {
    diags_.error("E0221", k->span, fmt::format("`{}` takes one signal, as in `{}({})`", fn.name, fn.name, signal));
    return std::nullopt;
  }
  double v = k->kind == ast::ExprKind::Number && !k->unit ? std::strtod(k->text.c_str(), nullptr) : 0.0;
  if (!(v >= 1 && v <= 1000 && v == std::floor(v))) {
    diags_.error("E0306", k->span,
                 fmt::format("the mesh order of `{}` is a whole number from 1 to 1000, as in `{}({}, 2)`", fn.name,
                             fn.name, signal));
    return std::nullopt;
  }
  return static_cast<int>(v);
}

void Analyser::sceneOutput(const ast::Expr* e, ir::Scene& out, const StageModel* stage, const GearboxModel& m, bool whole) {
  if (!e) return;
  ir::SceneOutput o;
  o.span = e->span;
  const ast::Expr* inner =
      e->kind == ast::ExprKind::Call && (e->args.size() == 2 || e->args.size() == 3) ? e->args[1].get() : nullptr;
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
    if (auto k = orderArgument(*findSignalFn(o.function), e->args.size() == 3 ? e->args[2].get() : nullptr, e->span,
                               o.signal))
      o.order = *k;
    else
      return;
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
  } else if (e->kind == ast::ExprKind::Call && (e->args.size() == 2 || e->args.size() == 3) && e->args[0] &&
             e->args[0]->kind == ast::ExprKind::Name && e->args[1] && e->args[1]->kind == ast::ExprKind::Name) {
    o.function = e->args[0]->text;
    o.signal = e->args[1]->text;
    const SignalFnSpec* fn = findSignalFn(o.function);
    if (!fn) {
      diags_.error("E0220", e->args[0]->span,
                   fmt::format("`{}` is not a scene result function ({})", o.function, signalFnList()));
      return;
    }
    if (auto k = orderArgument(*fn, e->args.size() == 3 ? e->args[2].get() : nullptr, e->span, o.signal))
      o.order = *k;
    else
      return;
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

ir::Modify Analyser::modify(const Stmt& st, const GearboxModel& m, const Scope& gs) {
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
void Analyser::missingInputs(const StageModel& stage, const ir::ModRule& r, const Stmt& b) {
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

ir::Split Analyser::split(const Stmt& st, const GearboxModel& m, const Scope& gs) {
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

// E0411 when a constant is beyond its row's size budget (catalogue/Budgets.h).
bool Analyser::beyondBudget(const AttrSpec& spec, const std::string& name, const ir::Expr& x) {
  if (!spec.budget || !spec.atMost || x.value.compare(*spec.atMost) <= 0) return false;
  diags_.error("E0411", x.span,
               fmt::format("`{}` = {} is beyond its budget of {} ({}); a larger value cannot be answered in bounded time and memory",
                           name, x.value.str(), spec.atMost->str(), spec.meaning));
  return true;
}

// Times in mesh periods and the samples they record, against their budgets; times in
// seconds are measured against a design's mesh period at run time.
void Analyser::sceneBudgets(const ir::Scene& sc, const std::string& owner) {
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

} // namespace gbx::sema
