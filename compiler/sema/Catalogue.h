#pragma once
// What the language knows by name, as sema sees it: the registries of compiler/catalogue
// (stage kinds, settings, effects, signals, functions, methods) and did-you-mean hints.
#include <string>
#include <vector>

#include "catalogue/Effects.h"
#include "catalogue/Functions.h"
#include "catalogue/Methods.h"
#include "catalogue/Settings.h"
#include "catalogue/Signals.h"
#include "catalogue/StageKinds.h"

namespace gbx::sema {

using namespace gbx::cat;

// Closest known name within two edits, for "did you mean" hints; "" when none.
std::string closest(const std::string& name, const std::vector<std::string>& candidates);
// "; did you mean `x`?" for a hint from `closest`, "" for none.
std::string suggestion(const std::string& hint);

} // namespace gbx::sema
