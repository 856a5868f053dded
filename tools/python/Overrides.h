#pragma once
// `gbxc.solve(..., overrides={"hs.face_width": "60 mm", "operating.power": "250 kW"})`: each
// overridden gearbox becomes a variant of itself written in the language (`gearbox V extends
// G { hs.face_width = 60 mm; operating { power = 250 kW; } }`), so the front end checks each
// override as it checks a spec: a name that names nothing, a value of the wrong dimension.
#include <string>
#include <utility>
#include <vector>

#include "ir/Ir.h"

namespace gbx::python {

using Overrides = std::vector<std::pair<std::string, std::string>>; // path, value as written

struct Overridden {
  std::string text;                                          // the spec with the variants after it
  std::vector<std::pair<std::string, std::string>> variants; // variant, the gearbox it overrides
  std::string error;                                         // an override that is not one path and one value
};

Overridden withOverrides(const std::string& spec, const std::vector<std::string>& gearboxes,
                         const Overrides& overrides);

// The program's gearboxes become the variants, under their baselines' names and in their
// order: the report reads as the spec's gearboxes, overridden.
void keepVariants(ir::Program& program, const std::vector<std::pair<std::string, std::string>>& variants);

} // namespace gbx::python
