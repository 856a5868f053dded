#include "study/Continuation.h"

#include <cmath>
#include <memory>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "dynamics/Scene.h"
#include "model/Deadline.h"
#include "model/Evaluator.h"
#include "model/StageKind.h"
#include "study/BranchEquations.h"
#include "study/Sweep.h"

namespace gbx::rt {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Solves the bordered system: full pivoting for a few unknowns (the shooting equations),
// partial for the many of harmonic balance.
VectorXd solveBordered(const MatrixXd& J, const VectorXd& rhs) {
  if (J.rows() <= 16) return J.fullPivLu().solve(rhs);
  return J.partialPivLu().solve(rhs);
}

// Pseudo-arclength continuation of one scene's periodic response over a sweep, step by step:
// the first orbit found by the equations' own method (shooting or harmonic balance), then
// predictor and corrector along the curve, with turning points found where the equations' fold
// indicator changes and gaps where the branch cannot be followed.
class Continuer {
public:
  Continuer(const Model& model, const Assignment& design, const ir::Study& study, const ScenePlan& sc,
            SweepStudy& result)
      : m(model), a(design), st(study), scene(sc), out(result),
        eq(sc.harmonicBalance ? balanceEquations(model, design, study, sc)
                              : shootingEquations(model, design, study, sc)) {
    double lo = st.lo->toDouble(), hi = st.hi->toDouble(), step = st.step->toDouble();
    dLambda = step / std::fabs(hi - lo);
    ds = dLambda;
    dsMax = 4.0 * dLambda;
    dsMin = 1e-4 * dLambda;
    maxPoints = 40 * static_cast<long>(std::ceil(1.0 / dLambda)) + 400;
    edge = 0.5 * dLambda;
  }

  // False when the scene is linear (a plain sweep serves); throws dyn::SceneFailure.
  bool run() {
    if (!start()) return false;
    follow();
    if (points >= pointBudget())
      throw dyn::SceneFailure{
          fmt::format("the continuation stopped after {} points at {} = {:.6g} {}, before the end of the range", points,
                      st.target, out.unit.shown(eq->x(z(n))), out.unit.name)};
    out.notes.push_back(
        fmt::format("pseudo-arclength continuation of {}: {} points, {} turning point{}, {} gap{}, {} RHS "
                    "evaluations",
                    eq->name(), out.points.size(), out.folds.size(), out.folds.size() == 1 ? "" : "s", out.gaps.size(),
                    out.gaps.size() == 1 ? "" : "s", eq->stats.rhsEvaluations));
    return true;
  }

private:
  // What one predictor-corrector step found.
  struct Step {
    VectorXd zz, tn;
    bool ok = false, turned = false;
    int iterations = 0, aboveThere = 0;
    SweepStudy::Point point;
  };

  const Model& m;
  const Assignment& a;
  const ir::Study& st;
  const ScenePlan& scene;
  SweepStudy& out;
  std::unique_ptr<BranchEquations> eq;
  double dLambda = 0, ds = 0, dsMax = 0, dsMin = 0, edge = 0;
  long maxPoints = 0;
  // The scene's own tolerance sets the corrector's; lambda's difference step balances the
  // integration error against truncation.
  double h = 0, tol = 0;
  long n = 0; // unknowns
  VectorXd z, t, start_, R;
  MatrixXd J;
  int branch = 1;
  bool afterGap = false;
  int aboveHere = 0;
  double reached = 0.0;  // the farthest lambda followed
  double runaway = 0.0;  // a state this large grows without bound (kRunaway times the first's)
  long points = 0;

  void jacobian(const VectorXd& zz, VectorXd& Rz, MatrixXd& Jz) {
    MatrixXd A;
    VectorXd u = zz.head(n);
    Rz = eq->residual(u, zz(n), &A);
    VectorXd Rl = (eq->residual(u, zz(n) + h, nullptr) - Rz) / h;
    Jz.resize(n + 1, n + 1);
    Jz.topLeftCorner(n, n) = A;
    Jz.topRightCorner(n, 1) = Rl;
  }
  // Tangent: [A R_lambda; t_old^T] t = [0; 1], normalised, continuing the old direction.
  VectorXd tangent(MatrixXd Jz, const VectorXd& old) const {
    Jz.bottomRows(1) = old.transpose();
    VectorXd rhs = VectorXd::Zero(n + 1);
    rhs(n) = 1.0;
    VectorXd tt = solveBordered(Jz, rhs);
    return VectorXd(tt / tt.norm());
  }
  int above(const MatrixXd& Jz) const { return eq->foldIndicator(Jz.topLeftCorner(n, n)); }

  // The first point: the periodic orbit at the sweep's start, by plain shooting.
  bool start() {
    std::optional<VectorXd> u = eq->first();
    if (!u) return false;
    n = u->size();
    runaway = BranchEquations::kRunaway * std::max(1.0, u->lpNorm<Eigen::Infinity>());
    z.resize(n + 1);
    z.head(n) = *u;
    z(n) = 0.0;
    h = std::max(1e-7, 30.0 * std::sqrt(eq->rtol)) * dLambda;
    tol = eq->tolerance();
    jacobian(z, R, J);
    start_ = VectorXd::Zero(n + 1);
    start_(n) = 1.0;
    t = tangent(J, start_);
    aboveHere = above(J);
    keep(measure(z));
    points = 1;
    return true;
  }

  // The point at zz: the scene's outputs and stability there (not yet kept).
  SweepStudy::Point measure(const VectorXd& zz) {
    double x = eq->x(zz(n));
    Evaluator ev(m);
    ev.setOverride(st.swept, Value::number(x));
    dyn::SceneOverrides ov;
    ov.evaluator = &ev;
    ov.keepSeries = false;
    ov.estimateError = false;
    ov.keepUnstable = true;
    eq->seed(zz.head(n), zz(n), ov);
    dyn::SceneResult res = dyn::runScene(m, a, scene, ov);
    if (!res.failure.empty()) throw dyn::SceneFailure{res.failure};
    eq->stats += res.stats;
    SweepStudy::Point p;
    p.x = x;
    if (out.points.empty()) resonanceMarks(out, st, x, res.meshFrequency, res.naturalFrequency);
    p.stability = res.stability;
    ev.sceneOutput = [&](const ir::Expr& e, const Assignment& aa, const Evaluator& asking) {
      // At a corner of the tolerance box (`worst`, `mean`) the scene runs again there, from
      // this point's orbit.
      dyn::SceneResult corner;
      const dyn::SceneResult* r = &res;
      if (!asking.offsets().empty()) {
        dyn::SceneOverrides co = ov;
        co.evaluator = &asking;
        co.keepUnstable = false;
        corner = dyn::runScene(m, aa, scene, co);
        r = &corner;
      }
      const dyn::SceneNumber* num = r->find(e.output);
      return num && std::isfinite(num->value) ? Value::number(num->value) : Value::invalid();
    };
    for (const auto& o2 : st.outputs) {
      Value v = ev.eval(*o2, a);
      p.y.push_back(v.isNumber() ? v.mid() : NAN);
      p.unstable.push_back(res.unstable);
    }
    return p;
  }

  void keep(SweepStudy::Point p) {
    p.branch = branch;
    p.afterGap = afterGap;
    afterGap = false;
    out.points.push_back(std::move(p));
  }

  // A step's outputs may change by at most a quarter of their size: more, and the corrector
  // has likely landed on another branch.
  bool smooth(const SweepStudy::Point& p) const {
    if (out.points.empty()) return true;
    const auto& q = out.points.back();
    for (size_t i = 0; i < p.y.size() && i < q.y.size(); ++i) {
      if (!std::isfinite(p.y[i]) || !std::isfinite(q.y[i])) continue;
      double scale = std::max(std::fabs(p.y[i]), std::fabs(q.y[i]));
      if (scale > 0 && std::fabs(p.y[i] - q.y[i]) > 0.25 * scale) return false;
    }
    return true;
  }

  // Where the branch cannot be followed (the step fell below its minimum, or the branch
  // leaves the range at its start), the stretch to the next sweep step past the farthest
  // point followed is a gap; the response there is found afresh by shooting from the last
  // orbit, and followed on as a new branch. False at the end of the range.
  bool gapFrom(const VectorXd& from, const std::string& why,
               BranchEquations::Start how = BranchEquations::Start::Newton) {
    const double start = std::max(from(n), reached);
    double resume = start + dLambda;
    if (resume >= 1.0 - 1e-12) resume = 1.0;
    VectorXd fresh;
    // Where no orbit is found (none of one period there), the next sweep step is tried, to
    // the end of the range; what was found instead is said once for the whole stretch.
    std::string none;
    double noneFrom = resume, noneTo = resume;
    for (;;) {
      try {
        fresh = eq->afresh(from.head(n), resume, how);
        break;
      } catch (const BranchEquations::NoOrbit& f) {
        if (Deadline::expired()) throw;
        if (none.empty()) noneFrom = resume;
        noneTo = resume;
        none = f.what;
      }
      if (resume >= 1.0) {
        out.gaps.emplace_back(eq->x(start), eq->x(1.0));
        out.notes.push_back(fmt::format("gap: {} from {:.6g} {} to the end of the range not followed ({}); no periodic "
                                        "response found from {:.6g} {} on: {}",
                                        st.target, out.unit.shown(eq->x(start)), out.unit.name, why,
                                        out.unit.shown(eq->x(noneFrom)), out.unit.name, none));
        return false;
      }
      resume = std::min(1.0, resume + dLambda);
      if (resume >= 1.0 - 1e-12) resume = 1.0;
    }
    if (!none.empty())
      out.notes.push_back(fmt::format("no periodic response followed at {} from {:.6g} to {:.6g} {}: {}", st.target,
                                      out.unit.shown(eq->x(noneFrom)), out.unit.shown(eq->x(noneTo)), out.unit.name,
                                      none));
    out.gaps.emplace_back(eq->x(start), eq->x(resume));
    out.notes.push_back(
        fmt::format("gap: {} from {:.6g} to {:.6g} {} not followed ({}); the response after it found afresh", st.target,
                    out.unit.shown(eq->x(start)), out.unit.shown(eq->x(resume)), out.unit.name, why));
    z.head(n) = fresh;
    z(n) = resume;
    reached = resume;
    ++branch;
    afterGap = true;
    keep(measure(z));
    ++points;
    if (resume >= 1.0) return false;
    jacobian(z, R, J);
    aboveHere = above(J);
    t = tangent(J, start_);
    ds = dLambda;
    return true;
  }

  // One predictor-corrector step of length ds from z. A corrector that lands far from its
  // predictor, or turns the branch sharply, may have jumped to another branch: not ok.
  // Newton from the predictor onto the branch, on the plane through it normal to t.
  bool corrector(VectorXd& zz, const VectorXd& pred, int& iterations) {
    zz = pred;
    for (; iterations < 8; ++iterations) {
      jacobian(zz, R, J);
      J.bottomRows(1) = t.transpose();
      VectorXd rhs(n + 1);
      rhs.head(n) = -R;
      rhs(n) = -t.dot(zz - pred);
      VectorXd d = solveBordered(J, rhs);
      zz += d;
      if (!std::isfinite(d.norm()) || zz(n) < -edge || zz(n) > 1.0 + stepCap() + edge) return false;
      if (d.lpNorm<Eigen::Infinity>() < tol) return true;
    }
    return false;
  }

  Step step() {
    Step r;
    VectorXd pred = z + ds * t;
    r.ok = corrector(r.zz, pred, r.iterations);
    r.aboveThere = aboveHere;
    if (r.ok) r.ok = (r.zz - pred).norm() <= 0.5 * ds + tol;
    if (r.ok) {
      jacobian(r.zz, R, J);
      r.tn = tangent(J, t);
      r.ok = t.dot(r.tn) >= 0.8;
    }
    if (r.ok && (r.tn(n) > 0) != (t(n) > 0)) {
      r.aboveThere = above(J);
      r.turned = r.aboveThere != aboveHere;
      r.ok = r.turned;  // a reversal without a multiplier crossing +1 is an error of the step
    }
    if (r.ok && r.zz(n) <= 1.0 + 1e-12 && r.zz(n) >= 0.0) {
      try {
        r.point = measure(r.zz);
        r.ok = smooth(r.point) || ds <= 4 * dsMin;
      } catch (const dyn::SceneFailure&) {
        // The scene's own Newton did not settle from this point (next to a turning point, where
        // the orbit is ill-conditioned): a shorter step, or a gap past it. Not past the time limit.
        if (Deadline::expired()) throw;
        r.ok = false;
      }
    }
    return r;
  }

  // Points for the range, and more for each turning point found (a resonance crossed by its
  // folds takes small steps around each).
  long pointBudget() const { return maxPoints + 400 * static_cast<long>(out.folds.size()); }

  // The longest step: one sweep step along the swept quantity (the curve drawn at the sweep's
  // resolution). Where the branch climbs steeply (a large response changing fast with the
  // speed) a step bounded in the whole norm would advance the speed by a sliver of it and the
  // points would run out before the range does; the state's part may then take up to four
  // thousand sweep steps, the smoothness check and the corrector guarding against a jump to
  // another branch.
  double stepCap() const { return dLambda / std::max(std::fabs(t(n)), 2.5e-4); }

  // The turning point between z and zz, to a small part of the step whatever its length: the
  // arc from z is bisected where the branch's tangent turns back in lambda; the quadratic
  // below where a corrector fails.
  double foldBetween(const VectorXd& zz) {
    double lo = 0, hi = ds, at = fold(zz);
    VectorXd keepR = R;
    MatrixXd keepJ = J;
    for (int i = 0; i < 12 && hi - lo > 1e-3 * ds; ++i) {
      double mid = 0.5 * (lo + hi);
      VectorXd q;
      int its = 0;
      if (!corrector(q, z + mid * t, its)) break;
      jacobian(q, R, J);
      VectorXd tq = tangent(J, t);
      ((tq(n) > 0) == (t(n) > 0) ? lo : hi) = mid;
      at = q(n);
    }
    R = keepR;
    J = keepJ;
    return at;
  }

  // The turning point between z and zz: where lambda(s), the quadratic through lambda and its
  // slope at z and lambda at zz, is extreme.
  double fold(const VectorXd& zz) const {
    double lz = z(n), lzz = zz(n), slope = t(n);
    double c = (lzz - lz - slope * ds) / (ds * ds);
    double sStar = c != 0 ? -slope / (2 * c) : -1;
    return sStar >= 0 && sStar <= ds ? lz - slope * slope / (4 * c) : (slope > 0 ? std::max(lz, lzz) : std::min(lz, lzz));
  }

  void follow() {
    while (points < pointBudget()) {
      Step r = step();
      if (!r.ok) {
        ds *= 0.5;
        if (ds < dsMin && !gapFrom(z, "the step fell below 1e-4 of the sweep step")) break;
        continue;
      }
      if (r.turned) {
        out.folds.push_back(eq->x(foldBetween(r.zz)));
        ++branch;
      }
      if (r.zz(n) < 0.0) {
        // The branch turns back out of the range at its start: the rest of the range lies
        // beyond the farthest turning point.
        if (!gapFrom(z, "the branch turned back out of the range at its start")) break;
        continue;
      }
      if (r.zz(n) > 1.0 + 1e-12) {
        // Leaving the range: the last point at its end, from the state interpolated there
        // (the scene's own Newton solves it exactly).
        double end = 1.0, w = (end - z(n)) / (r.zz(n) - z(n));
        VectorXd last = z + w * (r.zz - z);
        last(n) = end;
        keep(measure(last));
        break;
      }
      if (r.zz.head(n).lpNorm<Eigen::Infinity>() > runaway) {
        // A branch climbing without bound (a mesh in contact whose instability backlash no
        // longer limits at such amplitudes): not followed further; the response past it is
        // found afresh, settled from rest.
        out.notes.push_back(fmt::format("the branch grows without bound towards {} = {:.6g} {}: its state passed {:g} "
                                        "times the first point's and was not followed further",
                                        st.target, out.unit.shown(eq->x(r.zz(n))), out.unit.name,
                                        BranchEquations::kRunaway));
        if (!gapFrom(z, "the response grows without bound", BranchEquations::Start::SettleFromRest)) break;
        continue;
      }
      z = r.zz;
      t = r.tn;
      aboveHere = r.aboveThere;
      reached = std::max(reached, z(n));
      keep(std::move(r.point));
      ++points;
      ds = std::min(stepCap(), r.iterations <= 2 ? 1.5 * ds : ds);
    }
  }
};

} // namespace

bool continuation(const Model& m, const Assignment& a, const ir::Study& st, const ScenePlan& scene, SweepStudy& out) {
  if (scene.stage < 0 || m.info(scene.stage).kind->scene != SceneModel::SingleMesh) {
    out.failure = fmt::format("study `{}`: `continuation = arclength` follows the periodic response of a scene on a spur or helical "
                              "stage; scene `{}` is not one (use a plain sweep)",
                              st.name, scene.name);
    return true;
  }
  try {
    return Continuer(m, a, st, scene, out).run();
  } catch (const dyn::SceneFailure& f) {
    out.failure = fmt::format("study `{}`: scene `{}`: {}", st.name, scene.name, f.what);
  }
  return true;
}

} // namespace gbx::rt
