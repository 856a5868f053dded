#include "model/Model.h"

#include <algorithm>
#include <atomic>

#include <cmath>

#include <fmt/format.h>

#include "catalogue/StageKinds.h"
#include "model/StageKind.h"

namespace gbx::rt {

namespace {

Value constant(const units::Number& n) {
  if (n.isRational()) return Value::rational(n.rational());
  return Value::number(n.toDouble());
}

// A decision's values, ascending: its set's members, else every whole number of its range
// (sema checked the bounds to be whole numbers).
std::vector<Value> domainValues(const std::vector<units::Number>& members, const std::optional<units::Number>& lo,
                                const std::optional<units::Number>& hi) {
  std::vector<Value> out;
  for (const auto& m : members)
    out.push_back(constant(m));
  if (members.empty() && lo && hi)
    for (auto v = lo->rational().num(); v <= hi->rational().num(); ++v)
      out.push_back(Value::rational(Rational(static_cast<std::int64_t>(v))));
  return out;
}

std::uint64_t nextSerial() {
  static std::atomic<std::uint64_t> n{0};
  return ++n;
}
} // namespace

bool readsOwnStage(const ir::Expr& e, int stage, int depth) {
  if (depth > 64) return false;
  switch (e.op) {
  case ir::Op::Quantity:
    if (e.ref.owner == ir::QuantityRef::Stage && e.ref.index != stage) return false;
    if (e.ref.owner != ir::QuantityRef::Stage && e.ref.owner != ir::QuantityRef::Material) return false;
    break;
  case ir::Op::Let:
  case ir::Op::Scatter:
  case ir::Op::SceneOutput:
  case ir::Op::Relative: return false;
  default: break;
  }
  for (const auto& x : e.args)
    if (x && !readsOwnStage(*x, stage, depth + 1)) return false;
  return true;
}

Model::Model(const ir::Program& p, const ir::Gearbox& g) : program(p), gearbox(g), serial(nextSerial()) {
  for (const auto& st : g.stages) {
    StageInfo info;
    info.ir = &st;
    info.kind = &stageKindImpl(st.kind);
    info.entries.resize(static_cast<size_t>(st.gears.size() + 1) * cat::kKeyCount);
    int si = static_cast<int>(stages.size());
    auto at = [&](const ir::Attribute& a) -> StageInfo::Entry& {
      return info.entries[static_cast<size_t>(a.gear + 1) * cat::kKeyCount + static_cast<size_t>(a.key)];
    };
    for (const auto& a : st.attributes) {
      if (a.key == Q::None) continue;
      at(a).attr = &a;
      if (a.role == ir::Attribute::Decision || (a.role == ir::Attribute::Freedom && !a.members.empty())) {
        Slot s;
        s.path = st.name + "." + a.name;
        s.attr = a.name;
        s.stage = si;
        s.gear = a.gear;
        s.key = a.key;
        s.dim = a.dim;
        if (a.memberTexts.size() == a.members.size()) s.texts = a.memberTexts;
        s.values = domainValues(a.members, a.lo, a.hi);
        at(a).slot = static_cast<int>(slots.size());
        info.slots.push_back(static_cast<int>(slots.size()));
        slots.push_back(std::move(s));
      } else if (a.role == ir::Attribute::Freedom && a.lo && a.hi) {
        Freedom f;
        f.path = st.name + "." + a.name;
        f.attr = a.name;
        f.stage = si;
        f.gear = a.gear;
        f.key = a.key;
        f.dim = a.dim;
        f.lo = a.lo->toDouble();
        f.hi = a.hi->toDouble();
        at(a).freedom = static_cast<int>(freedoms.size());
        info.freedoms.push_back(static_cast<int>(freedoms.size()));
        freedoms.push_back(f);
      }
    }
    if (const ir::Attribute* mat = info.entry(-1, Q::Material).attr; mat && !mat->symbol.empty())
      info.material = p.findMaterial(mat->symbol);
    for (size_t gi = 0; gi < st.gears.size(); ++gi) {
      const ir::Attribute* own = info.entry(static_cast<int>(gi), Q::Material).attr;
      info.gearMaterial.push_back(own && !own->symbol.empty() ? p.findMaterial(own->symbol) : info.material);
    }
    // Elastic constants: the stage's material, else the pinion's own.
    const ir::Material* elasticOf = info.material ? info.material : info.gearMaterial.empty() ? nullptr : info.gearMaterial[0];
    if (elasticOf) {
      auto get = [&](Q key, double& out) {
        if (const auto* s = ir::findSetting(elasticOf->properties, key); s && s->value) out = s->value->toDouble();
      };
      get(Q::YoungsModulus, info.elastic.E);
      get(Q::Poisson, info.elastic.nu);
      get(Q::Density, info.elastic.density);
      info.elastic.assumed = false;
    }
    // The one range of the key the kind's condition fixes is solved, not searched.
    if (info.kind->solve) {
      std::vector<int> keyed;
      for (int f : info.freedoms)
        if (freedoms[static_cast<size_t>(f)].key == info.kind->solvedKey) keyed.push_back(f);
      if (keyed.size() == 1) {
        freedoms[static_cast<size_t>(keyed[0])].solved = true;
        info.freedoms.erase(std::find(info.freedoms.begin(), info.freedoms.end(), keyed[0]));
      }
    }
    // The shafts of its two gears, if both sit on one, and the last stage they carry a gear of.
    int pinionShaft = -1, wheelShaft = -1;
    for (size_t k = 0; k < g.shafts.size(); ++k)
      for (const auto& p : g.shafts[k].placed)
        if (p.kind == ir::Shaft::Place::Gear && p.stage == static_cast<int>(si))
          (p.gear == cat::gear::Pinion ? pinionShaft : wheelShaft) = static_cast<int>(k);
    // A bevel stage's K_Hbeta comes from its mounting, not from its shafts.
    const bool cylindrical = st.kind == ir::StageKind::Spur || st.kind == ir::StageKind::Helical;
    if (pinionShaft >= 0 && wheelShaft >= 0 && cylindrical)
      for (int k : {pinionShaft, wheelShaft})
        for (const auto& p : g.shafts[static_cast<size_t>(k)].placed)
          info.shaftStagesUpTo = std::max(info.shaftStagesUpTo, p.stage);
    info.selfContained = g.splits.empty() && info.shaftStagesUpTo < 0 &&
                         std::all_of(st.attributes.begin(), st.attributes.end(),
                                     [&](const ir::Attribute& a) { return !a.value || readsOwnStage(*a.value, si); });
    stages.push_back(std::move(info));
  }
  addShaftDomains();
  for (const auto& sc : g.scenes) scenes.push_back(planScene(sc));
}

namespace {

std::string mm(const units::Number& x) { return fmt::format("{:g}", x.toDouble() * 1e3); }

// A searched shaft setting's name in reports: `input.segment(35..70 mm).diameter`,
// `input.A.radial_stiffness`, `input.notch_at(60 mm).radius`, `input.heat_treatment_diameter`.
std::string shaftSettingPath(const ir::Shaft& sh, const ir::Setting& s) {
  for (const auto& seg : sh.segments)
    for (const auto& x : seg.settings)
      if (&x == &s) return fmt::format("{}.segment({}..{} mm).{}", sh.name, mm(seg.x0), mm(seg.x1), s.name);
  for (const auto& p : sh.placed)
    for (const auto& x : p.settings) {
      if (&x != &s) continue;
      if (p.kind == ir::Shaft::Place::Bearing) return fmt::format("{}.{}.{}", sh.name, p.name, s.name);
      const char* word = p.kind == ir::Shaft::Place::Notch  ? "notch"
                         : p.kind == ir::Shaft::Place::Disk ? "disk"
                                                            : "load";
      return fmt::format("{}.{}_at({} mm).{}", sh.name, word, mm(p.at), s.name);
    }
  return sh.name + "." + s.name;
}

} // namespace

void Model::addShaftDomains() {
  shaftDomains.resize(gearbox.shafts.size());
  if (stages.empty()) return;
  for (size_t k = 0; k < gearbox.shafts.size(); ++k) {
    const ir::Shaft& sh = gearbox.shafts[k];
    int host = -1;
    for (const auto& p : sh.placed)
      if (p.kind == ir::Shaft::Place::Gear && p.stage >= 0 && (host < 0 || p.stage < host)) host = p.stage;
    if (host < 0) host = 0;
    StageInfo& info = stages[static_cast<size_t>(host)];
    auto add = [&](const ir::Setting& s) {
      if (!s.searched()) return;
      ShaftSetting ref{static_cast<int>(k), &s};
      std::string path = shaftSettingPath(sh, s);
      if (!s.members.empty() || s.integer) {
        Slot sl;
        sl.path = path;
        sl.attr = path;
        sl.stage = host;
        sl.key = s.key;
        sl.dim = s.dim;
        sl.shaft = ref;
        sl.values = domainValues(s.members, s.lo, s.hi);
        if (!s.members.empty() && s.memberTexts.size() == s.members.size()) sl.texts = s.memberTexts;
        info.slots.push_back(static_cast<int>(slots.size()));
        shaftDomains[k].slots.push_back(static_cast<int>(slots.size()));
        slots.push_back(std::move(sl));
        return;
      }
      Freedom f;
      f.path = path;
      f.attr = path;
      f.stage = host;
      f.key = s.key;
      f.dim = s.dim;
      f.shaft = ref;
      f.lo = s.lo->toDouble();
      f.hi = s.hi->toDouble();
      info.freedoms.push_back(static_cast<int>(freedoms.size()));
      shaftDomains[k].freedoms.push_back(static_cast<int>(freedoms.size()));
      freedoms.push_back(f);
      shaftFreedoms = true;
    };
    for (const auto& s : sh.settings)
      add(s);
    for (const auto& seg : sh.segments)
      for (const auto& s : seg.settings)
        add(s);
    for (const auto& p : sh.placed)
      for (const auto& s : p.settings)
        add(s);
  }
}

Value shaftSettingValue(const Model& m, const ir::Setting& s, const Assignment& a) {
  if (s.value) return constant(*s.value);
  for (size_t i = 0; i < m.slots.size(); ++i)
    if (m.slots[i].shaft.setting == &s) {
      int c = i < a.choice.size() ? a.choice[i] : -1;
      return c < 0 ? Value::invalid() : m.slots[i].values[static_cast<size_t>(c)];
    }
  for (size_t f = 0; f < m.freedoms.size(); ++f)
    if (m.freedoms[f].shaft.setting == &s) {
      auto [lo, hi] = f < a.box.size() ? a.box[f] : std::pair{m.freedoms[f].lo, m.freedoms[f].hi};
      return lo == hi ? Value::number(lo) : Value::range(lo, hi);
    }
  return Value::invalid();
}

std::optional<double> Model::operating(Q key) const {
  const auto* s = ir::findSetting(gearbox.operating, key);
  if (!s || !s->value) return std::nullopt;
  return s->value->toDouble();
}

const ir::Material* Model::material(int stage) const { return info(stage).material; }

const ir::Material* Model::material(int stage, int gear) const {
  const auto& m = info(stage).gearMaterial;
  return gear >= 0 && static_cast<size_t>(gear) < m.size() ? m[static_cast<size_t>(gear)] : material(stage);
}

Assignment::Assignment(const Model& m) : choice(m.slots.size(), -1) {
  for (const auto& f : m.freedoms) box.emplace_back(f.lo, f.hi);
}

} // namespace gbx::rt
