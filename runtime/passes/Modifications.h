#pragma once
// Pass 5, modifications: every `modify` block's rules evaluated on the best design.
#include <string>
#include <vector>

#include "report/Report.h"
#include "model/Model.h"

namespace gbx::rt::passes {

struct Modifications {
  std::vector<ModifyReport> modifications;
  std::vector<std::string> errors;
};

Modifications modifications(const Model& m, const Assignment& best);

} // namespace gbx::rt::passes
