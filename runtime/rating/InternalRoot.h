#pragma once
// ISO 6336-3 method B for the tooth root of an internal gear cut by a pinion-type cutter
// (docs/rating.md "The ring's tooth root"): the fillet the cutter's tip rounding generates,
// the critical section where its tangent makes 60 degrees with the tooth's centre line, the
// load at the outer point of single pair contact of the virtual internal gear.
#include "rating/Iso6336.h"

namespace gbx::rt::rating {

// The cutter: teeth z0, profile shift x0, tip radius as a share of the module; its addendum
// is the internal gear's basic rack dedendum h_fP*.
struct PinionCutter {
  double z0 = 0, x0 = 0, rhoA0 = 0;
};

// The internal gear by magnitudes: z teeth, shift x (ISO 21771: positive thickens its teeth),
// tip and root diameters d_a, d_f [mm] (the cutter is set to cut d_f), module [mm], normal
// pressure and helix angles [rad], the mesh's transverse contact ratio. Lengths out in mm.
// Throws std::domain_error with a sentence when the cutter cannot cut that root.
ToothForm internalToothForm(double z, double x, double da, double df, double mn, double alphaN, double beta,
                            double epsAlpha, double hfP, const PinionCutter& cutter);

// Y_B of an internal gear (ISO 6336-3): rim thickness s_R under the root over the module;
// 1 from 3.5 up, 1.15 ln(8.324 m_n / s_R) from 1.75 to 3.5. Throws below 1.75.
double internalRimFactor(double sR, double mn);

} // namespace gbx::rt::rating
