#pragma once
// Thin-slice loaded tooth contact of a cylindrical gear pair (docs/dynamics.md): the face is cut
// into slices, each a spur pair with the single-pair stiffness along the path of contact;
// the profile and lead modifications and the deviations are initial separations; at every
// mesh position the approach that carries the load with only the slices in contact gives
// the loaded static transmission error and the mesh stiffness over one mesh period.
// Everything lies in the transverse plane, along the line of action, in SI.
#include <string>
#include <vector>

#include "dynamics/Stiffness.h"

namespace gbx::rt::dyn {

struct FlankGeometry {
  double rb1 = 0, rb2 = 0;      // base radii (pinion driving)
  double ra1 = 0, ra2 = 0;      // tip radii
  double centerDistance = 0;
  double workingPressureAngle = 0;  // transverse, rad
  double basePitch = 0;         // transverse base pitch p_bt
  double baseHelix = 0;         // beta_b, rad
  double faceWidth = 0;
};

// Initial separations of the flanks, m.
struct FlankSeparations {
  double tipRelief[2] = {0, 0};     // C_a at the tip of pinion, wheel (linear in roll length)
  double reliefLength[2] = {0, 0};  // roll length of the relief from each tip
  double leadCrowning = 0;          // both gears' crowning together, parabolic across the face
  double leadSlope = 0;             // a linear separation across the face (shaft wind-up and bending)
  double endRelief = 0;             // at both ends of the face, linear over endReliefWidth from each end
  double endReliefWidth = 0;
  double basePitch = 0;             // base pitch deviation: each incoming pair early by this much
  double profileForm = 0;           // both gears' profile form deviations: the ends of the path proud
  // A separation across the face of any shape (the shafts' deflections), at equally spaced
  // points from y = 0 to y = b, linear between them; empty: none.
  std::vector<double> leadProfile;
};

struct LoadedMeshInput {
  FlankGeometry g;
  FlankSeparations sep;
  double singleStiffness = 0;  // c', the single-pair stiffness per unit face width at its maximum, N/m per m
  double load = 0;             // transverse force along the line of action, N
  int slices = 40, positions = 64;
  bool sliceLoads = false;     // also the line load of each slice, mean over the period
  // Contact outside the path (dynamics/CornerContact.h): a pair within a base pitch of either
  // end of the path touches at its tip corner where the load closes the corner's separation.
  bool cornerContact = false;
  // Per gear (pinion, wheel), each tooth's position error along the line of action in the
  // order the teeth enter the mesh, positive for a tooth late (the pinion's touches later, the
  // wheel's earlier), m. Either given: the table runs over the hunting period, lcm(z1, z2)
  // mesh periods, each tooth meeting each tooth it can meet. Empty: the teeth are perfect.
  std::vector<double> toothLateness[2];
};

struct LoadedMeshTable {
  // Per position over `periods` mesh periods (one, or the hunting period with tooth errors).
  std::vector<double> te;         // loaded static transmission error per position, m
  std::vector<double> stiffness;  // mesh stiffness per position, N/m
  int periods = 1;
  // Contact outside the path: the positions where a corner carries load, and the largest share
  // of the load a corner carries.
  int cornerPositions = 0;
  double cornerShare = 0;
  double pathLength = 0, epsAlpha = 0, epsBeta = 0;
  double meanStiffness = 0, meanTe = 0, peakToPeakTe = 0;
  double lightLoadStiffness = 0;  // the mean of every pair's stiffness, all in contact (for c_gamma)
  // With sliceLoads: per slice across the face (from y = 0), the force it carries over all
  // its contact lines, averaged over the mesh period, per unit face width (N/m).
  std::vector<double> sliceLineLoad;
  std::string failure;            // a position where no tooth pair touches, or a geometry with no path
};

// The single-pair stiffness along the path, relative to c': 0.7 + 1.2 xi (1 - xi) for xi in
// [0, 1] from the start of contact to its end (its mean is 0.9).
double singlePairShape(double xi);

// The table; the last few are kept per thread and handed back for an identical input (a
// rerun where only the dynamics or the accuracy change, a rating reading the same mesh).
LoadedMeshTable loadedMesh(const LoadedMeshInput& in);
// Every number the table depends on, as a key.
std::vector<double> loadedMeshKey(const LoadedMeshInput& in);

// A periodic table of P values over one period as its mean and its first H Fourier
// harmonics (the trigonometric interpolant, truncated to H < P/2).
struct PeriodicSeries {
  double mean = 0;
  Fourier f;  // absolute coefficients
  double operator()(double tau) const { return mean + (relativeStiffness(f, tau) - 1.0); }
};
PeriodicSeries periodicSeries(const std::vector<double>& table, int harmonics);

} // namespace gbx::rt::dyn
