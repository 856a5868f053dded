#include "sema/Catalogue.h"

#include <algorithm>

namespace gbx::sema {

using namespace units::dims;
using units::Number;
using units::Rational;

namespace {

AttrSpec in(std::string n, Dim d, std::string meaning) {
  AttrSpec a;
  a.name = std::move(n);
  a.dim = d;
  a.meaning = std::move(meaning);
  return a;
}
AttrSpec pos(std::string n, Dim d, std::string meaning) {
  auto a = in(std::move(n), d, std::move(meaning));
  a.positive = true;
  return a;
}
AttrSpec count(std::string n, std::string meaning) {
  auto a = pos(std::move(n), none, std::move(meaning));
  a.integer = true;
  return a;
}
AttrSpec derived(std::string n, Dim d, std::string meaning, bool integer = false) {
  auto a = in(std::move(n), d, std::move(meaning));
  a.role = AttrRole::Derived;
  a.integer = integer;
  return a;
}
AttrSpec withDefault(AttrSpec a, Number v) {
  a.dflt = v;
  return a;
}
AttrSpec required(AttrSpec a) {
  a.required = true;
  return a;
}
AttrSpec symbol(std::string n, std::vector<std::string> words, std::string meaning) {
  auto a = in(std::move(n), none, std::move(meaning));
  a.value = ValueKind::Symbol;
  a.symbols = std::move(words);
  return a;
}
AttrSpec material() {
  auto a = in("material", none, "gear material (a `material` declaration)");
  a.value = ValueKind::Material;
  return a;
}
Number deg(std::int64_t d) { return Number::exact(Rational::make(d, 180), 1); }
Number num(std::int64_t n, std::int64_t d = 1) { return Number::exact(Rational::make(n, d)); }

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
    auto g = cylindricalGearAttrs();
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
    k.push_back({ir::StageKind::Idler, "idler", {"driver", "idler", "driven"}, a, cylindricalGearAttrs()});
  }
  return k;
}

} // namespace

const std::vector<KindSpec>& stageKinds() {
  static const std::vector<KindSpec> k = buildKinds();
  return k;
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

const std::vector<AttrSpec>& gearboxQuantities() {
  static const std::vector<AttrSpec> q = {
      derived("ratio", none, "overall reduction, the product of the stage ratios"),
      derived("input_speed", angularSpeed, "input shaft speed"),
      derived("output_speed", angularSpeed, "output shaft speed"),
      derived("input_torque", torque, "input torque"),
      derived("output_torque", torque, "output torque"),
      derived("power", power, "transmitted power"),
  };
  return q;
}

const std::vector<AttrSpec>& operatingSettings() {
  static const std::vector<AttrSpec> q = {
      pos("input_speed", angularSpeed, "input shaft speed"),
      pos("output_speed", angularSpeed, "output shaft speed"),
      pos("input_torque", torque, "input torque"),
      pos("output_torque", torque, "output torque"),
      pos("power", power, "transmitted power"),
  };
  return q;
}

const std::vector<AttrSpec>& materialProperties() {
  static const std::vector<AttrSpec> q = {
      required(pos("youngs_modulus", pressure, "Young's modulus")),
      required(pos("poisson", none, "Poisson's ratio")),
      required(pos("density", density, "density")),
      pos("shear_modulus", pressure, "shear modulus"),
      pos("sigma_hlim", pressure, "ISO 6336-5 allowable contact stress number"),
      pos("sigma_flim", pressure, "ISO 6336-5 nominal bending stress number"),
      pos("hardness", none, "surface hardness (HRC or HV, as the material states)"),
  };
  return q;
}

const std::vector<EffectSpec>& effects() {
  static const std::vector<EffectSpec> e = [] {
    std::vector<EffectSpec> v;
    auto harmonics = withDefault(count("harmonics", "Fourier harmonics of the contact-line length"), num(5));
    v.push_back({"varying_stiffness", "time-varying mesh stiffness from the contact-line length",
                 {harmonics, pos("stiffness", stiffness, "mean mesh stiffness (computed from geometry when absent)")}});
    v.push_back({"damping", "viscous mesh damping",
                 {pos("ratio", none, "damping ratio zeta"), pos("coefficient", dampingCoeff, "damping coefficient c")}});
    v.push_back({"transmission_error", "static transmission error e(t), force F = dk(t) e(t)",
                 {withDefault(in("mean", length, "mean error e0"), num(0)), required(in("amplitude", length, "error amplitude er")),
                  withDefault(in("phase", angle, "phase"), num(0))}});
    v.push_back({"backlash", "clearance with contact loss on both flanks",
                 {required(pos("clearance", length, "total backlash along the line of action"))}});
    v.push_back({"hertz_contact", "Hertzian contact force K d^e with penetration-ramp damping",
                 {withDefault(pos("exponent", none, "force exponent e"), num(3, 2)),
                  required(pos("penetration_ramp", length, "penetration over which damping ramps in")),
                  withDefault(in("damping", dampingCoeff, "maximum damping coefficient C"), num(0))}});
    auto freq = [](std::string meaning) {
      auto a = required(pos("frequency", angularSpeed, std::move(meaning)));
      a.altDim = frequency;
      return a;
    };
    v.push_back({"speed_fluctuation", "drive speed mean + amplitude sin(frequency t)",
                 {required(pos("mean", angularSpeed, "mean drive speed")), required(in("amplitude", angularSpeed, "amplitude")),
                  freq("angular frequency of the fluctuation")}});
    v.push_back({"torque_fluctuation", "load torque mean + amplitude sin(frequency t)",
                 {required(in("mean", torque, "mean load torque")), required(in("amplitude", torque, "amplitude")),
                  freq("angular frequency of the fluctuation")}});
    return v;
  }();
  return e;
}

const EffectSpec* findEffect(const std::string& name) {
  for (const auto& e : effects())
    if (e.name == name) return &e;
  return nullptr;
}

const std::vector<AttrSpec>& sceneSettings() {
  static const std::vector<AttrSpec> s = [] {
    auto t = [](std::string n, std::string m) {
      auto a = pos(std::move(n), time, std::move(m));
      a.meshPeriods = true;
      return a;
    };
    return std::vector<AttrSpec>{
        t("settle", "transient discarded before recording"),
        t("record", "recorded steady-state window"),
        withDefault(count("samples", "samples per recorded mesh period"), num(160)),
        t("duration", "simulated time from rest"),
        t("ramp", "smooth start-up time of the drive speed"),
    };
  }();
  return s;
}

const std::vector<AttrSpec>& accuracySettings() {
  static const std::vector<AttrSpec> s = [] {
    auto step = pos("max_step", time, "largest step");
    step.meshPeriods = true;
    auto hmin = pos("min_step", time, "smallest step");
    hmin.meshPeriods = true;
    return std::vector<AttrSpec>{
        symbol("method", {"rk8pd", "rkf45", "rkck", "rk4", "msbdf"}, "integration method"),
        withDefault(pos("rtol", none, "relative tolerance"), num(1, 1000000)),
        pos("atol", none, "absolute tolerance (SI units of the state)"),
        step,
        hmin,
        count("max_steps", "step limit"),
    };
  }();
  return s;
}

const std::vector<SignalSpec>& sceneSignals() {
  static const std::vector<SignalSpec> s = {
      {"displacement", length, {}, false},
      {"velocity", velocity, {}, false},
      {"acceleration", acceleration, {}, false},
      {"mesh_force", force, {}, false},
      {"stiffness", stiffness, {}, false},
      {"contact_force", force, {"hertz_contact", "backlash"}, false},
      {"transmission_error", length, {"transmission_error"}, false},
      {"input_speed", angularSpeed, {}, false},
      {"output_speed", angularSpeed, {}, false},
      {"dynamic_factor", none, {}, true},
      {"modes", frequency, {}, true},
  };
  return s;
}

const SignalSpec* findSignal(const std::string& name) {
  for (const auto& s : sceneSignals())
    if (s.name == name) return &s;
  return nullptr;
}

bool isSignalFunction(const std::string& fn) {
  return fn == "rms" || fn == "peak" || fn == "mean" || fn == "min" || fn == "max" || fn == "spectrum" || fn == "plot";
}

bool signalFunctionIsNumber(const std::string& fn) { return fn != "spectrum" && fn != "plot"; }

const std::vector<AttrSpec>& splitSettings() {
  static const std::vector<AttrSpec> s = [] {
    auto between = in("between", none, "the stage whose wheel feeds the branches");
    between.value = ValueKind::Stage;
    between.required = true;
    return std::vector<AttrSpec>{
        between,
        withDefault(count("branches", "number of branches"), num(2)),
        required(pos("torsion_shaft.length", length, "torsion shaft length")),
        required(pos("torsion_shaft.diameter", length, "torsion shaft diameter")),
        withDefault(pos("torsion_shaft.shear_modulus", pressure, "shear modulus G"), num(80000000000)),
        required(in("backlash_difference", length, "difference of circumferential backlash between branches")),
        required(symbol("install", {"free", "preloaded"}, "installation method")),
        in("preload_torque", torque, "installation torque M0 (preloaded installation)"),
    };
  }();
  return s;
}

const std::vector<AttrSpec>& splitOutputs() {
  static const std::vector<AttrSpec> s = {
      derived("twist", angle, "torsion-shaft twist at full load"),
      derived("displacement", length, "circumferential displacement at the stage-I wheel"),
      derived("imbalance", none, "load imbalance between the branches"),
      derived("branch_torque", torque, "torque in one branch"),
      derived("preload_displacement", length, "backlash taken up by the preload"),
  };
  return s;
}

const std::vector<AttrSpec>& workPrecisionSettings() {
  static const std::vector<AttrSpec> s = {
      pos("rtol", none, "relative tolerances to run"),
      count("harmonics", "harmonic counts to run"),
      symbol("methods", {"rk8pd", "rkf45", "rkck", "rk4", "msbdf"}, "methods to compare"),
  };
  return s;
}

const std::vector<std::string>& modificationTargets() {
  static const std::vector<std::string> t = {
      "tip_relief",    "tip_relief_height",   "root_relief",  "root_relief_height", "profile_crowning",
      "lead_crowning", "thermal_lead_relief", "end_relief",   "end_relief_width",   "helix_slope",
  };
  return t;
}

const std::vector<BuiltinSpec>& modifyBuiltins() {
  static const std::vector<BuiltinSpec> b = {
      {"load_deflection", length, false},
      {"pitch_deviation", length, true},
      {"profile_deviation", length, true},
      {"whole_depth", length, false},
      {"bending_deflection", length, true},
      {"torsion_deflection", length, true},
      {"pitch_line_velocity", velocity, false},
      {"mesh_stiffness", pressure, false},
      {"tangential_force", force, false},
      {"face_width", length, false},
  };
  return b;
}

bool isFunction(const std::string& n) {
  static const std::vector<std::string> f = {"abs",  "sqrt", "sin",   "cos",     "tan",    "asin",    "acos",
                                             "atan", "atan2", "exp",  "log",     "min",    "max",     "mean",
                                             "round", "floor", "ceil", "coprime", "gcd",   "relative"};
  return std::find(f.begin(), f.end(), n) != f.end();
}

std::string closest(const std::string& name, const std::vector<std::string>& candidates) {
  auto dist = [](const std::string& a, const std::string& b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      cur[0] = i;
      for (size_t j = 1; j <= b.size(); ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      std::swap(prev, cur);
    }
    return prev[b.size()];
  };
  std::string best;
  size_t bestD = 3;
  for (const auto& c : candidates) {
    size_t d = dist(name, c);
    if (d < bestD || (d == bestD && !best.empty() && c < best)) {
      if (d < bestD) bestD = d;
      best = c;
    }
  }
  return bestD <= 2 && name.size() > 1 ? best : "";
}

std::string suggestion(const std::string& hint) { return hint.empty() ? "" : "; did you mean `" + hint + "`?"; }

} // namespace gbx::sema
