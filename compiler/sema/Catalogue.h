#pragma once
// What the language knows by name, as sema sees it: the registries of compiler/catalogue
// (stage kinds, settings, effects, signals, functions, methods) and did-you-mean hints.
#include <string>
#include <vector>

#include "catalogue/Effects.h"
#include "catalogue/Functions.h"
#include "catalogue/Methods.h"
#include "catalogue/Settings.h"
#include "catalogue/Shafts.h"
#include "catalogue/Signals.h"
#include "catalogue/StageKinds.h"
#include "diag/Suggest.h"

namespace gbx::sema {

using namespace gbx::cat;
using diag::closest;
using diag::suggestion;

} // namespace gbx::sema
