#include "reference/Catalogue.h"

#include <fmt/format.h>

#include <map>
#include <set>
#include <vector>

#include "catalogue/Shafts.h"
#include "catalogue/Effects.h"
#include "catalogue/Settings.h"
#include "catalogue/StageKinds.h"
#include "units/Unit.h"

namespace gbx::reference {

namespace {

using cat::AttrSpec;
using cat::ValueKind;

// A table cell may not hold `|`, and a line break would end the row.
std::string cell(std::string s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

// The unit a row's values are written in: its hint where it has one (`um` for a clearance),
// else the dimension's display unit.
units::DisplayUnit shownUnit(const AttrSpec& a) {
  static const std::map<std::string, units::DisplayUnit> hints = {
      {"um", {"um", 1e-6}},          {"h", {"h", 3600}},  {"mm^2/s", {"mm^2/s", 1e-6}}, {"kg/m^3", {"kg/m^3", 1}},
      {"degC", {"degC", 1, 273.15}}, {"mm", {"mm", 1e-3}}, {"mrad", {"mrad", 1e-3}},
      {"rpm", {"rpm", 3.14159265358979323846 / 30}}, {"kN", {"kN", 1e3}},  {"N", {"N", 1}},
      {"N/um", {"N/um", 1e6}},       {"N*m", {"N*m", 1}}, {"MPa", {"MPa", 1e6}}};
  auto it = hints.find(a.unitHint);
  return it != hints.end() ? it->second : units::displayUnitFor(a.dim);
}

// A value of the row in its unit, to 10 significant digits (-50 degC, not -49.99999999999997).
std::string show(const units::Number& v, const AttrSpec& a) {
  auto u = shownUnit(a);
  std::string n = fmt::format("{:.10g}", u.shown(v.toDouble()));
  return u.name.empty() ? n : n + " " + u.name;
}

std::string unitOf(const AttrSpec& a) {
  if (a.value == ValueKind::Material) return "a material's name";
  if (a.value == ValueKind::Stage) return "a stage's name";
  if (a.value == ValueKind::Symbol) return "a word";
  if (a.dim == units::dims::none) return a.integer ? "whole number" : "number";
  std::string u = shownUnit(a).name;
  if (a.altDim) u += " (or " + units::displayUnitFor(*a.altDim).name + ")";
  if (a.meshPeriods) u += " or mesh_periods";
  return u;
}

// A value the row accepts, written as a spec would write it.
std::string sample(const AttrSpec& a) {
  if (a.value == ValueKind::Material) return "steel_18CrNiMo7_6";
  if (a.value == ValueKind::Stage) return "first";
  if (a.value == ValueKind::Symbol) return a.symbols.empty() ? "?" : a.symbols.front();
  if (a.value == ValueKind::List)
    return "{0 " + shownUnit(a).name + ", 2.5 " + shownUnit(a).name + ", -1.5 " + shownUnit(a).name + ", …}";
  if (!a.example.empty()) return a.example;
  if (a.dflt) return show(*a.dflt, a);
  if (a.atLeast && a.atMost) return show(*a.atMost, a);
  if (a.atLeast) return show(*a.atLeast, a);
  if (a.dim == units::dims::none) return a.integer ? "3" : "1.2";
  return "10 " + shownUnit(a).name;
}

std::string rules(const AttrSpec& a) {
  std::vector<std::string> r;
  if (a.role == cat::AttrRole::Derived) r.push_back("computed, read only");
  if (a.role == cat::AttrRole::Either) r.push_back("computed unless given");
  if (a.required) r.push_back("required");
  if (a.dflt) r.push_back("default " + show(*a.dflt, a));
  if (a.positive && !(a.atLeast && !a.budget)) r.push_back("> 0");
  if (a.atLeast && !a.budget) r.push_back(">= " + show(*a.atLeast, a));
  if (a.atMost) r.push_back((a.budget ? "at most " : "<= ") + show(*a.atMost, a));
  if (a.value == ValueKind::Symbol || !a.symbols.empty()) {
    std::string w;
    for (const auto& s : a.symbols)
      w += (w.empty() ? "" : ", ") + ("`" + s + "`");
    r.push_back((a.value == ValueKind::Symbol ? "one of " : "or the word ") + w);
  }
  if (a.sceneRef) r.push_back("or `scene NAME`");
  std::string out;
  for (const auto& s : r)
    out += (out.empty() ? "" : "; ") + s;
  return out;
}

std::string example(const AttrSpec& a, const std::string& prefix) {
  if (a.role == cat::AttrRole::Derived) return "`" + prefix + a.name + "`";
  return "`" + prefix + a.name + " = " + sample(a) + ";`";
}

// A row's cells after its name and before its example: unit, meaning, rules. Two rows of a
// name with the same cells (and example) are one row of the catalogue.
std::string middleCells(const AttrSpec& a) {
  return cell(unitOf(a)) + " | " + cell(a.meaning) + " | " + cell(rules(a));
}

// One table line; `kinds`, where given, is a column of its own after the name.
std::string line(const AttrSpec& a, const std::string& prefix, const std::string* kinds = nullptr) {
  return "| `" + a.name + "` | " + (kinds ? *kinds + " | " : "") + middleCells(a) + " | " + cell(example(a, prefix)) +
         " |\n";
}

void table(std::string& out, const std::vector<AttrSpec>& rows, const std::string& prefix = "") {
  out += "| name | unit | meaning | rules | example |\n| --- | --- | --- | --- | --- |\n";
  for (const auto& a : rows)
    out += line(a, prefix);
  out += "\n";
}

// Rows shared by several stage kinds appear once, with the kinds that take them; a name
// whose row differs between kinds (computed for one, given for another; other bounds) has a
// row for each version. A gear row's example names the first gear of its first kind (`sun.z`).
void kindRows(std::string& out, bool gear) {
  struct Merged {
    AttrSpec row;
    std::string kinds, prefix;
  };
  std::vector<Merged> rows;
  std::map<std::string, size_t> bySignature;
  for (const auto* kp : cat::stageKinds())
    for (const auto& k = *kp; const auto& a : gear ? k.gear : k.stage) {
      std::string signature = a.name + "|" + middleCells(a) + "|" + example(a, "");
      auto [it, fresh] = bySignature.emplace(signature, rows.size());
      if (fresh)
        rows.push_back(
            {a, "`" + k.name + "`", gear ? (a.exampleGear.empty() ? k.gears.front() : a.exampleGear) + "." : ""});
      else
        rows[it->second].kinds += ", `" + k.name + "`";
    }
  out += "| name | kinds | unit | meaning | rules | example |\n| --- | --- | --- | --- | --- | --- |\n";
  for (const auto& m : rows)
    out += line(m.row, m.prefix, &m.kinds);
  out += "\n";
}

void kinds(std::string& out) {
  out += "## Stage kinds\n\n| kind | gears |\n| --- | --- |\n";
  for (const auto* kp : cat::stageKinds()) {
    const auto& k = *kp;
    std::string g;
    for (const auto& n : k.gears)
      g += (g.empty() ? "" : ", ") + ("`" + n + "`");
    out += "| `" + k.name + "` | " + g + " |\n";
  }
  out += "\n## Stage attributes\n\nWritten inside a stage (`face_width = 60 mm;`), or at gearbox level through the "
         "stage's name (`hs.face_width`). A `rating.` row may also be written inside a `rating { … }` block of the "
         "stage without the prefix.\n\n";
  kindRows(out, false);
  out += "## Gear attributes\n\nWritten with the gear's name: `pinion.z = 21;`, `wheel.shift in -0.5..0.5;` "
         "(the gear names of each kind are listed above).\n\n";
  kindRows(out, true);
}

void blocks(std::string& out) {
  out += "## Gearbox quantities\n\nRead at gearbox level (`ratio`, `output_speed`) once `operating` is given.\n\n";
  table(out, cat::gearboxQuantities());
  out += "## `operating { … }`\n\nTwo of these fix the operating point: a speed and a torque or the power.\n\n";
  table(out, cat::operatingSettings());
  out += "## `material NAME { … }`\n\n";
  table(out, cat::materialProperties());
  out += "## Scene settings\n\nInside `scene NAME on TARGET { … }`.\n\n";
  table(out, cat::sceneSettings());
  out += "## `accuracy { … }` of a scene\n\n";
  table(out, cat::accuracySettings());
  out += "## Effects of a scene\n\nEach effect is a block inside `effects { … }`; its parameters follow.\n\n";
  for (const auto& e : cat::effects()) {
    out += "### `" + e.name + "`\n\n" + e.meaning + ".";
    if (!e.locals.empty()) {
      out += " A parameter may be written in terms of";
      for (const auto& l : e.locals)
        out += " `" + l + "`";
      out += ".";
    }
    out += "\n\n";
    if (e.params.empty())
      out += "No parameters: `" + e.name + ";`.\n\n";
    else
      table(out, e.params);
  }
  out += "## `split NAME { … }`\n\n";
  table(out, cat::splitSettings());
  out += "Results, read as `NAME.twist` and so on:\n\n";
  table(out, cat::splitOutputs(), "sharing.");
  out += "## `shaft NAME { … }`\n\nThe shaft's own settings (`life.…` and `strength.…` may also be written as blocks: "
         "`life { reliability = 0.95; }`):\n\n";
  table(out, cat::shaftSettings());
  out += "A `segment A .. B { … }`:\n\n";
  table(out, cat::segmentSettings());
  out += "A bevel gear's `gear STAGE.GEAR at X { … }`:\n\n";
  table(out, cat::gearSettings());
  out += "A `bearing NAME at X { … }`:\n\n";
  table(out, cat::bearingSettings());
  out += "A `load at X { … }`:\n\n";
  table(out, cat::loadSettings());
  out += "A `disk at X { … }`:\n\n";
  table(out, cat::diskSettings());
  out += "A `notch KIND at X { … }`, KIND one of";
  for (const auto& k : cat::notchKinds())
    out += " `" + k + "`";
  out += ":\n\n";
  table(out, cat::notchSettings());
  out += "Results of the shaft, read as `NAME.deflection`:\n\n";
  table(out, cat::shaftOutputs(), "input.");
  out += "Results at one of its gears, read as `NAME.deflection_at(STAGE.GEAR)`:\n\n";
  table(out, cat::shaftFunctions(), "input.");
  out += "Results at one of its notches, read as `NAME.notch_at(X).fatigue_safety` (X the notch's position):\n\n";
  table(out, cat::notchOutputs(), "input.notch_at(60 mm).");
  out += "Results of each bearing, read as `NAME.BEARING.life`:\n\n";
  table(out, cat::bearingOutputs(), "input.A.");
  out += "## Studies\n\nA sweep of a scene takes:\n\n";
  table(out, cat::sweepSettings());
  out += "`work_precision of SCENE` takes lists (`rtol in {1e-4, 1e-6, 1e-8};`):\n\n";
  table(out, cat::workPrecisionSettings());
  out += "## `tolerances { … }` of a gearbox\n\nBesides its `path +- amount;` lines:\n\n";
  table(out, cat::toleranceSettings());
  out += "## Words that stand alone\n\n| word | block | meaning |\n| --- | --- | --- |\n";
  for (const auto& f : cat::flags())
    out += std::string("| `") + f.word + "` | " + (f.id == cat::Flag::Plot ? "`study`" : "`report`") + " | " +
           f.meaning + " |\n";
  out += "\n";
}

} // namespace

std::string catalogueMarkdown() {
  std::string out =
      "# Catalogue: every attribute, setting and effect\n\n"
      "<!-- Written by `scripts/reference.sh` from the compiler's catalogue; a test fails when it is stale. -->\n\n"
      "Each row gives the name as a spec writes it, the unit a value is shown in (a spec may use any unit of the "
      "same dimension), what it means, the rules the checker applies, and an example. \"computed, read only\" rows "
      "are results a rule, an objective or a report column can read. How the language uses them is in "
      "[the language reference](language.md).\n\n";
  kinds(out);
  blocks(out);
  return out;
}

} // namespace gbx::reference
