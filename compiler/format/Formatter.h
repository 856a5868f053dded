#pragma once
// `gbxc fmt`: one layout for every .gbx file (docs/formatting.md). Only blanks and line
// breaks between tokens change; the tokens, their order and the comments stay, and the
// result is checked to parse to the same tokens with the same roles.
#include <optional>
#include <string>

#include "diag/Diagnostic.h"
#include "source/Source.h"

namespace gbx::format {

// The formatted text of a loaded file; nullopt, with the reasons in `diags`, when the file
// does not parse (syntax errors). Throws std::logic_error, leaving the file to the caller
// as it was, when the layout would not read as the input did (a defect of the formatter).
std::optional<std::string> formatFile(const source::SourceManager& sm, int fileId, diag::DiagnosticEngine& diags);

// The same for a text, named `displayPath` in diagnostics.
std::optional<std::string> formatText(const std::string& displayPath, const std::string& text,
                                      source::SourceManager& sm, diag::DiagnosticEngine& diags);

} // namespace gbx::format
