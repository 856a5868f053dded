#include "passes/Shafts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/Evaluator.h"
#include "shaft/ShaftPlan.h"

namespace gbx::rt::passes {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Each notch's DIN 743 sequence as the report shows it: N/mm^2 for stresses, 1/mm for G'.
void notches(const ShaftResult& s, ShaftReport& r) {
  using F = shaft::din743::Factors;
  using N = ShaftReport::Notch;
  r.loadCase = s.strength.din.loadCase;
  r.peakFactor = s.strength.peak;
  r.minFatigue = s.strength.minFatigue;
  r.minStatic = s.strength.minStatic;
  r.fatigueSafety = s.fatigueSafety;
  r.staticSafety = s.staticSafety;
  struct Row {
    const char *key, *label, *unit;
    double scale;
    double (*get)(const F&);
    bool formFactorOnly, testOnly;
  };
  static const Row rows[] = {
      {"mean", "mean stress", "N/mm^2", 1e6, [](const F& f) { return f.mean; }, false, false},
      {"amplitude", "stress amplitude", "N/mm^2", 1e6, [](const F& f) { return f.amplitude; }, false, false},
      {"max", "largest stress", "N/mm^2", 1e6, [](const F& f) { return f.max; }, false, false},
      {"K2", "K2", "", 1, [](const F& f) { return f.K2; }, false, false},
      {"alpha", "alpha", "", 1, [](const F& f) { return f.alpha; }, true, false},
      {"G_prime", "G'", "1/mm", 1e3, [](const F& f) { return f.Gprime; }, true, false},
      {"n", "n", "", 1, [](const F& f) { return f.n; }, true, false},
      {"beta_test", "beta(d_BK)", "", 1, [](const F& f) { return f.betaTest; }, false, true},
      {"K3_test", "K3(d_BK)", "", 1, [](const F& f) { return f.K3Test; }, false, true},
      {"K3", "K3(d)", "", 1, [](const F& f) { return f.K3; }, false, true},
      {"beta", "beta", "", 1, [](const F& f) { return f.beta; }, false, false},
      {"K_F", "K_F", "", 1, [](const F& f) { return f.KF; }, false, false},
      {"K", "K", "", 1, [](const F& f) { return f.K; }, false, false},
      {"sigma_W", "sigma_W(d_eff)", "N/mm^2", 1e6, [](const F& f) { return f.sigmaW; }, false, false},
      {"sigma_WK", "sigma_WK", "N/mm^2", 1e6, [](const F& f) { return f.sigmaWK; }, false, false},
      {"psi", "psi", "", 1, [](const F& f) { return f.psi; }, false, false},
      {"sigma_ADK", "sigma_ADK", "N/mm^2", 1e6, [](const F& f) { return f.sigmaADK; }, false, false},
      {"K2F", "K2F", "", 1, [](const F& f) { return f.K2F; }, false, false},
      {"gamma_F", "gamma_F", "", 1, [](const F& f) { return f.gammaF; }, false, false},
      {"sigma_FK", "sigma_FK", "N/mm^2", 1e6, [](const F& f) { return f.sigmaFK; }, false, false},
  };
  for (const auto& n : s.notches) {
    N o;
    o.kind = n.kind;
    o.x = n.x;
    o.d = n.notch.d;
    o.D = n.notch.D;
    o.radius = n.notch.radius;
    o.bending = n.loads[shaft::din743::Bending].amplitude;
    o.torque = n.loads[shaft::din743::Torsion].mean;
    o.axial = n.loads[shaft::din743::Tension].mean;
    o.SD = n.result.SD;
    o.SF = n.result.SF;
    bool formFactor = n.result.f[0].alpha > 0;
    for (const auto& row : rows) {
      if ((row.formFactorOnly && !formFactor) || (row.testOnly && formFactor)) continue;
      N::Factor f{row.key, row.label, row.unit, row.scale, {}};
      for (int k = 0; k < 3; ++k)
        f.si[k] = row.get(n.result.f[static_cast<size_t>(k)]);
      o.factors.push_back(std::move(f));
    }
    o.common = {{"K1B", "K1 (sigma_B)", "", 1, n.result.K1B},
                {"K1S", "K1 (sigma_S)", "", 1, n.result.K1S},
                {"sigma_B", "sigma_B(d_eff)", "N/mm^2", 1e6, n.result.tensileAt},
                {"sigma_S", "sigma_S(d_eff)", "N/mm^2", 1e6, n.result.yieldAt},
                {"phi", "phi", "", 1, formFactor ? n.result.phi : kNaN},
                {"sigma_mv", "sigma_mv", "N/mm^2", 1e6, n.result.sigmaMv}};
    r.notches.push_back(std::move(o));
  }
}

} // namespace

Shafts shafts(const Model& m, const Assignment& best) {
  Shafts out;
  Evaluator ev(m);
  for (size_t i = 0; i < m.gearbox.shafts.size(); ++i) {
    ShaftReport r;
    r.name = m.gearbox.shafts[i].name;
    std::string error;
    auto s = computeShaft(ev, static_cast<int>(i), best, &error);
    if (!s) {
      r.error = error;
      out.shafts.push_back(std::move(r));
      continue;
    }
    for (size_t k = 0; k < s->bearings.size(); ++k) {
      const auto& rc = s->solution.reactions[k];
      const auto& l = s->lives[k];
      r.bearings.push_back({s->bearings[k], shaft::kindName(s->kinds[k]), l.method, s->model.bearings[k].x, rc.radial(),
                            std::fabs(rc.Fx), l.P, l.L10h, l.Lnmh, l.s0});
    }
    for (const auto& g : s->gears)
      r.gears.push_back({g.gear, g.x, g.Ft, g.Fr, g.Fa});
    notches(*s, r);
    r.speed = s->speed;
    r.criticalSpeed = s->criticalSpeed;
    r.deflection = s->deflection;
    r.deflectionAt = s->deflectionAt;
    r.mass = s->mass;
    r.warnings = s->warnings;
    // The deflection line and the bending moment, sampled along the shaft for the charts.
    const auto& sol = s->solution;
    double x0 = sol.x.front(), x1 = sol.x.back();
    std::vector<double> at;
    for (int k = 0; k <= 200; ++k)
      at.push_back(x0 + (x1 - x0) * k / 200);
    // Each station from both sides: a couple there makes the moment jump.
    for (double x : sol.x)
      at.insert(at.end(), {std::max(x0, x - 1e-9), x});
    std::sort(at.begin(), at.end());
    for (double x : at) {
      r.lineX.push_back(x);
      r.lineDeflection.push_back(sol.deflectionAt(x));
      r.lineMoment.push_back(
          std::hypot(sol.moment(shaft::Solution::Plane::Y, x), sol.moment(shaft::Solution::Plane::Z, x)));
    }
    out.warnings.insert(out.warnings.end(), s->warnings.begin(), s->warnings.end());
    out.shafts.push_back(std::move(r));
  }
  return out;
}

} // namespace gbx::rt::passes
