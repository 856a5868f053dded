#pragma once
// The periodic steady state of a single-mesh scene (docs/dynamics.md): the orbit by harmonic
// balance or by shooting, the record run's confirmation of a linear orbit, and the check that a
// settled transient has died out.
#include <optional>
#include <string>
#include <vector>

#include "dynamics/HarmonicBalance.h"
#include "dynamics/MeshModel.h"
#include "dynamics/SampledOrbit.h"
#include "dynamics/Scene.h"

namespace gbx::rt::dyn {

// The periodic orbit of a single-mesh scene, from the model's initial state or the caller's
// guess, in y; by harmonic balance (its series in `balance`) where the scene asks for it and it
// is found, else by shooting: in fixed steps landing on the samples where the model is smooth
// (its samples in `sampled`), else adaptive. False (with r.failure) where it is not found.
bool steadyOrbit(const MeshModel& model, const MeshScene& ms, TimePlan& tp, const ScenePlan& scene,
                 const SceneOverrides& ov, const Accuracy& acc, SceneResult& r, std::vector<double>& y,
                 std::optional<BalanceOrbit>& balance, std::optional<SampledOrbit>& sampled);

// A linear orbit found in one Newton step, confirmed by the record run (see the definition).
std::string confirmOrbit(Integrator& integ, double t, std::vector<double> y, const std::vector<double>* atPeriod,
                         const System& sys, const Accuracy& acc, SceneResult& r, double Tz);

// `settle = N`: whether the transient has died out, as a warning.
void checkSettled(const MeshModel& model, const TimePlan& tp, const Accuracy& acc, SceneResult& r);

} // namespace gbx::rt::dyn
