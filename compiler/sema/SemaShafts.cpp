#include <cmath>

#include "catalogue/Shafts.h"
#include "catalogue/StageKinds.h"
#include "diag/Suggest.h"
#include "sema/Analyser.h"

// `shaft NAME { … }`: its settings, segments, gears, bearings, loads and disks (docs/language.md, "Shafts and
// bearings").

namespace gbx::sema {

namespace {

using Place = ir::Shaft::Place;

std::optional<Place> placeOf(const std::string& w) {
  static const std::pair<std::string_view, Place> words[] = {{"gear", Place::Gear}, {"coupling", Place::Coupling},
                                                             {"bearing", Place::Bearing}, {"load", Place::Load},
                                                             {"disk", Place::Disk}, {"notch", Place::Notch}};
  for (const auto& [word, place] : words)
    if (word == w) return place;
  return std::nullopt;
}

} // namespace

// What each kind of notch needs: a shoulder and a groove their fillet, a groove and a
// V-notch their depth, a hole its diameter.
void Analyser::notchNeeds(const ir::Shaft::Placed& p, const std::string& what, const Span& at) {
  auto need = [&](const char* key, const char* example) {
    if (!ir::findSetting(p.settings, key))
      diags_.error("E0225", at, fmt::format("{} needs `{}` (as `{}`)", what, key, example));
  };
  auto refuse = [&](const char* key) {
    if (const ir::Setting* x = ir::findSetting(p.settings, key))
      diags_.error("E0224", x->span, fmt::format("{} takes no `{}`", what, key));
  };
  namespace nk = cat::notchKind;
  const int k = p.notch;
  if (k == nk::Shoulder || k == nk::Groove) need("radius", "radius = 2 mm");
  else refuse("radius");
  if (k == nk::Groove || k == nk::VNotch) need("depth", "depth = 2 mm");
  else refuse("depth");
  if (k == nk::Hole) need("diameter", "diameter = 8 mm");
  else refuse("diameter");
  if (k != nk::Keyway) refuse("keys");
}

// A notch's place on the shaft: a shoulder where the diameter steps, a groove or V-notch
// shallower than the segment's radius; with notches, the material's DIN 743 strengths.
void Analyser::notchGeometry(const ir::Shaft& sh, const std::string& owner) {
  // A diameter searched over a range or a set (NaN) is checked at each design instead.
  auto diameterAt = [&](const Number& x, bool left) -> std::optional<double> {
    for (const auto& seg : sh.segments) {
      bool in = left ? x.compare(seg.x0) > 0 && x.compare(seg.x1) <= 0 : x.compare(seg.x0) >= 0 && x.compare(seg.x1) < 0;
      const ir::Setting* d = ir::findSetting(seg.settings, Q::Diameter);
      if (in && d && d->value) return d->value->toDouble();
      if (in && d && d->searched()) return std::nan("");
    }
    return std::nullopt;
  };
  bool any = false;
  for (const auto& p : sh.placed) {
    if (p.kind != Place::Notch) continue;
    any = true;
    auto l = diameterAt(p.at, true), r = diameterAt(p.at, false);
    std::string where = units::showQuantity(p.at, units::dims::length);
    const bool searched = (l && std::isnan(*l)) || (r && std::isnan(*r));
    if (searched) continue;
    if (p.notch == cat::notchKind::Shoulder && (!l || !r || *l == *r)) {
      diags_.error("E0405", p.span,
                   fmt::format("{}: a shoulder stands where the diameter steps, and it does not at {}", owner, where));
      continue;
    }
    const ir::Setting* depth = ir::findSetting(p.settings, Q::NotchDepth);
    double d = std::max(l.value_or(0), r.value_or(0));
    if (depth && depth->value && d > 0 && 2 * depth->value->toDouble() >= d)
      diags_.error("E0405", depth->span,
                   fmt::format("{}: the {} at {} is {} deep in a {} shaft: no section is left", owner, p.name, where,
                               units::showQuantity(*depth->value, units::dims::length),
                               units::showQuantity(Number::approx(d), units::dims::length)));
    const ir::Setting* hole = p.notch == cat::notchKind::Hole ? ir::findSetting(p.settings, Q::Diameter) : nullptr;
    if (hole && hole->value && d > 0 && hole->value->toDouble() >= d)
      diags_.error("E0405", hole->span,
                   fmt::format("{}: the hole at {} is as wide as the shaft", owner, where));
  }
  const ir::Setting* mat = ir::findSetting(sh.settings, Q::Material);
  if (!any || !mat) return;
  auto it = globals_.materials.find(mat->symbol);
  if (it == globals_.materials.end()) return;
  std::vector<std::string> missing;
  for (Q need : {Q::TensileStrength, Q::YieldStrength}) {
    std::string n(keyName(need));
    if (std::none_of(it->second->body.begin(), it->second->body.end(), [&](const Stmt& b) { return b.path.str() == n; }))
      missing.push_back("`" + n + "`");
  }
  if (!missing.empty())
    diags_.error("E0233", mat->span,
                 fmt::format("{} has notches to rate to DIN 743, but material `{}` does not give {}", owner,
                             mat->symbol, fmt::join(missing, ", ")));
}

// A position along the shaft: a constant length.
std::optional<Number> Analyser::position(const ast::Expr* e, const Scope& gs, const std::string& what) {
  if (!e) return std::nullopt;
  auto x = checker_.check(e, gs);
  if (x->type.isError()) return std::nullopt;
  if (!x->isConst() || !x->type.isNumber()) {
    diags_.error("E0410", x->span, fmt::format("the position of {} must be a constant length", what));
    return std::nullopt;
  }
  if (x->type.dim != units::dims::length) {
    bool bare = x->type.dim.dimensionless();
    diags_.error("E0302", x->span,
                 fmt::format("unit mismatch: the position of {} needs a length, got {}{}", what, describe(x->type),
                             bare ? fmt::format("; write it with a unit, as `{} mm`", x->value.str()) : ""));
    return std::nullopt;
  }
  if (x->value.sign() < 0) {
    diags_.error("E0405", x->span,
                 fmt::format("the position of {} must not be negative, got {}", what,
                             units::showQuantity(x->value, x->type.dim)));
    return std::nullopt;
  }
  return x->value;
}

// One `WORD [path] at x …` of a shaft: a gear of a stage, a coupling, a named bearing, a
// load or a disk, with its settings.
std::optional<ir::Shaft::Placed> Analyser::placed(const Stmt& s, const GearboxModel& m, const Scope& gs,
                                                  const std::string& owner, std::set<std::string>& bearings) {
  auto kind = placeOf(s.name);
  if (!kind) {
    diags_.error("E0110", nameOr(s),
                 fmt::format("`{} … at …` is not allowed in {}; it takes gear, coupling, bearing, load, disk and notch",
                             s.name, owner));
    return std::nullopt;
  }
  ir::Shaft::Placed p;
  p.kind = *kind;
  p.span = s.span;
  auto at = position(s.value.get(), gs, fmt::format("a {}", s.name));
  if (!at) return std::nullopt;
  p.at = *at;
  if (*kind == Place::Gear) {
    const StageModel* stage = s.path.parts.size() == 2 ? m.findStage(s.path.parts[0]) : nullptr;
    bool gearOk =
        stage && stage->kind &&
        std::find(stage->kind->gears.begin(), stage->kind->gears.end(), s.path.parts[1]) != stage->kind->gears.end();
    if (!gearOk) {
      std::vector<std::string> gears;
      for (const auto& sm : m.stages)
        if (sm.kind)
          for (const auto& g : sm.kind->gears)
            gears.push_back(sm.name + "." + g);
      diags_.error("E0201", s.path.span,
                   fmt::format("`{}` is not a gear of this gearbox (write `gear STAGE.GEAR at …`){}", s.path.str(),
                               diag::suggestion(diag::closest(s.path.str(), gears))));
      return std::nullopt;
    }
    const ir::StageKind sk = stage->kind->kind;
    if (sk != ir::StageKind::Spur && sk != ir::StageKind::Helical && sk != ir::StageKind::Bevel) {
      diags_.error("E0235", s.path.span,
                   fmt::format("`{}`: a shaft carries spur, helical and bevel gears so far (not a {} stage's)",
                               s.path.str(), stage->kind->name));
      return std::nullopt;
    }
    p.name = s.path.str();
    p.gear = static_cast<int>(std::find(stage->kind->gears.begin(), stage->kind->gears.end(), s.path.parts[1]) -
                              stage->kind->gears.begin());
    for (size_t i = 0; i < m.stages.size(); ++i)
      if (&m.stages[i] == stage) p.stage = static_cast<int>(i);
  } else if (*kind == Place::Bearing) {
    if (s.path.parts.size() != 1) {
      diags_.error("E0110", nameOr(s),
                   fmt::format("a bearing of {} needs a name: `bearing A at 30 mm {{ … }}`", owner));
      return std::nullopt;
    }
    p.name = s.path.str();
    if (!bearings.insert(p.name).second) {
      diags_.error("E0202", s.path.span,
                   fmt::format("duplicate declaration: {} already has a bearing `{}`", owner, p.name));
      return std::nullopt;
    }
  } else if (*kind == Place::Notch) {
    const auto& kinds = cat::notchKinds();
    auto k = s.path.parts.size() == 1 ? std::find(kinds.begin(), kinds.end(), s.path.parts[0]) : kinds.end();
    if (k == kinds.end()) {
      diags_.error("E0225", s.path.empty() ? nameOr(s) : s.path.span,
                   fmt::format("a notch of {} needs its kind: `notch shoulder at 60 mm {{ radius = 2 mm; }}` "
                               "(shoulder, groove, keyway, press_fit, hole or v_notch){}",
                               owner, diag::suggestion(diag::closest(s.path.str(), kinds))));
      return std::nullopt;
    }
    p.notch = static_cast<int>(k - kinds.begin());
    p.name = *k;
  } else if (!s.path.empty()) {
    diags_.error("E0110", s.path.span, fmt::format("a {} of {} takes no name", s.name, owner));
  }
  const bool bevel = *kind == Place::Gear && p.stage >= 0 && m.stages[static_cast<size_t>(p.stage)].kind &&
                     m.stages[static_cast<size_t>(p.stage)].kind->kind == ir::StageKind::Bevel;
  if (bevel) {
    bevelGear(s, m, gs, owner, p);
  } else if (s.hasBody && (*kind == Place::Gear || *kind == Place::Coupling))
    diags_.error("E0110", nameOr(s), fmt::format("a {} of {} takes no block", s.name, owner));
  else if (*kind != Place::Gear && *kind != Place::Coupling) {
    std::vector<std::pair<std::string, Binding>> own;
    std::string what = fmt::format("{}'s {}{}", owner, s.name, p.name.empty() ? "" : " " + p.name);
    flatten(s.body, "", what, own, {});
    p.settings = settings(own,
                          *kind == Place::Bearing ? cat::bearingSettings()
                          : *kind == Place::Disk  ? cat::diskSettings()
                          : *kind == Place::Notch ? cat::notchSettings()
                                                  : cat::loadSettings(),
                          gs, what, nameOr(s), "E0225");
    if (*kind == Place::Notch) notchNeeds(p, what, nameOr(s));
  }
  return p;
}

// A bevel gear on a shaft: where its cone apex points (`{ apex = left; }`), and its stage's
// spiral hand, which with the rotation sets the sense of the spiral's thrust.
void Analyser::bevelGear(const Stmt& s, const GearboxModel& m, const Scope& gs, const std::string& owner,
                         ir::Shaft::Placed& p) {
  std::vector<std::pair<std::string, Binding>> own;
  std::string what = fmt::format("{}'s gear {}", owner, p.name);
  flatten(s.body, "", what, own, {});
  p.settings = settings(own, cat::gearSettings(), gs, what, nameOr(s), "E0225");
  if (!ir::findSetting(p.settings, Q::Apex))
    diags_.error("E0225", nameOr(s),
                 fmt::format("{} is a bevel gear: say which end of the shaft its cone apex points to "
                             "(`gear {} at … {{ apex = left; }}` or `right`)",
                             what, p.name));
  const StageModel& st = m.stages[static_cast<size_t>(p.stage)];
  if (!st.findAttr("spiral_hand"))
    diags_.error("E0225", nameOr(s),
                 fmt::format("stage `{}` has a gear on {}: give its pinion's `spiral_hand` (`right` or `left`; for a "
                             "straight bevel pair either), which sets the sense of the spiral's thrust",
                             st.name, owner));
}

// A range or a set is searched with the stages' candidates: a gearbox of none has no search.
void Analyser::noStageToSearch(const ir::Shaft& out, const GearboxModel& m, const std::string& owner) {
  auto domainIn = [](const std::vector<ir::Setting>& v) -> const ir::Setting* {
    for (const auto& x : v)
      if (x.searched()) return &x;
    return nullptr;
  };
  const ir::Setting* searched = domainIn(out.settings);
  for (const auto& seg : out.segments)
    if (!searched) searched = domainIn(seg.settings);
  for (const auto& p : out.placed)
    if (!searched) searched = domainIn(p.settings);
  if (searched && m.stages.empty())
    diags_.error(
        "E0235", searched->span,
        fmt::format("{}: `{}` is a range or a set, searched with the stages' tooth counts, but gearbox `{}` has "
                    "no stage; give it one value",
                    owner, searched->name, m.name));
}

ir::Shaft Analyser::shaft(const Stmt& st, const GearboxModel& m, const Scope& gs) {
  ir::Shaft out;
  out.name = st.name;
  out.span = st.span;
  const std::string owner = fmt::format("shaft `{}`", st.name);
  std::vector<std::pair<std::string, Binding>> items;
  std::set<std::string> bearings;
  // A shaft's numeric settings may be ranges and sets, searched like a stage's attributes.
  struct Domains {
    bool& on;
    explicit Domains(bool& f) : on(f) { on = true; }
    ~Domains() { on = false; }
  } domains(shaftDomains_);
  for (const auto& s : st.body) {
    switch (s.kind) {
    case StmtKind::Assign:
    case StmtKind::Domain: items.emplace_back(s.path.str(), Binding{&s, owner}); break;
    case StmtKind::Block:
      if (s.name == "life")
        flatten(s.body, "life.", owner, items, {});
      else if (s.name == "strength")
        flatten(s.body, "strength.", owner, items, {"strength.min_safety"});
      else
        diags_.error("E0224", nameOr(s),
                     fmt::format("{} has no block `{}` (it takes `life {{ … }}` and `strength {{ … }}`)", owner, s.name));
      break;
    case StmtKind::Segment: {
      ir::Shaft::Segment seg;
      seg.span = s.span;
      auto lo = position(s.lo.get(), gs, "a segment's start"), hi = position(s.hi.get(), gs, "a segment's end");
      if (!lo || !hi) break;
      if (lo->compare(*hi) >= 0) {
        diags_.error("E0401", s.span,
                     fmt::format("empty segment {} .. {}", units::showQuantity(*lo, units::dims::length),
                                 units::showQuantity(*hi, units::dims::length)));
        break;
      }
      seg.x0 = *lo;
      seg.x1 = *hi;
      std::vector<std::pair<std::string, Binding>> own;
      flatten(s.body, "", owner + "'s segment", own, {});
      seg.settings = settings(own, cat::segmentSettings(), gs, owner + "'s segment", s.span, "E0225");
      out.segments.push_back(std::move(seg));
      break;
    }
    case StmtKind::Placed:
      if (auto p = placed(s, m, gs, owner, bearings)) out.placed.push_back(std::move(*p));
      break;
    default: notAllowed(s, owner);
    }
  }
  out.settings = settings(items, cat::shaftSettings(), gs, owner, nameOr(st), "E0225");
  // The segments follow each other from 0; every station lies on the shaft.
  Number end = Number::exact(units::Rational(0));
  for (const auto& seg : out.segments) {
    if (seg.x0.compare(end) != 0) {
      diags_.error("E0405", seg.span,
                   fmt::format("{}: a segment must start where the one before ends ({}), got {}", owner,
                               units::showQuantity(end, units::dims::length),
                               units::showQuantity(seg.x0, units::dims::length)));
      break;
    }
    end = seg.x1;
  }
  if (!out.segments.empty()) end = out.segments.back().x1;
  if (out.segments.empty())
    diags_.error("E0225", nameOr(st), fmt::format("{} has no `segment a .. b {{ diameter = …; }}`", owner));
  notchGeometry(out, owner);
  bool thrust = false;
  for (const auto& p : out.placed) {
    const auto* kind = p.kind == Place::Gear && p.stage >= 0 ? m.stages[static_cast<size_t>(p.stage)].kind : nullptr;
    if (kind && (kind->kind == ir::StageKind::Helical || kind->kind == ir::StageKind::Bevel)) thrust = true;
    if (p.kind == Place::Load && ir::findSetting(p.settings, "axial")) thrust = true;
  }
  int nBearings = 0, held = 0;
  for (const auto& p : out.placed) {
    if (!out.segments.empty() && p.at.compare(end) > 0)
      diags_.error("E0405", p.span,
                   fmt::format("{}: {} lies beyond the shaft's end at {}", owner,
                               units::showQuantity(p.at, units::dims::length),
                               units::showQuantity(end, units::dims::length)));
    if (p.kind != Place::Bearing) continue;
    ++nBearings;
    const ir::Setting* ax = ir::findSetting(p.settings, "axial");
    held += ax && ax->choice == 0; // `held`, the first of the catalogue's words
    const ir::Setting* kind = ir::findSetting(p.settings, Q::BearingKind);
    if (ax && ax->choice == 0 && kind && kind->choice == cat::bearingKind::CylindricalRoller)
      diags_.error("E0225", ax->span,
                   fmt::format("{}: bearing `{}` is a cylindrical roller bearing, which takes no axial load: let another "
                               "bearing hold the thrust (`axial = held`)",
                               owner, p.name));
    // The bearing that holds the thrust rates it by its catalogue's X and Y beyond e.
    if (thrust && ax && ax->choice == 0 &&
        (!ir::findSetting(p.settings, "e") || !ir::findSetting(p.settings, "X") || !ir::findSetting(p.settings, "Y")))
      diags_.error("E0225", p.span,
                   fmt::format("{}: bearing `{}` holds the shaft's thrust, which its life rates by P = X F_r + Y F_a "
                               "beyond F_a/F_r = e: give its catalogue's `e`, `X` and `Y`",
                               owner, p.name));
  }
  if (nBearings < 2)
    diags_.error("E0225", nameOr(st), fmt::format("{} needs two bearings (`bearing A at … {{ … }}`) to stand", owner));
  if (thrust && held == 0 && nBearings >= 2)
    diags_.error(
        "E0225", nameOr(st),
        fmt::format("{} carries an axial force (a helical gear's thrust or an axial load), but no bearing holds it: "
                    "give one bearing `axial = held`",
                    owner));
  if (held > 1)
    diags_.error("E0202", nameOr(st),
                 fmt::format("{}: {} bearings hold the axial force; one does (`axial = held`)", owner, held));
  noStageToSearch(out, m, owner);
  if (!m.hasOperating)
    diags_.error("E0231", nameOr(st),
                 fmt::format("{} needs an operating point, but gearbox `{}` has no `operating` block", owner, m.name));
  return out;
}

} // namespace gbx::sema
