#pragma once
// Pass 7, shafts: each shaft of the gearbox solved at the best design, as a table.
#include <string>
#include <vector>

#include "model/Model.h"
#include "report/Report.h"

namespace gbx::rt::passes {

struct Shafts {
  std::vector<ShaftReport> shafts;
  std::vector<std::string> warnings;
};

Shafts shafts(const Model& m, const Assignment& best);

} // namespace gbx::rt::passes
