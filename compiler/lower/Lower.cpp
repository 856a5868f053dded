#include "lower/Lower.h"

#include <algorithm>

#include "sema/Catalogue.h"

namespace gbx::lower {

namespace {

std::vector<std::string> catalogueOrder(const sema::KindSpec& k) {
  std::vector<std::string> order;
  for (const auto& g : k.gears)
    for (const auto& a : k.gear) order.push_back(g + "." + a.name);
  for (const auto& a : k.stage) order.push_back(a.name);
  return order;
}

void lowerStage(ir::Stage& st) {
  const sema::KindSpec* k = sema::findKind(ir::stageKindName(st.kind));
  if (!k) return;
  for (const auto& a : k->stage) {
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
  auto order = catalogueOrder(*k);
  auto rank = [&](const ir::Attribute& a) {
    auto it = std::find(order.begin(), order.end(), a.name);
    return it - order.begin();
  };
  std::stable_sort(st.attributes.begin(), st.attributes.end(),
                   [&](const ir::Attribute& a, const ir::Attribute& b) { return rank(a) < rank(b); });
}

} // namespace

ir::Program lower(ir::Program p) {
  for (auto& g : p.gearboxes)
    for (auto& st : g.stages) lowerStage(st);
  return p;
}

} // namespace gbx::lower
