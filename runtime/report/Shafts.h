#pragma once
// A shaft's table in every format: its bearings (reactions, equivalent load, lives, static
// safety), the gears' forces on it, and a line each for its speeds, deflection and mass.
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

std::vector<std::string> shaftBearingHeader();
std::vector<std::vector<std::string>> shaftBearingRows(const ShaftReport& s);
std::vector<std::string> shaftGearHeader();
std::vector<std::vector<std::string>> shaftGearRows(const ShaftReport& s);
std::vector<std::string> shaftNotes(const ShaftReport& s); // speeds, deflection, mass, warnings, or the error
std::string shaftJson(const ShaftReport& s);
std::vector<std::vector<std::string>> shaftCsvRows(const std::string& gearbox, const ShaftReport& s);
std::string textShaft(const ShaftReport& s);

} // namespace gbx::rt
