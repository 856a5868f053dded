#pragma once
// Contact outside the path of contact (corner contact, docs/dynamics.md). Under load the
// teeth in mesh deflect, so the next pair closes before it reaches the start of the path and
// the last pair stays closed after its end: the tip corner of one gear touches the mating
// flank off the line of action. This is the rigid separation the load must close there.
#include "dynamics/LoadedMesh.h"

namespace gbx::rt::dyn {

// The separation, along the line of action, of the tip corner from the mating flank when the
// pair stands s from the start of the path (m): s < 0 before it (the wheel's tip corner on
// the pinion's flank, the pinion driving), s > the path's length beyond its end (the pinion's
// tip corner on the wheel's flank); 0 on the path. It grows as s^2 near either end. Infinite
// where the corner no longer faces the mating flank (it lies inside the other's base circle).
double cornerSeparation(const FlankGeometry& g, double s);

} // namespace gbx::rt::dyn
