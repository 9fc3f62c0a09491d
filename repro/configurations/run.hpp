/// @file configurations/run.hpp
/// @brief What a run measures and the one function that runs a configuration (every program and check that needs the errors or the energy range of a run calls it).
#pragma once

#include "configurations/scaling.hpp"
#include "configurations/stress.hpp"

namespace mrm::repro {

/// What a run measures: the eight relative errors against the exact solution (mathematics.md §5; the
/// configuration's reference, see configuration_reference), the same over [0, T_k] for each horizon of
/// the configuration, the range of the discrete energy, the number of steps, and the phase
/// (mathematics.md §8): the impact times read off the contact indicator (phase.hpp; a contact that
/// starts less than L after the previous one ended continues it) and their errors against the exact
/// impacts: L + 3Lk with the unit 3L on the paper's benchmark, the characteristic solution's (by the
/// same chatter rule) with their mean interval as the unit for any other data.
struct Measures {
  ErrorNorms errors;
  std::vector<ErrorNorms> horizon_errors;  ///< one per Configuration::horizons, in order
  double energy_initial = 0, energy_final = 0, energy_min = 0, energy_max = 0;
  Index steps = 0;
  std::vector<double> impacts;
  std::optional<PhaseMeasures> phase;  ///< absent when the run or the exact solution has no impact
  /// The contact windows of the run (ImpactDetector::windows, same chatter rule as the impacts), in the
  /// configuration's time unit.
  std::vector<ContactInterval> contact_windows;
  /// The oscillation of the contact stress: TV(λ_h)/TV(λ_exact), the total variations of the scheme's
  /// multiplier and of the exact λ over the same instants (the samples' multiplier_time), levels 0..n.
  /// Absent when the exact λ does not vary over the run (no contact: the ratio is undefined).
  std::optional<double> lambda_tv_ratio;
  /// The stress lambda_tv_ratio is of (Configuration::stress).
  ContactStress stress = ContactStress::multiplier;
  /// The relative L²(0,T) error of that stress against the exact λ, trapezoidal over its instants
  /// (StressMeasures::l2_error): for the multiplier it is errors.lambda_L2 (the same sum over the same
  /// samples), for the other stresses their own, so that a run reports the error of the stress it
  /// reports. Absent when the exact λ does not vary over the run (as lambda_tv_ratio) or, for the
  /// multiplier, when the run measures no errors.
  std::optional<double> stress_l2_error;
  /// The histories of every stress (Configuration::keep_stress_history or a stress other than the
  /// multiplier).
  std::optional<StressHistory> stress_history;
  /// The largest penetration max_n max(0, −(u₀ⁿ + gap)) at the configuration's scale: 0 up to round-off
  /// for a scheme that enforces the constraint at the levels (CN, BE, EC, cn-switch); for
  /// Paoli–Schatzman only the average (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) is constrained, so a level may penetrate.
  double max_penetration = 0;
};

/// Runs the configuration to its final time, calling `observe` (if given) on every sample from level 0
/// on, and returns its measures. The run is the unit configuration's (unit_configuration); the samples
/// that `observe` sees and the measures (energies, impact times, phase) are scaled back to the
/// configuration's own scale by the scaling law (the relative errors do not change). The measures are: the errors against `reference` if given (not owned: it must outlive
/// the call; a closed form under test, or a reference shared by several runs), else against
/// configuration_reference up to reference_horizon. Throws std::runtime_error if the energy becomes
/// non-finite (a value that cannot be computed is an error, never a nan in a table),
/// std::invalid_argument for horizons that do not increase or exceed the final time.
///
/// Two bodies (is_two_body_configuration) run with mrm::TwoBodySimulation (Crank–Nicolson; any other
/// scheme throws InvalidParameter ("scheme")), N elements and the mass on each body; each body's eight
/// errors are measured in its own frame against the chain's exact solution (mrm::TwoBodyReference), and
/// each measure is the larger of the two bodies'; u(0,·) is each body's contact node, λ the contact
/// stress, the energy the pair's, the impacts, windows and penetration those of the gap between the
/// bodies. They take no `observe` and no `reference` (std::invalid_argument: a Sample is one body's).
Measures run_configuration(const Configuration& configuration, const std::function<void(const Sample&)>& observe = {},
                           const ReferenceSolution* reference = nullptr);

/// Where a run finds its reference: the unit configuration and the horizon in, the reference of that
/// unit configuration out (run_configuration's own: unit_configuration_reference; the sweep layer's
/// cache, repro/sweep.hpp, shares one among the runs of the same data, mesh, Δt and horizon).
using ReferenceSource =
    std::function<std::shared_ptr<const ReferenceSolution>(const Configuration& unit, double horizon)>;
/// The reference run_configuration measures a unit configuration (unit_configuration) against up to
/// `horizon`: the closed form for the paper's benchmark, a field benchmark's ImpactReference, otherwise the
/// characteristic solution of its data, tabulated on the lattice of h and Δt when one of them is a
/// whole multiple of the other.
std::shared_ptr<const ReferenceSolution> unit_configuration_reference(const Configuration& unit, double horizon);

/// run_configuration taken apart, for a driver that steps the simulation itself (the batched sweep of
/// repro/sweep.hpp): the constructor does run_configuration's set-up (the unit configuration, its
/// simulation, the reference, the accumulators), `add` takes the samples of levels 0 … steps() in order,
/// `measures` gives the result. run_configuration(c, observe, reference) is exactly
/// run(r.simulation(), r.steps(), add) then r.measures() on ConfigurationRun r(c, observe, reference).
class ConfigurationRun {
 public:
  /// `reference` as for run_configuration; without one, the unit configuration's reference comes from
  /// `source` (unit_configuration_reference if empty).
  explicit ConfigurationRun(const Configuration& configuration, std::function<void(const Sample&)> observe = {},
                            const ReferenceSolution* reference = nullptr, const ReferenceSource& source = {});
  /// The unit configuration's simulation at level 0 (a batched driver moves it out).
  BarSimulation& simulation() { return simulation_; }
  /// The number of steps of the run.
  Index steps() const { return measures_.steps; }
  /// The unit configuration that is run.
  const Configuration& unit() const { return unit_; }
  /// Adds the sample of the next level (levels 0 … steps(), in order). Throws std::runtime_error for a
  /// non-finite energy.
  void add(const Sample& sample);
  /// Whether `sample` may come with `lanes` (add(sample, lanes)): nothing but the error measures and the
  /// recovered strain reads more of its vectors than the displacement's first entry (no observer, no
  /// differenced velocity at that level), or the lanes are the sample's own vectors (a run of a batch
  /// stepped alone), which an observer may read.
  bool takes_lanes(const Sample& sample, const LaneVectors& lanes) const;
  /// Says that the observer reads none of a sample's vectors, only its level, instants, λ and energy
  /// (false), so that a batched driver may observe the run with its vectors in the lanes; the observer
  /// is then given samples whose displacement and velocity are null. Default: true.
  void set_observer_reads_vectors(bool reads) { observer_reads_vectors_ = reads; }
  /// The same as add(sample), the error measures and the recovered strain reading the displacement and
  /// velocity from `lanes` (the same bits); of the sample's own vectors only the displacement's first
  /// entry is read (and their size).
  void add(const Sample& sample, const LaneVectors& lanes);
  /// The accumulator of the error measures if `sample` may come with `lanes` and its errors are measured
  /// (a batched driver adds that level's errors of several runs in one pass, ErrorAccumulator::add_lanes,
  /// then calls add(sample, lanes, true)); null otherwise.
  ErrorAccumulator* lane_errors(const Sample& sample, const LaneVectors& lanes);
  /// add(sample, lanes), with this level's errors already added to lane_errors(sample, lanes) when
  /// `errors_added`.
  void add(const Sample& sample, const LaneVectors& lanes, bool errors_added);
  /// The measures of the levels added, at the configuration's scale.
  Measures measures();

 private:
  Scaling scaling_;
  Configuration unit_;
  UniformMesh mesh_;
  double dt_;
  std::vector<Index> horizon_levels_;
  Problem problem_;
  BarSimulation simulation_;
  ImpactDetector impacts_;
  std::size_t next_horizon_ = 0;
  double compliance_, gap_;
  Measures measures_;
  std::shared_ptr<const ReferenceSolution> exact_;
  std::optional<ErrorAccumulator> errors_;
  double energy_min_, energy_max_;
  bool difference_;
  Eigen::VectorXd velocity_, scaled_displacement_, scaled_velocity_;
  double u0_previous_ = 0;
  double tv_ = 0, tv_exact_ = 0, lambda_previous_ = 0, exact_previous_ = 0, penetration_ = 0;
  bool first_multiplier_ = true;
  // The contact stresses' histories (Configuration::stress, keep_stress_history).
  bool keep_ = false, keep_recovered_ = false;
  StressHistory history_;
  std::function<void(const Sample&)> observe_;
  bool observer_reads_vectors_ = true;
  void add_sample(const Sample& sample, const LaneVectors* lanes, bool errors_added = false);
};

/// One mesh of a convergence study: its number of elements and the eight errors of its run (in the
/// order of ErrorAccumulator::names).
struct ErrorRow {
  Index elements;
  std::array<double, 8> errors;
};
/// Writes the columns of a convergence block of a data file: the line "# columns: N h dt" followed by
/// the eight error names, then one line per mesh, N, h = L/N, Δt = C h and the errors (numbers as
/// cli::format_real writes them).
void write_error_rows(std::ostream& out, double length, double courant, const std::vector<ErrorRow>& rows);

/// Runs independent configurations on `threads` threads (0: one per hardware thread) and returns their
/// measures in the order given: the same numbers as one run_configuration each (every run is
/// deterministic and shares nothing). The first exception of a run, in the order given, is rethrown
/// after every thread has finished.
std::vector<Measures> run_configurations(const std::vector<Configuration>& configurations, unsigned threads = 0);

/// The phase of a run's impacts against its exact solution (phase.cpp): the closed form's impacts paired
/// by rank, the characteristic solution's or a field chain's as mutual nearest neighbours; none for any
/// other reference.
std::optional<PhaseMeasures> phase_against(const std::vector<double>& impacts, const ReferenceSolution& exact,
                                           double minimum_free_interval);
/// The phase of a run's impacts against exact contact intervals over [0, horizon]: the exact impacts by
/// the detector's chatter rule (`minimum_free_interval`), paired with the measured ones as mutual nearest
/// neighbours, with their mean interval as the unit; none unless the first exact impact has a partner.
std::optional<PhaseMeasures> phase_from_contacts(const std::vector<double>& impacts,
                                                 const std::vector<ContactInterval>& contacts, double horizon,
                                                 double minimum_free_interval);
/// The levels of the horizons T_k of a configuration (they must increase within (0, T]).
std::vector<Index> horizon_levels(const Configuration& c, double dt);
/// The measures of a run made at the unit scale brought to the configuration's scale (energies,
/// penetration, the phase's times, the impacts and the contact windows).
void to_configuration_scale(Measures& m, const Scaling& scaling, double energy_min, double energy_max,
                            double penetration, const ImpactDetector& impacts);

}  // namespace mrm::repro
