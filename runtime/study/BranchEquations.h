#pragma once
// The equations an arclength continuation follows (study/Continuation.cpp): R(u, lambda) = 0 for
// a scene's periodic orbit at lambda, the swept quantity's position in [lo, hi]. Two kinds, as
// the scene finds its orbit: the shooting equations (u the scaled initial state, R the scaled
// change over one period) and the harmonic balance equations (u the scaled Fourier coefficients
// of every state, R the scaled Galerkin residual).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "dynamics/MeshModel.h"
#include "dynamics/Periodic.h"
#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "model/Model.h"

namespace gbx::rt {

class BranchEquations {
public:
  BranchEquations(const Model& m, const Assignment& a, const ir::Study& st, const ScenePlan& scene);
  virtual ~BranchEquations() = default;

  double x(double lambda) const { return lo_ + lambda * (hi_ - lo_); }

  // The orbit at the sweep's start: its unknowns, or none for a linear scene (no turning points;
  // a plain sweep serves). Throws dyn::SceneFailure.
  virtual std::optional<Eigen::VectorXd> first() = 0;
  // R at (u, lambda); with A, also dR/du.
  virtual Eigen::VectorXd residual(const Eigen::VectorXd& u, double lambda, Eigen::MatrixXd* A) = 0;
  // Where no periodic response is found at a point (none of one period, or none Newton
  // converges on): the continuation goes on past it. Any other SceneFailure stops it.
  struct NoOrbit : dyn::SceneFailure {
    explicit NoOrbit(std::string w) : dyn::SceneFailure{std::move(w)} {}
  };
  // How afresh starts: Newton from u (settling from u where that fails); or settled from u,
  // or from rest, first, where Newton could find an orbit no slow sweep reaches.
  enum class Start { Newton, SettleFromU, SettleFromRest };
  // The orbit at lambda found afresh (past a gap); throws NoOrbit or dyn::SceneFailure.
  virtual Eigen::VectorXd afresh(const Eigen::VectorXd& u, double lambda, Start start = Start::Newton) = 0;
  // What the scene's own run at u starts from; `ov` may keep a pointer into this object until
  // the next call.
  virtual void seed(const Eigen::VectorXd& u, double lambda, dyn::SceneOverrides& ov) = 0;
  // Changes by one where the branch turns: the real Floquet multipliers above 1 (shooting) or
  // the sign of the Jacobian's determinant (harmonic balance).
  virtual int foldIndicator(const Eigen::MatrixXd& A) const = 0;
  // For the study's note: "the shooting equations", "the harmonic balance equations (N harmonics)".
  virtual std::string name() const = 0;

  // A state this many times its size at the sweep's start (or at rest, at least its scale: the
  // static deflection and its rate) is a response growing without bound: a mesh in contact
  // whose instability backlash no longer limits.
  static constexpr double kRunaway = 1e3;
  double rtol = 1e-6; // the scene's; the corrector's tolerance and lambda's difference step follow it
  double tolerance() const { return std::max(1e-9, 100.0 * rtol); } // the corrector's, of the unknowns' scale
  dyn::Stats stats;

protected:
  struct At {
    std::unique_ptr<Evaluator> ev;
    dyn::MeshScene ms;
    std::unique_ptr<dyn::MeshModel> model;
    double period = 0;
  };
  At build(double lambda) const;
  // The excitation's period at lambda: one of the last two scenes built's where it is at the
  // same lambda (a point measured right after its corrector's residual and lambda difference),
  // else built afresh.
  double periodAt(double lambda) const;
  static std::vector<double> scale(const At& at);
  // Past a gap where Newton from the last orbit fails: the response settled from that orbit's
  // state y (or from rest) period by period, as a slow sweep carries it onto the branch that
  // remains, then the orbit by shooting from there. Where the settled response does not
  // repeat every period, throws NoOrbit saying what it does instead.
  dyn::PeriodicOrbit settledOrbit(const At& at, std::vector<double> y, bool fromRest);
  // The scene at the sweep's start, rtol and the state's scales taken from it; none for a
  // linear scene.
  std::optional<At> atStart();

  std::vector<double> s_; // the state's scales

  const Model& m_;
  const Assignment& a_;
  const ir::Study& st_;
  const ScenePlan& scene_;
  double lo_, hi_;

private:
  mutable std::array<std::pair<double, double>, 2> built_{{{NAN, 0.0}, {NAN, 0.0}}}; // (lambda, period), newest first
};

std::unique_ptr<BranchEquations> shootingEquations(const Model& m, const Assignment& a, const ir::Study& st,
                                                   const ScenePlan& scene);
std::unique_ptr<BranchEquations> balanceEquations(const Model& m, const Assignment& a, const ir::Study& st,
                                                  const ScenePlan& scene);

} // namespace gbx::rt
