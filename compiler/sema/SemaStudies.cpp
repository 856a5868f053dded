#include "sema/Analyser.h"

// Studies (sweeps, work-precision, continuation) and the report block.

namespace gbx::sema {

ir::Study Analyser::study(const Stmt& st, const GearboxModel& m, const Scope& gs) {
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
    if (sweep) {
      seriesOf(*b, m, gs, owner, out);
      continue;
    }
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

// `Y in {a, b, …};` beside a sweep: the sweep once per value, a line each on its plot.
void Analyser::seriesOf(const Stmt& b, const GearboxModel& m, const Scope& gs, const std::string& owner,
                        ir::Study& out) {
  if (out.series) {
    diags_.error("E0202", b.span,
                 fmt::format("{} already draws a line per value of `{}`; a sweep takes one such set", owner,
                             out.series->target));
    return;
  }
  if (b.domain != ast::DomainKind::Set) {
    diags_.error("E0306", b.span,
                 fmt::format("{}: `{}` beside the sweep takes a set of values, as `{} in {{a, b}};`", owner,
                             b.path.str(), b.path.str()));
    return;
  }
  ir::Study::Series series;
  series.target = b.path.str();
  if (series.target == out.target) {
    diags_.error("E0202", b.path.span,
                 fmt::format("{} sweeps `{}` already; a line per value names another quantity", owner, series.target));
    return;
  }
  const AttrSpec* spec = nullptr;
  std::optional<units::Dim> dim = sweepTarget(b.path, m, &spec);
  if (!dim) return;
  series.dim = *dim;
  for (const auto& e : b.exprs) {
    auto x = checker_.check(e.get(), gs);
    if (x->type.isError()) return;
    if (!x->isConst() || x->type.dim != *dim) {
      diags_.error("E0302", x->span,
                   fmt::format("`{}` takes constants of {}, as the quantity it sets, but this is {}", series.target,
                               dim->describe(), describe(x->type)));
      return;
    }
    if (spec && !sweptValueFits(*spec, series.target, *x)) return;
    series.members.push_back(x->value);
  }
  if (series.members.size() > 12) {
    diags_.error("E0411", b.span,
                 fmt::format("{}: {} lines, beyond the 12 a plot keeps apart", owner, series.members.size()));
    return;
  }
  out.series = std::move(series);
}

// A value a sweep or its lines give the quantity: its row's whole-number rule and limits.
bool Analyser::sweptValueFits(const AttrSpec& spec, const std::string& target, const ir::Expr& x) {
  if (spec.integer && !(x.value.isRational() && x.value.rational().isInteger())) {
    diags_.error("E0403", x.span, fmt::format("`{}` must be a whole number, got {}", target, x.value.str()));
    return false;
  }
  if ((spec.atLeast && x.value.compare(*spec.atLeast) < 0) ||
      (spec.atMost && !spec.budget && x.value.compare(*spec.atMost) > 0)) {
    diags_.error("E0405", x.span, fmt::format("`{}` cannot be {}", target, units::showQuantity(x.value, x.type.dim)));
    return false;
  }
  return true;
}

// `sweep X in a..b step s;`: what is swept and its start, end and step.
void Analyser::sweepOf(const Stmt& b, const GearboxModel& m, const Scope& gs, const std::string& owner, ir::Study& out) {
  out.kind = ir::Study::Sweep;
  out.target = b.path.str();
  const AttrSpec* swept = nullptr;
  out.dim = sweepTarget(b.path, m, &swept);
  auto [lo, hi] = checker_.checkRange(b.lo.get(), b.hi.get(), gs);
  // A step is a difference: it takes the end's unit without that unit's zero (`degC`).
  checker_.refuseCelsiusDifference(b.step.get(), "a sweep's step");
  auto step = b.step && b.step->kind == ast::ExprKind::Number && !b.step->unit && b.hi && b.hi->unit
                  ? checker_.literal(*b.step, &*b.hi->unit, true)
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
    // The values a sweep gives take the swept attribute's own limits (its step is its own,
    // but a whole-number quantity takes whole steps).
    if (!limit) {
      if (swept && swept->integer && !(x->value.isRational() && x->value.rational().isInteger())) {
        diags_.error(
            "E0403", x->span,
            fmt::format("`{}` is a whole number: the sweep's step must be whole, got {}", out.target, x->value.str()));
        return std::nullopt;
      }
      return x->value;
    }
    if (swept && !sweptValueFits(*swept, out.target, *x)) return std::nullopt;
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
void Analyser::checkContinuation(const ir::Study& out, const std::string& owner) {
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
void Analyser::checkRuns(const ir::Study& out, const Stmt& st, const std::string& owner) {
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

ir::Setting Analyser::domainSetting(const Stmt& b, const AttrSpec& spec, const Scope& gs) {
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

std::optional<units::Dim> Analyser::sweepTarget(const ast::Path& p, const GearboxModel& m, const AttrSpec** spec) {
  const auto& parts = p.parts;
  if (parts.empty()) return std::nullopt;  // a sweep cut off by a syntax error names nothing
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

ir::Report Analyser::report(const Stmt& st, const Scope& gs) {
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

} // namespace gbx::sema
