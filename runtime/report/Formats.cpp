#include "report/Formats.h"

#include <array>

namespace gbx::rt {

namespace {

const std::array<ReportFormat, 5> kFormats = {{
    {"text", "txt", renderText, true},
    {"json", "json", renderJson, true},
    {"csv", "csv", renderCsv, false, csvTables, false, csvOtherTables},
    {"md", "md", renderMarkdown, false},
    {"html", "html", renderHtml, false, nullptr, true},
}};

} // namespace

std::span<const ReportFormat> reportFormats() { return kFormats; }

const ReportFormat* findReportFormat(std::string_view name) {
  for (const auto& f : kFormats)
    if (f.name == name) return &f;
  return nullptr;
}

} // namespace gbx::rt
