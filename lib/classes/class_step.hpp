/// @file class_step.hpp
/// @brief The step of a contact class as BarSimulation runs it (ContactClassStep) and as the batched
/// kernels take it (NewmarkTypeStep, OneSolveStep): the interfaces that newmark_type.cpp,
/// moreau_jean.cpp and dke.cpp implement.
#pragma once

#include <array>
#include <optional>

#include "steps/contact.hpp"
#include "steps/step.hpp"

namespace mrm {

/// One run's step of a contact class, on the unknowns 0..N−1 with mass M and stiffness S. It reads the
/// initial level from the StepState (U⁰ in u, V⁰ in w, the massless node's λ⁰ in lambda) and writes
/// every level there: u, w (the velocity), lambda (the contact stress λ ≤ 0 at the new level; Moreau–Jean:
/// the impulse per step −p/Δt), energy (the class's discrete energy), active. A run that loses
/// finiteness throws std::runtime_error naming the level.
class ContactClassStep : public Step {
 public:
  /// Advances `state` from level n to n+1 (n the argument, for the error message).
  virtual void step(StepState& state, Index level) = 0;
  /// One step (step); a class reads Fⁿ⁺¹ from the state when it was built with a load.
  void advance(StepState& state, Index level, bool) override { step(state, level); }
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

}  // namespace mrm
