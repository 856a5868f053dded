#pragma once
// Pass 3, the design table: every ranked design with its teeth, its other choices and
// the values of the report's columns.
#include <optional>
#include <string>
#include <vector>

#include "model/Evaluator.h"
#include "passes/Optimise.h"
#include "report/Report.h"

namespace gbx::rt::passes {

// `report { columns … }`, or else the objectives.
struct Columns {
  std::vector<const ir::Expr*> exprs;
  std::vector<std::string> names;
};
Columns reportColumns(const ir::Gearbox& gearbox);

// lazy: a CSV listing's rows are made as they are written (the designs move into the
// table), where every value is a point; otherwise every row is held.
GearboxReport designTable(const Model& m, Optimised& designs, const Columns& columns, bool lazy = false);

// An objective or a report column with no value for a listed design ranks or reports
// nothing: one message per such expression, naming the design and the quantity that
// cannot be computed. Scene results (known for the best design only) are not checked.
std::vector<std::string> unevaluated(const Model& m, const GearboxReport& table, const Columns& columns);

// What scenes, modifications and studies run on: the best design at its optimum freedoms.
std::optional<Assignment> bestDesign(const Model& m, const Optimised& designs);

// Deviations from the nominal design (SI, one per tolerance line) as a report writes them:
// "main.face_width +1 mm, main.helix_angle -0.05 deg"; the zero ones left out; a Monte Carlo
// sample's to four figures.
std::string deviationsText(const Model& m, const std::vector<double>& deviations, bool sample);

// Where a `worst(…)` column finds its value for design 1 (docs/language.md), as a report note;
// nothing for another column or where the evaluator cannot compute the corners.
std::optional<std::string> cornerNote(const Model& m, const Evaluator& ev, const ir::Expr& column,
                                      const std::string& name, const Assignment& a);

// A report column that is a scene result, as the scene pass computed it for the best design.
struct SceneColumn {
  size_t column = 0;
  double value = 0;  // SI
};
// Scene results are known for the best design only: its row takes them from the scene pass.
void setSceneColumns(GearboxReport& table, const std::vector<SceneColumn>& values);

} // namespace gbx::rt::passes
