/// @file dense_eigenvalues.cpp
/// @brief Reference eigenvalues of small dense matrices, through Eigen's eigensolvers.
///
/// The three solvers are instantiated here once: each is a large template (the nonsymmetric one adds
/// about 25 s of compilation to any file that uses it), and the doctests of several files use them only
/// as a reference, on matrices of a few hundred rows.
#include "fem/dense_eigenvalues.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <doctest/doctest.h>

namespace mrm {

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw std::runtime_error("symmetric_eigenvalues: no convergence");
  return solver.eigenvalues();
}

Eigen::VectorXd generalized_symmetric_eigenvalues(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m) {
  // Eigen's solver factorises M without reporting a pivot ≤ 0: the factorisation is checked first.
  if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success)
    throw std::runtime_error("generalized_symmetric_eigenvalues: M is not positive definite");
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, m, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw std::runtime_error("generalized_symmetric_eigenvalues: no convergence");
  return solver.eigenvalues();
}

Eigen::VectorXcd general_eigenvalues(const Eigen::MatrixXd& a) {
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(a, false);
  if (solver.info() != Eigen::Success) throw std::runtime_error("general_eigenvalues: no convergence");
  return solver.eigenvalues();
}

// The three on matrices whose spectra are known in closed form: the second difference matrix
// tridiag(−1, 2, −1) of size n has the eigenvalues 2 − 2 cos(jπ/(n+1)), j = 1..n; the pencil
// (2A, 2I) has the same; a rotation by θ has e^{±iθ}.
TEST_CASE("the reference eigenvalues reproduce spectra known in closed form") {
  const Eigen::Index n = 12;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    a(i, i) = 2;
    if (i > 0) a(i, i - 1) = a(i - 1, i) = -1;
  }
  const double pi = 3.14159265358979323846;
  const Eigen::VectorXd symmetric = symmetric_eigenvalues(a);
  const Eigen::VectorXd pencil = generalized_symmetric_eigenvalues(2 * a, 2 * Eigen::MatrixXd::Identity(n, n));
  for (Eigen::Index j = 1; j <= n; ++j) {
    const double exact = 2 - 2 * std::cos(j * pi / (n + 1));
    CHECK(std::abs(symmetric[j - 1] - exact) <= 1e-14);
    CHECK(std::abs(pencil[j - 1] - exact) <= 1e-14);
  }
  const double theta = 0.3;
  Eigen::MatrixXd rotation(2, 2);
  rotation << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  const Eigen::VectorXcd general = general_eigenvalues(rotation);
  CHECK(std::abs(std::abs(general[0].imag()) - std::sin(theta)) <= 1e-15);
  CHECK(std::abs(general[0].real() - std::cos(theta)) <= 1e-15);
  CHECK(std::abs(general[1] - std::conj(general[0])) <= 1e-15);
  CHECK_THROWS_AS(generalized_symmetric_eigenvalues(a, -Eigen::MatrixXd::Identity(n, n)), std::runtime_error);
}

}  // namespace mrm
