#include "shaft/Beam.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <fmt/format.h>

namespace gbx::rt::shaft {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Triplets = std::vector<Eigen::Triplet<double>>;
using Mat4 = Eigen::Matrix4d;

// The section an element between a and b lies in (section ends are nodes).
const Section& sectionOf(const Model& m, double a, double b) {
  double mid = 0.5 * (a + b);
  for (const auto& s : m.sections)
    if (mid >= s.x0 && mid <= s.x1) return s;
  throw std::invalid_argument(fmt::format("no section of the shaft at {} mm", mid * 1e3));
}

// Timoshenko's shear parameter Phi = 12 EI / (kappa G A L^2); 0 for Euler–Bernoulli.
double shearParameter(const Model& m, const Props& p, double L) {
  return m.shear ? 12 * m.material.E * p.I / (p.kappa * m.material.G * p.A * L * L) : 0.0;
}

// The bending element's stiffness on (deflection, slope) at both ends (Przemieniecki):
// exact for a Timoshenko beam loaded at its nodes.
Mat4 stiffness(double EI, double L, double phi) {
  Mat4 k;
  double L2 = L * L;
  k << 12, 6 * L, -12, 6 * L,                        //
      6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2, //
      -12, -6 * L, 12, -6 * L,                       //
      6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2;
  return k * (EI / ((1 + phi) * L * L2));
}

// Consistent mass of the element, translational and rotary (Friswell et al. 2010, ch. 5).
Mat4 mass(double rhoA, double rhoI, double L, double phi) {
  double L2 = L * L, p2 = phi * phi;
  Mat4 t, r;
  double a = 312 + 588 * phi + 280 * p2, b = (44 + 77 * phi + 35 * p2) * L, c = 108 + 252 * phi + 140 * p2;
  double d = (26 + 63 * phi + 35 * p2) * L, e = (8 + 14 * phi + 7 * p2) * L2, f = (6 + 14 * phi + 7 * p2) * L2;
  t << a, b, c, -d, //
      b, e, d, -f,  //
      c, d, a, -b,  //
      -d, -f, -b, e;
  t *= rhoA * L / (840 * (1 + phi) * (1 + phi));
  double g = (3 - 15 * phi) * L, h = (4 + 5 * phi + 10 * p2) * L2, q = (-1 - 5 * phi + 5 * p2) * L2;
  r << 36, g, -36, g,  //
      g, h, -g, q,     //
      -36, -g, 36, -g, //
      g, q, -g, h;
  r *= rhoI / (30 * (1 + phi) * (1 + phi) * L);
  return t + r;
}

size_t nodeAt(const std::vector<double>& x, double at) {
  auto it = std::lower_bound(x.begin(), x.end(), at - 1e-12);
  if (it == x.end() || std::fabs(*it - at) > 1e-9)
    throw std::invalid_argument(fmt::format("{} mm is not on the shaft", at * 1e3));
  return static_cast<size_t>(it - x.begin());
}

// A system on the free degrees of freedom: `free[i]` the reduced index of dof i, or -1.
struct Reduced {
  std::vector<int> free;
  int n = 0;
  explicit Reduced(const std::vector<bool>& fixed) : free(fixed.size(), -1) {
    for (size_t i = 0; i < fixed.size(); ++i)
      if (!fixed[i]) free[i] = n++;
  }
};

// Each element's section properties, computed once.
std::vector<Props> elementProps(const Model& m, const std::vector<double>& x) {
  std::vector<Props> p;
  p.reserve(x.size());
  for (size_t e = 0; e + 1 < x.size(); ++e)
    p.push_back(props(sectionOf(m, x[e], x[e + 1]), m.material.poisson()));
  return p;
}

// A bending plane: the assembled stiffness (with the bearings' springs) and its rigid supports.
struct Plane {
  Eigen::SparseMatrix<double> K; // full, springs included
  std::vector<bool> fixed;
};

Plane bendingPlane(const Model& m, const std::vector<double>& x, const std::vector<Props>& p) {
  size_t n = x.size();
  Triplets t;
  t.reserve(16 * n + m.bearings.size());
  for (size_t e = 0; e + 1 < n; ++e) {
    double L = x[e + 1] - x[e];
    Mat4 k = stiffness(m.material.E * p[e].I, L, shearParameter(m, p[e], L));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        t.emplace_back(static_cast<int>(2 * e) + i, static_cast<int>(2 * e) + j, k(i, j));
  }
  Plane pl;
  pl.fixed.assign(2 * n, false);
  for (const auto& b : m.bearings) {
    size_t i = nodeAt(x, b.x);
    if (std::isinf(b.radialStiffness))
      pl.fixed[2 * i] = true;
    else
      t.emplace_back(static_cast<int>(2 * i), static_cast<int>(2 * i), b.radialStiffness);
  }
  pl.K.resize(static_cast<int>(2 * n), static_cast<int>(2 * n));
  pl.K.setFromTriplets(t.begin(), t.end());
  return pl;
}

// Solves K U = F on the free dofs (fixed ones 0), for every column of F at one
// factorisation; returns U and the reactions K U - F.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> solveFixed(const Eigen::SparseMatrix<double>& K,
                                                       const std::vector<bool>& fixed, const Eigen::MatrixXd& F) {
  Reduced r(fixed);
  Triplets t;
  t.reserve(static_cast<size_t>(K.nonZeros()));
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it)
      if (r.free[static_cast<size_t>(it.row())] >= 0 && r.free[static_cast<size_t>(it.col())] >= 0)
        t.emplace_back(r.free[static_cast<size_t>(it.row())], r.free[static_cast<size_t>(it.col())], it.value());
  Eigen::SparseMatrix<double> Kf(r.n, r.n);
  Kf.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd Ff(r.n, F.cols());
  for (size_t i = 0; i < fixed.size(); ++i)
    if (r.free[i] >= 0) Ff.row(r.free[i]) = F.row(static_cast<int>(i));
  // The beam's dofs are banded already: no reordering.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(Kf);
  if (ldlt.info() != Eigen::Success)
    throw std::invalid_argument("the shaft is not held: its supports leave it free to move");
  Eigen::MatrixXd Uf = ldlt.solve(Ff);
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(static_cast<int>(fixed.size()), F.cols());
  for (size_t i = 0; i < fixed.size(); ++i)
    if (r.free[i] >= 0) U.row(static_cast<int>(i)) = Uf.row(r.free[i]);
  return {U, K * U - F};
}

// A bar along the shaft (torsion: GJ, axial: EA) held at node h, statically determinate: an
// element left of h carries minus the loads left of it, one right of h the loads right of it,
// and the displacement follows by summing N L / stiffness outward from h.
std::vector<double> bar(const Model& m, const std::vector<double>& x, const std::vector<Props>& p, bool torsion,
                        size_t h, const std::vector<double>& f, std::vector<double>* force) {
  size_t n = x.size();
  std::vector<double> N(n - 1), left(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i)
    left[i + 1] = left[i] + f[i];
  for (size_t e = 0; e + 1 < n; ++e)
    N[e] = e < h ? -left[e + 1] : left[n] - left[e + 1];
  std::vector<double> u(n, 0.0);
  auto stiff = [&](size_t e) { return torsion ? m.material.G * p[e].J : m.material.E * p[e].A; };
  for (size_t e = h; e + 1 < n; ++e)
    u[e + 1] = u[e] + N[e] * (x[e + 1] - x[e]) / stiff(e);
  for (size_t e = h; e-- > 0;)
    u[e] = u[e + 1] - N[e] * (x[e + 1] - x[e]) / stiff(e);
  if (force) *force = std::move(N);
  return u;
}

void checkModel(const Model& m) {
  if (m.sections.empty()) throw std::invalid_argument("the shaft has no segment");
  for (size_t i = 0; i < m.sections.size(); ++i) {
    const Section& s = m.sections[i];
    if (!(s.x1 > s.x0) || !(s.diameter > s.bore) || s.bore < 0)
      throw std::invalid_argument(
          fmt::format("segment {} mm .. {} mm: its ends or its bore are not a section", s.x0 * 1e3, s.x1 * 1e3));
    if (i > 0 && std::fabs(s.x0 - m.sections[i - 1].x1) > 1e-9)
      throw std::invalid_argument(fmt::format("the segments leave a gap or overlap at {} mm", s.x0 * 1e3));
  }
  std::vector<double> at;
  for (const auto& b : m.bearings)
    at.push_back(b.x);
  std::sort(at.begin(), at.end());
  if (at.size() < 2 || at.back() - at.front() < 1e-9)
    throw std::invalid_argument("a shaft needs two bearings at different positions");
}

} // namespace

double Solution::Reaction::radial() const { return std::hypot(Fy, Fz); }

size_t Solution::element(double at) const {
  if (at <= x.front()) return 0;
  if (at >= x.back()) return x.size() - 2;
  return static_cast<size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin()) - 1;
}

// Reddy's interdependent interpolation of a Timoshenko element free of load between its
// nodes (Hermite's cubics when phi = 0): the exact deflection and rotation there.
double Solution::deflection(Plane p, double at) const {
  const auto& d = p == Plane::Y ? v : w;
  const auto& r = p == Plane::Y ? slopeY : slopeZ;
  size_t e = element(at);
  double L = x[e + 1] - x[e], f = phi[e], s = std::clamp((at - x[e]) / L, 0.0, 1.0), s2 = s * s, s3 = s2 * s;
  double n1 = 1 - 3 * s2 + 2 * s3 + f * (1 - s), n2 = L * (s - 2 * s2 + s3 + f / 2 * (s - s2));
  double n3 = 3 * s2 - 2 * s3 + f * s, n4 = L * (-s2 + s3 + f / 2 * (s2 - s));
  return (n1 * d[e] + n2 * r[e] + n3 * d[e + 1] + n4 * r[e + 1]) / (1 + f);
}

double Solution::slope(Plane p, double at) const {
  const auto& d = p == Plane::Y ? v : w;
  const auto& r = p == Plane::Y ? slopeY : slopeZ;
  size_t e = element(at);
  double L = x[e + 1] - x[e], f = phi[e], s = std::clamp((at - x[e]) / L, 0.0, 1.0), s2 = s * s;
  double g = 6 / L * (s2 - s);
  return (g * d[e] + (1 - 4 * s + 3 * s2 + f * (1 - s)) * r[e] - g * d[e + 1] + (-2 * s + 3 * s2 + f * s) * r[e + 1]) /
         (1 + f);
}

double Solution::moment(Plane p, double at) const {
  size_t e = element(at);
  double s = std::clamp((at - x[e]) / (x[e + 1] - x[e]), 0.0, 1.0);
  double a = p == Plane::Y ? startY[e] : startZ[e], b = p == Plane::Y ? endY[e] : endZ[e];
  return a + s * (b - a);
}

double Solution::twistAt(double at) const {
  size_t e = element(at);
  double s = std::clamp((at - x[e]) / (x[e + 1] - x[e]), 0.0, 1.0);
  return twist[e] + s * (twist[e + 1] - twist[e]);
}

double Solution::torqueAt(double at) const { return torque[element(at)]; }

Props props(const Section& s, double nu) {
  double D = s.diameter, d = s.bore, D2 = D * D, d2 = d * d;
  Props p{};
  p.A = kPi / 4 * (D2 - d2);
  p.I = kPi / 64 * (D2 * D2 - d2 * d2);
  p.J = 2 * p.I;
  // Cowper (1966), a hollow circle: 6 (1+nu)(1+m^2)^2 / ((7+6nu)(1+m^2)^2 + (20+12nu) m^2), m = d/D.
  double m2 = d2 / D2, q = (1 + m2) * (1 + m2);
  p.kappa = 6 * (1 + nu) * q / ((7 + 6 * nu) * q + (20 + 12 * nu) * m2);
  return p;
}

std::vector<double> meshNodes(const Model& m, bool fine) {
  std::vector<double> at;
  for (const auto& s : m.sections)
    at.insert(at.end(), {s.x0, s.x1});
  for (const auto& b : m.bearings)
    at.push_back(b.x);
  // The static solve needs every load's station; the natural frequencies only the masses'.
  if (!fine) {
    for (const auto& l : m.loads)
      at.push_back(l.x);
    at.push_back(m.torsionFixedAt);
  }
  for (const auto& d : m.disks)
    at.push_back(d.x);
  std::sort(at.begin(), at.end());
  double lo = m.sections.front().x0, hi = m.sections.back().x1;
  for (double a : at)
    if (a < lo - 1e-9 || a > hi + 1e-9)
      throw std::invalid_argument(fmt::format("{} mm is off the shaft ({} .. {} mm)", a * 1e3, lo * 1e3, hi * 1e3));
  std::vector<double> x;
  for (double a : at)
    if (x.empty() || a - x.back() > 1e-9) x.push_back(a);
  if (!fine) return x;
  double most = (hi - lo) / std::max(1, m.elements);
  std::vector<double> out;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    int parts = std::max(1, static_cast<int>(std::ceil((x[i + 1] - x[i]) / most - 1e-9)));
    for (int k = 0; k < parts; ++k)
      out.push_back(x[i] + (x[i + 1] - x[i]) * k / parts);
  }
  out.push_back(x.back());
  return out;
}

Solution solve(const Model& m) {
  checkModel(m);
  Solution s;
  s.x = meshNodes(m, false);
  size_t n = s.x.size();
  std::vector<Props> p = elementProps(m, s.x);
  Plane pl = bendingPlane(m, s.x, p);
  // Both planes at one factorisation: column 0 plane y, column 1 plane z.
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(static_cast<int>(2 * n), 2);
  std::vector<double> ft(n, 0.0), fx(n, 0.0);
  for (const auto& l : m.loads) {
    size_t i = nodeAt(s.x, l.x);
    int d = static_cast<int>(2 * i);
    F(d, 0) += l.Fy;
    F(d + 1, 0) += l.My;
    F(d, 1) += l.Fz;
    F(d + 1, 1) += l.Mz;
    ft[i] += l.T;
    fx[i] += l.Fx;
  }
  auto [U, R] = solveFixed(pl.K, pl.fixed, F);
  for (size_t i = 0; i < n; ++i) {
    int d = static_cast<int>(2 * i);
    s.v.push_back(U(d, 0));
    s.slopeY.push_back(U(d + 1, 0));
    s.w.push_back(U(d, 1));
    s.slopeZ.push_back(U(d + 1, 1));
  }
  // The reaction on the shaft: at a rigid support what holds the node, at a spring -k u;
  // several bearings at one station: the first takes what holds it.
  for (size_t k = 0; k < m.bearings.size(); ++k) {
    const Bearing& b = m.bearings[k];
    int d = static_cast<int>(2 * nodeAt(s.x, b.x));
    bool rigid = std::isinf(b.radialStiffness), shared = false;
    for (size_t j = 0; j < k; ++j)
      shared = shared || (rigid && std::fabs(m.bearings[j].x - b.x) < 1e-9);
    Solution::Reaction r;
    if (!shared) {
      r.Fy = rigid ? R(d, 0) : -b.radialStiffness * U(d, 0);
      r.Fz = rigid ? R(d, 1) : -b.radialStiffness * U(d, 1);
    }
    s.reactions.push_back(r);
  }
  s.twist = bar(m, s.x, p, true, nodeAt(s.x, m.torsionFixedAt), ft, &s.torque);
  auto held = std::find_if(m.bearings.begin(), m.bearings.end(), [](const Bearing& b) { return b.axialHeld; });
  double thrust = 0;
  for (double f : fx)
    thrust += f;
  if (held == m.bearings.end()) {
    if (thrust != 0)
      throw std::invalid_argument("an axial force acts on the shaft, but no bearing holds it (`axial = held`)");
    s.axial.assign(n, 0.0);
  } else {
    s.axial = bar(m, s.x, p, false, nodeAt(s.x, held->x), fx, nullptr);
    s.reactions[static_cast<size_t>(held - m.bearings.begin())].Fx = -thrust;
  }
  // Each element's end moments (sagging positive); a station takes its left element's.
  for (size_t e = 0; e + 1 < n; ++e) {
    double L = s.x[e + 1] - s.x[e];
    s.phi.push_back(shearParameter(m, p[e], L));
    Mat4 k = stiffness(m.material.E * p[e].I, L, s.phi.back());
    Eigen::Vector4d ey(s.v[e], s.slopeY[e], s.v[e + 1], s.slopeY[e + 1]),
        ez(s.w[e], s.slopeZ[e], s.w[e + 1], s.slopeZ[e + 1]);
    Eigen::Vector4d fy = k * ey, fz = k * ez;
    if (e == 0) {
      s.momentY.push_back(-fy(1));
      s.momentZ.push_back(-fz(1));
    }
    s.momentY.push_back(fy(3));
    s.momentZ.push_back(fz(3));
    s.startY.push_back(-fy(1));
    s.endY.push_back(fy(3));
    s.startZ.push_back(-fz(1));
    s.endZ.push_back(fz(3));
  }
  return s;
}

std::vector<double> naturalFrequencies(const Model& m, int count) {
  checkModel(m);
  std::vector<double> x = meshNodes(m, true);
  size_t n = x.size();
  Plane pl = bendingPlane(m, x, elementProps(m, x));
  Eigen::MatrixXd K(pl.K), M = Eigen::MatrixXd::Zero(static_cast<int>(2 * n), static_cast<int>(2 * n));
  for (size_t e = 0; e + 1 < n; ++e) {
    double L = x[e + 1] - x[e];
    Props p = props(sectionOf(m, x[e], x[e + 1]), m.material.poisson());
    double rho = m.material.density;
    M.block<4, 4>(static_cast<int>(2 * e), static_cast<int>(2 * e)) +=
        mass(rho * p.A, rho * p.I, L, shearParameter(m, p, L));
  }
  for (const auto& d : m.disks) {
    int i = static_cast<int>(nodeAt(x, d.x));
    M(2 * i, 2 * i) += d.mass;
    M(2 * i + 1, 2 * i + 1) += d.diametralInertia;
  }
  Reduced r(pl.fixed);
  Eigen::MatrixXd Kf(r.n, r.n), Mf(r.n, r.n);
  for (size_t i = 0; i < 2 * n; ++i)
    for (size_t j = 0; j < 2 * n; ++j)
      if (r.free[i] >= 0 && r.free[j] >= 0) {
        Kf(r.free[i], r.free[j]) = K(static_cast<int>(i), static_cast<int>(j));
        Mf(r.free[i], r.free[j]) = M(static_cast<int>(i), static_cast<int>(j));
      }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kf, Mf);
  if (es.info() != Eigen::Success) throw std::invalid_argument("the shaft's natural frequencies could not be found");
  std::vector<double> out;
  for (int i = 0; i < es.eigenvalues().size() && static_cast<int>(out.size()) < count; ++i)
    out.push_back(std::sqrt(std::max(0.0, es.eigenvalues()(i))));
  return out;
}

std::vector<double> torsionalFrequencies(const Model& m, int count) {
  checkModel(m);
  std::vector<double> x = meshNodes(m, true);
  int n = static_cast<int>(x.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e + 1 < n; ++e) {
    double L = x[static_cast<size_t>(e + 1)] - x[static_cast<size_t>(e)];
    Props p = props(sectionOf(m, x[static_cast<size_t>(e)], x[static_cast<size_t>(e + 1)]), m.material.poisson());
    double k = m.material.G * p.J / L, mj = m.material.density * p.J * L / 6;
    K.block<2, 2>(e, e) += k * Eigen::Matrix2d{{1, -1}, {-1, 1}};
    M.block<2, 2>(e, e) += mj * Eigen::Matrix2d{{2, 1}, {1, 2}};
  }
  for (const auto& d : m.disks) {
    int i = static_cast<int>(nodeAt(x, d.x));
    M(i, i) += d.polarInertia;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  if (es.info() != Eigen::Success) throw std::invalid_argument("the shaft's torsional frequencies could not be found");
  std::vector<double> out;
  // The first eigenvalue is the rigid turning (0 up to rounding).
  for (int i = 1; i < es.eigenvalues().size() && static_cast<int>(out.size()) < count; ++i)
    out.push_back(std::sqrt(std::max(0.0, es.eigenvalues()(i))));
  return out;
}

} // namespace gbx::rt::shaft
