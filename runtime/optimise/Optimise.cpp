#include "optimise/Optimise.h"
#include "model/Deadline.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

#include <fmt/format.h>
#include <gsl/gsl_multimin.h>

#include "dynamics/Scene.h"
#include "model/Evaluator.h"
#include "optimise/Decide.h"
#include "optimise/Violation.h"
#include "parallel/Numbers.h"
#include "parallel/Ranks.h"

namespace gbx::rt {

namespace {

// The quantities under `relative(…)` in the objectives, in order.
// The arguments of `relative(…)`: as the gearbox resolves them, and as its baseline does.
void termsOf(const ir::Expr& e, std::vector<const ir::Expr*>& out, std::vector<const ir::Expr*>& inBaseline) {
  if (e.op == ir::Op::Relative) {
    out.push_back(e.args[0].get());
    inBaseline.push_back(e.inBaseline.get());
    return;
  }
  for (const auto& x : e.args)
    if (x) termsOf(*x, out, inBaseline);
}

struct Task {
  const Model* m;
  Evaluator* ev;
  Assignment* a;
  std::vector<double> lo, hi;
  const std::vector<const ir::Expr*>* terms;
  std::vector<std::pair<std::vector<double>, std::vector<double>>> points;  // feasible: freedoms, terms
  long evaluations = 0;
  double bestObjective = INFINITY;
  std::vector<double> bestFreedoms, bestTerms;
  bool feasible = false;
};

double objectiveAt(const gsl_vector* u, void* p) {
  auto* t = static_cast<Task*>(p);
  size_t n = t->lo.size();
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) {
    double s = std::sin(gsl_vector_get(u, i));
    x[i] = t->lo[i] + (t->hi[i] - t->lo[i]) * s * s;  // bounds by transform: never outside the domain
    t->a->box[i] = {x[i], x[i]};
  }
  t->ev->solveFreedoms(*t->a, x); // a solved freedom's coordinate moves nothing: its value is computed
  ++t->evaluations;
  double v = 0;
  for (const auto& r : t->m->gearbox.rules)
    if (r.expr) v += violation(*t->ev, *r.expr, *t->a);
  if (v > 0) return 1e3 * (1.0 + v);  // exterior penalty: any feasible design is better
  double f = 0;
  for (const auto& o : t->m->gearbox.objectives) {
    Value val = o.expr ? t->ev->eval(*o.expr, *t->a) : Value::invalid();
    if (!val.isNumber()) return 1e3 * 2;
    f += o.minimize ? val.mid() : -val.mid();
  }
  std::vector<double> terms;
  for (const auto* e : *t->terms) terms.push_back(t->ev->eval(*e, *t->a).mid());
  t->points.emplace_back(x, terms);
  if (f < t->bestObjective) {
    t->bestObjective = f;
    t->bestFreedoms = x;
    t->bestTerms = terms;
    t->feasible = true;
  }
  return f;
}

// One candidate's freedoms: decided as the search decides them (`plan`, no scene read), or by
// Nelder-Mead from the middle of every domain. The best point and its objective land in `task`.
void runCandidate(Task& task, const Model& m, Evaluator& ev, Assignment& a, const FreedomPlan* plan,
                  const std::vector<const ir::Expr*>& terms, const OptimiseOptions& opt) {
  for (const auto& f : m.freedoms) {
    task.lo.push_back(f.lo);
    task.hi.push_back(f.hi);
  }
  size_t n = task.lo.size();
  if (plan) {
    DecidedPoint p = plan->decide(ev, a.choice);
    task.evaluations += p.evaluations;
    if (p.feasible) {
      for (size_t f = 0; f < n; ++f)
        a.box[f] = {p.freedoms[f], p.freedoms[f]};
      double f = 0;
      for (const auto& o : m.gearbox.objectives) {
        Value v = o.expr ? ev.eval(*o.expr, a) : Value::invalid();
        f += v.isNumber() ? (o.minimize ? v.mid() : -v.mid()) : NAN;
      }
      if (std::isfinite(f)) {
        task.feasible = true;
        task.bestObjective = f;
        task.bestFreedoms = p.freedoms;
        for (const auto* e : terms) task.bestTerms.push_back(ev.eval(*e, a).mid());
        task.points.emplace_back(p.freedoms, task.bestTerms);
      }
    }
  } else if (n == 0) {
    gsl_vector* u = gsl_vector_alloc(1);
    objectiveAt(u, &task);
    gsl_vector_free(u);
  } else {
    const gsl_multimin_fminimizer_type* type = gsl_multimin_fminimizer_nmsimplex2;
    gsl_multimin_fminimizer* s = gsl_multimin_fminimizer_alloc(type, n);
    gsl_vector* u = gsl_vector_alloc(n);
    gsl_vector* step = gsl_vector_alloc(n);
    gsl_vector_set_all(u, M_PI / 4);  // the middle of every domain
    gsl_vector_set_all(step, 0.35);
    gsl_multimin_function fn{&objectiveAt, n, &task};
    gsl_multimin_fminimizer_set(s, &fn, u, step);
    for (int it = 0; it < opt.maxIterations && !Deadline::expired(); ++it) {
      if (gsl_multimin_fminimizer_iterate(s) != GSL_SUCCESS) break;
      if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s), 1e-4) == GSL_SUCCESS) break;
    }
    gsl_vector_free(step);
    gsl_vector_free(u);
    gsl_multimin_fminimizer_free(s);
  }
}

} // namespace

double ownSceneRtol(const Model& m) { return m.scenes.empty() ? 1e-9 : m.scenes[0].rtol.value_or(1e-9); }

void installHooks(Evaluator& ev, const Model& m, const Model* baseline, const Assignment* baseDesign, double rtol) {
  // One scene run per design point (and tolerance corner): outputs of one scene share it.
  // The cache holds the points of the design being evaluated, so a `worst(…)` read twice
  // (itself and inside `relative`) runs each corner once.
  using Key = std::pair<int, std::vector<double>>;
  auto cache = std::make_shared<std::map<Key, dyn::SceneResult>>();
  auto design = std::make_shared<std::vector<double>>();
  ev.sceneOutput = [&m, rtol, cache, design](const ir::Expr& e, const Assignment& a, const Evaluator& asking) -> Value {
    std::vector<double> point;
    for (int c : a.choice) point.push_back(c);
    for (const auto& b : a.box) point.push_back(b.first);
    if (point != *design) {
      cache->clear();
      *design = point;
    }
    int scene = e.output.scene;
    if (scene < 0 || static_cast<size_t>(scene) >= m.scenes.size()) return Value::invalid();
    Key k{scene, asking.offsetKey()};
    auto it = cache->find(k);
    if (it == cache->end()) {
      dyn::SceneOverrides ov;
      ov.rtol = rtol;
      ov.estimateError = false;
      ov.keepSeries = false;
      if (!asking.offsets().empty()) ov.evaluator = &asking;
      it = cache->emplace(k, dyn::runScene(m, a, m.scenes[static_cast<size_t>(scene)], ov)).first;
    }
    const auto* n = it->second.find(e.output.fn, e.output.signal, e.output.order);
    return n ? Value::number(n->value) : Value::invalid();
  };
  if (baseline && baseDesign) {
    auto baseEval = std::make_shared<Evaluator>(*baseline);
    installHooks(*baseEval, *baseline, nullptr, nullptr, rtol);
    auto values = std::make_shared<std::map<std::string, Value>>();
    auto mutex = std::make_shared<std::mutex>();
    ev.baseline = [baseEval, baseDesign, values, mutex](const ir::Expr& e) -> Value {
      std::lock_guard<std::mutex> lock(*mutex);
      // The printed expression, and the sense of each `worst` in it (printing does not show it).
      std::string k = ir::print(e);
      std::function<void(const ir::Expr&)> senses = [&](const ir::Expr& x) {
        if (x.op == ir::Op::Scatter) k += static_cast<char>('1' + x.sense);
        for (const auto& y : x.args)
          if (y) senses(*y);
      };
      senses(e);
      auto it = values->find(k);
      if (it != values->end()) return it->second;
      Value v = baseEval->eval(e, *baseDesign);
      values->emplace(k, v);
      return v;
    };
  }
}

// Rank check: the best few again with the scene at its own tolerance; empty where the scene's
// own tolerance is no tighter than the optimiser's, or fewer than two are ranked.
std::string rankCheck(const Model& m, const Model* baseline, const Assignment* baseDesign, const std::vector<OptCandidate>& ranked,
                      const OptimiseOptions& opt) {
  double tight = ownSceneRtol(m);
  size_t k = std::min(opt.rankCheck, ranked.size());
  if (k >= 2 && tight < opt.sceneRtol) {
    Evaluator ev(m);
    installHooks(ev, m, baseline, baseDesign, tight);
    std::vector<std::pair<double, size_t>> again;
    double worst = 0;
    for (size_t i = 0; i < k; ++i) {
      Assignment a(m);
      a.choice = ranked[i].choice;
      for (size_t f = 0; f < ranked[i].freedoms.size(); ++f) a.box[f] = {ranked[i].freedoms[f], ranked[i].freedoms[f]};
      double f = 0;
      for (const auto& o : m.gearbox.objectives) f += (o.minimize ? 1 : -1) * ev.eval(*o.expr, a).mid();
      again.emplace_back(f, i);
      worst = std::max(worst, std::fabs(f - ranked[i].objective) / std::max(std::fabs(f), 1e-300));
    }
    std::stable_sort(again.begin(), again.end());
    bool same = true;
    for (size_t i = 0; i < k; ++i) same = same && again[i].second == i;
    if (!same) return fmt::format("the ranking of the best {} changes at rtol {:.0e}: rank by a tighter tolerance", k, tight);
    return fmt::format("the best {} keep their ranks with the scene at rtol {:.0e} (objectives within {:.1e} relative of rtol {:.0e})",
                       k, tight, worst, opt.sceneRtol);
  }
  return "";
}

namespace {

// A candidate stopped by the time limit, in place of its numbers.
constexpr double kTimedOut = -1;

// A candidate's run as numbers (for the ranks to exchange): feasible, objective,
// evaluations, then the freedoms, the terms and the feasible points (each list after its
// length). A single kTimedOut: stopped by the time limit.
std::vector<double> packCandidate(const Task& task) {
  par::NumbersOut out;
  out.put(task.feasible ? 1.0 : 0.0);
  out.put(task.bestObjective);
  out.put(static_cast<double>(task.evaluations));
  out.list(task.bestFreedoms);
  out.list(task.bestTerms);
  out.put(static_cast<double>(task.points.size()));
  for (const auto& [x, t] : task.points) {
    out.list(x);
    out.list(t);
  }
  return out.take();
}

void unpackCandidate(const std::vector<double>& v, OptCandidate& c, std::vector<std::pair<std::vector<double>, std::vector<double>>>& points) {
  if (v.size() < 3) return;  // stopped by the time limit
  par::NumbersIn in(v);
  c.feasible = in.next() != 0;
  c.objective = in.next();
  c.evaluations = static_cast<long>(in.next());
  in.list(c.freedoms);
  in.list(c.terms);
  points.resize(static_cast<size_t>(in.next()));
  for (auto& [x, t] : points) {
    in.list(x);
    in.list(t);
  }
}

} // namespace

OptimiseResult optimise(const Model& m, const Model* baseline, const Assignment* baseDesign, const std::vector<Design>& candidates,
                        const OptimiseOptions& opt) {
  OptimiseResult res;
  double cpu0 = dyn::threadCpuSeconds();
  std::vector<const ir::Expr*> terms, baseTerms;
  for (const auto& o : m.gearbox.objectives)
    if (o.expr) termsOf(*o.expr, terms, baseTerms);
  for (const auto* t : terms) res.termNames.push_back(ir::print(*t));
  // The baseline's values, computed once and shared by every thread.
  Evaluator probe(m);
  installHooks(probe, m, baseline, baseDesign, opt.sceneRtol);
  for (const auto* t : baseTerms) res.baselineTerms.push_back(probe.baseline && t ? probe.baseline(*t).mid() : NAN);
  auto sharedBaseline = probe.baseline;

  // Without a scene in the rules or objectives, each candidate's freedoms are decided as the
  // search decides them (docs/language.md): the same point, rounded to the printed digits, so an
  // unchanged variant reads relative(x) = 1 exactly.
  std::unique_ptr<FreedomPlan> plan;
  if (!readsScenes(m.gearbox) && !m.freedoms.empty()) plan = std::make_unique<FreedomPlan>(m);

  // Each candidate's Nelder-Mead run is one task over the threads and, under mpirun, the
  // ranks (a fixed point of the pass: every rank reaches it once per gearbox); its result
  // packed into numbers, which every rank receives in candidate order.
  std::atomic<size_t> done{0};
  std::mutex progressLock;
  auto runOne = [&](size_t i) {
    // Past the time limit: a marker, so that every rank stops alike (the solve says so).
    if (Deadline::expired()) return std::vector<double>{kTimedOut};
    Evaluator ev(m);
    installHooks(ev, m, nullptr, nullptr, opt.sceneRtol);
    ev.baseline = sharedBaseline;
    Assignment a(m);
    a.choice = candidates[i].choice;
    Task task{&m, &ev, &a, {}, {}, &terms, {}, 0, INFINITY, {}, {}, false};
    runCandidate(task, m, ev, a, plan.get(), terms, opt);
    if (Deadline::expired()) return std::vector<double>{kTimedOut};  // cut short: not an optimum
    size_t d = ++done;
    if (opt.progress) {
      std::lock_guard<std::mutex> hold(progressLock);
      opt.progress(static_cast<double>(d) / static_cast<double>(candidates.size()));
    }
    return packCandidate(task);
  };
  std::vector<std::vector<double>> packed = par::map(candidates.size(), opt.jobs, runOne, true);
  for (const auto& p : packed)
    if (p.size() == 1 && p[0] == kTimedOut) Deadline::expireNow();
  std::vector<OptCandidate> out(candidates.size());
  std::vector<std::vector<std::pair<std::vector<double>, std::vector<double>>>> clouds(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) {
    out[i].choice = candidates[i].choice;
    out[i].ratio = candidates[i].ratio;
    unpackCandidate(packed[i], out[i], clouds[i]);
  }
  if (opt.progress) opt.progress(1.0);

  for (size_t i = 0; i < out.size(); ++i) {
    res.evaluations += out[i].evaluations;
    if (!out[i].feasible) {
      ++res.infeasible;
      continue;
    }
    res.ranked.push_back(out[i]);
    if (res.baselineTerms.size() == 2)
      for (const auto& [x, t] : clouds[i]) res.cloud.emplace_back(t[0] / res.baselineTerms[0], t[1] / res.baselineTerms[1]);
  }
  // Ties (equal objectives) fall back on the candidates' order: deterministic for any --jobs.
  std::stable_sort(res.ranked.begin(), res.ranked.end(), [](const OptCandidate& a, const OptCandidate& b) { return a.objective < b.objective; });
  // Pareto front of the two relative terms over every feasible evaluation.
  std::vector<std::pair<double, double>> pts = res.cloud;
  std::sort(pts.begin(), pts.end());
  double best = INFINITY;
  for (const auto& p : pts)
    if (p.second < best) {
      res.pareto.push_back(p);
      best = p.second;
    }
  res.rankCheck = rankCheck(m, baseline, baseDesign, res.ranked, opt);
  res.cpuSeconds = dyn::threadCpuSeconds() - cpu0;
  return res;
}

} // namespace gbx::rt
