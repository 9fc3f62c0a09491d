/// @file pencil.hpp
/// @brief The extreme eigenvalues of a symmetric tridiagonal pencil K x = μ M x (the P1 stiffness and
/// mass), by bisection on Sylvester's inertia count.
#pragma once

#include "core/problem.hpp"
#include "fem/p1.hpp"

namespace mrm {

/// The number of eigenvalues of the pencil (K, M) below μ: the negative pivots of the LDLᵀ
/// factorisation of K − μM (Sylvester's law of inertia), K and M symmetric tridiagonal, M positive
/// definite. A pivot that vanishes counts as negative (μ is then an eigenvalue, counted as below).
Index pencil_eigenvalues_below(const Tridiagonal& stiffness, const Tridiagonal& mass, double mu);

/// The smallest eigenvalue μ of the symmetric tridiagonal pencil K x = μ M x, K and M positive
/// definite, by bisection on Sylvester's inertia count of K − μM (to a relative width 1e-15).
/// Throws std::invalid_argument for sizes that differ, an empty pencil, or a K or M that is not
/// positive definite.
double smallest_eigenvalue(const Tridiagonal& stiffness, const Tridiagonal& mass);

/// The largest eigenvalue of the pencil K x = μ M x (K symmetric, M positive definite tridiagonal), by
/// bisection on the same count to a relative 1e-13; the upper end of the last bracket is returned, a
/// bound never below the eigenvalue by more than that.
double largest_pencil_eigenvalue(const Tridiagonal& stiffness, const Tridiagonal& mass);

}  // namespace mrm
