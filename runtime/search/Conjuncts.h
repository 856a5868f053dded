// The search's rules as conjuncts: what each reads, the ratio window they give, and
// whether a box of continuous freedoms holds a point where they all hold.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "model/Evaluator.h"
#include "model/Model.h"

namespace gbx::rt {

struct Conjunct {
  const ir::Expr* expr = nullptr;
  std::string text;
  std::set<int> stages;
  bool freedom = false;     // depends on a continuous freedom
  bool unsupported = false; // needs dynamics, load sharing or a baseline: not a search rule
  bool strength = false;    // reads a load-capacity rating: costly, so tested after the cheap rules
};

// Adds to c the stages an expression reads and whether it reads a freedom or a rating.
void dependencies(const Model& m, const ir::Expr& e, Conjunct& c, int depth = 0);

// A rule's conjuncts (`and`, `forall`) in order.
// A conjunct's text for the funnel: a bound on a quantity in the unit its column shows.
std::string ruleText(const ir::Expr& e);
void split(const ir::Expr& e, std::vector<const ir::Expr*>& out);

// The gearbox ratio's window, from the rules that bound it.
struct Window {
  std::optional<Rational> lo, hi;
  bool loStrict = false, hiStrict = false;
  bool empty() const {
    if (!lo || !hi) return false;
    int c = lo->compare(*hi);
    return c > 0 || (c == 0 && (loStrict || hiStrict));
  }
  void lower(const Rational& v, bool strict) {
    if (!lo || v > *lo || (v == *lo && strict)) {
      lo = v;
      loStrict = strict;
    }
  }
  void upper(const Rational& v, bool strict) {
    if (!hi || v < *hi || (v == *hi && strict)) {
      hi = v;
      hiStrict = strict;
    }
  }
  bool contains(const Rational& r) const {
    if (lo) {
      int c = r.compare(*lo);
      if (c < 0 || (c == 0 && loStrict)) return false;
    }
    if (hi) {
      int c = r.compare(*hi);
      if (c > 0 || (c == 0 && hiStrict)) return false;
    }
    return true;
  }
  std::string str() const;
};

// Recognises `ratio == t +- tol`, `ratio in a..b` and one-sided bounds on the gearbox ratio.
bool asWindow(const ir::Expr& e, Window& w);

enum class Verdict { Feasible, Infeasible, Undecided };

inline Truth truthOf(const Value& v) { return v.kind == Value::Bool ? v.truth : Truth::Unknown; }

// Whether some point of the assignment's box of `freedoms` satisfies every rule.
Verdict decide(const Evaluator& ev, Assignment& a, const std::vector<const Conjunct*>& rules,
               const std::vector<int>& freedoms);

} // namespace gbx::rt
