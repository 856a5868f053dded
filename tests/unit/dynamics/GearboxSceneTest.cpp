// Whole-gearbox scenes in time (docs/dynamics.md): the planetary stage and the idler train
// integrated together, against the stage models, the kinematics and the energy balance.
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "SceneFixture.h"
#include "Specs.h"
#include "driver/Driver.h"
#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "model/Model.h"

using namespace gbx;
using namespace gbx::rt::dyn;

namespace {

using test::Fixture;

Fixture compile(const std::string& text, const std::string& gearbox) { return test::compile("g.gbx", text, gearbox); }

double value(const SceneResult& r, const std::string& key) {
  const SceneNumber* n = r.find(key);
  EXPECT_TRUE(n) << key;
  return n ? n->value : NAN;
}

SceneOverrides quick() {
  SceneOverrides ov;
  ov.estimateError = false;
  ov.keepSeries = false;
  return ov;
}

} // namespace

// A gearbox of one planetary stage: its whole-gearbox scene is the planetary scene, the same
// members, meshes, contact law and load, so the same contact forces.
TEST(GearboxScene, PlanetaryStageAloneAgreesWithTheStageScene) {
  const char* effects = R"(effects {
      varying_stiffness { harmonics = 5; }
      hertz_contact { exponent = 1.5; penetration_ramp = 0.1 mm; damping = 0.01 * stiffness; }
    }
    ramp = 0.05 s; duration = 0.2 s;
    accuracy { method = rk8pd; rtol = 1e-8; })";
  auto f = compile(std::string(R"(gearbox P {
  stage ps: planetary { sun.z = 19; planet.z = 23; ring.z = 65; planets = 3; module = 0.6 mm; }
  operating { input_speed = 600 rpm; output_torque = 1.7458 N*m; }
  scene alone on ps { )") + effects + R"(
    output mean(output_speed), peak(contact_force), mean(contact_force), min(contact_force);
  }
  scene whole on P { )" + effects + R"(
    output mean(output_speed), peak(contact_force(ps.sun_planet)), mean(contact_force(ps.sun_planet)),
           min(contact_force(ps.sun_planet)), mean(contact_force(ps.ring_planet));
  }
})",
                   "P");
  ASSERT_TRUE(f.model);
  SceneResult alone = runScene(*f.model, *f.design, f.scene("alone"), quick());
  SceneResult whole = runScene(*f.model, *f.design, f.scene("whole"), quick());
  ASSERT_TRUE(alone.failure.empty()) << alone.failure;
  ASSERT_TRUE(whole.failure.empty()) << whole.failure;
  EXPECT_NEAR(value(whole, "mean(output_speed)") / value(alone, "mean(output_speed)"), 1.0, 1e-9);
  EXPECT_NEAR(value(whole, "mean(contact_force(ps.sun_planet))") / value(alone, "mean(contact_force)"), 1.0, 1e-6);
  EXPECT_NEAR(value(whole, "peak(contact_force(ps.sun_planet))") / value(alone, "peak(contact_force)"), 1.0, 1e-4);
  EXPECT_NEAR(value(whole, "min(contact_force(ps.sun_planet))") / value(alone, "min(contact_force)"), 1.0, 1e-4);
  // A planet in equilibrium carries the same force on both its meshes.
  EXPECT_NEAR(value(whole, "mean(contact_force(ps.ring_planet))") / value(whole, "mean(contact_force(ps.sun_planet))"), 1.0, 1e-6);
}

// A planetary stage with profile shifts (the NREL stage-1 counts 19/17/56, concentric on its
// working centre distances, each mesh at its own working pressure angle): the mean mesh force
// of the periodic steady state is the statics' at the working pressure angle, F_bn = F_tw /
// cos alpha_w with F_tw = 2 T / (N d_w) the sun's torque on its working pitch circle. (A run
// from rest settles slowly here: its window mean is off by 0.4 % after 0.2 s.)
TEST(GearboxScene, ShiftedPlanetaryMeanForcesMatchStatics) {
  auto f = compile(R"(gearbox P {
  stage ps: planetary { sun.z = 19; planet.z = 17; ring.z = 56; planets = 3; module = 3 mm; face_width = 30 mm;
                        sun.shift = 0.617; planet.shift = 0.8021; ring.shift = -0.5013; }
  operating { input_speed = 600 rpm; input_torque = 200 N*m; }
  scene run on ps {
    effects { varying_stiffness { harmonics = 5; } hertz_contact { exponent = 1.5; penetration_ramp = 0.1 mm; damping = 0.01 * stiffness; } }
    steady_state = periodic; record = 20 mesh_periods;
    output mean(contact_force);
  }
})",
                   "P");
  ASSERT_TRUE(f.model);
  SceneResult r = runScene(*f.model, *f.design, f.scene("run"), quick());
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  // Working pressure angle of the sun-planet mesh from the shifts (ISO 21771):
  // inv a_w = inv a + 2 tan a (x_s + x_p) / (z_s + z_p); d_w,sun = d_b,sun / cos a_w.
  const double a = 20 * M_PI / 180, inv = std::tan(a) - a;
  const double target = inv + 2 * std::tan(a) * (0.617 + 0.8021) / (19 + 17);
  double aw = 0.5;
  for (int i = 0; i < 60; ++i)
    aw -= (std::tan(aw) - aw - target) / (std::tan(aw) * std::tan(aw));
  EXPECT_NEAR(aw * 180 / M_PI, 28.1174, 1e-4); // as the NREL report prints it
  const double dbs = 19 * 3e-3 * std::cos(a), dws = dbs / std::cos(aw);
  const double Ftw = 2 * 200.0 / (3 * dws), Fbn = Ftw / std::cos(aw);
  EXPECT_NEAR(value(r, "mean(contact_force)") / Fbn, 1.0, 1e-4);
}

// The members turn at the stage ratios: carrier zs/(zs + zr), planet spin -(zs/zp)(1 - carrier),
// idler -(z1/z2) carrier, driven (z1/z3) carrier; the mean contact forces carry the load.
TEST(GearboxScene, ElectricCylinderMechanismKeepsTheStageRatiosAndCarriesTheLoad) {
  auto f = compile(readSpec("electric_cylinder.gbx"), "ElectricCylinderBuilt");
  ASSERT_TRUE(f.model);
  SceneResult r = runScene(*f.model, *f.design, f.scene("mechanism"), quick());
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  const auto& g = r.gearbox;
  ASSERT_EQ(g.members.size(), 7u);
  double carrier = 19.0 / 84.0;
  auto speedOf = [&](const std::string& member) -> double {
    for (size_t i = 0; i < g.members.size(); ++i)
      if (g.members[i] == member) return g.kinematic[i];
    ADD_FAILURE() << member;
    return NAN;
  };
  EXPECT_NEAR(speedOf("input shaft"), 1.0, 1e-15);
  EXPECT_NEAR(speedOf("planet_stage carrier"), carrier, 1e-12);
  for (int p = 1; p <= 3; ++p)
    EXPECT_NEAR(speedOf("planet_stage planet " + std::to_string(p)), -(19.0 / 23.0) * (1.0 - carrier), 1e-12);
  EXPECT_NEAR(speedOf("transfer idler"), -(29.0 / 30.0) * carrier, 1e-12);
  EXPECT_NEAR(speedOf("transfer driven"), 29.0 / 50.0 * carrier, 1e-12);
  // 600 rpm through 7.6225: 78.714 rpm at the output (472.3 deg/s).
  EXPECT_NEAR(value(r, "mean(output_speed)") * 60 / (2 * M_PI), 600.0 * 19.0 / 84.0 * 29.0 / 50.0, 1e-3);
  // Every planet meets the same mesh cycle (Parker and Lin phasing), so the first carries a third.
  // The load 3.01 N*m at the driven gear: the carrier carries 3.01 * 29/50 N*m on three planets
  // at rbs + rbr, the fixed-axis meshes 3.01 * 29/50 N*m at the driver's base radius.
  double cosA = std::cos(20.0 * M_PI / 180.0);
  double Tc = 3.01 * 29.0 / 50.0;
  double Fsp = Tc / (3.0 * 0.5 * (19 + 65) * 0.6e-3 * cosA), Ffa = Tc / (0.5 * 29 * 0.6e-3 * cosA);
  EXPECT_NEAR(value(r, "mean(contact_force(planet_stage.sun_planet))") / Fsp, 1.0, 1e-3);
  EXPECT_NEAR(value(r, "mean(contact_force(planet_stage.ring_planet))") / Fsp, 1.0, 1e-3);
  EXPECT_NEAR(value(r, "mean(contact_force(transfer.driver_idler))") / Ffa, 1.0, 1e-3);
  EXPECT_NEAR(value(r, "mean(contact_force(transfer.idler_driven))") / Ffa, 1.0, 1e-3);
}

// Energy over a run: the drive's work equals the work the load takes, the work the contact
// damping dissipates and the kinetic and elastic energy gained, on a spur stage followed by an
// idler train under a fluctuating drive and load (Hertz contact, mesh damping).
TEST(GearboxScene, EnergyBalanceOfDriveLoadAndDamping) {
  auto f = compile(R"(gearbox E {
  stage s: spur { pinion.z = 20; wheel.z = 41; normal_module = 2 mm; face_width = 20 mm; }
  stage t: idler { driver.z = 18; idler.z = 25; driven.z = 37; module = 2 mm; face_width = 20 mm; }
  operating { input_speed = 1500 rpm; output_torque = 80 N*m; }
  scene run on E {
    effects {
      hertz_contact { exponent = 1.5; penetration_ramp = 0.01 mm; damping = 0.001 * stiffness; }
      damping { ratio = 0.02; }
      speed_fluctuation { mean = 1500 rpm; amplitude = 300 rpm; frequency = 40 Hz; }
      torque_fluctuation { mean = 80 N*m; amplitude = 30 N*m; frequency = 25 Hz; }
    }
    duration = 0.05 s;
    accuracy { method = msbdf; rtol = 1e-9; }
    output mean(contact_force(s)), mean(contact_force(t.idler_driven));
  }
})",
                   "E");
  ASSERT_TRUE(f.model);
  SceneOverrides ov = quick();
  ov.energyAudit = true;
  SceneResult r = runScene(*f.model, *f.design, f.scene("run"), ov);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  const auto& g = r.gearbox;
  EXPECT_GT(g.driveWork, 0.0);
  EXPECT_GT(g.loadWork, 0.0);
  EXPECT_GT(g.dissipated, 0.0);
  double residual = g.driveWork - g.loadWork - g.dissipated - g.energyGained;
  EXPECT_LT(std::fabs(residual), 1e-6 * g.driveWork)
      << "drive " << g.driveWork << " load " << g.loadWork << " dissipated " << g.dissipated << " gained " << g.energyGained;
}

// Two stages driven by their loaded flanks (loaded_mesh on every pair): each mesh's mean force
// carries its stage's torque, T / rb1, over a long record.
TEST(GearboxScene, LoadedMeshesOfTwoStagesCarryTheirTorques) {
  auto f = compile(R"(import materials;
gearbox T {
  stage a: helical { pinion.z = 23; wheel.z = 71; normal_module = 4 mm; helix_angle = 12 deg; face_width = 60 mm; material = steel_20CrMnMo; accuracy = 6; }
  stage b: spur { pinion.z = 19; wheel.z = 58; normal_module = 6 mm; face_width = 80 mm; material = steel_20CrMnMo; accuracy = 6; }
  operating { input_speed = 1500 rpm; input_torque = 400 N*m; }
  scene whole on T {
    effects { loaded_mesh { slices = 40; positions = 64; } damping { ratio = 0.1; } }
    settle = 200 mesh_periods; record = 160 mesh_periods; samples = 32;
    accuracy { method = msbdf; rtol = 1e-7; }
    output mean(mesh_force(a)), mean(mesh_force(b)), peak_to_peak(mesh_force(b));
  }
})",
                   "T");
  ASSERT_TRUE(f.model);
  SceneResult r = runScene(*f.model, *f.design, f.scene("whole"), quick());
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  rt::Evaluator ev(*f.model);
  double rbA = ev.quantity("a.pinion.base_radius", *f.design).mid(), rbB = ev.quantity("b.pinion.base_radius", *f.design).mid();
  EXPECT_NEAR(value(r, "mean(mesh_force(a))") / (400.0 / rbA), 1.0, 1e-2);
  EXPECT_NEAR(value(r, "mean(mesh_force(b))") / (400.0 * 71.0 / 23.0 / rbB), 1.0, 1e-2);
  EXPECT_GT(value(r, "peak_to_peak(mesh_force(b))"), 0.0) << "the flanks excite the mesh";
}
