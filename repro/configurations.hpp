/// @file configurations.hpp
/// @brief The paper's named configurations and the one function that runs a configuration and returns its
/// measures (every program and check that needs the errors or the energy range of a run calls it).
#pragma once

#include <array>
#include <functional>
#include <optional>

#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "labels.hpp"
#include "mass_spec.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"

#include "exact/characteristics.hpp"
#include "measures/contact_stress.hpp"
#include "measures/errors.hpp"
#include "exact/impact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "measures/phase.hpp"
#include "exact/reference_solution.hpp"
#include "time/schemes.hpp"

namespace mrm::repro {

/// The scheme's parameters; Paoli–Schatzman with β = ¼, e = 0 and the given contact row (a mass that
/// keeps the contact node's inertia always takes the literal row: it has no algebraic one). CN-switch's
/// θ keeps its default (1, backward Euler); a program that offers it sets SchemeParameters::switch_theta.
inline mrm::SchemeParameters scheme_parameters(mrm::Scheme scheme, const std::string& ps_form,
                                               const std::string& mass) {
  mrm::SchemeParameters p;
  p.scheme = scheme;
  if (p.scheme == mrm::Scheme::paoli_schatzman)
    p.contact_row = mass == "consistent" ? mrm::ContactRow::literal : mrm::contact_row_by_name(ps_form);
  return p;
}
/// The same, the scheme named by its id in the registry (mrm::scheme_by_name).
inline mrm::SchemeParameters scheme_parameters(const std::string& scheme, const std::string& ps_form,
                                               const std::string& mass) {
  return scheme_parameters(mrm::scheme_by_name(scheme), ps_form, mass);
}

/// The redistribution named by the value `spec` of the mass option `option`, checked on the mesh of the run
/// (mass_redistribution_from_spec, mass_spec.hpp); a bad value throws cli::UsageError "<option>: \"spec\": why
/// (allowed: ...)", so that the program exits with status 2 before any work. `massless` additionally refuses
/// the consistent mass (for a program that needs a massless contact node). `blend`: the interior mass
/// blend A the member is defined on (interior_blend_from_spec, mass_spec.hpp; 0 the paper's).
MassRedistribution mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                    bool massless = false, double blend = 0.0);

/// The velocity of a massless contact node in the velocity measures. `algebraic` (the default): the
/// library's own, defined from the algebraic contact row (mathematics.md §7; BarSimulation sets V₀ at
/// every level of a two-level scheme). `backward_difference`: (u₀ⁿ − u₀ⁿ⁻¹)/Δt at every level n ≥ 1,
/// as GetFEM's demo_dynamic_contact_1D.py does (mathematics.md §13), to compare with that code. A
/// contact node with inertia keeps the scheme's velocity either way.
enum class ContactVelocity { algebraic, backward_difference };
/// "algebraic" or "backward-difference"; throws std::invalid_argument otherwise.
ContactVelocity contact_velocity_by_name(const std::string& name);

/// One run: the bar (0, L) released from the initial data of a benchmark (the paper's u⁰(x) = a (L − x)
/// by default) or of a file, a scheme, a mass, a mesh of N elements and Δt (given, or C h), to the first
/// level t_n ≥ T (or for a given number of steps).
struct Configuration {
  SchemeParameters scheme;
  MassRedistribution mass = mod3();
  Index elements = 100;
  double courant = 0.5;  ///< Δt = C h, unless dt > 0
  double dt = 0.0;       ///< the time step if > 0
  double final_time = 3.0;
  Index steps = -1;  ///< the number of steps if ≥ 0 (final_time is then unused)
  double length = 1.0;
  double amplitude = 0.5;
  InitialContactNode initial = InitialContactNode::consistent;
  /// Horizons T_k (increasing, each ≤ final_time) at which the errors over [0, T_k] are also measured,
  /// from the same run: a prefix of the run is the run to T_k.
  std::vector<double> horizons;
  /// One of benchmark_names(); `length` and `amplitude` apply to "paper" only (the smooth benchmarks have
  /// L = 1). Ignored when `data` is set. A field benchmark (is_impact_benchmark: bouncing, impacting,
  /// gravity-paper, layered) runs its chain of lib/exact/impact_solution.hpp: its load, gap, material and far
  /// end, in its own units, with the exact ImpactSolution as the reference.
  std::string benchmark = "paper";
  /// The field benchmark's chain and data when they are not the registry's: set by unit_configuration
  /// to the dimensionless ones (empty: the registry's entry named `benchmark`).
  std::shared_ptr<const ImpactBenchmark> field;
  /// Initial data of one's own (bar1d --initial-data), L = their last x; the reference is then the
  /// characteristic solution.
  std::shared_ptr<const InitialData> data;
  /// The contact node's velocity in the velocity measures (the library's by default).
  ContactVelocity contact_velocity = ContactVelocity::algebraic;
  /// The mesh's grading ratio r: element sizes h_k = h₀ r^k, k = 0..N−1, finer toward the contact for
  /// r > 1 (graded_mesh, lib/fem/p1.hpp); 1, the uniform mesh, by default. Not on a field benchmark
  /// (configuration_mesh refuses it: their interfaces and Δt = C h/c are set on the uniform mesh).
  double grading = 1.0;
  /// The contact stress whose oscillation Measures::lambda_tv_ratio reports (lib/measures/contact_stress.hpp; the
  /// scheme's multiplier by default, as before issue 26's item 3).
  ContactStress stress = ContactStress::multiplier;
  /// Whether Measures::stress_history keeps the histories every stress is computed from (fig_stress).
  /// A stress other than the multiplier keeps the histories it needs (the multiplier and the exact λ,
  /// 24 bytes per step; the recovered strain 24 more): a run's memory then grows with its steps.
  bool keep_stress_history = false;
  /// Whether the run measures the eight errors (Measures::errors and horizon_errors; false: they stay
  /// 0, for a study of the stresses only, which then costs the steps alone).
  bool measure_errors = true;

  /// The length of the bar: L of the data, of a field benchmark's chain, of the smooth benchmarks (1), or
  /// `length`.
  double bar_length() const;
  /// Δt: dt if given, otherwise C h/c with c the wave speed at the contact end (1 but on a field
  /// benchmark: C is the Courant number of the contact element), h the contact element's size: L/N, h₀
  /// on a graded mesh, ℓ/N on two bodies (N elements on each body, ℓ the left body's length).
  double step() const;
};

/// The scaling law of the problem (configurations.cpp, mathematics.md §1): with x = Lξ, t = Lτ and
/// u = σL û, the problem on (0, L) is the one on (0, 1) with the data divided by σ, and
/// u_t = σ û_τ, λ = u_x(0, ·) = σ λ̂, E = σ²L Ê. The library runs the unit problem; the harness maps a
/// configuration to it and its outputs back. σ is a power of two (configuration_scaling), so that the
/// mapping is exact in floating point whenever L is one too.
///
/// A field benchmark (lib/exact/impact_solution.hpp) has its own units: a wave speed c and a modulus E at the
/// contact end (E = ρc²). With t = (L/c)τ, u = σL û, E = E_c Ê, ρ = ρ_c ρ̂ the equation
/// ρu_tt − (E u_x)_x = f becomes (E_c σ/L)(ρ̂û_ττ − (Êû_ξ)_ξ) = f, so the unit problem has the load
/// f̂ = f L/(E_c σ), the gaps ĝ = g/(σL), the material Ê, ρ̂ (1 at the contact end), and u_t = σc û_τ,
/// u_x = σ û_ξ, the stress E u_x = E_c σ σ̂ (λ), the energy E_c σ²L Ê. c = E_c = 1 is the law above.
struct Scaling {
  double length = 1.0;                                            ///< L
  double amplitude = 1.0;                                         ///< σ, a power of two
  double wave_speed = 1.0;                                        ///< c, the wave speed at the contact end
  double modulus = 1.0;                                           ///< E_c, the modulus at the contact end
  double time_scale() const { return length / wave_speed; }       ///< L/c
  double time(double unit) const { return time_scale() * unit; }  ///< t = (L/c)τ
  double displacement(double unit) const { return (amplitude * length) * unit; }  ///< u = σL û
  double velocity(double unit) const { return (amplitude * wave_speed) * unit; }  ///< u_t = σc û_τ
  double strain(double unit) const { return amplitude * unit; }                   ///< u_x = σ û_ξ
  double stress(double unit) const { return (modulus * amplitude) * unit; }       ///< E u_x = E_c σ σ̂, also λ
  double energy(double unit) const { return modulus * ((amplitude * amplitude * length) * unit); }  ///< E_c σ²L Ê
  /// Nothing to scale.
  bool identity() const { return length == 1.0 && amplitude == 1.0 && wave_speed == 1.0 && modulus == 1.0; }
};
/// The scaling of a configuration: L its bar's length, σ = 2^e for the amplitude a = m 2^e, m ∈ [½, 1),
/// of its data (the paper's a; for other data the largest of |u⁰|/L and |v⁰| at the breakpoints;
/// σ = 1 for data at rest). The paper's benchmark with L = 1, a = ½ has σ = 1: nothing to scale.
Scaling configuration_scaling(const Configuration& configuration);
/// The configuration on the unit bar that run_configuration runs: its data divided by `scaling`
/// (the paper's benchmark with amplitude a/σ, other data as unit InitialData), Δt, T and the horizons
/// divided by L.
Configuration unit_configuration(const Configuration& configuration, const Scaling& scaling);

/// The problem of a configuration: its initial data, f = 0 (a field benchmark: its load and gap). Throws
/// std::invalid_argument for an unknown benchmark name, InvalidParameter ("benchmark") for two-bars (two
/// bodies have no one-body problem: run_configuration runs them).
Problem configuration_problem(const Configuration& configuration);

/// The field benchmark of a configuration (its `field`, or the registry's entry named `benchmark`), or
/// null for the paper's, the smooth ones and data of one's own.
const ImpactBenchmark* configuration_field(const Configuration& configuration);

/// The mesh of a configuration: N uniform elements on (0, L) (graded by Configuration::grading), and on
/// a field benchmark its material per element and its far end. Throws InvalidParameter ("elements") when
/// an interface between two materials is not a node (the allowed N named), InvalidParameter
/// ("grading") for a grading on a field benchmark. On two bodies (two-bars: is_two_body_chain), the
/// mesh of body k (0 the left one) in its own frame (lib/time/two_bodies.hpp: ξ from its contact end): N
/// elements on its length, its material, its far end; both bodies have N elements.
UniformMesh configuration_mesh(const Configuration& configuration, int body = 0);
/// Whether the configuration is a field benchmark of two bodies in contact (two-bars), which
/// run_configuration runs with lib/time/two_bodies.hpp (Crank–Nicolson only).
bool is_two_body_configuration(const Configuration& configuration);

/// two-bars by symmetry (repro/configurations.cpp, derived there): the one-bar problem each of the two
/// identical bodies solves, a free bar (L = 10, velocity −0.1) against a rigid wall at g₀/2.
std::shared_ptr<const ImpactBenchmark> two_bars_by_symmetry();
/// Makes a two-bars configuration run as two_bars_by_symmetry's one-bar problem, with every class of the
/// registry (the two-body run takes cn with a massless contact node only): its field, and γ₀' = 2γ₀ for
/// penalty and Nitsche.
void reduce_two_bars_by_symmetry(Configuration& configuration);

/// The initial data of a configuration as piecewise polynomials (the paper's, a smooth benchmark's or
/// the file's).
InitialData configuration_data(const Configuration& configuration);

/// The exact solution a configuration's errors are measured against: the closed form for "paper"
/// (mathematics.md §2), otherwise the characteristic solution of its data (mathematics.md §10) up to
/// `horizon`, tabulated on the lattice of h and Δt when one of them is a whole multiple of the other.
/// At the configuration's own scale (the characteristic solution is computed for the unit
/// configuration and scaled back).
std::shared_ptr<const ReferenceSolution> configuration_reference(const Configuration& configuration, double horizon);

/// Whether `benchmark` is one of the field's benchmarks of lib/exact/impact_solution.hpp (impact_benchmarks():
/// bouncing, impacting, gravity-paper, two-bars, layered), whose finite element runs need what the
/// schemes do not have yet (a load, a free far end, a gap, layers, two bodies).
bool is_impact_benchmark(const std::string& benchmark);

/// The exact solution's contact windows over [0, T] of a configuration's contact point, in the
/// configuration's own units: for a field benchmark (is_impact_benchmark) its chain and data, for the
/// others (paper, smooth ones, data of one's own) the clamped homogeneous bar of unit wave speed with
/// configuration_data. Computed by mrm::ImpactSolution (lib/exact/impact_solution.cpp), in the data's units
/// (SI for impacting: the exact solution needs no scaling). Throws mrm::InvalidParameter ("final_time")
/// when the horizon needs more wave fronts than the solver keeps.
std::vector<ContactInterval> configuration_contact_windows(const Configuration& configuration, double final_time);

/// A configuration named as the paper names it: a scheme of the registry (mrm::scheme_registry; Paoli–
/// Schatzman is (¼, 0) with the contact row `ps_form`), a mass spec of mass_redistribution_from_spec in
/// mass_spec.hpp ("mod1", "mod2", "mod3", "consistent", "node1:7/6", ...), N, Δt = C h, T.
Configuration paper_configuration(Scheme scheme, const std::string& ps_form, const std::string& mass, Index elements,
                                  double courant, double final_time);
/// The same, the scheme named by its id in the registry (mrm::scheme_by_name).
Configuration paper_configuration(const std::string& scheme, const std::string& ps_form, const std::string& mass,
                                  Index elements, double courant, double final_time);

/// One run of a study over benchmarks and variants (fig_stress, fig_phase_matched; fig_classes may use
/// it too): `scheme` with its registry defaults, the contact mass `mass`, N elements, Δt = C h (c the
/// wave speed at the contact end on a field benchmark), to T on `benchmark` (one of benchmark_names()).
/// Every other field keeps Configuration's default.
Configuration study_configuration(const std::string& benchmark, Scheme scheme, const MassRedistribution& mass,
                                  Index elements, double courant, double final_time);
/// The work of a run, elements × steps (the cost a study's costliest_first schedules by); throws
/// std::invalid_argument where Configuration::step() or mrm::steps_to_reach does.
double run_cost(const Configuration& c);

/// The histories of one run that every contact stress of lib/measures/contact_stress.hpp is computed from, at the
/// unit scale of the run (unit_configuration: a ratio or a relative error does not depend on it): the
/// multiplier λ_h at its instants, the recovered strain at the levels (k = recovered_elements(W(t), h)),
/// the exact λ at the multiplier's instants, h, the spacing Δt, the smearing order of the run's interior
/// step (interior_phase_order of the scheme, Δt/h and the blend: each scheme's own symbol, derived in
/// contact_stress.cpp §1b).
struct StressHistory {
  std::vector<double> time, multiplier, recovered_time, recovered, exact, exact_at_levels;
  double h = 0, spacing = 0;
  PhaseOrder order{2, 1.0 / 48};
  /// The stress's values: the multiplier, its box or spline window average of width 8 W(h, t), or the
  /// recovered strain projected onto λ ≤ 0 (contact_stress.cpp §2–§4).
  std::vector<double> values(ContactStress stress) const;
  /// The instants of values(stress) and the exact λ there.
  const std::vector<double>& instants(ContactStress stress) const;
  const std::vector<double>& exact_values(ContactStress stress) const;
};
/// What fig_stress and bar1d report of a stress: TV(stress)/TV(λ_exact) over the same instants, the
/// relative L²(0,T) error (trapezoidal, as ErrorAccumulator's λ error), and the largest error away from
/// the exact status changes, relative to max|λ_exact|: over the instants at a distance of at least
/// ε = ¼ of the shortest exact contact window from every start and end of one (a distance fixed in the
/// problem's units, so that it measures pointwise convergence; 0 when no instant qualifies). The exact
/// contact windows are read off the exact λ at the instants: the maximal runs where λ < 0.
struct StressMeasures {
  double tv_ratio = 0, l2_error = 0, max_error_away = 0;
};
StressMeasures stress_measures(const StressHistory& history, ContactStress stress);

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
/// `horizon`: the closed form for "paper", a field benchmark's ImpactReference, otherwise the
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

/// The instant up to which a reference must be known for a run of `steps` steps of size dt: the last
/// level plus one step (the schemes' staggered instants stay below it).
inline double reference_horizon(Index steps, double dt) { return static_cast<double>(steps + 1) * dt; }
/// A UsageError naming `option` unless the reference of a configuration (the characteristic solution
/// of data other than the paper's, up to `horizon`) fits in the memory the process may use
/// (cli::require_memory). Its memory grows with the coefficients of the data's pieces and the
/// periods of the horizon; measured on bar1d (peak resident size, 1e5 linear samples at T = 6 and 60,
/// S1 at T = 100 and 1000): below 400 + 128 T/L bytes per coefficient. The paper's closed form needs none.
void require_reference_memory(const Configuration& configuration, double horizon, std::string_view option);

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

}  // namespace mrm::repro
