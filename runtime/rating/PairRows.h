#pragma once
// The rating quantities of a pinion-wheel stage (spur, helical) as derived rows: each
// gathers the stage's geometry, load, material, `rating { … }` inputs and `modify` lead
// and tip rules at the design, and reads one factor of the ISO 6336 rating.
#include <optional>
#include <vector>

#include "model/StageKind.h"
#include "rating/Iso6336.h"

namespace gbx::rt::rating {

std::vector<DerivedRow> pairRows();

// The whole rating of a pinion-wheel stage at a point design (no freedom spans an
// interval), or nothing when an input is missing or the geometry admits no rating; the
// reason, when there is one, goes to `why`.
std::optional<PairRating> ratePair(const KindContext& c, std::string* why = nullptr);

} // namespace gbx::rt::rating
