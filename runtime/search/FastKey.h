#pragma once
// The first ranking key of a design in doubles, to screen and bound the join: when the
// key's expression is a sum of terms that each read one stage (`a.mass + b.mass`) or only
// the gearbox ratio (`abs(ratio - 13.37)`), its value is a sum of per-candidate tables and
// small compiled functions of the ratio, and a bound over a set of designs follows from
// the least table entries and the interval of their ratios. A screen only: a design that
// may enter the ranking is always keyed by the evaluator, so pruning never changes it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "model/Evaluator.h"

namespace gbx::rt {

// A function of the gearbox ratio alone, compiled to a postfix program.
class RatioFn {
public:
  static std::optional<RatioFn> compile(const ir::Expr& e);
  double at(double ratio) const;
  // The exact value at an exact ratio: the rational the evaluator's exact arithmetic gives
  // (the same number, found without reducing each step); nullopt where that would not be
  // exact (a constant with pi, a division by zero) or the parts grow past 2^100.
  std::optional<Rational> exactAt(const Rational& ratio) const;
  // An enclosure of the function over [lo, hi] (not outward rounded: callers add slack).
  // The usual objective, abs(ratio - target), inline: the join asks it once per window.
  std::pair<double, double> over(double lo, double hi) const {
    if (!absDiff_) return overProgram(lo, hi);
    double a = lo - target_, b = hi - target_;
    if (std::isnan(a) || std::isnan(b)) return {-INFINITY, INFINITY};
    return a >= 0 ? std::pair{a, b} : b <= 0 ? std::pair{-b, -a} : std::pair{0.0, std::max(-a, b)};
  }

private:
  enum class K : std::uint8_t { Const, Ratio, Neg, Add, Sub, Mul, Div, PowI, Abs, Sqrt, Min, Max };
  struct Node {
    K k;
    double c = 0;
    int n = 0;
    std::optional<Rational> exact = std::nullopt; // Const: the literal, when it is a rational
  };
  bool emit(const ir::Expr& e);
  std::pair<double, double> overProgram(double lo, double hi) const;
  std::vector<Node> code_;
  bool absDiff_ = false;  // the program is abs(ratio - target_)
  double target_ = 0;
};

class FastKey {
public:
  // What a term reads, as the search's rule analysis sees it.
  struct Reads {
    std::set<int> stages;
    bool other = false; // a freedom, a scene, a baseline: not a table over candidates
  };
  using ReadsOf = std::function<Reads(const ir::Expr&)>;
  // Sets stage s's decisions to its candidate c in the assignment.
  using Place = std::function<void(Assignment&, int s, size_t c)>;

  // nullopt when the expression is not of that shape. maximise: the key is the negated value.
  static std::optional<FastKey> build(const Evaluator& ev, const ir::Expr& e, bool maximise,
                                      const std::vector<size_t>& candidates, const ReadsOf& reads, const Place& place);

  // cand: candidate index per stage.
  double value(const std::uint32_t* cand, double ratio) const {
    double v = constant_;
    for (const auto& t : tables_)
      v += t.g[cand[t.stage]];
    for (const auto& [c, f] : ratio_)
      v += c * f.at(ratio);
    return v;
  }
  // A lower bound of the key at a ratio computed in doubles: the ratio widened by 1e-12 of
  // itself, the sum less its rounding.
  double lowerAt(const std::uint32_t* cand, double ratio) const {
    double v = constant_;
    for (const auto& t : tables_)
      v += t.g[cand[t.stage]];
    return v + ratioLower(ratio * (1 - 1e-12), ratio * (1 + 1e-12)) - rounding_;
  }
  // What summing the terms in doubles may lose, for any design (from their magnitudes).
  double rounding() const { return rounding_; }
  double entry(int s, std::uint32_t c) const {
    int t = tableOf_[static_cast<size_t>(s)];
    return t < 0 ? 0.0 : tables_[static_cast<size_t>(t)].g[c];
  }
  const std::vector<double>* table(int s) const {
    int t = tableOf_[static_cast<size_t>(s)];
    return t < 0 ? nullptr : &tables_[static_cast<size_t>(t)].g;
  }
  double least(int s) const {
    int t = tableOf_[static_cast<size_t>(s)];
    return t < 0 ? 0.0 : tables_[static_cast<size_t>(t)].least;
  }
  double constant() const { return constant_; }
  // A lower bound of the ratio terms over designs whose ratio lies in [lo, hi].
  double ratioLower(double lo, double hi) const {
    double v = 0;
    for (const auto& [c, f] : ratio_) {
      auto [a, b] = f.over(lo, hi);
      v += c >= 0 ? c * a : c * b;
    }
    return std::isnan(v) ? -INFINITY : v;
  }

private:
  struct Table {
    int stage = 0;
    std::vector<double> g;
    double least = 0;
  };
  double constant_ = 0;
  double rounding_ = 0;
  std::vector<Table> tables_;
  std::vector<int> tableOf_;
  std::vector<std::pair<double, RatioFn>> ratio_;
};

// Least entry of any range of a table in constant time (a sparse table).
class RangeMin {
public:
  RangeMin() = default;
  explicit RangeMin(const std::vector<double>& v);
  double least(size_t from, size_t to) const; // [from, to), non-empty
  bool empty() const { return levels_.empty(); }

private:
  std::vector<std::vector<double>> levels_;
};

} // namespace gbx::rt
