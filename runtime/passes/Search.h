#pragma once
// Pass 1, search: every design of a gearbox that satisfies its rules.
#include <functional>

#include "search/Search.h"

namespace gbx::rt::passes {

// Ranked and cut as the gearbox's `report` asks; all of them, unranked, when the
// objectives need the optimiser.
// `deciding`: the progress of deciding the designs' continuous freedoms. `compact`: the
// designs may come as a compact `listing` (rows made as a CSV listing is written), which
// they do where there are no freedoms and nothing for the optimiser.
SearchResult search(const Model& m, int jobs, double maxDesigns, std::function<void(double)> progress,
                    std::function<void(double)> deciding = nullptr, bool compact = false);

} // namespace gbx::rt::passes
