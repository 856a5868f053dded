#pragma once
// The outputs of a scene's mesh orders (docs/dynamics.md): `harmonic(x, k)`, `level(x[, k])`
// and `level_a(x[, k])`, from the loaded mesh's table or a recorded window of whole mesh
// periods.
#include <map>
#include <vector>

#include "dynamics/Levels.h"
#include "dynamics/Scene.h"

namespace gbx::rt::dyn {

// A table the orders read in place of the recorded window (nullptr: none), over its periods.
struct OrderSource {
  const std::vector<double>* table = nullptr;
  int periods = 1;
};

// One output of signal o.id at fz, the mesh frequency; w is the recorded window of spacing dt.
// `spectra`, when given, keeps each signal's transform for the scene's next order of it.
SceneNumber orderNumber(const ir::SceneOutput& o, OrderSource source, const std::vector<double>& w, double dt,
                        double fz, std::map<cat::Signal, OrderSpectrum>* spectra = nullptr);

} // namespace gbx::rt::dyn
