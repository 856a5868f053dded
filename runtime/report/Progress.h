#pragma once
// A one-line progress bar for a person at a terminal, on stderr: redrawn in place, and
// finished at 100 % with a newline, so the report never starts on its line. A bar that
// was drawn is finished when it is destroyed, whatever the work reported last.
#include <chrono>
#include <memory>
#include <ostream>
#include <string>

namespace gbx::rt {

class ProgressBar {
public:
  ProgressBar(std::ostream& out, std::string label) : out_(out), label_(std::move(label)) {}
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(double fraction);  // 0..1, never below a fraction reported before; 1 finishes the bar
  void finish();                 // 100 % and a newline, once, if the bar was drawn

private:
  void draw(double fraction);
  std::ostream& out_;
  std::string label_;
  bool drawn_ = false, finished_ = false;
  int last_ = -1;  // the last percentage drawn
  double best_ = 0;  // the largest fraction reported
  size_t leftWidth_ = 0;  // of the time-left text drawn last
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace gbx::rt
