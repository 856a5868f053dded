#pragma once
// The registry of built-in functions: one signature row per function, read by the
// checker (arity, argument and result rules) and matched by one implementation row in
// runtime/model/Builtins.cpp. The registry test fails when either side lacks the other.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gbx::cat {

enum class Fn : std::uint8_t {
  Abs, Sqrt, Sin, Cos, Tan, Asin, Acos, Atan, Atan2, Exp, Log,
  Min, Max, Mean, Round, Floor, Ceil, Coprime, Gcd, Relative, Worst, Quantile,
};

enum class ArgRule : std::uint8_t {
  Any,           // numbers of any dimension
  SameDim,       // numbers of one dimension
  AngleOrPlain,  // an angle or a plain number
  Plain,         // plain numbers
  WholePlain,    // whole plain numbers (tooth counts)
  Reduction,     // two or more numbers of one dimension, or one per-gear quantity
  Baseline,      // one number, divided by its value in the baseline gearbox
  Scatter,       // one number, evaluated over the gearbox's `tolerances`
  Sampled,       // one number and a constant probability, over the `tolerances` samples
};

enum class ResultRule : std::uint8_t {
  Plain,      // a plain number
  Whole,      // a whole plain number
  Angle,      // an angle
  Condition,  // true or false
  Like,       // the argument's type
  Dim,        // the first argument's dimension, not whole
  Root,       // the square root of the argument's dimension
  Extreme,    // the arguments' dimension, whole when every argument is
};

struct FunctionSpec {
  Fn id;
  std::string_view name;
  std::uint8_t minArgs, maxArgs;
  ArgRule args;
  ResultRule result;
};

inline constexpr FunctionSpec kFunctions[] = {
    {Fn::Abs, "abs", 1, 1, ArgRule::Any, ResultRule::Like},
    {Fn::Sqrt, "sqrt", 1, 1, ArgRule::Any, ResultRule::Root},
    {Fn::Sin, "sin", 1, 1, ArgRule::AngleOrPlain, ResultRule::Plain},
    {Fn::Cos, "cos", 1, 1, ArgRule::AngleOrPlain, ResultRule::Plain},
    {Fn::Tan, "tan", 1, 1, ArgRule::AngleOrPlain, ResultRule::Plain},
    {Fn::Asin, "asin", 1, 1, ArgRule::Plain, ResultRule::Angle},
    {Fn::Acos, "acos", 1, 1, ArgRule::Plain, ResultRule::Angle},
    {Fn::Atan, "atan", 1, 1, ArgRule::Plain, ResultRule::Angle},
    {Fn::Atan2, "atan2", 2, 2, ArgRule::SameDim, ResultRule::Angle},
    {Fn::Exp, "exp", 1, 1, ArgRule::Plain, ResultRule::Plain},
    {Fn::Log, "log", 1, 1, ArgRule::Plain, ResultRule::Plain},
    {Fn::Min, "min", 1, 64, ArgRule::Reduction, ResultRule::Extreme},
    {Fn::Max, "max", 1, 64, ArgRule::Reduction, ResultRule::Extreme},
    {Fn::Mean, "mean", 1, 64, ArgRule::Reduction, ResultRule::Dim},
    {Fn::Round, "round", 2, 2, ArgRule::SameDim, ResultRule::Dim},
    {Fn::Floor, "floor", 1, 1, ArgRule::Plain, ResultRule::Whole},
    {Fn::Ceil, "ceil", 1, 1, ArgRule::Plain, ResultRule::Whole},
    {Fn::Coprime, "coprime", 2, 2, ArgRule::WholePlain, ResultRule::Condition},
    {Fn::Gcd, "gcd", 2, 2, ArgRule::WholePlain, ResultRule::Whole},
    {Fn::Relative, "relative", 1, 1, ArgRule::Baseline, ResultRule::Plain},
    // worst(q): q at the corner of the tolerance box that is worst where q stands (mean(q), one
    // number, is the mean over the box: a Reduction row that the checker tells apart).
    {Fn::Worst, "worst", 1, 1, ArgRule::Scatter, ResultRule::Like},
    // quantile(q, p): the p-quantile of q over the Monte Carlo samples (docs/optimisation.md).
    {Fn::Quantile, "quantile", 2, 2, ArgRule::Sampled, ResultRule::Dim},
};

inline constexpr int kFunctionCount = static_cast<int>(sizeof(kFunctions) / sizeof(kFunctions[0]));

inline const FunctionSpec& functionSpec(Fn id) { return kFunctions[static_cast<size_t>(id)]; }

inline const FunctionSpec* findFunction(std::string_view name) {
  for (const auto& f : kFunctions)
    if (f.name == name) return &f;
  return nullptr;
}

inline std::vector<std::string> functionNames() {
  std::vector<std::string> v;
  for (const auto& f : kFunctions) v.emplace_back(f.name);
  return v;
}

} // namespace gbx::cat
