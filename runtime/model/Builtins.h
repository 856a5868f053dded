#pragma once
// The runtime side of the function registry (compiler/catalogue/Functions.h): one
// implementation row per function, over exact values, doubles and enclosures.
#include <vector>

#include "catalogue/Functions.h"
#include "model/Value.h"

namespace gbx::rt {

using BuiltinFn = Value (*)(const std::vector<Value>& args);

struct BuiltinRow {
  cat::Fn id;
  BuiltinFn fn;
};

const std::vector<BuiltinRow>& builtinRows();
// The implementation of a function (nullptr when it has none: the registry test fails).
BuiltinFn builtin(cat::Fn id);

} // namespace gbx::rt
