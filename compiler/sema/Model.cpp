#include "sema/Model.h"

namespace gbx::sema {

Binding* StageModel::findAttr(const std::string& path) {
  for (auto& [p, b] : attrs)
    if (p == path) return &b;
  return nullptr;
}

const Binding* StageModel::findAttr(const std::string& path) const {
  for (const auto& [p, b] : attrs)
    if (p == path) return &b;
  return nullptr;
}

void StageModel::setAttr(const std::string& path, Binding b) {
  if (auto* x = findAttr(path)) *x = std::move(b);
  else attrs.emplace_back(path, std::move(b));
}

const StageModel* GearboxModel::findStage(const std::string& n) const {
  for (const auto& s : stages)
    if (s.name == n) return &s;
  return nullptr;
}

StageModel* GearboxModel::findStage(const std::string& n) {
  for (auto& s : stages)
    if (s.name == n) return &s;
  return nullptr;
}

namespace {
const ast::Stmt* byName(const std::vector<const ast::Stmt*>& v, const std::string& n) {
  for (const auto* s : v)
    if (s->name == n) return s;
  return nullptr;
}
} // namespace

const ast::Stmt* GearboxModel::findScene(const std::string& n) const { return byName(scenes, n); }
const ast::Stmt* GearboxModel::findSplit(const std::string& n) const { return byName(splits, n); }
const ast::Stmt* GearboxModel::findShaft(const std::string& n) const { return byName(shafts, n); }
const ast::Stmt* GearboxModel::findLet(const std::string& n) const { return byName(lets, n); }

} // namespace gbx::sema
