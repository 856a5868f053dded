#include "dynamics/OrderOutputs.h"

#include <cmath>

#include <fmt/format.h>

#include "dynamics/SceneSupport.h"

namespace gbx::rt::dyn {

namespace {

// The reference of a level by the signal's kind: ISO 1683's for displacement (1 pm), velocity
// (1 nm/s), acceleration (1 um/s^2) and force (1 uN); one SI unit for any other.
double levelReference(const units::Dim& d) {
  if (d == units::dims::length) return 1e-12;
  if (d == units::dims::velocity) return 1e-9;
  if (d == units::dims::acceleration) return 1e-6;
  if (d == units::dims::force) return 1e-6;
  return 1.0;
}

} // namespace

// `harmonic(x, k)`, `level(x[, k])`, `level_a(x[, k])`: of the loaded mesh's table for the
// static transmission error, else of the recorded window, which spans whole mesh periods.
SceneNumber orderNumber(const ir::SceneOutput& o, OrderSource source, const std::vector<double>& w, double dt,
                        double fz, std::map<cat::Signal, OrderSpectrum>* spectra) {
  units::Dim dim = cat::signalSpec(o.id).dim;
  const std::vector<double>* table = source.table;
  OrderSpectrum sp;
  // One transform per signal, however many of its orders the scene reads.
  if (spectra && spectra->count(o.id)) {
    sp = spectra->at(o.id);
  } else if (table) {
    sp = orderSpectrum(*table, source.periods);
  } else {
    double periods = static_cast<double>(w.size()) * dt * fz;
    if (w.size() < 4 || std::fabs(periods - std::round(periods)) > 1e-6 * periods)
      throw SceneFailure{
          fmt::format("`{}` reads the mesh orders of a recorded window of whole mesh periods; record a whole number of "
                      "`mesh_periods`",
                      o.key())};
    sp = orderSpectrum(w, static_cast<int>(std::lround(periods)));
  }
  if (spectra) spectra->emplace(o.id, sp);
  if (o.order > 0 && static_cast<size_t>(o.order) * static_cast<size_t>(sp.periods) > sp.amplitude.size())
    throw SceneFailure{
        fmt::format("`{}` reads mesh order {}, above the {} its samples resolve ({} per mesh period); take more `{}`",
                    o.key(), o.order, sp.amplitude.size() / static_cast<size_t>(sp.periods),
                    2 * sp.amplitude.size() / static_cast<size_t>(sp.periods), table ? "positions" : "samples")};
  double ref = levelReference(dim);
  double value = NAN;
  switch (o.fn) {
  case cat::SignalFn::Harmonic: value = sp.harmonic(o.order); break;
  case cat::SignalFn::Level: value = o.order > 0 ? levelOf(sp.harmonic(o.order), ref) : sp.total(ref); break;
  case cat::SignalFn::LevelA:
    value = o.order > 0 ? levelOf(sp.harmonic(o.order), ref) + aWeighting(o.order * fz) : sp.total(ref, fz);
    break;
  default: break;
  }
  SceneNumber n{o.key(), value, cat::signalFnSpec(o.fn).decibels ? units::Dim{} : dim, o.fn, o.id};
  n.order = o.order;
  return n;
}

} // namespace gbx::rt::dyn
