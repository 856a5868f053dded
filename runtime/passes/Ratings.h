#pragma once
// Pass 6, ratings: each rated stage's ISO 6336 rating on the best design, as a table.
#include <string>
#include <vector>

#include "model/Model.h"
#include "report/Report.h"

namespace gbx::rt::passes {

struct Ratings {
  std::vector<RatingReport> ratings;
  std::vector<std::string> errors;
};

Ratings ratings(const Model& m, const Assignment& best);

} // namespace gbx::rt::passes
