#include "lower/Lower.h"

#include <algorithm>
#include <functional>
#include <optional>

#include "catalogue/Settings.h"
#include "catalogue/Shafts.h"
#include "catalogue/StageKinds.h"

namespace gbx::lower {

namespace {

using ir::Q;
using ir::QuantityRef;

std::vector<std::string> catalogueOrder(const cat::KindSpec& k) {
  std::vector<std::string> order;
  for (const auto& g : k.gears)
    for (const auto& a : k.gear) order.push_back(g + "." + a.name);
  for (const auto& a : k.stage) order.push_back(a.name);
  return order;
}

void lowerStage(ir::Stage& st) {
  const cat::KindSpec& k = cat::kindSpec(st.kind);
  for (const auto& a : k.stage) {
    if (!a.dflt || st.find(a.name)) continue;
    ir::Attribute d;
    d.name = a.name;
    d.dim = a.dim;
    d.integer = a.integer;
    d.role = ir::Attribute::Default;
    d.value = ir::makeConst(*a.dflt, a.dim, a.integer);
    d.origin = "default";
    st.attributes.push_back(std::move(d));
  }
  auto order = catalogueOrder(k);
  auto rank = [&](const ir::Attribute& a) {
    auto it = std::find(order.begin(), order.end(), a.name);
    return it - order.begin();
  };
  std::stable_sort(st.attributes.begin(), st.attributes.end(),
                   [&](const ir::Attribute& a, const ir::Attribute& b) { return rank(a) < rank(b); });
  for (auto& a : st.attributes) {
    auto dot = a.name.find('.');
    if (dot != std::string::npos) a.gear = cat::gearIndex(k, a.name.substr(0, dot));
    // `pinion.z` names a gear's attribute; `rating.life` is a block's setting of the stage.
    a.key = cat::keyOf(a.gear < 0 ? a.name : a.name.substr(dot + 1)).value_or(Q::None);
    if (const auto* row = cat::findAttr(k, a.name); row && !a.symbol.empty()) {
      auto w = std::find(row->symbols.begin(), row->symbols.end(), a.symbol);
      if (w != row->symbols.end()) a.choice = static_cast<int>(w - row->symbols.begin());
    }
  }
}

// Resolves the names of one gearbox: quantity paths, lets, functions, settings, effects,
// scene outputs and study targets.
class Resolver {
public:
  Resolver(const ir::Program& p, const ir::Gearbox& g, const Resolver* baseline = nullptr) : p_(p), g_(g), baseline_(baseline) {}

  QuantityRef quantity(const std::string& path) const { return quantityRef(p_, g_, path); }

  // `scene.effect.parameter` in gearbox g: the scene, the effect's position and the key.
  static ir::Study::EffectParam effectParam(const ir::Gearbox& g, const std::string& target) {
    auto d1 = target.find('.'), d2 = target.find('.', d1 == std::string::npos ? d1 : d1 + 1);
    if (d1 == std::string::npos || d2 == std::string::npos) return {};
    for (size_t i = 0; i < g.scenes.size(); ++i)
      if (g.scenes[i].name == target.substr(0, d1))
        for (size_t k = 0; k < g.scenes[i].effects.size(); ++k)
          if (g.scenes[i].effects[k].name == target.substr(d1 + 1, d2 - d1 - 1))
            if (const auto* spec = cat::findEffect(g.scenes[i].effects[k].name))
              for (const auto& prm : spec->params)
                if (prm.name == target.substr(d2 + 1)) return {static_cast<int>(i), static_cast<int>(k), prm.key};
    return {};
  }

  void expr(ir::Expr& e) const {
    switch (e.op) {
    case ir::Op::Quantity:
      e.ref = quantity(e.name);
      e.ref.perGear = e.type.kind == ir::Type::PerGear;
      break;
    case ir::Op::Let:
      for (size_t i = 0; i < g_.lets.size(); ++i)
        if (g_.lets[i].name == e.name) e.let = static_cast<int>(i);
      break;
    case ir::Op::Call:
      if (const auto* f = cat::findFunction(e.name)) e.fn = f->id;
      break;
    case ir::Op::SceneOutput: {
      // "scene.fn(signal)"
      auto dot = e.name.find('.'), open = e.name.find('('), close = e.name.rfind(')');
      if (dot == std::string::npos) break;
      for (size_t i = 0; i < g_.scenes.size(); ++i)
        if (g_.scenes[i].name == e.name.substr(0, dot)) e.output.scene = static_cast<int>(i);
      // "scene.signal": a single result (dynamic_factor, stability), read by its signal alone.
      if (open == std::string::npos) {
        e.output.bare = true;
        if (const auto* s = cat::findSignal(e.name.substr(dot + 1))) e.output.signal = s->id;
        break;
      }
      if (close == std::string::npos) break;
      if (const auto* f = cat::findSignalFn(e.name.substr(dot + 1, open - dot - 1))) e.output.fn = f->id;
      {
        // "scene.fn(signal, k)": a mesh order after the signal.
        std::string inside = e.name.substr(open + 1, close - open - 1);
        if (auto comma = inside.find(','); comma != std::string::npos) {
          e.output.order = std::stoi(inside.substr(comma + 1));
          inside.resize(comma);
        }
        if (const auto* s = cat::findSignal(inside)) e.output.signal = s->id;
      }
      break;
    }
    default: break;
    }
    for (auto& a : e.args)
      if (a) expr(*a);
    // `relative(x)` divides by x of the baseline gearbox: x resolved there too.
    if (e.op == ir::Op::Relative && baseline_ && !e.args.empty() && e.args[0]) {
      e.inBaseline = e.args[0]->clone();
      baseline_->expr(*e.inBaseline);
    }
  }

  void expr(ir::ExprPtr& e) const {
    if (e) expr(*e);
  }

  // Settings against their catalogue rows: the key, an enumerated word's position, a stage.
  void settings(std::vector<ir::Setting>& list, const std::vector<cat::AttrSpec>& rows,
                const std::vector<std::string>& locals = {}) const {
    for (auto& s : list) {
      for (const auto& row : rows)
        if (row.name == s.name) {
          s.key = row.key;
          // One word, or a list of words joined by commas.
          size_t from = 0;
          while (!s.symbol.empty() && from <= s.symbol.size()) {
            size_t to = std::min(s.symbol.find(',', from), s.symbol.size());
            auto w = std::find(row.symbols.begin(), row.symbols.end(), s.symbol.substr(from, to - from));
            if (w != row.symbols.end()) s.choices.push_back(static_cast<int>(w - row.symbols.begin()));
            from = to + 1;
          }
          if (s.choices.size() == 1) s.choice = s.choices[0];
          if (row.value == cat::ValueKind::Stage) s.stage = g_.stageIndex(s.symbol);
        }
      if (s.key == Q::None) s.key = cat::keyOf(s.name).value_or(Q::None);
      expr(s.expr);
      // An effect's own words (`stiffness` in hertz_contact): their position in its list.
      std::function<void(ir::Expr&)> local = [&](ir::Expr& e) {
        if (e.op == ir::Op::Symbol) {
          auto w = std::find(locals.begin(), locals.end(), e.name);
          if (w != locals.end()) e.let = static_cast<int>(w - locals.begin());
        }
        for (auto& a : e.args)
          if (a) local(*a);
      };
      if (s.expr) local(*s.expr);
    }
  }

  // `g` is the gearbox this resolver reads (`g_`), taken here to be written.
  void gearbox(ir::Gearbox& g) {
    for (auto& st : g.stages)
      for (auto& a : st.attributes) {
        expr(a.value);
        if (a.sceneRef)
          for (size_t k = 0; k < g.scenes.size(); ++k)
            if (g.scenes[k].name == a.symbol) a.scene = static_cast<int>(k);
      }
    for (auto& l : g.lets) expr(l.expr);
    for (auto& r : g.rules) expr(r.expr);
    for (auto& o : g.objectives) expr(o.expr);
    settings(g.operating, cat::operatingSettings());
    for (auto& sc : g.scenes) {
      sc.stage = g.stageIndex(sc.target);
      settings(sc.settings, cat::sceneSettings());
      settings(sc.accuracy, cat::accuracySettings());
      for (auto& fx : sc.effects)
        if (const auto* spec = cat::findEffect(fx.name)) {
          fx.kind = spec->id;
          settings(fx.params, spec->params, spec->locals);
        }
      for (auto& o : sc.outputs) {
        o.bare = o.function.empty();
        if (const auto* f = cat::findSignalFn(o.function)) o.fn = f->id;
        if (const auto* s = cat::findSignal(o.signal)) o.id = s->id;
      }
    }
    for (auto& md : g.modifies) {
      md.stageIndex = g.stageIndex(md.stage);
      for (auto& r : md.rules) {
        // `pinion.lead_crowning`: the gear's position and the target's position in the catalogue.
        auto dot = r.target.find('.');
        std::string what = r.target;
        if (dot != std::string::npos && md.stageIndex >= 0) {
          r.gear = cat::gearIndex(cat::kindSpec(g.stages[static_cast<size_t>(md.stageIndex)].kind), r.target.substr(0, dot));
          what = r.target.substr(dot + 1);
        }
        const auto& targets = cat::modificationTargets();
        auto t = std::find(targets.begin(), targets.end(), what);
        r.modTarget = t == targets.end() ? -1 : static_cast<int>(t - targets.begin());
        expr(r.value);
        expr(r.when);
      }
    }
    for (auto& sp : g.splits) settings(sp.settings, cat::splitSettings());
    for (auto& sh : g.shafts) {
      settings(sh.settings, cat::shaftSettings());
      for (auto& seg : sh.segments) settings(seg.settings, cat::segmentSettings());
      for (auto& p : sh.placed)
        settings(p.settings, p.kind == ir::Shaft::Place::Bearing ? cat::bearingSettings()
                             : p.kind == ir::Shaft::Place::Disk  ? cat::diskSettings()
                             : p.kind == ir::Shaft::Place::Notch ? cat::notchSettings()
                             : p.kind == ir::Shaft::Place::Gear  ? cat::gearSettings()
                                                                 : cat::loadSettings());
    }
    for (auto& t : g.tolerances) t.ref = quantity(t.target);
    settings(g.toleranceSettings, cat::toleranceSettings());
    for (auto& st : g.studies) {
      if (st.kind == ir::Study::Sweep) {
        st.swept = quantity(st.target);
        st.sweptEffect = effectParam(g_, st.target);
        if (st.series) {
          st.series->ref = quantity(st.series->target);
          st.series->effect = effectParam(g_, st.series->target);
        }
        if (baseline_) {
          st.sweptInBaseline = baseline_->quantity(st.target);
          st.sweptEffectInBaseline = effectParam(baseline_->g_, st.target);
          if (st.series) {
            st.seriesInBaseline = baseline_->quantity(st.series->target);
            st.seriesEffectInBaseline = effectParam(baseline_->g_, st.series->target);
          }
        }
      }
      for (size_t i = 0; i < g.scenes.size(); ++i)
        if (g.scenes[i].name == st.target) st.scene = static_cast<int>(i);
      for (auto& o : st.outputs) expr(o);
      settings(st.settings, st.kind == ir::Study::Sweep ? cat::sweepSettings() : cat::workPrecisionSettings());
    }
    if (g.report) {
      expr(g.report->sortBy);
      g.report->ratioColumn.clear();
      for (auto& c : g.report->columns) {
        expr(c);
        g.report->ratioColumn.push_back(c && c->op == ir::Op::Quantity && c->ref.owner == QuantityRef::Gearbox && c->ref.key == Q::Ratio);
      }
    }
  }

private:
  const ir::Program& p_;
  const ir::Gearbox& g_;
  const Resolver* baseline_;
};

} // namespace

QuantityRef quantityRef(const ir::Program& p_, const ir::Gearbox& g_, const std::string& path) {
  QuantityRef r;
  auto dot = path.find('.');
  if (dot == std::string::npos) {
    auto k = cat::keyOf(path);
    if (!k) return r;
    r.key = *k;
    r.owner = (*k == Q::Stages || *k == Q::Teeth) ? QuantityRef::Collection : QuantityRef::Gearbox;
    return r;
  }
  std::string head = path.substr(0, dot), rest = path.substr(dot + 1);
  if (int st = g_.stageIndex(head); st >= 0) {
    r.owner = QuantityRef::Stage;
    r.index = static_cast<std::int16_t>(st);
    const cat::KindSpec& k = cat::kindSpec(g_.stages[static_cast<size_t>(st)].kind);
    auto d2 = rest.find('.');
    std::string first = d2 == std::string::npos ? rest : rest.substr(0, d2);
    if (int gi = cat::gearIndex(k, first); gi >= 0) {
      r.gear = static_cast<std::int8_t>(gi);
      if (d2 == std::string::npos) return r;  // the gear itself
      rest = rest.substr(d2 + 1);
    }
    r.key = cat::keyOf(rest).value_or(Q::None);
    if (r.key == Q::Teeth) r.owner = QuantityRef::Collection;
    return r;
  }
  if (int sp = g_.splitIndex(head); sp >= 0) {
    r.owner = QuantityRef::Split;
    r.index = static_cast<std::int16_t>(sp);
    r.key = cat::keyOf(rest).value_or(Q::None);
    return r;
  }
  // `input.deflection`, `input.A.life`: the shaft's, or one bearing's (its position among them).
  if (int sh = g_.shaftIndex(head); sh >= 0) {
    r.owner = QuantityRef::Shaft;
    r.index = static_cast<std::int16_t>(sh);
    // `deflection_at(hs.pinion)`: the gear's position among the shaft's placements.
    if (rest.rfind("notch_at(", 0) == 0) {
      // `notch_at(60 mm).fatigue_safety`: the notch's position among the placements.
      auto close = rest.find(')');
      std::string at = rest.substr(9, close - 9);
      const auto& placed = g_.shafts[static_cast<size_t>(sh)].placed;
      for (size_t k = 0; k < placed.size() && r.gear == -1; ++k)
        if (placed[k].kind == ir::Shaft::Place::Notch && units::showQuantity(placed[k].at, units::dims::length) == at)
          r.gear = static_cast<std::int8_t>(-2 - static_cast<int>(k));
      r.key = cat::keyOf(rest.substr(std::min(rest.size(), close + 2))).value_or(Q::None);
      return r;
    }
    if (auto open = rest.find('('); open != std::string::npos) {
      std::string gear = rest.substr(open + 1, rest.size() - open - 2);
      const auto& placed = g_.shafts[static_cast<size_t>(sh)].placed;
      for (size_t k = 0; k < placed.size(); ++k)
        if (placed[k].kind == ir::Shaft::Place::Gear && placed[k].name == gear) r.gear = static_cast<std::int8_t>(k);
      r.key = cat::keyOf(rest.substr(0, open)).value_or(Q::None);
      return r;
    }
    auto d2 = rest.find('.');
    if (d2 != std::string::npos) {
      r.gear = static_cast<std::int8_t>(g_.shafts[static_cast<size_t>(sh)].bearingIndex(rest.substr(0, d2)));
      rest = rest.substr(d2 + 1);
    }
    r.key = cat::keyOf(rest).value_or(Q::None);
    return r;
  }
  if (int m = p_.materialIndex(head); m >= 0) {
    r.owner = QuantityRef::Material;
    r.index = static_cast<std::int16_t>(m);
    r.key = cat::keyOf(rest).value_or(Q::None);
  }
  return r;
}

ir::Program lower(ir::Program p) {
  for (auto& m : p.materials)
    for (auto& s : m.properties) {
      s.key = cat::keyOf(s.name).value_or(Q::None);
      for (const auto& row : cat::materialProperties())
        if (row.key == s.key && !s.symbol.empty()) {
          auto w = std::find(row.symbols.begin(), row.symbols.end(), s.symbol);
          if (w != row.symbols.end()) s.choice = static_cast<int>(w - row.symbols.begin());
        }
    }
  // Every stage first: a gearbox's `relative(x)` resolves x in its baseline too.
  for (auto& g : p.gearboxes)
    for (auto& st : g.stages) lowerStage(st);
  for (auto& g : p.gearboxes) {
    const ir::Gearbox* base = nullptr;
    for (const auto& b : p.gearboxes)
      if (!g.baseline.empty() && b.name == g.baseline) base = &b;
    std::optional<Resolver> baseline;
    if (base) baseline.emplace(p, *base);
    Resolver(p, g, baseline ? &*baseline : nullptr).gearbox(g);
  }
  return p;
}

} // namespace gbx::lower
