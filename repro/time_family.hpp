// The Δt study over a family of meshes (the error estimate in time, mathematics.md §5): Crank–Nicolson's
// error in time at fixed h, against a reference that is itself checked against a finer one, every halving
// of Δt in the asymptotic range judged, on every mesh of a family. Used by experiments/fig_time_error.cpp
// (the table of the report) and by the claims check's row on the order in time (repro/claims/). The
// derivations are in time_family.cpp.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "fem/mass_redistribution.hpp"
#include "time/schemes.hpp"

namespace mrm::repro {

/// The protocol of the study on one mesh.
struct TimeFamilySettings {
  long reference_ratio = 2048;      ///< the reference Δt_ref = h/R, checked against h/(2R)
  double largest_courant = 4;       ///< the largest step P h (P h/Δt_ref an integer)
  long finest_divisor = 16;         ///< the smallest step is Δt_ref times this (h/128 for R = 2048)
  double final_time = 3;            ///< T, rounded up to a whole largest step
  double predicted_order = 2;       ///< the trapezoidal rule on the semi-discrete Lipschitz ODE
  double tolerance = 0.25;          ///< |local order − 2| allowed at every judged halving
  double asymptotic_courant = 0.5;  ///< halvings are judged from Δt ≤ this × h on (ω_max Δt ≤ 1)
  double floor_factor = 20;         ///< a halving is judged when both errors are ≥ this × the reference's bound
};

/// The measures that cannot converge on all levels (an L∞ or L² in time of the velocity, whose node-0
/// value jumps at every impact and release) and are judged on the levels where both runs are in the
/// same contact state.
bool judged_on_matched_levels(std::size_t measure);

/// The study on one mesh: the errors of each step against the reference (all levels; matched levels),
/// the reference's own error bound, every local order and the verdict per measure.
struct TimeFamilyMesh {
  long elements = 0;
  double final_time_used = 0;
  std::vector<double> dt;                           ///< the steps, largest first
  std::vector<std::array<double, 8>> all, matched;  ///< relative errors, all levels / matched levels
  std::vector<long> mismatched;                     ///< levels in another contact state than the reference
  std::array<double, 8> reference_bound{};          ///< (4/3) ‖ref − finer ref‖, per measure (judged levels)
  long reference_mismatched = 0;                    ///< the same count for the reference against the finer one
  /// Per measure: the local order of each halving j → j+1 (of the judged errors), whether it is
  /// judged (asymptotic and above the floor), the least and largest judged local orders, the verdict.
  std::array<std::vector<double>, 8> local;
  std::array<std::vector<bool>, 8> judged;
  std::array<double, 8> lowest{}, highest{};
  std::array<int, 8> judged_count{};
  std::array<bool, 8> holds{};
  /// Per measure: the largest step Δt_j from which every halving (j → j+1, …, to the finest) above the
  /// floor is within the tolerance (the region where order 2 holds); dt.size() − 1 (the finest step, no
  /// halving left) when even the last one is not.
  std::array<std::size_t, 8> onset{};
  /// The all-levels velocity measures: whether a level fell between the two runs' switches at some step
  /// (then they have no order, see time_family.cpp).
  bool velocity_jump_sampled = false;

  const std::array<double, 8>& judged_errors(std::size_t j, std::size_t measure) const;
};

/// Runs the study on N elements with `mass` (a massless contact node) for Crank–Nicolson with
/// `parameters` (its kernel etc.); throws std::runtime_error for a non-finite error.
TimeFamilyMesh time_family_mesh(long elements, const MassRedistribution& mass, const SchemeParameters& parameters,
                                const TimeFamilySettings& settings);

/// The meshes of the family: every N from `from` to `to` in steps of `by`, then the powers of two above
/// `to` up to `powers_to`.
std::vector<long> time_family_meshes(long from, long to, long by, long powers_to);

}  // namespace mrm::repro
