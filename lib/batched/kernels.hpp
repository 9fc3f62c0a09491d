/// @file kernels.hpp
/// @brief The vector kernels of the batched step (kernels.cpp): the interleaved arrays each pass reads and
/// writes, and the passes, each dispatched to the current target at the width of a group.
#pragma once

#include <cstddef>

/// @cond MRM_INTERNAL (the kernels' plumbing: not part of the library's interface)
namespace mrm::batched {

// The interleaved arrays of one group and what the two sweeps exchange with the per-lane contact
// decision between them (plain pointers: the same struct for every target).
struct Kernel {
  // head: the explicit head rows of the lane with the most; rows head_min … head − 1 are explicit in the lanes
  // whose own head (heads, per lane, as doubles) is longer, Toeplitz rows of the interior in the others.
  std::size_t n = 0, lanes = 0, head = 0, head_min = 0;
  const double* heads = nullptr;
  // Per lane 1 where the lane's run has n − 1 unknowns (its last row is n − 2: a fixed far end beside runs
  // with a free one), 0 where it has n; null when every lane has n.
  const double* short_lanes = nullptr;
  std::size_t flat_begin = 0, flat_end = 0;  // rows [flat_begin, flat_end) of the interior: constant factors
  bool three_level = false, keeps = false;   // keeps: a lane may be left untouched (CN-switch, step(advance))
  double *u = nullptr, *y = nullptr, *w = nullptr, *x = nullptr;
  const double *elimination = nullptr, *elimination_pair = nullptr, *inverse_pivot = nullptr, *upward = nullptr,
               *upward_pair = nullptr;
  const double *head_rows = nullptr, *interior = nullptr, *last = nullptr;  // 10 coefficients × lanes per row
  const double *rate = nullptr, *memory = nullptr, *ps_q_weight = nullptr;  // per lane; 1 − 4β for PS
  const double *u0_next = nullptr, *recurrence_d0 = nullptr, *keep = nullptr;
  double* energy = nullptr;      // per lane, written by the sweep up
  const double* load = nullptr;  // the steady loads' terms of the right-hand side, per node and lane (or null)
};

// The same for the Newmark-type steps (contact_classes.cpp, NewmarkTypeStep): the interleaved state (U, Y =
// Uⁿ⁺¹, V, Rⁿ, Rⁿ⁺¹, T the mass solve's right-hand side), the rows of M, S and S_ℓ, the factors of A and M̃,
// z, and per lane Δt, Δt²(½ − β), 1 − γ, γ, g₀, g₁, the massless flag, the decision (u₀, λ, shift), the keep
// flag and the two forms of the energy.
struct NewmarkKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *r = nullptr, *r_next = nullptr, *t = nullptr;
  const double *m_diag = nullptr, *m_lower = nullptr, *m_upper = nullptr, *s_diag = nullptr, *s_lower = nullptr,
               *s_upper = nullptr, *l_diag = nullptr, *l_lower = nullptr, *l_upper = nullptr;
  const double *elimination = nullptr, *inverse_pivot = nullptr, *upward = nullptr, *mass_elimination = nullptr,
               *mass_inverse_pivot = nullptr, *mass_upward = nullptr, *z = nullptr;
  const double *dt = nullptr, *force_weight = nullptr, *one_minus_gamma = nullptr, *gamma = nullptr, *g0 = nullptr,
               *g1 = nullptr, *massless = nullptr, *u0 = nullptr, *lambda = nullptr, *shift = nullptr, *keep = nullptr;
  double* kinetic_strain = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level
};

// The same for Moreau–Jean and DKE (contact_classes.cpp, OneSolveStep): the interleaved state (U, Y the
// solve's unknowns, V, P DKE's projected predictor), the rows of the right-hand side's matrix (right), of M
// and S, the factors of A, DKE's M⁻¹e₀, and per lane Δt, c, θ, 1 − θ, 2/Δt, the flag b₀ = 0, the projection
// (α, its flag, −g₀), the decision's first unknown x₀, the keep flag and the two forms of the energy.
struct OneSolveKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false, dke = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *p = nullptr;
  const double *right_diag = nullptr, *right_lower = nullptr, *right_upper = nullptr, *m_diag = nullptr,
               *m_lower = nullptr, *m_upper = nullptr, *s_diag = nullptr, *s_lower = nullptr, *s_upper = nullptr;
  const double *elimination = nullptr, *inverse_pivot = nullptr, *upward = nullptr, *column = nullptr;
  const double *dt = nullptr, *weight = nullptr, *theta = nullptr, *one_minus_theta = nullptr, *two_over_dt = nullptr,
               *row0_zero = nullptr, *alpha = nullptr, *projected = nullptr, *minus_gap = nullptr, *x0 = nullptr,
               *keep = nullptr;
  double* kinetic_strain = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level
};

// The same for the explicit classes (explicit_schemes.cpp, ExplicitStep): the interleaved state (U, Y the
// drift's Ũ and then Uⁿ⁺¹, V, A the consistent mass's solve), the rows of S and M, the lumped inverse mass or
// the consistent mass's LDLᵀ (pivots, factors), r = M⁻¹e₀, and per lane Δt, Δt/2, h, whether the bar is
// clamped at its far end, Taylor–Flanagan's correction (its flag, Δtμ, Δt²μ), the keep flag and the energy.
struct ExplicitKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false, lumped = true, corrects = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *a = nullptr;
  const double *s_diag = nullptr, *s_lower = nullptr, *s_upper = nullptr, *m_diag = nullptr, *m_lower = nullptr,
               *m_upper = nullptr, *inverse_mass = nullptr, *pivot = nullptr, *factor = nullptr,
               *impulse_response = nullptr;
  const double *dt = nullptr, *half_dt = nullptr, *h = nullptr, *clamped = nullptr, *correct = nullptr,
               *dt_mu = nullptr, *dt2_mu = nullptr, *keep = nullptr;
  double* energy = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level (BarSimulation's)
};

// The width of a group's kernel: the target's full width, or capped at 4 or 2 doubles (the remainder of a
// family, BatchedSimulation's constructor).
enum class Width { full, four, two };

// The number of double lanes of the current target at a width (at most the full width).
std::size_t lane_count(Width width);
// The widest of the target's full width, 4 and 2 lanes whose lane count divides `stride` (the lanes of a
// group, or of a batch's narrower remainder: batched_step.cpp); false when none does.
bool width_dividing(std::size_t stride, Width& width);

// The passes, on the current target at the group's width: the two sweeps of the fused step (fast_step.cpp),
// the Newmark type's sweep down and the rest of its step, Moreau–Jean's and DKE's sweep down and sweep up,
// the explicit classes' half kick and drift and their second half kick.
void sweep_down(Width width, const Kernel& k);
void sweep_up(Width width, const Kernel& k);
void newmark_down(Width width, const NewmarkKernel& k);
void newmark_up(Width width, const NewmarkKernel& k);
void one_solve_down(Width width, const OneSolveKernel& k);
void one_solve_up(Width width, const OneSolveKernel& k);
void explicit_drift(Width width, const ExplicitKernel& k);
void explicit_kick(Width width, const ExplicitKernel& k);

}  // namespace mrm::batched
/// @endcond
