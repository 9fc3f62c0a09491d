/// @file one_step_form.hpp
/// @brief The step of the paper's schemes (Crank–Nicolson, backward Euler, Paoli–Schatzman) and of EC and
/// CN-switch, all written as one step (★) A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀ with the closed-form contact
/// step (mathematics.md §4, the paper's §3): the reference step written as its derivation, the fast kernel
/// (fast_step.hpp), and their registry entries.
#pragma once

#include <memory>
#include <vector>

#include "steps/contact.hpp"
#include "steps/fast_step.hpp"
#include "steps/step.hpp"
#include "steps/step_matrices.hpp"

namespace mrm {

/// One run's step (★): A factorised once, the reference step or the fast kernel (as
/// SchemeParameters::kernel says), and CN-switch's θ-step with its own factorisation. Memory is O(N): the
/// fast kernel keeps only its rows, and B₁, B₂ are kept for the reference step only.
class OneStepFormStep final : public Step {
 public:
  /// Assembles (★) for the run (step_matrices), factorises A and, for CN-switch, the θ-step's matrix.
  explicit OneStepFormStep(const StepContext& context);
  /// One step: the fast kernel, or the reference step; CN-switch's θ-step where the contact status changes.
  void advance(StepState& state, Index level, bool has_load) override;
  /// CN-switch's θ-step from `state`, replacing a Crank–Nicolson step at a change of the contact status
  /// (`has_load`: Fⁿ⁺¹ has been filled in).
  void switch_step(StepState& state, bool has_load) const;
  /// The fast kernel (null for the reference step), for the batched step.
  const FastStep* fast() const { return fast_.get(); }
  /// A of (★), factorised, for the batched step.
  const ContactSolver& solver() const { return solver_; }

 private:
  void reference_step(StepState& state, bool has_load) const;

  UniformMesh mesh_;
  Tridiagonal mass_;  // M, for the energies of the reference step and of the θ-step (empty otherwise)
  double restitution_, beta_, gap_;
  bool three_level_, energy_conserving_;
  // (★)'s matrices and scalars (step_matrices), A factorised in solver_; B₁ and B₂ only for the reference step.
  StepMatrices step_;
  ContactSolver solver_;
  std::unique_ptr<const FastStep> fast_;
  // CN-switch: the θ-step's matrices and scalars (theta_step_matrices) and its factorisation.
  struct SwitchStep {
    StepMatrices matrices;
    ContactSolver solver;
  };
  std::unique_ptr<const SwitchStep> switch_;
};

/// The registry entries of the schemes written as (★): cn, be, ps, ec, cn-switch.
const std::vector<SchemeInfo>& one_step_form_schemes();

}  // namespace mrm
