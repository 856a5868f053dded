#pragma once
// Physical dimension as integer exponents of length, mass, time, plane angle and temperature.
// Angle is kept as a dimension of its own so that an angular speed (rpm, deg/s) is
// not mistaken for a frequency (Hz) or a torque for an energy-like product.
#include <array>
#include <cstdint>
#include <string>

namespace gbx::units {

class Dim {
public:
  enum Base { Length, Mass, Time, Angle, Temperature, Count };
  constexpr Dim() = default;
  constexpr Dim(int l, int m, int t, int a, int th = 0)
      : e_{static_cast<int8_t>(l), static_cast<int8_t>(m), static_cast<int8_t>(t), static_cast<int8_t>(a), static_cast<int8_t>(th)} {}

  int exp(Base b) const { return e_[b]; }
  bool dimensionless() const { return e_ == std::array<int8_t, Count>{}; }
  Dim operator*(const Dim& o) const;
  Dim operator/(const Dim& o) const;
  Dim pow(int k) const;
  // Half of every exponent; false when one is odd.
  bool sqrt(Dim& out) const;
  bool operator==(const Dim& o) const { return e_ == o.e_; }
  bool operator!=(const Dim& o) const { return e_ != o.e_; }
  bool operator<(const Dim& o) const { return e_ < o.e_; }

  // The SI unit in reports' notation: "kg*m^2/s^2", "rad/s", "1".
  std::string siUnit() const;
  // What an engineer calls it, where it has a common name: "a torque", "an angular speed".
  std::string describe() const;

private:
  std::array<int8_t, Count> e_{};
};

namespace dims {
inline constexpr Dim none{0, 0, 0, 0};
inline constexpr Dim length{1, 0, 0, 0};
inline constexpr Dim mass{0, 1, 0, 0};
inline constexpr Dim time{0, 0, 1, 0};
inline constexpr Dim angle{0, 0, 0, 1};
inline constexpr Dim frequency{0, 0, -1, 0};
inline constexpr Dim angularSpeed{0, 0, -1, 1};
inline constexpr Dim velocity{1, 0, -1, 0};
inline constexpr Dim acceleration{1, 0, -2, 0};
inline constexpr Dim force{1, 1, -2, 0};
inline constexpr Dim torque{2, 1, -2, 0};
inline constexpr Dim power{2, 1, -3, 0};
inline constexpr Dim pressure{-1, 1, -2, 0};
inline constexpr Dim density{-3, 1, 0, 0};
inline constexpr Dim stiffness{0, 1, -2, 0};
inline constexpr Dim dampingCoeff{0, 1, -1, 0};
inline constexpr Dim inertia{2, 1, 0, 0};
inline constexpr Dim area{2, 0, 0, 0};
inline constexpr Dim temperature{0, 0, 0, 0, 1};
inline constexpr Dim kinematicViscosity{2, 0, -1, 0};
} // namespace dims

} // namespace gbx::units
