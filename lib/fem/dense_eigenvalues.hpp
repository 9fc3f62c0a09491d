/// @file dense_eigenvalues.hpp
/// @brief Reference eigenvalues of small dense matrices (LAPACK-style QR iterations, through GSL), the
/// yardstick of the doctests that check a bisection, a step limit or a spectrum derived in closed form.
#pragma once

#include <Eigen/Core>

namespace mrm {

/// The eigenvalues of a symmetric matrix A, ascending (tridiagonalisation and implicit symmetric QR:
/// each within a modest multiple of ε‖A‖ of the exact one). Throws std::runtime_error if the iteration
/// does not converge.
Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& a);

/// The eigenvalues μ of the symmetric-definite pencil K x = μ M x, ascending (Cholesky M = LLᵀ, then the
/// symmetric L⁻¹ K L⁻ᵀ). Throws std::runtime_error if M is not positive definite or the iteration does
/// not converge.
Eigen::VectorXd generalized_symmetric_eigenvalues(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m);

/// The eigenvalues of a general real square matrix A (Hessenberg reduction and the real Schur form),
/// complex, in the order of the Schur form's diagonal blocks. Throws std::runtime_error if the iteration
/// does not converge.
Eigen::VectorXcd general_eigenvalues(const Eigen::MatrixXd& a);

}  // namespace mrm
