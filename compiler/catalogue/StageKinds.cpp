#include "catalogue/StageKinds.h"

#include <algorithm>

namespace gbx::cat {

using namespace units::dims;
using namespace rows;
using units::Number;

namespace {

AttrSpec material() {
  auto a = in("material", none, "gear material (a `material` declaration)");
  a.value = ValueKind::Material;
  return a;
}

std::vector<AttrSpec> commonDerived() {
  return {
      derived("ratio", none, "reduction: input speed / output speed"),
      derived("input_speed", angularSpeed, "speed of the stage's input member"),
      derived("output_speed", angularSpeed, "speed of the stage's output member"),
      derived("input_torque", torque, "torque on the stage's input member"),
      derived("output_torque", torque, "torque on the stage's output member"),
      derived("mesh_frequency", frequency, "tooth-mesh frequency"),
  };
}

std::vector<AttrSpec> cylindricalGearAttrs() {
  return {
      required(count("z", "tooth count")),
      in("shift", none, "profile shift coefficient"),
      pos("pitch_deviation", length, "single (base) pitch deviation"),
      pos("profile_deviation", length, "total profile deviation"),
      pos("bending_deflection", length, "shaft bending deflection across the face"),
      pos("torsion_deflection", length, "torsional wind-up across the face"),
      pos("inertia", inertia, "mass moment of inertia about the gear axis"),
      pos("bearing_span", length, "distance between the gear's bearings"),
      pos("shaft_diameter", length, "diameter of the gear's shaft"),
      derived("d", length, "reference diameter"),
      derived("base_radius", length, "base circle radius"),
      derived("tip_radius", length, "tip circle radius"),
      derived("speed", angularSpeed, "rotational speed"),
      derived("torque", torque, "transmitted torque"),
  };
}

// Gears of planetary and idler stages: their tip radius has no formula here (the ring is
// internal), so it is not offered.
std::vector<AttrSpec> plainGearAttrs() {
  auto g = cylindricalGearAttrs();
  g.erase(std::remove_if(g.begin(), g.end(), [](const AttrSpec& a) { return a.key == Q::TipRadius; }), g.end());
  return g;
}

std::vector<KindSpec> buildKinds() {
  std::vector<KindSpec> k;
  auto cylStage = [](bool helical) {
    std::vector<AttrSpec> a = {
        pos("normal_module", length, "normal module"),
        withDefault(pos("pressure_angle", angle, "normal pressure angle"), deg(20)),
        pos("face_width", length, "face width"),
        pos("center_distance", length, "centre distance"),
        material(),
        count("accuracy", "ISO 1328-1 accuracy grade"),
        pos("mesh_stiffness", pressure, "mesh stiffness per unit face width (c_gamma)"),
        derived("pitch_line_velocity", velocity, "pitch-line velocity"),
        derived("eps_alpha", none, "transverse contact ratio"),
        derived("eps_beta", none, "overlap ratio"),
        derived("mass", units::dims::mass, "gear-pair mass (DOMAIN.md §3, f2)"),
        derived("whole_depth", length, "whole depth 2.25 mn"),
        derived("sliding_balance", none, "specific-sliding balance value (DOMAIN.md §3)"),
        derived("working_pressure_angle", angle, "transverse working pressure angle"),
        derived("tangential_force", force, "nominal tangential force"),
        derived("load_deflection", length, "elastic deflection w_t / c_gamma"),
        derived("total_contact_ratio", none, "eps_alpha + eps_beta"),
    };
    a[3].role = AttrRole::Either;
    if (helical) a.insert(a.begin() + 1, required(in("helix_angle", angle, "helix angle at the reference circle")));
    for (auto& d : commonDerived()) a.push_back(d);
    return a;
  };
  k.push_back({ir::StageKind::Spur, "spur", {"pinion", "wheel"}, cylStage(false), cylindricalGearAttrs()});
  k.push_back({ir::StageKind::Helical, "helical", {"pinion", "wheel"}, cylStage(true), cylindricalGearAttrs()});

  {
    std::vector<AttrSpec> a = {
        in("spiral_angle", angle, "mean spiral angle beta_m"),
        pos("face_ratio", none, "face width over outer cone distance b/Re"),
        withDefault(pos("shaft_angle", angle, "shaft angle"), deg(90)),
        count("blade_groups", "cutter blade groups (face hobbing)"),
        pos("mean_normal_module", length, "mean normal module"),
        pos("face_width", length, "face width"),
        withDefault(pos("pressure_angle", angle, "normal pressure angle"), deg(20)),
        material(),
        count("accuracy", "ISO 1328-1 accuracy grade"),
        derived("mmn_b", none, "mean normal module over face width (DOMAIN.md §1)"),
    };
    for (auto& d : commonDerived()) a.push_back(d);
    std::vector<AttrSpec> g = {
        required(count("z", "tooth count")),
        derived("cone_angle", angle, "pitch cone angle"),
        derived("speed", angularSpeed, "rotational speed"),
        derived("torque", torque, "transmitted torque"),
        pos("inertia", inertia, "mass moment of inertia about the gear axis"),
    };
    k.push_back({ir::StageKind::Bevel, "bevel", {"pinion", "wheel"}, a, g});
  }
  {
    std::vector<AttrSpec> a = {
        required(count("planets", "number of planets, equally spaced")),
        pos("module", length, "module"),
        withDefault(pos("pressure_angle", angle, "pressure angle"), deg(20)),
        pos("face_width", length, "face width"),
        material(),
        count("accuracy", "ISO 1328-1 accuracy grade"),
        pos("mesh_stiffness", pressure, "mesh stiffness per unit face width (c_gamma)"),
        pos("carrier_inertia", inertia, "carrier moment of inertia"),
        derived("center_distance", length, "sun-planet centre distance"),
        derived("carrier_speed", angularSpeed, "carrier speed"),
    };
    for (auto& d : commonDerived()) a.push_back(d);
    auto g = plainGearAttrs();
    g.push_back(pos("mass", mass, "gear mass (planets: each)"));
    k.push_back({ir::StageKind::Planetary, "planetary", {"sun", "planet", "ring"}, a, g});
  }
  {
    std::vector<AttrSpec> a = {
        pos("module", length, "module"),
        withDefault(pos("pressure_angle", angle, "pressure angle"), deg(20)),
        pos("face_width", length, "face width"),
        material(),
        count("accuracy", "ISO 1328-1 accuracy grade"),
        derived("center_distance", length, "driver-to-driven distance (z1/2 + z2 + z3/2) m"),
    };
    for (auto& d : commonDerived()) a.push_back(d);
    k.push_back({ir::StageKind::Idler, "idler", {"driver", "idler", "driven"}, a, plainGearAttrs()});
  }
  return k;
}

} // namespace


const std::vector<KindSpec>& stageKinds() {
  static const std::vector<KindSpec> k = buildKinds();
  return k;
}

const KindSpec& kindSpec(ir::StageKind kind) { return stageKinds()[static_cast<size_t>(kind)]; }

int gearIndex(const KindSpec& k, const std::string& name) {
  auto it = std::find(k.gears.begin(), k.gears.end(), name);
  return it == k.gears.end() ? -1 : static_cast<int>(it - k.gears.begin());
}

const KindSpec* findKind(const std::string& name) {
  for (const auto& k : stageKinds())
    if (k.name == name) return &k;
  return nullptr;
}

bool isGear(const KindSpec& k, const std::string& name) {
  return std::find(k.gears.begin(), k.gears.end(), name) != k.gears.end();
}

const AttrSpec* findAttr(const KindSpec& k, const std::string& path) {
  auto dot = path.find('.');
  if (dot == std::string::npos) {
    for (const auto& a : k.stage)
      if (a.name == path) return &a;
    return nullptr;
  }
  if (!isGear(k, path.substr(0, dot))) return nullptr;
  std::string rest = path.substr(dot + 1);
  for (const auto& a : k.gear)
    if (a.name == rest) return &a;
  return nullptr;
}


} // namespace gbx::cat
