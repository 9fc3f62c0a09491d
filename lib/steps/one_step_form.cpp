/// @file one_step_form.cpp
/// @brief The step (★) of the paper's schemes and of EC and CN-switch (mathematics.md §4, the paper's §3):
/// the schemes, their contact rows, the reference step written as its derivation, CN-switch's θ-step,
/// and their registry entries.
///
/// The semi-discrete problem is M U'' + S U = −λ e₀ + F, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (5)), with M the
/// consistent mass or a redistributed mass M^mod whose row and column 0 vanish (paper eq. (6)).
///
/// One step of every scheme, written on all unknowns 0..N−1, is
///
///     A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀,     0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0,                         (★)
///
/// that is, \f$ A U^{n+1} = B_1 U^n + B_2 W + G - \kappa \lambda e_0 \f$ with \f$ 0 \le u_0^{n+1} - g \perp \lambda \le 0 \f$,
/// with constant tridiagonal A, B₁, B₂, a scalar κ > 0, W = Vⁿ for the two-level schemes and
/// W = Uⁿ⁻¹ for the three-level one, and g the obstacle (0, or −e u₀ⁿ⁻¹). (★) is solved by the
/// closed-form contact step of contact.cpp: one sweep down, the contact decision at the contact
/// node's pivot, one sweep up. The schemes differ only in their coefficients (step_matrices.cpp). The
/// runs that check these steps are the doctests of time/schemes.cpp and time/one_step_form_runs.cpp.
#include "steps/one_step_form.hpp"

#include <cmath>
#include <memory>

#include "steps/energy_step.hpp"

namespace mrm {

/// @file one_step_form.cpp
/// ## The schemes (mathematics.md §4, the paper's §3)
///
/// Crank–Nicolson (trapezoidal rule for U' = V, M V' = −SU − λe₀ + F). Eliminating
/// Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ from M(Vⁿ⁺¹ − Vⁿ) = Δt/2 (−S(Uⁿ⁺¹ + Uⁿ) − (λⁿ⁺¹ + λⁿ)e₀ + Fⁿ⁺¹ + Fⁿ):
///
///     (M + θS) Uⁿ⁺¹ = (M − θS) Uⁿ + Δt M Vⁿ + θ(Fⁿ + Fⁿ⁺¹) − θλⁿe₀ − θλⁿ⁺¹e₀,    θ = Δt²/4.
///
/// Backward Euler: Uⁿ⁺¹ = Uⁿ + Δt Vⁿ⁺¹, M(Vⁿ⁺¹ − Vⁿ) = Δt(−SUⁿ⁺¹ − λⁿ⁺¹e₀ + Fⁿ⁺¹):
///
///     (M + Δt²S) Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt² Fⁿ⁺¹ − Δt² λⁿ⁺¹ e₀,   Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt.
///
/// Paoli–Schatzman (three levels, β ≥ 0, restitution e ∈ [0, 1]):
///
///     M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹)/Δt² + S(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Fⁿ − λⁿe₀,
///     0 ≤ (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ⊥ λⁿ ≤ 0,
///
/// that is (M + βΔt²S) Uⁿ⁺¹ = (2M − (1−2β)Δt²S) Uⁿ − (M + βΔt²S) Uⁿ⁻¹ + Δt²Fⁿ − Δt²λⁿe₀ with the
/// obstacle g = −e u₀ⁿ⁻¹.
///
/// Energy-conserving Crank–Nicolson (EC) and CN-switch (mathematics.md §12, derived in energy_step.cpp).
/// Crank–Nicolson creates energy at every release of a massless contact node. EC keeps Crank–Nicolson's
/// (★) and replaces the contact force of the step, the trapezoidal average of ψ'(sⁿ) and ψ'(sⁿ⁺¹)
/// (s = u₁ + hF₀, ψ(s) = max(0, s)²/2h), by the discrete gradient (ψ(sⁿ⁺¹) − ψ(sⁿ))/(sⁿ⁺¹ − sⁿ): the
/// contact is then decided on row 1 after the sweep down, by the closed-form root of a monotone scalar
/// equation, and the sweep up starts from the value of u₀ that carries that force
/// (energy_conserving_contact). It needs the condensed contact row (a massless contact node). CN-switch
/// takes Crank–Nicolson's step unless the contact status changes across it (decided after the sweep
/// down, before anything is written), and then takes a θ-step of the θ-rule instead,
///
///     Uⁿ⁺¹ − Uⁿ = Δt((1 − θ)Vⁿ + θVⁿ⁺¹),   M(Vⁿ⁺¹ − Vⁿ) = Δt((1 − θ)Gⁿ + θGⁿ⁺¹),   G = −SU − λe₀ + F,
///
/// that is (M + θ²Δt²S) Uⁿ⁺¹ = (M − θ(1−θ)Δt²S) Uⁿ + Δt M Vⁿ + θ(1−θ)Δt²(Fⁿ − λⁿe₀) + θ²Δt²(Fⁿ⁺¹ − λⁿ⁺¹e₀),
/// Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/(θΔt) − ((1−θ)/θ)Vⁿ: θ = ½ is Crank–Nicolson, θ = 1 backward Euler (the default,
/// whose energy provably never increases), with the same contact rows as they.
///
/// The massless contact row. With a redistributed mass, row 0 of the system has no inertia: it is
/// the algebraic contact row S₀·U = F₀ − λ, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (6)), to hold at every time level.
/// Crank–Nicolson's row 0 is then (S₀·Uⁿ⁺¹ − F₀ⁿ⁺¹ + λⁿ⁺¹) + (S₀·Uⁿ − F₀ⁿ + λⁿ) = 0 and backward Euler's
/// is S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹: with the row holding at level n, both are the algebraic row at level n+1.
/// This implementation writes it as such for every scheme ("algebraic" form): row 0 of A is S₀·,
/// row 0 of B₁ and B₂ vanish, G₀ = F₀ⁿ⁺¹ and κ = 1 for that row, so the row holds at every level
/// whatever round-off or initial data did before. Paoli–Schatzman applied literally ("literal" form)
/// keeps its own row 0, Δt² S₀·(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Δt²(F₀ⁿ − λⁿ): the contact row then only
/// holds in the β-average of three levels, and its defect dⁿ = S₀·Uⁿ − F₀ⁿ + λ obeys
/// βdⁿ⁺¹ + (1−2β)dⁿ + βdⁿ⁻¹ = 0 while the contact is inactive: for β = ¼, dⁿ = (p + qn)(−1)ⁿ, a
/// sawtooth that may grow (mathematics.md §4). The experiments show whether it does.
///

// ---------------------------------------------------------------------------------------------------
// The reference step: (★) written as derived above (mathematics.md §4).
//
// With A, B₁, B₂, κ and the load weights assembled once by the constructor, one step is
//
//   1. the right-hand side  b = B₁ Uⁿ + B₂ W + g_now Fⁿ + g_next Fⁿ⁺¹, row 0 corrected: with the
//      algebraic contact row b₀ = F₀ⁿ⁺¹ (and κ = 1); Crank–Nicolson with inertia at node 0 carries
//      its −θλⁿ there;
//   2. one tridiagonal solve of A Uⁿ⁺¹ = b − κ λ e₀ with 0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0, by the closed-form
//      contact step ContactSolver::solve (contact.cpp), g = 0 or, for Paoli–Schatzman, −e u₀ⁿ⁻¹;
//   3. the velocity from its definition: Crank–Nicolson Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ, backward Euler
//      Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt, Paoli–Schatzman X = (Uⁿ⁺¹ − Uⁿ)/Δt (and W becomes Uⁿ);
//   4. the energy from its definition: Eⁿ⁺¹ = ½ Vⁿ⁺¹ᵀMVⁿ⁺¹ + ½ Uⁿ⁺¹ᵀSUⁿ⁺¹ (two levels),
//      Eⁿ⁺½ = ½ XᵀMX + ½ (β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ) (Paoli–Schatzman).
//
// The stiffness forms are summed element by element, UᵀSV = ∫ u_h' v_h' dx = Σ_e (u_{e+1} − u_e)
// (v_{e+1} − v_e)/h with the clamped value u_N = 0: the same number as S's bilinear form, without
// cancelling the terms 2u_i²/h against −2u_{i−1}u_i/h (whose sizes grow like N² times the energy).
// This step allocates its temporaries and walks the vectors several times; the fast path
// (fast_step.cpp) does the same arithmetic inside the two sweeps of the solve. The doctest of
// fast_step.cpp ("the fast step and the reference step agree to round-off") compares them.
void OneStepFormStep::reference_step(StepState& state, bool has_load) const {
  const double h = mesh_.contact_compliance();
  const Tridiagonal& M = mass_;
  const Eigen::VectorXd& u = state.u;  // Uⁿ
  const Eigen::VectorXd& w = state.w;  // W': Vⁿ (two levels) or Uⁿ − Uⁿ⁻¹ (Paoli–Schatzman)

  // 1. The right-hand side of the increment form.
  const Eigen::VectorXd rhs = increment_right_hand_side(step_, u, w, state.lambda, has_load ? &state.f_now : nullptr,
                                                        has_load ? &state.f_next : nullptr);

  // 2. One solve for ΔU with the closed-form contact step, the obstacle of the increment g − u₀ⁿ. EC
  // decides the contact on row 1 after the sweep down and starts the sweep up from the u₀ that carries
  // its discrete-gradient force (energy_step.cpp); its scalar problem is written for u, so row 1's
  // ΔU₁ = z + μΔU₀ is passed as u₁ⁿ⁺¹ = (u₁ⁿ + z − μu₀ⁿ) + μu₀ⁿ⁺¹. CN-switch decides it as Crank–Nicolson
  // does, and if the status changes, takes its θ-step instead (nothing has been written yet). The gap
  // moves the obstacle by step_.obstacle_offset.
  double obstacle = three_level_ ? -restitution_ * (u[0] - w[0]) : 0.0;  // g
  if (step_.obstacle_offset != 0.0) obstacle += step_.obstacle_offset;   // (keeps a −0)
  Eigen::VectorXd& du = state.u_new;                                     // ΔU, then Uⁿ⁺¹
  double contact_multiplier, u0_next;
  if (energy_conserving_) {
    solver_.sweep_down(rhs.data(), du.data());
    const double load0_now = has_load ? state.f_now[0] : 0.0, load0_next = has_load ? state.f_next[0] : 0.0;
    const double mu = -solver_.upward()[1];
    const EnergyConservingContact contact = energy_conserving_contact(
        u[1] + solver_.inverse_pivot()[1] * du[1] - mu * u[0], mu, u[0], u[1] + h * load0_now, h, load0_next, gap_);
    solver_.sweep_up(contact.recurrence_u0 - u[0], du.data());
    u0_next = contact.u0;
    contact_multiplier = contact.multiplier;
    state.active = contact.active;
  } else if (switch_) {
    solver_.sweep_down(rhs.data(), du.data());
    const ContactStep contact = solver_.resolve_contact(du[0], step_.kappa, obstacle - u[0]);
    if (contact.active != state.active) return switch_step(state, has_load);
    solver_.sweep_up(contact.u0, du.data());
    u0_next = contact.active ? obstacle : u[0] + contact.u0;
    contact_multiplier = contact.multiplier;
    state.active = contact.active;
  } else {
    const ContactStep contact = solver_.solve(rhs.data(), du.data(), step_.kappa, obstacle - u[0]);
    u0_next = contact.active ? obstacle : u[0] + contact.u0;
    contact_multiplier = contact.multiplier;
    state.active = contact.active;
  }
  du[0] = u0_next - u[0];  // EC's recurrence value is not the contact node's new value

  // 3 and 4. The velocity and the energy from their definitions, the velocity from ΔU.
  const auto kinetic = [&](const Eigen::VectorXd& v) { return 0.5 * M.bilinear(v, v); };
  Eigen::VectorXd u_next = u + du;
  u_next[0] = u0_next;
  if (three_level_) {
    const double beta = beta_;
    state.x = step_.velocity_rate * du;  // X = ΔU/Δt
    const auto potential = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return 0.5 * (beta * stiffness_form(a, a, mesh_) + (1 - 2 * beta) * stiffness_form(a, b, mesh_) +
                    beta * stiffness_form(b, b, mesh_));
    };
    state.energy = kinetic(state.x) + potential(u_next, u);
    state.w = du;  // W' = Uⁿ⁺¹ − Uⁿ
  } else {
    Eigen::VectorXd& v_next = state.w;  // Vⁿ⁺¹ overwrites Vⁿ, entry by entry
    v_next = step_.velocity_rate * du - step_.velocity_memory * w;
    state.energy = kinetic(v_next) + 0.5 * stiffness_form(u_next, u_next, mesh_);
  }
  state.u = u_next;  // U = Uⁿ⁺¹
  state.lambda = contact_multiplier;
  if (has_load) state.f_now.swap(state.f_next);
}

// CN-switch's θ-step, steps 1–4 of the reference step with the θ-step's matrices (both kernels call it:
// it replaces a Crank–Nicolson step at a change of the contact status only, a few steps per period).
void OneStepFormStep::switch_step(StepState& state, bool has_load) const {
  const StepMatrices& theta_step = switch_->matrices;
  const Eigen::VectorXd rhs =
      increment_right_hand_side(theta_step, state.u, state.w, state.lambda, has_load ? &state.f_now : nullptr,
                                has_load ? &state.f_next : nullptr);
  Eigen::VectorXd& du = state.u_new;                   // ΔU (the increment form), then Uⁿ⁺¹
  const double obstacle = theta_step.obstacle_offset;  // g: the gap, 0 without one
  const ContactStep contact = switch_->solver.solve(rhs.data(), du.data(), theta_step.kappa, obstacle - state.u[0]);
  const double u0_next = contact.active ? obstacle : state.u[0] + contact.u0;
  du[0] = u0_next - state.u[0];
  state.w = theta_step.velocity_rate * du - theta_step.velocity_memory * state.w;
  du += state.u;
  du[0] = u0_next;
  state.energy = 0.5 * mass_.bilinear(state.w, state.w) + 0.5 * stiffness_form(du, du, mesh_);
  state.u.swap(state.u_new);
  state.lambda = contact.multiplier;
  state.active = contact.active;
  if (has_load) state.f_now.swap(state.f_next);
}

// ---------------------------------------------------------------------------------------------------
// The checks of a run of these schemes (the run's own, of Δt and of the ranges, come first: time/schemes.cpp).
namespace {

void validate_one_step_form(const StepContext& context) {
  const SchemeParameters& parameters = context.parameters;
  const bool massless = context.massless, three_level = parameters.scheme == Scheme::paoli_schatzman;
  if (three_level && parameters.contact_row == ContactRow::algebraic && !massless)
    throw InvalidParameter("contact_row",
                           "the algebraic contact row needs a massless contact node (allowed: any mass but "
                           "consistent, or the literal Paoli–Schatzman row with the consistent mass)");
  const bool literal_massless_row = massless && three_level && parameters.contact_row == ContactRow::literal;
  if (parameters.scheme == Scheme::energy_conserving && !massless)
    throw InvalidParameter("mass",
                           "the energy-conserving scheme (ec) needs a massless contact node (allowed: any mass but "
                           "consistent): with inertia at the contact node the contact energy is not a function of u1");
  // The literal Paoli–Schatzman row with a massless contact node: row 0 of A is βΔt²S₀·, singular for
  // β = 0. Off contact, row 0 reads β dⁿ⁺¹ + (1 − 2β) dⁿ + β dⁿ⁻¹ = 0 for d = u₀ − u₁ (S's row 0 is
  // (1, −1)/h): the roots of β r² + (1 − 2β) r + β have product 1 and are real and distinct when
  // β < ¼, so one exceeds 1 in modulus and d grows geometrically at every step of free flight (by 1.5
  // per step at β = 0.24, overflowing within a few thousand steps): no finite or meaningful value can
  // come out. β ≥ ¼ puts both roots on the unit circle.
  if (literal_massless_row && parameters.beta == 0.0)
    throw InvalidParameter("beta",
                           "0 with the literal Paoli–Schatzman row and a massless contact node is singular (row 0 "
                           "of the step matrix vanishes) (allowed: beta >= 1/4, or the algebraic row)");
  if (literal_massless_row && parameters.beta < 0.25)
    throw InvalidParameter("beta",
                           "below 1/4 with the literal Paoli–Schatzman row and a massless contact node, u0 - u1 "
                           "grows at every step of free flight (allowed: beta >= 1/4, the algebraic row, or the "
                           "consistent mass)");
  // The literal row with a massless contact node and a restitution e > 0. The restitution
  // law is a law on the velocity of a node with inertia; on the massless node the obstacle −e u₀ⁿ⁻¹
  // follows the literal row's undamped sawtooth of u₀ − u₁ (above: β dⁿ⁺¹ + (1 − 2β) dⁿ + β dⁿ⁻¹ = 0 off
  // contact, roots on the unit circle) and, as measured, feeds it: E(T) = 7e9 at e = ½ (N = 100, c = ½,
  // T = 30, Mod 3), a non-finite energy at e = 1 on N = 20 and 100, c = ¼ and 1, Mod 1 and Mod 3 (bounded at
  // e = 0 and e = 0.1 on those runs; the ratchet is our reading of the measurements, not a proof). The
  // algebraic row with e ∈ [0, 1] stays bounded on the same runs (E(T)/E(0) ≤ 1.01): it is the sound
  // form, and the literal one is refused with e > 0.
  if (literal_massless_row && parameters.restitution > 0)
    throw InvalidParameter("restitution",
                           "above 0 with the literal Paoli–Schatzman row and a massless contact node: the restitution "
                           "acts on a node without inertia and the run grows without bound (measured: E = 7e9 at "
                           "e = 0.5, N = 100) (allowed: e = 0, the algebraic row, or the consistent mass)");
  if (three_level && parameters.ps_explicit_start && massless)
    throw InvalidParameter("ps_start",
                           "the explicit first step solves with M, singular with a massless contact node "
                           "(allowed: the Crank-Nicolson start, or the consistent mass)");
}

}  // namespace

// The matrices and scalars of (★) (step_matrices.cpp), A factorised once per run.
OneStepFormStep::OneStepFormStep(const StepContext& context)
    : mesh_(context.mesh),
      restitution_(context.parameters.restitution),
      beta_(context.parameters.beta),
      gap_(context.gap),
      three_level_(context.parameters.scheme == Scheme::paoli_schatzman),
      energy_conserving_(context.parameters.scheme == Scheme::energy_conserving) {
  const Tridiagonal& M = context.mass;
  const Tridiagonal& S = context.stiffness;
  const SchemeParameters& parameters = context.parameters;
  const double dt = context.dt;
  step_ = step_matrices(M, S, parameters, dt);
  // The gap moves the obstacle: u₀ⁿ⁺¹ ≥ −gap (Paoli–Schatzman: the averaged constraint, see StepMatrices).
  // (+0.0 without a gap: a −0.0 would print as "-0" where the contact node sits on the obstacle.)
  if (context.gap != 0.0) step_.obstacle_offset = -(three_level_ ? 1 + parameters.restitution : 1.0) * context.gap;
  solver_ = ContactSolver(step_.a);
  // CN-switch's θ-step, with its own factorisation (once per run, like A's).
  if (parameters.scheme == Scheme::switching) {
    SwitchStep theta_step;
    theta_step.matrices = theta_step_matrices(M, S, parameters.switch_theta, dt);
    theta_step.matrices.obstacle_offset = step_.obstacle_offset;
    theta_step.solver = ContactSolver(theta_step.matrices.a);
    switch_ = std::make_unique<const SwitchStep>(std::move(theta_step));
  }
  // The fast path reads B₁, B₂, M and S from its own rows (fast_step.cpp): B₁, B₂ and M are kept only
  // for the reference step (and M for CN-switch's θ-step), so that the fast path's memory is that of the
  // state and the factors.
  if (parameters.kernel == StepKernel::fast) {
    fast_ = std::make_unique<const FastStep>(step_, M, S, parameters, context.mesh.contact_compliance());
    step_.b1 = Tridiagonal();
    step_.b2 = Tridiagonal();
  }
  if (!fast_ || switch_) mass_ = M;
  step_.a = Tridiagonal();
}

void OneStepFormStep::advance(StepState& state, Index, bool has_load) {
  if (!fast_)
    reference_step(state, has_load);
  else if (!fast_->step(state, solver_, has_load))
    switch_step(state, has_load);  // CN-switch at a change of status
}

// ---------------------------------------------------------------------------------------------------
// The registry entries of the schemes of this file (time/scheme_registry.hpp gathers them).

const std::vector<SchemeInfo>& one_step_form_schemes() {
  using P = SchemeParameter;
  const auto make = [](const StepContext& context) -> std::unique_ptr<Step> {
    return std::make_unique<OneStepFormStep>(context);
  };
  static const std::vector<SchemeInfo> entries = {
      {Scheme::crank_nicolson,
       "cn",
       "Crank–Nicolson (trapezoidal rule), two levels",
       {},
       validate_one_step_form,
       make,
       0,
       "Crank–Nicolson",
       "Crank--Nicolson",
       "CN"},
      {Scheme::backward_euler,
       "be",
       "backward Euler, two levels",
       {},
       validate_one_step_form,
       make,
       0,
       "backward Euler",
       "backward Euler",
       "BE"},
      {Scheme::paoli_schatzman,
       "ps",
       "Paoli–Schatzman (β, e), three levels, algebraic or literal contact row",
       {P::beta, P::restitution, P::contact_row, P::ps_start},
       validate_one_step_form,
       make,
       1,
       "Paoli–Schatzman (¼, 0)",
       "Paoli--Schatzman $(\\frac14, 0)$",
       "PS"},
      {Scheme::energy_conserving,
       "ec",
       "energy-conserving Crank–Nicolson: the discrete gradient of the contact energy (massless contact node)",
       {},
       validate_one_step_form,
       make,
       2,
       "EC",
       "energy-conserving Crank--Nicolson",
       "EC"},
      {Scheme::switching,
       "cn-switch",
       "Crank–Nicolson with a θ-step at each change of the contact status (θ = 1: backward Euler)",
       {P::switch_theta},
       validate_one_step_form,
       make,
       3,
       "CN-switch",
       "Crank--Nicolson with a $\\theta$-step at each status change",
       "CN-switch"},
  };
  return entries;
}
}  // namespace mrm
