#pragma once
// The drive's speed profile: constant, a smooth start-up ramp, a sinusoidal fluctuation,
// or both. Its angle is closed-form where one exists; only a ramped fluctuation needs
// the angle as a state of its own.
#include <algorithm>
#include <cmath>

namespace gbx::rt::dyn {

struct Drive {
  double speed0 = 0;      // nominal angular speed, rad/s
  double ramp = 0;        // start-up time, s (0: none)
  bool fluctuates = false;
  double mean = 0, amplitude = 0, omega = 0;  // fluctuation: mean + amplitude sin(omega t)

  bool needsState() const { return ramp > 0 && fluctuates; }
  // Smoothstep 3u² - 2u³ from 0 to 1 over the ramp.
  double rampFactor(double t) const {
    if (ramp <= 0 || t >= ramp) return 1.0;
    if (t <= 0) return 0.0;
    double u = t / ramp;
    return u * u * (3.0 - 2.0 * u);
  }
  double base(double t) const { return fluctuates ? mean + amplitude * std::sin(omega * t) : speed0; }
  double speed(double t) const { return rampFactor(t) * base(t); }
  double acceleration(double t) const {
    double b = base(t), db = fluctuates ? amplitude * omega * std::cos(omega * t) : 0.0;
    double s = rampFactor(t), ds = 0;
    if (ramp > 0 && t > 0 && t < ramp) {
      double u = t / ramp;
      ds = 6.0 * u * (1.0 - u) / ramp;
    }
    return ds * b + s * db;
  }
  // Closed-form angle (valid unless needsState()).
  double angle(double t) const {
    if (fluctuates) return mean * t + amplitude / omega * (1.0 - std::cos(omega * t));
    if (ramp > 0 && t < ramp) {
      double u = std::max(0.0, t / ramp);
      return speed0 * ramp * (u * u * u - 0.5 * u * u * u * u);
    }
    if (ramp > 0) return speed0 * (0.5 * ramp + (t - ramp));
    return speed0 * t;
  }
};

} // namespace gbx::rt::dyn
