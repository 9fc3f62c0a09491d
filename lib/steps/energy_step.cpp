/// @file energy_step.cpp
/// @brief Energy-conserving Crank–Nicolson (EC) and Crank–Nicolson with a θ-step at each status change
/// (CN-switch): the derivation (mathematics.md §12) and the scalar pieces of both steps.
///
/// ### 1. The reduced problem and its energy.
///
/// With a massless contact node the contact row is algebraic (mathematics.md §3): u₀ = max(0, s) with
/// s = u₁ + hF₀. Substituting it into the free rows, M̄Ü + S̄Ū + C u₀ = F̄ with C = (−1/h, 0, …)ᵀ, the
/// contact node acts on node 1 through the force −C u₀ = (u₀/h) e₁ = ψ'(s) e₁, where
///
///     ψ(s) = max(0, s)²/(2h),   ψ'(s) = max(0, s)/h   (ψ convex, ψ' nondecreasing and 1/h-Lipschitz).
///
/// For f = 0 the reduced problem is the gradient system M̄Ü + ∇Φ(Ū) = 0 with
///
///     Φ(Ū) = ½ ŪᵀS̄Ū − ψ(u₁),
///
/// and Φ is the library's potential energy ½UᵀSU evaluated at the condensed u₀: the first element's
/// strain (u₁ − u₀)/h is 0 while the node is free, so Φ = (1/2h) Σ over the elements of the squared
/// differences of (u₀, u₁, …, u_{N−1}, 0), the form used below. The sign: S̄ counts the first element
/// as if u₀ were 0 (S̄₁₁ = 2/h); a free contact node follows node 1 and takes that element's energy
/// u₁²/(2h) away again, hence −ψ. The energy E = ½ VᵀM̄V + Φ(Ū) is conserved by the exact flow.
///
/// Φ is convex and C¹: its Hessian where it exists is S̄ − (1/h) e₁e₁ᵀ (free) or S̄ (active), and
/// S̄ − (1/h) e₁e₁ᵀ is the stiffness matrix of the elements [x₁, x₂], …, [x_{N−1}, x_N] with node 1 free
/// and x_N clamped, positive definite. The same inequality bounds every step below:
///
///     (L)  DᵀS̄D ≥ (D₁)²/h for every vector D.
///
/// ### 2. Crank–Nicolson's energy defect.
///
/// A θ-step (θ = ½: Crank–Nicolson; θ = 1: backward Euler) of M̄V̇ = −S̄Ū + ψ'(s)e₁ is, with D = Ūⁿ⁺¹ − Ūⁿ,
/// ΔV = Vⁿ⁺¹ − Vⁿ, a = sⁿ and b = sⁿ⁺¹,
///
///     D = Δt((1 − θ)Vⁿ + θVⁿ⁺¹),   M̄ΔV = Δt[−S̄((1 − θ)Ūⁿ + θŪⁿ⁺¹) + g e₁],
///     g = (1 − θ)ψ'(a) + θψ'(b).
///
/// Since (1 − θ)Vⁿ + θVⁿ⁺¹ = V̄ + (θ − ½)ΔV with V̄ the mean, ½(Vⁿ⁺¹ + Vⁿ)ᵀM̄ΔV = DᵀM̄ΔV/Δt − (θ − ½)‖ΔV‖²_M̄,
/// and (1 − θ)Ūⁿ + θŪⁿ⁺¹ = Ū-mean + (θ − ½)D. Adding the change of Φ gives the energy identity (f = 0)
///
///     Eⁿ⁺¹ − Eⁿ = −(θ − ½)(‖ΔV‖²_M̄ + DᵀS̄D) + κ(a, b),   κ(a, b) = (b − a) g − (ψ(b) − ψ(a)).    (E)
///
/// The contact term κ is the error of the quadrature g(b − a) of ∫ₐᵇ ψ'. For Crank–Nicolson,
/// κ = ½(ψ'(a) + ψ'(b))(b − a) − (ψ(b) − ψ(a)) is 0 when a and b lie on the same side of 0 (ψ is 0 or a
/// quadratic there, and the trapezoidal rule is exact), ab/(2h) ≤ 0 at an impact (a ≥ 0 > b) and
/// −ab/(2h) ≥ 0 at a release (a < 0 ≤ b): Crank–Nicolson gains energy at every release. As a and b
/// have opposite signs there, |ab| ≤ (b − a)²/4 and |κ| ≤ (b − a)²/(8h) ≈ (Δt/h)² h v²/8 with v the
/// speed of node 1: small for Δt ≲ h, and the gains at releases win for Δt ≫ h.
///
/// ### 3. EC: the discrete gradient.
///
/// Replace the trapezoidal force by the discrete gradient of ψ,
///
///     g = φ(a, b) = (ψ(b) − ψ(a))/(b − a)   (ψ'(a) when b = a).
///
/// Then κ = 0 in (E) with θ = ½: Eⁿ⁺¹ = Eⁿ exactly, at every step, status changes included. With
/// χ = 2hφ (independent of h), case by case by the signs:
///
///     a < 0, b < 0:  χ = 0;                a ≥ 0, b ≥ 0:  χ = a + b;
///     a < 0 ≤ b:     χ = b²/(b − a);       a ≥ 0 > b:     χ = a²/(a − b),
///
/// (the split by the status of mathematics.md §3, active when s < 0; at s = 0 neighbouring cases agree),
/// which is Crank–Nicolson's χ = max(0, a) + max(0, b) in the first two cases: EC is Crank–Nicolson on
/// every step without a status change, and no case divides by zero.
///
/// The step. Everything in the step is linear except g. Write it as Crank–Nicolson's with the contact
/// force moved to the right: (M̄ + θS̄)Ūⁿ⁺¹ = M̄(Ūⁿ + ΔtVⁿ) − θS̄Ūⁿ + 2θ g e₁, θ = Δt²/4. With Ā = M̄ + θS̄
/// (constant, factorised once), z = Ā⁻¹(M̄(Ūⁿ + ΔtVⁿ) − θS̄Ūⁿ) and r = Ā⁻¹e₁,
///
///     Ūⁿ⁺¹ = z + 2θ g r,   so   b = z₁ + 2θ(Ā⁻¹)₁₁ φ(a, b) = c + μ χ(a, b),
///     c = z₁ (+ hF₀ⁿ⁺¹ with a load),   μ = θ(Ā⁻¹)₁₁/h.
///
/// (In mathematics.md §4's notation Ūⁿ⁺¹ = z − w u₀ with w = θĀ⁻¹C = −(θ/h) r: the contact node's value u₀
/// is replaced by the effective 2hφ(a, b) split over the two levels.) Two facts make this scalar
/// equation harmless:
///
/// (i) 0 < μ < 1. By (L), Ā − (θ/h)e₁e₁ᵀ = M̄ + θ(S̄ − (1/h)e₁e₁ᵀ) is positive definite, and for a
///     positive definite Ā that holds if and only if (θ/h) e₁ᵀĀ⁻¹e₁ < 1.
/// (ii) χ(a, ·) is nondecreasing with slope at most 1: χ(a, b) = (1/(b − a)) ∫ₐᵇ p with p(σ) = 2max(0, σ)
///     nondecreasing and 2-Lipschitz, so ∂χ/∂b = (1/(b − a)²) ∫ₐᵇ (p(b) − p(σ)) dσ ∈ [0, 1].
///
/// Hence G(s) = s − μχ(a, s) − c is continuous with G(s₂) − G(s₁) ≥ (1 − μ)(s₂ − s₁): strictly
/// increasing from −∞ to +∞, one root exactly, and a change δc of the data moves it by at most
/// |δc|/(1 − μ). Its sign is the sign of −G(0), with χ(a, 0) = max(0, a): the root is positive if and
/// only if c > −μ max(0, a). Then, case by case (P = a + c):
///
///     a < 0, c ≤ 0:       s = c   (no contact force).
///     a ≥ 0, c > −μa:     s − μ(a + s) = c,  s = (c + μa)/(1 − μ)   (Crank–Nicolson's value).
///     a < 0 < c (release): s − μs²/(s − a) = c with s − a > 0, i.e. (1 − μ)s² − Ps + ca = 0. The product
///         of its roots ca/(1 − μ) ≤ 0: the wanted root is the non-negative one,
///         s = (P + D)/(2(1 − μ)) for P > 0, s = 2ca/(P − D) for P ≤ 0,   D = √(P² − 4(1 − μ)ca) ≥ |P|,
///         both forms free of cancellation.
///     a ≥ 0, c ≤ −μa (impact): s − μa²/(a − s) = c with a − s > 0, i.e. s² − Ps + a(c + μa) = 0. The
///         product of its roots a(c + μa) ≤ 0: the wanted root is the non-positive one,
///         s = (P − D')/2 for P ≤ 0, s = 2a(c + μa)/(P + D') for P > 0,
///         D' = √((a − c)² − 4μa²) = √((a − c − 2√μ a)(a − c + 2√μ a)), real since a − c ≥ (1 + μ)a ≥ 2√μ a.
///
/// Each quadratic has one root on each side of 0 (or at 0), and G has one root: the root found on the
/// side predicted by G(0) is G's root.
///
/// In the library's step. The library solves Crank–Nicolson on all unknowns 0..N−1 with the algebraic
/// contact row (schemes.cpp): after the sweep down from node N−1 (contact.cpp), row 1 reads
/// d₁u₁ⁿ⁺¹ + A₁₀u₀ = y₁ with A₁₀ = θS₁₀ = −θ/h, d₁ = 1/(Ā⁻¹)₁₁ the pivot at node 1, and y₁ containing the
/// old level's contact term −B₁₀u₀ⁿ = (θ/h)u₀ⁿ. The total contact force on row 1 is (θ/h)(u₀ⁿ + u₀) and
/// must be 2θφ = (θ/h)χ(a, b): so the sweep up starts from the value u₀ = χ(a, b) − u₀ⁿ (not the contact
/// node's new value max(0, b)), and
///
///     u₁ⁿ⁺¹ = z₁ + μ(χ(a, b) − u₀ⁿ),   z₁ = y₁/d₁,   μ = −A₁₀/d₁ = θ(Ā⁻¹)₁₁/h,
///
/// which is the scalar equation with c = z₁ − μu₀ⁿ + hF₀ⁿ⁺¹ (in s = u₁ + hF₀). The contact node's new value
/// is max(0, b), the condensed row's at the new level, and λⁿ⁺¹ = min(0, b)/h. On a step without a status
/// change χ − u₀ⁿ = max(0, b): the sweep starts from the contact node's own value, as Crank–Nicolson's.
///
/// With a load. ψ is then evaluated at s = u₁ + hF₀(t) (the contact row couples u₁ and the load at the
/// contact node), a = u₁ⁿ + hF₀ⁿ, and the right-hand side gains θ(F̄ⁿ + F̄ⁿ⁺¹); the scalar equation is the
/// same with c = z₁ + hF₀ⁿ⁺¹. The mechanical energy E = ½VᵀM̄V + ½ŪᵀS̄Ū − ψ(s) then changes by the work of
/// the loads only: with D = Ūⁿ⁺¹ − Ūⁿ and u₁ⁿ⁺¹ − u₁ⁿ = (b − a) − h(F₀ⁿ⁺¹ − F₀ⁿ),
///
///     Eⁿ⁺¹ − Eⁿ = ½(F̄ⁿ + F̄ⁿ⁺¹)·D − ½ χ(a, b)(F₀ⁿ⁺¹ − F₀ⁿ),
///
/// the discrete form of dE/dt = F̄·V − ψ'(s) h dF₀/dt. (The library's energy ½VᵀMV + ½UᵀSU over all nodes
/// with u₀ = max(0, s) is this E plus F₀u₀.)
///
/// With a gap. The constraint is u₀ + g₀ ≥ 0 (g₀ ≥ 0 the initial gap): the condensed row gives
/// u₀ = max(−g₀, u₁ + hF₀) = max(0, s) − g₀ with s = u₁ + hF₀ + g₀, λ = min(0, s)/h, and the force of the
/// contact node on node 1 is u₀/h = ψ'(s) − g₀/h: ψ's force and a constant one. The reduced potential is
/// Φ = ½ŪᵀS̄Ū − ψ(s) + g₀(2u₁ + g₀)/(2h) (f = 0). It is the library's ½UᵀSU at the condensed u₀: the
/// first element's energy (u₁ − u₀)²/(2h) is 0 when free and (u₁ + g₀)²/(2h) in contact, min(0, s)²/(2h)
/// in both cases, S̄ counts it as u₁²/(2h), and −u₁²/(2h) + min(0, s)²/(2h) = −ψ(s) + (s² − u₁²)/(2h);
/// its u₁-derivative is (S̄Ū)₁ − u₀/h. The extra term is affine in u₁, and the trapezoidal rule integrates its constant force exactly: EC replaces
/// ψ' by φ(a, b) at a = sⁿ, b = sⁿ⁺¹ and keeps the constant force, and conserves E exactly as without a
/// gap. In the step, row 1's contact force (θ/h)(u₀ⁿ + u₀) must be (θ/h)(χ(a, b) − 2g₀): the sweep up
/// starts from u₀ = χ(a, b) − 2g₀ − u₀ⁿ, so u₁ⁿ⁺¹ = z₁ + μ(χ − 2g₀ − u₀ⁿ) and
///
///     b = c + μχ(a, b),   c = z₁ − μu₀ⁿ + hF₀ⁿ⁺¹ + (1 − 2μ)g₀,
///
/// the same scalar equation (unique root, closed form); the new u₀ is max(0, b) − g₀. On a step without
/// a status change the sweep starts from u₀ⁿ⁺¹ itself (χ − 2g₀ − u₀ⁿ = max(0, b) − g₀ both when a, b < 0
/// and when a, b ≥ 0), Crank–Nicolson's step with the obstacle −g₀ (doctest below).
///
/// ### 4. CN-switch: a θ-step at each status change.
///
/// Take the Crank–Nicolson step; if the contact status changes across it (active: s < 0, the contact
/// node held at 0 by a compressive λ), discard it and take a θ-step instead (default θ = 1, backward
/// Euler). The energy never increases (f = 0):
///  - a Crank–Nicolson step without a status change has κ = 0 in (E): Eⁿ⁺¹ = Eⁿ;
///  - a θ-step: by (E) and (L), Eⁿ⁺¹ − Eⁿ ≤ −(θ − ½)‖ΔV‖²_M̄ + ρ_θ(a, b), ρ_θ = κ − (θ − ½)(b − a)²/h, and
///    case by case (g = (1 − θ)ψ'(a) + θψ'(b)):
///        a, b < 0:          ρ_θ = −(θ − ½)(b − a)²/h ≤ 0;
///        a, b ≥ 0:          ρ_θ = 0  (κ = (θ − ½)(b − a)²/h);
///        a ≥ 0 > b (impact): ρ_θ = (θab − (θ − ½)b²)/h ≤ 0;
///        a < 0 ≤ b (release): ρ_θ = ((1 − θ)|ab| − (θ − ½)a²)/h.
///    For θ = 1 every case is ≤ 0, so a backward-Euler step dissipates at least ½‖ΔV‖²_M̄. (The same
///    follows from the convexity of Φ alone: Φ(Ūⁿ) ≥ Φ(Ūⁿ⁺¹) + ∇Φ(Ūⁿ⁺¹)·(Ūⁿ − Ūⁿ⁺¹).) For ½ < θ < 1 a
///    release with (1 − θ)|b| > (θ − ½)|a| may still gain energy: the guarantee is θ = 1's.
/// With the consistent mass the contact node keeps its inertia and the contact is the constraint
/// u₀ ≥ 0 itself; the same holds with κ = −(u₀ⁿ⁺¹ − u₀ⁿ)((1 − θ)λⁿ + θλⁿ⁺¹) = θλⁿ⁺¹u₀ⁿ − (1 − θ)λⁿu₀ⁿ⁺¹
/// (by λu₀ = 0 at each level): 0 without a status change, ≤ 0 for θ = 1. EC has no analogue there
/// (the indicator of u₀ ≥ 0 has no discrete gradient): it needs a massless contact node.
///
/// ### 5. Round-off: how much a step that does not increase E may seem to gain.
///
/// The guarantees above hold in exact arithmetic; the computed energy of the computed states can still
/// rise by round-off on a step of CN-switch. A model of its size, on a mesh of N elements (h = L/N): the
/// computed Ūⁿ⁺¹ is the exact step from the computed (Ūⁿ, Vⁿ) with every nodal value off by at most c ulps
/// of the largest, |δu_i| ≤ c ε max|u| (the tridiagonal solve is backward stable and Ā is diagonally
/// dominant; the contact root is a closed form of a few operations), and max|u| ≤ √(L‖u_x‖²) ≤ √(2EL)
/// since u vanishes at the clamp. Then
///  - the strain energy: ‖δU‖²_S = Σ(δu_{i+1} − δu_i)²/h ≤ 4N max|δu|²/h, so ‖δU‖_S ≤ 2Ncε√(2E) and ½‖U‖²_S
///    moves by at most ‖U‖_S‖δU‖_S ≤ 4cNε E: the differences u_{i+1} − u_i are h/L times smaller than u,
///    so an ulp of u is N ulps of the strain;
///  - the kinetic energy: V is formed as 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ (backward Euler: (Uⁿ⁺¹ − Uⁿ)/Δt), so
///    |δv_i| ≤ 2 max|δu|/Δt and ‖δV‖_M ≤ 2cε√(2E)·L/Δt = 2cεN(h/Δt)√(2E): ½‖V‖²_M moves by at most
///    4cNε(h/Δt) E;
///  - the evaluation of Eⁿ and Eⁿ⁺¹ (sums of N + 1 products each) adds at most 2(N + 2)ε E.
/// With c = 2 the sum is (8(1 + h/Δt) + 2 + 4/N) Nε E ≤ 11 Nε(1 + h/Δt) E (N ≥ 4); allowed, with E ≤ E₀:
///
///     (Eⁿ⁺¹ − Eⁿ)/E₀ ≤ 16 N ε (1 + h/Δt)   (energy_round_off_per_step).
///
/// This is a model, not a proof: the per-node error c of the solve is assumed, not bounded (for Δt ≫ h, Ā
/// is ill-conditioned). The checks below and fig_energy_schemes (every run of its map, N = 16 … 128,
/// Δt/h = ¼ … 40, and the long runs) measure the largest increase against it.
///
/// The bound max|u| ≤ √(2EL) needs u to vanish somewhere: a clamped end. A bar with a free far end that
/// has left the obstacle translates: max|u| ≈ |u(0, t)| grows like its velocity times t, with E fixed.
/// The same model then gives an error of order ε N u(0, t)² / L in the computed energy (relative:
/// ε N u(0, t)²/(L E₀)), growing like t²: the differences u_{i+1} − u_i keep their absolute error ε|u|,
/// and the end rows of the energy are evaluated as products (S_ii u_i² + 2 S_{i,i−1} u_{i−1}u_i, each
/// of size u²/h, which cancel; fast_step.cpp sums the interior rows in differences). fig_energy_schemes'
/// drifting bar (EC + Mod 3 on the layered bar, N = 50 and 100, t up to 1000) measures the range of the
/// computed energy against that scale; the report quotes the ratio. The doctest "EC on a bar that flies
/// off" (time/one_step_form_runs.cpp) separates the evaluation from the step on a uniform bar: the
/// state's energy summed in differences drifts 40–60 times less than the evaluated one, so most of the
/// drift is the evaluation's; the rest, also growing with u, is the step's (V = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ
/// loses ε|u|/Δt per step). Summing the end rows in differences too would remove the larger part; the
/// step is left as it is, so that every output keeps its bits.
#include "steps/energy_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <doctest/doctest.h>

#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "steps/step_matrices.hpp"

namespace mrm {

double energy_round_off_per_step(long elements, double dt_over_h) {
  if (!(elements >= 1 && std::isfinite(dt_over_h) && dt_over_h > 0))
    throw std::invalid_argument("energy_round_off_per_step: N >= 1 and a finite dt/h > 0 are required");
  return 16 * static_cast<double>(elements) * std::numeric_limits<double>::epsilon() * (1 + 1 / dt_over_h);
}

double contact_energy(double s, double h) {
  const double p = std::max(0.0, s);
  return p * p / (2 * h);
}

double contact_energy_derivative(double s, double h) { return std::max(0.0, s) / h; }

double contact_secant(double a, double b) {
  const bool active_a = contact_is_active(a), active_b = contact_is_active(b);
  if (active_a && active_b) return 0.0;
  if (!active_a && !active_b) return a + b;
  if (active_a) return b * b / (b - a);  // release: a < 0 ≤ b
  return a * a / (a - b);                // impact: b < 0 ≤ a
}

double contact_discrete_gradient(double a, double b, double h) { return contact_secant(a, b) / (2 * h); }

double contact_energy_defect(double a, double b, double h, double theta) {
  const double g = (1 - theta) * contact_energy_derivative(a, h) + theta * contact_energy_derivative(b, h);
  return (b - a) * g - (contact_energy(b, h) - contact_energy(a, h));
}

double contact_energy_bound(double a, double b, double h, double theta) {
  const double excess = theta - 0.5;
  const bool active_a = contact_is_active(a), active_b = contact_is_active(b);
  if (active_a && active_b) return -excess * (b - a) * (b - a) / h;
  if (!active_a && !active_b) return 0.0;
  if (active_b) return (theta * a * b - excess * b * b) / h;    // impact
  return ((1 - theta) * std::abs(a * b) - excess * a * a) / h;  // release
}

namespace {

void check_root_arguments(double alpha, double c, double mu) {
  if (!(std::isfinite(alpha) && std::isfinite(c)))
    throw std::invalid_argument("contact root: alpha and c must be finite");
  if (!(mu >= 0 && mu < 1))
    throw std::invalid_argument("contact root: mu = " + std::to_string(mu) + " (allowed: 0 <= mu < 1)");
}

}  // namespace

double energy_conserving_contact_root(double alpha, double c, double mu) {
  check_root_arguments(alpha, c, mu);
  const double p = alpha + c;
  if (contact_is_active(alpha)) {
    if (c <= 0) return c;
    // Release: (1 − μ)s² − Ps + cα = 0, the non-negative root.
    const double d = std::sqrt(p * p - 4 * (1 - mu) * c * alpha);
    return p > 0 ? (p + d) / (2 * (1 - mu)) : 2 * c * alpha / (p - d);
  }
  if (c > -mu * alpha) return (c + mu * alpha) / (1 - mu);
  // Impact: s² − Ps + α(c + μα) = 0, the non-positive root.
  const double root_mu = std::sqrt(mu);
  const double gap = alpha - c;
  const double d = std::sqrt(std::max(0.0, (gap - 2 * root_mu * alpha) * (gap + 2 * root_mu * alpha)));
  return p > 0 ? 2 * alpha * (c + mu * alpha) / (p + d) : (p - d) / 2;
}

double crank_nicolson_contact_root(double alpha, double c, double mu) {
  check_root_arguments(alpha, c, mu);
  const double shifted = c + mu * std::max(0.0, alpha);
  return shifted > 0 ? shifted / (1 - mu) : shifted;
}

EnergyConservingContact energy_conserving_contact(double z1, double mu, double u0_now, double s_now, double h,
                                                  double load0_next, double gap) {
  // "With a gap" (file comment): a = sⁿ + g₀, c = z₁ − μu₀ⁿ + hF₀ⁿ⁺¹ + (1 − 2μ)g₀, the sweep up from χ − 2g₀ − u₀ⁿ.
  // (Without a gap every term below is the gap-free one bit for bit: + 0.0 changes no value.)
  const double a = s_now + gap;
  const double c = z1 - mu * u0_now + h * load0_next + (1 - 2 * mu) * gap;
  const double s = energy_conserving_contact_root(a, c, mu);
  return {s, std::max(0.0, s) - gap, contact_secant(a, s) - 2 * gap - u0_now, std::min(0.0, s) / h,
          contact_is_active(s)};
}

// ---------------------------------------------------------------------------------------------------
// Checks of the scalar pieces: the cases of χ and κ, and the root against a bracketing solver.

namespace {

// G(s) = s − μχ(α, s) − c, the function whose root the EC step needs.
[[maybe_unused]] double ec_residual(double s, double alpha, double c, double mu) {
  return s - mu * contact_secant(alpha, s) - c;
}

struct RootProblem {
  double alpha, c, mu;
};

// GSL's Brent solver on a bracket [c − 1 − |c|, hi]: G(c − 1 − |c|) ≤ −1 − |c| < 0 since χ ≥ 0, and
// χ(α, s) ≤ max(0, α) + s for s > max(0, α), so G(s) ≥ (1 − μ)s − c − μ max(0, α) > 0 beyond hi.
[[maybe_unused]] double brent_root(const RootProblem& problem) {
  gsl_set_error_handler_off();
  gsl_function g;
  g.function = [](double s, void* p) {
    const RootProblem& q = *static_cast<const RootProblem*>(p);
    return ec_residual(s, q.alpha, q.c, q.mu);
  };
  g.params = const_cast<RootProblem*>(&problem);
  const double lo = problem.c - 1 - std::abs(problem.c);
  const double hi = std::max(std::abs(problem.alpha),
                             (std::abs(problem.c) + problem.mu * std::max(0.0, problem.alpha)) / (1 - problem.mu)) *
                        2 +
                    1;
  // Every GSL failure is an error of the check (thrown: the test case fails with its message).
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver == nullptr) throw std::runtime_error("brent_root: gsl_root_fsolver_alloc failed");
  int status = gsl_root_fsolver_set(solver, &g, lo, hi);
  double root = 0;
  if (status == GSL_SUCCESS) status = GSL_CONTINUE;
  for (int iteration = 0; iteration < 500 && status == GSL_CONTINUE; ++iteration) {
    status = gsl_root_fsolver_iterate(solver);
    if (status != GSL_SUCCESS) break;
    root = gsl_root_fsolver_root(solver);
    status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 1e-300, 1e-15);
  }
  gsl_root_fsolver_free(solver);
  if (status != GSL_SUCCESS) throw std::runtime_error(std::string("brent_root: ") + gsl_strerror(status));
  return root;
}

// A signed magnitude spread over many decades, and exact zeros now and then.
[[maybe_unused]] double random_value(std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double u = unit(random);
  if (u < 0.04) return 0.0;
  const double magnitude = std::pow(10.0, -6.0 + 8.0 * unit(random));
  return unit(random) < 0.5 ? -magnitude : magnitude;
}

[[maybe_unused]] double random_mu(std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double u = unit(random);
  if (u < 0.2) return std::pow(10.0, -8.0 + 7.0 * unit(random));        // μ → 0 (Δt ≪ h)
  if (u < 0.4) return 1.0 - std::pow(10.0, -6.0 + 5.0 * unit(random));  // μ → 1
  if (u < 0.45) return 0.0;
  return unit(random);
}

}  // namespace

TEST_CASE("the contact secant is the discrete gradient of psi, case by case, and CN's value on one side") {
  const double h = 0.03;
  std::mt19937 random(2024);
  for (int trial = 0; trial < 2000; ++trial) {
    const double a = random_value(random), b = random_value(random);
    CAPTURE(a);
    CAPTURE(b);
    const double chi = contact_secant(a, b);
    // The definition, where b − a is not tiny against a and b.
    if (std::abs(b - a) > 1e-3 * (std::abs(a) + std::abs(b))) {
      const double direct = 2 * h * (contact_energy(b, h) - contact_energy(a, h)) / (b - a);
      CHECK(std::abs(chi - direct) <= 1e-12 * (std::abs(a) + std::abs(b)));
    }
    CHECK(std::abs(contact_discrete_gradient(a, b, h) - chi / (2 * h)) <= 1e-15 * std::abs(chi) / h);
    // χ lies between 2ψ'-values times h: 2 max(0, min(a, b)) ≤ χ ≤ 2 max(0, max(a, b)).
    CHECK(chi >= 2 * std::max(0.0, std::min(a, b)) * (1 - 1e-15));
    CHECK(chi <= 2 * std::max(0.0, std::max(a, b)) * (1 + 1e-15));
    if (contact_is_active(a) == contact_is_active(b))
      CHECK(chi == std::max(0.0, a) + std::max(0.0, b));  // Crank–Nicolson's trapezoidal value, bitwise
  }
  CHECK(contact_secant(0.4, 0.4) == 0.8);  // 2ψ'(a)h at b = a
  CHECK(contact_secant(-0.4, -0.4) == 0.0);
  CHECK(contact_secant(0.0, 0.0) == 0.0);
}

TEST_CASE("Crank–Nicolson's contact energy defect is 0 on one side, ab/2h at an impact, -ab/2h at a release") {
  const double h = 0.05;
  std::mt19937 random(11);
  int impacts = 0, releases = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double a = random_value(random), b = random_value(random);
    const double kappa = contact_energy_defect(a, b, h, 0.5);
    const double scale = (a * a + b * b) / h;
    CAPTURE(a);
    CAPTURE(b);
    if (contact_is_active(a) == contact_is_active(b)) {
      CHECK(std::abs(kappa) <= 1e-15 * scale);
    } else if (!contact_is_active(a)) {
      CHECK(std::abs(kappa - a * b / (2 * h)) <= 1e-15 * scale);
      ++impacts;
    } else {
      CHECK(std::abs(kappa + a * b / (2 * h)) <= 1e-15 * scale);
      ++releases;
    }
    CHECK(std::abs(kappa) <= (b - a) * (b - a) / (8 * h) + 1e-15 * scale);  // |κ| ≤ (b − a)²/(8h)
  }
  CHECK(impacts > 200);
  CHECK(releases > 200);
}

TEST_CASE("the theta-step's contact bound rho is its closed form, and never positive for theta = 1") {
  const double h = 0.02;
  std::mt19937 random(5);
  int positive_releases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double a = random_value(random), b = random_value(random);
    for (double theta : {0.5, 0.6, 0.75, 0.9, 1.0}) {
      const double rho = contact_energy_bound(a, b, h, theta);
      const double definition = contact_energy_defect(a, b, h, theta) - (theta - 0.5) * (b - a) * (b - a) / h;
      CAPTURE(a);
      CAPTURE(b);
      CAPTURE(theta);
      CHECK(std::abs(rho - definition) <= 1e-14 * (a * a + b * b) / h);
      if (theta == 1.0) CHECK(rho <= 0.0);
      if (theta == 0.5) CHECK(std::abs(rho - contact_energy_defect(a, b, h, 0.5)) <= 1e-14 * (a * a + b * b) / h);
      positive_releases += rho > 0;
    }
  }
  CHECK(positive_releases > 0);  // below θ = 1 a release may gain energy: the guarantee is θ = 1's
}

TEST_CASE("the EC scalar equation has a unique root, found in closed form and by GSL's Brent solver") {
  std::mt19937 random(31415);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int cases[4] = {0, 0, 0, 0};  // no force, same side (free), release, impact
  for (int trial = 0; trial < 5000; ++trial) {
    const RootProblem problem{random_value(random), random_value(random), random_mu(random)};
    const double s = energy_conserving_contact_root(problem.alpha, problem.c, problem.mu);
    const double brent = brent_root(problem);
    const double scale = std::abs(problem.alpha) + std::abs(problem.c) + std::abs(s);
    CAPTURE(problem.alpha);
    CAPTURE(problem.c);
    CAPTURE(problem.mu);
    CAPTURE(s);
    CAPTURE(brent);
    // G is evaluated with an error of a few ulps of the size of its terms (|s|, |c|, μχ ≤ |s| + |α|),
    // and the root moves by at most |δG|/(1 − μ) when G moves by δG: the two solvers agree within
    // 20 ulps of that scale divided by 1 − μ (μ → 1 is the ill-conditioned end, Δt ≫ h on a fine mesh).
    CHECK(std::abs(s - brent) <= 4e-15 * scale / (1 - problem.mu) + 1e-300);  // Brent stops near 0 at a denormal
    CHECK(std::abs(ec_residual(s, problem.alpha, problem.c, problem.mu)) <= 4e-15 * scale);
    // Uniqueness: G is increasing with slope ≥ 1 − μ (checked on random pairs around the root), so it
    // is negative below s and positive above.
    const double spread = scale > 0 ? scale : 1.0;  // α = c = 0: s = 0, and G(s) = (1 − μ) max(0, s) + min(0, s)
    for (int k = 0; k < 4; ++k) {
      const double s1 = s + (unit(random) - 0.5) * 4 * spread;
      const double s2 = s + (unit(random) - 0.5) * 4 * spread;
      if (std::abs(s2 - s1) < 1e-6 * spread) continue;
      const double slope = (ec_residual(s2, problem.alpha, problem.c, problem.mu) -
                            ec_residual(s1, problem.alpha, problem.c, problem.mu)) /
                           (s2 - s1);
      CHECK(slope >= (1 - problem.mu) - 1e-9 * spread / std::abs(s2 - s1));
    }
    const bool before = contact_is_active(problem.alpha), after = contact_is_active(s);
    if (problem.alpha <= 0 && problem.c <= 0)
      ++cases[0];
    else if (before == after)
      ++cases[1];
    else if (before)
      ++cases[2];
    else
      ++cases[3];
  }
  for (int k = 0; k < 4; ++k) {
    CAPTURE(k);
    CHECK(cases[k] > 300);
  }
}

TEST_CASE("the EC root is Crank–Nicolson's, bitwise, when the status does not change") {
  std::mt19937 random(99);
  int same = 0, changed = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const double alpha = random_value(random), c = random_value(random), mu = random_mu(random);
    const double ec = energy_conserving_contact_root(alpha, c, mu);
    const double cn = crank_nicolson_contact_root(alpha, c, mu);
    CAPTURE(alpha);
    CAPTURE(c);
    CAPTURE(mu);
    if (contact_is_active(alpha) == contact_is_active(cn) && contact_is_active(alpha) == contact_is_active(ec)) {
      CHECK(ec == cn);
      ++same;
    } else {
      // Across a status change the two roots lie on the same side of 0 as each other: sign(c + μα₊)
      // decides both (G(0) is −c − μα₊ for both equations).
      CHECK(contact_is_active(ec) == contact_is_active(cn));
      ++changed;
    }
  }
  CHECK(same > 1000);
  CHECK(changed > 1000);
}

TEST_CASE("the contact roots reject mu outside 0 <= mu < 1 and non-finite data") {
  for (double mu : {-0.1, 1.0, 1.5, std::nan("")}) {
    CAPTURE(mu);
    CHECK_THROWS_WITH_AS(energy_conserving_contact_root(0.1, 0.2, mu), doctest::Contains("allowed: 0 <= mu < 1"),
                         std::invalid_argument);
    CHECK_THROWS_AS(crank_nicolson_contact_root(0.1, 0.2, mu), std::invalid_argument);
  }
  CHECK_THROWS_AS(energy_conserving_contact_root(HUGE_VAL, 0.2, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(energy_conserving_contact_root(0.1, std::nan(""), 0.5), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Checks of the derivation on the reduced problem itself: a dense, textbook implementation of the
// three steps above on the free nodes 1..N−1 (f = 0), independent of the library's step but for its
// matrices (the one builder, theta_step_matrices), run on the
// benchmark of mathematics.md §2 (period 3): the energy identity (E) at every step, EC's exact
// conservation, EC = CN away from status changes, and CN-switch's monotone energy.

namespace {

struct ReducedBar {
  double h, dt;
  Tridiagonal full_mass, full_stiffness;  // M̄, S̄ on nodes 0..N−1 (row and column 0 of M̄ vanish)
  Eigen::MatrixXd mass, stiffness;        // M̄, S̄ on nodes 1..N−1

  ReducedBar(Index elements, const MassRedistribution& redistribution, double courant)
      : h(1.0 / static_cast<double>(elements)), dt(courant / static_cast<double>(elements)) {
    const UniformMesh mesh(1.0, elements);
    full_mass = modified_mass(mesh, redistribution);
    full_stiffness = p1_stiffness(mesh);
    mass = free_block(full_mass);
    stiffness = free_block(full_stiffness);
  }
  // The block of a matrix on nodes 1..N−1, dense.
  static Eigen::MatrixXd free_block(const Tridiagonal& a) {
    const Index m = a.size() - 1;
    return Eigen::MatrixXd(a.to_sparse()).bottomRightCorner(m, m);
  }

  // The benchmark's data u⁰ = ½(1 − x), v⁰ = 0 on the free nodes.
  void initial(Eigen::VectorXd& u, Eigen::VectorXd& v) const {
    const Index m = mass.rows();
    u.resize(m);
    for (Index i = 0; i < m; ++i) u[i] = 0.5 * (1 - static_cast<double>(i + 1) * h);
    v.setZero(m);
  }

  // E = ½VᵀM̄V + Φ(Ū), Φ as the sum over the elements of the squared differences of
  // (max(0, u₁), u₁, …, u_{N−1}, 0), divided by 2h: free of cancellation.
  double energy(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
    const Index m = u.size();
    const double first = u[0] - std::max(0.0, u[0]);
    double potential = first * first;
    for (Index i = 0; i < m; ++i) {
      const double d = (i + 1 < m ? u[i + 1] : 0.0) - u[i];
      potential += d * d;
    }
    return 0.5 * v.dot(mass * v) + potential / (2 * h);
  }

  // The θ-rule D = Δt((1 − θ)V + θV'), M̄ΔV = Δt[−S̄((1 − θ)Ū + θŪ') + g e₁] gives
  //     (M̄ + θ²Δt²S̄)Ū' = M̄(Ū + ΔtV) − θ(1 − θ)Δt²S̄Ū + θΔt² g e₁,
  // whose matrices on the free nodes are the library's θ-step's (theta_step_matrices, schemes.cpp):
  // A, B₁ and B₂ restricted to nodes 1..N−1, the weights θ(1 − θ)Δt² and θ²Δt² its load weights.
  // The matrix is factorised once per θ (here: inverted, the system is small).
  struct Factor {
    double theta, t1, t2;  // θ, θ(1 − θ)Δt², θ²Δt²
    Eigen::MatrixXd inverse, b1, b2;
    double mu;  // θ²Δt² (Ā⁻¹)₁₁ / h
  };
  Factor factor(double theta) const {
    const StepMatrices step = theta_step_matrices(full_mass, full_stiffness, theta, dt);
    Factor f{theta, step.load_now, step.load_next, {}, free_block(step.b1), free_block(step.b2), 0};
    f.inverse = free_block(step.a).inverse();
    f.mu = f.t2 * f.inverse(0, 0) / h;
    return f;
  }

  // One step with the force g = (1 − θ)ψ'(a) + θψ'(b) (θ-rule), ½(ψ'(a) + ψ'(b)) computed as CN's
  // trapezoidal χ/(2h) (trapezoidal, θ = ½), or φ(a, b) (discrete gradient, θ = ½).
  enum class Force { theta_rule, trapezoidal, discrete_gradient };
  void step(Eigen::VectorXd& u, Eigen::VectorXd& v, const Factor& f, Force force) const {
    const double a = u[0], theta = f.theta;
    Eigen::VectorXd rhs = f.b1 * u + f.b2 * v;
    if (force == Force::theta_rule) rhs[0] += f.t1 * contact_energy_derivative(a, h);
    const Eigen::VectorXd z = f.inverse * rhs;
    const auto r = f.inverse.col(0);
    Eigen::VectorXd u_new;
    if (force == Force::theta_rule) {
      // b = z₁ + μ max(0, b): the closed-form contact step.
      const double b = z[0] > 0 ? z[0] / (1 - f.mu) : z[0];
      u_new = z + f.t2 * contact_energy_derivative(b, h) * r;
    } else {
      // θ = ½: θΔt² g = (Δt²/2) g = 2t₂ g, and b = z₁ + μ χ(a, b).
      const bool ec = force == Force::discrete_gradient;
      const double b = ec ? energy_conserving_contact_root(a, z[0], f.mu) : crank_nicolson_contact_root(a, z[0], f.mu);
      const double chi = ec ? contact_secant(a, b) : std::max(0.0, a) + std::max(0.0, b);
      u_new = z + (f.t2 / h) * chi * r;  // 2t₂ · χ/(2h)
    }
    v = Eigen::VectorXd(((u_new - u) / dt - (1 - theta) * v) / theta);
    u = u_new;
  }
};

}  // namespace

TEST_CASE("theta-steps obey the energy identity (E) and the bound of the derivation at every step") {
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    for (double courant : {0.5, 3.0}) {
      for (double theta : {0.5, 0.75, 1.0}) {
        const ReducedBar bar(16, mass, courant);
        const ReducedBar::Factor factor = bar.factor(theta);
        Eigen::VectorXd u, v;
        bar.initial(u, v);
        CAPTURE(mass.name);
        CAPTURE(courant);
        CAPTURE(theta);
        int changes = 0;
        const double e0 = bar.energy(u, v);
        for (int k = 0; k < static_cast<int>(12.0 / bar.dt); ++k) {
          const Eigen::VectorXd u_old = u, v_old = v;
          const double e_old = bar.energy(u, v);
          bar.step(u, v, factor, ReducedBar::Force::theta_rule);
          const Eigen::VectorXd d = u - u_old, dv = v - v_old;
          const double kinetic = dv.dot(bar.mass * dv);
          const double predicted = -(theta - 0.5) * (kinetic + d.dot(bar.stiffness * d)) +
                                   contact_energy_defect(u_old[0], u[0], bar.h, theta);
          const double change = bar.energy(u, v) - e_old;
          CAPTURE(k);
          CHECK(std::abs(change - predicted) <= 1e-14 * e0 * (1 + 1 / (courant * courant)));
          CHECK(change <= -(theta - 0.5) * kinetic + contact_energy_bound(u_old[0], u[0], bar.h, theta) + 1e-14 * e0);
          changes += contact_is_active(u_old[0]) != contact_is_active(u[0]);
        }
        CHECK(changes >= 6);  // impacts and releases were crossed (one of each per period)
      }
    }
  }
}

namespace {

// The largest |E_k − E₀|/E₀ of EC over a run, and the number of status changes crossed.
struct EcRun {
  double largest_drift = 0;
  int changes = 0;
  Index steps = 0;
};
[[maybe_unused]] EcRun run_ec(Index elements, const MassRedistribution& mass, double courant, double final_time) {
  const ReducedBar bar(elements, mass, courant);
  const ReducedBar::Factor factor = bar.factor(0.5);
  Eigen::VectorXd u, v;
  bar.initial(u, v);
  const double e0 = bar.energy(u, v);
  EcRun run;
  run.steps = static_cast<Index>(std::ceil(final_time / bar.dt - 1e-9));
  for (Index k = 0; k < run.steps; ++k) {
    const double a = u[0];
    bar.step(u, v, factor, ReducedBar::Force::discrete_gradient);
    run.changes += contact_is_active(a) != contact_is_active(u[0]);
    run.largest_drift = std::max(run.largest_drift, std::abs(bar.energy(u, v) - e0) / e0);
  }
  return run;
}

}  // namespace

TEST_CASE("EC conserves the energy to round-off at every step, status changes included") {
  // Round-off in E accumulates at most linearly with the number of steps k: |E_k − E₀| ≤ (1e-14 + k·1e-15)E₀
  // (the measured drift stays far below; Crank–Nicolson gains 10⁷ E₀ on the first run, 3× on the second).
  struct Case {
    Index elements;
    double courant, final_time;
    MassRedistribution mass;
  };
  for (const Case& c : {Case{16, 10.0, 300.0, mod1()}, Case{16, 10.0, 300.0, mod3()}, Case{20, 1.0, 3000.0, mod2()},
                        Case{20, 1.0, 3000.0, mod1()}}) {
    const EcRun run = run_ec(c.elements, c.mass, c.courant, c.final_time);
    CAPTURE(c.elements);
    CAPTURE(c.courant);
    CAPTURE(c.mass.name);
    CAPTURE(run.largest_drift);
    CHECK(run.largest_drift <= 1e-14 + static_cast<double>(run.steps) * 1e-15);
    CHECK(run.changes >= static_cast<int>(c.final_time / 3));  // about two per period: many impacts
  }
}

TEST_CASE("EC is Crank–Nicolson on every step without a status change, and differs across one") {
  for (double courant : {0.5, 1.0, 5.0}) {
    const ReducedBar bar(24, mod3(), courant);
    const ReducedBar::Factor factor = bar.factor(0.5);
    Eigen::VectorXd u, v;
    bar.initial(u, v);
    int same = 0, changed = 0;
    CAPTURE(courant);
    for (int k = 0; k < static_cast<int>(30.0 / bar.dt); ++k) {
      Eigen::VectorXd u_cn = u, v_cn = v, u_rule = u, v_rule = v;
      const double a = u[0];
      bar.step(u, v, factor, ReducedBar::Force::discrete_gradient);
      bar.step(u_cn, v_cn, factor, ReducedBar::Force::trapezoidal);
      bar.step(u_rule, v_rule, factor, ReducedBar::Force::theta_rule);  // CN written as the θ-rule
      CAPTURE(k);
      CHECK((u_cn - u_rule).cwiseAbs().maxCoeff() <= 1e-14);
      if (contact_is_active(a) == contact_is_active(u[0])) {
        CHECK(u == u_cn);
        CHECK(v == v_cn);
        ++same;
      } else {
        CHECK(u != u_cn);
        ++changed;
      }
      u = u_cn, v = v_cn;  // both continue from Crank–Nicolson's state
    }
    CHECK(same > 2 * changed);
    CHECK(changed >= 18);
  }
}

TEST_CASE("the round-off bound of one step grows like N and like h/dt, and refuses bad arguments") {
  CHECK(energy_round_off_per_step(40, 1.0) == 2 * energy_round_off_per_step(20, 1.0));
  CHECK(energy_round_off_per_step(20, 0.5) == 1.5 * energy_round_off_per_step(20, 1.0));
  CHECK_THROWS_AS(energy_round_off_per_step(0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(energy_round_off_per_step(20, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(energy_round_off_per_step(20, std::nan("")), std::invalid_argument);
}

TEST_CASE("CN-switch (a backward-Euler step at each status change) never increases the energy") {
  struct Case {
    Index elements;
    double courant, final_time;
  };
  for (const Case& c : {Case{16, 10.0, 300.0}, Case{20, 1.0, 3000.0}, Case{40, 0.5, 30.0}}) {
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
      const ReducedBar bar(c.elements, mass, c.courant);
      const ReducedBar::Factor cn = bar.factor(0.5), redo = bar.factor(1.0);
      Eigen::VectorXd u, v;
      bar.initial(u, v);
      const double e0 = bar.energy(u, v);
      double e = e0, largest_increase = -1;
      int redone = 0;
      const Index steps = static_cast<Index>(std::ceil(c.final_time / bar.dt - 1e-9));
      for (Index k = 0; k < steps; ++k) {
        const Eigen::VectorXd u_old = u, v_old = v;
        bar.step(u, v, cn, ReducedBar::Force::trapezoidal);
        if (contact_is_active(u_old[0]) != contact_is_active(u[0])) {
          u = u_old, v = v_old;
          bar.step(u, v, redo, ReducedBar::Force::theta_rule);
          ++redone;
        }
        const double e_new = bar.energy(u, v);
        largest_increase = std::max(largest_increase, (e_new - e) / e0);
        e = e_new;
      }
      CAPTURE(c.elements);
      CAPTURE(c.courant);
      CAPTURE(mass.name);
      CAPTURE(largest_increase);
      CAPTURE(energy_round_off_per_step(c.elements, c.courant));
      CHECK(largest_increase <= energy_round_off_per_step(c.elements, c.courant));  // one step's round-off (§5)
      CHECK(redone >= static_cast<int>(c.final_time / 3));
      CHECK(e < e0);  // and it does dissipate at the status changes
    }
  }
}

}  // namespace mrm
