#include "diag/Suggest.h"

#include <algorithm>

namespace gbx::diag {

std::string closest(const std::string& name, const std::vector<std::string>& candidates) {
  auto dist = [](const std::string& a, const std::string& b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      cur[0] = i;
      for (size_t j = 1; j <= b.size(); ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      std::swap(prev, cur);
    }
    return prev[b.size()];
  };
  std::string best;
  size_t bestD = 3;
  for (const auto& c : candidates) {
    size_t d = dist(name, c);
    if (d < bestD || (d == bestD && !best.empty() && c < best)) {
      if (d < bestD) bestD = d;
      best = c;
    }
  }
  return bestD <= 2 && name.size() > 1 ? best : "";
}

std::string suggestion(const std::string& hint) { return hint.empty() ? "" : "; did you mean `" + hint + "`?"; }

} // namespace gbx::diag
