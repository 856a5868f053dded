#include "rating/Spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gbx::rt::rating {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEnd = 1e10; // the life curves' last point

// The gear's permissible stresses (without S_min) when it has run n cycles (`perRev` load
// cycles per revolution).
template <class Input, class Rate>
std::pair<double, double> limitsAt(Input in, int gear, double n, double perRev, Rate rate) {
  const auto& g = in.gear[static_cast<size_t>(gear)];
  if (!(g.speed * perRev > 0)) throw std::domain_error("a gear that does not turn has no life curve to rate a load spectrum on");
  in.life = n * 2 * kPi / (g.speed * perRev);
  const auto r = rate(in);
  const auto& o = r.gear[static_cast<size_t>(gear)];
  return {o.sigmaHP * in.SHmin, o.sigmaFP * in.SFmin};
}

double damageOf(const SnCurve& c, const std::vector<double>& stress, const std::vector<double>& cycles, double k) {
  double d = 0;
  for (size_t i = 0; i < stress.size(); ++i) {
    if (!(cycles[i] > 0)) continue;
    double n = c.cycles(k * stress[i]);
    if (n <= 0) return INFINITY;
    if (std::isfinite(n)) d += cycles[i] / n;
  }
  return d;
}

// The factor on every stress at which Miner's sum reaches 1: D(k) grows with k, so bisect
// in log k between a factor that leaves every bin below the curve's end and one beyond the
// static strength.
double safetyOf(const SnCurve& c, const std::vector<double>& stress, const std::vector<double>& cycles) {
  double top = 0;
  for (size_t i = 0; i < stress.size(); ++i)
    if (cycles[i] > 0) top = std::max(top, stress[i]);
  if (!(top > 0)) return INFINITY;
  double hi = 2 * c.sStatic / top, lo = 0.5 * c.sEnd / top;
  for (int i = 0; i < 200 && hi / lo > 1 + 1e-13; ++i) {
    double mid = std::sqrt(lo * hi);
    (damageOf(c, stress, cycles, mid) > 1 ? hi : lo) = mid;
  }
  return std::sqrt(lo * hi);
}

} // namespace

double SnCurve::cycles(double stress) const {
  if (stress > sStatic * (1 + 1e-12)) return 0;
  if (stress >= sKnee) {
    if (sStatic <= sKnee) return nKnee;
    return std::exp(std::log(nKnee) - std::log(stress / sKnee) / std::log(sStatic / sKnee) * std::log(nKnee / nStatic));
  }
  if (stress > sEnd && sKnee > sEnd)
    return std::exp(std::log(nKnee) + std::log(sKnee / stress) / std::log(sKnee / sEnd) * std::log(kEnd / nKnee));
  return INFINITY;
}

namespace {

// Miner's rule for a pair of either standard: `rate` rates an input; `perRev` gives each
// gear's load cycles per revolution.
template <class Input, class Rate>
auto miner(const Input& in, const std::vector<SpectrumBin>& bins, Rate rate, const std::array<double, 2>& perRev) {
  using Rating = decltype(rate(in));
  SpectrumOf<Rating> out;
  if (bins.empty()) throw std::domain_error("an empty load spectrum");
  Rating nominal = rate(in);
  for (int g = 0; g < 2; ++g) {
    const double k = perRev[static_cast<size_t>(g)];
    Treatment t = in.gear[static_cast<size_t>(g)].treatment.value_or(in.treatment);
    LifeCurve c = contactCurve(t), b = bendingCurve(t);
    auto [hs, fs0] = limitsAt(in, g, c.nStatic, k, rate);
    auto [hk, fk0] = limitsAt(in, g, c.nKnee, k, rate);
    auto [he, fe] = limitsAt(in, g, kEnd, k, rate);
    auto [hs1, fs] = limitsAt(in, g, b.nStatic, k, rate);
    auto [hk1, fk] = limitsAt(in, g, b.nKnee, k, rate);
    out.contactCurve[static_cast<size_t>(g)] = {c.nStatic, hs, c.nKnee, hk, he};
    out.bendingCurve[static_cast<size_t>(g)] = {b.nStatic, fs, b.nKnee, fk, fe};
  }
  // Each bin's duration in each gear's load cycles: its share of the life.
  std::array<std::vector<double>, 2> n, sH, sF;
  for (const auto& b : bins) {
    Input at = in;
    at.torque1 = b.torqueShare * in.torque1;
    out.bins.push_back(rate(at));
    const Rating& r = out.bins.back();
    for (size_t g = 0; g < 2; ++g) {
      n[g].push_back(b.lifeShare * nominal.gear[g].cycles);
      sH[g].push_back(r.gear[g].sigmaH);
      sF[g].push_back(r.gear[g].sigmaF);
    }
  }
  for (size_t g = 0; g < 2; ++g) {
    out.contact[g] = {damageOf(out.contactCurve[g], sH[g], n[g], 1.0), safetyOf(out.contactCurve[g], sH[g], n[g])};
    if (std::isfinite(nominal.gear[g].SF))
      out.bending[g] = {damageOf(out.bendingCurve[g], sF[g], n[g], 1.0), safetyOf(out.bendingCurve[g], sF[g], n[g])};
  }
  return out;
}

} // namespace

SpectrumRating rateSpectrum(const PairInput& in, const std::vector<SpectrumBin>& bins) {
  return miner(in, bins, [](const PairInput& x) { return rate(x); }, {in.gear[0].cyclesPerRev, in.gear[1].cyclesPerRev});
}

BevelSpectrum rateBevelSpectrum(const BevelInput& in, const std::vector<SpectrumBin>& bins) {
  return miner(in, bins, [](const BevelInput& x) { return rateBevel(x); }, {1.0, 1.0});
}

} // namespace gbx::rt::rating
