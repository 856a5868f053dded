#include "ir/Ir.h"

#include "catalogue/StageKinds.h"

namespace gbx::ir {

std::string Type::str() const {
  switch (kind) {
  case Number: return (integer ? std::string("integer") : std::string("real")) + (dim.dimensionless() ? "" : " " + dim.siUnit());
  case Bool: return "bool";
  case Interval: return "interval " + dim.siUnit();
  case Set: return "set " + dim.siUnit();
  case Stage: return "stage " + detail;
  case Gear: return "gear " + detail;
  case Collection: return "collection " + detail;
  case Signal: return "signal";
  case Symbol: return "symbol";
  case Material: return "material";
  case Scene: return "scene";
  case Split: return "split";
  case PerGear: return "per-gear " + dim.siUnit();
  case Block: return "block " + detail;
  case Shaft: return "shaft";
  case Bearing: return "bearing " + detail;
  case Notch: return "notch " + detail;
  case Error: return "error";
  }
  return "?";
}

Setting Setting::clone() const {
  Setting s;
  s.name = name;
  s.key = key;
  s.choice = choice;
  s.choices = choices;
  s.stage = stage;
  s.dim = dim;
  s.integer = integer;
  s.meshPeriods = meshPeriods;
  s.value = value;
  s.symbol = symbol;
  s.sceneRef = sceneRef;
  if (expr) s.expr = expr->clone();
  s.members = members;
  s.lo = lo;
  s.hi = hi;
  s.memberTexts = memberTexts;
  s.span = span;
  return s;
}

Scene Scene::clone() const {
  Scene s;
  s.name = name;
  s.target = target;
  s.stage = stage;
  for (const auto& e : effects) {
    Effect c{e.name, e.kind, {}, e.span};
    for (const auto& p : e.params) c.params.push_back(p.clone());
    s.effects.push_back(std::move(c));
  }
  for (const auto& x : settings) s.settings.push_back(x.clone());
  for (const auto& x : accuracy) s.accuracy.push_back(x.clone());
  s.outputs = outputs;
  s.span = span;
  return s;
}

ExprPtr Expr::clone() const {
  auto e = std::make_unique<Expr>();
  e->op = op;
  e->type = type;
  e->value = value;
  e->name = name;
  e->span = span;
  e->ref = ref;
  e->let = let;
  e->fn = fn;
  e->marker = marker;
  e->relative = relative;
  e->output = output;
  e->sense = sense;
  if (inBaseline) e->inBaseline = inBaseline->clone();
  for (const auto& a : args) e->args.push_back(a ? a->clone() : nullptr);
  return e;
}

bool uses(const Expr* e, std::initializer_list<Op> ops) {
  if (!e) return false;
  for (Op op : ops)
    if (e->op == op) return true;
  for (const auto& a : e->args)
    if (uses(a.get(), ops)) return true;
  return false;
}

ExprPtr makeConst(Number v, Dim d, bool integer, Span span) {
  auto e = std::make_unique<Expr>();
  e->op = Op::Const;
  e->value = v;
  e->type = Type::number(d, integer);
  e->span = span;
  return e;
}

const char* stageKindName(StageKind k) { return cat::kindSpec(k).name.c_str(); }

const Attribute* Stage::find(const std::string& n) const {
  for (const auto& a : attributes)
    if (a.name == n) return &a;
  return nullptr;
}

const Setting* findSetting(const std::vector<Setting>& s, const std::string& name) {
  for (const auto& x : s)
    if (x.name == name) return &x;
  return nullptr;
}

const Setting* findSetting(const std::vector<Setting>& s, Q key) {
  for (const auto& x : s)
    if (x.key == key) return &x;
  return nullptr;
}

const Effect* Scene::findEffect(cat::Effect kind) const {
  for (const auto& e : effects)
    if (e.kind == kind) return &e;
  return nullptr;
}

cat::Method Scene::method() const {
  const Setting* s = findSetting(accuracy, Q::Method);
  return s && s->choice >= 0 ? cat::kMethods[static_cast<size_t>(s->choice)].id : cat::Method::Rk8pd;
}

int Gearbox::stageIndex(const std::string& n) const {
  for (size_t i = 0; i < stages.size(); ++i)
    if (stages[i].name == n) return static_cast<int>(i);
  return -1;
}

int Gearbox::shaftIndex(const std::string& n) const {
  for (size_t i = 0; i < shafts.size(); ++i)
    if (shafts[i].name == n) return static_cast<int>(i);
  return -1;
}

int Gearbox::splitIndex(const std::string& n) const {
  for (size_t i = 0; i < splits.size(); ++i)
    if (splits[i].name == n) return static_cast<int>(i);
  return -1;
}

int Program::materialIndex(const std::string& n) const {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == n) return static_cast<int>(i);
  return -1;
}

bool Scene::hasEffect(const std::string& n) const {
  for (const auto& e : effects)
    if (e.name == n) return true;
  return false;
}

const Stage* Gearbox::findStage(const std::string& n) const {
  for (const auto& s : stages)
    if (s.name == n) return &s;
  return nullptr;
}

const Material* Program::findMaterial(const std::string& n) const {
  for (const auto& m : materials)
    if (m.name == n) return &m;
  return nullptr;
}

int Shaft::bearingIndex(const std::string& n) const {
  int k = 0;
  for (const auto& p : placed) {
    if (p.kind != Place::Bearing) continue;
    if (p.name == n) return k;
    ++k;
  }
  return -1;
}

} // namespace gbx::ir
