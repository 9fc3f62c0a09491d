/// @file configurations/run.cpp
/// @brief One run's measures: the errors, energy range, phase and stresses of a configuration, and many of them in parallel.
#include "configurations/run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "parallel.hpp"
#include "time/two_bodies.hpp"
#include "configurations.hpp"

namespace mrm::repro {

// The phase against the run's exact solution (phase.cpp), never pairing impacts farther apart than half
// the exact inter-impact time, and no phase unless the first exact impact has a partner: the closed
// form's impacts L + 3Lk paired by rank while less than 3L/2 apart, with the period 3L as the unit
// (benchmark_phase); the characteristic solution's (the starts of its contact intervals, by the
// detector's chatter rule) paired as mutual nearest neighbours, with their mean interval as the unit.
// Any other reference (a closed form under test) gives no phase.
std::optional<PhaseMeasures> phase_against(const std::vector<double>& impacts, const ReferenceSolution& exact,
                                           double minimum_free_interval) {
  if (const auto* closed_form = dynamic_cast<const ExactSolution*>(&exact))
    return benchmark_phase(impacts, *closed_form);
  const CharacteristicSolution* characteristic = dynamic_cast<const CharacteristicSolution*>(&exact);
  if (const auto* tabulated = dynamic_cast<const TabulatedSolution*>(&exact)) characteristic = &tabulated->solution();
  const auto* chain = dynamic_cast<const ImpactReference*>(&exact);
  if (!characteristic && !chain) return std::nullopt;
  return phase_from_contacts(impacts, characteristic ? characteristic->contact_intervals() : chain->contact_windows(),
                             characteristic ? characteristic->horizon() : chain->solution().horizon(),
                             minimum_free_interval);
}

// The phase against exact contact intervals over [0, horizon] (the rule above).
std::optional<PhaseMeasures> phase_from_contacts(const std::vector<double>& impacts,
                                                 const std::vector<ContactInterval>& contacts, double horizon,
                                                 double minimum_free_interval) {
  const std::vector<double> exact_impacts = impact_times(contacts, minimum_free_interval);
  // The free flight before a lone exact impact starts at the release from a contact held from t = 0.
  double free_flight_start = 0;
  for (const ContactInterval& contact : contacts)
    if (!exact_impacts.empty() && contact.end <= exact_impacts.front()) free_flight_start = contact.end;
  const auto [measured, exact_paired] = nearest_impact_pairs(impacts, exact_impacts, free_flight_start);
  if (exact_paired.empty() || exact_paired.front() != exact_impacts.front()) return std::nullopt;
  const double unit = exact_impacts.size() >= 2 ? mean_impact_interval(exact_impacts) : horizon;
  return phase_measures(measured, exact_paired, unit);
}

// The levels of the horizons T_k: they must increase within (0, T] (checked before the run is set up).
std::vector<Index> horizon_levels(const Configuration& c, double dt) {
  std::vector<Index> levels;
  for (std::size_t k = 0; k < c.horizons.size(); ++k) {
    if (!(c.horizons[k] > 0 && c.horizons[k] <= c.final_time && (k == 0 || c.horizons[k] > c.horizons[k - 1])))
      throw std::invalid_argument("run_configuration: the horizons must increase within (0, T]");
  }
  for (double t : c.horizons) levels.push_back(steps_to_reach(t, dt));
  return levels;
}

// The measures of a run made at the unit scale, brought to the configuration's scale (Scaling): the
// energies (initial, final, least, largest), the largest penetration, the phase's times, the impacts and
// the contact windows. The errors are relative and the TV ratio a ratio of two stresses: both are
// scale-free. Shared by the one-body run (ConfigurationRun::measures) and the two bodies' run.
void to_configuration_scale(Measures& m, const Scaling& scaling, double energy_min, double energy_max,
                            double penetration, const ImpactDetector& impacts) {
  m.energy_initial = scaling.energy(m.energy_initial);
  m.energy_final = scaling.energy(m.energy_final);
  m.energy_min = scaling.energy(energy_min);
  m.energy_max = scaling.energy(energy_max);
  m.max_penetration = scaling.displacement(1.0) * penetration;
  if (m.phase) {
    m.phase->first_impact_error = scaling.time(m.phase->first_impact_error);
    m.phase->period = scaling.time(m.phase->period);
    if (m.phase->drift_per_period) m.phase->drift_per_period = scaling.time(*m.phase->drift_per_period);
  }
  for (const double t : impacts.impacts()) m.impacts.push_back(scaling.time(t));
  for (ContactInterval w : impacts.windows()) {
    w.start = scaling.time(w.start);
    w.end = scaling.time(w.end);
    m.contact_windows.push_back(w);
  }
}

std::shared_ptr<const ReferenceSolution> unit_configuration_reference(const Configuration& unit, double horizon) {
  return unit_reference(unit, horizon);
}

// The horizons are levels of the same run: the errors over [0, T_k] are the accumulator's relative
// errors right after the level steps_to_reach(T_k, Δt) was added (the L∞ maxima and the L² integrals
// of a prefix). The impacts come from the contact indicator of every level (phase.cpp), with the
// chatter filter set to L, half the exact free flight 2L between two contacts; their errors against
// the exact impacts are measured by phase_against. With
// ContactVelocity::backward_difference the errors see a copy of the velocity whose contact entry is
// (u₀ⁿ − u₀ⁿ⁻¹)/Δt from level 1 on; the impacts and the energy are the scheme's either way.

namespace {
// The unit run's simulation: from the mass the configuration assembled once on the unit run's mesh
// (Configuration::assembled_mass, kept by unit_configuration), otherwise from the redistribution,
// assembled here.
BarSimulation unit_simulation(const Problem& problem, const UniformMesh& mesh, const Configuration& unit, double dt) {
  const AssembledMass* shared = unit.assembled_mass.get();
  if (shared && shared->redistribution.name == unit.mass.name &&
      shared->redistribution.interior_blend == unit.mass.interior_blend && shared->matrix.size() == mesh.unknowns())
    return BarSimulation(problem, mesh, *shared, unit.scheme, dt, unit.initial);
  return BarSimulation(problem, mesh, unit.mass, unit.scheme, dt, unit.initial);
}
}  // namespace

ConfigurationRun::ConfigurationRun(const Configuration& configuration, std::function<void(const Sample&)> observe,
                                   const ReferenceSolution* reference, const ReferenceSource& source)
    : scaling_(configuration_scaling(configuration)),
      unit_(unit_configuration(configuration, scaling_)),
      mesh_(configuration_mesh(unit_)),
      dt_(unit_.step()),
      horizon_levels_(horizon_levels(unit_, dt_)),
      problem_(configuration_problem(unit_)),
      simulation_(unit_simulation(problem_, mesh_, unit_, dt_)),
      impacts_(mesh_.length),
      // The contact indicator's compliance h₀/E₀ (h on the paper's mesh, the same double) and the gap.
      compliance_(mesh_.contact_compliance()),
      gap_(problem_.gap),
      energy_min_(std::numeric_limits<double>::infinity()),
      energy_max_(-energy_min_),
      // The backward difference replaces the contact node's entry of a copy of the velocity (level ≥ 1).
      difference_(unit_.contact_velocity == ContactVelocity::backward_difference &&
                  simulation_.massless_contact_node()),
      observe_(std::move(observe)) {
  if (is_two_body_configuration(configuration))
    throw std::invalid_argument("ConfigurationRun: two bodies run through run_configuration (run_two_bodies)");
  measures_.steps = unit_.steps >= 0 ? unit_.steps : steps_to_reach(unit_.final_time, dt_);
  // The histories of the contact stresses (unit scale), kept when asked or when a stress other than
  // the multiplier is reported.
  keep_ = unit_.keep_stress_history || unit_.stress != ContactStress::multiplier;
  keep_recovered_ = unit_.keep_stress_history || unit_.stress == ContactStress::recovered;
  if (keep_) {
    history_.h = mesh_.h(0);  // the contact element (the recovered fit assumes uniform elements near x = 0)
    history_.spacing = dt_;
    history_.order = interior_phase_order(unit_.scheme, dt_ / history_.h, unit_.mass.interior_blend);
    // One sample per level (or per step): room for all of them at once.
    const std::size_t samples = static_cast<std::size_t>(std::max<long>(0, measures_.steps)) + 2;
    history_.time.reserve(samples), history_.multiplier.reserve(samples), history_.exact.reserve(samples);
  }
  // A given reference is the caller's, at the configuration's scale (not owned: an aliasing pointer
  // with no owner), brought to the unit scale; otherwise the unit configuration's own, kept for the run.
  const double horizon = reference_horizon(measures_.steps, dt_);
  exact_ = reference ? to_unit(std::shared_ptr<const ReferenceSolution>(std::shared_ptr<void>(), reference), scaling_)
           : source  ? source(unit_, horizon)
                     : unit_reference(unit_, horizon);
  errors_.emplace(mesh_, exact_);
}

void ConfigurationRun::add(const Sample& s) { add_sample(s, nullptr); }

bool ConfigurationRun::takes_lanes(const Sample& s, const LaneVectors& lanes) const {
  const bool own_vectors =
      lanes.stride == 1 && lanes.displacement == s.displacement->data() && lanes.velocity == s.velocity->data();
  return (!observe_ || !observer_reads_vectors_ || own_vectors) &&
         !(unit_.measure_errors && difference_ && s.level >= 1);
}

void ConfigurationRun::add(const Sample& s, const LaneVectors& lanes) { add(s, lanes, false); }

ErrorAccumulator* ConfigurationRun::lane_errors(const Sample& s, const LaneVectors& lanes) {
  return takes_lanes(s, lanes) && unit_.measure_errors ? &*errors_ : nullptr;
}

void ConfigurationRun::add(const Sample& s, const LaneVectors& lanes, bool errors_added) {
  if (!takes_lanes(s, lanes)) throw std::logic_error("ConfigurationRun: this level needs the sample's vectors");
  if (errors_added && !unit_.measure_errors) throw std::logic_error("ConfigurationRun: this run measures no errors");
  add_sample(s, &lanes, errors_added);
}

void ConfigurationRun::add_sample(const Sample& s, const LaneVectors* lanes, bool errors_added) {
  Measures& m = measures_;
  // TV(λ_h) and TV(λ_exact) summed over the successive multiplier samples; the penetration against the
  // problem's gap (unit scale).
  penetration_ = std::max(penetration_, -((*s.displacement)[0] + gap_));
  if (s.has_multiplier) {
    const double lambda_exact = exact_->contact_multiplier(s.multiplier_time);
    if (!first_multiplier_)
      tv_ += std::abs(s.multiplier - lambda_previous_), tv_exact_ += std::abs(lambda_exact - exact_previous_);
    lambda_previous_ = s.multiplier, exact_previous_ = lambda_exact, first_multiplier_ = false;
    if (keep_) {
      history_.time.push_back(s.multiplier_time);
      history_.multiplier.push_back(s.multiplier);
      history_.exact.push_back(lambda_exact);
    }
  }
  if (keep_recovered_) {
    // The recovered strain through the first k(t) elements (the displacement has N nodes, 0..N−1).
    const Index k = std::min<Index>(recovered_elements(smearing_width(history_.h, s.time, history_.order), history_.h),
                                    static_cast<Index>(s.displacement->size()) - 1);
    history_.recovered_time.push_back(s.time);
    // From the lanes of a batch the sample's own displacement is current at entry 0 only: read it there.
    const double strain = lanes ? recovered_strain(lanes->displacement, lanes->stride, k, history_.h)
                                : recovered_strain(s.displacement->data(), k, history_.h);
    history_.recovered.push_back(std::min(0.0, strain));
    history_.exact_at_levels.push_back(exact_->contact_multiplier(s.time));
  }
  if (!unit_.measure_errors) {
    // the stresses only: no error measures
  } else if (difference_ && s.level >= 1) {
    velocity_ = *s.velocity;
    velocity_[0] = ((*s.displacement)[0] - u0_previous_) / dt_;
    Sample differenced = s;
    differenced.velocity = &velocity_;
    errors_->add(differenced);
  } else if (lanes) {
    if (!errors_added) errors_->add(s, *lanes);
  } else {
    errors_->add(s);
  }
  u0_previous_ = (*s.displacement)[0];
  impacts_.add(s.time, contact_indicator(s, compliance_) + gap_);
  while (next_horizon_ < horizon_levels_.size() && s.level == horizon_levels_[next_horizon_]) {
    m.horizon_errors.push_back(unit_.measure_errors ? errors_->relative() : ErrorNorms{});
    ++next_horizon_;
  }
  if (s.level == 0) m.energy_initial = s.energy;
  m.energy_final = s.energy;
  energy_min_ = std::min(energy_min_, s.energy);
  energy_max_ = std::max(energy_max_, s.energy);
  if (!std::isfinite(s.energy)) throw std::runtime_error("the run produced a non-finite energy");
  if (!observe_) return;
  if (!observer_reads_vectors_) {  // its scalars only, at the configuration's scale
    Sample scalars = s;
    scalars.displacement = scalars.velocity = nullptr;
    if (!scaling_.identity()) {
      scalars.time = scaling_.time(s.time);
      scalars.velocity_time = scaling_.time(s.velocity_time);
      scalars.multiplier_time = scaling_.time(s.multiplier_time);
      scalars.multiplier = scaling_.stress(s.multiplier);
      scalars.energy_time = scaling_.time(s.energy_time);
      scalars.energy = scaling_.energy(s.energy);
    }
    return observe_(scalars);
  }
  if (scaling_.identity()) return observe_(s);
  // The sample at the configuration's scale.
  scaled_displacement_ = scaling_.displacement(1.0) * *s.displacement;
  scaled_velocity_ = scaling_.velocity(1.0) * *s.velocity;
  Sample scaled = s;
  scaled.time = scaling_.time(s.time);
  scaled.displacement = &scaled_displacement_;
  scaled.velocity_time = scaling_.time(s.velocity_time);
  scaled.velocity = &scaled_velocity_;
  scaled.multiplier_time = scaling_.time(s.multiplier_time);
  scaled.multiplier = scaling_.stress(s.multiplier);
  scaled.energy_time = scaling_.time(s.energy_time);
  scaled.energy = scaling_.energy(s.energy);
  observe_(scaled);
}

Measures ConfigurationRun::measures() {
  Measures m = measures_;
  m.errors = unit_.measure_errors ? errors_->relative() : ErrorNorms{};
  if (tv_exact_ > 0) m.lambda_tv_ratio = tv_ / tv_exact_;  // a ratio of two stresses: scale-free
  m.stress = unit_.stress;
  if (unit_.stress == ContactStress::multiplier && unit_.measure_errors && tv_exact_ > 0)
    m.stress_l2_error = m.errors.lambda_L2;
  if (keep_) {
    if (unit_.stress != ContactStress::multiplier) {
      if (tv_exact_ > 0) {
        const StressMeasures own = stress_measures(history_, unit_.stress);
        m.lambda_tv_ratio = own.tv_ratio;
        m.stress_l2_error = own.l2_error;
      } else {
        m.lambda_tv_ratio.reset();
      }
    }
    m.stress_history = std::move(history_);
  }
  if (!impacts_.impacts().empty()) m.phase = phase_against(impacts_.impacts(), *exact_, mesh_.length);
  to_configuration_scale(m, scaling_, energy_min_, energy_max_, penetration_, impacts_);
  return m;
}

Measures run_configuration(const Configuration& configuration, const std::function<void(const Sample&)>& observe,
                           const ReferenceSolution* reference) {
  if (is_two_body_configuration(configuration)) {
    if (observe || reference)
      throw std::invalid_argument(
          "run_configuration: two bodies take no observer and no reference (a Sample is one "
          "body's)");
    return run_two_bodies(configuration);
  }
  ConfigurationRun r(configuration, observe, reference);
  run(r.simulation(), r.steps(), [&](const Sample& s) { r.add(s); });
  return r.measures();
}
void write_error_rows(std::ostream& out, double length, double courant, const std::vector<ErrorRow>& rows) {
  out << "# columns: N h dt";
  for (const char* name : ErrorAccumulator::names) out << ' ' << name;
  out << '\n';
  for (const ErrorRow& r : rows) {
    const double h = length / static_cast<double>(r.elements);
    out << r.elements << ' ' << cli::format_real(h) << ' ' << cli::format_real(courant * h);
    for (double e : r.errors) out << ' ' << cli::format_real(e);
    out << '\n';
  }
}

// The configurations on the shared worker pool (parallel.hpp), in the order given; each result goes to
// its own slot, so the order of completion does not matter.
std::vector<Measures> run_configurations(const std::vector<Configuration>& configurations, unsigned threads) {
  std::vector<Measures> results(configurations.size());
  std::vector<std::size_t> order(configurations.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  run_in_parallel(order, static_cast<long>(threads),
                  [&](std::size_t k) { results[k] = run_configuration(configurations[k]); });
  return results;
}

TEST_CASE("a configuration's measures are those of the same run observed by hand") {
  // The prediction: run_configuration is the library's run with an ErrorAccumulator, so its measures
  // equal, bit for bit, those of the same simulation stepped here; its energy range contains every
  // sample's energy, and the observer sees the levels 0..steps.
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 20, 0.5, 3.0);
  Index observed = 0;
  double lowest = 1e300, highest = -1e300;
  const Measures m = run_configuration(c, [&](const Sample& s) {
    CHECK(s.level == observed);
    ++observed;
    lowest = std::min(lowest, s.energy);
    highest = std::max(highest, s.energy);
  });
  const UniformMesh mesh(1.0, 20);
  BarSimulation simulation(benchmark_problem(), mesh, mod3(), c.scheme, 0.5 * mesh.h());
  ErrorAccumulator errors(mesh, ExactSolution());
  run(simulation, steps_to_reach(3.0, 0.5 * mesh.h()), [&](const Sample& s) { errors.add(s); });
  const auto expected = ErrorAccumulator::values(errors.relative());
  const auto got = ErrorAccumulator::values(m.errors);
  for (std::size_t k = 0; k < got.size(); ++k) {
    CAPTURE(ErrorAccumulator::names[k]);
    CHECK(got[k] == expected[k]);
  }
  CHECK(observed == m.steps + 1);
  CHECK(m.steps == 120);
  CHECK(m.energy_min == lowest);
  CHECK(m.energy_max == highest);
}

TEST_CASE("the errors at a horizon are those of the run stopped there, and threads change nothing") {
  // The prediction: a prefix of a run is the shorter run (same levels, same accumulator), so the
  // errors at the horizon T = 3 of a run to T = 9 equal, bit for bit, those of the run to T = 3; the
  // parallel runner returns the sequential measures in the order given.
  Configuration longer = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod2", 16, 0.5, 9.0);
  longer.horizons = {3.0, 6.0};
  Configuration shorter = longer;
  shorter.final_time = 3.0;
  shorter.horizons.clear();
  const Measures a = run_configuration(longer), b = run_configuration(shorter);
  REQUIRE(a.horizon_errors.size() == 2);
  const auto at_horizon = ErrorAccumulator::values(a.horizon_errors[0]), whole = ErrorAccumulator::values(b.errors);
  for (std::size_t k = 0; k < 8; ++k) CHECK(at_horizon[k] == whole[k]);
  const std::vector<Measures> parallel = run_configurations({shorter, longer, shorter}, 2);
  REQUIRE(parallel.size() == 3);
  const auto p0 = ErrorAccumulator::values(parallel[0].errors), p1 = ErrorAccumulator::values(parallel[1].errors);
  const auto s1 = ErrorAccumulator::values(a.errors);
  for (std::size_t k = 0; k < 8; ++k) {
    CHECK(p0[k] == whole[k]);
    CHECK(p1[k] == s1[k]);
  }
  // Three impacts in [0, 9] (at about 1, 4, 7), a drift measured, the first error about −h/3 (Mod 2).
  CHECK(a.impacts.size() == 3);
  REQUIRE(a.phase.has_value());
  CHECK(a.phase->drift_per_period.has_value());
  CHECK(std::abs(a.phase->first_impact_error + (1.0 / 16) / 3) < 0.05 / 16);
  longer.horizons = {6.0, 3.0};
  CHECK_THROWS_AS(run_configuration(longer), std::invalid_argument);
  longer.horizons = {12.0};
  CHECK_THROWS_AS(run_configurations({shorter, longer}, 2), std::invalid_argument);
}

TEST_CASE(
    "the phase of the benchmark's data given as data is the closed form's, and S1's extra contacts stay unpaired") {
  // Two references, one phase: for the benchmark's data the characteristic solution's impacts are
  // L + 3Lk to round-off (phase.cpp) and over 5 periods no run drifts by half a period (−4h/3 per period
  // at most, 0.22 on N = 30), so nearest pairing pairs what in-order pairing pairs; the errors and
  // drifts agree to the rounding of the two data paths (1e-9, far above it).
  for (const std::string mass : {"mod1", "mod2", "mod3"}) {
    Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", mass, 30, 0.37, 15.0);
    const Measures paper = run_configuration(c);
    c.data = std::make_shared<const InitialData>(benchmark_initial_data(1.0, 0.5));
    const Measures own = run_configuration(c);
    CAPTURE(mass);
    REQUIRE(paper.phase.has_value());
    REQUIRE(own.phase.has_value());
    CHECK(paper.phase->matched == 5);
    CHECK(own.phase->matched == paper.phase->matched);
    CHECK(std::abs(own.phase->first_impact_error - paper.phase->first_impact_error) <= 1e-9);
    CHECK(std::abs(own.phase->period - 3.0) <= 1e-9);
    REQUIRE(own.phase->drift_per_period.has_value());
    CHECK(std::abs(*own.phase->drift_per_period - *paper.phase->drift_per_period) <= 1e-9);
  }
  // S1 over 20 time units (N = 200, Crank–Nicolson, Mod 3): the exact impacts, by the chatter rule with
  // the interval L = 1, are at ½ + 6k (four of them, mean interval 6); the run floats off and lands again
  // in between (phase.cpp). Every exact impact must find its partner, the run's own contacts must stay
  // unpaired, and the first impact is on time to 0.05h as the period law predicts for Mod 3 (phase.cpp).
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 200, 0.5, 20.0);
  c.benchmark = "smooth-impact";
  const Measures s1 = run_configuration(c);
  REQUIRE(s1.phase.has_value());
  CHECK(s1.phase->matched == 4);
  CHECK(std::abs(s1.phase->period - 6.0) <= 1e-9);
  CHECK(s1.impacts.size() > s1.phase->matched);
  CHECK(std::abs(s1.phase->first_impact_error) <= 0.05 / 200);
}

TEST_CASE("every benchmark runs with its reference, and the smooth ones converge") {
  // The prediction (mathematics.md §11): on the smooth benchmarks Crank–Nicolson with Mod 3 converges at
  // order 2 in u(0,·); doubling N must divide its error by more than 3 (order > 1.58) on both.
  for (const std::string& benchmark : {std::string("smooth-impact"), std::string("grazing")}) {
    double previous = 0;
    for (const Index elements : {40, 80}) {
      Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", elements, 0.5, 2.0);
      c.benchmark = benchmark;
      const Measures m = run_configuration(c);
      CAPTURE(benchmark);
      CAPTURE(elements);
      for (double e : ErrorAccumulator::values(m.errors)) CHECK((std::isfinite(e) && e > 0 && e < 1));
      if (previous > 0) CHECK(m.errors.u0_L2 < previous / 3);
      previous = m.errors.u0_L2;
    }
  }
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 10, 0.5, 1.0);
  c.benchmark = "nonsense";
  CHECK_THROWS_WITH_AS(run_configuration(c), doctest::Contains("allowed: paper, smooth-impact, grazing"),
                       std::invalid_argument);
  // Data of one's own: the paper's benchmark as data gives the paper's measures (the characteristic
  // solution equals the closed form; Δt = 0.37 h keeps the levels off the corners t = kL).
  c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 30, 0.37, 4.0);
  const Measures paper = run_configuration(c);
  c.data = std::make_shared<const InitialData>(benchmark_initial_data(1.0, 0.5));
  const Measures own = run_configuration(c);
  const auto a = ErrorAccumulator::values(paper.errors), b = ErrorAccumulator::values(own.errors);
  for (std::size_t k = 0; k < a.size(); ++k) {
    CAPTURE(std::string(ErrorAccumulator::names[k]));
    CHECK(std::abs(a[k] - b[k]) <= 1e-9 * a[k]);
  }
}

TEST_CASE("the field's benchmarks run through the harness in their own units against the chain's exact solution") {
  // The prediction (repro/configurations.hpp, Scaling): impacting (SI units) is run at the unit scale with
  // c and E of its bar, so the unit chain has Ê = ρ̂ = 1 and length 1, and the measures come back in
  // seconds and J/m². Mod 3 keeps the total mass (its level-0 energy is ½ρLv² = 8e6 J/m² to round-off);
  // the bar flies freely across the gap, so the contact starts at g₀/v within one step and lasts 2L/c
  // within 4h/c (lib/measures/loads_and_gaps.cpp, derivation 4). Every benchmark the runs take gives eight
  // finite positive errors, or 0 for u(0,·) where the exact u(0,·) ≡ 0 (gravity-paper, held: the
  // absolute error, as ErrorNorms says, and the run's u₀ is exactly 0 too), and the error of u in
  // L²(0,T; L²) decreases from N = 20 to 40.
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 40, 0.5, 1.0);
  c.benchmark = "impacting";
  c.final_time = impact_benchmark("impacting").final_time;
  const Scaling s = configuration_scaling(c);
  const BarSegment& bar = impact_benchmark("impacting").configuration.segments.front();
  const double wave_speed = std::sqrt(bar.modulus / bar.density);
  CHECK(s.wave_speed == wave_speed);
  CHECK(s.modulus == bar.modulus);
  const Configuration unit = unit_configuration(c, s);
  REQUIRE(unit.field);
  CHECK(unit.field->configuration.segments.front().modulus == 1.0);
  CHECK(std::abs(unit.field->configuration.segments.front().density - 1.0) <= 1e-15);
  CHECK(unit.bar_length() == 1.0);
  const Measures m = run_configuration(c);
  CHECK(std::abs(m.energy_initial - 0.5 * 8000 * 0.2 * 100 * 100) <= 1e-12 * 8e6);
  REQUIRE(m.contact_windows.size() == 1);
  const double h_over_c = 0.2 / 40 / wave_speed, t1 = 2e-3 / 100;
  CHECK(std::abs(m.contact_windows[0].start - t1) <= 0.5 * h_over_c);
  CHECK(std::abs(m.contact_windows[0].end - m.contact_windows[0].start - 2 * 0.2 / wave_speed) <= 4 * h_over_c);
  CHECK(m.max_penetration <= 1e-12 * 2e-3);
  for (const std::string benchmark : {"bouncing", "impacting", "gravity-paper", "layered"}) {
    double previous = HUGE_VAL;
    for (const Index elements : {20, 40}) {
      Configuration b = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod1", elements, 0.5, 1.0);
      b.benchmark = benchmark;
      b.final_time = impact_benchmark(benchmark).final_time;
      const auto errors = ErrorAccumulator::values(run_configuration(b).errors);
      CAPTURE(benchmark);
      CAPTURE(elements);
      for (std::size_t k = 0; k < errors.size(); ++k) {
        CAPTURE(std::string(ErrorAccumulator::names[k]));
        if (benchmark == "gravity-paper" && k == 0)
          CHECK(errors[k] == 0.0);
        else
          CHECK((std::isfinite(errors[k]) && errors[k] > 0));
      }
      CHECK(errors[5] < previous);  // err_u_L2L2 decreases from N = 20 to 40
      previous = errors[5];
    }
  }
  // Two bodies: Crank–Nicolson only (named), N elements on each 10-long bar (h = 10/N, Δt = C h).
  c.benchmark = "two-bars";
  c.elements = 20;
  CHECK(is_two_body_configuration(c));
  CHECK(c.step() == 0.5 * (10.0 / 20));
  CHECK(configuration_mesh(c, 1).length == 10.0);
  CHECK(configuration_mesh(c, 0).far_end == FarEnd::free);
  c.scheme.scheme = Scheme::backward_euler;
  CHECK_THROWS_WITH_AS(run_configuration(c), doctest::Contains("allowed: cn"), InvalidParameter);
  c.scheme.scheme = Scheme::crank_nicolson;
  // The multiplier is the two bodies' stress: a stress computed from one body's history is refused, named.
  c.stress = ContactStress::window;
  CHECK_THROWS_WITH_AS(run_configuration(c), doctest::Contains("allowed: multiplier"), InvalidParameter);
  c.stress = ContactStress::multiplier;
  c.keep_stress_history = true;
  CHECK_THROWS_WITH_AS(run_configuration(c), doctest::Contains("no stress history"), InvalidParameter);
  c.keep_stress_history = false;
  CHECK_THROWS_AS(configuration_problem(c), InvalidParameter);
  c.grading = 1.01;
  CHECK_THROWS_WITH_AS(configuration_mesh(c), doctest::Contains("grading"), InvalidParameter);
  c.grading = 1.0;
  c.benchmark = "layered";
  c.elements = 42;
  CHECK_THROWS_WITH_AS(configuration_mesh(c), doctest::Contains("N a multiple of 5"), InvalidParameter);
  c.elements = 45;
  const UniformMesh layered = configuration_mesh(c);
  CHECK(layered.young(17) == 4.0);  // the interface at x = 1 of L = 2.5 is node 18
  CHECK(layered.young(18) == 1.0);
  CHECK(layered.far_end == FarEnd::free);
}

TEST_CASE("a configuration run for a given number of steps is measured against the reference given") {
  // The prediction: with steps = 7 the observer sees the levels 0..7 whatever T says, and the errors
  // against a reference that is not the data's solution (amplitude 0.4 for data of amplitude 0.5) are,
  // bit for bit, those of the same 7 steps accumulated by hand against that reference.
  Configuration c = paper_configuration(Scheme::backward_euler, "algebraic", "mod1", 16, 0.5, 3.0);
  c.steps = 7;
  const ExactSolution other(1.0, 0.4);
  Index observed = 0;
  const Measures m = run_configuration(
      c, [&](const Sample&) { ++observed; }, &other);
  CHECK(m.steps == 7);
  CHECK(observed == 8);
  const UniformMesh mesh(1.0, 16);
  BarSimulation simulation(benchmark_problem(), mesh, mod1(), c.scheme, 0.5 * mesh.h());
  ErrorAccumulator errors(mesh, other);
  run(simulation, 7, [&](const Sample& s) { errors.add(s); });
  const auto expected = ErrorAccumulator::values(errors.relative());
  const auto got = ErrorAccumulator::values(m.errors);
  for (std::size_t k = 0; k < got.size(); ++k) {
    CAPTURE(ErrorAccumulator::names[k]);
    CHECK(got[k] == expected[k]);
  }
}

}  // namespace mrm::repro
