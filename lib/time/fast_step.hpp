/// @file fast_step.hpp
/// @brief The fast path of BarSimulation: one step of the schemes fused into the two sweeps of the
/// tridiagonal solve, each sweep run as two chains (mathematics.md §4; the reference step it must
/// reproduce to round-off is BarSimulation's, in schemes.cpp).
#pragma once

#include <vector>

#include "time/contact.hpp"
#include "fem/p1.hpp"
#include "time/schemes.hpp"

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

 private:
  // One row of B₁ and B₂ (lower, diagonal, upper) and of M and S (diagonal and twice the lower entry).
  struct Row {
    double c1l, c1d, c1u, c2l, c2d, c2u;
    double md, ml2, sd, sl2;
  };
  std::vector<Row> head_;      // rows 0 … head−1, explicitly
  Row interior_{}, last_{};    // the common row of head … N−2, and row N−1
  StepMatrices coefficients_;  // the step's scalars (its matrices are in the Rows)
  bool three_level_, energy_conserving_, switching_;
  double restitution_, beta_, h_;
  friend class BatchedSimulation;  // reads the rows and scalars (batched_step.cpp)
  // Row 0 and the contact decision of one run (fast_step.cpp), shared with the batched step.
  struct ContactDecision {
    double u0_next = 0, recurrence_d0 = 0, lambda = 0;
    bool active = false, status_change = false;  // status_change: CN-switch must take its θ-step
  };
  ContactDecision contact_decision(double u0, double u1, double w0, double w1, double y_next, double lambda,
                                   bool active, const ContactSolver& solver, bool has_load, double f0_now,
                                   double f0_next) const;
  template <bool three_level, bool has_load>
  bool fused_step(StepState& state, const ContactSolver& solver) const;
};

}  // namespace mrm
