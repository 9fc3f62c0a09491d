/// @file step_matrices.cpp
/// @brief The coefficients of one step (★) of every scheme of the paper (mathematics.md §4; the form
/// (★) itself is derived in schemes.cpp): the θ-rule (Crank–Nicolson, backward Euler, CN-switch's
/// θ-step), Paoli–Schatzman, the algebraic contact row of a massless contact node, and the increment form
/// that the steps solve.
#include "steps/step_matrices.hpp"

#include <cmath>

#include <doctest/doctest.h>

#include "fem/mass_redistribution.hpp"

namespace mrm {

// The one builder of (★): the matrices and scalars of the derivation in schemes.cpp, scheme by scheme
// (mathematics.md §4), M the mass (consistent or redistributed), S the stiffness.
//
// Crank–Nicolson, backward Euler and CN-switch's θ-step are the θ-rule with θ = ½, 1 and θ:
// (M + θ²Δt²S) Uⁿ⁺¹ = (M − θ(1−θ)Δt²S) Uⁿ + Δt M Vⁿ + θ(1−θ)Δt²(Fⁿ − λⁿe₀) + θ²Δt²(Fⁿ⁺¹ − λⁿ⁺¹e₀),
// Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/(θΔt) − ((1−θ)/θ)Vⁿ. For θ = ½ the weights θ(1−θ)Δt² = θ²Δt² = Δt²/4 are
// Crank–Nicolson's, 1/(θΔt) = 2/Δt and (1−θ)/θ = 1 (every product by ½ is exact, so these are the
// same doubles as Δt²/4 and 2/Δt); for θ = 1, θ(1−θ)Δt² = 0 and the step is backward Euler's.
// Paoli–Schatzman: (M + βΔt²S) Uⁿ⁺¹ = (2M − (1−2β)Δt²S) Uⁿ − (M + βΔt²S) Uⁿ⁻¹ + Δt²Fⁿ − Δt²λⁿe₀,
// and X = (Uⁿ⁺¹ − Uⁿ)/Δt. With a massless contact node every scheme but the literal Paoli–Schatzman
// writes row 0 as the algebraic contact row S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹: row 0 of A is S₀·, rows 0 of B₁
// and B₂ vanish, κ = 1 and G₀ = F₀ⁿ⁺¹ (set by step_right_hand_side).
//
// The increment form (what the steps solve). Written for Uⁿ⁺¹, (★) loses the velocity to round-off:
// Uⁿ⁺¹ is rounded to ε|U| and the two-level velocity Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/(θΔt) − ((1−θ)/θ)Vⁿ turns that
// into ε|U|/Δt per step, which the next step carries on (Δt M Vⁿ in the right-hand side); over T/Δt
// steps the error grows like Δt⁻² (N = 40, Mod 1, the first impact time: 7.5e-7 off at Δt = h/4096,
// 1.6e-4 at h/65536, 1.8e-3 at h/262144). Solving for ΔU = Uⁿ⁺¹ − Uⁿ instead, with
// Uⁿ⁺¹ = Uⁿ + ΔU, Uⁿ⁻¹ = Uⁿ − W' (W' = Uⁿ − Uⁿ⁻¹, Paoli–Schatzman's previous increment):
//
//     A ΔU = (B₁ − A) Uⁿ + B₂ Vⁿ + G − κλe₀                         (two levels),
//     A ΔU = (B₁ + B₂ − A) Uⁿ − B₂ W' + G − κλe₀                    (three levels),
//
// and B₁ − A = (M − θ(1−θ)Δt²S) − (M + θ²Δt²S) = −θΔt²S, B₁ + B₂ − A = (2M − (1−2β)Δt²S) − (M + βΔt²S)
// − (M + βΔt²S) = −Δt²S, −B₂ = A: the mass cancels exactly in the algebra, so C₁ = −θΔt²S (−Δt²S) is
// built as a multiple of S and no difference of O(|U|) numbers is rounded. ΔU is O(Δt|V|) and is
// computed to ε|ΔU|, so the velocity rate ΔU − memory Vⁿ keeps a relative error ε: the per-step loss is
// ε|V| instead of ε|U|/Δt. The addition Uⁿ + ΔU rounds U by ε|U|/2 per step, a displacement error that
// the scheme carries like any other (no division by Δt): a random walk of √(T/Δt) ε|U| ~ 1e-12 at
// 3·10⁷ steps. The contact row: 0 ≤ u₀ⁿ⁺¹ − g reads Δu₀ ≥ g − u₀ⁿ (the obstacle of the increment), and
// on contact u₀ⁿ⁺¹ = g is written exactly. The algebraic row S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λ becomes
// S₀·ΔU = F₀ⁿ⁺¹ − S₀·Uⁿ − λ: row 0 of C₁ is −S₀ and of C₂ zero (A's row 0 is S₀); it still holds at
// the new level to round-off whatever the old level, since S₀·Uⁿ is read from Uⁿ.
namespace {

void algebraic_contact_row(StepMatrices& m, const Tridiagonal& stiffness) {
  m.a.diag[0] = stiffness.diag[0];
  m.a.upper[0] = stiffness.upper[0];
  for (Tridiagonal* b : {&m.b1, &m.b2, &m.c2}) {
    b->diag[0] = 0.0;
    b->upper[0] = 0.0;
  }
  m.c1.diag[0] = -stiffness.diag[0];
  m.c1.upper[0] = -stiffness.upper[0];
  m.kappa = 1.0;
  m.lambda_in_rhs = 0.0;
  m.algebraic_row = true;
}

}  // namespace

StepMatrices theta_step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, double theta, double dt) {
  const double dt2 = dt * dt, t1 = theta * (1 - theta) * dt2, t2 = theta * theta * dt2;
  StepMatrices m;
  m.a = mass.plus(t2, stiffness);
  m.b1 = mass.plus(-t1, stiffness);
  m.b2 = mass.scaled(dt);
  m.c1 = stiffness.scaled(-theta * dt2);  // B₁ − A = −(θ(1−θ) + θ²)Δt²S
  m.c2 = m.b2;
  m.kappa = t2;
  m.load_now = t1;
  m.load_next = t2;
  m.lambda_in_rhs = t1;
  m.velocity_rate = 1 / (theta * dt);
  m.velocity_memory = (1 - theta) / theta;
  if (contact_node_is_massless(mass)) algebraic_contact_row(m, stiffness);
  return m;
}

StepMatrices step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& p,
                           double dt) {
  switch (p.scheme) {
    case Scheme::crank_nicolson:
    case Scheme::energy_conserving:
    case Scheme::switching:
      return theta_step_matrices(mass, stiffness, 0.5, dt);
    case Scheme::backward_euler:
      return theta_step_matrices(mass, stiffness, 1.0, dt);
    case Scheme::paoli_schatzman:
      break;
    default:  // the other families build their own steps (classes/, explicit_schemes.cpp): no (★)
      throw InvalidParameter(
          "scheme", "the scheme has no step of the form (★) (allowed: the schemes of steps/one_step_form.cpp)");
  }
  const double dt2 = dt * dt, beta = p.beta;
  StepMatrices m;
  m.a = mass.plus(beta * dt2, stiffness);
  m.b1 = mass.scaled(2.0).plus(-(1 - 2 * beta) * dt2, stiffness);
  m.b2 = mass.scaled(-1.0).plus(-beta * dt2, stiffness);
  m.c1 = stiffness.scaled(-dt2);  // B₁ + B₂ − A
  m.c2 = m.a;                     // −B₂
  m.kappa = dt2;
  m.load_now = dt2;
  m.load_next = 0;
  m.velocity_rate = 1 / dt;  // X = (Uⁿ⁺¹ − Uⁿ)/Δt; W' = Uⁿ⁺¹ − Uⁿ
  m.velocity_memory = 0;
  if (contact_node_is_massless(mass) && p.contact_row == ContactRow::algebraic) algebraic_contact_row(m, stiffness);
  return m;
}

Eigen::VectorXd step_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                     double lambda, const Eigen::VectorXd* load_now, const Eigen::VectorXd* load_next) {
  Eigen::VectorXd rhs = step.b1 * u + step.b2 * w;
  if (load_now && load_next) rhs += step.load_now * *load_now + step.load_next * *load_next;
  if (step.algebraic_row)
    rhs[0] = load_next ? (*load_next)[0] : 0.0;
  else
    rhs[0] -= step.lambda_in_rhs * lambda;
  return rhs;
}

Eigen::VectorXd increment_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                          double lambda, const Eigen::VectorXd* load_now,
                                          const Eigen::VectorXd* load_next) {
  Eigen::VectorXd rhs = step.c1 * u + step.c2 * w;
  if (load_now && load_next) rhs += step.load_now * *load_now + step.load_next * *load_next;
  if (step.algebraic_row)
    rhs[0] = step.c1.diag[0] * u[0] + step.c1.upper[0] * u[1] + (load_next ? (*load_next)[0] : 0.0);
  else
    rhs[0] -= step.lambda_in_rhs * lambda;
  return rhs;
}

TEST_CASE("the increment form's matrices are (★)'s, combined exactly: C1 = B1 - A (+ B2), C2 = B2 (or -B2)") {
  const UniformMesh mesh(1.0, 9);
  const double dt = 0.37 * mesh.h();
  for (const MassRedistribution& r : {consistent_mass(), mod3()}) {
    const Tridiagonal m = modified_mass(mesh, r), s = p1_stiffness(mesh);
    for (const Scheme scheme : {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman}) {
      SchemeParameters p;
      p.scheme = scheme;
      if (scheme == Scheme::paoli_schatzman && r.name == "consistent") p.contact_row = ContactRow::literal;
      const StepMatrices k = step_matrices(m, s, p, dt);
      const bool three = scheme == Scheme::paoli_schatzman;
      CAPTURE(r.name);
      CAPTURE(static_cast<int>(scheme));
      for (Index i = 0; i < m.size(); ++i)
        for (Index j = std::max<Index>(0, i - 1); j <= std::min<Index>(m.size() - 1, i + 1); ++j) {
          const double c1 = k.b1(i, j) - k.a(i, j) + (three ? k.b2(i, j) : 0.0);
          const double c2 = three ? -k.b2(i, j) : k.b2(i, j);
          // Every entry is a difference of O(1/h) numbers: equal to a few of their round-offs.
          CHECK(std::abs(k.c1(i, j) - c1) <= 1e-13 * (std::abs(k.a(i, j)) + std::abs(k.b1(i, j)) + 1));
          CHECK(std::abs(k.c2(i, j) - c2) <= 1e-13 * (std::abs(k.b2(i, j)) + 1));
        }
    }
  }
}

TEST_CASE("Crank–Nicolson and backward Euler are the theta-rule with theta = 1/2 and 1, bit for bit") {
  const UniformMesh mesh(1.0, 9);
  const double dt = 0.37 * mesh.h(), dt2 = dt * dt;
  for (const MassRedistribution& r : {consistent_mass(), mod3()}) {
    const Tridiagonal m = modified_mass(mesh, r), s = p1_stiffness(mesh);
    const bool massless = contact_node_is_massless(m);
    SchemeParameters p;
    const StepMatrices cn = step_matrices(m, s, p, dt);
    p.scheme = Scheme::backward_euler;
    const StepMatrices be = step_matrices(m, s, p, dt);
    const Tridiagonal cn_a = m.plus(dt2 / 4, s), be_a = m.plus(dt2, s);
    CAPTURE(r.name);
    for (Index i = massless ? 1 : 0; i < m.size(); ++i) {
      CHECK(cn.a.diag[i] == cn_a.diag[i]);
      CHECK(cn.b1.diag[i] == m.plus(-dt2 / 4, s).diag[i]);
      CHECK(be.a.diag[i] == be_a.diag[i]);
      CHECK(be.b1.diag[i] == m.diag[i]);
      CHECK(be.b2.lower[i] == dt * m.lower[i]);
    }
    CHECK(cn.velocity_rate == 2 / dt);
    CHECK(cn.velocity_memory == 1.0);
    CHECK(be.velocity_rate == 1 / dt);
    CHECK(be.velocity_memory == 0.0);
    CHECK(be.load_now == 0.0);
    CHECK(cn.algebraic_row == massless);
    CHECK(cn.kappa == (massless ? 1.0 : dt2 / 4));
    CHECK(cn.lambda_in_rhs == (massless ? 0.0 : dt2 / 4));
    if (massless) CHECK(cn.a.diag[0] == s.diag[0]);
  }
}

}  // namespace mrm
