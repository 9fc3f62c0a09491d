/// @file contact.hpp
/// @brief The contact node: condensation of the massless contact row and the closed-form contact
/// step of one implicit time step (mathematics.md §3–§4).
#pragma once

#include "fem/p1.hpp"

namespace mrm {

/// The algebraic contact row of the redistributed problem (paper eq. (6)) solved for the massless
/// contact node given u₁: u₀ = max(0, u₁ + h F₀) and λ = min(0, F₀ + u₁/h).
struct CondensedContact {
  double u0;          ///< the contact-node displacement u₀ ≥ 0
  double multiplier;  ///< the contact stress λ ≤ 0
};
/// The massless contact node's row solved in closed form (see CondensedContact): u₀ = max(g, u₁ + h F₀),
/// λ = min(0, F₀ + (u₁ − g)/h), for the node-1 value `u1`, the compliance `h` of the contact element
/// (1/S₀₀: the mesh size on the paper's mesh, h₀/E₀ in general), the node-0 load `load0` and the
/// obstacle g (0; −gap with a gap).
CondensedContact condense_contact_node(double u1, double h, double load0, double obstacle = 0.0);

/// The outcome of a contact step: the contact-node value, the multiplier λ ≤ 0 and whether the
/// constraint is active.
struct ContactStep {
  double u0;          ///< the new contact-node value u₀
  double multiplier;  ///< the multiplier λ ≤ 0 (0 when the constraint is inactive)
  bool active;        ///< whether u₀ sits on the obstacle (λ may then be < 0)
};

/// Solves A U = b − κ λ e₀ with 0 ≤ u₀ − g ⊥ λ ≤ 0 (g the obstacle position, 0 except for a
/// restitution e > 0), for a tridiagonal A whose elimination from node n−1 down to node 0 has positive
/// pivots (A symmetric positive definite, or such a matrix with row 0 rescaled). The factorisation is
/// done once; each solve is one sweep down and one sweep up, with the contact decided at the last
/// pivot, which is the Schur complement of A onto the contact node.
class ContactSolver {
 public:
  ContactSolver() = default;
  /// Factorises A; throws std::invalid_argument if a pivot is not positive.
  explicit ContactSolver(const Tridiagonal& a);

  /// Solves for u (size n) given b (size n); u may alias b. Throws std::invalid_argument unless
  /// kappa > 0 (finite) and a matrix has been factorised.
  ContactStep solve(const double* b, double* u, double kappa, double obstacle = 0.0) const;

  /// The two halves of solve() for a step that decides the contact itself (the energy-conserving
  /// scheme, schemes.cpp): sweep_down writes y (size n; may alias b) with y₀ the reduced contact row;
  /// sweep_up turns y into u (in place) starting from u₀ = `u0` (no check of the contact).
  void sweep_down(const double* b, double* y) const;
  void sweep_up(double u0, double* y) const;  ///< see sweep_down

  /// The pivot d₀ = 1/(A⁻¹)₀₀, the Schur complement of A onto the contact node.
  double schur_complement() const { return pivot_[0]; }
  /// The dimension n of the factorised matrix (0 before a factorisation).
  Index size() const { return pivot_.size(); }

  // The factors, for fused time-stepping kernels that do the sweeps themselves:
  // sweep down  y_{n−1} = b_{n−1}, y_i = b_i − elimination_[i] y_{i+1};
  // contact     d₀ u₀ = y₀ − κ λ;
  // sweep up    u_i = (y_i − lower_[i] u_{i−1}) · inverse_pivot_[i]
  //                 = inverse_pivot_[i] y_i − upward_[i] u_{i−1},   upward_[i] = lower_[i] / d_i.
  // The second form of the sweep up is the one used (solve() and the schemes): its chain of
  // dependent operations from u_{i−1} to u_i is one multiplication and one subtraction.
  const Eigen::VectorXd& elimination() const { return elimination_; }      ///< ε_i of the sweep down
  const Eigen::VectorXd& inverse_pivot() const { return inverse_pivot_; }  ///< 1/d_i
  const Eigen::VectorXd& lower() const { return lower_; }                  ///< the subdiagonal of A
  const Eigen::VectorXd& upward() const { return upward_; }                ///< c_i = lower_i/d_i of the sweep up
  // The same recurrences substituted into themselves, two nodes at a time:
  //   y_i = (b_i − ε_i b_{i+1}) + elimination_pair_[i] y_{i+2},          elimination_pair_[i] = ε_i ε_{i+1},
  //   u_i = (z_i − c_i z_{i−1}) + upward_pair_[i] u_{i−2},  z_i = y_i/d_i,  upward_pair_[i] = c_i c_{i−1},
  // so that each sweep is two independent chains (even and odd nodes) of half the length: the
  // schemes' fused step uses this form (fast_step.cpp), solve() the plain one.
  const Eigen::VectorXd& elimination_pair() const { return elimination_pair_; }  ///< ε_i ε_{i+1}
  const Eigen::VectorXd& upward_pair() const { return upward_pair_; }            ///< c_i c_{i−1}
  /// The contact decision on the reduced row d₀ u₀ = y₀ − κ λ.
  ContactStep resolve_contact(double y0, double kappa, double obstacle) const;

 private:
  Eigen::VectorXd pivot_, inverse_pivot_, elimination_, lower_, upward_, elimination_pair_, upward_pair_;
};

/// A verification solve, not a step of the schemes: A U + κ λ e₀ = b with the active set fixed, the
/// last row u₀ = g (`active`) or λ = 0, as one (N + 1) × (N + 1) saddle-point system in (U, λ)
/// assembled from triplets and solved by Eigen's sparse LU. Returns (U, λ) (size N + 1). The doctests
/// of the closed-form contact step and the harness's claims check the step against it. Throws
/// std::runtime_error if the factorisation or the solve fails.
Eigen::VectorXd saddle_point_solve(const Tridiagonal& a, const Eigen::VectorXd& b, double kappa, double obstacle,
                                   bool active);

}  // namespace mrm
