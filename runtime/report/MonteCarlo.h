#pragma once
// The Monte Carlo part of a report (docs/optimisation.md): what was sampled, one row per
// statistic of each sampled quantity with its standard error, the JSON value and the CSV
// rows (engineering units).
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

// "2000 samples of the tolerances at design 1, normal (each ± is three standard deviations), seed 1"
std::string monteCarloHeadline(const MonteCarloReport& r);
// "main.face_width ± 1 mm, main.helix_angle ± 0.05 deg"
std::string monteCarloTolerances(const MonteCarloReport& r);
std::vector<std::string> monteCarloHeader();
// quantity, unit, statistic, value, standard error, sample (the worst's)
std::vector<std::vector<std::string>> monteCarloRows(const MonteCarloReport& r);
// How the standard errors are found, and what they say about the sample count.
std::vector<std::string> monteCarloNotes(const MonteCarloReport& r);
std::string monteCarloJson(const MonteCarloReport& r);
// Tidy rows: gearbox, quantity, unit, statistic, value, standard_error, sample.
std::vector<std::vector<std::string>> monteCarloCsvRows(const std::string& gearbox, const MonteCarloReport& r);
// One row per sample: gearbox, sample, each tolerance's deviation, each quantity's value.
std::vector<std::string> sampleCsvHeader(const MonteCarloReport& r);
std::vector<std::vector<std::string>> sampleCsvRows(const std::string& gearbox, const MonteCarloReport& r);

} // namespace gbx::rt
