/// @file step_pieces.hpp
/// @brief The pieces that the contact classes' steps share (newmark_type.cpp, moreau_jean.cpp, dke.cpp):
/// a solve without contact, the kinetic and strain energy, a row of a tridiagonal product, the sweep
/// down with its right-hand side formed on the way, the finiteness check. Internal to lib/classes/.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "classes/class_step.hpp"
#include "steps/contact.hpp"

namespace mrm::class_steps {

/// A solve with a factorised matrix and no contact: the sweep down, u₀ from the reduced row, the sweep up.
inline void solve_free(const ContactSolver& solver, Eigen::VectorXd& x) {
  solver.sweep_down(x.data(), x.data());
  solver.sweep_up(x[0] * solver.inverse_pivot()[0], x.data());
}

/// The discrete energy ½ VᵀMV + ½ UᵀSU of a level (each class adds its contact law's own part, if any).
/// Tridiagonal::form is xᵀAx in one pass without a product vector, the bits of bilinear(x, x) (p1.cpp).
inline double kinetic_and_strain(const Tridiagonal& mass, const Tridiagonal& stiffness, const StepState& s) {
  return 0.5 * mass.form(s.w) + 0.5 * stiffness.form(s.u);
}

/// (A x)_i as Tridiagonal::multiply sums it: (A_ii x_i + A_{i,i−1} x_{i−1}) + A_{i,i+1} x_{i+1}, the terms
/// that exist, in this order (the fused steps below form their products row by row with these bits).
inline double row_product(const Tridiagonal& a, const double* x, Index i, Index n) {
  double s = a.diag[i] * x[i];
  if (i > 0) s += a.lower[i] * x[i - 1];
  if (i + 1 < n) s += a.upper[i] * x[i + 1];
  return s;
}
/// The same for an interior row, 0 < i < n − 1, read from raw diagonals (no test per row).
inline double interior_row(const double* d, const double* lo, const double* up, const double* x, Index i) {
  double s = d[i] * x[i];
  s += lo[i] * x[i - 1];
  s += up[i] * x[i + 1];
  return s;
}

/// The sweep down of the solver's A (contact.cpp: y_{n−1} = b_{n−1}, y_i = b_i − ε_i y_{i+1}) with b formed
/// row by row: b_row(i, P_i, Q_i) from the two matrix–vector rows (P x)_i and (Q y)_i, row_product at the
/// last row and interior_row on rows n − 2 … 1; b0, row 0's, is the caller's (a massless node's differs).
template <class Row>
inline void sweep_down_forming(const ContactSolver& solver, Index n, double* y, const Tridiagonal& p_matrix,
                               const double* x, const Tridiagonal& q_matrix, const double* z, const Row& b_row,
                               double b0) {
  const double* eps = solver.elimination().data();
  const double *pd = p_matrix.diag.data(), *pl = p_matrix.lower.data(), *pu = p_matrix.upper.data();
  const double *qd = q_matrix.diag.data(), *ql = q_matrix.lower.data(), *qu = q_matrix.upper.data();
  double yi = b_row(n - 1, row_product(p_matrix, x, n - 1, n), row_product(q_matrix, z, n - 1, n));
  y[n - 1] = yi;
  for (Index i = n - 2; i > 0; --i) {
    yi = b_row(i, interior_row(pd, pl, pu, x, i), interior_row(qd, ql, qu, z, i)) - eps[i] * yi;
    y[i] = yi;
  }
  y[0] = b0 - eps[0] * yi;
}

/// Throws std::runtime_error naming the scheme (its registry id) and the level when the discrete energy is
/// not finite.
inline void require_finite(double energy, const std::string& id, Index level) {
  if (!std::isfinite(energy))
    throw std::runtime_error("scheme " + id + ": the run lost finiteness at level " + std::to_string(level) +
                             " (the discrete energy is not finite)");
}

/// The step of a Newmark-type class (newmark, penalty, nitsche: newmark_type.cpp); `id` its registry id, for its messages.
std::unique_ptr<ContactClassStep> make_newmark_type_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                         const SchemeParameters& p, double dt, double h, bool has_load,
                                                         double gap, const std::string& id);
/// The step of Moreau–Jean (moreau_jean.cpp).
std::unique_ptr<ContactClassStep> make_moreau_jean_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                        const SchemeParameters& p, double dt, bool has_load, double gap,
                                                        const std::string& id);
/// The step of DKE (dke.cpp).
std::unique_ptr<ContactClassStep> make_dke_step(const Tridiagonal& mass, const Tridiagonal& stiffness, double dt,
                                                bool has_load, double gap, bool fused, const std::string& id);

}  // namespace mrm::class_steps
