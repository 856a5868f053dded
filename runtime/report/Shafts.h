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
// One table of a shaft as every format draws it: a caption (empty for the first two), its
// header and rows, and which columns read left to right.
struct ShaftTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> left;
};
// Bearings, gears, notches and each notch's DIN 743 factors (none for a shaft not solved).
std::vector<ShaftTable> shaftTables(const ShaftReport& s);
std::vector<std::string> shaftNotes(const ShaftReport& s); // speeds, deflection, mass, warnings, or the error
std::string shaftJson(const ShaftReport& s);
std::vector<std::vector<std::string>> shaftCsvRows(const std::string& gearbox, const ShaftReport& s);
std::string textShaft(const ShaftReport& s);

} // namespace gbx::rt
