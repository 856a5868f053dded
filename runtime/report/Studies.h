#pragma once
// Studies as reports show them: a table with notes, and a JSON value.
#include <string>
#include <vector>

#include "report/Report.h"

namespace gbx::rt {

struct StudyTable {
  std::string name, kind;  // kind: "sweep" or "work_precision"
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  // a stretch a continuation did not follow
};

std::string studyName(const StudyReport& study);
StudyTable studyTable(const StudyReport& study, const RenderOptions& o);
std::string studyJson(const StudyReport& study, const RenderOptions& o);

} // namespace gbx::rt
