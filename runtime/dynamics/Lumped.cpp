#include "dynamics/Lumped.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "catalogue/StageKinds.h"

#include "dynamics/SceneSupport.h"
#include "model/Standards.h"

namespace gbx::rt::dyn {

namespace {

double need(const Value& v, const std::string& what) { return needNumber(v, what); }

struct Lumped {
  std::vector<std::string> names;
  std::vector<double> inertia;
  std::vector<std::tuple<std::vector<std::pair<int, double>>, double>> springs;  // coupling (dof, coefficient), stiffness
  int add(const std::string& n) {
    names.push_back(n);
    inertia.push_back(0);
    return static_cast<int>(names.size()) - 1;
  }
};

} // namespace

namespace {

// The train as lumped rotations, stage by stage: what each stage kind adds to it.
class TrainBuilder {
public:
  TrainBuilder(const Model& model, const Assignment& design, LumpedModes& result) : m(model), a(design), ev(model), out(result) {
    if (const ir::Split* split = m.gearbox.splits.empty() ? nullptr : &m.gearbox.splits[0]) {
      const ir::Setting* b = ir::findSetting(split->settings, Q::Between);
      splitStage = b ? b->stage : -1;
      const ir::Setting* n = ir::findSetting(split->settings, Q::Branches);
      branches = n && n->value ? static_cast<int>(n->value->toDouble()) : 2;
    }
  }

  Lumped build() {
    shaft = {L.add("input shaft")};
    for (int st = 0; st < static_cast<int>(m.stages.size()); ++st) {
      const ir::Stage& s = *m.stages[static_cast<size_t>(st)].ir;
      double alpha = need(ev.attribute(st, Q::PressureAngle, a), "a pressure angle");
      switch (s.kind) {
      case ir::StageKind::Planetary: planetary(st, s.name, alpha); break;
      case ir::StageKind::Idler: idler(st, s.name, alpha); break;
      default: pair(st, s.name, alpha);
      }
    }
    return std::move(L);
  }

  const Evaluator& evaluator() const { return ev; }

private:
  const Model& m;
  const Assignment& a;
  Evaluator ev;
  LumpedModes& out;
  Lumped L;
  int splitStage = -1, branches = 1;
  std::vector<int> shaft;

  double density(int st) const { return m.info(st).elastic.density; }
  double faceWidth(int st) const {
    Value b = ev.attribute(st, Q::FaceWidth, a);
    if (b.isNumber()) return b.mid();
    throw SceneFailure{fmt::format("the gearbox model needs the `face_width` of stage `{}`", m.stages[static_cast<size_t>(st)].ir->name)};
  }
  // A gear's inertia: given, or a solid cylinder of its pitch diameter and face width.
  double gearInertia(int st, int gear, double d) const {
    Value J = ev.attribute(st, gear, Q::Inertia, a);
    if (J.isNumber()) return J.mid();
    double r = 0.5 * d;
    return 0.5 * density(st) * M_PI * faceWidth(st) * r * r * r * r;
  }
  double meshStiffness(int st) const {
    Value cg = ev.attribute(st, Q::MeshStiffness, a);
    double c = cg.isNumber() ? cg.mid() : 20e9;  // c_gamma 20 N/(mm*um) where no formula applies
    return c * faceWidth(st);
  }
  double d(int st, int g) const {
    const ir::Stage& s = *m.stages[static_cast<size_t>(st)].ir;
    return need(ev.derived(st, g, Q::D, a), s.name + "." + s.gears[static_cast<size_t>(g)] + " pitch diameter");
  }

  void planetary(int st, const std::string& n, double alpha) {
    using namespace cat::gear;
    auto d = [&](int g) { return this->d(st, g); };
    double zs = need(ev.attribute(st, Sun, Q::Z, a), "sun.z"), zp = need(ev.attribute(st, Planet, Q::Z, a), "planet.z"),
           zr = need(ev.attribute(st, Ring, Q::Z, a), "ring.z"), mod = need(ev.attribute(st, Q::Module, a), "module");
    int N = static_cast<int>(need(ev.attribute(st, Q::Planets, a), "planets"));
    double rbs = 0.5 * zs * mod * std::cos(alpha), rbp = 0.5 * zp * mod * std::cos(alpha), rbr = 0.5 * zr * mod * std::cos(alpha);
    double rc = 0.5 * (zs + zp) * mod, rp = 0.5 * zp * mod, b = faceWidth(st), rho = density(st);
    double mp = rho * M_PI * rp * rp * b, k = meshStiffness(st);
    int sun = shaft[0], carrier = L.add(n + " carrier");
    L.inertia[static_cast<size_t>(sun)] += gearInertia(st, Sun, d(Sun));
    L.inertia[static_cast<size_t>(carrier)] += 0.5 * rho * M_PI * (rc + rp) * (rc + rp) * b * (rc + rp) * (rc + rp) + N * mp * rc * rc;
    for (int i = 0; i < N; ++i) {
      int p = L.add(fmt::format("{} planet {}", n, i + 1));
      L.inertia[static_cast<size_t>(p)] = 0.5 * mp * rp * rp;
      // Sun-planet: rbs (ts - tc) + rbp phi; ring-planet: -rbp phi - rbr tc.
      L.springs.push_back({{{sun, rbs}, {carrier, -rbs}, {p, rbp}}, k});
      L.springs.push_back({{{p, -rbp}, {carrier, -rbr}}, k});
    }
    shaft = {carrier};
  }

  void idler(int st, const std::string& n, double alpha) {
    using namespace cat::gear;
    auto d = [&](int g) { return this->d(st, g); };
    double k = meshStiffness(st);
    double rb1 = 0.5 * d(Driver) * std::cos(alpha), rb2 = 0.5 * d(Idler) * std::cos(alpha), rb3 = 0.5 * d(Driven) * std::cos(alpha);
    int idler = L.add(n + " idler"), driven = L.add(n + " driven");
    L.inertia[static_cast<size_t>(shaft[0])] += gearInertia(st, Driver, d(Driver));
    L.inertia[static_cast<size_t>(idler)] += gearInertia(st, Idler, d(Idler));
    L.inertia[static_cast<size_t>(driven)] += gearInertia(st, Driven, d(Driven));
    L.springs.push_back({{{shaft[0], rb1}, {idler, rb2}}, k});
    L.springs.push_back({{{idler, -rb2}, {driven, -rb3}}, k});
    shaft = {driven};
  }

  // A spur or helical pair; at a power split, one per branch (and a torsion shaft after each),
  // merging again at the next pair.
  void pair(int st, const std::string& n, double alpha) {
    using namespace cat::gear;
    auto d = [&](int g) { return this->d(st, g); };
    double k = meshStiffness(st);
    double dp = d(Pinion), dw = d(Wheel);
    // Base radii in the transverse section (cos a_t), as the stage's own quantity has them.
    auto baseRadius = [&](int g, double dg) {
      Value rb = ev.derived(st, g, Q::BaseRadius, a);
      return rb.isNumber() ? rb.mid() : 0.5 * dg * std::cos(alpha);
    };
    double rb1 = baseRadius(Pinion, dp), rb2 = baseRadius(Wheel, dw);
    bool branching = st == splitStage;
    bool merging = shaft.size() > 1;
    std::vector<int> next;
    if (merging) next = {L.add(n + " wheel")};
    for (size_t b = 0; b < (branching ? static_cast<size_t>(branches) : shaft.size()); ++b) {
      int from = shaft[std::min(b, shaft.size() - 1)];
      L.inertia[static_cast<size_t>(from)] += (branching && b > 0) ? 0.0 : gearInertia(st, Pinion, dp);
      int to = merging ? next[0] : L.add(branching ? fmt::format("{} wheel, branch {}", n, b + 1) : n + " wheel");
      if (!merging) next.push_back(to);
      L.inertia[static_cast<size_t>(to)] += (merging && b > 0) ? 0.0 : gearInertia(st, Wheel, dw);
      L.springs.push_back({{{from, rb1}, {to, rb2}}, k});
    }
    if (branching) {
      // Each branch carries on through its torsion shaft to its own next pinion.
      auto setting = [&](Q key) { return ev.splitQuantity(0, key, a); };
      double len = need(setting(Q::TorsionShaftLength), "the torsion shaft's length");
      double ds = need(setting(Q::TorsionShaftDiameter), "the torsion shaft's diameter");
      double G = need(setting(Q::TorsionShaftShearModulus), "the torsion shaft's shear modulus");
      double kt = G * M_PI * std::pow(ds, 4) / 32.0 / len;
      out.provenance.push_back(fmt::format("{} branches from stage `{}`, torsion shafts {:.4g} N*m/rad", branches, n, kt));
      std::vector<int> pinions;
      for (size_t b = 0; b < next.size(); ++b) {
        int p = L.add(fmt::format("branch {} pinion shaft", b + 1));
        L.springs.push_back({{{next[b], 1.0}, {p, -1.0}}, kt});
        pinions.push_back(p);
      }
      next = pinions;
    }
    shaft = next;
  }
};

// Modes of the lumped train, each with the two members that carry most of its kinetic energy.
void modesOf(const Lumped& L, LumpedModes& out) {
  size_t n = L.names.size();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(static_cast<long>(n), static_cast<long>(n)), M = K;
  for (size_t i = 0; i < n; ++i) M(static_cast<long>(i), static_cast<long>(i)) = std::max(L.inertia[i], 1e-12);
  for (const auto& [coupling, k] : L.springs) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<long>(n));
    for (const auto& [dof, c] : coupling) g(dof) += c;
    K += k * g * g.transpose();
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  double top = eig.eigenvalues().maxCoeff();
  for (long i = 0; i < eig.eigenvalues().size(); ++i) {
    double lam = eig.eigenvalues()(i);
    if (lam <= 1e-9 * top) continue;  // the free train's rigid rotation
    out.frequencies.push_back(std::sqrt(lam) / (2.0 * M_PI));
    // Members by kinetic participation J v^2.
    std::vector<std::pair<double, size_t>> part;
    for (size_t j = 0; j < n; ++j) {
      double v = eig.eigenvectors()(static_cast<long>(j), i);
      part.emplace_back(L.inertia[j] * v * v, j);
    }
    std::sort(part.rbegin(), part.rend());
    double total = 0;
    for (const auto& p : part) total += p.first;
    std::string shape;
    for (size_t j = 0; j < std::min<size_t>(2, part.size()); ++j)
      shape += fmt::format("{}{} {:.0f} %", j ? ", " : "", L.names[part[j].second], 100 * part[j].first / total);
    out.shapes.push_back(shape);
  }
  out.provenance.push_back(fmt::format("{} degrees of freedom (one rotation per shaft, idler, carrier and planet); inertias given "
                                       "or of solid cylinders; mesh stiffness c_gamma x b",
                                       n));
}

} // namespace

LumpedModes gearboxModes(const Model& m, const Assignment& a) {
  LumpedModes out;
  TrainBuilder builder(m, a, out);
  Lumped L = builder.build();
  modesOf(L, out);
  const Evaluator& ev = builder.evaluator();
  // Mesh frequencies near a mode.
  for (int st = 0; st < static_cast<int>(m.stages.size()); ++st) {
    Value fz = ev.derived(st, Q::MeshFrequency, a);
    if (!fz.isNumber()) continue;
    for (double f : out.frequencies)
      for (int k = 1; k <= 5; ++k)
        if (std::fabs(k * fz.mid() - f) <= 0.1 * f)
          out.provenance.push_back(fmt::format("warning: {} x the mesh frequency of `{}` ({:.2f} Hz) lies within 10 % of the mode at {:.2f} Hz",
                                               k, m.stages[static_cast<size_t>(st)].ir->name, fz.mid(), f));
  }
  return out;
}

std::vector<double> naturalFrequencies(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  std::vector<double> out;
  for (long i = 0; i < eig.eigenvalues().size(); ++i) {
    double lam = eig.eigenvalues()(i);
    out.push_back(lam > 0 ? std::sqrt(lam) / (2.0 * M_PI) : 0.0);
  }
  return out;
}

std::string frequencyList(const std::vector<double>& f) {
  std::string s;
  for (double x : f) s += (s.empty() ? "" : ", ") + fmt::format("{:.1f}", x);
  return s;
}

std::string lumpedMaxStep(double& maxStep, double Tz, double fmax, std::optional<double> factor, const char* meshRule) {
  double Tn = fmax > 0 ? 1.0 / fmax : Tz;
  maxStep = std::min(Tz, Tn) / 20.0;
  std::string rule = Tn < Tz ? "Tn/20 (the highest linearised mode)" : meshRule;
  if (factor) {
    maxStep *= *factor;
    rule += fmt::format(" x {:g}", *factor);
  }
  return fmt::format("max step {} = {:.4g} ms", rule, maxStep * 1e3);
}

} // namespace gbx::rt::dyn
