#pragma once
// Evaluates a `modify` block's rules on a design: each rule's value, whether its `when`
// holds, and the inputs it read.
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "model/Model.h"

namespace gbx::rt {

struct ModInput {
  std::string name;
  double value = 0;  // SI
  units::Dim dim;
  bool given = false;  // fixed in the spec, not computed
};

struct ModOutcome {
  std::string target, text;
  int modTarget = -1;         // its position in cat::modificationTargets()
  bool present = true;        // false when `when` is false
  std::optional<double> value;  // SI
  std::string condition;      // the `when` condition as evaluated
  std::vector<ModInput> inputs;
  std::string error;
};

std::vector<ModOutcome> evaluateModify(const Model& m, const Assignment& design, const ir::Modify& modify);

} // namespace gbx::rt
