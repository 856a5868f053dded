#include "search/Model.h"

#include <cmath>

namespace gbx::rt {

namespace {

Value constant(const units::Number& n) {
  if (n.isRational()) return Value::rational(n.rational());
  return Value::number(n.toDouble());
}

} // namespace

Model::Model(const ir::Program& p, const ir::Gearbox& g) : program(p), gearbox(g) {
  for (const auto& st : g.stages) {
    StageInfo info;
    info.ir = &st;
    int si = static_cast<int>(stages.size());
    for (const auto& a : st.attributes) {
      info.attrs[a.name] = &a;
      if (a.role == ir::Attribute::Decision || (a.role == ir::Attribute::Freedom && !a.members.empty())) {
        Slot s;
        s.path = st.name + "." + a.name;
        s.attr = a.name;
        s.stage = si;
        if (!a.members.empty()) {
          for (const auto& m : a.members) s.values.push_back(constant(m));
        } else if (a.lo && a.hi) {
          // Integer ranges: bounds were checked to be whole numbers by sema.
          auto lo = a.lo->rational().num(), hi = a.hi->rational().num();
          for (auto v = lo; v <= hi; ++v) s.values.push_back(Value::rational(Rational(static_cast<std::int64_t>(v))));
        }
        info.slots.push_back(static_cast<int>(slots.size()));
        slots.push_back(std::move(s));
      } else if (a.role == ir::Attribute::Freedom && a.lo && a.hi) {
        Freedom f;
        f.path = st.name + "." + a.name;
        f.attr = a.name;
        f.stage = si;
        f.lo = a.lo->toDouble();
        f.hi = a.hi->toDouble();
        info.freedoms.push_back(static_cast<int>(freedoms.size()));
        freedoms.push_back(f);
      }
    }
    stages.push_back(std::move(info));
  }
}

int Model::stageIndex(const std::string& name) const {
  for (size_t i = 0; i < stages.size(); ++i)
    if (stages[i].ir->name == name) return static_cast<int>(i);
  return -1;
}

const ir::Attribute* Model::attribute(int stage, const std::string& name) const {
  auto it = stages[static_cast<size_t>(stage)].attrs.find(name);
  return it == stages[static_cast<size_t>(stage)].attrs.end() ? nullptr : it->second;
}

int Model::slotOf(int stage, const std::string& attr) const {
  for (int s : stages[static_cast<size_t>(stage)].slots)
    if (slots[static_cast<size_t>(s)].attr == attr) return s;
  return -1;
}

int Model::freedomOf(int stage, const std::string& attr) const {
  for (int f : stages[static_cast<size_t>(stage)].freedoms)
    if (freedoms[static_cast<size_t>(f)].attr == attr) return f;
  return -1;
}

std::optional<double> Model::operating(const std::string& name) const {
  const auto* s = ir::findSetting(gearbox.operating, name);
  if (!s || !s->value) return std::nullopt;
  return s->value->toDouble();
}

Assignment::Assignment(const Model& m) : choice(m.slots.size(), -1) {
  for (const auto& f : m.freedoms) box.emplace_back(f.lo, f.hi);
}

} // namespace gbx::rt
