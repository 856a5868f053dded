#pragma once
// `study … { sweep X in a..b step s; output …; plot; }`: the outputs at every value of X,
// with every other input as the design has it.
#include <string>

#include "ir/Ir.h"
#include "report/Report.h"
#include "model/Model.h"

namespace gbx::rt {

StudyReport sweep(const Model& m, const Assignment& design, const ir::Study& study, const std::string& outDir, const std::string& filePrefix);

} // namespace gbx::rt
