/// @file p1.hpp
/// @brief Uniform mesh of (0, L), tridiagonal matrices and the P1 mass and stiffness matrices.
///
/// mathematics.md §3: nodes x_i = i h, h = L/N, i = 0..N; node 0 is the contact node, node N is clamped.
/// The unknowns of every discrete problem of this library are the values at nodes 0..N-1.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace mrm {

/// The index type of vectors, matrices and meshes (Eigen's signed index).
using Index = Eigen::Index;

/// The uniform mesh x_i = i h, h = L/N, of the bar (0, L).
struct UniformMesh {
  /// Builds the mesh; throws std::invalid_argument unless L > 0 (finite) and N >= 2.
  UniformMesh(double length, Index elements);

  double length;   ///< L
  Index elements;  ///< N
  /// The mesh size h = L/N.
  double h() const { return length / static_cast<double>(elements); }
  /// The node x_i = i L/N (computed as L i/N, exact at i = N).
  double x(Index i) const { return length * static_cast<double>(i) / static_cast<double>(elements); }
  /// The number of unknowns, N: the nodes 0..N-1 (node N is clamped and eliminated).
  Index unknowns() const { return elements; }
};

/// A tridiagonal matrix stored by its three diagonals: `lower[i]` = A(i, i-1), `diag[i]` = A(i, i),
/// `upper[i]` = A(i, i+1); `lower[0]` and `upper[n-1]` are zero. Symmetric matrices have
/// `lower[i+1] == upper[i]`.
struct Tridiagonal {
  Eigen::VectorXd lower;  ///< the subdiagonal: lower[i] = A(i, i−1), lower[0] = 0
  Eigen::VectorXd diag;   ///< the diagonal: diag[i] = A(i, i)
  Eigen::VectorXd upper;  ///< the superdiagonal: upper[i] = A(i, i+1), upper[n−1] = 0

  /// The n×n zero matrix.
  explicit Tridiagonal(Index n = 0)
      : lower(Eigen::VectorXd::Zero(n)), diag(Eigen::VectorXd::Zero(n)), upper(Eigen::VectorXd::Zero(n)) {}
  /// The dimension n.
  Index size() const { return diag.size(); }
  // The operations below throw std::invalid_argument for an operand whose size is not size(), an
  // index outside [0, size()), and a block size outside [1, size()].
  /// The entry A(i, j) (zero outside the three diagonals).
  double operator()(Index i, Index j) const;
  /// y = A x.
  Eigen::VectorXd operator*(const Eigen::VectorXd& x) const;
  /// xᵀ A y.
  double bilinear(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const;
  /// 1ᵀ A 1, the sum of all entries.
  double sum() const;
  /// The leading n×n block (used to drop the clamped node N).
  Tridiagonal leading_block(Index n) const;
  /// c A.
  Tridiagonal scaled(double c) const;
  /// A + c B.
  Tridiagonal plus(double c, const Tridiagonal& b) const;
  /// The same matrix in Eigen's sparse format (for general-purpose solvers and checks).
  Eigen::SparseMatrix<double> to_sparse() const;
};

/// P1 mass matrix M_ij = ∫ φ_i φ_j dx on all nodes 0..N (size N+1, clamped node included).
Tridiagonal p1_mass_all_nodes(const UniformMesh& mesh);
/// P1 stiffness matrix S_ij = ∫ φ_i' φ_j' dx on all nodes 0..N (size N+1).
Tridiagonal p1_stiffness_all_nodes(const UniformMesh& mesh);
/// The stiffness matrix S on the unknowns 0..N-1 (clamped node eliminated).
Tridiagonal p1_stiffness(const UniformMesh& mesh);
/// The consistent mass matrix M on the unknowns 0..N-1 (clamped node eliminated).
Tridiagonal p1_mass(const UniformMesh& mesh);

/// The load vector F_i = ∫ f(x) φ_i(x) dx on the unknowns 0..N-1, by two-point Gauss quadrature on
/// each element (exact for f of degree ≤ 2), written into `load` (resized to N if needed: a time loop
/// that reuses its vector does not allocate). Throws std::invalid_argument if f is not finite at a
/// quadrature point.
template <class Load>
void p1_load(const UniformMesh& mesh, Load&& f, Eigen::VectorXd& load) {
  const Index n = mesh.unknowns();
  load.setZero(n);
  const double h = mesh.h();
  const double g = 0.5 / 1.7320508075688772935;  // Gauss points at the element's centre ± h/(2√3)
  for (Index e = 0; e < mesh.elements; ++e) {
    const double xl = mesh.x(e);
    for (double xi : {0.5 - g, 0.5 + g}) {
      const double x = xl + xi * h, fx = f(x) * 0.5 * h;
      if (!std::isfinite(fx))
        throw std::invalid_argument("p1_load: the load f(x) is not finite at x = " + std::to_string(x) +
                                    " (allowed: finite values)");
      load[e] += fx * (1.0 - xi);
      if (e + 1 < n) load[e + 1] += fx * xi;
    }
  }
}

/// The load vector as above, returned.
template <class Load>
Eigen::VectorXd p1_load(const UniformMesh& mesh, Load&& f) {
  Eigen::VectorXd load;
  p1_load(mesh, std::forward<Load>(f), load);
  return load;
}

}  // namespace mrm
