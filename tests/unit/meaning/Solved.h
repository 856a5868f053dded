#pragma once
// A spec solved as `gbxc solve` solves it (the search, then the optimiser where needed), with
// each design's values read at its decided point: for tests of what a report promises.
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "passes/Optimise.h"
#include "passes/Search.h"

namespace gbx::solved {

struct Solved {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
  rt::SearchResult result;
  std::unique_ptr<rt::Evaluator> ev;
  // Design i as the reports read it: its choices and its decided freedoms.
  rt::Assignment at(size_t i) const {
    rt::Assignment a(*model);
    const auto& d = result.designs.at(i);
    a.choice = d.choice;
    for (size_t f = 0; f < d.freedoms.size(); ++f)
      a.box[f] = {d.freedoms[f], d.freedoms[f]};
    return a;
  }
  double value(const std::string& path, size_t i = 0) const {
    rt::Value v = ev->quantity(path, at(i));
    EXPECT_TRUE(v.isPoint()) << path << " is not a point: [" << v.lo << ", " << v.hi << "]";
    return v.mid();
  }
};

inline Solved solve(const std::string& text, size_t gearbox = 0) {
  Solved s;
  s.c = driver::compileText("t.gbx", text);
  EXPECT_TRUE(s.c->ok()) << s.c->diags.renderText(s.c->sources);
  if (!s.c->ok()) throw std::runtime_error("spec has errors");
  s.model = std::make_unique<rt::Model>(s.c->program, s.c->program.gearboxes.at(gearbox));
  // The search, then the optimiser where the rules or objectives need it (as `gbxc solve`).
  auto designs =
      rt::passes::optimise(s.c->program, *s.model, rt::passes::search(*s.model, 1, 1e9, nullptr), 1, nullptr);
  s.result = std::move(designs.designs);
  for (size_t i = 0; i < designs.freedoms.size() && i < s.result.designs.size(); ++i)
    s.result.designs[i].freedoms = designs.freedoms[i];
  s.ev = std::make_unique<rt::Evaluator>(*s.model);
  return s;
}

} // namespace gbx::solved
