#pragma once
// Completes the checked program: every stage attribute the catalogue defaults (pressure
// angle 20°, shaft angle 90°) is made explicit, and attributes are put in catalogue
// order so that the runtime and `dump ir` see one canonical form.
#include "ir/Ir.h"

namespace gbx::lower {

ir::Program lower(ir::Program checked);

} // namespace gbx::lower
