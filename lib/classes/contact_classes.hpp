/// @file contact_classes.hpp
/// @brief The field's contact treatments in time (Doyen–Ern–Piperno's classes, doc/contact_treatments.md) as schemes
/// of the registry: Newmark(β, γ) with exact enforcement (`newmark`), with a penalty (`penalty`), with
/// Nitsche's terms (`nitsche`), Moreau–Jean's velocity-level impact law (`moreau-jean`) and
/// Deuflhard–Krause–Ertel's contact-stabilised Newmark (`dke`). Derived in
/// contact_classes.cpp; BarSimulation (schemes.hpp) runs them through ContactClassStep.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "time/contact.hpp"
#include "time/schemes.hpp"

namespace mrm {

/// Whether `scheme` is one of the contact classes of this file (its registry entry's step family).
inline bool is_contact_class(Scheme scheme) { return scheme_info(scheme).family == StepFamily::contact_class; }

/// The checks of a contact class's parameters and mass, before any work; throws InvalidParameter naming
/// the parameter: β < 0 or not finite, γ < ½ (Newmark amplifies), γ₀ ≤ 0, θ_N ∉ [−1, 1], θ_N ≥ γ₀_N
/// (the first element's stiffness (1 − θ/γ₀)/h is not positive), Moreau–Jean's θ ∉ [½, 1]; exact
/// enforcement with β = 0 and a contact node with inertia (no explicit step exists: the constraint
/// has no force to act through in the step); Moreau–Jean with a massless contact node (a velocity law
/// needs the node's inertia). Every class takes a load f and a gap (contact_classes.cpp, "The load and
/// the gap").
void validate_contact_class(const SchemeParameters& parameters, bool massless_contact_node);

/// The largest stable step of a Newmark contact class (newmark, penalty, nitsche) with β < γ/2:
/// Ω_c/ω_max, Ω_c = 1/√(γ/2 − β), ω²_max over both sides of the contact law (the penalty stiffness γ₀/h,
/// Nitsche's terms; the contact node eliminated when massless); +∞ for β ≥ γ/2 or another scheme.
/// `contact_compliance` is h/E of the contact element.
double newmark_stability_limit(const Tridiagonal& mass, const Tridiagonal& stiffness,
                               const SchemeParameters& parameters, double contact_compliance);
/// Throws InvalidParameter("dt", "… (allowed: 0 < dt <= Δt_max, i.e. Courant number <= Δt_max/h; or beta >=
/// gamma/2)") when dt is above newmark_stability_limit; `mesh_size` is h for the Courant number (0: none).
void check_newmark_step(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& parameters,
                        double dt, double contact_compliance, double mesh_size);

/// Central differences (Newmark β = 0, γ = ½) with the penalty k min(0, q), q = u₀ + gap, contact node with
/// inertia (contact_classes.cpp, "Central differences with a penalty"): the modified energy (Eh) of the
/// half level n+½, ½vᵀMv + ½UⁿᵀSUⁿ⁺¹ + ½k q₋ⁿq₋ⁿ⁺¹, v = (Uⁿ⁺¹ − Uⁿ)/Δt; conserved by every step without a
/// change of the contact status.
double penalty_modified_energy(const Tridiagonal& mass, const Tridiagonal& stiffness, double k, double gap, double dt,
                               const Eigen::VectorXd& u_now, const Eigen::VectorXd& u_next);
/// The change (J) of that energy over step n, from the gap function q at the levels n−1, n, n+1:
/// −½k min(0, qⁿ)(max(0, qⁿ⁺¹) − max(0, qⁿ⁻¹)), nonzero only at a switch.
double penalty_switch_jump(double k, double q_previous, double q_now, double q_next);
/// The largest Δt/Δt_max at which explicit penalty runs kept E_max ≤ 2E₀ up to `periods` periods of the
/// paper's benchmark: a measured region (fig_classes, block 5, which checks it), not a derived bound;
/// 0 beyond the measured horizons. No step limit sufficient over all times is derived (the comment).
double penalty_measured_safe_fraction(double periods);
/// The same for explicit Nitsche (Newmark β = 0, γ = ½; fig_classes block 6: θ = 0, 1, γ₀ = 5, 50): a measured
/// region, not a derived bound (contact_classes.cpp, "Central differences with Nitsche's terms": for θ ≠ 1 no
/// modified energy is conserved even between switches); 0 beyond the measured horizons.
double nitsche_measured_safe_fraction(double periods);

/// One run's step of a contact class, on the unknowns 0..N−1 with mass M and stiffness S. It reads the
/// initial level from the StepState (U⁰ in u, V⁰ in w, the massless node's λ⁰ in lambda) and writes
/// every level there: u, w (the velocity), lambda (the contact stress λ ≤ 0 at the new level; Moreau–Jean:
/// the impulse per step −p/Δt), energy (the class's discrete energy), active. A run that loses
/// finiteness throws std::runtime_error naming the level.
class ContactClassStep {
 public:
  virtual ~ContactClassStep() = default;
  /// Advances `state` from level n to n+1 (n the argument, for the error message).
  virtual void step(StepState& state, Index level) = 0;
};

/// The step of the Newmark type (newmark, penalty, nitsche: contact_classes.cpp, (N)) as the batched step
/// (batched_step.cpp) takes it apart: its factors and rows, the contact decision between the two sweeps of
/// the step matrix A, and the end of a step. BatchedSimulation advances runs of this type in vector lanes
/// with the operations of the fused step, in its order, and calls decide() and finish() of each run, so that
/// the scalar pieces are this class's own.
class NewmarkTypeStep : public ContactClassStep {
 public:
  /// What the lanes copy of a run (pointers into the step, valid while it lives).
  struct Lanes {
    const Tridiagonal* mass;           ///< M
    const Tridiagonal* stiffness;      ///< S (for the energy)
    const Tridiagonal* linear;         ///< S_ℓ: S with Nitsche's linear part (the force)
    const ContactSolver* solver;       ///< A = M + βΔt²S_ℓ (row 0 S_ℓ's if massless)
    const ContactSolver* mass_solver;  ///< M̃: M with row 0 e₀ᵀ if massless
    const Eigen::VectorXd* z;          ///< A⁻¹ of the law's weights (empty for newmark)
    Eigen::VectorXd* force;            ///< Rⁿ: the step's own state beside the StepState
    double dt;                         ///< Δt
    double beta;                       ///< Newmark's β
    double gamma;                      ///< Newmark's γ
    bool massless;                     ///< whether the contact node is massless
    std::array<double, 2> g;           ///< the law's force −λg on rows 0 and 1
  };
  /// The contact decision on the sweep down's y₀ and y₁.
  struct Decision {
    double lambda = 0;   ///< λⁿ⁺¹
    double u0 = 0;       ///< u₀ of U_f (penalty, Nitsche) or of Uⁿ⁺¹ (newmark)
    bool shift = false;  ///< whether U = U_f − λz
  };
  /// Whether the step is the fused one without a load (the batched step's only form).
  virtual bool batchable() const = 0;
  /// The run's rows, factors and Rⁿ, for the lanes.
  virtual Lanes lanes() = 0;
  /// The contact decision of the fused step on y₀ and y₁ of the sweep down of A.
  virtual Decision decide(double y0, double y1) const = 0;
  /// The end of step `level` → level + 1, with Uⁿ⁺¹ (its entries 0 and 1 at least) and Vⁿ⁺¹ in `state`:
  /// λ, the status, the energy from ½VᵀMV + ½UᵀSU (`kinetic_and_strain`); throws if it is not finite.
  virtual void finish(StepState& state, double lambda, double kinetic_and_strain, Index level) = 0;
};

/// The steps of Moreau–Jean and DKE (contact_classes.cpp) as the batched step (batched_step.cpp) takes them
/// apart. Each is one solve with A whose right-hand side b_i = (P x)_i − c(SUⁿ)_i is formed inside the sweep
/// down (Moreau–Jean: P = M − θ(1 − θ)Δt²S, x = Vⁿ, c = Δt; DKE: P = M, x the projected predictor, c = Δt²/4),
/// the contact step on row 0 between the sweeps, and a sweep up that updates the other vector node by node
/// (Moreau–Jean: Uⁿ⁺¹ from Vⁿ⁺¹; DKE: Vⁿ⁺¹ from Uⁿ⁺¹). BatchedSimulation advances runs of one of the two in
/// vector lanes with the operations of the fused step, in its order, and calls predict(), decide() and
/// finish() of each run, so that the scalar pieces are this class's own.
class OneSolveStep : public ContactClassStep {
 public:
  /// What the lanes copy of a run (pointers into the step, valid while it lives).
  struct Lanes {
    const Tridiagonal* mass;        ///< M (the energy; DKE's P)
    const Tridiagonal* stiffness;   ///< S
    const Tridiagonal* right;       ///< P, the matrix of the right-hand side's first term
    const ContactSolver* solver;    ///< A
    const Eigen::VectorXd* column;  ///< DKE: M⁻¹e₀, the projection's direction (empty for Moreau–Jean)
    double dt;                      ///< Δt
    double weight;                  ///< c: Δt (Moreau–Jean) or Δt²/4 (DKE)
    double theta;                   ///< Moreau–Jean's θ (1 for DKE, unused)
    double gap;                     ///< the initial gap g₀
    bool row0_zero;                 ///< b₀ = 0: DKE's algebraic contact row of a massless node
  };
  /// What the step decides on row 0: the sweep up's first unknown and what finish() needs.
  struct Decision {
    double x0 = 0;     ///< v₀ⁿ⁺¹ (Moreau–Jean) or u₀ⁿ⁺¹ (DKE)
    double value = 0;  ///< Moreau–Jean's impulse p, DKE's multiplier μ
  };
  /// Whether the step is the fused one without a load (the batched step's only form).
  virtual bool batchable() const = 0;
  /// The run's rows and factors, for the lanes.
  virtual Lanes lanes() const = 0;
  /// DKE's projection α of the predictor from u₀ⁿ and v₀ⁿ, if it projects; Moreau–Jean never does.
  virtual std::optional<double> projection(double u0, double v0) const = 0;
  /// The contact step on the sweep down's y₀, with u₀ⁿ and v₀ⁿ of the level before.
  virtual Decision decide(double y0, double u0, double v0) const = 0;
  /// The end of step `level` → level + 1, with Uⁿ⁺¹ and Vⁿ⁺¹ in `state` (their entries 0 and 1 at least): λ,
  /// the status, the energy from ½VᵀMV + ½UᵀSU (`kinetic_and_strain`); throws if it is not finite.
  virtual void finish(StepState& state, const Decision& decision, double alpha, double kinetic_and_strain,
                      Index level) = 0;
};

/// The step of `parameters.scheme` (a contact class), set up on `state`'s initial level (which it
/// completes: λ⁰, the energy E⁰). `contact_compliance` is h/E of the contact element (h on the paper's mesh);
/// with `has_load` the step reads Fⁿ from state.f_now and Fⁿ⁺¹ from state.f_next (which the caller fills
/// before each step) and swaps them; `gap` is the initial gap g₀ ≥ 0 (the constraint u₀ + g₀ ≥ 0).
std::unique_ptr<ContactClassStep> make_contact_class_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                          const SchemeParameters& parameters, double dt,
                                                          double contact_compliance, bool has_load, double gap,
                                                          StepState& state);

}  // namespace mrm
