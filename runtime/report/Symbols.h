#pragma once
// Symbols and units as engineers write them, for HTML and Markdown: `K_Hbeta` as K<sub>Hβ</sub>,
// `sigma_Hlim` as σ<sub>Hlim</sub>, `[mm^2/s]` as [mm²/s], `[um]` as [µm]. Text and CSV keep
// ASCII, and the schema's names stay as they are.
#include <string>

namespace gbx::rt {

// A rating table's label (`K_Hbeta`, `Z_B, Z_D`, `d_a [mm]`, `contact_stress [MPa]`): each
// symbol (a letter or a Greek letter's name, `_`, a short subscript) in HTML, and the unit in
// brackets with its superscripts and µ; a word with an underscore (`contact_stress`) stays.
// The result is HTML: `<`, `>` and `&` of the label are escaped.
std::string symbolHtml(const std::string& label);

// A unit (`mm^2/s`, `um`, `N*m`, `degC`) as written in a document: mm²/s, µm, N·m, °C.
std::string unitHtml(const std::string& unit);

} // namespace gbx::rt
