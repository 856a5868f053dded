// Every catalogue row has its runtime row and every runtime row its catalogue row: an
// entry added to one side only fails here instead of passing checking and being ignored
// at run time.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "catalogue/Effects.h"
#include "catalogue/Functions.h"
#include "catalogue/Methods.h"
#include "catalogue/Settings.h"
#include "catalogue/Signals.h"
#include "catalogue/StageKinds.h"
#include "driver/Driver.h"
#include "dynamics/Effects.h"
#include "dynamics/Ode.h"
#include "dynamics/Scene.h"
#include "dynamics/Statistics.h"
#include "model/Builtins.h"
#include "model/Evaluator.h"
#include "model/StageKind.h"
#include "report/Formats.h"

namespace gbx {
namespace {

// Catalogue rows stand at the position of their id, so id-indexed look-ups hold.
template <class Rows>
void expectIndexed(const Rows& rows, const char* what) {
  size_t i = 0;
  for (const auto& r : rows) EXPECT_EQ(static_cast<size_t>(r.id), i++) << what << " row " << r.name << " is out of place";
}

TEST(Registry, EveryFunctionHasOneImplementation) {
  expectIndexed(cat::kFunctions, "function");
  for (const auto& f : cat::kFunctions) EXPECT_NE(rt::builtin(f.id), nullptr) << "function `" << f.name << "` has no implementation";
  std::set<int> seen;
  for (const auto& r : rt::builtinRows()) {
    EXPECT_LT(static_cast<int>(r.id), cat::kFunctionCount) << "an implementation has no catalogue row";
    EXPECT_TRUE(seen.insert(static_cast<int>(r.id)).second) << "two implementations of one function";
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(cat::kFunctionCount));
}

TEST(Registry, EveryEffectIsImplementedByEverySceneModel) {
  expectIndexed(cat::effects(), "effect");
  std::set<int> seen;
  for (const auto& r : rt::dyn::effectRows()) {
    EXPECT_TRUE(seen.insert(static_cast<int>(r.id)).second);
    EXPECT_LT(static_cast<size_t>(r.id), cat::effects().size()) << "a runtime effect has no catalogue row";
  }
  for (const auto& e : cat::effects()) {
    const auto* row = rt::dyn::effectRow(e.id);
    ASSERT_NE(row, nullptr) << "effect `" << e.name << "` has no runtime row";
    EXPECT_TRUE(row->mesh || row->drive) << "effect `" << e.name << "` changes nothing in the single-mesh model";
    for (const auto& p : e.params) EXPECT_NE(p.key, cat::Q::None) << e.name << "." << p.name << " has no key";
    if (row->planetary) continue;
    // An effect the planetary model lacks is refused by the checker, not dropped at run time.
    auto c = driver::compileText("registry.gbx", R"(gearbox P {
      stage p: planetary { sun.z = 20; planet.z = 31; ring.z = 82; planets = 3; module = 1 mm; face_width = 10 mm; }
      operating { input_speed = 600 rpm; input_torque = 10 N*m; }
      scene v on p { effects { )" + e.name + R"( { } } settle = 20 mesh_periods; record = 4 mesh_periods; output rms(displacement); }
    })");
    EXPECT_FALSE(c->ok()) << "effect `" << e.name << "` is not implemented by the planetary model, and the checker lets it through";
  }
}

TEST(Registry, EveryNumberFunctionOfASignalHasAStatistic) {
  expectIndexed(cat::kSignalFns, "signal function");
  for (const auto& f : cat::kSignalFns) {
    // A function of the mesh orders reads the signal's spectrum, not a statistic of it.
    if (f.number && f.order == cat::OrderArg::None)
      EXPECT_NE(rt::dyn::statistic(f.id), nullptr) << "`" << f.name << "` has no statistic";
    else
      EXPECT_EQ(rt::dyn::statistic(f.id), nullptr) << "`" << f.name << "` is a series or an order's, not a statistic";
  }
  for (const auto& r : rt::dyn::statisticRows()) EXPECT_TRUE(cat::signalFnSpec(r.id).number);
  expectIndexed(cat::sceneSignals(), "signal");
}

TEST(Registry, EveryMethodHasAStepper) {
  expectIndexed(cat::kMethods, "method");
  for (const auto& m : cat::kMethods) EXPECT_NE(rt::dyn::stepType(m.id), nullptr) << "method `" << m.name << "` has no stepper";
  EXPECT_EQ(rt::dyn::methodRows().size(), std::size(cat::kMethods));
}

TEST(Registry, EveryStageKindComputesWhatItsCatalogueDerives) {
  ASSERT_EQ(cat::stageKinds().size(), rt::stageKindImpls().size());
  for (size_t i = 0; i < cat::stageKinds().size(); ++i)
    EXPECT_EQ(static_cast<size_t>(cat::stageKinds()[i]->kind), i)
        << "kind row " << cat::stageKinds()[i]->name << " is out of place";
  for (const auto* kp : cat::stageKinds()) {
    const auto& k = *kp;
    const auto& impl = rt::stageKindImpl(k.kind);
    EXPECT_EQ(impl.kind, k.kind);
    for (const auto& a : k.stage) {
      EXPECT_NE(a.key, cat::Q::None) << k.name << "." << a.name << " has no key";
      if (a.role != cat::AttrRole::Input) {
        EXPECT_NE(impl.stageFn(a.key), nullptr) << k.name << " stages do not compute `" << a.name << "`";
      }
    }
    for (const auto& a : k.gear) {
      EXPECT_NE(a.key, cat::Q::None) << k.name << " gear ." << a.name << " has no key";
      if (a.role != cat::AttrRole::Input) {
        EXPECT_NE(impl.gearFn(a.key), nullptr) << k.name << " gears do not compute `" << a.name << "`";
      }
    }
    // And nothing the runtime computes is missing from the catalogue (it could never be named).
    for (const auto& row : impl.rows) {
      bool listed = false;
      for (const auto& a : row.perGear ? k.gear : k.stage) listed = listed || a.key == row.key;
      EXPECT_TRUE(listed) << k.name << " computes `" << cat::keyName(row.key) << "`, which its catalogue row does not list";
    }
  }
}

TEST(Registry, EverySettingRowHasAKey) {
  for (const auto* rows : {&cat::gearboxQuantities(), &cat::operatingSettings(), &cat::materialProperties(), &cat::sceneSettings(),
                           &cat::accuracySettings(), &cat::splitSettings(), &cat::splitOutputs(), &cat::workPrecisionSettings()})
    for (const auto& a : *rows) EXPECT_NE(a.key, cat::Q::None) << "`" << a.name << "` has no key";
}

TEST(Registry, ReportFormatsAreDistinct) {
  std::set<std::string_view> names;
  for (const auto& f : rt::reportFormats()) EXPECT_TRUE(names.insert(f.name).second);
}

rt::dyn::SceneOverrides quickRun() {
  rt::dyn::SceneOverrides o;
  o.estimateError = false;
  o.keepSeries = false;
  return o;
}

// Run end to end: every gearbox and split quantity evaluates, every time signal is
// recorded by both scene models.
std::unique_ptr<driver::Compilation> compile(const std::string& text) {
  auto c = driver::compileText("registry.gbx", text);
  EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  return c;
}

// Every time signal that one of these effects enables (or that needs none).
std::string allSignals(const std::set<cat::Effect>& listed) {
  std::string out;
  for (const auto& s : cat::sceneSignals()) {
    bool on = s.needsAnyEffect.empty();
    for (auto x : s.needsAnyEffect) on = on || listed.count(x);
    if (!s.scalar && on) out += std::string(out.empty() ? "" : ", ") + "rms(" + std::string(s.name) + ")";
  }
  return out;
}

TEST(Registry, EveryGearboxQuantityEvaluates) {
  auto c = compile(R"(gearbox G {
    stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
    operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
  })");
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  for (const auto& q : cat::gearboxQuantities()) {
    auto v = ev.gearboxQuantity(q.key, a);
    EXPECT_TRUE(v.isNumber() && std::isfinite(v.lo)) << "`" << q.name << "` does not evaluate";
  }
}

TEST(Registry, EverySignalIsRecordedBySingleMeshAndPlanetaryScenes) {
  using cat::Effect;
  std::string effects = "effects { varying_stiffness { harmonics = 3; } damping { ratio = 0.05; } "
                        "transmission_error { amplitude = 5 um; } backlash { clearance = 0.1 mm; } }";
  std::set<Effect> listed = {Effect::VaryingStiffness, Effect::Damping, Effect::TransmissionError, Effect::Backlash};
  // The loaded mesh replaces varying_stiffness and transmission_error: a scene of its own.
  std::string loaded = "effects { loaded_mesh { slices = 10; positions = 32; } damping { ratio = 0.05; } backlash { clearance = 0.1 mm; } }";
  std::set<Effect> loadedListed = {Effect::LoadedMesh, Effect::Damping, Effect::Backlash};
  auto c = compile(R"(gearbox G {
    stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
    operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
    scene v on s { )" + effects + R"( settle = 20 mesh_periods; record = 4 mesh_periods; output )" + allSignals(listed) + R"(; }
  }
  gearbox L {
    stage s: spur { pinion.z = 20; wheel.z = 60; normal_module = 2 mm; face_width = 20 mm; }
    operating { input_speed = 1000 rpm; input_torque = 100 N*m; }
    scene v on s { )" + loaded + R"( settle = 20 mesh_periods; record = 4 mesh_periods; output )" + allSignals(loadedListed) + R"(; }
  }
  gearbox P {
    stage p: planetary { sun.z = 20; planet.z = 31; ring.z = 82; planets = 3; module = 1 mm; face_width = 10 mm; }
    operating { input_speed = 600 rpm; input_torque = 10 N*m; }
    scene v on p { )" + effects + R"( settle = 20 mesh_periods; record = 4 mesh_periods; output )" + allSignals(listed) + R"(; }
  })");
  std::set<cat::Signal> recorded;
  for (const auto& g : c->program.gearboxes) {
    rt::Model m(c->program, g);
    rt::Assignment a(m);
    auto r = rt::dyn::runScene(m, a, g.scenes[0], quickRun());
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    size_t n = 0;
    for (const auto& o : g.scenes[0].outputs) {
      const auto* x = r.find(cat::SignalFn::Rms, o.id);
      ASSERT_NE(x, nullptr) << g.name << ": no " << o.signal;
      EXPECT_TRUE(std::isfinite(x->value)) << g.name << ": `" << o.signal << "` is not recorded";
      recorded.insert(o.id);
      ++n;
    }
    EXPECT_EQ(r.numbers.size(), n);
  }
  for (const auto& s : cat::sceneSignals()) {
    if (!s.scalar) {
      EXPECT_TRUE(recorded.count(s.id)) << "`" << s.name << "` is recorded by no scene model";
    }
  }
}

} // namespace
} // namespace gbx
