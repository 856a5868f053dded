#pragma once
// A budget for every size a spec can ask for, decided before the work starts. A constant
// beyond one is E0411 at check time; a size known only at run time (a duration in seconds
// against a design's mesh period, a search space) stops the solve with exit 3 naming the
// budget. Each is far above what a real gearbox needs and small enough to answer in
// seconds and bounded memory.
#include <cstdint>

namespace gbx::cat::budget {

inline constexpr std::int64_t kDomainValues = 100'000;        // values of one decision range
inline constexpr std::int64_t kWholeNumber = 1'000'000'000;   // magnitude of a whole-number decision bound
inline constexpr std::int64_t kSamplesPerPeriod = 100'000;    // a scene's `samples`
inline constexpr std::int64_t kRecordedSamples = 2'000'000;   // recorded samples of one scene run
inline constexpr std::int64_t kMeshPeriods = 1'000'000'000;   // settle, record or duration in mesh periods
inline constexpr std::int64_t kHarmonics = 1'000;             // Fourier harmonics of an effect or a study
inline constexpr std::int64_t kBalanceHarmonics = 256; // a harmonic-balance orbit's harmonics (a dense Newton system)
inline constexpr std::int64_t kSlices = 2'000;                // loaded_mesh slices
inline constexpr std::int64_t kPositions = 8'192;             // loaded_mesh positions per mesh period
inline constexpr std::int64_t kMaxSteps = 1'000'000'000;      // accuracy { max_steps }
inline constexpr std::int64_t kPlanets = 32;                  // planets of a planetary stage
inline constexpr std::int64_t kSweepPoints = 10'000;          // points of one sweep
inline constexpr std::int64_t kWorkPrecisionRuns = 200;       // runs of one work-precision study
inline constexpr std::int64_t kToleranceSamples = 1'000'000;  // Monte Carlo samples of a `tolerances` block
inline constexpr std::int64_t kBranches = 64;                 // branches of a split
inline constexpr double kDefaultMaxDesigns = 1e9;             // search space, `--max-designs`
inline constexpr double kMostMaxDesigns = 4e9;                // the largest `--max-designs` (32-bit indices)
inline constexpr double kMostTimeLimit = 1e7;                 // the largest `--time-limit`, seconds
inline constexpr std::int64_t kKeptDesigns = 2'000'000;       // designs a report lists (`top N`)

} // namespace gbx::cat::budget
