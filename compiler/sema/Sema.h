#pragma once
// Semantic analysis: names, `extends`, presets, `like`, the attribute catalogue,
// units and dimensions. Produces the program as declared, in IR form; `lower` then
// completes it with catalogue defaults.
#include "diag/Diagnostic.h"
#include "ir/Ir.h"
#include "sema/Loader.h"

namespace gbx::sema {

ir::Program analyse(const LoadedProgram& program, diag::DiagnosticEngine& diags);

} // namespace gbx::sema
