/// @file contact_classes.cpp
/// @brief The field's contact treatments in time (doc/contact_treatments.md, Doyen–Ern–Piperno's classes) as schemes of
/// the registry: `newmark`, `penalty`, `nitsche` (one Newmark(β, γ) step with three contact laws),
/// `moreau-jean` (the θ-method with a velocity-level impact law) and `dke` (Deuflhard–Krause–Ertel's
/// contact-stabilised Newmark, an energy-consistent treatment from the literature).
///
/// Notation of doc/mathematics.md and schemes.cpp: M the mass on the unknowns 0..N−1 (consistent, or
/// redistributed with a massless contact node), S the P1 stiffness, u₀ the contact node's value, λ ≤ 0
/// the contact stress, the semi-discrete problem M U'' + S U = F_c(U), F_c the contact force on the bar
/// (−λe₀ for exact enforcement and the penalty). h is the contact element's compliance h₀/E₀ (the mesh
/// size on the paper's mesh).
///
///
/// The steps: newmark_type.cpp (Newmark(β, γ) with a contact force, (N)), moreau_jean.cpp ((MJ)), dke.cpp
/// ((DKE)); their step limits: newmark_stability.cpp. This file: the checks of the classes' parameters,
/// the choice of the step, the load and the gap, and the doctests that run the classes.
///
/// ## The load and the gap
///
/// A load f enters every class as the consistent load vector F(t) = (∫fφ_i)_i of p1_load, the same
/// vector Crank–Nicolson's (★) takes (schemes.cpp), at the instants where each scheme evaluates its
/// forces; an initial gap g₀ ≥ 0 shifts the constraint to u₀ + g₀ ≥ 0 (doc/benchmarks.md: the obstacle at −g₀).
///
/// - Newmark (N): the load is part of the force, Rⁿ = −S_ℓUⁿ + F_c(Uⁿ) + Fⁿ. Its implicit part βΔt²Fⁿ⁺¹ is
///   known before the solve: b = MUⁿ + ΔtMVⁿ + Δt²(½ − β)Rⁿ + βΔt²Fⁿ⁺¹, and the velocity line takes
///   (1 − γ)Rⁿ + γRⁿ⁺¹ with both loads. A massless node's row R₀ = 0 becomes the algebraic contact row
///   with its load, S_ℓ₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λ g₀ (paper eq. (6)): right-hand side F₀ⁿ⁺¹ instead of 0.
/// - The gap: exact enforcement solves the same closed-form contact step with the obstacle −g₀
///   (0 ≤ u₀ⁿ⁺¹ + g₀ ⊥ λ ≤ 0); the penalty's law is λ = (γ₀/h) min(0, u₀ + g₀), Φ = λ²/(2γ₀/h) unchanged;
///   Nitsche's P(U) = γ(u₀ + g₀) + d·U (the gap function replaces u₀ in γg + σ, Chouly–Hild–Renard), whose
///   linear part is unchanged, and for θ = 1 still F_c = −∇Φ with Φ = (1/2γ)(λ² − (d·U)²). Both laws are
///   affine in U on each side of the kink, P = ℓ·U + o (o = g₀ or γg₀), so the superposition above holds
///   with P_f = ℓ·U_f + o.
/// - Energy with the load (β = ¼, γ = ½). MΔU = (Δt/2)M(Vⁿ + Vⁿ⁺¹) and MΔV = (Δt/2)(Rⁿ + Rⁿ⁺¹) give
///   ½(Vⁿ + Vⁿ⁺¹)ᵀMΔV = ½ΔU·(Rⁿ + Rⁿ⁺¹) (both sides of row 0 vanish for a massless node), so (E) becomes
///
///       Eⁿ⁺¹ − Eⁿ = ½(F_cⁿ + F_cⁿ⁺¹)·ΔU + ½(Fⁿ + Fⁿ⁺¹)·ΔU,                                          (EF)
///
///   the trapezoidal work of the load added to the contact's: E + Φ changes by exactly W = ½(Fⁿ + Fⁿ⁺¹)·ΔU
///   on a step whose levels lie on one side of the kink (doctest).
/// - Moreau–Jean: M(Vⁿ⁺¹ − Vⁿ) = −ΔtS(θUⁿ⁺¹ + (1 − θ)Uⁿ) + ΔtF_θ + p e₀ with F_θ = θFⁿ⁺¹ + (1 − θ)Fⁿ (the
///   load by the θ-rule, like the stiffness), the index set u₀ + g₀ + ½Δt v₀ ≤ 0. In (MJ) the load is one
///   more force paired with θVⁿ⁺¹ + (1 − θ)Vⁿ = ΔU/Δt: Eⁿ⁺¹ − Eⁿ gains F_θ·ΔU (doctest).
/// - A constant load without contact (a free bar falling, U = −gt²/2 on every node when the load vector
///   is M·1 times −g, as for the consistent mass): Newmark with γ = ½ integrates a constant acceleration
///   exactly for every β (its truncation error involves U''' = 0), so the free fall is exact at the nodes;
///   Moreau–Jean's Uⁿ⁺¹ = Uⁿ + ΔtVⁿ − θgΔt² is exact for θ = ½ and off by (θ − ½)gΔt·tₙ otherwise
///   (doctest, both).
/// - The gap in free flight changes nothing before the contact, so the first impact moves by g₀/v, v the
///   contact end's approach speed (½ on the paper's benchmark before t = 2: u(0, t) = ½ − t/2) (doctest).
#include "classes/contact_classes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include "classes/step_pieces.hpp"
#include "steps/contact.hpp"

namespace mrm {

void validate_contact_class(const SchemeParameters& p, bool massless) {
  const SchemeInfo* entry = find_entry(contact_class_schemes(), p.scheme);
  if (!entry) return;
  if (entry->takes(SchemeParameter::newmark_beta)) {
    if (!(std::isfinite(p.newmark_beta) && p.newmark_beta >= 0))
      throw InvalidParameter("newmark_beta", "Newmark's beta must be finite and >= 0 (allowed: 0 <= beta < inf)");
    // Newmark's amplification matrix has spectral radius > 1 for γ < ½ at every step size (Hughes,
    // The Finite Element Method, §9.1): the scheme gains energy at every step.
    if (!(std::isfinite(p.newmark_gamma) && p.newmark_gamma >= 0.5))
      throw InvalidParameter("newmark_gamma",
                             "Newmark's gamma below 1/2 amplifies every mode (allowed: 1/2 <= gamma < inf)");
    if (p.scheme == Scheme::newmark && p.newmark_beta == 0 && !massless)
      throw InvalidParameter("newmark_beta",
                             "0 with exact enforcement and a contact node with inertia: the constraint's force has no "
                             "weight in an explicit step (GetFEM's demo refuses it too) (allowed: beta > 0, or a "
                             "mass with a massless contact node)");
  }
  if (p.scheme == Scheme::penalty && !(std::isfinite(p.penalty) && p.penalty > 0))
    throw InvalidParameter("penalty",
                           "the penalty parameter gamma0 must be positive and finite (allowed: 0 < "
                           "gamma0 < inf)");
  if (p.scheme == Scheme::nitsche) {
    if (!(std::isfinite(p.nitsche_gamma) && p.nitsche_gamma > 0))
      throw InvalidParameter("nitsche_gamma",
                             "Nitsche's gamma0 must be positive and finite (allowed: 0 < gamma0 < inf)");
    if (!(p.nitsche_theta >= -1 && p.nitsche_theta <= 1))
      throw InvalidParameter("nitsche_theta", "Nitsche's theta must lie in [-1, 1] (allowed: -1 <= theta <= 1)");
    if (!(p.nitsche_theta < p.nitsche_gamma))
      throw InvalidParameter("nitsche_theta",
                             "Nitsche's theta must be below gamma0: the first element's stiffness (1 - theta/gamma0)/h "
                             "is not positive otherwise (allowed: theta < gamma0)");
  }
  if (p.scheme == Scheme::moreau_jean) {
    if (!(p.moreau_theta >= 0.5 && p.moreau_theta <= 1))
      throw InvalidParameter("moreau_theta",
                             "Moreau-Jean's theta must lie in [0.5, 1]; below 1/2 the theta-method amplifies "
                             "(allowed: 0.5 <= theta <= 1)");
    if (massless)
      throw InvalidParameter("mass",
                             "moreau-jean needs a contact node with inertia: its impact law acts on the node's "
                             "velocity (allowed: the consistent mass, or another scheme)");
  }
}

std::unique_ptr<ContactClassStep> make_contact_class_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                          const SchemeParameters& p, double dt, double h, bool has_load,
                                                          double gap) {
  const SchemeInfo* entry = find_entry(contact_class_schemes(), p.scheme);
  if (!entry) throw std::logic_error("make_contact_class_step: the scheme is not a contact class");
  if (p.scheme == Scheme::moreau_jean)
    return class_steps::make_moreau_jean_step(mass, stiffness, p, dt, has_load, gap, entry->id);
  if (p.scheme == Scheme::dke)
    return class_steps::make_dke_step(mass, stiffness, dt, has_load, gap, p.kernel == StepKernel::fast, entry->id);
  return class_steps::make_newmark_type_step(mass, stiffness, p, dt, h, has_load, gap, entry->id);
}

SchemeParameters class_parameters(Scheme scheme, double beta, double gamma) {
  SchemeParameters p;
  p.scheme = scheme;
  const SchemeInfo* entry = find_entry(contact_class_schemes(), scheme);  // null for the other schemes
  if (entry && entry->takes(SchemeParameter::newmark_beta)) {
    p.newmark_beta = beta;
    p.newmark_gamma = gamma;
  }
  return p;
}

// ---------------------------------------------------------------------------------------------------
// The registry entries of the contact classes (time/scheme_registry.hpp gathers them).
namespace {

// A run's checks: the class's parameters and mass, and the step limit of Newmark with β < γ/2 (before
// any work, newmark_stability.cpp).
void validate_class_run(const StepContext& c) {
  validate_contact_class(c.parameters, c.massless);
  check_newmark_step(c.mass, c.stiffness, c.parameters, c.dt, c.mesh.contact_compliance(),
                     c.mesh.uniform() && c.mesh.homogeneous() ? c.mesh.h() : 0.0);
}

// The step of a run: StepKernel::fast runs the fused step, StepKernel::reference the readable one (the same
// bits: the doctest "the fused class steps are their readable steps, bit for bit").
std::unique_ptr<Step> make_class_run_step(const StepContext& c) {
  return make_contact_class_step(c.mass, c.stiffness, c.parameters, c.dt, c.mesh.contact_compliance(), c.has_load,
                                 c.gap);
}

}  // namespace

const std::vector<SchemeInfo>& contact_class_schemes() {
  using P = SchemeParameter;
  static const std::vector<SchemeInfo> entries = {
      {Scheme::newmark,
       "newmark",
       "Newmark (β, γ) with exact contact enforcement by a multiplier at the new level (β = 0: explicit)",
       {P::newmark_beta, P::newmark_gamma},
       validate_class_run,
       make_class_run_step,
       4,
       "Newmark (β, γ), exact contact",
       "Newmark $(\\beta, \\gamma)$, exact contact",
       "Newmark"},
      {Scheme::penalty,
       "penalty",
       "Newmark (β, γ) with the penalty force (γ₀/h) min(0, u₀)",
       {P::newmark_beta, P::newmark_gamma, P::penalty},
       validate_class_run,
       make_class_run_step,
       4,
       "penalty",
       "Newmark $(\\beta, \\gamma)$ with a penalty",
       "penalty"},
      {Scheme::nitsche,
       "nitsche",
       "Newmark (β, γ) with Nitsche's contact terms (θ, γ₀), GetFEM's formulation",
       {P::newmark_beta, P::newmark_gamma, P::nitsche_theta, P::nitsche_gamma},
       validate_class_run,
       make_class_run_step,
       4,
       "Nitsche",
       "Newmark $(\\beta, \\gamma)$ with Nitsche's terms",
       "Nitsche"},
      {Scheme::moreau_jean,
       "moreau-jean",
       "Moreau–Jean (θ, e): the θ-method with the velocity impact law v⁺ = −e v⁻ (contact node with inertia)",
       {P::moreau_theta, P::restitution},
       validate_class_run,
       make_class_run_step,
       5,
       "Moreau–Jean",
       "Moreau--Jean $(\\theta, e)$",
       "MJ"},
      // An energy-consistent treatment from the literature.
      {Scheme::dke,
       "dke",
       "Deuflhard–Krause–Ertel's contact-stabilised Newmark (¼, ½): the predictor projected onto the admissible "
       "set in the mass norm, the contact force at the new level only",
       {},
       validate_class_run,
       make_class_run_step,
       6,
       "DKE (contact-stabilised Newmark)",
       "Deuflhard--Krause--Ertel's contact-stabilised Newmark",
       "DKE"},
  };
  return entries;
}

}  // namespace mrm
