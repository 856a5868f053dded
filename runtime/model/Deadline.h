#pragma once
// The wall-time limit of a solve (`--time-limit`). Long loops (a stage's candidates, the
// join, an integration's steps) ask `expired()` now and then and stop with a failure that
// names what they were doing; with no limit set, asking costs one relaxed atomic load.
#include <atomic>
#include <chrono>

namespace gbx::rt {

class Deadline {
public:
  using Clock = std::chrono::steady_clock;

  // From now on, `seconds` of wall time (<= 0: no limit).
  static void start(double seconds) {
    limit_.store(seconds > 0 ? seconds : 0, std::memory_order_relaxed);
    at_.store(seconds > 0 ? (Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)))
                                .time_since_epoch()
                                .count()
                          : 0,
              std::memory_order_relaxed);
  }
  static void clear() { start(0); }
  // Past the limit from now on (another MPI rank reached it: every rank must stop alike).
  static void expireNow() {
    if (limit_.load(std::memory_order_relaxed) > 0) at_.store(1, std::memory_order_relaxed);
  }
  // Stop now, limit or not (an embedding program's interrupt: Ctrl-C in Python). The loops
  // stop as at the time limit; `clear()` or the next `start()` lifts it.
  static void interrupt() { at_.store(1, std::memory_order_relaxed); }
  static bool expired() {
    auto at = at_.load(std::memory_order_relaxed);
    return at != 0 && Clock::now().time_since_epoch().count() >= at;
  }
  static double seconds() { return limit_.load(std::memory_order_relaxed); }

private:
  static inline std::atomic<Clock::rep> at_{0};
  static inline std::atomic<double> limit_{0};
};

} // namespace gbx::rt
