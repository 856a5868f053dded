#pragma once
// A stage's rating table as reports show it: one row per factor with a column per gear,
// the verdict line, a JSON value and CSV rows (engineering units).
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

std::vector<std::string> ratingHeader(const RatingReport& r);
// The lines below a rating's table: its warnings, what it leaves out and why, how the
// factors from the models were found.
std::vector<std::string> ratingNotes(const RatingReport& r);
std::vector<std::vector<std::string>> ratingRows(const RatingReport& r);
// "governs: …; K_v subcritical"; or why the stage could not be rated.
std::string ratingVerdict(const RatingReport& r);
std::string ratingJson(const RatingReport& r);
// Tidy rows: gearbox, stage, gear (empty for a mesh quantity), quantity, unit, value.
std::vector<std::vector<std::string>> ratingCsvRows(const std::string& gearbox, const RatingReport& r);

} // namespace gbx::rt
