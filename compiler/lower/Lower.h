#pragma once
// Completes the checked program: every name is resolved once to its typed id (quantities,
// lets, functions, settings, effects, signals, methods, study targets); every stage
// attribute the catalogue defaults (pressure angle 20°, shaft angle 90°) is made
// explicit, and attributes are put in catalogue order so that the runtime and `dump ir`
// see one canonical form.
#include "ir/Ir.h"

namespace gbx::lower {

ir::Program lower(ir::Program checked);

// A quantity path as the language writes it (`main.pinion.z`, `sharing.twist`, `ratio`)
// resolved against a gearbox; owner Unresolved when it names nothing.
ir::QuantityRef quantityRef(const ir::Program& program, const ir::Gearbox& gearbox, const std::string& path);

} // namespace gbx::lower
