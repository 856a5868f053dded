#pragma once
// A shaft as beam finite elements: two bending planes and torsion, hollow
// round sections, Timoshenko shear by default (Euler–Bernoulli on request), bearings as
// radial springs (rigid where no stiffness is given) and one of them holding the thrust.
// SI throughout: m, N, N m, rad.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace gbx::rt::shaft {

inline constexpr double kRigid = std::numeric_limits<double>::infinity();

// A piece of the shaft with one outer diameter and one bore (0: solid).
struct Section {
  double x0 = 0, x1 = 0;
  double diameter = 0, bore = 0;
  double roughness = 0; // Rz of its surface (DIN 743's K_F); 0: not given
};

struct Material {
  double E = 206e9, G = 79.3e9, density = 7850;
  double poisson() const { return E / (2 * G) - 1; }
};

struct Bearing {
  std::string name;
  double x = 0;
  double radialStiffness = kRigid; // N/m in either bending plane
  bool axialHeld = false;          // takes the shaft's axial force
};

// A force at a station: radial components in the two bending planes (y, z), axial x, the
// bending moments an axial force at a radius makes (about z for plane y, about y for plane z,
// each as the slope of its plane), and a torque about the axis.
struct PointLoad {
  double x = 0;
  double Fy = 0, Fz = 0, Fx = 0;
  double My = 0, Mz = 0; // moment acting on the slope of plane y and of plane z
  double T = 0;
};

// A rigid disk at a station for the natural frequencies: its mass, diametral and polar inertia.
struct Disk {
  double x = 0;
  double mass = 0, diametralInertia = 0, polarInertia = 0;
};

struct Model {
  std::vector<Section> sections; // contiguous, left to right
  Material material;
  std::vector<Bearing> bearings;
  std::vector<PointLoad> loads;
  std::vector<Disk> disks;
  bool shear = true;         // Timoshenko; false: Euler–Bernoulli
  double torsionFixedAt = 0; // the station where the twist is 0 (the coupling)
  int elements = 100;        // natural frequencies: at least this many elements along the shaft
};

// The shaft's static answer on the stations (section ends, bearings, loads, disks): both
// planes' deflection and slope, the twist and the axial displacement, each bearing's
// reaction. Between stations nothing is loaded, so the element's own shape functions give
// the exact line there (Timoshenko's interdependent interpolation).
struct Solution {
  std::vector<double> x;
  std::vector<double> v, slopeY; // plane y: deflection, section rotation
  std::vector<double> w, slopeZ; // plane z
  std::vector<double> twist, axial;
  std::vector<double> phi; // per element: the shear parameter (0: Euler–Bernoulli)
  struct Reaction {
    double Fy = 0, Fz = 0, Fx = 0;
    double radial() const;
  };
  std::vector<Reaction> reactions; // per bearing, the force the bearing puts on the shaft
  std::vector<double> momentY,
      momentZ;                // bending moment at each station (from its left element; the first from its right)
  std::vector<double> torque; // per element: the torque it carries
  // Per element, its own end moments (a couple acting at a station makes them jump there).
  std::vector<double> startY, endY, startZ, endZ;

  enum class Plane { Y, Z };
  double deflection(Plane p, double at) const;
  double slope(Plane p, double at) const;
  double moment(Plane p, double at) const; // linear within an element; at a station, the element on its right
  double deflectionAt(double at) const { return std::hypot(deflection(Plane::Y, at), deflection(Plane::Z, at)); }
  double slopeAt(double at) const { return std::hypot(slope(Plane::Y, at), slope(Plane::Z, at)); }
  double twistAt(double at) const; // linear between stations
  double torqueAt(double at) const; // the torque carried there; at a station, by the element on its right

private:
  size_t element(double at) const;
};

// Section properties of a hollow round section.
struct Props {
  double A, I, J, kappa; // area, second moment, polar moment, shear coefficient (Cowper)
};
Props props(const Section& s, double poisson);

// The nodes of the mesh: every section end, bearing and disk station, with every load's
// station for the static solve, or (`fine`, the natural frequencies) enough points between
// them for `elements`.
std::vector<double> meshNodes(const Model& m, bool fine);

// Solves the static deflection; throws std::invalid_argument on a shaft that cannot stand
// (fewer than two radial supports, no section, a station off the shaft).
Solution solve(const Model& m);

// The first `count` bending natural frequencies on the bearings, rad/s, at standstill:
// Timoshenko (or Euler–Bernoulli) elements with rotary inertia, disks as rigid masses.
std::vector<double> naturalFrequencies(const Model& m, int count);

// The first `count` torsional natural frequencies of the free shaft with its disks, rad/s
// (the rigid turning at 0 left out).
std::vector<double> torsionalFrequencies(const Model& m, int count);

} // namespace gbx::rt::shaft
