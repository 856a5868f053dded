#pragma once
// Evaluates IR expressions at an assignment: exactly where the inputs are exact
// (tooth counts, decimal literals), in doubles where a formula needs them, and as
// outward-rounded enclosures where continuous freedoms span an interval. Every name was
// resolved by lowering: quantities arrive as (owner, gear, key), functions as ids.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ir/Ir.h"
#include "model/Model.h"
#include "model/Value.h"
#include "units/Unit.h"

namespace gbx::rt {

class Evaluator {
public:
  explicit Evaluator(const Model& m) : m_(m) {}

  Value eval(const ir::Expr& e, const Assignment& a) const;
  Value quantity(const ir::QuantityRef& r, const Assignment& a) const;
  // A quantity path as the language writes it (`main.pinion.z`), resolved on the spot:
  // for tests and tools, never for the search.
  Value quantity(const std::string& path, const Assignment& a) const;
  // The solved freedoms (Freedom::solved) at the design `a`, into `freedoms` (SI, model
  // order; NaN where none meets its condition) and a's box.
  void solveFreedoms(Assignment& a, std::vector<double>& freedoms) const;
  // A stage attribute as the design has it: fixed, chosen, a freedom's interval, a default.
  Value attribute(int stage, int gear, Q key, const Assignment& a) const;
  Value attribute(int stage, Q key, const Assignment& a) const { return attribute(stage, -1, key, a); }
  // A derived quantity of a stage or of one of its gears (kinematics and geometry).
  Value derived(int stage, int gear, Q key, const Assignment& a) const;
  Value derived(int stage, Q key, const Assignment& a) const { return derived(stage, -1, key, a); }
  // Gearbox-level quantity: ratio, input_speed, output_speed, input_torque, output_torque, power.
  Value gearboxQuantity(Q key, const Assignment& a) const;
  // A split's setting or result (twist, displacement, imbalance, …).
  Value splitQuantity(int split, Q key, const Assignment& a) const;
  // The product of the ratios of stages [from, to).
  Value ratioProduct(int from, int to, const Assignment& a) const;
  // A property of the stage's material, when it names one.
  Value materialProperty(int stage, Q property) const;

  const Model& model() const { return m_; }

  // Whether an evaluation on this thread gave up since the last call because a definition
  // nested deeper than any acyclic one can: it needs itself (`face_width = 0.1 mm/kg * mass`,
  // where the mass reads the face width). Reading it clears it.
  static bool tookCycle();

  // A sweep's value for a fixed quantity: an operating value (`power`), a stage attribute
  // (`main.face_width`) or a split setting (`sharing.torsion_shaft.diameter`).
  void setOverride(const ir::QuantityRef& r, Value v);
  // Whether a sweep gives this stage attribute a value (which then counts as given).
  bool overrides(int stage, int gear, Q key) const;

  // A manufacturing deviation added to a stage attribute (a corner of the `tolerances` box).
  void addOffset(const ir::QuantityRef& r, double delta);
  const std::vector<std::pair<ir::QuantityRef, double>>& offsets() const { return offsets_; }
  // The deviations as a cache key (empty at the nominal design).
  std::vector<double> offsetKey() const;
  // The sweep's overrides as a cache key (empty without any).
  std::vector<double> overrideKey() const;
  // `worst(q)` and `mean(q)` read q at the nominal design only (the optimiser's sensitivity
  // evaluates q at each tolerance itself).
  bool nominalOnly = false;
  // Where `worst(q)` (a Scatter of fn Worst) finds its worst value at this design: each
  // tolerance's deviation (SI; all 0 at the nominal design), or nothing where it reads both
  // ends or there are no tolerances.
  struct Where {
    std::vector<double> deviations;  // each tolerance's, SI
    long sample = -1;                // the Monte Carlo sample, or -1 at a corner
  };
  std::optional<Where> worstCorner(const ir::Expr& scatter, const Assignment& a) const;
  // q at every Monte Carlo sample of the gearbox's `tolerances` (docs/optimisation.md), in sample
  // order; nothing where the tolerances are not sampled or q has no value at some sample.
  // shareRanks: under mpirun, the samples are dealt out over the ranks too (a fixed point of
  // a pass only: see parallel/Ranks.h).
  std::optional<std::vector<double>> overSamples(const ir::Expr& q, const Assignment& a, bool shareRanks = false) const;

  // Scene results (`vibration.rms(acceleration)`) and `relative(x)` need the dynamics
  // and the baseline gearbox: the optimiser provides them. The scene is built with the
  // evaluator that asks (its overrides and offsets).
  std::function<Value(const ir::Expr&, const Assignment&, const Evaluator&)> sceneOutput;
  std::function<Value(const ir::Expr&)> baseline;

private:
  const Value* overridden(const ir::QuantityRef& r) const;
  const Value* overridden(Q gearboxKey) const;
  Value withOffset(int stage, int gear, Q key, Value v) const;
  Value givenAttribute(int stage, int gear, Q key, const Assignment& a) const;
  Value scatter(const ir::Expr& e, const Assignment& a) const;
  Value sampled(const ir::Expr& e, const Assignment& a) const;
  Value perGear(const ir::Expr& e, int gear, const Assignment& a) const;
  Value perGearReduce(const ir::Expr& call, const Assignment& a) const;
  Value call(const ir::Expr& e, const Assignment& a) const;
  const Model& m_;
  std::vector<std::pair<ir::QuantityRef, Value>> overrides_;
  std::vector<std::pair<ir::QuantityRef, double>> offsets_;
};

// The unit an expression's values read in: its dimension's display unit, except that only a
// temperature quantity reads in degC; any other temperature expression (a difference, a
// sum) is no absolute temperature and reads in K.
units::DisplayUnit valueUnitOf(const ir::Expr& e);
// The unit a table or a sweep shows an expression in: valueUnitOf, an imbalance in percent.
units::DisplayUnit displayUnitOf(const ir::Expr& e);
// Which end of q is the worse: +1 its largest (stresses, vibration), -1 its smallest
// (safeties, margins), 0 not known.
int betterSense(const ir::Expr& q);

// Interval and exact arithmetic used by the evaluator (exposed for tests).
namespace arith {
Value add(const Value& a, const Value& b);
Value sub(const Value& a, const Value& b);
Value mul(const Value& a, const Value& b);
Value div(const Value& a, const Value& b);
Value neg(const Value& a);
Value powi(const Value& a, int k);
Truth less(const Value& a, const Value& b, bool orEqual);
Truth equal(const Value& a, const Value& b);
Truth land(Truth a, Truth b);
Truth lor(Truth a, Truth b);
Truth lnot(Truth a);
// f monotone in each argument over the box: exact image bounds from the corners.
template <class F>
Value corners(const std::vector<Value>& in, F f);
} // namespace arith

} // namespace gbx::rt

#include "model/Corners.inl"
