#pragma once
// A solved shaft's DIN 743 strength at each of its notches: the section's loads from the beam
// (bending from both planes, the torque, the axial force), the notch's geometry from the
// segments, the material's strengths and the `strength` settings.
#include <array>
#include <string>
#include <vector>

#include "ir/Ir.h"
#include "shaft/Beam.h"
#include "shaft/Din743.h"

namespace gbx::rt::shaft {

struct NotchRating {
  std::string kind; // shoulder, groove, …
  double x = 0;     // m
  din743::Notch notch;
  std::array<din743::Load, 3> loads; // tension N, bending N m, torsion N m
  din743::Result result;
};

struct StrengthSettings {
  din743::Material material;
  din743::Settings din;
  double peak = 1; // the largest load over the nominal one
  double minFatigue = 1.2, minStatic = 1.2;
};

// The loads of a section at x: a rotating shaft's bending is fully reversed, its torque and
// axial force steady; the larger side where a couple or a load makes them jump.
std::array<din743::Load, 3> sectionLoads(const Model& m, const Solution& s, double x, double peak);

// Every notch of the shaft rated; throws std::invalid_argument naming the notch it cannot rate.
std::vector<NotchRating> rateNotches(const ir::Shaft& sh, const Model& m, const Solution& s,
                                     const StrengthSettings& st);

} // namespace gbx::rt::shaft
