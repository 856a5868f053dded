// Every rating setting on every kind that is rated: a setting the catalogue accepts for a
// kind changes what that kind's rating computes; none is accepted and ignored. Each kind is
// rated with a full `rating` block, then with one setting changed (or added), and at least
// one of its rating quantities must move.
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "catalogue/StageKinds.h"
#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "passes/Ratings.h"

using namespace gbx;

namespace {

// The full block each kind is rated with, and another value for each setting.
const std::map<std::string, std::string>& baseValues() {
  static const std::map<std::string, std::string> v = {
      {"application_factor", "1.25"},
      {"life", "20000 h"},
      {"lubricant.viscosity_40", "150 mm^2/s"},
      {"lubricant.viscosity_100", "15 mm^2/s"},
      {"lubricant.density", "890 kg/m^3"},
      {"lubricant.oil_temperature", "70 degC"},
      {"lubricant.fzg_load_stage", "9"},
      {"lubricant.micropitting_load_stage", "8"},
      {"roughness.flank", "0.6 um"},
      {"roughness.root", "3 um"},
  };
  return v;
}

const std::map<std::string, std::string>& otherValues() {
  static const std::map<std::string, std::string> v = {
      {"application_factor", "1.5"},
      {"life", "2000 h"},
      {"life_curve", "optimum"},
      {"lubricant.viscosity_40", "460 mm^2/s"},
      {"lubricant.viscosity_100", "30 mm^2/s"},
      {"lubricant.density", "1000 kg/m^3"},
      {"lubricant.oil_temperature", "95 degC"},
      {"lubricant.fzg_load_stage", "6"},
      {"lubricant.micropitting_load_stage", "5"},
      {"lubricant.base", "polyglycol"},
      {"lubricant.supply", "injection"},
      {"roughness.flank", "1.6 um"},
      {"roughness.root", "8 um"},
      {"roughness.flank_rz", "12 um"},
      {"roughness.root_rz", "40 um"},
      {"basic_rack.addendum", "1.1"},
      {"basic_rack.dedendum", "1.4"},
      {"basic_rack.root_radius", "0.25"},
      {"face_load_factor", "1.7"},
      {"dynamic_factor", "1.3"},
      {"ring_planet.dynamic_factor", "1.3"},
      {"transverse_load_factor", "1.3"},
      {"mesh_load_factor", "1.3"},
      {"mesh_misalignment", "40 um"},
      {"min_safety.contact", "1.3"},
      {"min_safety.bending", "1.6"},
      {"min_safety.scuffing", "2.5"},
      {"min_safety.integral_scuffing", "2.8"},
      {"min_safety.micropitting", "1.7"},
      {"mounting", "both_cantilever"},
      {"contact_pattern", "0.6"},
  };
  return v;
}

// A `rating { … }` block from setting paths (`lubricant.density`) to values.
std::string block(const std::map<std::string, std::string>& settings) {
  std::map<std::string, std::string> groups;
  std::string out = "rating { ";
  for (const auto& [path, value] : settings) {
    auto dot = path.find('.');
    if (path == "load_spectrum")
      groups[path] = "load_spectrum { " + value + " } ";
    else if (dot == std::string::npos)
      out += fmt::format("{} = {}; ", path, value);
    else
      groups[path.substr(0, dot)] += fmt::format("{} = {}; ", path.substr(dot + 1), value);
  }
  for (const auto& [g, body] : groups)
    out += g == "load_spectrum" ? body : g + " { " + body + "} ";
  return out + "}";
}

struct Kind {
  ir::StageKind kind;
  std::string stage; // the stage with `%RATING%` where its rating block goes
  std::vector<std::string> gears;
};

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> k = {
      {ir::StageKind::Spur,
       "stage s: spur { pinion.z = 23; wheel.z = 71; normal_module = 4 mm; face_width = 50 mm; material = "
       "steel_18CrNiMo7_6; accuracy = 6; %RATING% }",
       {"pinion", "wheel"}},
      {ir::StageKind::Helical,
       "stage s: helical { pinion.z = 23; wheel.z = 71; normal_module = 4 mm; helix_angle = 12 deg; face_width = 50 "
       "mm; "
       "material = steel_18CrNiMo7_6; accuracy = 6; %RATING% }",
       {"pinion", "wheel"}},
      {ir::StageKind::Idler,
       "stage s: idler { driver.z = 20; idler.z = 31; driven.z = 40; module = 3 mm; face_width = 30 mm; material = "
       "steel_18CrNiMo7_6; accuracy = 6; %RATING% }",
       {"driver", "idler", "driven"}},
      {ir::StageKind::Planetary,
       "stage s: planetary { sun.z = 22; planet.z = 30; ring.z = 82; planets = 3; module = 3 mm; face_width = 40 mm; "
       "material = steel_18CrNiMo7_6; accuracy = 6; %RATING% }",
       {"sun", "planet", "ring"}},
      {ir::StageKind::Bevel,
       "stage s: bevel { pinion.z = 14; wheel.z = 39; mean_normal_module = 3.213 mm; face_width = 25.4 mm; "
       "spiral_angle "
       "= 35 deg; outer_cone_distance = 93.973 mm; pinion.pitch_deviation = 12 um; wheel.pitch_deviation = 26 um; "
       "material = steel_18CrNiMo7_6; %RATING% }",
       {"pinion", "wheel"}},
  };
  return k;
}

// The base block without the settings the kind does not take (a bevel pair's rating has no
// scuffing, so no oil data beyond the viscosity at 40 degC).
std::map<std::string, std::string> baseFor(const Kind& k) {
  std::map<std::string, std::string> out;
  for (const auto& [path, value] : baseValues())
    if (cat::findAttr(cat::kindSpec(k.kind), "rating." + path)) out[path] = value;
  return out;
}

// The kind's rating quantities at its one design, as text (a change anywhere shows).
std::string rated(const Kind& k, const std::map<std::string, std::string>& settings, std::string* error) {
  std::string stage = k.stage;
  stage.replace(stage.find("%RATING%"), 8, block(settings));
  std::string text = "import materials;\ngearbox G {\n  " + stage +
                     "\n  operating { input_speed = 1000 rpm; input_torque = 400 N*m; }\n}\n";
  auto c = driver::compileText("settings.gbx", text);
  if (!c->ok()) {
    *error = c->diags.renderText(c->sources);
    return "";
  }
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::Evaluator ev(m);
  rt::Assignment a(m);
  std::string out;
  auto add = [&](const std::string& path) {
    rt::Value v = ev.quantity(path, a);
    out += fmt::format("{}={:.12g} ", path, v.isNumber() ? v.mid() : -1.0);
  };
  for (const char* q :
       {"K_v", "K_Hbeta", "K_Halpha", "scuffing_safety", "integral_scuffing_safety", "micropitting_safety"})
    add(std::string("s.") + q);
  for (const auto& g : k.gears)
    for (const char* q :
         {"contact_safety", "bending_safety", "permissible_contact_stress", "permissible_bending_stress"})
      add("s." + g + "." + q);
  // The minimum safeties of scuffing and micropitting set what the rating table's verdict
  // compares against.
  for (const auto& r : rt::passes::ratings(m, a).ratings)
    out += fmt::format("minima={},{},{} ", r.minScuffing, r.minIntegralScuffing, r.minMicropitting);
  return out;
}

} // namespace

TEST(RatingSettings, EverySettingOnEveryRatedKindCountsOrIsRefused) {
  int walked = 0;
  for (const Kind& k : kinds()) {
    std::string error;
    const std::string base = rated(k, baseFor(k), &error);
    ASSERT_FALSE(base.empty()) << error;
    for (const auto& a : cat::kindSpec(k.kind).stage) {
      if (a.name.rfind("rating.", 0) != 0) continue;
      const std::string path = a.name.substr(7);
      auto other = otherValues().find(path);
      ASSERT_NE(other, otherValues().end()) << "no other value for `" << a.name << "`: add one to this test";
      auto settings = baseFor(k);
      settings[path] = other->second;
      const std::string changed = rated(k, settings, &error);
      ++walked;
      if (changed.empty()) continue; // refused, with a diagnostic
      EXPECT_NE(changed, base) << cat::kindSpec(k.kind).name << ": `rating." << path << " = " << other->second
                               << "` is accepted but changes nothing the rating computes";
    }
    // A load spectrum (a block, not a setting of the catalogue's list): one bin above the
    // operating torque for the whole life lowers the safeties.
    auto settings = baseFor(k);
    settings["load_spectrum"] = "bin 150% torque for 100% of life;";
    const std::string spectrum = rated(k, settings, &error);
    ++walked;
    if (!spectrum.empty()) {
      EXPECT_NE(spectrum, base) << cat::kindSpec(k.kind).name << ": a load spectrum is accepted but changes nothing";
    }
  }
  EXPECT_GT(walked, 60);
}
