#include "dynamics/Lumped.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "dynamics/SceneSupport.h"
#include "kinematics/Standards.h"

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

LumpedModes gearboxModes(const Model& m, const Assignment& a) {
  LumpedModes out;
  Evaluator ev(m);
  Lumped L;
  auto density = [&](int st) {
    const ir::Attribute* mat = m.attribute(st, "material");
    if (mat && !mat->symbol.empty())
      if (const auto* x = m.program.findMaterial(mat->symbol))
        if (const auto* s = ir::findSetting(x->properties, "density"); s && s->value) return s->value->toDouble();
    return 7850.0;
  };
  auto faceWidth = [&](int st) {
    Value b = ev.attribute(st, "face_width", a);
    if (b.isNumber()) return b.mid();
    throw SceneFailure{fmt::format("the gearbox model needs the `face_width` of stage `{}`", m.stages[static_cast<size_t>(st)].ir->name)};
  };
  // A gear's inertia: given, or a solid cylinder of its pitch diameter and face width.
  auto gearInertia = [&](int st, const std::string& gear, double d) {
    Value J = ev.attribute(st, gear + ".inertia", a);
    if (J.isNumber()) return J.mid();
    double r = 0.5 * d;
    return 0.5 * density(st) * M_PI * faceWidth(st) * r * r * r * r;
  };
  auto meshStiffness = [&](int st) {
    Value cg = ev.quantity(m.stages[static_cast<size_t>(st)].ir->name + ".mesh_stiffness", a);
    double c = cg.isNumber() ? cg.mid() : 20e9;  // c_gamma 20 N/(mm*um) where no formula applies
    return c * faceWidth(st);
  };
  const ir::Split* split = m.gearbox.splits.empty() ? nullptr : &m.gearbox.splits[0];
  int splitStage = -1, branches = 1;
  if (split) {
    const ir::Setting* b = ir::findSetting(split->settings, "between");
    splitStage = b ? m.stageIndex(b->symbol) : -1;
    const ir::Setting* n = ir::findSetting(split->settings, "branches");
    branches = n && n->value ? static_cast<int>(n->value->toDouble()) : 2;
  }
  std::vector<int> shaft = {L.add("input shaft")};
  for (int st = 0; st < static_cast<int>(m.stages.size()); ++st) {
    const ir::Stage& s = *m.stages[static_cast<size_t>(st)].ir;
    const std::string& n = s.name;
    auto d = [&](const std::string& g) { return need(ev.derived(st, g + ".d", a), n + "." + g + " pitch diameter"); };
    double alpha = need(ev.attribute(st, "pressure_angle", a), "a pressure angle");
    switch (s.kind) {
    case ir::StageKind::Planetary: {
      double zs = need(ev.attribute(st, "sun.z", a), "sun.z"), zp = need(ev.attribute(st, "planet.z", a), "planet.z"),
             zr = need(ev.attribute(st, "ring.z", a), "ring.z"), mod = need(ev.attribute(st, "module", a), "module");
      int N = static_cast<int>(need(ev.attribute(st, "planets", a), "planets"));
      double rbs = 0.5 * zs * mod * std::cos(alpha), rbp = 0.5 * zp * mod * std::cos(alpha), rbr = 0.5 * zr * mod * std::cos(alpha);
      double rc = 0.5 * (zs + zp) * mod, rp = 0.5 * zp * mod, b = faceWidth(st), rho = density(st);
      double mp = rho * M_PI * rp * rp * b, k = meshStiffness(st);
      int sun = shaft[0], carrier = L.add(n + " carrier");
      L.inertia[static_cast<size_t>(sun)] += gearInertia(st, "sun", d("sun"));
      L.inertia[static_cast<size_t>(carrier)] += 0.5 * rho * M_PI * (rc + rp) * (rc + rp) * b * (rc + rp) * (rc + rp) + N * mp * rc * rc;
      for (int i = 0; i < N; ++i) {
        int p = L.add(fmt::format("{} planet {}", n, i + 1));
        L.inertia[static_cast<size_t>(p)] = 0.5 * mp * rp * rp;
        // Sun-planet: rbs (ts - tc) + rbp phi; ring-planet: -rbp phi - rbr tc.
        L.springs.push_back({{{sun, rbs}, {carrier, -rbs}, {p, rbp}}, k});
        L.springs.push_back({{{p, -rbp}, {carrier, -rbr}}, k});
      }
      shaft = {carrier};
      break;
    }
    case ir::StageKind::Idler: {
      double k = meshStiffness(st);
      double rb1 = 0.5 * d("driver") * std::cos(alpha), rb2 = 0.5 * d("idler") * std::cos(alpha), rb3 = 0.5 * d("driven") * std::cos(alpha);
      int idler = L.add(n + " idler"), driven = L.add(n + " driven");
      L.inertia[static_cast<size_t>(shaft[0])] += gearInertia(st, "driver", d("driver"));
      L.inertia[static_cast<size_t>(idler)] += gearInertia(st, "idler", d("idler"));
      L.inertia[static_cast<size_t>(driven)] += gearInertia(st, "driven", d("driven"));
      L.springs.push_back({{{shaft[0], rb1}, {idler, rb2}}, k});
      L.springs.push_back({{{idler, -rb2}, {driven, -rb3}}, k});
      shaft = {driven};
      break;
    }
    default: {
      double k = meshStiffness(st);
      double dp = d("pinion"), dw = d("wheel");
      double rb1 = 0.5 * dp * std::cos(alpha), rb2 = 0.5 * dw * std::cos(alpha);
      bool branching = st == splitStage;
      bool merging = shaft.size() > 1;
      std::vector<int> next;
      if (merging) next = {L.add(n + " wheel")};
      for (size_t b = 0; b < (branching ? static_cast<size_t>(branches) : shaft.size()); ++b) {
        int from = shaft[std::min(b, shaft.size() - 1)];
        L.inertia[static_cast<size_t>(from)] += (branching && b > 0) ? 0.0 : gearInertia(st, "pinion", dp);
        int to = merging ? next[0] : L.add(branching ? fmt::format("{} wheel, branch {}", n, b + 1) : n + " wheel");
        if (!merging) next.push_back(to);
        L.inertia[static_cast<size_t>(to)] += (merging && b > 0) ? 0.0 : gearInertia(st, "wheel", dw);
        L.springs.push_back({{{from, rb1}, {to, rb2}}, k});
      }
      if (branching) {
        // Each branch carries on through its torsion shaft to its own next pinion.
        auto setting = [&](const char* x) { return ev.quantity(split->name + "." + x, a); };
        double len = need(setting("torsion_shaft.length"), "the torsion shaft's length");
        double ds = need(setting("torsion_shaft.diameter"), "the torsion shaft's diameter");
        double G = need(setting("torsion_shaft.shear_modulus"), "the torsion shaft's shear modulus");
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
    }
  }
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
  // Mesh frequencies near a mode.
  for (int st = 0; st < static_cast<int>(m.stages.size()); ++st) {
    Value fz = ev.derived(st, "mesh_frequency", a);
    if (!fz.isNumber()) continue;
    for (double f : out.frequencies)
      for (int k = 1; k <= 5; ++k)
        if (std::fabs(k * fz.mid() - f) <= 0.1 * f)
          out.provenance.push_back(fmt::format("warning: {} x the mesh frequency of `{}` ({:.2f} Hz) lies within 10 % of the mode at {:.2f} Hz",
                                               k, m.stages[static_cast<size_t>(st)].ir->name, fz.mid(), f));
  }
  return out;
}

} // namespace gbx::rt::dyn
