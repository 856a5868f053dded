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

// The sun's motion (u, dx, dy) with the given planets in contact: its torque, sum F_i =
// force, and, floating, its force balance, sum F_i n_i = 0, as linear equations.
Eigen::VectorXd sunMotion(const Paths& p, const std::vector<bool>& active, bool floating, double force) {
  const int m = floating ? 3 : 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (size_t i = 0; i < p.eps.size(); ++i) {
    if (!active[i]) continue;
    Eigen::VectorXd w(m); // d F_i / d(u, dx, dy) over k, and the planet's weight in the balance
    w(0) = 1;
    if (floating) w.tail(2) = p.n[i];
    A += p.k * w * w.transpose();
    b += p.k * p.eps[i] * w;
  }
  b(0) += force;
  // Two loaded planets opposite each other leave a floating sun free to slide along their
  // lines: the loads are still determined, the slide is not (the smallest solution is taken).
  Eigen::VectorXd x = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).solve(b);
  if (!((A * x - b).norm() <= 1e-9 * b.norm()))
    throw std::domain_error("a floating sun on fewer than three loaded planets cannot balance their forces");
  return x;
}

// How far planet i's path is pressed by the sun's motion x (negative: open).
double pressed(const Paths& p, size_t i, const Eigen::VectorXd& x, bool floating) {
  return x(0) + (floating ? p.n[i].dot(x.tail(2)) : 0.0) - p.eps[i];
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
  // solve again; a dropped planet whose gap has closed again comes back. Bounded rounds.
  for (int round = 0;; ++round) {
    if (round > 4 * in.planets)
      throw std::domain_error("the planets' contact does not settle (pin errors that exclude each other)");
    Eigen::VectorXd x = sunMotion(p, active, in.floatingSun, in.force);
    F.assign(p.eps.size(), 0.0);
    int back = -1;
    for (size_t i = 0; i < F.size(); ++i) {
      double d = pressed(p, i, x, in.floatingSun);
      if (active[i])
        F[i] = p.k * d;
      else if (back < 0 && d > 1e-12 * in.force / p.k)
        back = static_cast<int>(i);
    }
    auto worst = std::min_element(F.begin(), F.end());
    if (*worst < -1e-12 * in.force)
      active[static_cast<size_t>(worst - F.begin())] = false;
    else if (back >= 0)
      active[static_cast<size_t>(back)] = true;
    else
      break;
  }
  LoadSharing out;
  const double mean = in.force / in.planets;
  for (size_t i = 0; i < F.size(); ++i) {
    out.share.push_back(std::max(F[i], 0.0) / mean);
    if (!active[i] || F[i] <= 1e-12 * in.force) ++out.unloaded; // open, or just touching
  }
  out.Kgamma = *std::max_element(out.share.begin(), out.share.end());
  return out;
}

} // namespace gbx::rt::rating
