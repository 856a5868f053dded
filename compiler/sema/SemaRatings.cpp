#include "sema/Analyser.h"

// Rating blocks and what a rating needs: materials, operating points, inputs.

namespace gbx::sema {

namespace {

// The expressions a gearbox reads, each with where it is used: its rules, objectives, lets,
// report columns and sort key, modification rules (with `modifications`), study outputs.
void eachUse(const ir::Gearbox& g, bool modifications, const std::function<void(const ir::Expr*, const char*)>& visit) {
  for (const auto& r : g.rules) visit(r.expr.get(), "used in a rule");
  for (const auto& o : g.objectives) visit(o.expr.get(), "used in an objective");
  for (const auto& l : g.lets) visit(l.expr.get(), "used in a let");
  if (g.report) {
    for (const auto& c : g.report->columns) visit(c.get(), "reported");
    visit(g.report->sortBy.get(), "used to sort");
  }
  if (modifications)
    for (const auto& md : g.modifies)
      for (const auto& r : md.rules) visit(r.value.get(), "used in a modification rule");
  for (const auto& st : g.studies)
    for (const auto& o : st.outputs) visit(o.get(), "output of a study");
}

} // namespace

// A kind whose stages take a `rating` (its catalogue row lists `rating.life`).
bool Analyser::rateable(const cat::KindSpec& kind) { return findAttr(kind, "rating.life"); }

// `rating { … }`: its settings become the stage's `rating.…` attributes, so that a
// variant overrides them (`hs.rating.life = …`) like any other attribute.
void Analyser::ratingBlock(StageModel& m, const Stmt& b, std::map<std::string, const Stmt*>& seen) {
  if (m.kind && !rateable(*m.kind)) {
    diags_.error("E0235", nameOr(b),
                 fmt::format("{} {} stage has no load-capacity rating yet", m.kind->name[0] == 'i' ? "an" : "a", m.kind->name));
    return;
  }
  if (m.rated) {
    diags_.error("E0202", nameOr(b), fmt::format("duplicate declaration: stage `{}` already has a `rating` block", m.name));
    return;
  }
  std::vector<std::pair<std::string, Binding>> items;
  std::string spectrum = std::string(kRatingBlock) + "." + std::string(kSpectrumBlock);
  flatten(b.body, std::string(kRatingBlock) + ".", fmt::format("the `rating` of stage `{}`", m.name), items,
          {"rating.lubricant", "rating.roughness", "rating.basic_rack", "rating.min_safety", "rating.ring_planet"},
          {spectrum});
  for (const auto& st : b.body)
    if (st.kind == StmtKind::Block && st.name == kSpectrumBlock) {
      if (m.spectrum) {
        auto& d = diags_.error("E0202", nameOr(st), fmt::format("duplicate declaration: stage `{}` already has a `load_spectrum`", m.name));
        d.notes.push_back({nameOr(*m.spectrum), "first given here"});
        continue;
      }
      m.spectrum = &st;
    }
  stageItems(m, items, seen);
  m.rated = true;
}

// A block's flattened settings as the stage's attributes, each given once.
void Analyser::stageItems(StageModel& m, std::vector<std::pair<std::string, Binding>>& items,
                          std::map<std::string, const Stmt*>& seen) {
  for (auto& [p, bind] : items) {
    if (auto it = seen.find(p); it != seen.end()) {
      auto& d = diags_.error("E0202", bind.stmt->path.span, fmt::format("duplicate declaration: `{}` is already given in stage `{}`", p, m.name));
      d.notes.push_back({it->second->path.span, "first given here"});
      continue;
    }
    seen[p] = bind.stmt;
    m.setAttr(p, {bind.stmt, "stage"});
  }
}

// A gear's block (`ring.cutter { teeth = 36; … }`): its settings become the gear's
// `cutter.…` attributes, checked like any other.
void Analyser::gearBlock(StageModel& m, const Stmt& b, std::map<std::string, const Stmt*>& seen) {
  std::vector<std::pair<std::string, Binding>> items;
  flatten(b.body, b.name + ".", fmt::format("`{}` of stage `{}`", b.name, m.name), items, {});
  stageItems(m, items, seen);
}

// `load_spectrum { bin 130% torque for 0.1% of life; … }` (docs/rating.md): each bin a
// share of the operating torque or a torque, for a share of the life or a number of load
// cycles of the driving gear; the shares of the life add up to the whole life.
std::vector<ir::SpectrumBin> Analyser::spectrumBins(const StageModel& st) {
  std::vector<ir::SpectrumBin> out;
  if (!st.spectrum) return out;
  Scope scope;
  scope.context = Scope::ConstExpr;
  const std::string usage = "a bin is `bin 130% torque for 0.1% of life;` or `bin 12 kN*m for 1e7 cycles;`";
  auto constant = [&](const ast::Expr* e, const char* what) -> std::optional<ir::ExprPtr> {
    auto x = checker_.check(e, scope);
    if (x->type.isError()) return std::nullopt;
    if (!x->isConst()) {
      diags_.error("E0410", x->span, fmt::format("a spectrum bin's {} must be a constant", what));
      return std::nullopt;
    }
    if (!x->type.isNumber() || x->value.sign() <= 0) {
      diags_.error("E0405", x->span, fmt::format("a spectrum bin's {} must be positive", what));
      return std::nullopt;
    }
    return x;
  };
  bool anyCycles = false, anyShare = false;
  double total = 0;
  for (const auto& b : st.spectrum->body) {
    if (b.kind != StmtKind::Bin || b.name != kBinWord) {
      diags_.error("E0110", b.span, fmt::format("`load_spectrum` of stage `{}` holds bins only: {}", st.name, usage));
      continue;
    }
    ir::SpectrumBin bin;
    bin.span = b.span;
    auto load = constant(b.value.get(), "load");
    auto duration = constant(b.step.get(), "duration");
    if (!load || !duration) continue;
    bin.share = !b.word.empty();
    if (bin.share && b.word != kTorqueWord) {
      diags_.error("E0406", b.wordSpan, fmt::format("`{}`: a bin's load is a share of the operating `torque` or a torque; {}", b.word, usage));
      continue;
    }
    units::Dim want = bin.share ? units::dims::none : units::dims::torque;
    if ((*load)->type.dim != want) {
      diags_.error("E0302", (*load)->span,
                   fmt::format("unit mismatch: a bin's load is {} ({}), got {}", bin.share ? "a share (`130% torque`)" : "a torque",
                               usage, describe((*load)->type)));
      continue;
    }
    bin.cycles = b.cycles;
    if (!bin.cycles && b.base != kLifeWord) {
      diags_.error("E0406", b.base.empty() ? b.span : b.baseSpan,
                   fmt::format("a bin lasts a share `of life` or a number of `cycles`; {}", usage));
      continue;
    }
    if ((*duration)->type.dim != units::dims::none) {
      diags_.error("E0302", (*duration)->span, fmt::format("unit mismatch: a bin's duration is a share of the life or a count of cycles, got {}",
                                                           describe((*duration)->type)));
      continue;
    }
    bin.load = (*load)->value;
    bin.duration = (*duration)->value;
    (bin.cycles ? anyCycles : anyShare) = true;
    if (!bin.cycles) total += bin.duration.toDouble();
    out.push_back(std::move(bin));
  }
  if (anyCycles && anyShare)
    diags_.error("E0225", nameOr(*st.spectrum),
                 fmt::format("the `load_spectrum` of stage `{}` mixes shares of the life with counts of cycles: give every bin one kind", st.name));
  else if (anyShare && std::fabs(total - 1) > 1e-9)
    diags_.error("E0225", nameOr(*st.spectrum),
                 fmt::format("the bins of stage `{}`'s `load_spectrum` last {} % of the life, not 100 %", st.name, units::formatDouble(total * 100)));
  if (out.empty() && !st.spectrum->body.empty()) return out;
  if (st.spectrum->body.empty()) diags_.error("E0225", nameOr(*st.spectrum), fmt::format("the `load_spectrum` of stage `{}` has no bin; {}", st.name, usage));
  return out;
}

// A rated bevel stage (ISO 10300 method B1) needs its size (an outer cone distance, or a mean
// normal module, and a face width or face ratio; or a face width and a face ratio, b/R_e) and each gear's single pitch deviation.
void Analyser::bevelRatingInputs(const StageModel& st, Span where) {
  bool re = st.findAttr("outer_cone_distance"), mmn = st.findAttr("mean_normal_module"), b = st.findAttr("face_width"),
       ratio = st.findAttr("face_ratio");
  if (!re && !mmn && !(b && ratio))
    diags_.error("E0225", where,
                 fmt::format("bevel stage `{}` is rated but gives neither `outer_cone_distance` nor `mean_normal_module` (nor "
                             "`face_width` with `face_ratio`): the rating needs the size of the gears",
                             st.name));
  if (!b && !ratio)
    diags_.error("E0225", where, fmt::format("bevel stage `{}` is rated but gives neither `face_width` nor `face_ratio`", st.name));
  for (const auto& g : st.kind->gears)
    if (!st.findAttr(g + ".pitch_deviation"))
      diags_.error("E0225", where,
                   fmt::format("bevel stage `{}` is rated but does not give `{}.pitch_deviation` (the single pitch deviation f_pt that "
                               "K_v and K_Halpha read)",
                               st.name, g));
}

// A rated stage needs its service life and a material with the ISO 6336-5 numbers.
namespace {
bool inside(const Span& s, const Span& outer) {
  auto before = [](int l1, int c1, int l2, int c2) { return l1 < l2 || (l1 == l2 && c1 <= c2); };
  return s.file == outer.file && before(outer.line, outer.col, s.line, s.col) && before(s.endLine, s.endCol, outer.endLine, outer.endCol);
}
} // namespace

// Whether the stage misspells `need` (an E0211 in it suggests that name): then its absence is
// the misspelling's doing, and a second error for it would only hide the first.
bool Analyser::misspeltIn(const StageModel& st, const std::string& need) const {
  if (!st.decl) return false;
  for (const auto& d : diags_.all())
    if (d.code == "E0211" && inside(d.span, st.decl->span) && d.message.find("did you mean `" + need + "`") != std::string::npos)
      return true;
  return false;
}

void Analyser::ratingInputs(const StageModel& st, Span where, bool bearingsReadOil) {
  for (const char* need : {"rating.life", "rating.lubricant.viscosity_40", "rating.roughness.flank", "rating.roughness.root"}) {
    std::string rz = std::string(need) + "_rz";
    if (!st.findAttr(need) && !st.findAttr(rz))
      diags_.error("E0225", where,
                   fmt::format("the `rating` of stage `{}` does not give `{}` ({})", st.name, std::string(need).substr(7),
                               findAttr(*st.kind, need)->meaning));
  }
  // Scuffing and micropitting read the oil's viscosity line and its temperature.
  const char* fzgStage = "rating.lubricant.fzg_load_stage";
  const char* fvaStage = "rating.lubricant.micropitting_load_stage";
  // A kind without them (bevel: ISO/TS 10300-20 is not implemented) has its own message
  // for each such input, as an attribute it does not take.
  bool oil = findAttr(*st.kind, fzgStage);
  bool fzg = oil && st.findAttr(fzgStage), fva = oil && st.findAttr(fvaStage);
  for (const auto& [test, given] : {std::pair{fzgStage, fzg}, std::pair{fvaStage, fva}}) {
    if (!given) continue;
    for (const char* need : {"rating.lubricant.viscosity_100", "rating.lubricant.oil_temperature"})
      if (!st.findAttr(need))
        diags_.error("E0225", where,
                     fmt::format("the `rating` of stage `{}` gives `{}` but not `{}` ({})", st.name, std::string(test).substr(7),
                                 std::string(need).substr(7), findAttr(*st.kind, need)->meaning));
  }
  // An input only scuffing or micropitting reads, given where neither is rated, does nothing.
  const std::pair<const char*, int> only[] = {{"rating.lubricant.viscosity_100", 3},  {"rating.lubricant.oil_temperature", 3},
                                              {"rating.lubricant.density", 3},        {"rating.lubricant.base", 3},
                                              {"rating.lubricant.supply", 3},         {"rating.min_safety.scuffing", 1},
                                              {"rating.min_safety.integral_scuffing", 1}, {"rating.min_safety.micropitting", 2}};
  for (const auto& [name, uses] : only) {
    const Binding* b = st.findAttr(name);
    std::string n(name);
    bool oilLine = n == "rating.lubricant.viscosity_100" || n == "rating.lubricant.oil_temperature";
    bool used = ((uses & 1) && fzg) || ((uses & 2) && fva) || (bearingsReadOil && oilLine);
    if (b && !used && oil)
      diags_.warning("W0502", b->stmt->path.span,
                     fmt::format("`{}` of stage `{}` does nothing: it is read by {} only, and the oil gives no {}", std::string(name).substr(7),
                                 st.name, uses == 1 ? "scuffing" : uses == 2 ? "micropitting" : "scuffing and micropitting",
                                 uses == 2   ? "`micropitting_load_stage`"
                                 : uses == 1 ? "`fzg_load_stage`"
                                             : "`fzg_load_stage` or `micropitting_load_stage`"));
  }
  // Micropitting's pressure-viscosity law is known for mineral and polyalphaolefin oils.
  const Binding* base = st.findAttr("rating.lubricant.base");
  if (base && base->stmt->value && fva) {
    const auto& words = findAttr(*st.kind, "rating.lubricant.base")->symbols;
    auto it = std::find(words.begin(), words.end(), base->stmt->value->text);
    auto choice = it - words.begin();
    if (it != words.end() && choice != cat::oilBase::Mineral && choice != cat::oilBase::Polyalphaolefin)
      diags_.error("E0235", base->stmt->value->span,
                   fmt::format("micropitting of stage `{}`: the pressure-viscosity coefficient of a {} oil is not implemented (ISO/TS "
                               "6336-22 gives it for mineral and polyalphaolefin oils)",
                               st.name, *it));
  }
  if (st.kind->kind == ir::StageKind::Bevel) {
    bevelRatingInputs(st, where);
  } else {
    bool plainModule = st.kind->kind == ir::StageKind::Idler || st.kind->kind == ir::StageKind::Planetary;
    for (const char* need : {plainModule ? "module" : "normal_module", "face_width"})
      if (!st.findAttr(need) && !misspeltIn(st, need))
        diags_.error("E0225", where, fmt::format("stage `{}` is rated but does not give `{}` ({})", st.name, need, findAttr(*st.kind, need)->meaning));
  }
  if (st.kind->kind != ir::StageKind::Bevel && !st.findAttr("accuracy")) {
    std::vector<std::string> missing;
    // f_falpha may come from the total `profile_deviation` the loaded mesh reads too.
    const std::pair<const char*, const char*> devs[] = {
        {"pitch_deviation", nullptr}, {"profile_form_deviation", "profile_deviation"}, {"helix_slope_deviation", nullptr}};
    for (const auto& g : st.kind->gears)
      for (const auto& [dev, alt] : devs)
        if (!st.findAttr(g + "." + dev) && !(alt && st.findAttr(g + "." + alt))) missing.push_back("`" + g + "." + dev + "`");
    if (!missing.empty())
      diags_.error("E0225", where,
                   fmt::format("stage `{}` is rated but gives no `accuracy` (ISO 1328-1 grade) from which to take {}", st.name,
                               fmt::join(missing, ", ")));
  }
  for (const auto& g : st.kind->gears)
    if (st.findAttr(g + ".web_thickness") && !st.findAttr(g + ".rim_thickness"))
      diags_.error("E0225", where, fmt::format("`{}.web_thickness` needs `{}.rim_thickness` (C_R of a webbed blank)", g, g));
  // The stage's material, or one per gear (`pinion.material`), each with the numbers the
  // rating needs.
  std::string matName(keyName(Q::Material));
  std::vector<const Binding*> mats;
  std::vector<std::string> without;
  for (const auto& g : st.kind->gears) {
    if (const Binding* b = st.findAttr(g + "." + matName)) mats.push_back(b);
    else without.push_back("`" + g + "`");
  }
  if (const Binding* b = st.findAttr(matName)) mats.push_back(b);
  else if (!without.empty()) {
    diags_.error("E0233", where,
                 fmt::format("stage `{}` is rated but names no `material` for {} (the rating needs its E, nu, sigma_hlim, sigma_flim and "
                             "treatment)",
                             st.name, fmt::join(without, ", ")));
    return;
  }
  for (const Binding* mat : mats) {
    const ast::Expr* v = mat->stmt->value.get();
    if (!v || v->kind != ast::ExprKind::Name) continue;
    auto it = globals_.materials.find(v->text);
    if (it == globals_.materials.end()) continue;  // reported as an unknown material
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
}

// A gear pair's mass needs its material's density: say so at check time, not as `n/a`.
void Analyser::requireMaterial(const ir::Gearbox& g, const GearboxModel& m) {
  std::set<std::pair<int, int>> reported;
  auto visit = [&](const ir::Expr* e, const char* where) {
    if (!e) return;
    walk(*e, [&](const ir::Expr& x) {
      if (x.op != Op::Quantity || !x.type.isNumber() || keyOf(lastPart(x.name)) != Q::Mass) return;
      auto dot = x.name.find('.');
      const StageModel* st = dot == std::string::npos ? nullptr : m.findStage(x.name.substr(0, dot));
      if (!st || !st->kind) return;
      const std::string material(keyName(Q::Material));
      auto second = x.name.find('.', dot + 1);
      std::string gear = second == std::string::npos ? "" : x.name.substr(dot + 1, second - dot - 1);
      // A planetary gear's mass, given, or from its geometry: the ring's needs its rim.
      if (!gear.empty() && st->findAttr(gear + ".mass")) return;
      bool ring = st->kind->kind == ir::StageKind::Planetary && gear == st->kind->gears.back();
      bool dense = st->findAttr(material) || (!gear.empty() && st->findAttr(gear + "." + material));
      if (dense && !(ring && !st->findAttr(gear + ".rim_thickness"))) return;
      if (!reported.insert({x.span.line, x.span.col}).second) return;
      if (!dense)
        diags_.error("E0233", x.span,
                     fmt::format("`{}` needs the density of the stage's material, but stage `{}` names no `material` ({}){}", x.name,
                                 st->name, where, gear.empty() ? "" : fmt::format("; or give `{}.mass`", gear)));
      else
        diags_.error("E0233", x.span,
                     fmt::format("`{}` needs the ring's `{}.rim_thickness` (its mass is the annulus below the root) or its `{}.mass` ({})",
                                 x.name, gear, gear, where));
    });
  };
  for (const auto& o : g.objectives) visit(o.expr.get(), "used in an objective");
  for (const auto& r : g.rules) visit(r.expr.get(), "used in a rule");
  if (g.report)
    for (const auto& c : g.report->columns) visit(c.get(), "reported");
}

// A gear's tooth-thickness allowances come as a pair, the upper one not below the lower.
void Analyser::thicknessAllowances(const ir::Gearbox& g, const GearboxModel& m) {
  const std::string upper(keyName(Q::UpperThicknessAllowance)), lower(keyName(Q::LowerThicknessAllowance));
  for (const auto& st : g.stages)
    for (const auto& gear : st.gears) {
      const ir::Attribute* u = st.find(gear + "." + upper);
      const ir::Attribute* l = st.find(gear + "." + lower);
      if (!u && !l) continue;
      const StageModel* sm = m.findStage(st.name);
      if (sm && !sm->rated) {
        diags_.warning("W0503", (u ? u : l)->span,
                       fmt::format("`{}` does nothing here: the backlash is part of the rating table, and stage `{}` has no "
                                   "`rating {{ … }}` block",
                                   (u ? u : l)->name, st.name));
        continue;
      }
      if (sm && (misspeltIn(*sm, gear + "." + upper) || misspeltIn(*sm, gear + "." + lower))) continue;
      if (st.kind == ir::StageKind::Planetary && gear == st.gears.back()) {
        diags_.error("E0235", (u ? u : l)->span,
                     fmt::format("`{}`: the backlash of an internal mesh is not computed (the sun-planet mesh's is)", (u ? u : l)->name));
        continue;
      }
      if (!u || !l) {
        const ir::Attribute* given = u ? u : l;
        diags_.error("E0225", given->span,
                     fmt::format("`{}` needs `{}.{}` too: the backlash takes both allowances of the tooth thickness", given->name, gear,
                                 u ? lower : upper));
        continue;
      }
      bool fixed = u->role == ir::Attribute::Fixed && l->role == ir::Attribute::Fixed && u->value && l->value;
      if (fixed && u->value->isConst() && l->value->isConst() && u->value->value.compare(l->value->value) < 0)
        diags_.error("E0401", u->span,
                     fmt::format("`{}` ({:g} um) is below `{}` ({:g} um): the upper allowance is the thicker tooth", u->name,
                                 u->value->value.toDouble() * 1e6, l->name, l->value->value.toDouble() * 1e6));
    }
}

// A safety or an influence factor needs the stage's `rating` inputs.
void Analyser::requireRating(const ir::Gearbox& g, const GearboxModel& m) {
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
        // An internal gear's tooth root is the one its pinion-type cutter generates.
        static const std::set<Q> root = {Q::BendingSafety,
                                         Q::BendingStress,
                                         Q::PermissibleBendingStress,
                                         Q::YF,
                                         Q::YS,
                                         Q::Ybeta,
                                         Q::YNT,
                                         Q::YdeltarelT,
                                         Q::YRrelT,
                                         Q::YX,
                                         Q::BendingDamage};
        const bool planetary = st->kind->kind == ir::StageKind::Planetary;
        const std::string ringName = planetary ? st->kind->gears[cat::gear::Ring] : std::string();
        bool ring = planetary && x.name.find("." + ringName + ".") != std::string::npos;
        if (ring && root.count(*k) && !st->findAttr(ringName + ".cutter.teeth") &&
            reported.insert({x.span.line, x.span.col}).second)
          diags_.error(
              "E0225", x.span,
              fmt::format(
                  "`{}` needs the ring's pinion-type cutter, `{}.cutter {{ teeth = …; }}` in stage `{}` (its tooth "
                  "root is the one the cutter generates; its contact is rated without) ({})",
                  x.name, ringName, st->name, where));
        planetBearingInputs(*st, x, *k, where, reported);
        // Scuffing needs the oil's FZG load stage, micropitting its FVA load stage.
        Q test = scuffingInput(*k);
        std::string testName(keyName(test));
        if (test != Q::None && !st->findAttr(testName) && reported.insert({x.span.line, x.span.col}).second)
          diags_.error("E0225", x.span,
                       fmt::format("`{}` needs the oil's `{}` in stage `{}`'s rating ({}; {})", x.name, testName.substr(7), st->name,
                                   findAttr(*st->kind, testName)->meaning, where));
        return;
      }
      if (!reported.insert({x.span.line, x.span.col}).second) return;
      diags_.error("E0236", x.span,
                   fmt::format("`{}` is a load-capacity result, but stage `{}` has no `rating {{ … }}` block with its inputs ({})",
                               x.name, st->name, where));
    });
  };
  eachUse(g, false, visit);
}

// A planet bearing's quantities need its kind and rating; its modified life also its pitch
// diameter and the oil's viscosity line at its temperature (E0225).
void Analyser::planetBearingInputs(const StageModel& st, const ir::Expr& x, Q k, const char* where,
                                   std::set<std::pair<int, int>>& reported) {
  if ((k != Q::BearingLoad && k != Q::BearingLife && k != Q::BearingModifiedLife) ||
      st.kind->kind != ir::StageKind::Planetary)
    return;
  const std::string& planet = st.kind->gears[cat::gear::Planet];
  if (x.name.find("." + planet + ".") == std::string::npos) {
    if (reported.insert({x.span.line, x.span.col}).second)
      diags_.error(
          "E0214", x.span,
          fmt::format("`{}`: the stage's bearings are its planets' (`{}.{}.{}`)", x.name, st.name, planet, keyName(k)));
    return;
  }
  std::vector<std::string> need;
  if (k != Q::BearingLoad)
    for (const char* n : {".bearing.kind", ".bearing.C"})
      if (!st.findAttr(planet + n)) need.push_back("`" + planet + n + "`");
  if (k == Q::BearingModifiedLife) {
    if (!st.findAttr(planet + ".bearing.pitch_diameter")) need.push_back("`" + planet + ".bearing.pitch_diameter`");
    for (const char* n : {"rating.lubricant.viscosity_100", "rating.lubricant.oil_temperature"})
      if (!st.findAttr(n)) need.push_back(fmt::format("`{}`", n));
  }
  if (need.empty() || !reported.insert({x.span.line, x.span.col}).second) return;
  diags_.error("E0225", x.span,
               fmt::format("`{}` needs {} in stage `{}` ({})", x.name, fmt::join(need, ", "), st.name, where));
}

// A planetary stage's gear settings that belong to one of its gears: the pin error to the
// planet (the load sharing's), the pinion-type cutter to the ring.
void Analyser::planetaryGears(const ir::Gearbox& g) {
  for (const auto& st : g.stages) {
    const ir::Attribute *kind = nullptr, *rating = nullptr, *loadSharing = nullptr, *pinError = nullptr,
                        *support = nullptr;
    bool bearingGiven = false;
    for (const auto& a : st.attributes) {
      auto dot = a.name.find('.');
      int gear = dot == std::string::npos ? -1 : cat::gearIndex(cat::kindSpec(st.kind), a.name.substr(0, dot));
      auto key = cat::keyOf(gear < 0 ? a.name : a.name.substr(dot + 1));
      if (!key) continue;
      // Read at one value by the rating: a range or set would be rated at its middle.
      bool cutter = *key == Q::CutterTeeth || *key == Q::CutterShift || *key == Q::CutterTipRadius;
      bool plain = cutter || *key == Q::PinError || *key == Q::GearFlankRz || *key == Q::GearRootRz ||
                   *key == Q::RatingRingPlanetDynamicFactor || cat::isPlanetBearingSetting(*key);
      if (plain && (a.role == ir::Attribute::Decision || a.role == ir::Attribute::Freedom))
        diags_.error("E0110", a.span,
                     fmt::format("`{}` of stage `{}` takes one value: it is not searched", a.name, st.name));
      if (st.kind != ir::StageKind::Planetary) continue;
      if (cutter && gear != cat::gear::Ring)
        diags_.error(
            "E0214", a.span,
            fmt::format("`{}` of stage `{}`: only the ring is cut by a pinion-type cutter (`ring.cutter {{ … }}`)",
                        a.name, st.name));
      if (*key == Q::PinError && gear != cat::gear::Planet)
        diags_.error(
            "E0214", a.span,
            fmt::format("`{}` of stage `{}`: a pin error belongs to a planet (`planet.pin_error`)", a.name, st.name));
      if (cat::isPlanetBearingSetting(*key) && gear != cat::gear::Planet)
        diags_.error("E0214", a.span,
                     fmt::format("`{}` of stage `{}`: the stage's bearings are its planets' (`planet.bearing {{ … }}`)",
                                 a.name, st.name));
      bool planet = gear == cat::gear::Planet;
      bearingGiven = bearingGiven || (cat::isPlanetBearingSetting(*key) && planet);
      if (planet && *key == Q::PlanetBearingKind) kind = &a;
      if (planet && *key == Q::PlanetBearingC) rating = &a;
      if (planet && *key == Q::PinError) pinError = &a;
      if (*key == Q::RatingMeshLoadFactor && !a.symbol.empty()) loadSharing = &a; // its one word, `load_sharing`
      if (*key == Q::SunSupport) support = &a;
    }
    if (bearingGiven && (!kind || !rating))
      diags_.error(
          "E0225", st.span,
          fmt::format("stage `{}`: the planets' bearings need their {} (`planet.bearing {{ kind = …; C = …; }}`)",
                      st.name,
                      !kind && !rating ? "`kind` and `C`"
                      : !kind          ? "`kind`"
                                       : "`C`"));
    ringRim(st);
    if (loadSharing && !pinError)
      diags_.warning(
          "W0504", loadSharing->span,
          fmt::format("stage `{}`: load sharing without `planet.pin_error` shares the load equally (K_gamma = 1)",
                      st.name));
    for (const ir::Attribute* a : {pinError, support})
      if (a && !loadSharing)
        diags_.warning(
            "W0505", a->span,
            fmt::format("`{}` of stage `{}` does nothing unless `rating {{ mesh_load_factor = load_sharing; }}`",
                        a->name, st.name));
  }
}

// A cut ring's rim given thinner than ISO 6336-3's rim factor covers (1.75 modules), where
// both are constants: said at check time rather than as an unrated root.
void Analyser::ringRim(const ir::Stage& st) {
  if (st.kind != ir::StageKind::Planetary) return;
  const ir::Attribute *rim = nullptr, *module = nullptr, *cutter = nullptr;
  const std::string ring = cat::kindSpec(st.kind).gears[cat::gear::Ring] + ".";
  for (const auto& a : st.attributes) {
    auto key = a.name.rfind(ring, 0) == 0 ? cat::keyOf(a.name.substr(ring.size())) : std::nullopt;
    if (key == Q::RimThickness) rim = &a;
    if (key == Q::CutterTeeth) cutter = &a;
    if (cat::keyOf(a.name) == Q::Module) module = &a;
  }
  auto constant = [](const ir::Attribute* a) {
    return a && a->role == ir::Attribute::Fixed && a->value && a->value->isConst();
  };
  if (!cutter || !constant(rim) || !constant(module)) return; // Y_B is read only where the root is rated
  double sR = rim->value->value.toDouble(), m = module->value->value.toDouble();
  if (sR < 1.75 * m)
    diags_.error(
        "E0405", rim->span,
        fmt::format(
            "`{}` of stage `{}` is {:g} mm, below 1.75 modules ({:g} mm): ISO 6336-3's rim factor of an internal gear "
            "does not cover so thin a rim",
            rim->name, st.name, sR * 1e3, 1.75 * m * 1e3));
}

// `dynamic_factor = scene NAME`: K_v by method A from a periodic single-mesh scene on the
// rated stage itself.
void Analyser::sceneFactors(const ir::Gearbox& g) {
  for (const auto& st : g.stages)
    for (const auto& a : st.attributes) {
      bool cylindrical = st.kind == ir::StageKind::Spur || st.kind == ir::StageKind::Helical;
      if (!a.sceneRef && !a.symbol.empty() && cat::keyOf(a.name) == Q::RatingFaceLoadFactor && !cylindrical)
        diags_.error("E0235", a.span,
                     fmt::format("`{} = {}` of stage `{}`: the contact analysis reads a spur or helical pair's loaded mesh; that of "
                                 "a stage of kind `{}` is not implemented (give K_Hbeta, or leave it to method B)",
                                 a.name, a.symbol, st.name, cat::kindSpec(st.kind).name));
      if (!a.sceneRef) continue;
      const ir::Scene* sc = nullptr;
      for (const auto& s : g.scenes)
        if (s.name == a.symbol) sc = &s;
      if (!sc) continue;  // reported as an unknown scene
      if (sc->target != st.name)
        diags_.error("E0232", a.span,
                     fmt::format("`{}` of stage `{}` names scene `{}`, which runs on {}: K_v comes from a scene on this stage", a.name,
                                 st.name, sc->name, sc->target.empty() ? "the whole gearbox" : fmt::format("stage `{}`", sc->target)));
      else if (!cylindrical)
        diags_.error("E0235", a.span,
                     fmt::format("`{}` of stage `{}`: K_v by method A reads a single mesh's scene; that of a stage of kind `{}` is not implemented", a.name,
                                 st.name, cat::kindSpec(st.kind).name));
      else if (!ir::findSetting(sc->settings, Q::SteadyState))
        diags_.error("E0225", a.span,
                     fmt::format("`{}` of stage `{}` names scene `{}`, which is not periodic: K_v is the peak of the periodic mesh force "
                                 "(write `steady_state = periodic;` in the scene)",
                                 a.name, st.name, sc->name));
    }
}

void Analyser::requireOperating(const ir::Gearbox& g) {
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
  eachUse(g, true, visit);
}

void Analyser::checkOperating(const GearboxModel& m, const std::vector<ir::Setting>& op, const Stmt* decl) {
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

} // namespace gbx::sema
