#pragma once
// "Did you mean" hints, for every stage that reports an unknown word.
#include <string>
#include <vector>

namespace gbx::diag {

// Closest known name within two edits; "" when none.
std::string closest(const std::string& name, const std::vector<std::string>& candidates);
// "; did you mean `x`?" for a hint from `closest`, "" for none.
std::string suggestion(const std::string& hint);

} // namespace gbx::diag
