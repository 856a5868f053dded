#include "rating/LoadSharing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace gbx::rt::rating {

namespace {

// The unknowns: the sun's turn as a displacement along its lines of action u, and, floating,
// its translation (dx, dy). Planet i carries k (u + d.n_i - eps_i) while that is positive;
// n_i is the sun-planet line of action at the planet's position angle psi_i.
struct Paths {
  std::vector<double> eps; // each path's error along the lines of action [m]
  std::vector<Eigen::Vector2d> n;
  double k = 0;
};

Paths pathsOf(const LoadSharingInput& in) {
  Paths p;
  p.k = in.kSun * in.kRing / (in.kSun + in.kRing);
  const double project = std::cos(in.alphaSun) + std::cos(in.alphaRing);
  for (int i = 0; i < in.planets; ++i) {
    double psi = 2 * std::numbers::pi * i / in.planets;
    Eigen::Vector2d t(-std::sin(psi), std::cos(psi)), r(std::cos(psi), std::sin(psi));
    p.n.push_back(std::cos(in.alphaSun) * t + std::sin(in.alphaSun) * r);
    double e = static_cast<size_t>(i) < in.pinError.size() ? in.pinError[static_cast<size_t>(i)] : 0.0;
    p.eps.push_back(e * project);
  }
  return p;
}

// The loads with the given planets in contact: the sun's torque (and, floating, its force
// balance) as linear equations in (u, dx, dy).
std::vector<double> loadsWith(const Paths& p, const std::vector<bool>& active, bool floating, double force) {
  const int m = floating ? 3 : 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (size_t i = 0; i < p.eps.size(); ++i) {
    if (!active[i]) continue;
    Eigen::VectorXd row(m); // d F_i / d(u, dx, dy) over k
    row(0) = 1;
    if (floating) row.tail(2) = p.n[i];
    // Torque: sum F_i = force; force balance: sum F_i n_i = 0.
    Eigen::VectorXd weight(m);
    weight(0) = 1;
    if (floating) weight.tail(2) = p.n[i];
    A += p.k * weight * row.transpose();
    b += p.k * p.eps[i] * weight;
  }
  b(0) += force;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.rank() < m) throw std::domain_error("a floating sun needs at least three loaded planets not all in a line");
  Eigen::VectorXd x = lu.solve(b);
  std::vector<double> F(p.eps.size(), 0.0);
  for (size_t i = 0; i < p.eps.size(); ++i) {
    if (!active[i]) continue;
    double d = floating ? p.n[i].dot(x.tail(2)) : 0.0;
    F[i] = p.k * (x(0) + d - p.eps[i]);
  }
  return F;
}

} // namespace

LoadSharing shareLoad(const LoadSharingInput& in) {
  if (in.planets < 1) throw std::domain_error("load sharing needs at least one planet");
  if (!(in.kSun > 0 && in.kRing > 0)) throw std::domain_error("load sharing needs both meshes' stiffness");
  if (!(in.force > 0)) throw std::domain_error("load sharing needs a positive load");
  const Paths p = pathsOf(in);
  std::vector<bool> active(p.eps.size(), true);
  std::vector<double> F;
  // A planet whose path would carry a pull has lost contact: drop the most negative and
  // solve again (each round removes one planet, so at most `planets` rounds).
  for (;;) {
    F = loadsWith(p, active, in.floatingSun, in.force);
    auto worst = std::min_element(F.begin(), F.end());
    if (*worst >= -1e-12 * in.force) break;
    active[static_cast<size_t>(worst - F.begin())] = false;
  }
  LoadSharing out;
  const double mean = in.force / in.planets;
  for (size_t i = 0; i < F.size(); ++i) {
    out.share.push_back(std::max(F[i], 0.0) / mean);
    if (!active[i]) ++out.unloaded;
  }
  out.Kgamma = *std::max_element(out.share.begin(), out.share.end());
  return out;
}

} // namespace gbx::rt::rating
