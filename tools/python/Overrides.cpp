#include "python/Overrides.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace gbx::python {

namespace {

// A path of names separated by dots (`hs.pinion.shift`, `operating.power`).
bool isPath(const std::string& p) {
  bool start = true;
  for (char c : p) {
    if (c == '.') {
      if (start) return false;
      start = true;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_' ||
               (!start && std::isdigit(static_cast<unsigned char>(c)))) {
      start = false;
    } else {
      return false;
    }
  }
  return !start;
}

// One value: an expression the front end reads, with nothing that would end the statement or
// open another (`60 mm`, `0.3`, `steel_18CrNiMo7_6`, `20 deg`).
std::string valueError(const std::string& path, const std::string& v) {
  if (v.find_first_not_of(" \t") == std::string::npos) return fmt::format("override `{}` has no value", path);
  for (const char* bad : {";", "{", "}", "\n", "\r", "//", "/*"})
    if (v.find(bad) != std::string::npos)
      return fmt::format("override `{}`: its value `{}` holds `{}`; give one value, such as \"60 mm\"", path, v, bad);
  return {};
}

} // namespace

Overridden withOverrides(const std::string& spec, const std::vector<std::string>& gearboxes,
                         const Overrides& overrides) {
  Overridden out;
  std::string members, operating;
  for (const auto& [path, value] : overrides) {
    if (!isPath(path)) {
      out.error = fmt::format("override `{}`: not a path of names separated by dots, such as \"hs.face_width\"", path);
      return out;
    }
    if (std::string e = valueError(path, value); !e.empty()) {
      out.error = e;
      return out;
    }
    if (path.rfind("operating.", 0) == 0)
      operating += fmt::format(" {} = {};", path.substr(10), value);
    else
      members += fmt::format("  {} = {};\n", path, value);
  }
  out.text = spec;
  if (!out.text.empty() && out.text.back() != '\n') out.text += '\n';
  out.text += "\n// gbxc.solve(overrides=...)\n";
  for (size_t i = 0; i < gearboxes.size(); ++i) {
    std::string variant = fmt::format("gbxc_override_{}_{}", i, gearboxes[i]);
    out.text += fmt::format("gearbox {} extends {} {{\n{}", variant, gearboxes[i], members);
    if (!operating.empty()) out.text += fmt::format("  operating {{{} }}\n", operating);
    out.text += "}\n";
    out.variants.emplace_back(variant, gearboxes[i]);
  }
  return out;
}

void keepVariants(ir::Program& program, const std::vector<std::pair<std::string, std::string>>& variants) {
  std::vector<ir::Gearbox> kept;
  for (const auto& pair : variants) {
    const std::string &variant = pair.first, &base = pair.second;
    std::string baseline;
    for (const auto& g : program.gearboxes)
      if (g.name == base) baseline = g.baseline;
    auto v = std::find_if(program.gearboxes.begin(), program.gearboxes.end(),
                          [&](const ir::Gearbox& g) { return g.name == variant; });
    if (v == program.gearboxes.end()) continue;
    kept.push_back(std::move(*v));
    ir::Gearbox& g = kept.back();
    g.name = base;
    g.baseline = baseline;
    for (auto& st : g.stages)
      for (auto& a : st.attributes)
        if (a.origin == "gearbox " + variant) a.origin = "override";
  }
  program.gearboxes = std::move(kept);
}

} // namespace gbx::python
