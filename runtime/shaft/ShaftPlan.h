#pragma once
// A gearbox's shaft at a design (docs/language.md, "Shafts and bearings"): its beam model with the mesh forces of
// the gears it carries, solved, with each bearing's life and its first critical speed.
#include <optional>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "model/Value.h"
#include "shaft/Beam.h"
#include "shaft/Iso281.h"
#include "shaft/ShaftStrength.h"

namespace gbx::rt {

class Evaluator;
class Model;
struct Assignment;

struct ShaftResult {
  shaft::Model model;
  shaft::Solution solution;
  std::vector<std::string> bearings;  // names, in order
  std::vector<shaft::BearingKind> kinds;
  std::vector<shaft::BearingLife> lives;
  double speed = 0;         // rad/s
  double criticalSpeed = 0; // rad/s
  double deflection = 0;    // largest radial deflection, m
  double deflectionAt = 0;   // where, m
  double mass = 0;          // kg
  struct GearLoad {
    std::string gear;
    double x = 0, Ft = 0, Fr = 0, Fa = 0; // N, at the working pitch circle
  };
  std::vector<GearLoad> gears;
  std::vector<shaft::NotchRating> notches;
  shaft::StrengthSettings strength;
  double fatigueSafety = 0, staticSafety = 0; // the least over the notches (infinite without one)
  std::vector<std::string> warnings;
};

// A stage's mesh force spread across the face as its contact analysis loads it: each
// slice's share (from the face's end nearer the shaft's left end), times `scale`.
struct LoadSpread {
  int stage = -1;
  std::vector<double> share; // sums to 1
  double scale = 1;          // of the forces at the operating point (F_m / F_t)
};

// The shaft `index` of the evaluator's gearbox at the design; nullopt with `error` said when
// the design leaves something unknown or the shaft cannot stand.
// With `spread` (a mesh's misalignment), its deflections alone: no lives, no strength.
// `modes`: also its first critical speed (an eigenproblem, the costly part: a rule on a
// bearing's life does not pay for it).
std::optional<ShaftResult> computeShaft(const Evaluator& ev, int index, const Assignment& a, std::string* error = nullptr,
                                        bool modes = true, const LoadSpread* spread = nullptr);

// The sense of rotation of a stage's pinion (driving) or wheel about its own shaft's +x (+1 or -1).
double senseOf(const Model& model, int stage, bool driving);

// A quantity of a stage (gear -1) or of one of its gears at the design; nullopt where it has no number.
std::optional<double> stageNumber(const Evaluator& ev, const Assignment& a, int stage, int gear, cat::Q key);

// `input.deflection`, `input.A.life`: one quantity of a shaft or of its bearing (`r.gear`).
Value shaftQuantity(const Evaluator& ev, const ir::QuantityRef& r, const Assignment& a);

} // namespace gbx::rt
