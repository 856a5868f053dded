#include "dynamics/LoadedMesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "dynamics/CornerContact.h"
#include "model/Deadline.h"
#include "model/Recent.h"

namespace gbx::rt::dyn {

double singlePairShape(double xi) { return 0.7 + 1.2 * xi * (1.0 - xi); }

namespace {

// The initial separation of a contact point, split as the profile's part (a function of
// the roll position s along the path) plus the lead's (a function of y across the face),
// with the divisions taken once.
struct Separation {
  double path, tipStart0, tipSlope0, tipEnd1, tipSlope1, pitchSlope, form, twoOverPath;

  Separation(const FlankSeparations& sep, double path, double p) : path(path) {
    tipStart0 = sep.reliefLength[0] > 0 ? path - sep.reliefLength[0] : INFINITY;
    tipSlope0 = sep.reliefLength[0] > 0 ? sep.tipRelief[0] / sep.reliefLength[0] : 0.0;
    tipEnd1 = sep.reliefLength[1] > 0 ? sep.reliefLength[1] : -INFINITY;
    tipSlope1 = sep.reliefLength[1] > 0 ? sep.tipRelief[1] / sep.reliefLength[1] : 0.0;
    pitchSlope = sep.basePitch / p;
    form = sep.profileForm;
    twoOverPath = 2.0 / path;
  }
  double profile(double s) const {
    double gap = pitchSlope * (s - 0.5 * path);
    if (s > tipStart0) gap += tipSlope0 * (s - tipStart0);
    if (s < tipEnd1) gap += tipSlope1 * (tipEnd1 - s);
    double w = twoOverPath * s - 1.0;
    return gap - form * w * w;
  }
  static double lead(const FlankSeparations& sep, double y, double b) {
    double u = 2.0 * y / b - 1.0;
    double gap = sep.leadCrowning * u * u + sep.leadSlope * 0.5 * u;
    if (sep.endReliefWidth > 0) {
      double w = sep.endReliefWidth;
      gap += sep.endRelief * (std::max(0.0, w - y) + std::max(0.0, y - (b - w))) / w;
    }
    if (size_t n = sep.leadProfile.size(); n == 1) {
      gap += sep.leadProfile[0];
    } else if (n > 1) {
      double t = std::clamp(y / b, 0.0, 1.0) * static_cast<double>(n - 1);
      size_t i = std::min(static_cast<size_t>(t), n - 2);
      gap += sep.leadProfile[i] + (t - static_cast<double>(i)) * (sep.leadProfile[i + 1] - sep.leadProfile[i]);
    }
    return gap;
  }
};

// The pairs in contact at one mesh position: their separations and stiffnesses side by side,
// in arrays sized once for the most pairs a position can hold.
struct Contacts {
  std::vector<double> gap, c;
  std::vector<int> slice;
  std::vector<char> corner; // the pair touches outside the path, at a tip corner
  size_t n = 0;
  explicit Contacts(size_t most) : gap(most), c(most), slice(most), corner(most) {}
};

// The approach delta at which F(delta) = sum c max(0, delta - gap) carries the load. F is
// convex, piecewise linear and increasing, so Newton's step from any delta with a pair in
// contact lands at or beyond the root and from there descends to it; it ends when the pairs
// in contact stop changing, which is the exact root of the piecewise-linear equation.
// Starting from the last position's root takes two passes as a rule (one to find the
// pairs, one to see them unchanged).
struct Approach {
  double delta, K;
  bool settled = true;
};
Approach approach(const Contacts& pts, double load, double start) {
  size_t n = pts.n;
  const double* gap = pts.gap.data();
  const double* c = pts.c.data();
  auto pass = [&](double d, size_t& count, double& K) {
    double KG = 0;
    K = 0;
    count = 0;
    for (size_t i = 0; i < n; ++i) {
      bool in = gap[i] < d;  // no branch: whether a pair touches is data, not control
      double ci = in ? c[i] : 0.0;
      K += ci;
      KG += ci * gap[i];
      count += in;
    }
    return (load + KG) / K;
  };
  size_t count = 0, last = n + 1;
  double K = 0, delta = start;
  for (size_t it = 0; it < 2 * n + 4; ++it) {
    double next = pass(delta, count, K);
    // No pair touches below delta: every pair in contact bounds the root from above.
    if (count == 0) next = pass(INFINITY, count, K);
    else if (count == last) {
      return {next, K};
    }
    last = count;
    delta = next;
  }
  return {delta, K, false};
}

} // namespace

std::vector<double> loadedMeshKey(const LoadedMeshInput& in) {
  const FlankGeometry& g = in.g;
  const FlankSeparations& s = in.sep;
  std::vector<double> k = {g.rb1,
                           g.rb2,
                           g.ra1,
                           g.ra2,
                           g.centerDistance,
                           g.workingPressureAngle,
                           g.basePitch,
                           g.baseHelix,
                           g.faceWidth,
                           s.tipRelief[0],
                           s.tipRelief[1],
                           s.reliefLength[0],
                           s.reliefLength[1],
                           s.leadCrowning,
                           s.leadSlope,
                           s.basePitch,
                           s.profileForm,
                           s.endRelief,
                           s.endReliefWidth,
                           in.singleStiffness,
                           in.load,
                           static_cast<double>(in.slices),
                           static_cast<double>(in.positions),
                           in.sliceLoads ? 1.0 : 0.0,
                           in.cornerContact ? 1.0 : 0.0};
  k.push_back(static_cast<double>(s.leadProfile.size()));
  k.insert(k.end(), s.leadProfile.begin(), s.leadProfile.end());
  for (const auto& v : in.toothLateness) {
    k.push_back(static_cast<double>(v.size()));
    k.insert(k.end(), v.begin(), v.end());
  }
  return k;
}

namespace {
LoadedMeshTable tabulate(const LoadedMeshInput& in);
} // namespace

LoadedMeshTable loadedMesh(const LoadedMeshInput& in) {
  thread_local Recent<std::vector<double>, LoadedMeshTable> recent;
  std::vector<double> key = loadedMeshKey(in);
  // A NaN has no order: such an input is tabulated (and fails) without the cache.
  if (std::any_of(key.begin(), key.end(), [](double v) { return std::isnan(v); })) return tabulate(in);
  if (const LoadedMeshTable* hit = recent.find(key)) return *hit;
  // A table over the hunting period is not kept: a few of them would hold the memory of many.
  if (!in.toothLateness[0].empty() || !in.toothLateness[1].empty()) return tabulate(in);
  return recent.put(std::move(key), tabulate(in));
}

namespace {

// The pairs of every slice at one mesh position, over one mesh period or over the hunting
// period of two gears with tooth errors.
struct Slices {
  const LoadedMeshInput& in;
  Separation sep;
  double p, path, eps, db, cScale, invPath;
  int S;
  std::vector<double> phase, lead; // per slice: its contact lines' phase (fraction of a base pitch) and lead separation
  std::vector<long> whole;         // per slice: the whole base pitches of its stagger (which tooth its lines belong to)
  double ext = 0;                  // how far outside the path a pair is looked at, base pitches
  long z[2] = {1, 1};
  bool errors = false;
  double rigidSum = 0;

  Slices(const LoadedMeshInput& in, double path)
      : in(in), sep(in.sep, path, in.g.basePitch), p(in.g.basePitch), path(path) {
    const FlankGeometry& g = in.g;
    double b = g.faceWidth, shift = std::tan(g.baseHelix);
    eps = path / p;
    S = std::max(1, in.slices);
    db = b / S;
    cScale = in.singleStiffness * db;
    invPath = 1.0 / path;
    phase.resize(static_cast<size_t>(S));
    lead.resize(static_cast<size_t>(S));
    whole.resize(static_cast<size_t>(S));
    for (int j = 0; j < S; ++j) {
      double y = (j + 0.5) * db;
      double o = y * shift / p;
      whole[static_cast<size_t>(j)] = static_cast<long>(std::floor(o));
      phase[static_cast<size_t>(j)] = o - std::floor(o);
      lead[static_cast<size_t>(j)] = Separation::lead(in.sep, y, b);
    }
    errors = !in.toothLateness[0].empty() || !in.toothLateness[1].empty();
    for (int k = 0; k < 2; ++k)
      z[k] = std::max<long>(1, static_cast<long>(in.toothLateness[k].size()));
    if (in.cornerContact) ext = 1.0;
  }
  // A pair outside the path: its separation where it stands (the profile's at the path's
  // end, the base pitch deviation's slope carried on) plus the corner's.
  double outside(double s) const {
    double end = std::clamp(s, 0.0, path);
    return sep.profile(end) + sep.pitchSlope * (s - end) + cornerSeparation(in.g, s);
  }
  // The errors of the pair whose tooth count from the start is N (later teeth larger).
  double toothError(long N) const {
    if (!errors) return 0.0;
    auto at = [&](int k) {
      const auto& v = in.toothLateness[k];
      if (v.empty()) return 0.0;
      long i = N % z[k];
      return v[static_cast<size_t>(i < 0 ? i + z[k] : i)];
    };
    return at(0) - at(1);
  }
  // The pairs of one position as every period has them, the tooth errors aside: `offset` is
  // the pair's tooth count from the start less the period's number.
  struct Pair {
    double gap, c;
    int slice;
    bool corner;
    long offset;
  };
  // Every position's pairs, built in the first period, one after another in a buffer the
  // thread keeps (a table is built thousands of times in a search: no allocation each time).
  std::vector<Pair>& templates = scratch();
  std::vector<size_t> templateFrom;  // per position, where its pairs start in `templates`
  std::vector<double> templateRigid; // per position, the stiffness of the pairs on the path
  static std::vector<Pair>& scratch() {
    thread_local std::vector<Pair> buffer;
    buffer.clear();
    return buffer;
  }
  // The tooth errors of period n for every offset the pairs have (a division per tooth pair
  // met, not per pair and position).
  long lowest = 0, highest = 0, errorsOf = -1;
  std::vector<double> errorAt;
  double errorFor(long n, long offset) {
    if (n == 0) return toothError(offset);
    if (errorsOf != n) {
      errorAt.resize(static_cast<size_t>(highest - lowest + 1));
      for (long k = lowest; k <= highest; ++k)
        errorAt[static_cast<size_t>(k - lowest)] = toothError(n + k);
      errorsOf = n;
    }
    return errorAt[static_cast<size_t>(offset - lowest)];
  }

  void build(int i, int P, std::vector<Pair>& out, double& rigid) {
    double tau = static_cast<double>(i) / P;
    for (int j = 0; j < S; ++j) {
      const size_t js = static_cast<size_t>(j);
      // The slice's first pair lies at (tau - phase) mod 1 base pitches along the path.
      double t0 = tau - phase[js];
      long base = -whole[js];
      if (t0 < 0) {
        t0 += 1.0;
        base -= 1;
      }
      if (t0 >= 1.0) { // just below 0 and rounded up to 1: the pair is coming in
        t0 = 0.0;
        base += 1;
      }
      // Each pair touches over [0, eps_alpha) base pitches (to within a billionth of one):
      // where one pair leaves as the next comes in (a whole contact ratio), a position
      // counts one of them, not both. Outside, within ext of either end, at its corner.
      long m = ext > 0 ? -1 : 0;
      for (double t = t0 - (ext > 0 ? 1.0 : 0.0); t < eps + ext - 1e-9; t += 1.0, ++m) {
        double s = t * p;
        bool onPath = t >= 0 && t < eps - 1e-9;
        if (!onPath && (t < -ext || !in.cornerContact)) continue;
        double c = cScale * singlePairShape(std::clamp(s * invPath, 0.0, 1.0));
        double gap = onPath ? sep.profile(s) : outside(s);
        if (!std::isfinite(gap)) continue;
        out.push_back({gap + lead[js], c, j, !onPath, base - m});
        lowest = std::min(lowest, base - m);
        highest = std::max(highest, base - m);
        if (onPath) rigid += c;
      }
    }
  }

  // Every pair of every slice at mesh position i of period n.
  size_t collect(long n, int i, int P, Contacts& pts) {
    const size_t ip = static_cast<size_t>(i);
    if (templateFrom.empty()) {
      templateFrom.assign(static_cast<size_t>(P) + 1, 0);
      templateRigid.assign(static_cast<size_t>(P), 0.0);
    }
    if (n == 0) { // positions are built in order, each once
      templateFrom[ip] = templates.size();
      build(i, P, templates, templateRigid[ip]);
      templateFrom[ip + 1] = templates.size();
    }
    size_t count = 0;
    for (size_t k = templateFrom[ip]; k < templateFrom[ip + 1]; ++k) {
      const Pair& q = templates[k];
      pts.gap[count] = q.gap + (errors ? errorFor(n, q.offset) : 0.0);
      pts.c[count] = q.c;
      pts.slice[count] = q.slice;
      pts.corner[count] = q.corner;
      ++count;
    }
    rigidSum += templateRigid[static_cast<size_t>(i)];
    pts.n = count;
    return count;
  }
};

void summarise(LoadedMeshTable& out, double rigidSum) {
  size_t N = out.te.size();
  double sumK = 0, sumT = 0;
  for (size_t i = 0; i < N; ++i) {
    sumK += out.stiffness[i];
    sumT += out.te[i];
  }
  out.meanStiffness = sumK / static_cast<double>(N);
  out.meanTe = sumT / static_cast<double>(N);
  auto [lo, hi] = std::minmax_element(out.te.begin(), out.te.end());
  out.peakToPeakTe = *hi - *lo;
  out.lightLoadStiffness = rigidSum / static_cast<double>(N);
}

LoadedMeshTable tabulate(const LoadedMeshInput& in) {
  LoadedMeshTable out;
  const FlankGeometry& g = in.g;
  double roll1 = std::sqrt(g.ra1 * g.ra1 - g.rb1 * g.rb1), roll2 = std::sqrt(g.ra2 * g.ra2 - g.rb2 * g.rb2);
  double path = roll1 + roll2 - g.centerDistance * std::sin(g.workingPressureAngle);
  out.pathLength = path;
  if (!(path > 0) || !(g.basePitch > 0) || !(g.faceWidth > 0)) {
    out.failure = fmt::format("the flanks have no path of contact (length {:.4g} mm)", path * 1e3);
    return out;
  }
  // The approach is where the pairs in contact carry the load: none without a load.
  if (!(in.load > 0) || !std::isfinite(in.load)) {
    out.failure = fmt::format("the mesh carries no load ({:.4g} N along the line of action): the loaded contact needs a positive "
                              "torque through the stage",
                              in.load);
    return out;
  }
  // The corner's geometry needs the path within the two interference points.
  double L = g.centerDistance * std::sin(g.workingPressureAngle);
  if (in.cornerContact && (roll2 > L || roll1 > L)) {
    out.failure = fmt::format(
        "the path of contact runs past the {}'s interference point (its tip reaches beyond the other's base "
        "circle tangent), where contact outside the path is not modelled; leave out `corner_contact`",
        roll1 > L ? "pinion" : "wheel");
    return out;
  }
  Slices sl(in, path);
  out.epsAlpha = sl.eps;
  out.epsBeta = g.faceWidth * std::tan(g.baseHelix) / g.basePitch;
  int P = std::max(2, in.positions);
  // With tooth errors: every tooth meets every tooth it can, once, over lcm(z1, z2) periods.
  long periods = sl.errors ? std::lcm(sl.z[0], sl.z[1]) : 1;
  out.periods = static_cast<int>(periods);
  // A slice holds at most floor(eps_alpha) + 1 pairs at once, and two corners.
  Contacts pts(static_cast<size_t>(sl.S) * (static_cast<size_t>(sl.eps) + 4));
  if (in.sliceLoads) out.sliceLineLoad.assign(static_cast<size_t>(sl.S), 0.0);
  size_t total = static_cast<size_t>(P) * static_cast<size_t>(periods);
  out.te.reserve(total);
  out.stiffness.reserve(total);
  double delta = NAN;
  for (long n = 0; n < periods; ++n) {
    if (n > 0 && Deadline::expired()) { // the first period is cached and so never cut short
      out.failure = fmt::format("time limit of {:g} s (--time-limit) reached after {} of {} mesh periods",
                                Deadline::seconds(), n, periods);
      return out;
    }
    for (int i = 0; i < P; ++i) {
      size_t count = sl.collect(n, i, P, pts);
      if (count == 0) {
        out.failure = fmt::format("no tooth pair touches at mesh position {}/{} (a contact ratio below 1)", i, P);
        return out;
      }
      Approach a = approach(pts, in.load, std::isnan(delta) ? -INFINITY : delta);
      if (!a.settled) {
        out.failure = fmt::format(
            "the load balance at mesh position {}/{} did not settle (the pairs in contact kept changing)", i, P);
        return out;
      }
      delta = a.delta;
      double cornerLoad = 0;
      for (size_t q = 0; q < count; ++q) {
        if (!(delta > pts.gap[q])) continue;
        double f = pts.c[q] * (delta - pts.gap[q]);
        if (in.sliceLoads)
          out.sliceLineLoad[static_cast<size_t>(pts.slice[q])] += f / (sl.db * static_cast<double>(total));
        if (pts.corner[q]) cornerLoad += f;
      }
      if (cornerLoad > 0) {
        ++out.cornerPositions;
        out.cornerShare = std::max(out.cornerShare, cornerLoad / in.load);
      }
      out.te.push_back(delta);
      out.stiffness.push_back(a.K);
    }
  }
  summarise(out, sl.rigidSum);
  return out;
}
} // namespace

PeriodicSeries periodicSeries(const std::vector<double>& table, int harmonics) {
  PeriodicSeries s;
  size_t P = table.size();
  if (P == 0) return s;
  for (double v : table) s.mean += v;
  s.mean /= static_cast<double>(P);
  int H = std::min<int>(harmonics, static_cast<int>((P - 1) / 2));
  // cos and sin of 2 pi m / P once; harmonic k at position i reads entry k i mod P.
  std::vector<double> cs(P), sn(P);
  for (size_t m = 0; m < P; ++m) {
    double w = 2.0 * M_PI * static_cast<double>(m) / static_cast<double>(P);
    cs[m] = std::cos(w);
    sn[m] = std::sin(w);
  }
  // Four partial sums each, so the additions do not wait on each other.
  std::vector<size_t> idx(P);
  for (int k = 1; k <= H; ++k) {
    size_t m = 0;
    for (size_t i = 0; i < P; ++i) {
      idx[i] = m;
      m += static_cast<size_t>(k);
      if (m >= P) m -= P;
    }
    double a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};
    size_t i = 0;
    for (; i + 4 <= P; i += 4)
      for (size_t q = 0; q < 4; ++q) {
        a[q] += table[i + q] * cs[idx[i + q]];
        b[q] += table[i + q] * sn[idx[i + q]];
      }
    for (size_t q = 0; i < P; ++i, ++q) {
      a[q] += table[i] * cs[idx[i]];
      b[q] += table[i] * sn[idx[i]];
    }
    s.f.a.push_back(2.0 * ((a[0] + a[1]) + (a[2] + a[3])) / static_cast<double>(P));
    s.f.b.push_back(2.0 * ((b[0] + b[1]) + (b[2] + b[3])) / static_cast<double>(P));
  }
  return s;
}

} // namespace gbx::rt::dyn
