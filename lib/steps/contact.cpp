/// @file contact.cpp
/// @brief The contact node: mathematics.md §3 (condensation) and §4 (the closed-form contact step).
#include "steps/contact.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <doctest/doctest.h>

#include "fem/mass_redistribution.hpp"

namespace mrm {

/// @file contact.cpp
/// ## Condensation of the massless contact node (paper eq. (6), second and third lines).
///
/// With the mass redistributed, row 0 of the system has no inertia and reads
///
///     S_00 u₀ + Cᵀ Ū = −λ + F₀,   0 ≤ u₀ ⊥ λ ≤ 0,        S_00 = 1/h, Cᵀ Ū = S_01 u₁ = −u₁/h.
///
/// So λ = F₀ − (u₀ − u₁)/h. If u₀ > 0 then λ = 0 and u₀ = u₁ + h F₀, which requires u₁ + h F₀ > 0;
/// if u₀ = 0 then λ = F₀ + u₁/h, which must be ≤ 0, i.e. u₁ + h F₀ ≤ 0. The two cases join into
///
///     u₀ = max(0, u₁ + h F₀),   λ = min(0, F₀ + u₁/h):
///
/// u₀ is a Lipschitz function of Ū, and the reduced problem M̄ Ū'' + S̄ Ū = −C u₀(Ū) + F̄ is a Lipschitz
/// ODE, which is why the redistributed semi-discrete problem is well posed.

// With an obstacle at g (a gap: g = −gap) the same two cases give u₀ = max(g, u₁ + hF₀) and, in
// contact, λ = F₀ − (g − u₁)/h. On a graded mesh or with a material, S₀₀ = E₀/h₀ and h is read as the
// compliance 1/S₀₀ = h₀/E₀ throughout.
CondensedContact condense_contact_node(double u1, double h, double load0, double obstacle) {
  if (obstacle == 0.0) return {std::max(0.0, u1 + h * load0), std::min(0.0, load0 + u1 / h)};
  return {std::max(obstacle, u1 + h * load0), std::min(0.0, load0 + (u1 - obstacle) / h)};
}

TEST_CASE("the condensed contact node satisfies its row and the complementarity") {
  const double h = 0.05;
  for (double u1 : {-0.3, -0.01, 0.0, 1e-3, 0.2}) {
    for (double f0 : {-2.0, 0.0, 0.7}) {
      const CondensedContact c = condense_contact_node(u1, h, f0);
      CAPTURE(u1);
      CAPTURE(f0);
      CHECK(std::abs(c.u0 / h - u1 / h - (f0 - c.multiplier)) < 1e-12);  // S₀₀u₀ + S₀₁u₁ = F₀ − λ
      CHECK(c.u0 >= 0.0);
      CHECK(c.multiplier <= 0.0);
      CHECK(c.u0 * c.multiplier == 0.0);
    }
  }
}

/// @file contact.cpp
/// ## The closed-form contact step (mathematics.md §4).
///
/// Every implicit step of this library (Crank–Nicolson, backward Euler, Paoli–Schatzman) solves
///
///     A U = b − κ λ e₀,   0 ≤ u₀ − g ⊥ λ ≤ 0,
///
/// (\f$ A U = b - \kappa \lambda e_0 \f$, \f$ 0 \le u_0 - g \perp \lambda \le 0 \f$)
/// with A tridiagonal and constant over a run, κ > 0 a constant and g the obstacle (g = 0, or
/// g = −e u₀ⁿ⁻¹ for the Paoli–Schatzman restitution law). mathematics.md writes the solution with
/// z = A⁻¹ b and the response to the contact force, A⁻¹ e₀: the contact node moves as
/// u₀ = z₀ − κ λ (A⁻¹)₀₀. Since (A⁻¹)₀₀ > 0, the complementarity has the closed-form solution
///
///     if z₀ ≥ g :  free,    λ = 0,                    U = z,
///     else      :  contact, λ = (z₀ − g)/(κ (A⁻¹)₀₀), U = z − κ λ A⁻¹ e₀   (so u₀ = g).
///
/// Eliminating the tridiagonal system from the far end (node n−1) toward the contact node makes this
/// cheaper than two solves: after the sweep down the last row is d₀ u₀ = y₀ − κ λ, where the pivot
/// d₀ = 1/(A⁻¹)₀₀ is the Schur complement of A onto node 0 and y₀ = d₀ z₀. The contact is decided
/// there, and the sweep up then gives U for the right u₀ at once: one solve per step, whatever the
/// contact status.
///
/// For a massless contact node this is mathematics.md's formula in other clothes: with row 0 of A the
/// contact row (S_00, S_01) and Ā = M̄ + θS̄ on the free nodes, z₀ ≥ 0 ⇔ z̄₁ + hF₀ > 0 with z̄ = Ā⁻¹b̄,
/// and the free value u₀ = (hF₀ + z̄₁)/(1 + w₁), w = θĀ⁻¹C, is z₀ (a Schur complement identity); the
/// doctests below check both forms and a direct solve against each other.

ContactSolver::ContactSolver(const Tridiagonal& a)
    : pivot_(a.size()),
      inverse_pivot_(a.size()),
      elimination_(Eigen::VectorXd::Zero(a.size())),
      lower_(a.lower),
      upward_(a.size()) {
  const Index n = a.size();
  if (n < 1) throw std::invalid_argument("contact solver: empty matrix");
  pivot_[n - 1] = a.diag[n - 1];
  for (Index i = n - 2; i >= 0; --i) {
    elimination_[i] = a.upper[i] / pivot_[i + 1];
    pivot_[i] = a.diag[i] - elimination_[i] * a.lower[i + 1];
  }
  for (Index i = 0; i < n; ++i) {
    if (!(pivot_[i] > 0.0 && std::isfinite(pivot_[i])))
      throw std::invalid_argument("contact solver: the step matrix is not positive definite (pivot " +
                                  std::to_string(i) + " is " + std::to_string(pivot_[i]) + ")");
    inverse_pivot_[i] = 1.0 / pivot_[i];
    upward_[i] = lower_[i] * inverse_pivot_[i];
  }
  elimination_pair_.setZero(n);
  upward_pair_.setZero(n);
  for (Index i = 0; i < n; ++i) {
    if (i + 1 < n) elimination_pair_[i] = elimination_[i] * elimination_[i + 1];
    if (i >= 1) upward_pair_[i] = upward_[i] * upward_[i - 1];
  }
}

ContactStep ContactSolver::resolve_contact(double y0, double kappa, double obstacle) const {
  const double free_u0 = y0 * inverse_pivot_[0];
  if (free_u0 >= obstacle) return {free_u0, 0.0, false};
  return {obstacle, (y0 - pivot_[0] * obstacle) / kappa, true};
}

ContactStep ContactSolver::solve(const double* b, double* u, double kappa, double obstacle) const {
  if (!(kappa > 0 && std::isfinite(kappa)))
    throw std::invalid_argument("contact solver: kappa = " + std::to_string(kappa) +
                                " (allowed: a positive finite number)");
  if (size() == 0) throw std::invalid_argument("contact solver: solve before factorising a matrix");
  sweep_down(b, u);
  const ContactStep step = resolve_contact(u[0], kappa, obstacle);
  sweep_up(step.u0, u);
  return step;
}

void ContactSolver::sweep_down(const double* b, double* y) const {
  const Index n = size();
  double yi = b[n - 1];
  y[n - 1] = yi;
  for (Index i = n - 2; i >= 0; --i) {
    yi = b[i] - elimination_[i] * yi;
    y[i] = yi;
  }
}

void ContactSolver::sweep_up(double u0, double* y) const {
  y[0] = u0;
  for (Index i = 1; i < size(); ++i) y[i] = inverse_pivot_[i] * y[i] - upward_[i] * y[i - 1];
}

// ---------------------------------------------------------------------------------------------------
// The verification solve: (★) with the active set fixed is the saddle-point system
//
//     [ A    κe₀ ] [U]   [b]                                    [ e₀ᵀ  0 ]  (u₀ = g, active)
//     [ rᵀ   c   ] [λ] = [g or 0],   with the last row (rᵀ, c) = [ 0    1 ]  (λ = 0, inactive),
//
// regular whenever A is, assembled from triplets and factorised by Eigen's general sparse LU: nothing
// of the closed form's elimination order or its Schur complement is shared.
Eigen::VectorXd saddle_point_solve(const Tridiagonal& a, const Eigen::VectorXd& b, double kappa, double obstacle,
                                   bool active) {
  const Index n = a.size();
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, a.diag[i]);
    if (i > 0) t.emplace_back(i, i - 1, a.lower[i]);
    if (i + 1 < n) t.emplace_back(i, i + 1, a.upper[i]);
  }
  t.emplace_back(0, n, kappa);
  t.emplace_back(n, active ? 0 : n, 1.0);
  Eigen::SparseMatrix<double> k(n + 1, n + 1);
  k.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd rhs(n + 1);
  rhs << b, (active ? obstacle : 0.0);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(k);
  if (lu.info() != Eigen::Success) throw std::runtime_error("saddle_point_solve: the sparse LU factorisation failed");
  Eigen::VectorXd x = lu.solve(rhs);
  if (lu.info() != Eigen::Success) throw std::runtime_error("saddle_point_solve: the sparse LU solve failed");
  return x;
}

// ---------------------------------------------------------------------------------------------------
// Checks: the closed-form step against (1) a direct sparse LU solve of the saddle-point system with
// the active set fixed, for both outcomes, and (2) mathematics.md's condensed formula on the free nodes.

namespace {

[[maybe_unused]] Tridiagonal step_matrix(const UniformMesh& mesh, const MassRedistribution& r, double theta,
                                         bool contact_row) {
  const Tridiagonal s = p1_stiffness(mesh);
  Tridiagonal a = modified_mass(mesh, r).plus(theta, s);
  if (contact_row) {  // row 0 is the algebraic contact row S_00 u₀ + S_01 u₁ = F₀ − λ
    a.diag[0] = s.diag[0];
    a.upper[0] = s.upper[0];
  }
  return a;
}

}  // namespace

TEST_CASE("the closed-form contact step agrees with a direct saddle-point solve in both cases") {
  const UniformMesh mesh(1.0, 30);
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const MassRedistribution& r : {consistent_mass(), mod1(), mod3()}) {
    const bool massless = r.name != "consistent";
    const double theta = 0.01 * 0.01 / 4, kappa = massless ? 1.0 : theta;
    const Tridiagonal a = step_matrix(mesh, r, theta, massless);
    const ContactSolver solver(a);
    int active_seen = 0, free_seen = 0;
    for (int trial = 0; trial < 40; ++trial) {
      Eigen::VectorXd b(mesh.unknowns());
      for (Index i = 0; i < b.size(); ++i) b[i] = uniform(random);
      const double g = trial % 3 == 0 ? -0.1 * std::abs(uniform(random)) : 0.0;
      Eigen::VectorXd u(b.size());
      const ContactStep step = solver.solve(b.data(), u.data(), kappa, g);
      const Eigen::VectorXd direct = saddle_point_solve(a, b, kappa, g, step.active);
      CAPTURE(r.name);
      CAPTURE(trial);
      CHECK((u - direct.head(b.size())).cwiseAbs().maxCoeff() < 1e-10 * (1 + direct.cwiseAbs().maxCoeff()));
      CHECK(std::abs(step.multiplier - direct[b.size()]) < 1e-9 * (1 + std::abs(direct[b.size()])));
      // The complementarity: u₀ ≥ g, λ ≤ 0, one of them an equality.
      CHECK(step.u0 >= g);
      CHECK(step.multiplier <= 0.0);
      CHECK((step.u0 - g) * step.multiplier == 0.0);
      // The other active set would violate it: the solution is the unique one.
      const Eigen::VectorXd other = saddle_point_solve(a, b, kappa, g, !step.active);
      CHECK((step.active ? other[0] < g : other[b.size()] > 0.0));
      (step.active ? active_seen : free_seen)++;
    }
    CHECK(active_seen > 5);
    CHECK(free_seen > 5);
  }
}

TEST_CASE("the closed-form contact step is mathematics.md's condensed formula for a massless node") {
  const UniformMesh mesh(1.0, 25);
  const double h = mesh.h(), theta = 0.04 * 0.04 / 4;
  const Tridiagonal a = step_matrix(mesh, mod2(), theta, true);
  const ContactSolver solver(a);
  // Ā = M̄ + θS̄ on the free nodes 1..N−1 and C = (−1/h, 0, …)ᵀ, solved densely.
  const Index m = mesh.unknowns() - 1;
  Eigen::MatrixXd a_bar = Eigen::MatrixXd(a.to_sparse()).bottomRightCorner(m, m);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(m);
  c[0] = -1.0 / h;
  const Eigen::VectorXd w = theta * a_bar.ldlt().solve(c);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int contacts = 0;
  for (int trial = 0; trial < 30; ++trial) {
    Eigen::VectorXd b(mesh.unknowns());
    for (Index i = 0; i < b.size(); ++i) b[i] = uniform(random);
    const double f0 = b[0];  // row 0 of the right-hand side is the load F₀
    const Eigen::VectorXd z_bar = a_bar.ldlt().solve(b.tail(m));
    double u0;
    Eigen::VectorXd u_bar;
    if (z_bar[0] + h * f0 <= 0) {
      u0 = 0.0;
      u_bar = z_bar;
      ++contacts;
    } else {
      u0 = (h * f0 + z_bar[0]) / (1.0 + w[0]);
      u_bar = z_bar - w * u0;
    }
    Eigen::VectorXd u(b.size());
    const ContactStep step = solver.solve(b.data(), u.data(), 1.0);
    CAPTURE(trial);
    CHECK(std::abs(u[0] - u0) < 1e-12);
    CHECK((u.tail(m) - u_bar).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(std::abs(step.multiplier - std::min(0.0, f0 + u_bar[0] / h)) < 1e-10);
  }
  CHECK(contacts > 3);
  CHECK(contacts < 27);
}

TEST_CASE("the contact solver rejects a step matrix that is not positive definite") {
  Tridiagonal a(3);
  a.diag << 1.0, -2.0, 1.0;
  CHECK_THROWS_AS(ContactSolver{a}, std::invalid_argument);
  CHECK_THROWS_WITH_AS(ContactSolver{Tridiagonal(0)}, "contact solver: empty matrix", std::invalid_argument);
}

TEST_CASE("the contact step refuses kappa <= 0 and a solver without a matrix") {
  const ContactSolver solver(p1_mass(UniformMesh(1.0, 4)));
  double b[4] = {1, 1, 1, 1}, u[4];
  CHECK_NOTHROW(solver.solve(b, u, 1.0));
  for (double kappa : {0.0, -1.0, std::nan("")}) {
    CAPTURE(kappa);
    CHECK_THROWS_WITH_AS(solver.solve(b, u, kappa), doctest::Contains("(allowed: a positive finite number)"),
                         std::invalid_argument);
  }
  CHECK_THROWS_AS(ContactSolver().solve(b, u, 1.0), std::invalid_argument);
}

}  // namespace mrm
