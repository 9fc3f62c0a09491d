/// @file explicit_schemes.hpp
/// @brief The explicit contact classes of Doyen–Ern–Piperno (doc/contact_treatments.md §6): central differences
/// with a lumped mass and the contact by Taylor–Flanagan's velocity correction (`taylor-flanagan`, GetFEM's
/// demo_dynamic_contact_1D.py version 4), or with a massless contact node whose algebraic row mass
/// redistribution makes explicit (`explicit`). Derivations, stability limits and doctests in
/// explicit_schemes.cpp; BarSimulation (schemes.hpp) runs them through the scheme registry.
#pragma once

#include <string>

#include <Eigen/Core>

#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "steps/step.hpp"

namespace mrm {

/// The row-sum lumping of a mass: m_i = Σ_j M̄_ij over all nodes 0..N (the clamped node's column
/// included, as GetFEM's demo sums it before it eliminates the node), on the unknowns 0..N−1. For the
/// consistent P1 mass on the paper's mesh: (h/2, h, …, h); for Mod 3: (0, 3h/2, h, …, h).
Eigen::VectorXd row_sum_lumped_mass(const UniformMesh& mesh, const MassRedistribution& mass);

/// The largest step of an explicit scheme (explicit_schemes.cpp, "the stability limits"), derived from
/// a bound ω²_max ≤ Λ of the squared frequencies of M⁻¹S, Δt_max = 2/√Λ:
/// - a lumped mass (`lumped` non-null, entry 0 zero for a massless contact node): Gershgorin's bound
///   Λ = max_i Σ_j |S_ij| / m_i over the nodes with mass, with node 0 held (the contact-active rows,
///   whose bound is the larger) when it is massless; Δt_max = h on the paper's mesh for the lumped
///   consistent mass and for lumped Mod 3;
/// - the consistent mass (`lumped` null): the element bound Λ = max_e 12 E_e/(ρ_e h_e²)
///   (Irons–Treharne), Δt_max = h/√3.
double explicit_stability_limit(const UniformMesh& mesh, const Eigen::VectorXd* lumped);

/// One step of an explicit scheme (explicit_schemes.cpp) on the state of a BarSimulation: central
/// differences in velocity-Verlet form, the contact by Taylor–Flanagan's correction or by the massless
/// node's algebraic row. The constructor checks, before any work, what only these schemes need, and
/// throws InvalidParameter naming the parameter: `mass` (taylor-flanagan needs a contact node with
/// inertia, explicit a massless one; `lumping none` the consistent mass), `mass_lumping` (explicit
/// takes row-sum only), `dt` (above the stability limit: "dt: dt = … is above … (allowed: 0 < dt <= Δt_max, i.e. C <= …)").
class ExplicitStep final : public Step {
 public:
  /// `mass` the redistribution of the run (assembled here), `stiffness` S on the unknowns, `gap` the
  /// initial gap.
  ExplicitStep(const UniformMesh& mesh, const MassRedistribution& mass, const Tridiagonal& stiffness,
               const SchemeParameters& parameters, double dt, double gap);
  /// The same with the mass the run assembled once on `mesh` (StepContext::assembled).
  ExplicitStep(const UniformMesh& mesh, const AssembledMass& mass, const Tridiagonal& stiffness,
               const SchemeParameters& parameters, double dt, double gap);
  /// The mass the step uses, on the unknowns: diagonal (row-sum lumped) or the consistent one.
  const Tridiagonal& mass() const { return mass_; }
  /// The stability limit Δt_max of this run (explicit_stability_limit).
  double stability_limit() const { return limit_; }
  /// Advances `state` by one step: Uⁿ, Vⁿ = W, λⁿ, Fⁿ (and Fⁿ⁺¹ already loaded when `has_load`) to
  /// level n+1 (Fⁿ⁺¹ swapped into f_now). The energy is left to the caller (BarSimulation: ½VᵀMV + ½UᵀSU).
  void step(StepState& state, bool has_load) const;
  /// One step (step) and the energy of the new level, ½VᵀMV + ½UᵀSU with this step's mass M.
  void advance(StepState& state, Index level, bool has_load) override;
  /// This step's mass, which the run takes for its own (mass()).
  const Tridiagonal* own_mass() const override { return &mass_; }

  /// What the batched step (batched_step.cpp) copies of a run: the step's arrays and scalars (pointers
  /// into this step, valid while it lives).
  struct Lanes {
    const Tridiagonal* stiffness;             ///< S
    const Eigen::VectorXd* inverse_mass;      ///< 1/m_i (lumped; 0 at a massless node), empty otherwise
    const Eigen::VectorXd* pivot;             ///< the consistent mass's LDLᵀ pivots d_i (lumping none)
    const Eigen::VectorXd* factor;            ///< and its factors ℓ_i
    const Eigen::VectorXd* impulse_response;  ///< r = M⁻¹e₀ (taylor-flanagan), empty otherwise
    double dt;                                ///< Δt
    bool lumped;                              ///< whether M is diagonal
  };
  /// The step's arrays, for the lanes.
  Lanes lanes() const;
  /// The contact after the drift (explicit_schemes.cpp): Taylor–Flanagan's correction, if ũ₀ + gap < 0,
  /// or the massless node's algebraic row.
  struct Contact {
    double lambda = 0;     ///< λⁿ⁺¹ (Taylor–Flanagan's μ)
    bool active = false;   ///< the status
    bool correct = false;  ///< Taylor–Flanagan: V −= Δtμ r, U −= Δt²μ r
    bool set_u0 = false;   ///< explicit: u₀ⁿ⁺¹ = u0
    double u0 = 0;         ///< the massless node's new value
  };
  /// The contact of the step from the drift's ũ₀, ũ₁, ṽ₀ (Vⁿ⁺½'s) and the load's F₀ⁿ⁺¹.
  Contact contact(double u0, double u1, double v0, double load0) const;

 private:
  void accelerate(const Eigen::VectorXd& u, const Eigen::VectorXd* load, double lambda, Eigen::VectorXd& a) const;
  UniformMesh mesh_;
  bool taylor_flanagan_, lumped_, massless_;
  double dt_, gap_, compliance_, limit_;
  Tridiagonal mass_, stiffness_;
  Eigen::VectorXd inverse_mass_;      // 1/m_i (lumped; 0 at a massless node)
  Eigen::VectorXd pivot_, factor_;    // LDLᵀ of the consistent mass (lumping none)
  Eigen::VectorXd impulse_response_;  // r = M⁻¹e₀ (taylor-flanagan)
};

/// The registry entries of central differences: taylor-flanagan, explicit (time/scheme_registry.hpp gathers
/// them). Their checks are ExplicitStep's constructor's.
const std::vector<SchemeInfo>& central_difference_schemes();

}  // namespace mrm
