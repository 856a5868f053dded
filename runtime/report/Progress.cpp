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
  // The time left, from the pace so far, once there is a pace to go by.
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string left = f >= 0.01 && f < 1 && elapsed >= 2 ? fmt::format(", about {:.0f} s left", elapsed * (1 - f) / f) : "";
  // Blanks over a longer text drawn before.
  std::string blank(leftWidth_ > left.size() ? leftWidth_ - left.size() : 0, ' ');
  leftWidth_ = left.size();
  out_ << fmt::format("\r  {} [{}{}] {:3d}%{}{}", label_, std::string(static_cast<size_t>(filled), '#'),
                      std::string(static_cast<size_t>(30 - filled), '.'), percent, left, blank)
       << std::flush;
  drawn_ = true;
}

void ProgressBar::update(double fraction) {
  if (finished_) return;
  // The fraction never goes back: work that grows (more designs to decide) holds the bar.
  fraction = std::max(fraction, best_);
  best_ = fraction;
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
