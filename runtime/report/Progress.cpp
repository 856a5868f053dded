#include "report/Progress.h"

#include <algorithm>

#include <fmt/format.h>

namespace gbx::rt {

void ProgressBar::draw(double f) {
  f = std::clamp(f, 0.0, 1.0);
  int percent = static_cast<int>(f * 100);
  if (percent == last_) return;  // redraw only when the figure changes
  last_ = percent;
  int filled = static_cast<int>(f * 30);
  out_ << fmt::format("\r  {} [{}{}] {:3d}%", label_, std::string(static_cast<size_t>(filled), '#'),
                      std::string(static_cast<size_t>(30 - filled), '.'), percent)
       << std::flush;
  drawn_ = true;
}

void ProgressBar::update(double fraction) {
  if (finished_) return;
  draw(fraction);
  if (fraction >= 1.0) finish();
}

void ProgressBar::finish() {
  if (!drawn_ || finished_) return;
  draw(1.0);
  out_ << "\n" << std::flush;
  finished_ = true;
}

} // namespace gbx::rt
