/// @file pencil.cpp
/// @brief The extreme eigenvalues of a symmetric tridiagonal pencil by bisection on an inertia count.
///
/// K − μM is symmetric tridiagonal; by Sylvester's law of inertia the number of negative pivots of its
/// LDLᵀ factorisation, d₀ = a₀, d_i = a_i − b_i²/d_{i−1}, is the number of eigenvalues of the pencil
/// (K, M) below μ (M positive definite). Bisection on that count between a lower bound and an upper
/// bound of the k-th eigenvalue halves the bracket in O(N) per step, for any N: the smallest (k = 1)
/// starts from 0 (K positive definite) and the Rayleigh quotient of the vector of ones, the largest
/// (k = N) from 0 and the first power of 2 above it.
#include "fem/pencil.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace mrm {

Index pencil_eigenvalues_below(const Tridiagonal& k, const Tridiagonal& m, double mu) {
  Index count = 0;
  double d = 1.0;
  // A pivot that vanishes is replaced by a tiny negative one (the usual safeguard: it counts as an
  // eigenvalue at μ).
  const double tiny = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  for (Index i = 0; i < k.size(); ++i) {
    const double a = k.diag[i] - mu * m.diag[i];
    if (i == 0) {
      d = a;
    } else {
      const double b = k.lower[i] - mu * m.lower[i];
      d = a - b * b / d;
    }
    if (std::abs(d) < tiny) d = -tiny;
    if (d < 0) ++count;
  }
  return count;
}

namespace {

bool positive_definite(const Tridiagonal& a) {
  const Tridiagonal zero(a.size());
  for (Index i = 0; i < a.size(); ++i)
    if (a.lower[i] != (i > 0 ? a.upper[i - 1] : 0.0)) return false;
  return pencil_eigenvalues_below(a, zero, 0.0) == 0;
}

// The bisection for the k-th eigenvalue (k = 1, 2, …) from the bracket [lo, hi] until hi − lo ≤
// width·hi (at most 200 halvings): a midpoint with at least k eigenvalues below it is the new upper end.
struct Bracket {
  double lo, hi;
};
Bracket bisect(const Tridiagonal& k, const Tridiagonal& m, Index which, Bracket b, double width) {
  for (int iteration = 0; iteration < 200 && b.hi - b.lo > width * b.hi; ++iteration) {
    const double mid = 0.5 * (b.lo + b.hi);
    (pencil_eigenvalues_below(k, m, mid) >= which ? b.hi : b.lo) = mid;
  }
  return b;
}

}  // namespace

double smallest_eigenvalue(const Tridiagonal& stiffness, const Tridiagonal& mass) {
  if (stiffness.size() != mass.size() || stiffness.size() < 1)
    throw std::invalid_argument("smallest_eigenvalue: K and M must have the same size >= 1 (got " +
                                std::to_string(stiffness.size()) + " and " + std::to_string(mass.size()) + ")");
  if (!positive_definite(stiffness) || !positive_definite(mass))
    throw std::invalid_argument("smallest_eigenvalue: K and M must be symmetric positive definite");
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(stiffness.size());
  double hi = stiffness.bilinear(ones, ones) / mass.bilinear(ones, ones);
  while (pencil_eigenvalues_below(stiffness, mass, hi) < 1) hi *= 2;  // the quotient is a bound; round-off aside
  const Bracket b = bisect(stiffness, mass, 1, {0.0, hi}, 1e-15);
  return 0.5 * (b.lo + b.hi);
}

double largest_pencil_eigenvalue(const Tridiagonal& stiffness, const Tridiagonal& mass) {
  const Index n = stiffness.size();
  double hi = 1.0;
  while (pencil_eigenvalues_below(stiffness, mass, hi) < n) hi *= 2;
  return bisect(stiffness, mass, n, {0.0, hi}, 1e-13).hi;
}

}  // namespace mrm
