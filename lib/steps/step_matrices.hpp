/// @file step_matrices.hpp
/// @brief The coefficients of one step (★) of the paper's schemes (mathematics.md §4): the matrices A,
/// B₁, B₂ and the scalars of each scheme, and the right-hand sides of (★) and of its increment form.
#pragma once

#include <Eigen/Core>

#include "fem/p1.hpp"
#include "steps/scheme_parameters.hpp"

namespace mrm {

/// The matrices and scalars of one step (★) of schemes.cpp,
/// A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀, 0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0, for one scheme, mass and Δt: the one
/// builder of the step's coefficients, used by the reference step, the fast kernel's set-up,
/// CN-switch's θ-step and the harness's checks of the contact step (repro/claims/).
struct StepMatrices {
  Tridiagonal a;   ///< A, the step matrix (row 0 the algebraic contact row S₀· when `algebraic_row`)
  Tridiagonal b1;  ///< B₁, applied to Uⁿ (row 0 zero with the algebraic row)
  Tridiagonal b2;  ///< B₂, applied to W = Vⁿ (two levels) or Uⁿ⁻¹ (three levels) (row 0 zero likewise)
  /// The increment form the steps solve (schemes.cpp, "the increment form"): A ΔU = C₁ Uⁿ + C₂ W' + G
  /// − κλe₀ for ΔU = Uⁿ⁺¹ − Uⁿ, with C₁ = B₁ − A = −θΔt²S (two levels) or B₁ + B₂ − A = −Δt²S (three),
  /// row 0 −S₀· with the algebraic row, built as multiples of S (no difference of matrices is rounded).
  Tridiagonal c1;
  /// C₂ = B₂ applied to W' = Vⁿ (two levels), or −B₂ = A applied to W' = Uⁿ − Uⁿ⁻¹ (three levels);
  /// row 0 zero with the algebraic row.
  Tridiagonal c2;
  double kappa = 0;  ///< κ: the weight of λⁿ⁺¹ (or λⁿ for Paoli–Schatzman) in row 0; 1 with the algebraic row
  double load_now = 0;   ///< G = load_now Fⁿ + load_next Fⁿ⁺¹ on the rows of inertia
  double load_next = 0;  ///< see load_now (with the algebraic row, G₀ = F₀ⁿ⁺¹)
  double lambda_in_rhs = 0;  ///< the weight of −λⁿ in row 0 (Crank–Nicolson-type steps with an inertial contact node)
  double velocity_rate = 0;  ///< two levels: Vⁿ⁺¹ = rate (Uⁿ⁺¹ − Uⁿ) − memory Vⁿ; three levels: X = rate (Uⁿ⁺¹ − Uⁿ)
  double velocity_memory = 0;  ///< see velocity_rate
  bool algebraic_row = false;  ///< whether row 0 is the algebraic contact row S₀·U = F₀ − λ (massless contact node)
  /// The part of the obstacle g that the gap sets: −gap, or −(1 + e) gap for Paoli–Schatzman's
  /// averaged constraint (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ≥ −gap; 0 without a gap (set by BarSimulation).
  double obstacle_offset = 0;
};
/// The step of `parameters.scheme` (CN-switch's and EC's is Crank–Nicolson's) on the unknowns 0..N−1
/// with mass M and stiffness S (schemes.cpp, mathematics.md §4). Does not check the parameters
/// (BarSimulation does).
StepMatrices step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& parameters,
                           double dt);
/// The step of the θ-rule, θ ∈ [½, 1] (θ = ½ is Crank–Nicolson, θ = 1 backward Euler; CN-switch's
/// θ-step), with the algebraic contact row when the contact node is massless.
StepMatrices theta_step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, double theta, double dt);
/// The right-hand side of (★) before the contact force: b = B₁ Uⁿ + B₂ W + G − lambda_in_rhs λⁿ e₀,
/// row 0 replaced by F₀ⁿ⁺¹ with the algebraic row. `load_now` and `load_next` are Fⁿ and Fⁿ⁺¹, or
/// null for f = 0.
Eigen::VectorXd step_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                     double lambda, const Eigen::VectorXd* load_now = nullptr,
                                     const Eigen::VectorXd* load_next = nullptr);
/// The right-hand side of the increment form before the contact force: c = C₁ Uⁿ + C₂ W' + G −
/// lambda_in_rhs λⁿ e₀, row 0 −S₀·Uⁿ + F₀ⁿ⁺¹ with the algebraic row; W' = Vⁿ or Uⁿ − Uⁿ⁻¹.
Eigen::VectorXd increment_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                          double lambda, const Eigen::VectorXd* load_now = nullptr,
                                          const Eigen::VectorXd* load_next = nullptr);

}  // namespace mrm
