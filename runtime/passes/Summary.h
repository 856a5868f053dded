#pragma once
// What a report's summary says a gearbox was solved for: its operating point and the inputs
// that decide the answer (each stage's kind, material and accuracy; a rated stage's
// application factor, life and lubricant), as the spec gives them, in display units.
#include <vector>

#include "ir/Ir.h"
#include "report/Report.h"

namespace gbx::rt::passes {

std::vector<GearboxReport::Input> decisiveInputs(const ir::Gearbox& gearbox);

} // namespace gbx::rt::passes
