#include "report/Shafts.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"
#include "report/Numbers.h"

namespace gbx::rt {

namespace {

using diag::jsonEscape;
constexpr double kRpm = 3.14159265358979323846 / 30;

std::string mm(double m) { return fmt::format("{:g}", m * 1e3); }
std::string newton(double f) { return fmt::format("{:.1f}", f + 0.0); }
std::string hours(double h) { return std::isfinite(h) ? fmt::format("{:.0f}", h) : "no load"; }
std::string jsonNumberOf(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

} // namespace

std::vector<std::string> shaftBearingHeader() {
  return {"bearing", "at [mm]", "kind", "F_r [N]", "F_a [N]", "P [N]", "L10h [h]", "L_nmh [h]", "s0", "method"};
}

std::vector<std::vector<std::string>> shaftBearingRows(const ShaftReport& s) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& b : s.bearings)
    rows.push_back({b.name, mm(b.x), b.kind, newton(b.Fr), newton(b.Fa), newton(b.P), hours(b.L10h), hours(b.Lnmh),
                    std::isfinite(b.s0) ? fmt::format("{:.2f}", b.s0) : "no load", b.method});
  return rows;
}

std::vector<std::string> shaftGearHeader() { return {"gear", "at [mm]", "F_t [N]", "F_r [N]", "F_a [N]"}; }

std::vector<std::vector<std::string>> shaftGearRows(const ShaftReport& s) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& g : s.gears)
    rows.push_back({g.name, mm(g.x), newton(g.Ft), newton(g.Fr), newton(g.Fa)});
  return rows;
}

namespace {

std::string safety(double v, const char* none) { return std::isfinite(v) ? fmt::format("{:.3f}", v) : none; }
std::string factor(double v, double scale) {
  return std::isfinite(v) ? formatNumber(v / scale) : "-";
}
std::string notchName(const ShaftReport::Notch& n) { return fmt::format("{} at {} mm", n.kind, mm(n.x)); }

const char* kLoadTypes[] = {"tension", "bending", "torsion"};

} // namespace

std::vector<ShaftTable> shaftTables(const ShaftReport& s) {
  if (!s.error.empty()) return {};
  std::vector<ShaftTable> t;
  t.push_back({"", shaftBearingHeader(), shaftBearingRows(s), {true, false, true, false, false, false, false, false, false, true}});
  t.push_back({"", shaftGearHeader(), shaftGearRows(s), {true, false, false, false, false}});
  if (s.notches.empty()) return t;
  ShaftTable n{fmt::format("DIN 743, load case {}, peak factor {:g}", s.loadCase, s.peakFactor),
               {"notch", "at [mm]", "d [mm]", "D [mm]", "r [mm]", "M_b [N*m]", "T [N*m]", "F_zd [N]", "S_D", "S_D,min",
                "S_F", "S_F,min"},
               {},
               {true, false, false, false, false, false, false, false, false, false, false, false}};
  for (const auto& x : s.notches)
    n.rows.push_back({x.kind, mm(x.x), mm(x.d), mm(x.D), x.radius > 0 ? mm(x.radius) : "-", newton(x.bending),
                      newton(x.torque), newton(x.axial), safety(x.SD, "static only"), fmt::format("{:.2f}", s.minFatigue),
                      safety(x.SF, "no load"), fmt::format("{:.2f}", s.minStatic)});
  t.push_back(std::move(n));
  for (const auto& x : s.notches) {
    ShaftTable f{"DIN 743 factors, " + notchName(x), {"factor", "tension", "bending", "torsion", "unit"}, {},
                 {true, false, false, false, true}};
    for (const auto& c : x.factors)
      f.rows.push_back({c.label, factor(c.si[0], c.scale), factor(c.si[1], c.scale), factor(c.si[2], c.scale), c.unit});
    for (const auto& c : x.common)
      if (std::isfinite(c.si)) f.rows.push_back({c.label, factor(c.si, c.scale), "", "", c.unit});
    t.push_back(std::move(f));
  }
  return t;
}

std::vector<std::string> shaftNotes(const ShaftReport& s) {
  if (!s.error.empty()) return {"not solved: " + s.error};
  std::vector<std::string> n;
  n.push_back(fmt::format("speed {:.0f} rpm; first critical speed {:.0f} rpm{}", s.speed / kRpm, s.criticalSpeed / kRpm,
                          s.speed > 0 ? fmt::format(" ({:.2f} times the speed)", s.criticalSpeed / s.speed) : ""));
  n.push_back(fmt::format("largest deflection {} um at {} mm; mass {} kg", formatNumber(s.deflection * 1e6),
                          mm(s.deflectionAt), formatNumber(s.mass)));
  for (const auto& w : s.warnings)
    n.push_back("warning: " + w);
  for (const auto& f : s.files)
    n.push_back("chart: " + f);
  return n;
}

std::string textShaft(const ShaftReport& s) {
  std::string o = fmt::format("  shaft {} (design 1)\n", s.name);
  // Names and words read left to right, numbers align right.
  auto table = [&](std::vector<std::string> head, std::vector<std::vector<std::string>> rows,
                   const std::vector<bool>& left) {
    if (rows.empty()) return;
    rows.insert(rows.begin(), std::move(head));
    std::vector<size_t> w(rows[0].size(), 0);
    for (const auto& r : rows)
      for (size_t i = 0; i < r.size(); ++i)
        w[i] = std::max(w[i], r[i].size());
    for (const auto& r : rows) {
      std::string line = "   ";
      for (size_t i = 0; i < r.size(); ++i)
        line += " " + (left[i] ? fmt::format("{:<{}}", r[i], w[i]) : fmt::format("{:>{}}", r[i], w[i]));
      while (!line.empty() && line.back() == ' ')
        line.pop_back();
      o += line + "\n";
    }
  };
  for (auto& t : shaftTables(s)) {
    if (!t.caption.empty()) o += "    " + t.caption + "\n";
    table(std::move(t.header), std::move(t.rows), t.left);
  }
  for (const auto& n : shaftNotes(s))
    o += "    " + n + "\n";
  return o;
}

std::string shaftJson(const ShaftReport& s) {
  std::string o = fmt::format("{{\"error\": {}", s.error.empty() ? "null" : fmt::format("\"{}\"", jsonEscape(s.error)));
  o += fmt::format(", \"speed\": {}, \"critical_speed\": {}, \"deflection\": {}, \"deflection_at\": {}, \"mass\": {}",
                   jsonNumberOf(s.speed), jsonNumberOf(s.criticalSpeed), jsonNumberOf(s.deflection),
                   jsonNumberOf(s.deflectionAt), jsonNumberOf(s.mass));
  o += ", \"bearings\": {";
  for (size_t i = 0; i < s.bearings.size(); ++i) {
    const auto& b = s.bearings[i];
    o += fmt::format(
        "{}\"{}\": {{\"at\": {}, \"kind\": \"{}\", \"reaction\": {}, \"axial_reaction\": {}, \"equivalent_load\": {}, "
        "\"life\": {}, \"modified_life\": {}, \"static_safety\": {}, \"method\": \"{}\"}}",
        i ? ", " : "", jsonEscape(b.name), jsonNumberOf(b.x), b.kind, jsonNumberOf(b.Fr), jsonNumberOf(b.Fa),
        jsonNumberOf(b.P), jsonNumberOf(b.L10h * 3600), jsonNumberOf(b.Lnmh * 3600), jsonNumberOf(b.s0),
        jsonEscape(b.method));
  }
  o += "}, \"gears\": {";
  for (size_t i = 0; i < s.gears.size(); ++i) {
    const auto& g = s.gears[i];
    o += fmt::format("{}\"{}\": {{\"at\": {}, \"tangential_force\": {}, \"radial_force\": {}, \"axial_force\": {}}}",
                     i ? ", " : "", jsonEscape(g.name), jsonNumberOf(g.x), jsonNumberOf(g.Ft), jsonNumberOf(g.Fr),
                     jsonNumberOf(g.Fa));
  }
  o += "}";
  if (!s.notches.empty())
    o += fmt::format(", \"load_case\": {}, \"peak_factor\": {}, \"fatigue_safety\": {}, \"static_safety\": {}, "
                     "\"min_fatigue_safety\": {}, \"min_static_safety\": {}",
                     s.loadCase, jsonNumberOf(s.peakFactor), jsonNumberOf(s.fatigueSafety), jsonNumberOf(s.staticSafety),
                     jsonNumberOf(s.minFatigue), jsonNumberOf(s.minStatic));
  o += ", \"notches\": [";
  for (size_t i = 0; i < s.notches.size(); ++i) {
    const auto& n = s.notches[i];
    o += fmt::format("{}{{\"kind\": \"{}\", \"at\": {}, \"d\": {}, \"D\": {}, \"radius\": {}, \"bending_moment\": {}, "
                     "\"torque\": {}, \"axial_force\": {}, \"fatigue_safety\": {}, \"static_safety\": {}, \"factors\": {{",
                     i ? ", " : "", n.kind, jsonNumberOf(n.x), jsonNumberOf(n.d), jsonNumberOf(n.D), jsonNumberOf(n.radius),
                     jsonNumberOf(n.bending), jsonNumberOf(n.torque), jsonNumberOf(n.axial), jsonNumberOf(n.SD),
                     jsonNumberOf(n.SF));
    for (size_t k = 0; k < n.factors.size(); ++k) {
      const auto& f = n.factors[k];
      o += fmt::format("{}\"{}\": [{}, {}, {}]", k ? ", " : "", f.key, jsonNumberOf(f.si[0]), jsonNumberOf(f.si[1]),
                       jsonNumberOf(f.si[2]));
    }
    for (const auto& c : n.common)
      o += fmt::format(", \"{}\": {}", c.key, jsonNumberOf(c.si));
    o += "}}";
  }
  o += "], \"warnings\": [";
  for (size_t i = 0; i < s.warnings.size(); ++i)
    o += fmt::format("{}\"{}\"", i ? ", " : "", jsonEscape(s.warnings[i]));
  return o + "]}";
}

std::vector<std::vector<std::string>> shaftCsvRows(const std::string& gearbox, const ShaftReport& s) {
  std::vector<std::vector<std::string>> rows;
  auto add = [&](const std::string& item, const char* quantity, const char* unit, double si, double scale,
                 const std::string& method = "") {
    rows.push_back({gearbox, s.name, item, quantity, unit, csvNumber(si, unit, scale), method});
  };
  if (!s.error.empty()) return rows;
  add("", "speed", "rpm", s.speed, kRpm);
  add("", "critical_speed", "rpm", s.criticalSpeed, kRpm);
  add("", "deflection", "um", s.deflection, 1e-6);
  add("", "deflection_at", "mm", s.deflectionAt, 1e-3);
  add("", "mass", "kg", s.mass, 1);
  for (const auto& b : s.bearings) {
    add(b.name, "at", "mm", b.x, 1e-3, b.kind);
    add(b.name, "reaction", "N", b.Fr, 1);
    add(b.name, "axial_reaction", "N", b.Fa, 1);
    add(b.name, "equivalent_load", "N", b.P, 1, b.method);
    add(b.name, "life", "h", b.L10h * 3600, 3600);
    add(b.name, "modified_life", "h", b.Lnmh * 3600, 3600);
    add(b.name, "static_safety", "", b.s0, 1);
  }
  for (const auto& n : s.notches) {
    std::string item = notchName(n);
    add(item, "bending_moment", "N*m", n.bending, 1, "amplitude (the shaft turning)");
    add(item, "torque", "N*m", n.torque, 1, "steady");
    add(item, "axial_force", "N", n.axial, 1, "steady, tension positive");
    add(item, "fatigue_safety", "", n.SD, 1, fmt::format("DIN 743, load case {}", s.loadCase));
    add(item, "static_safety", "", n.SF, 1, fmt::format("DIN 743, peak factor {:g}", s.peakFactor));
    for (const auto& f : n.factors)
      for (int k = 0; k < 3; ++k)
        if (std::isfinite(f.si[k]))
          rows.push_back({gearbox, s.name, item, f.key + "." + kLoadTypes[k], f.unit, csvNumber(f.si[k], f.unit, f.scale), ""});
    for (const auto& c : n.common)
      if (std::isfinite(c.si)) rows.push_back({gearbox, s.name, item, c.key, c.unit, csvNumber(c.si, c.unit, c.scale), ""});
  }
  for (const auto& g : s.gears) {
    add(g.name, "at", "mm", g.x, 1e-3);
    add(g.name, "tangential_force", "N", g.Ft, 1);
    add(g.name, "radial_force", "N", g.Fr, 1);
    add(g.name, "axial_force", "N", g.Fa, 1);
  }
  return rows;
}

} // namespace gbx::rt
