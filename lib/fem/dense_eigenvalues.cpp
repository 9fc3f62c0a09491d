/// @file dense_eigenvalues.cpp
/// @brief Reference eigenvalues of small dense matrices, through GSL's eigensystems.
///
/// GSL's routines are compiled once, in GSL: the doctests of several files use them only as a reference,
/// on matrices of a few hundred rows, and Eigen's eigensolvers, being templates, cost every build about
/// 15 s of compilation of this file for the same answers.
#include "fem/dense_eigenvalues.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <doctest/doctest.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>

#include "core/constants.hpp"

namespace mrm {

namespace {

/// A copy of A in GSL's row-major storage, and its view as a gsl_matrix (which the routines overwrite).
struct GslMatrix {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> data;
  gsl_matrix_view view;
  explicit GslMatrix(const Eigen::MatrixXd& a)
      : data(a),
        view(gsl_matrix_view_array(data.data(), static_cast<size_t>(a.rows()), static_cast<size_t>(a.cols()))) {}
  GslMatrix(const GslMatrix&) = delete;
  GslMatrix& operator=(const GslMatrix&) = delete;
};

void require_square(const Eigen::MatrixXd& a, const char* name) {
  if (a.rows() != a.cols() || a.rows() == 0) throw std::invalid_argument(std::string(name) + ": not a square matrix");
}

}  // namespace

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& a) {
  require_square(a, "symmetric_eigenvalues");
  gsl_set_error_handler_off();  // a failure is the returned status, reported below
  GslMatrix copy(a);
  Eigen::VectorXd eigenvalues(a.rows());
  gsl_vector_view values = gsl_vector_view_array(eigenvalues.data(), static_cast<size_t>(a.rows()));
  gsl_eigen_symm_workspace* work = gsl_eigen_symm_alloc(static_cast<size_t>(a.rows()));
  const int status = gsl_eigen_symm(&copy.view.matrix, &values.vector, work);
  gsl_eigen_symm_free(work);
  if (status != GSL_SUCCESS) throw std::runtime_error("symmetric_eigenvalues: no convergence");
  std::sort(eigenvalues.begin(), eigenvalues.end());
  return eigenvalues;
}

Eigen::VectorXd generalized_symmetric_eigenvalues(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m) {
  require_square(k, "generalized_symmetric_eigenvalues");
  if (m.rows() != k.rows() || m.cols() != k.cols())
    throw std::invalid_argument("generalized_symmetric_eigenvalues: K and M differ in size");
  gsl_set_error_handler_off();
  GslMatrix k_copy(k), m_copy(m);
  Eigen::VectorXd eigenvalues(k.rows());
  gsl_vector_view values = gsl_vector_view_array(eigenvalues.data(), static_cast<size_t>(k.rows()));
  gsl_eigen_gensymm_workspace* work = gsl_eigen_gensymm_alloc(static_cast<size_t>(k.rows()));
  // GSL factorises M = LLᵀ first and returns GSL_EDOM if a pivot is ≤ 0.
  const int status = gsl_eigen_gensymm(&k_copy.view.matrix, &m_copy.view.matrix, &values.vector, work);
  gsl_eigen_gensymm_free(work);
  if (status == GSL_EDOM) throw std::runtime_error("generalized_symmetric_eigenvalues: M is not positive definite");
  if (status != GSL_SUCCESS) throw std::runtime_error("generalized_symmetric_eigenvalues: no convergence");
  std::sort(eigenvalues.begin(), eigenvalues.end());
  return eigenvalues;
}

Eigen::VectorXcd general_eigenvalues(const Eigen::MatrixXd& a) {
  require_square(a, "general_eigenvalues");
  gsl_set_error_handler_off();
  GslMatrix copy(a);
  const auto n = static_cast<size_t>(a.rows());
  gsl_vector_complex* values = gsl_vector_complex_alloc(n);
  gsl_eigen_nonsymm_workspace* work = gsl_eigen_nonsymm_alloc(n);
  const int status = gsl_eigen_nonsymm(&copy.view.matrix, values, work);
  gsl_eigen_nonsymm_free(work);
  Eigen::VectorXcd eigenvalues(a.rows());
  for (size_t i = 0; i < n; ++i) {
    const gsl_complex z = gsl_vector_complex_get(values, i);
    eigenvalues[static_cast<Eigen::Index>(i)] = {GSL_REAL(z), GSL_IMAG(z)};
  }
  gsl_vector_complex_free(values);
  if (status != GSL_SUCCESS) throw std::runtime_error("general_eigenvalues: no convergence");
  return eigenvalues;
}

// The three on matrices whose spectra are known in closed form: the second difference matrix
// tridiag(−1, 2, −1) of size n has the eigenvalues 2 − 2 cos(jπ/(n+1)), j = 1..n; the pencil
// (2A, 2I) has the same; a rotation by θ has e^{±iθ}. A matrix that is not positive definite is
// refused as the pencil's M.
TEST_CASE("the reference eigenvalues reproduce spectra known in closed form") {
  const Eigen::Index n = 12;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    a(i, i) = 2;
    if (i > 0) a(i, i - 1) = a(i - 1, i) = -1;
  }
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

// The general solver on a non-symmetric, non-normal matrix: the companion matrix of
// x³ − 7x² + 14x − 8 = (x − 1)(x − 2)(x − 4) has the eigenvalues 1, 2 and 4.
TEST_CASE("the general eigenvalues of a companion matrix are the roots of its polynomial") {
  Eigen::MatrixXd c(3, 3);
  c << 0, 0, 8, 1, 0, -14, 0, 1, 7;
  Eigen::VectorXcd roots = general_eigenvalues(c);
  std::vector<double> real;
  for (Eigen::Index i = 0; i < roots.size(); ++i) {
    CHECK(std::abs(roots[i].imag()) <= 1e-12);
    real.push_back(roots[i].real());
  }
  std::sort(real.begin(), real.end());
  CHECK(real[0] == doctest::Approx(1).epsilon(1e-12));
  CHECK(real[1] == doctest::Approx(2).epsilon(1e-12));
  CHECK(real[2] == doctest::Approx(4).epsilon(1e-12));
}

}  // namespace mrm
