#pragma once
// How every CSV table writes a number: the shortest decimal that, read back in the header's
// unit, gives the value itself (71 for a fixed 71 mm, not 70.99999999999999).
#include <string>

namespace gbx::rt {

// `si` shown in `unit` (its name as a header writes it: `mm`, `deg`, `mm^2/s`, `degC`), which
// is `scale` SI units with its zero at `offset`: the fewest significant digits whose reading
// as `DIGITS unit` is `si` again, exactly as the compiler reads that literal (a decimal times
// the unit's exact scale, π included, rounded once). A unit name that does not parse falls
// back to the double scale. Empty for a non-finite value; a plain number (no unit) is its
// shortest round-trip form.
std::string csvNumber(double si, const std::string& unit = "", double scale = 1.0, double offset = 0.0);

} // namespace gbx::rt
