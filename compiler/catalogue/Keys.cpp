#include "catalogue/Keys.h"

#include <algorithm>
#include <array>
#include <utility>

namespace gbx::cat {

namespace {

constexpr std::array<std::string_view, kKeyCount> kNames = {
#define GBX_KEY_NAME(id, name) name,
    GBX_KEYS(GBX_KEY_NAME)
#undef GBX_KEY_NAME
};

// Sorted once for the look-ups lowering makes.
const std::array<std::pair<std::string_view, Q>, kKeyCount>& sorted() {
  static const auto s = [] {
    std::array<std::pair<std::string_view, Q>, kKeyCount> a{};
    for (int i = 0; i < kKeyCount; ++i) a[static_cast<size_t>(i)] = {kNames[static_cast<size_t>(i)], static_cast<Q>(i)};
    std::sort(a.begin(), a.end());
    return a;
  }();
  return s;
}

} // namespace

std::string_view keyName(Q q) {
  if (q == Q::None) return {};
  std::string_view n = kNames[static_cast<size_t>(q)];
  // A word the language spells like another carries its owner after '#'.
  return n.substr(0, n.find('#'));
}

std::optional<Q> keyOf(std::string_view name) {
  const auto& s = sorted();
  auto it = std::lower_bound(s.begin(), s.end(), std::pair<std::string_view, Q>{name, Q{}},
                             [](const auto& a, const auto& b) { return a.first < b.first; });
  if (it == s.end() || it->first != name) return std::nullopt;
  return it->second;
}

Better betterOf(Q q) {
  switch (q) {
  case Q::ContactSafety:
  case Q::BendingSafety:
  case Q::PermissibleContactStress:
  case Q::PermissibleBendingStress:
  case Q::ScuffingSafety:
  case Q::IntegralScuffingSafety:
  case Q::ScuffingTemperature:
  case Q::MicropittingSafety:
  case Q::SpecificFilmThickness:
  case Q::PermissibleFilmThickness:
  case Q::Life:
  case Q::ModifiedLife:
  case Q::BearingLife:
  case Q::BearingModifiedLife:
  case Q::StaticSafety: return Better::Larger;
  case Q::ContactStress:
  case Q::BendingStress:
  case Q::Mass:
  case Q::LoadDeflection:
  case Q::Deflection:
  case Q::Reaction:
  case Q::BendingDeflection:
  case Q::TorsionDeflection:
  case Q::SlidingBalance:
  case Q::Imbalance:
  case Q::PitchDeviation:
  case Q::ProfileDeviation:
  case Q::ProfileFormDeviation:
  case Q::HelixSlopeDeviation:
  case Q::ContactDamage:
  case Q::BendingDamage:
  case Q::ContactTemperature:
  case Q::IntegralTemperature:
  case Q::BulkTemperature: return Better::Smaller;
  default: return Better::Unknown;
  }
}

bool readsInMicrometres(Q q) {
  switch (q) {
  case Q::PitchDeviation:
  case Q::ProfileDeviation:
  case Q::ProfileFormDeviation:
  case Q::HelixSlopeDeviation:
  case Q::BendingDeflection:
  case Q::TorsionDeflection:
  case Q::LoadDeflection:
  case Q::Deflection:
  case Q::DeflectionAt:
  case Q::TorsionAt:
  case Q::TipRelief:
  case Q::LeadCrowning:
  case Q::RatingMeshMisalignment:
  case Q::RatingRoughnessFlank:
  case Q::RatingRoughnessRoot:
  case Q::RatingRoughnessFlankRz:
  case Q::RatingRoughnessRootRz:
  case Q::SpecificFilmThickness:
  case Q::PermissibleFilmThickness: return true;
  default: return false;
  }
}

} // namespace gbx::cat
