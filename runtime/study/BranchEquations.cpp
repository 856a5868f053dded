#include "study/BranchEquations.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "dynamics/HarmonicBalance.h"
#include "dynamics/Periodic.h"
#include "model/Deadline.h"

namespace gbx::rt {

using Eigen::MatrixXd;
using Eigen::VectorXd;

BranchEquations::BranchEquations(const Model& m, const Assignment& a, const ir::Study& st, const ScenePlan& scene)
    : m_(m), a_(a), st_(st), scene_(scene), lo_(st.lo->toDouble()), hi_(st.hi->toDouble()) {}

BranchEquations::At BranchEquations::build(double lambda) const {
  At at;
  at.ev = std::make_unique<Evaluator>(m_);
  at.ev->setOverride(st_.swept, Value::number(x(lambda)));
  dyn::SceneOverrides ov;
  ov.evaluator = at.ev.get();
  at.ms = dyn::meshScene(m_, a_, scene_, ov);
  at.model = std::make_unique<dyn::MeshModel>(at.ms.params, at.ms.effects);
  at.period = at.model->excitationPeriod();
  if (at.period <= 0)
    throw dyn::SceneFailure{"the excitation is not periodic, so there is no periodic response to follow"};
  built_[1] = built_[0];
  built_[0] = {lambda, at.period};
  return at;
}

double BranchEquations::periodAt(double lambda) const {
  for (const auto& [l, period] : built_)
    if (l == lambda) return period;
  return build(lambda).period;
}

std::optional<BranchEquations::At> BranchEquations::atStart() {
  At at = build(0.0);
  if (at.model->linear()) return std::nullopt;
  rtol = at.ms.accuracy.rtol;
  s_ = scale(at);
  return at;
}

std::vector<double> BranchEquations::scale(const At& at) {
  std::vector<double> s = at.model->system().scale;
  s.resize(at.model->system().dim, 1.0);
  return s;
}

dyn::PeriodicOrbit BranchEquations::settledOrbit(const At& at, std::vector<double> y, bool fromRest) {
  const dyn::System& sys = at.model->system();
  const double settled = std::max(1e-7, 10.0 * rtol); // a period's change that counts as settled
  constexpr long kMostPeriods = 1000;
  constexpr size_t kLongest = 8; // the longest repetition looked for, in periods
  auto scaledSize = [&](const std::vector<double>& v) {
    double m = 0;
    for (size_t i = 0; i < v.size(); ++i)
      m = std::max(m, std::fabs(v[i]) / s_[i]);
    return m;
  };
  auto distance = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0;
    for (size_t i = 0; i < a.size(); ++i)
      d = std::max(d, std::fabs(a[i] - b[i]) / s_[i]);
    return d;
  };
  // Growing without bound: past kRunaway times the state at rest (backlash puts that
  // above the scale by the clearance).
  const std::vector<double> rest = at.model->initialState();
  const double runaway = kRunaway * std::max(1.0, scaledSize(rest));
  if (fromRest) y = rest;
  bool atRest = fromRest; // where the settling started
  auto integ = std::make_unique<dyn::Integrator>(sys, at.ms.accuracy);
  std::vector<std::vector<double>> last; // the states at the last kLongest + 1 period starts
  double t = 0, change = INFINITY;
  long k = 0;
  for (; k < kMostPeriods && !(change <= settled); ++k) {
    if (!(scaledSize(y) <= runaway)) {
      // Growing without bound from there: once more from rest, as a run-up would start.
      if (atRest)
        throw NoOrbit{fmt::format("no orbit of one period: settled from rest, the response grows without bound "
                                  "(past {:g} times its state at rest after {} periods)",
                                  kRunaway, k)};
      atRest = true;
      y = rest;
      t = 0;
      k = 0;
      last.clear();
      stats += integ->stats();
      integ = std::make_unique<dyn::Integrator>(sys, at.ms.accuracy);
    }
    std::vector<double> before = y;
    bool ok = integ->advance(t, y, static_cast<double>(k + 1) * at.period, {}, [](double, const double*) {});
    if (!ok) {
      stats += integ->stats();
      if (Deadline::expired()) throw dyn::SceneFailure{integ->error()};
      throw NoOrbit{fmt::format("settling from {} failed: {}", atRest ? "rest" : "the last orbit", integ->error())};
    }
    change = distance(y, before);
    last.push_back(y);
    if (last.size() > kLongest + 1) last.erase(last.begin());
  }
  stats += integ->stats();
  const char* from = atRest ? "rest" : "the last orbit";
  dyn::PeriodicOptions po;
  po.period = at.period;
  dyn::PeriodicOrbit o = dyn::periodicOrbit(sys, at.ms.accuracy, po, y);
  stats += o.stats;
  if (o.converged && (change <= settled || o.stability <= 1.0)) return o;
  if (Deadline::expired()) throw dyn::SceneFailure{o.failure};
  // What the settled response does instead: one period that shooting cannot converge on,
  // a repetition every p periods (and not every one), or none.
  if (change <= 1e3 * settled)
    throw NoOrbit{fmt::format("settled from {} to a response of one period ({} periods), but shooting from it "
                              "failed: {}",
                              from, k, o.failure.empty() ? "its orbit is unstable" : o.failure)};
  for (size_t p = 2; p <= kLongest && p < last.size(); ++p)
    if (distance(last.back(), last[last.size() - 1 - p]) <= 1e3 * settled)
      throw NoOrbit{fmt::format("no orbit of one period: settled from {} for {} periods, the response repeats every "
                                "{} periods (a subharmonic response)",
                                from, k, p)};
  throw NoOrbit{fmt::format("no orbit of one period: settled from {} for {} periods, the response still changes by "
                            "{:.3g} of its scale each period and repeats within none of {} periods (quasi-periodic "
                            "or chaotic)",
                            from, k, change, kLongest)};
}

namespace {

// R(u, lambda) = S^-1 (phi_T(S u) - S u): the state's change over one period, S its scale.
class Shooting final : public BranchEquations {
public:
  using BranchEquations::BranchEquations;

  std::optional<VectorXd> first() override {
    std::optional<At> start = atStart();
    if (!start) return std::nullopt;
    At& at = *start;
    dyn::PeriodicOptions po;
    po.period = at.period;
    dyn::PeriodicOrbit o = dyn::periodicOrbit(at.model->system(), at.ms.accuracy, po, at.model->initialState());
    stats += o.stats;
    if (!o.converged)
      throw dyn::SceneFailure{"the periodic steady state at the sweep's start was not found: " + o.failure};
    return scaled(o.y0);
  }

  VectorXd residual(const VectorXd& u, double lambda, MatrixXd* A) override {
    At at = build(lambda);
    const long n = u.size();
    std::vector<double> y0 = state(u);
    VectorXd R(n);
    if (A) {
      dyn::FlowResult f = dyn::flowWithMonodromy(at.model->system(), at.ms.accuracy, 0.0, at.period, y0, stats);
      if (!f.ok) throw dyn::SceneFailure{f.failure};
      A->resize(n, n);
      for (long i = 0; i < n; ++i) {
        R(i) = (f.y[static_cast<size_t>(i)] - y0[static_cast<size_t>(i)]) / s_[static_cast<size_t>(i)];
        for (long j = 0; j < n; ++j)
          (*A)(i, j) = f.phi(i, j) * s_[static_cast<size_t>(j)] / s_[static_cast<size_t>(i)] - (i == j ? 1.0 : 0.0);
      }
      return R;
    }
    dyn::Integrator integ(at.model->system(), at.ms.accuracy);
    double t = 0;
    std::vector<double> y = y0;
    bool ok = integ.advance(t, y, at.period, {}, [](double, const double*) {});
    stats += integ.stats();
    if (!ok) throw dyn::SceneFailure{integ.error()};
    for (long i = 0; i < n; ++i)
      R(i) = (y[static_cast<size_t>(i)] - y0[static_cast<size_t>(i)]) / s_[static_cast<size_t>(i)];
    return R;
  }

  VectorXd afresh(const VectorXd& u, double lambda, Start start) override {
    At at = build(lambda);
    dyn::PeriodicOptions po;
    po.period = at.period;
    if (start != Start::Newton) return scaled(settledOrbit(at, state(u), start == Start::SettleFromRest).y0);
    dyn::PeriodicOrbit o = dyn::periodicOrbit(at.model->system(), at.ms.accuracy, po, state(u));
    stats += o.stats;
    if (!o.converged) o = settledOrbit(at, state(u), false);
    return scaled(o.y0);
  }

  void seed(const VectorXd& u, double, dyn::SceneOverrides& ov) override { ov.guess = state(u); }

  // Real multipliers above 1: their count changes by one where the branch turns, and not
  // where a step merely reverses by error.
  int foldIndicator(const MatrixXd& A) const override {
    MatrixXd M = A + MatrixXd::Identity(A.rows(), A.cols());
    Eigen::EigenSolver<MatrixXd> es(M, false);
    int c = 0;
    for (long i = 0; i < es.eigenvalues().size(); ++i) {
      auto mu = es.eigenvalues()(i);
      if (std::fabs(mu.imag()) <= 1e-9 * std::max(1.0, std::abs(mu)) && mu.real() > 1.0) ++c;
    }
    return c;
  }

  std::string name() const override { return "the shooting equations"; }

private:
  std::vector<double> state(const VectorXd& u) const {
    std::vector<double> y(static_cast<size_t>(u.size()));
    for (size_t i = 0; i < y.size(); ++i)
      y[i] = s_[i] * u(static_cast<long>(i));
    return y;
  }
  VectorXd scaled(const std::vector<double>& y) const {
    VectorXd u(static_cast<long>(y.size()));
    for (size_t i = 0; i < y.size(); ++i)
      u(static_cast<long>(i)) = y[i] / s_[i];
    return u;
  }
};

// The Galerkin residual of N harmonics. Every kinematic equation y_a' = y_b holds exactly when
// b's coefficients are D a's (D the derivative in the basis), so the unknowns are the other
// states' coefficients, u(h m + i) = c(h, kept_i) / s, and the equations those of the other
// rows, R(h, row) / (w s): half the unknowns of a mechanical model. N is the scene's
// `harmonics`, or chosen at the sweep's start for the corrector's tolerance (doubled from 8);
// it stays fixed along the branch, and every point's scene run solves
// with it (a point whose contact changes between the instants falls back to shooting there,
// as any scene's harmonic balance does).
class Balance final : public BranchEquations {
public:
  using BranchEquations::BranchEquations;

  std::optional<VectorXd> first() override {
    std::optional<At> start = atStart();
    if (!start) return std::nullopt;
    const At& at = *start;
    dyn::BalanceOrbit o = startOrbit(at);
    if (!o.converged)
      throw dyn::SceneFailure{"the periodic steady state at the sweep's start was not found by harmonic balance: " +
                              o.failure};
    N_ = o.harmonics;
    pairs_ = dyn::balanceKinematicPairs(at.model->system(), options(at), o.coeffs);
    const long n = static_cast<long>(s_.size());
    std::vector<bool> rowGone(static_cast<size_t>(n), false), colGone(static_cast<size_t>(n), false);
    for (auto [a, b] : pairs_) {
      rowGone[static_cast<size_t>(a)] = true;
      colGone[static_cast<size_t>(b)] = true;
    }
    for (long a = 0; a < n; ++a) {
      if (!rowGone[static_cast<size_t>(a)]) rows_.push_back(a);
      if (!colGone[static_cast<size_t>(a)]) kept_.push_back(a);
    }
    return scaled(o.coeffs);
  }

  VectorXd residual(const VectorXd& u, double lambda, MatrixXd* A) override {
    At at = build(lambda);
    const long n = static_cast<long>(s_.size()), K = 2L * N_ + 1, m = static_cast<long>(kept_.size());
    const double w = 2.0 * M_PI / at.period;
    MatrixXd J;
    MatrixXd R = dyn::balanceResidual(at.model->system(), options(at), coeffs(u, at.period), A ? &J : nullptr, stats);
    VectorXd r(K * m);
    for (long h = 0; h < K; ++h)
      for (long i = 0; i < m; ++i) {
        long row = rows_[static_cast<size_t>(i)];
        r(h * m + i) = R(h, row) / (w * s_[static_cast<size_t>(row)]);
      }
    // The kinematic rows hold by construction only where y_a' is y_b alone (no term of its own,
    // no drift): anything else is not these equations.
    for (auto [a, b] : pairs_)
      for (long h = 0; h < K; ++h)
        if (!(std::fabs(R(h, a)) <= tolerance() * w * s_[static_cast<size_t>(a)]))
          throw dyn::SceneFailure{"the harmonic balance continuation needs each velocity to be its displacement's rate "
                                  "exactly; this model's is not"};
    if (!A) return r;
    // dR/dc_a plus dR/dc_b D, b's coefficients being D a's; then scaled.
    dyn::KinematicReduction red = dyn::withoutVelocities(J, pairs_, K, n, w);
    *A = std::move(red.jacobian);
    for (long c = 0; c < K * m; ++c)
      for (long i = 0; i < K * m; ++i)
        (*A)(i, c) = (*A)(i, c) * s_[static_cast<size_t>(red.keep[static_cast<size_t>(c)] % n)] /
                     (w * s_[static_cast<size_t>(red.rows[static_cast<size_t>(i)] % n)]);
    return r;
  }

  VectorXd afresh(const VectorXd& u, double lambda, Start start) override {
    At at = build(lambda);
    dyn::BalanceOptions bo = options(at);
    bo.stability = false;
    Eigen::MatrixXd c = coeffs(u, at.period);
    dyn::BalanceOrbit o;
    if (start == Start::Newton) {
      o = dyn::harmonicBalance(at.model->system(), bo, {}, &c);
      stats += o.stats;
    }
    if (!o.converged) {
      // From the settled orbit's samples instead (shooting's), as its series.
      dyn::PeriodicOrbit p = settledOrbit(at, stateAtStart(c), start == Start::SettleFromRest);
      const long M = 4L * N_ + 4;
      std::vector<std::vector<double>> samples;
      dyn::Integrator integ(at.model->system(), at.ms.accuracy);
      std::vector<double> y = p.y0, times;
      for (long i = 0; i < M; ++i)
        times.push_back(at.period * static_cast<double>(i) / static_cast<double>(M));
      double t = 0;
      bool ok = integ.advance(t, y, at.period, times,
                              [&](double, const double* ys) { samples.emplace_back(ys, ys + y.size()); });
      stats += integ.stats();
      if (!ok || samples.size() != static_cast<size_t>(M)) {
        if (Deadline::expired()) throw dyn::SceneFailure{integ.error()};
        throw NoOrbit{"the settled orbit's samples: " + integ.error()};
      }
      Eigen::MatrixXd fromSamples = dyn::seriesOfSamples(samples, {}, N_);
      o = dyn::harmonicBalance(at.model->system(), bo, {}, &fromSamples);
      stats += o.stats;
      if (!o.converged)
        throw NoOrbit{fmt::format("shooting found the settled orbit, but harmonic balance with {} harmonics did not "
                                  "converge from it: {}",
                                  N_, o.failure)};
    }
    return scaled(o.coeffs);
  }

  void seed(const VectorXd& u, double lambda, dyn::SceneOverrides& ov) override {
    start_ = coeffs(u, periodAt(lambda));
    ov.balanceStart = &start_;
    ov.balanceHarmonics = N_;
    ov.harmonicBalance = true;
    ov.guess = stateAtStart(start_);
  }

  // The sign of det(dR/du): one real eigenvalue crosses zero where the branch turns.
  int foldIndicator(const MatrixXd& A) const override {
    Eigen::PartialPivLU<MatrixXd> lu(A);
    double sign = lu.permutationP().determinant();
    for (long i = 0; i < A.rows(); ++i)
      if (lu.matrixLU()(i, i) < 0) sign = -sign;
    return sign < 0 ? 1 : 0;
  }

  std::string name() const override { return fmt::format("the harmonic balance equations ({} harmonics)", N_); }

private:
  int N_ = 0;
  // The state at t = 0 of a series: the sum of its cosine terms.
  std::vector<double> stateAtStart(const Eigen::MatrixXd& c) const {
    std::vector<double> y(s_.size(), 0.0);
    for (long a = 0; a < c.cols(); ++a)
      for (long h = 0; h <= N_; ++h)
        y[static_cast<size_t>(a)] += c(h == 0 ? 0 : 2 * h - 1, a);
    return y;
  }
  std::vector<std::pair<long, long>> pairs_; // kinematic (a, b)
  std::vector<long> rows_, kept_;            // the equations and unknowns' states kept
  Eigen::MatrixXd start_;

  dyn::BalanceOptions options(const At& at) const {
    dyn::BalanceOptions bo;
    bo.period = at.period;
    bo.harmonics = N_;
    bo.floquet = at.ms.accuracy;
    return bo;
  }
  dyn::BalanceOrbit startOrbit(const At& at) {
    dyn::BalanceOptions bo = options(at);
    bo.stability = false;
    if (scene_.balanceHarmonics) {
      bo.harmonics = *scene_.balanceHarmonics;
      dyn::BalanceOrbit o = dyn::harmonicBalance(at.model->system(), bo, at.model->initialState());
      stats += o.stats;
      return o;
    }
    dyn::BalanceOrbit o =
        dyn::harmonicBalanceTo(at.model->system(), bo, tolerance(), at.model->initialState(), 8, 1024);
    stats += o.stats;
    return o;
  }
  // The full coefficients at the period T: the kept states' from u, the velocities' from theirs.
  Eigen::MatrixXd coeffs(const VectorXd& u, double T) const {
    const long n = static_cast<long>(s_.size()), m = static_cast<long>(kept_.size()), K = u.size() / m;
    const double w = 2.0 * M_PI / T;
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(K, n);
    for (long h = 0; h < K; ++h)
      for (long i = 0; i < m; ++i) {
        long a = kept_[static_cast<size_t>(i)];
        c(h, a) = u(h * m + i) * s_[static_cast<size_t>(a)];
      }
    for (auto [a, b] : pairs_)
      for (long j = 1; 2 * j < K; ++j) {
        c(2 * j - 1, b) = j * w * c(2 * j, a);
        c(2 * j, b) = -j * w * c(2 * j - 1, a);
      }
    return c;
  }
  VectorXd scaled(const Eigen::MatrixXd& c) const {
    const long K = c.rows(), m = static_cast<long>(kept_.size());
    VectorXd u(K * m);
    for (long h = 0; h < K; ++h)
      for (long i = 0; i < m; ++i) {
        long a = kept_[static_cast<size_t>(i)];
        u(h * m + i) = c(h, a) / s_[static_cast<size_t>(a)];
      }
    return u;
  }
};

} // namespace

std::unique_ptr<BranchEquations> shootingEquations(const Model& m, const Assignment& a, const ir::Study& st,
                                                   const ScenePlan& scene) {
  return std::make_unique<Shooting>(m, a, st, scene);
}

std::unique_ptr<BranchEquations> balanceEquations(const Model& m, const Assignment& a, const ir::Study& st,
                                                  const ScenePlan& scene) {
  return std::make_unique<Balance>(m, a, st, scene);
}

} // namespace gbx::rt
