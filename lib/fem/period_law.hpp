/// @file period_law.hpp
/// @brief The period law (mathematics.md §8): the effective free and contact lengths of a mass
/// redistribution from the first eigenvalue of its reduced pencils, the discrete period of the
/// benchmark and its error, and the leading-order rule ΔP = 2 δm_loc + (3/2) δm_glob.
#pragma once

#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "fem/pencil.hpp"

namespace mrm {

/// The two linear systems a bar with a massless contact node alternates between (f = 0), on the
/// nodes 1..N−1 (mathematics.md §8): free flight, u₀ = u₁, stiffness S̄ − e₁e₁ᵀ/h (the element
/// (0, h) moves rigidly: a free end at node 1); contact, u₀ = 0, stiffness S̄ (held at both ends).
/// The mass is M̄, the redistributed mass without row and column 0. For a contact node with inertia
/// (the consistent mass) the free pencil is (S, M) on nodes 0..N−1 and the contact pencil the same
/// as above with M's block on 1..N−1.
struct ReducedPencils {
  Tridiagonal mass_free;          ///< the mass of the free-flight pencil
  Tridiagonal stiffness_free;     ///< the stiffness of the free-flight pencil
  Tridiagonal mass_contact;       ///< the mass of the contact pencil (u₀ = 0)
  Tridiagonal stiffness_contact;  ///< the stiffness of the contact pencil (u₀ = 0)
};
/// Throws std::invalid_argument for a mesh with N < 3 (the reduced pencils need two free nodes).
ReducedPencils reduced_pencils(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// The same from M^mod already assembled on the unknowns (AssembledMass::matrix).
ReducedPencils reduced_pencils(const UniformMesh& mesh, const Tridiagonal& mass);

/// The lengths of the continuous bars whose first frequency is that of the reduced pencils:
/// ℓ_f = π/(2ω_f) (free–clamped, a quarter wave), ℓ_c = π/ω_c (clamped–clamped, a half wave).
struct EffectiveLengths {
  double free;     ///< ℓ_f
  double contact;  ///< ℓ_c
  /// The discrete period of the benchmark (free flight, contact, free flight back): 2ℓ_f + ℓ_c.
  double period() const { return 2 * free + contact; }
};
/// ℓ_f and ℓ_c of a redistribution on a mesh, from the smallest eigenvalues of its reduced pencils.
EffectiveLengths effective_lengths(const UniformMesh& mesh, const MassRedistribution& redistribution);

/// The period law's prediction for the benchmark (u⁰ = a(L − x), period 3L) on a mesh: the discrete
/// period 2ℓ_f + ℓ_c, its error against 3L (the drift of the impact times per period), and the error
/// of the first impact time, ℓ_f − L. Negative errors mean early impacts.
struct PeriodPrediction {
  EffectiveLengths lengths;   ///< ℓ_f and ℓ_c
  double period_error;        ///< 2ℓ_f + ℓ_c − 3L
  double first_impact_error;  ///< ℓ_f − L
};
/// The prediction of the period law for a redistribution on a mesh (see PeriodPrediction).
PeriodPrediction predict_period(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// The same from M^mod already assembled on the unknowns (AssembledMass::matrix): the same bits.
PeriodPrediction predict_period(const UniformMesh& mesh, const Tridiagonal& mass);

/// The leading-order period change of a redistribution that adds the mass `local` at node 1 beyond
/// Mod 3's M̄₁₁ = 4h/3 and spreads the mass `global` uniformly over the bar: ΔP = 2 δm_loc +
/// (3/2) δm_glob (the effective lengths change by δℓ_f = δm_loc + δm_glob/2, δℓ_c = δm_glob/2).
double predicted_period_change(double local, double global);

/// The drift kernel of the benchmark's period, κ(ξ) = 2 cos²(πξ/2) + sin²(πξ), ξ = x/L: a point mass
/// δm at x changes the period by κ(x/L) δm to first order (period_law.cpp, "unequal elements").
/// κ(0) = 2 (a mass at the contact end: 2 δm_loc), its mean over the bar 3/2 (spread: (3/2) δm_glob).
double drift_kernel(double xi);

/// The period law on any mesh (graded), to first order in the mass change: with δm_i the
/// row sums (lumped masses) of M̄ − M̄_Mod3 at the nodes i ≥ 1 of a homogeneous bar of unit wave
/// speed, ΔP = Σ_i δm_i κ(x_i/L), the change of the period 2ℓ_f + ℓ_c against Mod 3's (which is 0 +
/// O(h²) on any mesh). On the uniform mesh it is 2 δm_loc + (3/2) δm_glob up to O(h²). Throws
/// std::invalid_argument for a material that is not E = ρ = 1, a free far end, or a contact node with
/// inertia.
double first_order_period_change(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// The two parts of first_order_period_change: δℓ_f = Σ δm_i cos²(πx_i/2L) (the first impact moves by
/// it) and δℓ_c = Σ δm_i sin²(πx_i/L), as an EffectiveLengths of changes (period() is ΔP). Same refusals.
EffectiveLengths first_order_length_changes(const UniformMesh& mesh, const MassRedistribution& redistribution);

}  // namespace mrm
