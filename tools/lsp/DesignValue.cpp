#include "lsp/DesignValue.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <fmt/format.h>

#include "model/Evaluator.h"
#include "model/Model.h"
#include "report/Report.h"
#include "units/Unit.h"

namespace gbx::lsp {

bool fixedDesign(const ir::Gearbox& g) {
  for (const auto& st : g.stages)
    for (const auto& a : st.attributes)
      if ((a.role == ir::Attribute::Decision || a.role == ir::Attribute::Freedom) && a.members.size() != 1)
        return false;
  return true;
}

namespace {

// An attribute's expression larger than this, its lets expanded, is not evaluated for a hover.
constexpr double kMaxNodes = 1e6;

// The nodes an evaluation of e visits, a let's expression counted each time it is named;
// infinite for a let that names itself.
double expandedSize(const ir::Expr* e, const ir::Gearbox& g, std::vector<double>& memo, std::vector<char>& state) {
  if (!e) return 0;
  double n = 1;
  if (e->op == ir::Op::Let && e->let >= 0 && static_cast<size_t>(e->let) < g.lets.size()) {
    size_t i = static_cast<size_t>(e->let);
    if (state[i] == 1) return INFINITY;
    if (state[i] == 0) {
      state[i] = 1;
      memo[i] = expandedSize(g.lets[i].expr.get(), g, memo, state);
      state[i] = 2;
    }
    n += memo[i];
  }
  for (const auto& x : e->args)
    n += expandedSize(x.get(), g, memo, state);
  return n;
}

} // namespace

std::optional<std::string> designValue(const ir::Program& p, const ir::Gearbox& g, const ir::QuantityRef& r,
                                       const units::Dim& dim) {
  if ((r.owner != ir::QuantityRef::Stage && r.owner != ir::QuantityRef::Gearbox) || r.perGear || !fixedDesign(g))
    return std::nullopt;
  rt::Value v;
  try {
    rt::Model m(p, g);
    rt::Assignment a(m);
    std::fill(a.choice.begin(), a.choice.end(), 0); // every slot holds one value
    rt::Evaluator ev(m);
    // Attributes given by expressions, each evaluated once and then read as a sweep's value,
    // in rounds until none gains a value: one that needs itself through a computed quantity
    // (`face_width = (mass + mass) * 1 mm/kg`, a cycle sema cannot see) stays without one.
    struct Given {
      ir::QuantityRef ref;
      const ir::Expr* expr;
      bool known = false;
    };
    std::vector<Given> given;
    std::vector<double> memo(g.lets.size(), 0);
    std::vector<char> state(g.lets.size(), 0);
    for (size_t s = 0; s < g.stages.size(); ++s)
      for (const auto& at : g.stages[s].attributes) {
        if (at.role != ir::Attribute::Fixed || !at.value || at.value->isConst() || at.key == cat::Q::None) continue;
        if (!(expandedSize(at.value.get(), g, memo, state) <= kMaxNodes)) return std::nullopt;
        ir::QuantityRef ref;
        ref.owner = ir::QuantityRef::Stage;
        ref.index = static_cast<std::int16_t>(s);
        ref.gear = static_cast<std::int8_t>(at.gear);
        ref.key = at.key;
        ev.setOverride(ref, rt::Value::invalid());
        given.push_back({ref, at.value.get()});
      }
    for (bool progress = true; progress;) {
      progress = false;
      for (auto& x : given)
        if (!x.known)
          if (rt::Value y = ev.eval(*x.expr, a); y.kind != rt::Value::Invalid) {
            ev.setOverride(x.ref, y);
            x.known = progress = true;
          }
    }
    v = ev.quantity(r, a);
  } catch (const std::exception&) {
    return std::nullopt; // a spec the runtime cannot evaluate: the hover goes without
  }
  if (!v.isPoint() || !std::isfinite(v.lo)) return std::nullopt;
  units::DisplayUnit u = dim == units::dims::length && cat::readsInMicrometres(r.key) ? units::micrometres() : units::displayUnitFor(dim);
  std::string shown =
      dim.dimensionless() && v.exact && v.exact->isInteger() ? v.exact->str() : rt::formatNumber(u.shown(v.lo));
  if (!u.name.empty()) shown += " " + u.name;
  // A ratio reads as the reports write it, with its exact fraction.
  if (r.key == cat::Q::Ratio && v.exact && !v.exact->isInteger()) shown += " (" + v.exact->str() + ")";
  if (u.scale != 1 || u.offset != 0) shown += fmt::format(" ({:.6g} {} in SI)", v.lo, dim.siUnit());
  return fmt::format("= {} for the design of {}", shown, g.name);
}

namespace {

void walk(const ir::Expr* e, const std::function<void(const ir::Expr&)>& f) {
  if (!e) return;
  f(*e);
  // `inBaseline` is resolved in another gearbox: its ids are not this one's.
  for (const auto& x : e->args)
    walk(x.get(), f);
}

void walk(const std::vector<ir::Setting>& settings, const std::function<void(const ir::Expr&)>& f) {
  for (const auto& s : settings)
    walk(s.expr.get(), f);
}

} // namespace

const ir::Expr* quantityAt(const ir::Gearbox& g, const std::function<bool(const source::Span&)>& at) {
  const ir::Expr* best = nullptr;
  bool ambiguous = false;
  auto extent = [](const source::Span& s) {
    int endLine = s.endLine > 0 ? s.endLine : s.line, endCol = s.endLine > 0 ? s.endCol : s.col;
    return std::pair{endLine - s.line, endCol - s.col};
  };
  auto visit = [&](const ir::Expr& e) {
    if (e.op != ir::Op::Quantity || !e.type.isNumber() || !at(e.span)) return;
    if (e.ref.owner != ir::QuantityRef::Stage && e.ref.owner != ir::QuantityRef::Gearbox && e.ref.owner != ir::QuantityRef::Shaft) return;
    if (!best || extent(e.span) < extent(best->span)) {
      best = &e;
      ambiguous = false;
    } else if (extent(e.span) == extent(best->span) && !(e.ref == best->ref)) {
      ambiguous = true;
    }
  };
  for (const auto& st : g.stages)
    for (const auto& a : st.attributes)
      walk(a.value.get(), visit);
  for (const auto& l : g.lets)
    walk(l.expr.get(), visit);
  for (const auto& r : g.rules)
    walk(r.expr.get(), visit);
  for (const auto& o : g.objectives)
    walk(o.expr.get(), visit);
  walk(g.operating, visit);
  for (const auto& sc : g.scenes) {
    walk(sc.settings, visit);
    walk(sc.accuracy, visit);
    for (const auto& fx : sc.effects)
      walk(fx.params, visit);
  }
  for (const auto& m : g.modifies)
    for (const auto& rule : m.rules) {
      walk(rule.value.get(), visit);
      walk(rule.when.get(), visit);
    }
  for (const auto& sp : g.splits)
    walk(sp.settings, visit);
  for (const auto& st : g.studies) {
    for (const auto& o : st.outputs)
      walk(o.get(), visit);
    walk(st.settings, visit);
  }
  if (g.report) {
    for (const auto& c : g.report->columns)
      walk(c.get(), visit);
    walk(g.report->sortBy.get(), visit);
  }
  return ambiguous ? nullptr : best;
}

} // namespace gbx::lsp
