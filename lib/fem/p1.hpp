/// @file p1.hpp
/// @brief Uniform mesh of (0, L), tridiagonal matrices and the P1 mass and stiffness matrices.
///
/// mathematics.md §3: nodes x_i = i h, h = L/N, i = 0..N; node 0 is the contact node, node N is clamped.
/// The unknowns of every discrete problem of this library are the values at nodes 0..N-1.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/problem.hpp"

namespace mrm {

/// The condition at the far end x = L: held (u(L) = 0, node N eliminated) or free (σ(L) = 0, node N
/// an unknown).
enum class FarEnd { clamped, free };

/// The mesh of the bar (0, L) and its material. By default the uniform mesh x_i = i h, h = L/N, of a
/// homogeneous bar (E = ρ = 1, unit wave speed) clamped at x = L: the mesh of the paper. Three extensions,
/// each off by default so that the default mesh is the paper's, bit for bit (the field's benchmarks of
/// doc/benchmarks.md use the last two): a graded mesh (graded_mesh: element sizes h_k = h₀ r^k, finer toward
/// the contact for r > 1), piecewise-constant material (with_material: E_e and ρ_e per element) and a free
/// far end (with_far_end). The name says the default: "uniform" is the paper's mesh, uniform() says whether
/// this one is.
struct UniformMesh {
  /// Builds the uniform mesh; throws std::invalid_argument unless L > 0 (finite) and N >= 2.
  UniformMesh(double length, Index elements);

  double length;                     ///< L
  Index elements;                    ///< N
  FarEnd far_end = FarEnd::clamped;  ///< the condition at x = L

  /// The mesh size h = L/N of a uniform mesh. Throws std::logic_error on a graded mesh, where no single
  /// h exists (use h(e), or contact_compliance() for the contact row): a formula written for the
  /// uniform mesh must not run silently on another one.
  double h() const {
    if (!nodes_.empty())
      throw std::logic_error("mesh: h() asked of a graded mesh (allowed: h(e), the size of element e)");
    return length / static_cast<double>(elements);
  }
  /// The size h_e = x_{e+1} − x_e of element e (h() on a uniform mesh, the same double).
  double h(Index e) const {
    return nodes_.empty() ? length / static_cast<double>(elements) : nodes_[e + 1] - nodes_[e];
  }
  /// The node x_i (uniform: computed as L i/N, exact at i = N).
  double x(Index i) const {
    return nodes_.empty() ? length * static_cast<double>(i) / static_cast<double>(elements) : nodes_[i];
  }
  /// The number of unknowns: N (nodes 0..N−1, node N clamped and eliminated) or N + 1 (free far end).
  Index unknowns() const { return far_end == FarEnd::clamped ? elements : elements + 1; }
  /// Whether all elements have the size L/N.
  bool uniform() const { return nodes_.empty(); }
  /// Whether E = ρ = 1 on every element.
  bool homogeneous() const { return young_.empty(); }
  /// Young's modulus E_e of element e (1 for a homogeneous bar).
  double young(Index e) const { return young_.empty() ? 1.0 : young_[e]; }
  /// The density ρ_e of element e (1 for a homogeneous bar).
  double density(Index e) const { return density_.empty() ? 1.0 : density_[e]; }
  /// 1/S₀₀ = h₀/E₀, the compliance of the contact element: the massless contact row S₀₀(u₀ − u₁) = F₀ − λ
  /// gives u₀ = u₁ + (h₀/E₀)F₀ (contact.cpp). h() on the paper's mesh (the same double).
  double contact_compliance() const { return uniform() && homogeneous() ? h() : h(0) / young(0); }
  /// The mass of the bar, Σ ρ_e h_e (L on a homogeneous bar, returned as L).
  double bar_mass() const;

  // Set by graded_mesh and with_material, which check them.
  std::vector<double> nodes_;    ///< the nodes x_0..x_N of a graded mesh (empty: uniform)
  std::vector<double> young_;    ///< E_e per element (empty: E = 1)
  std::vector<double> density_;  ///< ρ_e per element (empty: ρ = 1)
};

/// The mesh of (0, L) with N elements of sizes h_k = h₀ r^k, k = 0..N−1, h₀ = L(r − 1)/(rᴺ − 1)
/// (h₀ = L/N for r = 1, which returns the uniform mesh itself); the nodes are the partial sums, the
/// last one set to L. Throws std::invalid_argument unless r > 0 is finite (and N, L as for the mesh).
UniformMesh graded_mesh(double length, Index elements, double ratio);
/// The mesh with E_e = young[e], ρ_e = density[e] (N values each, positive and finite; otherwise
/// std::invalid_argument naming what is wrong).
UniformMesh with_material(UniformMesh mesh, std::vector<double> young, std::vector<double> density);
/// The mesh with the far-end condition `far_end`.
UniformMesh with_far_end(UniformMesh mesh, FarEnd far_end);

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
  /// y = A x into a vector the caller keeps (resized if needed; no allocation when it has size()
  /// entries already), the same arithmetic as operator*, bit for bit; `y` must not be `x`.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// xᵀ A y.
  double bilinear(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const;
  /// xᵀ A x in one pass, without the product vector: the same bits as bilinear(x, x).
  double form(const Eigen::VectorXd& x) const;
  /// The same for the vector x_i = x[i·stride], i < size() (e.g. a run's lane in a batch): the same
  /// operations in the same order, so the same bits as form of that vector. Sizes are not checked.
  double form(const double* x, std::size_t stride) const;
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
/// The blended interior mass M^A = (1 − A) M + A M_L on all nodes 0..N, M_L the row-sum lumped mass
/// (lib/fem/interior_mass.hpp): per element of mass m = ρ_e h_e the matrix
/// m/6 [2 + A, 1 − A; 1 − A, 2 + A]. A = 0 returns p1_mass_all_nodes itself (the same doubles), A = 1 the
/// lumped mass. Throws std::invalid_argument unless 0 ≤ A ≤ 1.
Tridiagonal p1_blended_mass_all_nodes(const UniformMesh& mesh, double blend);
/// P1 stiffness matrix S_ij = ∫ φ_i' φ_j' dx on all nodes 0..N (size N+1).
Tridiagonal p1_stiffness_all_nodes(const UniformMesh& mesh);
/// The stiffness matrix S on the unknowns 0..N-1 (clamped node eliminated).
Tridiagonal p1_stiffness(const UniformMesh& mesh);
/// The consistent mass matrix M on the unknowns 0..N-1 (clamped node eliminated).
Tridiagonal p1_mass(const UniformMesh& mesh);
/// UᵀSV for the P1 stiffness on the unknowns 0..N−1, summed element by element (node N clamped, or an
/// unknown at a free far end): Σ_e (E_e/h_e) Δu_e Δv_e, as Σ Δu Δv / h on the paper's mesh. The same number
/// as S's bilinear form, without cancelling the terms 2u_i²/h against −2u_{i−1}u_i/h (whose sizes grow like
/// N² times the energy): the schemes' energies use it.
double stiffness_form(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const UniformMesh& mesh);

/// The load vector F_i = ∫ f(x) φ_i(x) dx on the unknowns, by two-point Gauss quadrature on each
/// element (exact for f of degree ≤ 2 on each element, so for a piecewise-quadratic f whose pieces
/// meet at nodes), written into `load` (resized if needed: a time loop that reuses its vector does not
/// allocate). Throws std::invalid_argument if f is not finite at a quadrature point.
template <class Load>
void p1_load(const UniformMesh& mesh, Load&& f, Eigen::VectorXd& load) {
  const Index n = mesh.unknowns();
  load.setZero(n);
  const double g = 0.5 / 1.7320508075688772935;  // Gauss points at the element's centre ± h/(2√3)
  for (Index e = 0; e < mesh.elements; ++e) {
    const double xl = mesh.x(e), h = mesh.h(e);
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
