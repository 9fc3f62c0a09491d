/// @file fast_step.hpp
/// @brief The fast path of BarSimulation: one step of the schemes fused into the two sweeps of the
/// tridiagonal solve, each sweep run as two chains (mathematics.md §4; the reference step it must
/// reproduce to round-off is BarSimulation's, in schemes.cpp).
#pragma once

#include <vector>

#include "steps/contact.hpp"
#include "fem/p1.hpp"
#include "steps/step.hpp"
#include "steps/step_matrices.hpp"

namespace mrm {

/// The fused two-chain kernel of one time step (fast_step.cpp). It computes the step (★) of
/// schemes.cpp, A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀ with the closed-form contact step, without
/// forming the right-hand side, the velocity or the energy as whole vectors: everything is done
/// inside the sweep down and the sweep up of the solve. It keeps the scalars of the step and the rows
/// of B₁, B₂, M and S it reads (a few explicit rows near the contact node, one for the Toeplitz
/// interior, the last), and advances the StepState it is given.
class FastStep {
 public:
  /// Reads the step's scalars and the rows of B₁, B₂ (step_matrices), M and S (the energies), all of
  /// size N, and finds the Toeplitz interior (rows compared exactly); `parameters` gives the scheme
  /// (its β and e for Paoli–Schatzman), h the mesh size.
  FastStep(const StepMatrices& step, const Tridiagonal& mass, const Tridiagonal& stiffness,
           const SchemeParameters& parameters, double h);

  /// Advances `state` by one step of the scheme, with A factorised in `solver`: Uⁿ⁺¹, the velocity, λ
  /// and the energy replace the current ones. `has_load` tells whether the problem has a load (then
  /// Fⁿ⁺¹ has been filled in). Returns false, with the state untouched, where CN-switch must take its
  /// θ-step instead (a change of the contact status across the Crank–Nicolson step).
  bool step(StepState& state, const ContactSolver& solver, bool has_load) const;

  // What the batched step (batched_step.cpp) reads of one run's fast step to step it in a vector lane:
  // its rows, its scalars, and the contact decision of row 0, the scalar code every lane runs.

  /// One row of B₁ and B₂ (lower, diagonal, upper) and of M and S (diagonal and twice the lower entry).
  struct Row {
    double c1l;  ///< C₁'s lower entry (the increment form's C₁ = B₁ − A, or B₁ + B₂ − A)
    double c1d;  ///< C₁'s diagonal entry
    double c1u;  ///< C₁'s upper entry
    double c2l;  ///< C₂'s lower entry (B₂, or −B₂ for three levels)
    double c2d;  ///< C₂'s diagonal entry
    double c2u;  ///< C₂'s upper entry
    double md;   ///< M's diagonal entry
    double ml2;  ///< twice M's lower entry
    double sd;   ///< S's diagonal entry
    double sl2;  ///< twice S's lower entry
  };
  /// Row 0 and the contact decision of one run (fast_step.cpp).
  struct ContactDecision {
    double u0_next = 0;          ///< u₀ⁿ⁺¹
    double recurrence_d0 = 0;    ///< the sweep up's start at row 0
    double lambda = 0;           ///< λⁿ⁺¹
    bool active = false;         ///< the contact status
    bool status_change = false;  ///< CN-switch must take its θ-step
  };
  /// The contact decision at row 0 from the sweep down's last values (fast_step.cpp).
  ContactDecision contact_decision(double u0, double u1, double w0, double w1, double y_next, double lambda,
                                   bool active, const ContactSolver& solver, bool has_load, double f0_now,
                                   double f0_next) const;
  const std::vector<Row>& head() const { return head_; }              ///< rows 0 … head−1
  const Row& interior() const { return interior_; }                   ///< the common row of head … N−2
  const Row& last() const { return last_; }                           ///< row N−1
  const StepMatrices& coefficients() const { return coefficients_; }  ///< the step's scalars
  bool three_level() const { return three_level_; }                   ///< Paoli–Schatzman
  bool energy_conserving() const { return energy_conserving_; }       ///< EC
  bool switching() const { return switching_; }                       ///< CN-switch
  double beta() const { return beta_; }                               ///< Paoli–Schatzman's β

 private:
  std::vector<Row> head_;      // rows 0 … head−1, explicitly
  Row interior_{}, last_{};    // the common row of head … N−2, and row N−1
  StepMatrices coefficients_;  // the step's scalars (its matrices are in the Rows)
  bool three_level_, energy_conserving_, switching_;
  double restitution_, beta_, h_;
  template <bool three_level, bool has_load>
  bool fused_step(StepState& state, const ContactSolver& solver) const;
};

}  // namespace mrm
