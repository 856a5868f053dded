#pragma once
// A planet's bearings (docs/rating.md "Planet bearings"): the load on them is the vector sum
// of the planet's two mesh forces, each along its mesh's line of action at its working
// pressure angle; their life is ISO 281's at the planet's speed relative to the carrier.
namespace gbx::rt::rating {

// The force on a planet's pin from its meshes, per unit of the transverse mesh force F_bt
// (the same on both meshes of a spur planet): tangential F_bt (cos a_sun + cos a_ring), both
// pushing it forward; radial F_bt (sin a_sun - sin a_ring), the sun pushing it out and the
// ring in. Returns the magnitude [N].
double planetPinLoad(double Fbt, double alphaSun, double alphaRing);

} // namespace gbx::rt::rating
