#pragma once
// A compiled spec text with one gearbox's model and its first design, for scene tests.
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "model/Model.h"

namespace gbx::test {

struct Fixture {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
  std::unique_ptr<rt::Assignment> design;
  const ir::Scene& scene(const std::string& name) const {
    for (const auto& s : model->gearbox.scenes)
      if (s.name == name) return s;
    throw std::runtime_error(name);
  }
  const ir::Study& study(const std::string& name) const {
    for (const auto& s : model->gearbox.studies)
      if (s.name == name) return s;
    throw std::runtime_error(name);
  }
};

inline Fixture compile(const std::string& file, const std::string& text, const std::string& gearbox) {
  Fixture f;
  f.c = driver::compileText(file, text);
  EXPECT_TRUE(f.c->ok()) << f.c->diags.renderText(f.c->sources);
  for (const auto& g : f.c->program.gearboxes)
    if (g.name == gearbox) {
      f.model = std::make_unique<rt::Model>(f.c->program, g);
      f.design = std::make_unique<rt::Assignment>(*f.model);
      for (size_t i = 0; i < f.model->slots.size(); ++i) f.design->choice[i] = 0;
    }
  EXPECT_TRUE(f.model) << gearbox;
  return f;
}

} // namespace gbx::test
