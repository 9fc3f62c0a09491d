/// @file phase.hpp
/// @brief Phase diagnostics of a run (mathematics.md §8): the impact times read off the contact
/// node's time series, their errors against the exact impact times, the error of the first impact
/// and the drift of the impact times per period.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "exact/characteristics.hpp"
#include "exact/exact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "fem/period_law.hpp"
#include "core/problem.hpp"

namespace mrm {

/// The signed contact indicator of one level: g = u₀ + hλ when the multiplier belongs to the same
/// instant as the displacement (every scheme with the algebraic contact row; then g = u₁ + hF₀
/// exactly), u₀ otherwise. g > 0: the gap is open; g ≤ 0: the contact is active.
double contact_indicator(const Sample& sample, double h);

/// Reads the impact times off a time series of the contact indicator, one level at a time, in O(1)
/// memory per level. An impact is a level n with gₙ ≤ 0 after a level with gₙ₋₁ > 0; its time is the
/// zero of the straight line through (tₙ₋₁, gₙ₋₁) and (tₙ, gₙ). A contact that starts less than
/// `minimum_free_interval` after the previous one ended (chatter) continues that contact instead.
class ImpactDetector {
 public:
  /// Throws std::invalid_argument for a negative or non-finite interval.
  explicit ImpactDetector(double minimum_free_interval = 0.0);
  /// Adds the level (t, g); the times must increase. Throws std::invalid_argument otherwise or for a
  /// non-finite value.
  void add(double time, double indicator);
  /// The impact times found so far, in increasing order.
  const std::vector<double>& impacts() const { return impacts_; }
  /// The contact windows found so far: [start, end] between the interpolated crossings of the
  /// indicator, one per impact (a chatter contact extends the window it continues), the first from t₀
  /// when the contact is active at the first level; the last one `open` (ending at the last level) if
  /// still active.
  const std::vector<ContactInterval>& windows() const { return windows_; }

 private:
  double minimum_free_interval_;
  bool started_ = false, in_contact_ = false, contact_seen_ = false;
  double time_ = 0, indicator_ = 0, release_ = 0;
  std::vector<double> impacts_;
  std::vector<ContactInterval> windows_;
};

/// The phase of a run against the exact solution. The k-th measured impact is compared with the
/// k-th exact one (k = 0 … min(counts) − 1); errors eₖ = t̂ₖ − tₖ, negative when the run hits early.
struct PhaseMeasures {
  std::size_t matched;        ///< the number of impacts compared
  double first_impact_error;  ///< e₀
  double period;              ///< P, the unit of the drift (3L on the benchmark; see mean_impact_interval)
  /// P times the least-squares slope of eₖ against tₖ: the time the impacts gain (> 0) or lose
  /// (< 0, early) per period P, in time units. Needs two impacts at least (std::nullopt otherwise).
  std::optional<double> drift_per_period;
};
/// Throws std::invalid_argument when no impact can be compared, for a non-positive period, or for
/// exact impact times that do not increase.
PhaseMeasures phase_measures(const std::vector<double>& impacts, const std::vector<double>& exact_impacts,
                             double period);

/// The first `count` impact times of the benchmark's exact solution: L + 3L k (mathematics.md §2).
std::vector<double> benchmark_impact_times(const ExactSolution& exact, std::size_t count);

/// The impact times of an exact solution with the given contact intervals (increasing, as
/// CharacteristicSolution::contact_intervals returns them), by the rule ImpactDetector applies to a
/// run: a contact held from t = 0 is not an impact; the first contact that begins later is; a later
/// one is when it begins at least `minimum_free_interval` after the previous contact ended. Throws
/// std::invalid_argument for a negative or non-finite interval or intervals that do not increase.
std::vector<double> impact_times(const std::vector<ContactInterval>& contacts, double minimum_free_interval);

/// Measured impacts paired with exact ones as mutual nearest neighbours: t̂ and t are a pair when t is
/// the exact impact nearest to t̂, t̂ the measured impact nearest to t, and |t̂ − t| is less than half
/// the smallest interval between consecutive exact impacts. A pair farther apart would compare two
/// unrelated events: a measured impact that far from t is nearer (or as near) to the exact impact
/// before or after t, so its error says nothing about t's phase. With a single exact impact there is
/// no such interval; the gate is then half the exact free flight before it, t − `free_flight_start`
/// (the release from a contact held from the start, or 0), for the same reason. Returns the pairs as
/// two sequences of equal length (measured, exact), in increasing order; impacts without a partner (a
/// run's extra contact, an exact impact the run misses or hits too far off) are left out.
std::pair<std::vector<double>, std::vector<double>> nearest_impact_pairs(const std::vector<double>& impacts,
                                                                         const std::vector<double>& exact_impacts,
                                                                         double free_flight_start = 0.0);

/// The phase of a run on the benchmark (exact impacts L + 3Lk, period 3L): the k-th measured impact is
/// paired with the k-th exact one (every resolved run has one impact per period, and its error grows
/// steadily with k by the period law, so the rank, not the nearest time, identifies the partner), up to
/// the first pair farther apart than half the period 3L/2: from there on the run is more than half a
/// period off and the k-th impacts are no longer the same event, so they are not compared (matched
/// counts the pairs kept). std::nullopt when even the first pair is that far apart.
std::optional<PhaseMeasures> benchmark_phase(const std::vector<double>& impacts, const ExactSolution& exact);

/// The mean time between consecutive impacts, (t_last − t_first)/(n − 1): the unit of the drift for
/// data whose motion has no period (3L for the benchmark's impacts). Throws std::invalid_argument for
/// fewer than two impacts.
double mean_impact_interval(const std::vector<double>& impacts);

/// The phase of the paper's benchmark measured on a mesh (graded or not): Crank–Nicolson with Δt =
/// courant·h₀ over `periods` periods, the impacts read off the contact indicator u₀ + (h₀/E₀)λ, their
/// errors against the exact 1 + 3k, the drift the least-squares slope per period (phase.hpp).
struct MeasuredPhase {
  double drift_per_period;    ///< time units per period, early = negative
  double first_impact_error;  ///< the first impact's error
};
/// Runs it; throws std::runtime_error when the run does not have one impact per period.
MeasuredPhase measure_benchmark_phase(const UniformMesh& mesh, const MassRedistribution& redistribution, double courant,
                                      double periods);

}  // namespace mrm
