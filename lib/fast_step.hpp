/// @file fast_step.hpp
/// @brief The fast path of BarSimulation: one step of the schemes fused into the two sweeps of the
/// tridiagonal solve, each sweep run as two chains (mathematics.md §4; the reference step it must
/// reproduce to round-off is BarSimulation's, in schemes.cpp).
#pragma once

#include <vector>

#include "p1.hpp"

namespace mrm {

class BarSimulation;

/// The fused two-chain kernel of one time step (fast_step.cpp). It computes the step (★) of
/// schemes.cpp, A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀ with the closed-form contact step, without
/// forming the right-hand side, the velocity or the energy as whole vectors: everything is done
/// inside the sweep down and the sweep up of the solve. It keeps the rows of B₁, B₂, M and S it
/// reads (a few explicit rows near the contact node, one for the Toeplitz interior, the last) and
/// works on the state of the BarSimulation it is given.
class FastStep {
 public:
  /// Reads the rows of B₁, B₂ (the step's right-hand side matrices), M and S (the energies), all of
  /// size N, and finds the Toeplitz interior (rows compared exactly). Rows below `minimum_head` are
  /// kept explicit whatever their values (the energy-conserving scheme needs row 1 explicit).
  FastStep(const Tridiagonal& b1, const Tridiagonal& b2, const Tridiagonal& mass, const Tridiagonal& stiffness,
           Index minimum_head = 1);

  /// Advances `simulation` by one step of its scheme: Uⁿ⁺¹, the velocity, λ and the energy replace
  /// the current state. `has_load` tells whether the problem has a load (then Fⁿ⁺¹ has been filled in).
  /// Returns false, with the state untouched, where CN-switch must take its θ-step instead (a change
  /// of the contact status across the Crank–Nicolson step).
  bool step(BarSimulation& simulation, bool has_load) const;

 private:
  // One row of B₁ and B₂ (lower, diagonal, upper) and of M and S (diagonal and twice the lower entry).
  struct Row {
    double b1l, b1d, b1u, b2l, b2d, b2u;
    double md, ml2, sd, sl2;
  };
  std::vector<Row> head_;    // rows 0 … head−1, explicitly
  Row interior_{}, last_{};  // the common row of head … N−2, and row N−1
  template <bool three_level, bool has_load>
  bool fused_step(BarSimulation& simulation) const;
};

}  // namespace mrm
