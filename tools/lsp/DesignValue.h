#pragma once
// A quantity's value for a gearbox whose design is fixed, for a hover: the runtime's
// evaluator on that one design. No search and no scene run; a quantity that needs one has
// no value here.
#include <functional>
#include <optional>
#include <string>

#include "ir/Ir.h"

namespace gbx::lsp {

// Whether nothing is left to choose (no `in` range or set of more than one member): the
// gearbox has exactly one candidate design.
bool fixedDesign(const ir::Gearbox& g);

// "= 855.0000 mm (0.855 in SI) for the design of MarineReducer": a stage or gearbox
// quantity in its display unit, as the reports show it. nullopt when the design is not
// fixed or the quantity has no value there.
std::optional<std::string> designValue(const ir::Program& p, const ir::Gearbox& g, const ir::QuantityRef& r,
                                       const units::Dim& dim);

// The stage or gearbox quantity that an expression of the gearbox names where `at` holds:
// the innermost one; nullptr when there is none, or several that differ (a `forall`'s
// instances share their span).
const ir::Expr* quantityAt(const ir::Gearbox& g, const std::function<bool(const source::Span&)>& at);

} // namespace gbx::lsp
