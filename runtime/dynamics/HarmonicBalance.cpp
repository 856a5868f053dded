#include "dynamics/HarmonicBalance.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "dynamics/Periodic.h"

namespace gbx::rt::dyn {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The series' values at L instants (synthesis, L x K) and the Galerkin projection back (K x L).
struct Basis {
  int N = 0, L = 0;
  Eigen::MatrixXd phi, proj;
  Eigen::MatrixXd mid, midRate; // the series and its rate over w halfway between the instants (L x K)
  Eigen::MatrixXd cosQ, sinQ;   // cos and sin of 2 pi q k / L, q = 0 .. 2N (rows), over L
};

const Basis& basisFor(int N, int L) {
  thread_local std::vector<std::unique_ptr<Basis>> kept;
  for (const auto& b : kept)
    if (b->N == N && b->L == L) return *b;
  auto b = std::make_unique<Basis>();
  b->N = N;
  b->L = L;
  int K = 2 * N + 1;
  // Every angle is a multiple of pi / L: one table of 2L cosines and sines, indexed exactly.
  std::vector<double> ct(2 * static_cast<size_t>(L)), st(2 * static_cast<size_t>(L));
  for (size_t i = 0; i < ct.size(); ++i) {
    ct[i] = std::cos(M_PI * static_cast<double>(i) / L);
    st[i] = std::sin(M_PI * static_cast<double>(i) / L);
  }
  // Column by column (Eigen's order), the table index stepping by the column's angle mod 2L.
  const size_t wrap = 2 * static_cast<size_t>(L);
  auto column = [&](Eigen::MatrixXd& m, long col, bool sine, size_t first, size_t step, double factor) {
    size_t i = first % wrap;
    for (long k = 0; k < m.rows(); ++k) {
      m(k, col) = factor * (sine ? st[i] : ct[i]);
      i += step;
      if (i >= wrap) i -= wrap;
    }
  };
  b->phi.resize(L, K);
  b->mid.resize(L, K);
  b->midRate.resize(L, K);
  b->phi.col(0).setOnes();
  b->mid.col(0).setOnes();
  b->midRate.col(0).setZero();
  for (long j = 1; j <= N; ++j) {
    size_t step = static_cast<size_t>(2 * j) % wrap, half = static_cast<size_t>(j) % wrap; // at k: 2jk, j(2k + 1)
    double dj = static_cast<double>(j);
    column(b->phi, 2 * j - 1, false, 0, step, 1.0);
    column(b->phi, 2 * j, true, 0, step, 1.0);
    column(b->mid, 2 * j - 1, false, half, step, 1.0);
    column(b->mid, 2 * j, true, half, step, 1.0);
    column(b->midRate, 2 * j - 1, true, half, step, -dj);
    column(b->midRate, 2 * j, false, half, step, dj);
  }
  // (2N + 1) x L: row q at instant k is the angle 2qk; built transposed, column by column.
  Eigen::MatrixXd cq(L, K), sq(L, K);
  for (long q = 0; q < K; ++q) {
    size_t step = static_cast<size_t>(2 * q) % wrap;
    column(cq, q, false, 0, step, 1.0 / L);
    column(sq, q, true, 0, step, 1.0 / L);
  }
  b->cosQ = cq.transpose();
  b->sinQ = sq.transpose();
  b->proj = b->phi.transpose() * (2.0 / L);
  b->proj.row(0) *= 0.5;
  // At most 8 bases and about 32 MB a thread (a basis of N = 256 is 20 MB): the oldest go first.
  // Callers hold a basis only while nothing asks for another (N, L).
  auto bytes = [](const Basis& x) {
    return 8 * (x.phi.size() + x.proj.size() + x.mid.size() + x.midRate.size() + x.cosQ.size() + x.sinQ.size());
  };
  size_t total = bytes(*b);
  for (const auto& x : kept)
    total += bytes(*x);
  while (!kept.empty() && (kept.size() >= 8 || total > (size_t{32} << 20))) {
    total -= bytes(*kept.front());
    kept.erase(kept.begin());
  }
  kept.push_back(std::move(b));
  return *kept.back();
}

int timePointsFor(int N, int given) {
  if (given >= 2 * N + 1) return given;
  int L = 4;
  while (L < 3 * N + 2)
    L *= 2;
  return L;
}

// One pass over the L instants: the right-hand side F (L x n) and, when asked, each
// instant's state Jacobian (row-major n x n, one after another).
struct Sampled {
  RowMatrix Y, F;
  std::vector<double> J;
};

void sample(const System& sys, const Basis& B, const BalanceOrbit& o, bool jacobian, Sampled& s) {
  const size_t n = sys.dim;
  const int L = B.L;
  s.Y.noalias() = B.phi * o.coeffs;
  s.F.resize(L, static_cast<long>(n));
  if (jacobian) s.J.resize(static_cast<size_t>(L) * n * n);
  std::vector<double> dy(n), yp(n), fp(n);
  for (int k = 0; k < L; ++k) {
    double t = o.period * k / L;
    double* y = s.Y.row(k).data();
    for (size_t a = 0; a < n && a < o.drift.size(); ++a)
      y[a] += o.drift[a] * k / L;
    double* f = s.F.row(k).data();
    if (!jacobian) {
      sys.rhs(t, y, f);
      continue;
    }
    double* J = s.J.data() + static_cast<size_t>(k) * n * n;
    if (sys.rhsDfdy) {
      sys.rhsDfdy(t, y, f, J);
    } else if (sys.dfdy) {
      sys.rhs(t, y, f);
      sys.dfdy(t, y, J);
    } else { // central differences, column by column
      sys.rhs(t, y, f);
      for (size_t b = 0; b < n; ++b) {
        double h = 1e-7 * std::max(std::fabs(y[b]), 1e-3);
        std::copy(y, y + n, yp.begin());
        yp[b] = y[b] + h;
        sys.rhs(t, yp.data(), fp.data());
        yp[b] = y[b] - h;
        sys.rhs(t, yp.data(), dy.data());
        for (size_t a = 0; a < n; ++a)
          J[a * n + b] = (fp[a] - dy[a]) / (2 * h);
      }
    }
  }
}

// R = D c - P f (+ the drift's constant rate), K x n.
Eigen::MatrixXd residual(const Basis& B, const BalanceOrbit& o, const Sampled& s) {
  double w = 2.0 * M_PI / o.period;
  Eigen::MatrixXd R = -(B.proj * s.F);
  for (int j = 1; j <= B.N; ++j) {
    R.row(2 * j - 1) += (j * w) * o.coeffs.row(2 * j);
    R.row(2 * j) -= (j * w) * o.coeffs.row(2 * j - 1);
  }
  for (long a = 0; a < R.cols() && a < static_cast<long>(o.drift.size()); ++a)
    R(0, a) += o.drift[static_cast<size_t>(a)] / o.period;
  return R;
}

// dR/dc, unknowns ordered harmonic by harmonic (h n + a): D (x) I - sum_k P_k Phi_k (x) J_k.
// The block of one Jacobian entry, P diag(w) Phi, holds only the discrete Fourier sums of w
// at the orders |j - m| and j + m (products of cosines and sines): 2N + 1 sums of L terms
// each, then the K x K entries from them.
Eigen::MatrixXd jacobianOf(const Basis& B, size_t n, double period, const Sampled& s) {
  const long K = 2 * B.N + 1, nn = static_cast<long>(n);
  const int L = B.L, Q = 2 * B.N;
  Eigen::MatrixXd Jac = Eigen::MatrixXd::Zero(K * nn, K * nn);
  Eigen::VectorXd C(Q + 1), S(Q + 1), w(L);
  auto c = [&](long q) { return C(std::labs(q)); };
  auto sn = [&](long q) { return q >= 0 ? S(q) : -S(-q); };
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b) {
      bool any = false, constant = true;
      for (int k = 0; k < L; ++k) {
        w(k) = s.J[static_cast<size_t>(k) * n * n + a * n + b];
        any = any || w(k) != 0.0;
        constant = constant && w(k) == w(0);
      }
      if (!any) continue; // no coupling from b to a (most of a mechanical system's pairs)
      if (constant) {     // a kinematic or constant coefficient: its mean alone
        C.setZero();
        S.setZero();
        C(0) = w(0);
      } else {
        C.noalias() = B.cosQ * w;
        S.noalias() = B.sinQ * w;
      }
      auto at = [&](long h, long m) -> double& {
        return Jac(h * nn + static_cast<long>(a), m * nn + static_cast<long>(b));
      };
      at(0, 0) = -c(0);
      for (long m = 1; m <= B.N; ++m) {
        at(0, 2 * m - 1) = -c(m);
        at(0, 2 * m) = -sn(m);
        at(2 * m - 1, 0) = -2 * c(m);
        at(2 * m, 0) = -2 * sn(m);
      }
      for (long j = 1; j <= B.N; ++j)
        for (long m = 1; m <= B.N; ++m) {
          at(2 * j - 1, 2 * m - 1) = -(c(j - m) + c(j + m));
          at(2 * j - 1, 2 * m) = -(sn(m + j) + sn(m - j));
          at(2 * j, 2 * m - 1) = -(sn(j + m) + sn(j - m));
          at(2 * j, 2 * m) = -(c(j - m) - c(j + m));
        }
    }
  double omega = 2.0 * M_PI / period;
  for (long j = 1; j <= B.N; ++j)
    for (long a = 0; a < nn; ++a) {
      Jac((2 * j - 1) * nn + a, 2 * j * nn + a) += j * omega;
      Jac(2 * j * nn + a, (2 * j - 1) * nn + a) -= j * omega;
    }
  return Jac;
}

// The kinematic equations y_a' = y_b (a displacement and its velocity): where every instant's
// Jacobian row a is exactly the unit row of b, the Newton step's block of b follows from a's,
// d_b = D d_a + R_a, so b's unknowns leave the linear system (a mechanical model's velocities:
// half the unknowns, an eighth of the factorisation). Pairs (a, b); b never a kinematic row.
std::vector<std::pair<long, long>> kinematicPairs(size_t n, int L, const Sampled& s) {
  std::vector<long> target(n, -1);
  for (size_t a = 0; a < n; ++a) {
    long b = -1;
    bool unit = true;
    for (int k = 0; k < L && unit; ++k) { // exactly one entry, 1, in the same column at every instant
      const double* row = s.J.data() + (static_cast<size_t>(k) * n + a) * n;
      int ones = 0;
      for (size_t c = 0; c < n && unit; ++c) {
        if (row[c] == 0.0) continue;
        if (row[c] != 1.0 || c == a || (b >= 0 && b != static_cast<long>(c))) unit = false;
        b = static_cast<long>(c);
        ++ones;
      }
      unit = unit && ones == 1;
    }
    if (unit && b >= 0) target[a] = b;
  }
  std::vector<std::pair<long, long>> pairs;
  std::vector<bool> used(n, false);
  for (size_t a = 0; a < n; ++a) {
    long b = target[a];
    if (b < 0 || target[static_cast<size_t>(b)] >= 0 || used[static_cast<size_t>(b)]) continue;
    used[static_cast<size_t>(b)] = true;
    pairs.emplace_back(static_cast<long>(a), b);
  }
  return pairs;
}

// Solves Jac d = rhs (unknowns h n + a) with the kinematic pairs' velocities eliminated;
// false where the reduced system is singular.
bool reducedSolve(const Eigen::MatrixXd& Jac, const Eigen::VectorXd& rhs,
                  const std::vector<std::pair<long, long>>& pairs, long K, long nn, double omega, Eigen::VectorXd& d) {
  // Jac's row block a is D on a and -I on b, so d_b = D d_a - rhs_a.
  KinematicReduction red = withoutVelocities(Jac, pairs, K, nn, omega);
  const std::vector<long>&rows = red.rows, &keep = red.keep;
  const Eigen::MatrixXd& Jr = red.jacobian;
  const long m = static_cast<long>(keep.size());
  Eigen::VectorXd rr(m);
  for (long r = 0; r < m; ++r)
    rr(r) = rhs(rows[static_cast<size_t>(r)]);
  for (auto [a, b] : pairs)
    for (long h = 0; h < K; ++h) { // Jac_{r,b} d_b moved to the right
      double ra = rhs(h * nn + a);
      for (long r = 0; r < m; ++r)
        rr(r) += Jac(rows[static_cast<size_t>(r)], h * nn + b) * ra;
    }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(Jr);
  Eigen::VectorXd dr = lu.solve(rr);
  if (!dr.allFinite() || (Jr * dr - rr).norm() > 1e-6 * rr.norm()) return false;
  d.setZero(K * nn);
  for (long r = 0; r < m; ++r)
    d(keep[static_cast<size_t>(r)]) = dr(r);
  for (auto [a, b] : pairs)
    for (long h = 0; h < K; ++h) {
      double Dd = 0;
      if (h > 0) {
        long j = (h + 1) / 2;
        Dd = h % 2 == 1 ? j * omega * d((h + 1) * nn + a) : -j * omega * d((h - 1) * nn + a);
      }
      d(h * nn + b) = Dd - rhs(h * nn + a);
    }
  // The whole system too: a row taken for kinematic that is not falls back to the full solve.
  return (Jac * d - rhs).norm() <= 1e-6 * rhs.norm();
}

// Hill's method: the eigenvalues of the linearised operator J(t) - d/dt in the truncated basis
// come in families lambda + i k w; the n nearest the real axis are the Floquet exponents. Their
// sum must be the mean trace of J over the period (Liouville); where the truncation blurs the
// families so that it is not, false (the caller integrates the variational equations instead).
bool hill(const Eigen::MatrixXd& Jac, size_t n, double meanTrace, BalanceOrbit& o) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(-Jac, false);
  if (es.info() != Eigen::Success) return false;
  std::vector<std::complex<double>> ev(es.eigenvalues().data(), es.eigenvalues().data() + es.eigenvalues().size());
  std::stable_sort(ev.begin(), ev.end(), [](auto x, auto y) { return std::fabs(x.imag()) < std::fabs(y.imag()); });
  // One exponent per family: members of a family differ by a whole multiple of i w (a
  // period-doubling pair sits at +-w/2 twice).
  const double w = 2.0 * M_PI / o.period;
  std::vector<std::complex<double>> picked;
  for (auto l : ev) {
    if (picked.size() == n) break;
    bool same = std::any_of(picked.begin(), picked.end(), [&](std::complex<double> p) {
      double k = (l.imag() - p.imag()) / w;
      return std::fabs(l.real() - p.real()) <= 1e-6 * (std::fabs(p.real()) + w) && std::fabs(k - std::round(k)) < 1e-3;
    });
    if (!same) picked.push_back(l);
  }
  double sum = 0;
  for (auto l : picked)
    sum += l.real();
  if (picked.size() != n || !(std::fabs(sum - meanTrace) <= 1e-6 * (std::fabs(meanTrace) + w))) return false;
  o.multipliers.clear();
  for (auto l : picked)
    o.multipliers.push_back(std::exp(l * o.period));
  std::stable_sort(o.multipliers.begin(), o.multipliers.end(),
                   [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  o.stability = o.multipliers.empty() ? NAN : std::abs(o.multipliers.front());
  return std::isfinite(o.stability);
}

// The series and its derivative at time t.
void synthesise(const BalanceOrbit& o, double t, double* y, double* dy) {
  const long n = o.coeffs.cols();
  double w = 2.0 * M_PI / o.period;
  std::complex<double> step(std::cos(w * t), std::sin(w * t)), e = step;
  for (long a = 0; a < n; ++a) {
    double d = a < static_cast<long>(o.drift.size()) ? o.drift[static_cast<size_t>(a)] : 0.0;
    y[a] = o.coeffs(0, a) + d * t / o.period;
    if (dy) dy[a] = d / o.period;
  }
  for (int j = 1; j <= o.harmonics; ++j, e *= step)
    for (long a = 0; a < n; ++a) {
      double c = o.coeffs(2 * j - 1, a), s = o.coeffs(2 * j, a);
      y[a] += c * e.real() + s * e.imag();
      if (dy) dy[a] += j * w * (s * e.real() - c * e.imag());
    }
}

// Largest |y' - f| between the samples over the largest |y'| of the same state.
void check(const System& sys, const BalanceOptions& opt, BalanceOrbit& o) {
  const size_t n = sys.dim;
  long M = static_cast<long>(o.timePoints) * std::max(1, opt.checkRefine);
  std::vector<double> y(n), dy(n), f(n), worst(n, 0.0), top(n, 0.0);
  // Halfway between the instants, the basis has the series and its rate as matrices.
  RowMatrix Ym, dYm;
  if (M == o.timePoints) {
    const Basis& B = basisFor(o.harmonics, o.timePoints);
    Ym.noalias() = B.mid * o.coeffs;
    dYm.noalias() = B.midRate * o.coeffs;
    dYm *= 2.0 * M_PI / o.period;
  }
  for (long m = 0; m < M; ++m) {
    double t = o.period * (static_cast<double>(m) + 0.5) / static_cast<double>(M); // between the instants
    if (M == o.timePoints) {
      for (size_t a = 0; a < n; ++a) {
        double d = a < o.drift.size() ? o.drift[a] : 0.0;
        y[a] = Ym(m, static_cast<long>(a)) + d * t / o.period;
        dy[a] = dYm(m, static_cast<long>(a)) + d / o.period;
      }
    } else {
      synthesise(o, t, y.data(), dy.data());
    }
    sys.rhs(t, y.data(), f.data());
    for (size_t a = 0; a < n; ++a) {
      double r = std::fabs(dy[a] - f[a]), d = std::fabs(dy[a]);
      if (!(r <= worst[a])) worst[a] = r; // a NaN stays (std::max would drop it)
      if (!(d <= top[a])) top[a] = d;
    }
  }
  o.stats.rhsEvaluations += M;
  std::vector<double> sc = stateScale(sys);
  double w = 2.0 * M_PI / o.period;
  o.gapResidual = 0;
  for (size_t a = 0; a < n; ++a) {
    double floor = 1e-12 * w * sc[a]; // a state that does not move
    double g = worst[a] / std::max(top[a], floor);
    if (!(g <= o.gapResidual)) o.gapResidual = g;
  }
}

} // namespace

void BalanceOrbit::state(double t, double* y) const { synthesise(*this, t, y, nullptr); }

std::vector<double> BalanceOrbit::state(double t) const {
  std::vector<double> y(static_cast<size_t>(coeffs.cols()));
  state(t, y.data());
  return y;
}

namespace {

// The orbit's Floquet multipliers: Hill's method in a small basis, else (or where Hill's
// exponents do not add up) one period of the variational equations from the orbit's start.
void stabilityOf(const System& sys, const BalanceOptions& opt, BalanceOrbit& o) {
  const size_t n = sys.dim;
  if ((2L * o.harmonics + 1) * static_cast<long>(n) <= opt.hillLimit) {
    const Basis& B = basisFor(o.harmonics, o.timePoints);
    Sampled s;
    sample(sys, B, o, true, s);
    o.stats.rhsEvaluations += o.timePoints;
    o.stats.jacobianEvaluations += o.timePoints;
    double trace = 0;
    for (int k = 0; k < B.L; ++k)
      for (size_t a = 0; a < n; ++a)
        trace += s.J[static_cast<size_t>(k) * n * n + a * n + a];
    if (hill(jacobianOf(B, n, o.period, s), n, trace / B.L, o)) {
      o.stabilityMethod = "Hill's method";
      return;
    }
  }
  FlowResult f = flowWithMonodromy(sys, opt.floquet, 0.0, o.period, o.state(0), o.stats);
  if (f.ok) {
    o.stability = spectralRadius(f.phi, &o.multipliers);
    o.stabilityMethod = "one period of the variational equations";
  } else {
    o.stability = NAN;
    o.stabilityMethod = "not found: " + f.failure;
  }
}

} // namespace

BalanceOrbit harmonicBalance(const System& sys, const BalanceOptions& opt, const std::vector<double>& guess,
                             const Eigen::MatrixXd* start) {
  double cpu0 = threadCpuSeconds();
  BalanceOrbit o;
  const size_t n = sys.dim;
  const int N = std::max(1, opt.harmonics);
  o.harmonics = N;
  o.timePoints = timePointsFor(N, opt.timePoints);
  o.period = opt.period;
  o.drift = opt.drift;
  o.drift.resize(n, 0.0);
  const long K = 2 * N + 1, nn = static_cast<long>(n);
  o.coeffs = Eigen::MatrixXd::Zero(K, nn);
  if (start && start->cols() == nn) {
    long rows = std::min<long>(K, start->rows());
    o.coeffs.topRows(rows) = start->topRows(rows);
  } else {
    for (size_t a = 0; a < n && a < guess.size(); ++a)
      o.coeffs(0, static_cast<long>(a)) = guess[a];
  }
  const Basis& B = basisFor(N, o.timePoints);
  std::vector<double> sc = stateScale(sys);
  const double w = 2.0 * M_PI / opt.period;
  Sampled s;
  Eigen::MatrixXd Jac;
  double lastStep = INFINITY;
  for (int it = 0; it <= opt.maxIterations; ++it) {
    bool needJacobian = !(opt.linear && it > 0);
    sample(sys, B, o, needJacobian, s);
    o.stats.rhsEvaluations += o.timePoints;
    if (needJacobian) o.stats.jacobianEvaluations += o.timePoints;
    Eigen::MatrixXd R = residual(B, o, s);
    o.residual = 0;
    for (long a = 0; a < nn; ++a)
      if (!R.col(a).allFinite())
        o.residual = NAN;
      else
        o.residual = std::max(o.residual, R.col(a).cwiseAbs().maxCoeff() / (w * sc[static_cast<size_t>(a)]));
    if (!std::isfinite(o.residual)) {
      o.failure = "the right-hand side is not finite on the series (a state outside the model's range)";
      break;
    }
    if ((opt.linear && it > 0) || lastStep <= opt.newtonTolerance) {
      // A step that no longer moves with a residual left is a least-squares stall (the
      // teeth apart over the whole period), not an orbit.
      o.converged = opt.linear || o.residual <= std::max(1e-6, 1e3 * opt.newtonTolerance);
      if (!o.converged)
        o.failure = fmt::format(
            "Newton stalled with a residual of {:.3g} of the state scale (from a guess outside the orbit's basin)",
            o.residual);
      break;
    }
    if (it == opt.maxIterations) {
      o.failure = fmt::format("Newton did not converge in {} iterations (last step {:.3g} of the state scale)",
                              opt.maxIterations, lastStep);
      break;
    }
    Jac = jacobianOf(B, n, opt.period, s);
    Eigen::VectorXd rhs(K * nn);
    for (long h = 0; h < K; ++h)
      for (long a = 0; a < nn; ++a)
        rhs(h * nn + a) = -R(h, a);
    Eigen::VectorXd d;
    auto pairs = kinematicPairs(n, B.L, s);
    if (pairs.empty() || !reducedSolve(Jac, rhs, pairs, K, nn, w, d)) {
      d = Eigen::PartialPivLU<Eigen::MatrixXd>(Jac).solve(rhs);
      // A singular step (an iterate that leaves the teeth apart over the whole period, where
      // the mean displacement does not enter): the least-squares step of least norm instead.
      if (!d.allFinite() || (Jac * d - rhs).norm() > 1e-6 * rhs.norm())
        d = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Jac).solve(rhs);
    }
    if (!d.allFinite()) {
      o.failure = "the balance's Jacobian is singular (an orbit that is not isolated: a resonance without damping?)";
      break;
    }
    double sn = 0;
    for (long h = 0; h < K; ++h)
      for (long a = 0; a < nn; ++a)
        sn = std::max(sn, std::fabs(d(h * nn + a)) / sc[static_cast<size_t>(a)]);
    // Never more than ten state scales at once, except a linear system's step, which is exact.
    double damp = sn > 10.0 && !opt.linear ? 10.0 / sn : 1.0;
    for (long h = 0; h < K; ++h)
      for (long a = 0; a < nn; ++a)
        o.coeffs(h, a) += damp * d(h * nn + a);
    lastStep = damp * sn;
    ++o.iterations;
    // Linear: the step is exact; what it leaves is measured between the instants (check), and
    // the Galerkin residual at them is rounding.
    if (opt.linear && damp == 1.0) {
      o.residual = NAN;
      o.converged = true;
      break;
    }
  }
  if (o.converged) {
    check(sys, opt, o);
    if (!(o.gapResidual <= opt.gapLimit)) {
      o.converged = false;
      o.unresolved = true;
      o.failure = fmt::format(
          "the equation's residual between the {} instants of the transform is {:.2g} of the state's rate (a "
          "change the instants step over, such as a brief contact loss): {} harmonics do not resolve the orbit",
          o.timePoints, o.gapResidual, N);
    }
  }
  if (o.converged && opt.stability) stabilityOf(sys, opt, o);
  o.stats.cpuSeconds = threadCpuSeconds() - cpu0;
  return o;
}

KinematicIndices keptIndices(const std::vector<std::pair<long, long>>& pairs, long K, long n) {
  std::vector<bool> rowGone(static_cast<size_t>(n), false), colGone(static_cast<size_t>(n), false);
  for (auto [a, b] : pairs) {
    rowGone[static_cast<size_t>(a)] = true;
    colGone[static_cast<size_t>(b)] = true;
  }
  KinematicIndices k;
  for (long h = 0; h < K; ++h)
    for (long a = 0; a < n; ++a) {
      if (!rowGone[static_cast<size_t>(a)]) k.rows.push_back(h * n + a);
      if (!colGone[static_cast<size_t>(a)]) k.keep.push_back(h * n + a);
    }
  return k;
}

KinematicReduction withoutVelocities(const Eigen::MatrixXd& Jac, const std::vector<std::pair<long, long>>& pairs,
                                     long K, long n, double w) {
  KinematicReduction red;
  static_cast<KinematicIndices&>(red) = keptIndices(pairs, K, n);
  const long m = static_cast<long>(red.keep.size());
  std::vector<long> colOf(static_cast<size_t>(K * n), -1);
  for (long c = 0; c < m; ++c)
    colOf[static_cast<size_t>(red.keep[static_cast<size_t>(c)])] = c;
  Eigen::MatrixXd& Jr = red.jacobian;
  Jr.resize(m, m);
  for (long c = 0; c < m; ++c)
    for (long r = 0; r < m; ++r)
      Jr(r, c) = Jac(red.rows[static_cast<size_t>(r)], red.keep[static_cast<size_t>(c)]);
  // dR/dc_b D: c_b,2j-1 = j w c_a,2j and c_b,2j = -j w c_a,2j-1.
  for (auto [a, b] : pairs)
    for (long h = 1; h < K; ++h) {
      long j = (h + 1) / 2, col = colOf[static_cast<size_t>(h * n + a)];
      long src = h % 2 == 0 ? (h - 1) * n + b : (h + 1) * n + b;
      double factor = h % 2 == 0 ? j * w : -j * w;
      for (long r = 0; r < m; ++r)
        Jr(r, col) += factor * Jac(red.rows[static_cast<size_t>(r)], src);
    }
  return red;
}

namespace {

// The series of coefficients c on opt's period, drift and instants (nothing solved).
BalanceOrbit seriesOf(const System& sys, const BalanceOptions& opt, const Eigen::MatrixXd& coeffs) {
  BalanceOrbit o;
  o.harmonics = static_cast<int>((coeffs.rows() - 1) / 2);
  o.timePoints = timePointsFor(o.harmonics, opt.timePoints);
  o.period = opt.period;
  o.drift = opt.drift;
  o.drift.resize(sys.dim, 0.0);
  o.coeffs = coeffs;
  return o;
}

} // namespace

Eigen::MatrixXd balanceResidual(const System& sys, const BalanceOptions& opt, const Eigen::MatrixXd& coeffs,
                                Eigen::MatrixXd* jacobian, Stats& stats) {
  BalanceOrbit o = seriesOf(sys, opt, coeffs);
  const Basis& B = basisFor(o.harmonics, o.timePoints);
  Sampled s;
  sample(sys, B, o, jacobian != nullptr, s);
  stats.rhsEvaluations += o.timePoints;
  if (jacobian) {
    stats.jacobianEvaluations += o.timePoints;
    *jacobian = jacobianOf(B, sys.dim, opt.period, s);
  }
  return residual(B, o, s);
}

std::vector<std::pair<long, long>> balanceKinematicPairs(const System& sys, const BalanceOptions& opt,
                                                         const Eigen::MatrixXd& coeffs) {
  BalanceOrbit o = seriesOf(sys, opt, coeffs);
  const Basis& B = basisFor(o.harmonics, o.timePoints);
  Sampled s;
  sample(sys, B, o, true, s);
  return kinematicPairs(sys.dim, B.L, s);
}

Eigen::MatrixXd seriesOfSamples(const std::vector<std::vector<double>>& samples, const std::vector<double>& drift,
                                int N) {
  const size_t M = samples.size();
  const long n = M ? static_cast<long>(samples.front().size()) : 0;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2 * N + 1, n);
  for (size_t k = 0; k < M; ++k) {
    double frac = static_cast<double>(k) / static_cast<double>(M);
    for (long a = 0; a < n; ++a) {
      double v = samples[k][static_cast<size_t>(a)] -
                 (static_cast<size_t>(a) < drift.size() ? drift[static_cast<size_t>(a)] * frac : 0.0);
      c(0, a) += v / static_cast<double>(M);
      for (int j = 1; j <= N && 2 * j < static_cast<int>(M); ++j) {
        double th = 2.0 * M_PI * j * frac;
        c(2 * j - 1, a) += 2.0 * v * std::cos(th) / static_cast<double>(M);
        c(2 * j, a) += 2.0 * v * std::sin(th) / static_cast<double>(M);
      }
    }
  }
  return c;
}

BalanceOrbit harmonicBalanceTo(const System& sys, BalanceOptions opt, double target, const std::vector<double>& guess,
                               int first, long maxUnknowns, const Eigen::MatrixXd* start) {
  opt.harmonics = std::max(1, first);
  const bool stability = opt.stability;
  opt.stability = false; // of the last orbit only
  Stats total;
  BalanceOrbit o, last;
  const Eigen::MatrixXd* previous = start;
  Eigen::MatrixXd kept;
  std::vector<double> sc = stateScale(sys);
  for (;;) {
    o = harmonicBalance(sys, opt, guess, previous);
    total += o.stats;
    // The truncation: how far the orbit moved from the one with half the harmonics.
    if (last.converged && o.converged) {
      o.truncation = 0;
      for (int k = 0; k < 4 * o.timePoints; ++k) {
        double t = o.period * k / (4.0 * o.timePoints);
        std::vector<double> a = o.state(t), b = last.state(t);
        for (size_t i = 0; i < a.size(); ++i)
          o.truncation = std::max(o.truncation, std::fabs(a[i] - b[i]) / sc[i]);
      }
    }
    bool met = o.converged && o.truncation <= target;
    long next = (4L * opt.harmonics + 1) * static_cast<long>(sys.dim);
    if (met || next > maxUnknowns) break;
    if (o.converged || o.unresolved) {
      kept = o.coeffs;
      previous = &kept;
    }
    last = o;
    opt.harmonics *= 2;
  }
  // The change measures the error of the orbit with half the harmonics: that one is within
  // the target, with half the unknowns.
  if (o.converged && o.truncation <= target && last.converged) {
    double change = o.truncation;
    o = std::move(last);
    o.truncation = change;
  }
  o.stats = total;
  if (o.converged && stability) {
    opt.stability = true;
    double cpu = threadCpuSeconds();
    Stats before = o.stats;
    stabilityOf(sys, opt, o);
    o.stats.cpuSeconds = before.cpuSeconds + (threadCpuSeconds() - cpu); // the flow's own CPU is inside this
  }
  return o;
}

} // namespace gbx::rt::dyn
