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

// A spur mesh (eps_alpha 1.68: the stiffness swings by about a third) with 2 % damping, its
// mesh frequency twice its natural frequency at 27 693 rpm: the principal parametric
// resonance, with a sweep `tongue` across it.
inline std::string spurTongueSpec(const std::string& rtol, const std::string& outputs) {
  return R"(import materials;
gearbox SpurTongue {
  stage s1: spur {
    pinion.z = 25;  wheel.z = 50;
    normal_module = 3 mm; pressure_angle = 20 deg;
    face_width = 30 mm; material = steel_42CrMo4;
  }
  operating { input_speed = 27693 rpm; input_torque = 200 N*m; }
  scene mesh on s1 {
    effects { varying_stiffness { harmonics = 10; } damping { ratio = 0.02; } }
    steady_state = periodic;
    record = 1 mesh_period; samples = 160;
    accuracy { method = rk8pd; rtol = )" +
         rtol + R"(; }
    output )" +
         outputs + R"(;
  }
  study tongue { sweep input_speed in 20000..36000 rpm step 1000 rpm; output mesh.stability; }
}
)";
}

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
