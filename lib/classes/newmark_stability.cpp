/// @file newmark_stability.cpp
/// @brief The step limits of the explicit Newmark classes (β < γ/2): the linear limit from the largest
/// eigenvalue of the pencil (K, M), and what it does not cover, the switching laws of central differences
/// with a penalty or with Nitsche's terms (a modified energy, its jumps at the switches, the measured safe
/// fractions).
#include "classes/contact_classes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include "classes/step_pieces.hpp"
#include "fem/pencil.hpp"
#include "steps/contact.hpp"

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// The explicit step limit of Newmark with β < γ/2: derivation in the header of this section.
//
// ## The stability limit of Newmark (β < γ/2) with a contact law
//
// Newmark(β, γ), γ ≥ ½, applied to one mode q'' + ω²q = 0 has an amplification matrix of spectral radius ≤ 1
// (and distinct unit-modulus roots) iff Ω = ωΔt satisfies, for β < γ/2, Ω ≤ Ω_c = 1/√(γ/2 − β) (Hughes,
// The Finite Element Method, §9.1, Table 9.1.1 without damping; Ω_c = 2 for central differences, β = 0,
// γ = ½); β ≥ γ/2 is unconditionally stable. The modes are those of M U'' + K U = 0 with K the stiffness
// of the step's linear law on each side of the contact kink, so the step is stable iff Δt ≤ Ω_c/ω_max,
// ω²_max = the largest eigenvalue of the pencil (K, M) over both sides:
// - free (inactive): K = S_ℓ (S, or S − (θ/γ)ddᵀ for Nitsche);
// - active: penalty K = S + (γ₀/h)e₀e₀ᵀ (the penalty stiffness γ₀/h on the contact node); Nitsche
//   K = S_ℓ + (1/γ)(γe₀ + θd)(γe₀ + d)ᵀ (the derivative of −F_c); exact enforcement: the contact node held,
//   the pencil on the nodes 1..N−1.
// With a massless contact node the nodes 1..N−1 carry the modes and node 0 is eliminated by its algebraic
// row: K is replaced by its Schur complement on 1..N−1, K̂ = K₁₁-block − K₁₀K₀₁/K₀₀ (free, penalty and
// Nitsche active), or node 0 is held (exact enforcement active). A Schur complement of a positive
// semi-definite K is ≤ the held block in the Loewner order, so the held pencil (S on 1..N−1, M on 1..N−1)
// bounds every case for the symmetric laws: it is the one used. (For Nitsche with θ ≠ 1 K is not
// symmetric; the limit is that of its symmetric part, a conjecture checked against the eigenvalues of the
// actual matrices in the doctest.)
// For a symmetric tridiagonal K and a positive definite tridiagonal M, the number of eigenvalues of the
// pencil below σ is the number of negative pivots of the LDLᵀ factorisation of K − σM (Sylvester's law
// of inertia): a bisection on σ gives ω²_max to a relative 1e-13 in O(N) per count, and its upper end is
// the bound used (so the refusal's limit is never above the true one by more than that).
namespace {

// The rows and columns first..n−1 of a tridiagonal matrix.
Tridiagonal trailing_block(const Tridiagonal& a, Index first) {
  const Index n = a.size() - first;
  Tridiagonal b(n);
  b.diag = a.diag.tail(n);
  b.upper = a.upper.tail(n);
  b.lower = a.lower.tail(n);
  b.lower[0] = 0.0;
  return b;
}

}  // namespace

double newmark_stability_limit(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& p,
                               double contact_compliance) {
  const SchemeInfo* entry = find_entry(contact_class_schemes(), p.scheme);
  if (!entry || !entry->takes(SchemeParameter::newmark_beta) || p.newmark_beta >= 0.5 * p.newmark_gamma)
    return HUGE_VAL;
  const double omega_c = 1 / std::sqrt(0.5 * p.newmark_gamma - p.newmark_beta);
  const double h = contact_compliance;
  double largest = 0;  // ω²_max over the sides of the kink
  if (contact_node_is_massless(mass)) {
    largest = largest_pencil_eigenvalue(trailing_block(stiffness, 1), trailing_block(mass, 1));
  } else {
    // Free: S_ℓ; active: the law's stiffness added (symmetric part), or node 0 held (exact enforcement).
    Tridiagonal free = stiffness, active = stiffness;
    if (p.scheme == Scheme::penalty) active.diag[0] += p.penalty / h;
    if (p.scheme == Scheme::nitsche) {
      const double gamma = p.nitsche_gamma / h, theta = p.nitsche_theta;
      // −(θ/γ)ddᵀ with d = (−1/h, 1/h): entries ∓θ/(γh²) on the first element.
      const double c = theta == 0 ? 0.0 : theta / (gamma * h * h);  // θ = 0: none, whatever γ
      free.diag[0] -= c, free.diag[1] -= c, free.upper[0] += c, free.lower[1] += c;
      active = free;
      // + (1/γ)(γe₀ + θd)(γe₀ + d)ᵀ, symmetrised: a = γe₀ + θd = (γ − θ/h, θ/h), b = γe₀ + d = (γ − 1/h, 1/h).
      const double a0 = gamma - theta / h, a1 = theta / h, b0 = gamma - 1 / h, b1 = 1 / h;
      active.diag[0] += a0 * b0 / gamma;
      active.diag[1] += a1 * b1 / gamma;
      active.upper[0] += 0.5 * (a0 * b1 + a1 * b0) / gamma;
      active.lower[1] += 0.5 * (a0 * b1 + a1 * b0) / gamma;
    }
    largest = largest_pencil_eigenvalue(free, mass);
    if (p.scheme == Scheme::newmark)
      largest = std::max(largest, largest_pencil_eigenvalue(trailing_block(stiffness, 1), trailing_block(mass, 1)));
    else
      largest = std::max(largest, largest_pencil_eigenvalue(active, mass));
  }
  return omega_c / std::sqrt(largest);
}

void check_newmark_step(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& p, double dt,
                        double contact_compliance, double mesh_size) {
  const double limit = newmark_stability_limit(mass, stiffness, p, contact_compliance);
  if (dt <= limit * (1 + 1e-12)) return;
  char text[320];
  std::snprintf(
      text, sizeof text,
      "dt = %.6g is above the stability limit of %s with Newmark beta = %g < gamma/2 = %g (the largest frequency "
      "of M^-1 K with the contact law's stiffness) (allowed: 0 < dt <= %.6g",
      dt, find_entry(contact_class_schemes(), p.scheme)->id.c_str(), p.newmark_beta, 0.5 * p.newmark_gamma, limit);
  std::string message = text;
  if (mesh_size > 0) {
    std::snprintf(text, sizeof text, ", i.e. Courant number <= %.6g", limit / mesh_size);
    message += text;
  }
  throw InvalidParameter("dt", message + "; or beta >= gamma/2)");
}

// ---------------------------------------------------------------------------------------------------
// ## Central differences with a penalty: the linear limit is necessary, not sufficient
//
// Newmark(0, ½) with the penalty k = γ₀/h on the gap function q = u₀ + g₀ and a contact node with inertia
// (no load) is central differences with a force that switches between two linear laws:
//
//     M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹) = −Δt²(SUⁿ + k q₋ⁿ e₀),      q₋ = min(0, q),                              (CD)
//
// (checked row by row in the doctest "Newmark with beta = 0 is explicit"). With vⁿ⁺½ = (Uⁿ⁺¹ − Uⁿ)/Δt, take
// the scalar product of (CD) with (Uⁿ⁺¹ − Uⁿ⁻¹)/(2Δt²) = (vⁿ⁺½ + vⁿ⁻½)/2. The left side is
// ½‖vⁿ⁺½‖²_M − ½‖vⁿ⁻½‖²_M; S symmetric gives −½(UⁿᵀSUⁿ⁺¹ − Uⁿ⁻¹ᵀSUⁿ); and, writing q = q₋ + q₊,
// −½k q₋ⁿ(qⁿ⁺¹ − qⁿ⁻¹) = −½k(q₋ⁿq₋ⁿ⁺¹ − q₋ⁿ⁻¹q₋ⁿ) − ½k q₋ⁿ(q₊ⁿ⁺¹ − q₊ⁿ⁻¹). So the modified energy of the
// half level
//
//     E_h^{n+½} = ½ vⁿ⁺½ᵀ M vⁿ⁺½ + ½ UⁿᵀS Uⁿ⁺¹ + ½ k q₋ⁿ q₋ⁿ⁺¹                                         (Eh)
//
// changes over step n by exactly
//
//     J_n = E_h^{n+½} − E_h^{n−½} = −½ k q₋ⁿ (q₊ⁿ⁺¹ − q₊ⁿ⁻¹),                                            (J)
//
// zero unless qⁿ < 0 and a neighbouring level has q > 0: only a change of the contact status (a switch)
// changes E_h. Entering (qⁿ⁻¹ > 0 > qⁿ, qⁿ⁺¹ ≤ 0): J = −½k|qⁿ|qⁿ⁻¹ < 0, a loss; leaving (qⁿ⁻¹ ≤ 0, qⁿ < 0 <
// qⁿ⁺¹): J = +½k|qⁿ|qⁿ⁺¹ > 0, a gain; a contact of one level: ½k|qⁿ|(qⁿ⁺¹ − qⁿ⁻¹), either sign. The sign of
// each jump depends on where the crossing falls inside the step, which the step size does not control.
//
// What the linear limit gives. Δt = rΔt_max, Δt_max = 2/ω_max with ω²_max the largest eigenvalue of
// (S + ke₀e₀ᵀ, M) (newmark_stability_limit). With Ū the mean of Uⁿ, Uⁿ⁺¹ and δ = q₋ⁿ⁺¹ − q₋ⁿ,
// UⁿᵀSUⁿ⁺¹ = ŪᵀSŪ − ¼Δt² vᵀSv and q₋ⁿq₋ⁿ⁺¹ = q̄₋² − ¼δ², |δ| ≤ Δt|v₀| (min(0, ·) is 1-Lipschitz), so
//
//     E_h ≥ ½ vᵀ(M − ¼Δt²(S + ke₀e₀ᵀ)) v + ½ŪᵀSŪ + ½k q̄₋² ≥ (1 − r²) ½‖v‖²_M + ½ŪᵀSŪ + ½k q̄₋² ≥ 0:       (C)
//
// below the limit E_h is a norm of the state, with the constant 1 − r² (r → 1: E_h no longer controls the
// kinetic energy). That is all the limit gives: it makes each side's step conservative, not the switches.
//
// A bound of the jumps. At a switch q changes sign between two adjacent levels, so the product of the two
// moduli is at most (Δq/2)² = ¼Δt²v₀² on that half level (arithmetic–geometric means); for each case of (J),
//
//     |J_n| ≤ ⅛ k Δt² max(v₀ⁿ⁻½², v₀ⁿ⁺½²).                                                             (B)
//
// With A = M − ¼Δt²(S + ke₀e₀ᵀ) ≥ (1 − r²)M, v₀² ≤ (e₀ᵀA⁻¹e₀) vᵀAv ≤ 2E_h (e₀ᵀA⁻¹e₀), so a switching step
// changes E_h by at most ρ times the larger of its two values, ρ = ¼kΔt² e₀ᵀA⁻¹e₀; for ρ < 1,
//
//     E_h^{n+½} ≤ E_h^{½} (1 − ρ)^{−s_n},      s_n the number of switching steps up to n.                (G)
//
// (G) is sufficient for a finite number of impacts only: ρ > 0 for every Δt > 0 (ρ ~ ¼r²Ω_c² k/(k + ·) of
// the node's stiffness, an O(1) fraction near the limit), so no step size makes (G) uniform in time, and
// the energy method proves no step limit that is sufficient over all times. The problem without gap or
// load is positively homogeneous (U ↦ cU, c > 0, maps runs to runs), so a run that gains a factor over one
// return gains it again: energy that grows, grows exponentially, and boundedness over all times is a
// question of the switched map's largest Lyapunov exponent, which (G) does not decide. What is measured
// instead (fig_classes, block 5, the paper's benchmark, the consistent mass): E_max/E₀ over 10, 10² and 10³
// periods for r = Δt/Δt_max and γ₀ = 1, 10, 100; penalty_measured_safe_fraction below is the edge of the
// measured region where E_max ≤ 2E₀ (a measured region, not a derived bound; fig_classes checks it
// against its own measurement and fails when they differ). The doctest checks (J), (B), (C) and (G).
double penalty_modified_energy(const Tridiagonal& mass, const Tridiagonal& stiffness, double k, double gap, double dt,
                               const Eigen::VectorXd& u_now, const Eigen::VectorXd& u_next) {
  const Eigen::VectorXd v = (u_next - u_now) / dt;
  return 0.5 * v.dot(mass * v) + 0.5 * u_now.dot(stiffness * u_next) +
         0.5 * k * std::min(0.0, u_now[0] + gap) * std::min(0.0, u_next[0] + gap);
}

double penalty_switch_jump(double k, double q_previous, double q_now, double q_next) {
  return -0.5 * k * std::min(0.0, q_now) * (std::max(0.0, q_next) - std::max(0.0, q_previous));
}

double penalty_measured_safe_fraction(double periods) {
  // fig_classes block 5 (measured, not derived): the largest r of the grid 0.3, 0.4, …, 0.9, 0.99 at which
  // every run (N = 16, 64; γ₀ = 1, 10, 100) kept E_max ≤ 2E₀ up to that many periods; 0: none measured.
  if (periods <= 10) return 0.7;
  if (periods <= 100) return 0.5;
  if (periods <= 1000) return 0.3;
  return 0.0;
}

// ---------------------------------------------------------------------------------------------------
// ## Central differences with Nitsche's terms: the same route, and where it stops
//
// Newmark(0, ½) with Nitsche's law (file comment: γ = γ₀/h, d the P1 gradient at x = 0, σ = d·U = u_x(0),
// ℓ = γe₀ + d, P = ℓ·U + γg₀, λ = min(0, P), F_c = (θ/γ)σd − (1/γ)P₋(γe₀ + θd)) and a contact node with
// inertia. Write γe₀ + θd = ℓ − (1 − θ)d: the force splits into a gradient and a remainder,
//
//     F_c = −∇[(1/2γ)P₋² − (θ/2γ)σ²] + ((1 − θ)/γ) P₋ d,                                              (Nθ)
//
// and with S_θ = S − (θ/γ)ddᵀ (the step's S_ℓ) the scheme is M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹) = −Δt²(S_θUⁿ + (1/γ)P₋ⁿℓ
// − ((1 − θ)/γ)P₋ⁿd). The penalty's pairing with (Uⁿ⁺¹ − Uⁿ⁻¹)/(2Δt²) goes through term by term: ℓ·(Uⁿ⁺¹ −
// Uⁿ⁻¹) = Pⁿ⁺¹ − Pⁿ⁻¹ plays q's part with k = 1/γ, and d·(Uⁿ⁺¹ − Uⁿ⁻¹) = σⁿ⁺¹ − σⁿ⁻¹. So the modified energy
//
//     E_N^{n+½} = ½ vⁿ⁺½ᵀ M vⁿ⁺½ + ½ UⁿᵀS_θ Uⁿ⁺¹ + (1/2γ) P₋ⁿ P₋ⁿ⁺¹                                       (EN)
//
// changes over step n by exactly
//
//     J_n^N = −(1/2γ) P₋ⁿ (P₊ⁿ⁺¹ − P₊ⁿ⁻¹) + ((1 − θ)/2γ) P₋ⁿ (σⁿ⁺¹ − σⁿ⁻¹).                               (JN)
//
// What is the same and what differs from the penalty:
// - θ = 1 (symmetric Nitsche, F_c = −∇Φ): (JN) is (J) with q → P, k → 1/γ: E_N changes only at a switch,
//   by at most (1/8γ)Δt² max (ℓ·v)² (the bound (B), |ΔP| = Δt|ℓ·v|); the coercivity (C) and the Grönwall
//   bound (G) follow as for the penalty with S_θ ≥ 0 (θ < γ₀) and the active side's symmetric stiffness
//   S_θ + (1/γ)ℓℓᵀ, whose largest frequency newmark_stability_limit takes. Same conclusion: necessary, not
//   sufficient over all times.
// - θ ≠ 1 (θ = 0 is GetFEM's default): the second term of (JN) is the work of the circulatory force
//   ((1 − θ)/γ)P₋d (not a gradient: the active side's stiffness S_θ + (1/γ)(ℓ − (1 − θ)d)ℓᵀ is not
//   symmetric), nonzero at every step in contact, not only at switches, and of either sign. Central
//   differences with a non-symmetric stiffness conserve no quadratic form, so no modified energy is
//   conserved even between switches, and the step limit itself is the conjecture stated in
//   newmark_stability_limit's doctest (the symmetric part's frequency bounds the eigenvalues' moduli).
//   Nothing is derived here beyond (JN); the region is measured.
//
// Measured region (fig_classes, block 6, the paper's benchmark, the consistent mass, N = 16 and 64,
// (θ, γ₀) ∈ {0, 1} × {5, 50}, r = Δt/Δt_max on the penalty's grid): nitsche_measured_safe_fraction holds its
// edges, fig_classes fails when they differ, bar1d warns outside them. The doctest below checks (JN) to
// round-off for θ = 1 and θ = 0, and that the θ = 0 remainder is not zero between switches.
double nitsche_measured_safe_fraction(double periods) {
  // fig_classes block 6 (measured, not derived): the largest r of the grid 0.3, 0.4, …, 0.9, 0.99 at which
  // every run (N = 16, 64; θ = 0, 1; γ₀ = 5, 50) kept E_max ≤ 2E₀ up to that many periods; 0: none. Up to 10³
  // periods (N = 16) not even r = 0.3 did (E_max/E₀ 2.03 at θ = 0, γ₀ = 5; 3.39 at θ = 0, γ₀ = 50), where the
  // penalty's edge is 0.3; beyond 10³ periods nothing is measured.
  if (periods <= 10) return 0.7;
  if (periods <= 100) return 0.5;
  return 0.0;
}

}  // namespace mrm
