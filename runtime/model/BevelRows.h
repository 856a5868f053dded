#pragma once
// The geometry and rating quantities of a bevel stage (ISO 23509, ISO 10300 method B1) as
// derived rows: each gathers the stage's cone, load, material and `rating { … }` inputs at the
// design, rates the pair and reads one value.
#include <optional>
#include <string>
#include <vector>

#include "model/StageKind.h"
#include "rating/Iso10300.h"

namespace gbx::rt::rating {

std::vector<DerivedRow> bevelRows();

// The pair rated at the design (a freedom spanning an interval at its middle), with the inputs
// it was rated with; none, with the reason, when an input is missing or the geometry admits no
// rating.
struct BevelStageRating {
  BevelInput input;
  BevelRating rating;
};
std::optional<BevelStageRating> rateBevelStage(const KindContext& c, std::string* why = nullptr);

} // namespace gbx::rt::rating
