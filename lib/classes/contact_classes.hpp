/// @file contact_classes.hpp
/// @brief The field's contact treatments in time (Doyen–Ern–Piperno's classes, doc/contact_treatments.md) as schemes
/// of the registry: Newmark(β, γ) with exact enforcement (`newmark`), with a penalty (`penalty`), with
/// Nitsche's terms (`nitsche`), Moreau–Jean's velocity-level impact law (`moreau-jean`) and
/// Deuflhard–Krause–Ertel's contact-stabilised Newmark (`dke`). Derived in
/// contact_classes.cpp; a run (time/schemes.hpp) holds one as its Step.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "classes/class_step.hpp"
#include "steps/contact.hpp"
#include "steps/step.hpp"

namespace mrm {

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

/// The step of `parameters.scheme` (a contact class), whose start() completes the run's initial level (λ⁰,
/// the energy E⁰). `contact_compliance` is h/E of the contact element (h on the paper's mesh);
/// with `has_load` the step reads Fⁿ from state.f_now and Fⁿ⁺¹ from state.f_next (which the caller fills
/// before each step) and swaps them; `gap` is the initial gap g₀ ≥ 0 (the constraint u₀ + g₀ ≥ 0).
std::unique_ptr<ContactClassStep> make_contact_class_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                          const SchemeParameters& parameters, double dt,
                                                          double contact_compliance, bool has_load, double gap);

/// The parameters of `scheme` with Newmark's (β, γ) where it takes them (a Newmark-type class), the defaults
/// otherwise: the runs of the doctests.
SchemeParameters class_parameters(Scheme scheme, double beta = 0.25, double gamma = 0.5);

/// The registry entries of the contact classes: newmark, penalty, nitsche, moreau-jean, dke
/// (time/scheme_registry.hpp gathers them). Their checks are validate_contact_class and check_newmark_step.
const std::vector<SchemeInfo>& contact_class_schemes();

}  // namespace mrm
