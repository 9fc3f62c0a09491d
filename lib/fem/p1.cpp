/// @file p1.cpp
/// @brief P1 Lagrange finite elements on a uniform mesh of the bar (0, L): mathematics.md §3, paper eq. (5).
///
/// The semi-discrete problem (5) of the paper is M U'' + S U = −λ e₀ + F with the P1 hat functions
/// φ_i, i = 0..N, of the uniform mesh x_i = i h. On one element [x_e, x_e + h] the two hat functions
/// are 1 − ξ and ξ (ξ = (x − x_e)/h), so the element matrices are
///
///     ∫ φ_a φ_b dx   = h/6 [2 1; 1 2],        ∫ φ_a' φ_b' dx = 1/h [1 −1; −1 1].
///
/// Summing the two elements that meet at an interior node gives M_ii = 2h/3, M_{i,i±1} = h/6,
/// S_ii = 2/h, S_{i,i±1} = −1/h; the end nodes 0 and N belong to one element only: M_00 = h/3,
/// S_00 = 1/h. The clamped node N is then eliminated (u_N = 0): the unknowns are nodes 0..N-1.
#include "fem/p1.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <doctest/doctest.h>

#include "fem/dense_eigenvalues.hpp"

namespace mrm {

UniformMesh::UniformMesh(double length_, Index elements_) : length(length_), elements(elements_) {
  if (!(std::isfinite(length_) && length_ > 0))
    throw std::invalid_argument("mesh: the length L must be a positive finite number (got " + std::to_string(length_) +
                                ")");
  if (elements_ < 2)
    throw std::invalid_argument("mesh: the number of elements N must be an integer >= 2 (got " +
                                std::to_string(elements_) + ")");
}

double UniformMesh::bar_mass() const {
  if (homogeneous()) return length;
  double m = 0;
  for (Index e = 0; e < elements; ++e) m += density(e) * h(e);
  return m;
}

// The graded mesh: h_k = h₀ r^k with Σ h_k = h₀ (rᴺ − 1)/(r − 1) = L. The nodes are the
// partial sums x_{k+1} = x_k + h_k; the last is set to L (the sum carries round-off).
UniformMesh graded_mesh(double length, Index elements, double ratio) {
  UniformMesh mesh(length, elements);
  if (!(std::isfinite(ratio) && ratio > 0))
    throw std::invalid_argument("mesh: the grading ratio r must be a positive finite number (got " +
                                std::to_string(ratio) + ")");
  if (ratio == 1.0) return mesh;
  const double h0 = length * (ratio - 1.0) / (std::pow(ratio, static_cast<double>(elements)) - 1.0);
  if (!(std::isfinite(h0) && h0 > 0))
    throw std::invalid_argument("mesh: the grading ratio r = " + std::to_string(ratio) +
                                " gives no representable first element (allowed: r^N finite)");
  mesh.nodes_.resize(static_cast<std::size_t>(elements + 1));
  mesh.nodes_[0] = 0.0;
  double hk = h0;
  for (Index k = 0; k < elements; ++k, hk *= ratio)
    mesh.nodes_[static_cast<std::size_t>(k + 1)] = mesh.nodes_[static_cast<std::size_t>(k)] + hk;
  mesh.nodes_.back() = length;
  return mesh;
}

UniformMesh with_material(UniformMesh mesh, std::vector<double> young, std::vector<double> density) {
  const auto check = [&](const std::vector<double>& values, const char* name) {
    if (static_cast<Index>(values.size()) != mesh.elements)
      throw std::invalid_argument(std::string("mesh: ") + name + " has " + std::to_string(values.size()) +
                                  " values (allowed: one per element, " + std::to_string(mesh.elements) + ")");
    for (double v : values)
      if (!(std::isfinite(v) && v > 0))
        throw std::invalid_argument(std::string("mesh: ") + name + " = " + std::to_string(v) +
                                    " on an element (allowed: positive finite values)");
  };
  check(young, "the modulus E");
  check(density, "the density rho");
  mesh.young_ = std::move(young);
  mesh.density_ = std::move(density);
  return mesh;
}

UniformMesh with_far_end(UniformMesh mesh, FarEnd far_end) {
  mesh.far_end = far_end;
  return mesh;
}

// The sizes and indices that the operations below require are checked in every build: an assertion
// would vanish from a release build, and a wrong size would then read or write past a vector's end.
static void require_size(const char* operation, Index given, Index expected) {
  if (given != expected)
    throw std::invalid_argument(std::string("Tridiagonal::") + operation + ": the operand has size " +
                                std::to_string(given) + " (allowed: the matrix size " + std::to_string(expected) + ")");
}

double Tridiagonal::operator()(Index i, Index j) const {
  if (!(0 <= i && i < size() && 0 <= j && j < size()))
    throw std::invalid_argument("Tridiagonal: entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") requested (allowed: indices in [0, " + std::to_string(size() - 1) + "])");
  if (i == j) return diag[i];
  if (j == i - 1) return lower[i];
  if (j == i + 1) return upper[i];
  return 0.0;
}

Eigen::VectorXd Tridiagonal::operator*(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y;
  multiply(x, y);
  return y;
}

void Tridiagonal::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  require_size("operator*", x.size(), size());
  if (&x == &y) throw std::invalid_argument("Tridiagonal::multiply: the result cannot overwrite the operand");
  const Index n = size();
  y.resize(n);
  if (n == 0) return;
  // y_i = (A_ii x_i + A_{i,i−1} x_{i−1}) + A_{i,i+1} x_{i+1}, the terms that exist, in this order; the
  // interior rows in a loop of their own (no test per row, so the compiler can vectorise it across
  // rows, each row's sum unchanged).
  if (n == 1) {
    y[0] = diag[0] * x[0];
    return;
  }
  const double *d = diag.data(), *lo = lower.data(), *up = upper.data(), *xs = x.data();
  double* ys = y.data();
  ys[0] = d[0] * xs[0] + up[0] * xs[1];
  for (Index i = 1; i + 1 < n; ++i) {
    double s = d[i] * xs[i];
    s += lo[i] * xs[i - 1];
    s += up[i] * xs[i + 1];
    ys[i] = s;
  }
  ys[n - 1] = d[n - 1] * xs[n - 1] + lo[n - 1] * xs[n - 2];
}

double Tridiagonal::bilinear(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const {
  require_size("bilinear", x.size(), size());
  return x.dot((*this) * y);
}

// xᵀAx in one pass, bit for bit what bilinear(x, x) = x.dot(A x) computes, without the product vector.
// Each row's (A x)_i is summed as multiply sums it, and the products p_i = x_i (A x)_i are added in the
// order of Eigen 3.4's vectorised sum (Redux.h, LinearVectorizedTraversal, packets of two doubles on
// the SSE2 baseline this project compiles for: the p_i with i mod 4 = 0, 1, 2, 3 in four partial sums
// up to the last multiple of 4, the first pair added to the second, then the next pair if one is left,
// the two halves added, then the last p_i if n is odd; for n < 4 the same with one pair). The doctest
// below compares the bits with bilinear's for n = 1 to 40.
namespace {

// form's algorithm for x_i at xs[i·stride]; `contiguous` (stride 1) loads a pair of x with one copy.
template <bool contiguous>
double form_of(const double* d, const double* lo, const double* up, Index n, const double* xs, std::size_t stride) {
  if (n == 0) return 0.0;
  const auto at = [&](Index i) { return contiguous ? xs[i] : xs[static_cast<std::size_t>(i) * stride]; };
  const auto row = [&](Index i) {  // x_i (A x)_i, the terms that exist
    double s = d[i] * at(i);
    if (i > 0) s += lo[i] * at(i - 1);
    if (i + 1 < n) s += up[i] * at(i + 1);
    return at(i) * s;
  };
  if (n < 4) {
    if (n == 1) return row(0);
    double r = row(0) + row(1);
    if (n == 3) r += row(2);
    return r;
  }
  const Index end4 = n / 4 * 4, end2 = n / 2 * 2;
  double a0 = row(0), a1 = row(1), b0 = row(2), b1 = row(3);
  Index i = 4;
  {
    // The interior groups two rows at a time in a pair of doubles (GCC's vector extension: each lane's
    // operations are the scalar ones, in the same order, so the bits are those of `interior`).
    typedef double Pair __attribute__((vector_size(16)));
    const auto load = [](const double* p) {
      Pair v;
      std::memcpy(&v, p, sizeof v);
      return v;
    };
    const auto load_x = [&](Index k) {  // x_k and x_{k+1}
      if constexpr (contiguous) {
        return load(xs + k);
      } else {
        return Pair{at(k), at(k + 1)};
      }
    };
    const auto products = [&](Index k) {  // x_k (A x)_k and x_{k+1} (A x)_{k+1}, 0 < k, k + 2 < n
      const Pair xk = load_x(k);
      Pair s = load(d + k) * xk;
      s += load(lo + k) * load_x(k - 1);
      s += load(up + k) * load_x(k + 1);
      return xk * s;
    };
    Pair a{a0, a1}, b{b0, b1};
    for (; i + 4 < n; i += 4) {  // rows i … i + 3 all interior
      a += products(i);
      b += products(i + 2);
    }
    a0 = a[0], a1 = a[1], b0 = b[0], b1 = b[1];
  }
  if (i < end4) {  // the last group of four ends at row n − 1
    a0 += row(i), a1 += row(i + 1);
    b0 += row(i + 2), b1 += row(i + 3);
  }
  a0 += b0, a1 += b1;
  if (end2 > end4) a0 += row(end4), a1 += row(end4 + 1);
  double r = a0 + a1;
  if (n > end2) r += row(n - 1);
  return r;
}

}  // namespace

double Tridiagonal::form(const Eigen::VectorXd& x) const {
  require_size("form", x.size(), size());
  return form_of<true>(diag.data(), lower.data(), upper.data(), size(), x.data(), 1);
}

double Tridiagonal::form(const double* x, std::size_t stride) const {
  if (stride == 1) return form_of<true>(diag.data(), lower.data(), upper.data(), size(), x, 1);
  return form_of<false>(diag.data(), lower.data(), upper.data(), size(), x, stride);
}

double Tridiagonal::sum() const { return lower.sum() + diag.sum() + upper.sum(); }

Tridiagonal Tridiagonal::leading_block(Index n) const {
  if (!(1 <= n && n <= size()))
    throw std::invalid_argument("Tridiagonal::leading_block: block size " + std::to_string(n) + " (allowed: 1 to " +
                                std::to_string(size()) + ")");
  Tridiagonal block(n);
  block.lower = lower.head(n);
  block.diag = diag.head(n);
  block.upper = upper.head(n);
  block.upper[n - 1] = 0.0;
  return block;
}

Tridiagonal Tridiagonal::scaled(double c) const {
  Tridiagonal r(size());
  r.lower = c * lower;
  r.diag = c * diag;
  r.upper = c * upper;
  return r;
}

Tridiagonal Tridiagonal::plus(double c, const Tridiagonal& b) const {
  require_size("plus", b.size(), size());
  Tridiagonal r(size());
  r.lower = lower + c * b.lower;
  r.diag = diag + c * b.diag;
  r.upper = upper + c * b.upper;
  return r;
}

double stiffness_form(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const UniformMesh& mesh) {
  const Index n = u.size();
  double sum = 0;
  const bool plain = mesh.uniform() && mesh.homogeneous();
  for (Index e = 0; e < mesh.elements; ++e) {
    const double du = (e + 1 < n ? u[e + 1] : 0.0) - u[e];
    const double dv = (e + 1 < n ? v[e + 1] : 0.0) - v[e];
    sum += plain ? du * dv : du * dv * mesh.young(e) / mesh.h(e);
  }
  return plain ? sum / mesh.h() : sum;
}

Eigen::SparseMatrix<double> Tridiagonal::to_sparse() const {
  const Index n = size();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(3 * n));
  for (Index i = 0; i < n; ++i) {
    if (i > 0) triplets.emplace_back(i, i - 1, lower[i]);
    triplets.emplace_back(i, i, diag[i]);
    if (i + 1 < n) triplets.emplace_back(i, i + 1, upper[i]);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

// Assembly element by element: the element matrix [a b; b a] of element e adds to the block of nodes
// (e, e+1). Both P1 matrices have this form: on an element of size h_e, density ρ_e and modulus E_e,
// ∫ ρ φ_a φ_b dx = ρ_e h_e/6 [2 1; 1 2] and ∫ E φ_a' φ_b' dx = E_e/h_e [1 −1; −1 1], so
// a = ρ_e h_e/3, b = ρ_e h_e/6 for M and a = E_e/h_e, b = −E_e/h_e for S. (On the paper's mesh,
// ρ_e = E_e = 1 and h_e = L/N: the products by 1.0 are exact, the same doubles as h/3, h/6, 1/h.)
template <class Entries>
static Tridiagonal assemble_all_nodes(const UniformMesh& mesh, Entries entries) {
  Tridiagonal m(mesh.elements + 1);
  for (Index e = 0; e < mesh.elements; ++e) {
    const auto [a, b] = entries(e);
    m.diag[e] += a;
    m.diag[e + 1] += a;
    m.upper[e] += b;
    m.lower[e + 1] += b;
  }
  return m;
}

Tridiagonal p1_mass_all_nodes(const UniformMesh& mesh) {
  return assemble_all_nodes(mesh, [&](Index e) {
    const double m = mesh.density(e) * mesh.h(e);
    return std::pair{m / 3.0, m / 6.0};
  });
}

// The blend of the consistent element mass m/6 [2, 1; 1, 2] with the lumped one m/2 [1, 0; 0, 1]:
// (1 − A) m/6 [2, 1; 1, 2] + A m/6 [3, 0; 0, 3] = m/6 [2 + A, 1 − A; 1 − A, 2 + A]. Every row keeps the
// sum m/2, so the total mass is the bar's for every A; for 0 ≤ A ≤ 1 the element matrix is positive
// definite (eigenvalues (2 + A ± (1 − A))m/6 = m/2 and (1 + 2A)m/6 > 0), so M^A is
// positive definite like M.
Tridiagonal p1_blended_mass_all_nodes(const UniformMesh& mesh, double blend) {
  if (!(blend >= 0.0 && blend <= 1.0))
    throw std::invalid_argument("p1_blended_mass_all_nodes: the blend A must be in [0, 1]");
  if (blend == 0.0) return p1_mass_all_nodes(mesh);
  return assemble_all_nodes(mesh, [&](Index e) {
    const double m = mesh.density(e) * mesh.h(e);
    return std::pair{m * (2.0 + blend) / 6.0, m * (1.0 - blend) / 6.0};
  });
}

TEST_CASE("the blended mass keeps the row sums (the lumped masses) and interpolates consistent and lumped") {
  const UniformMesh uniform(1.0, 8), graded = graded_mesh(1.0, 8, 1.2);
  for (const UniformMesh& mesh : {uniform, graded}) {
    const Tridiagonal m = p1_mass_all_nodes(mesh), lumped = p1_blended_mass_all_nodes(mesh, 1.0);
    CHECK(lumped.upper.cwiseAbs().maxCoeff() == 0.0);
    for (double a : {0.25, 0.5}) {
      const Tridiagonal b = p1_blended_mass_all_nodes(mesh, a);
      const Tridiagonal expected = m.scaled(1.0 - a).plus(a, lumped);
      for (Index i = 0; i < b.size(); ++i) {
        CHECK(b.diag[i] == doctest::Approx(expected.diag[i]).epsilon(1e-14));
        CHECK(b.upper[i] == doctest::Approx(expected.upper[i]).epsilon(1e-14));
        CHECK(b.diag[i] + b.lower[i] + b.upper[i] ==
              doctest::Approx(m.diag[i] + m.lower[i] + m.upper[i]).epsilon(1e-14));
      }
    }
  }
  CHECK_THROWS_AS(p1_blended_mass_all_nodes(uniform, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(p1_blended_mass_all_nodes(uniform, 1.5), std::invalid_argument);
}

Tridiagonal p1_stiffness_all_nodes(const UniformMesh& mesh) {
  return assemble_all_nodes(mesh, [&](Index e) {
    const double k = mesh.young(e) / mesh.h(e);
    return std::pair{k, -k};
  });
}

Tridiagonal p1_mass(const UniformMesh& mesh) { return p1_mass_all_nodes(mesh).leading_block(mesh.unknowns()); }

Tridiagonal p1_stiffness(const UniformMesh& mesh) {
  return p1_stiffness_all_nodes(mesh).leading_block(mesh.unknowns());
}

// ---------------------------------------------------------------------------------------------------
// Checks of the P1 matrices. The mass matrix integrates products of P1 functions exactly, so
// 1ᵀM1 = ∫ 1 dx = L and xᵀM1 = ∫ x dx = L²/2; the stiffness matrix annihilates constants on the full
// node set (S1 = 0) and, with node N eliminated, is positive definite (the clamp removes the kernel).

TEST_CASE("the P1 mass matrix has the entries h/3, 2h/3, h/6 and sums to L") {
  for (Index n : {2, 3, 10, 257}) {
    const UniformMesh mesh(2.5, n);
    const double h = mesh.h();
    CAPTURE(n);
    const Tridiagonal m = p1_mass_all_nodes(mesh);
    CHECK(m.diag[0] == doctest::Approx(h / 3).epsilon(1e-14));
    CHECK(m.diag[1] == doctest::Approx(2 * h / 3).epsilon(1e-14));
    CHECK(m.upper[0] == doctest::Approx(h / 6).epsilon(1e-14));
    CHECK(m.diag[n] == doctest::Approx(h / 3).epsilon(1e-14));
    CHECK(std::abs(m.sum() - mesh.length) < 1e-13);
    Eigen::VectorXd x(n + 1), one = Eigen::VectorXd::Ones(n + 1);
    for (Index i = 0; i <= n; ++i) x[i] = mesh.x(i);
    CHECK(std::abs(m.bilinear(x, one) - mesh.length * mesh.length / 2) < 1e-13);
    CHECK(std::abs(m.bilinear(x, x) - std::pow(mesh.length, 3) / 3) < 1e-12);
  }
}

TEST_CASE("the P1 stiffness matrix annihilates constants and integrates u' v' exactly") {
  const UniformMesh mesh(1.5, 12);
  const Tridiagonal s = p1_stiffness_all_nodes(mesh);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(13);
  CHECK((s * one).cwiseAbs().maxCoeff() < 1e-12);
  Eigen::VectorXd x(13);
  for (Index i = 0; i <= 12; ++i) x[i] = mesh.x(i);
  CHECK(std::abs(s.bilinear(x, x) - mesh.length) < 1e-12);  // ∫ (x')² dx = L
  CHECK(s.diag[0] == doctest::Approx(1 / mesh.h()).epsilon(1e-14));
  CHECK(s.diag[5] == doctest::Approx(2 / mesh.h()).epsilon(1e-14));
}

TEST_CASE("the clamped P1 matrices are symmetric and positive definite") {
  const UniformMesh mesh(1.0, 40);
  for (const Tridiagonal& a : {p1_mass(mesh), p1_stiffness(mesh)}) {
    const Eigen::MatrixXd dense(a.to_sparse());
    CHECK(dense.rows() == 40);
    CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() == 0.0);
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(dense);
    REQUIRE(ldlt.info() == Eigen::Success);
    CHECK(ldlt.vectorD().minCoeff() > 0.0);
  }
  // The unclamped stiffness is singular: its smallest eigenvalue is zero (constants).
  const Eigen::MatrixXd s_all(p1_stiffness_all_nodes(mesh).to_sparse());
  CHECK(std::abs(symmetric_eigenvalues(s_all)[0]) < 1e-10);
}

TEST_CASE("a mesh needs L > 0 finite and N >= 2, and says so") {
  CHECK_NOTHROW(UniformMesh(1.0, 2));
  for (double length : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    CAPTURE(length);
    CHECK_THROWS_WITH_AS(UniformMesh(length, 10), doctest::Contains("the length L must be a positive finite number"),
                         std::invalid_argument);
  }
  for (Index elements : {1, 0, -5}) {
    CAPTURE(elements);
    CHECK_THROWS_WITH_AS(UniformMesh(1.0, elements), doctest::Contains("N must be an integer >= 2"),
                         std::invalid_argument);
  }
}

TEST_CASE("tridiagonal operations refuse operands of the wrong size and entries outside the matrix") {
  const Tridiagonal a = p1_mass(UniformMesh(1.0, 4));
  const Eigen::VectorXd right(4), wrong(5);
  CHECK_NOTHROW(a * right);
  CHECK_THROWS_WITH_AS(a * wrong, "Tridiagonal::operator*: the operand has size 5 (allowed: the matrix size 4)",
                       std::invalid_argument);
  CHECK_THROWS_AS(a.bilinear(wrong, right), std::invalid_argument);
  CHECK_THROWS_AS(a.plus(1.0, Tridiagonal(3)), std::invalid_argument);
  CHECK_NOTHROW(a.leading_block(4));
  CHECK_THROWS_WITH_AS(a.leading_block(5), "Tridiagonal::leading_block: block size 5 (allowed: 1 to 4)",
                       std::invalid_argument);
  CHECK_THROWS_AS(a.leading_block(0), std::invalid_argument);
  CHECK(a(3, 1) == 0.0);
  CHECK_THROWS_WITH_AS(a(4, 3), doctest::Contains("allowed: indices in [0, 3]"), std::invalid_argument);
  CHECK_THROWS_AS(a(-1, 0), std::invalid_argument);
}

namespace {

// A tridiagonal matrix and a vector of size n whose entries all differ (so that a sum taken in another
// order, or a term taken twice, changes the bits).
void distinct_entries(Index n, Tridiagonal& a, Eigen::VectorXd& x) {
  a = Tridiagonal(n);
  x.resize(n);
  for (Index i = 0; i < n; ++i) {
    const double k = static_cast<double>(i + 1);
    a.diag[i] = 1.0 / (3 * k) + 0.7;
    if (i > 0) a.lower[i] = -1.0 / (7 * k) + 0.1;
    if (i + 1 < n) a.upper[i] = 1.0 / (11 * k) - 0.3;
    x[i] = std::sin(1.3 * k) + 0.01 / k;
  }
}

}  // namespace

// The product row by row: (A_ii x_i + A_{i,i−1} x_{i−1}) + A_{i,i+1} x_{i+1}, the terms that exist, in
// this order (the order the measures' bits depend on: convergence.cpp's ReferenceComparison), bit for
// bit, on matrices whose every entry differs, for sizes 1 to 9 (ends, and interiors of odd and even
// length); multiply into a kept vector gives the same bits as operator*, and refuses to overwrite x.
TEST_CASE("the tridiagonal product sums each row in the written order, bit for bit") {
  for (Index n = 1; n <= 9; ++n) {
    Tridiagonal a;
    Eigen::VectorXd x;
    distinct_entries(n, a, x);
    const Eigen::VectorXd y = a * x;
    Eigen::VectorXd kept = Eigen::VectorXd::Constant(n, 5.0);
    a.multiply(x, kept);
    for (Index i = 0; i < n; ++i) {
      double expected = a(i, i) * x[i];
      if (i > 0) expected += a(i, i - 1) * x[i - 1];
      if (i + 1 < n) expected += a(i, i + 1) * x[i + 1];
      CAPTURE(n);
      CAPTURE(i);
      CHECK(y[i] == expected);
      CHECK(kept[i] == expected);
    }
    CHECK_THROWS_AS(a.multiply(x, x), std::invalid_argument);
  }
}

// form(x) against bilinear(x, x), bit for bit: every size from 1 to 40 (each remainder of the four
// partial sums, the n < 4 cases and the rows at both ends), entries that all differ.
TEST_CASE("the one-pass quadratic form has the bits of bilinear(x, x)") {
  for (Index n = 1; n <= 40; ++n) {
    Tridiagonal a;
    Eigen::VectorXd x;
    distinct_entries(n, a, x);
    const double expected = a.bilinear(x, x), got = a.form(x);
    CAPTURE(n);
    CHECK(std::memcmp(&expected, &got, sizeof got) == 0);
  }
  CHECK_THROWS_AS(Tridiagonal(3).form(Eigen::VectorXd::Zero(2)), std::invalid_argument);
}

// form(x, stride) against form(x), bit for bit: the same sizes, x's entries spread at several strides
// (as in a batch's lanes, with other values between them).
TEST_CASE("the strided quadratic form has the bits of form(x)") {
  for (Index n = 1; n <= 40; ++n)
    for (const std::size_t stride : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{4}, std::size_t{8}}) {
      Tridiagonal a;
      Eigen::VectorXd x;
      distinct_entries(n, a, x);
      std::vector<double> spread(static_cast<std::size_t>(n) * stride, -7.25);
      for (Index i = 0; i < n; ++i) spread[static_cast<std::size_t>(i) * stride] = x[i];
      const double expected = a.form(x), got = a.form(spread.data(), stride);
      CAPTURE(n);
      CAPTURE(stride);
      CHECK(std::memcmp(&expected, &got, sizeof got) == 0);
    }
}

TEST_CASE("the P1 load vector integrates f φ_i exactly for a quadratic f") {
  const UniformMesh mesh(2.0, 8);
  const Eigen::VectorXd f = p1_load(mesh, [](double x) { return 1.0 + x * x; });
  // Σ_i F_i over all nodes equals ∫ f dx; node N is dropped, so add its share back by hand:
  // F_N = ∫_{L-h}^{L} f φ_N dx.
  const double h = mesh.h(), L = mesh.length, a = L - h;
  auto antiderivative = [&](double x) {  // ∫ (1 + x²) (x − a)/h dx
    return ((x * x * x * x) / 4 - a * x * x * x / 3 + x * x / 2 - a * x) / h;
  };
  const double f_clamped = antiderivative(L) - antiderivative(a);
  CHECK(std::abs(f.sum() + f_clamped - (L + L * L * L / 3)) < 1e-12);
  CHECK(std::abs(f[0] - (h / 2 + h * h * h / 12)) < 1e-13);  // ∫₀ʰ (1 + x²)(1 − x/h) dx
}

TEST_CASE("the P1 load vector refuses a load that is not finite") {
  const UniformMesh mesh(1.0, 4);
  CHECK_THROWS_WITH_AS(p1_load(mesh, [](double x) { return x > 0.5 ? std::nan("") : 1.0; }),
                       doctest::Contains("p1_load: the load f(x) is not finite"), std::invalid_argument);
  CHECK_THROWS_AS(p1_load(mesh, [](double x) { return 1.0 / (x - x); }), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Graded meshes, piecewise material and the free far end (the field's benchmarks, doc/benchmarks.md).
// The element matrices integrate ρ φ_a φ_b and E φ_a' φ_b' exactly on each element, so 1ᵀM1 = Σ ρ_e h_e
// = ∫ρ, xᵀMx = ∫ρx², S1 = 0 on all nodes, and xᵀSx = ∫E (x' = 1).

TEST_CASE("a graded mesh has h_k = h0 r^k, ends at L, and its P1 matrices integrate rho and E exactly") {
  for (const double r : {1.0, 0.9, 1.05, 1.3}) {
    const UniformMesh mesh = graded_mesh(2.0, 12, r);
    CAPTURE(r);
    CHECK(mesh.x(12) == 2.0);
    CHECK(mesh.uniform() == (r == 1.0));
    const double h0 = mesh.h(0);
    for (Index k = 0; k < 12; ++k) CHECK(std::abs(mesh.h(k) - h0 * std::pow(r, static_cast<double>(k))) < 1e-14);
    std::vector<double> young(12), density(12);
    for (Index e = 0; e < 12; ++e)
      young[e] = 1.0 + static_cast<double>(e % 3), density[e] = 0.5 + 0.25 * static_cast<double>(e % 2);
    const UniformMesh layered = with_material(mesh, young, density);
    double rho = 0, rho_x2 = 0, e_int = 0;
    for (Index e = 0; e < 12; ++e) {
      const double a = mesh.x(e), b = mesh.x(e + 1);
      rho += density[e] * (b - a), rho_x2 += density[e] * (b * b * b - a * a * a) / 3, e_int += young[e] * (b - a);
    }
    const Tridiagonal m = p1_mass_all_nodes(layered), s = p1_stiffness_all_nodes(layered);
    Eigen::VectorXd x(13), one = Eigen::VectorXd::Ones(13);
    for (Index i = 0; i <= 12; ++i) x[i] = mesh.x(i);
    CHECK(std::abs(m.sum() - rho) < 1e-14);
    CHECK(std::abs(layered.bar_mass() - rho) < 1e-14);
    CHECK(std::abs(m.bilinear(x, x) - rho_x2) < 1e-13);
    CHECK((s * one).cwiseAbs().maxCoeff() < 1e-11);
    CHECK(std::abs(s.bilinear(x, x) - e_int) < 1e-12);
    CHECK(layered.contact_compliance() == mesh.h(0) / young[0]);
  }
  // The paper's mesh is untouched: h(e) is h(), the compliance h, the unknowns 0..N−1.
  const UniformMesh plain(1.0, 7);
  CHECK(plain.h(3) == plain.h());
  CHECK(plain.contact_compliance() == plain.h());
  CHECK(plain.unknowns() == 7);
  CHECK(with_far_end(plain, FarEnd::free).unknowns() == 8);
  CHECK(p1_mass(with_far_end(plain, FarEnd::free)).size() == 8);
  CHECK_THROWS_AS(graded_mesh(1.0, 10, 1.1).h(), std::logic_error);
  CHECK_THROWS_WITH_AS(graded_mesh(1.0, 10, 0.0), doctest::Contains("grading ratio"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(with_material(plain, std::vector<double>(7, 1.0), std::vector<double>(6, 1.0)),
                       doctest::Contains("one per element"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(with_material(plain, std::vector<double>(7, -1.0), std::vector<double>(7, 1.0)),
                       doctest::Contains("positive finite"), std::invalid_argument);
}

TEST_CASE("the load vector on a graded mesh with a free end integrates f phi_i exactly for a quadratic f") {
  const UniformMesh mesh = with_far_end(graded_mesh(1.0, 9, 1.2), FarEnd::free);
  const Eigen::VectorXd f = p1_load(mesh, [](double x) { return 1.0 + x * x; });
  REQUIRE(f.size() == 10);
  CHECK(std::abs(f.sum() - (1.0 + 1.0 / 3)) < 1e-14);  // every node kept: Σ F_i = ∫ f
  const double h0 = mesh.h(0);
  CHECK(std::abs(f[0] - (h0 / 2 + h0 * h0 * h0 / 12)) < 1e-15);
}

}  // namespace mrm
