// The one function that runs a configuration and returns its measures; see configurations.hpp.
#include "configurations.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "exact_solution.hpp"

namespace mrm::repro {

Configuration paper_configuration(const std::string& scheme, const std::string& ps_form, const std::string& mass,
                                  Index elements, double courant, double final_time) {
  Configuration c;
  c.scheme = scheme_parameters(scheme, ps_form, mass);
  c.mass = mass_redistribution_by_name(mass);
  c.elements = elements;
  c.courant = courant;
  c.final_time = final_time;
  return c;
}

// The horizons are levels of the same run: the errors over [0, T_k] are the accumulator's relative
// errors right after the level steps_to_reach(T_k, Δt) was added (the L∞ maxima and the L² integrals
// of a prefix). The impacts come from the contact indicator of every level (phase.cpp), with the
// chatter filter set to L, half the exact free flight 2L between two contacts.
Measures run_configuration(const Configuration& c, const std::function<void(const Sample&)>& observe) {
  const UniformMesh mesh(c.length, c.elements);
  const double dt = c.step();
  for (std::size_t k = 0; k < c.horizons.size(); ++k)
    if (!(c.horizons[k] > 0 && c.horizons[k] <= c.final_time && (k == 0 || c.horizons[k] > c.horizons[k - 1])))
      throw std::invalid_argument("run_configuration: the horizons must increase within (0, T]");
  BarSimulation simulation(benchmark_problem(c.length, c.amplitude), mesh, c.mass, c.scheme, dt, c.initial);
  const ExactSolution exact(c.length, c.amplitude);
  ErrorAccumulator errors(mesh, exact);
  ImpactDetector impacts(c.length);
  std::vector<Index> horizon_levels;
  for (double t : c.horizons) horizon_levels.push_back(steps_to_reach(t, dt));
  std::size_t next_horizon = 0;
  const double h = mesh.h();
  Measures m;
  m.steps = steps_to_reach(c.final_time, dt);
  m.energy_min = std::numeric_limits<double>::infinity();
  m.energy_max = -m.energy_min;
  run(simulation, m.steps, [&](const Sample& s) {
    errors.add(s);
    impacts.add(s.time, contact_indicator(s, h));
    while (next_horizon < horizon_levels.size() && s.level == horizon_levels[next_horizon]) {
      m.horizon_errors.push_back(errors.relative());
      ++next_horizon;
    }
    if (s.level == 0) m.energy_initial = s.energy;
    m.energy_final = s.energy;
    m.energy_min = std::min(m.energy_min, s.energy);
    m.energy_max = std::max(m.energy_max, s.energy);
    if (!std::isfinite(s.energy)) throw std::runtime_error("the run produced a non-finite energy");
    if (observe) observe(s);
  });
  m.errors = errors.relative();
  m.impacts = impacts.impacts();
  if (!m.impacts.empty())
    m.phase = phase_measures(m.impacts, benchmark_impact_times(exact, m.impacts.size()), exact.period());
  return m;
}

// A pool of threads that take the next configuration from a shared counter; each result goes to its
// own slot, so the order of completion does not matter.
std::vector<Measures> run_configurations(const std::vector<Configuration>& configurations, unsigned threads) {
  const std::size_t n = configurations.size();
  std::vector<Measures> results(n);
  std::vector<std::exception_ptr> errors(n);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(n, 1)));
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t k = next++; k < n; k = next++) {
      try {
        results[k] = run_configuration(configurations[k]);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return results;
}

TEST_CASE("a configuration's measures are those of the same run observed by hand") {
  // The prediction: run_configuration is the library's run with an ErrorAccumulator, so its measures
  // equal, bit for bit, those of the same simulation stepped here; its energy range contains every
  // sample's energy, and the observer sees the levels 0..steps.
  Configuration c = paper_configuration("cn", "algebraic", "mod3", 20, 0.5, 3.0);
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
  Configuration longer = paper_configuration("cn", "algebraic", "mod2", 16, 0.5, 9.0);
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

}  // namespace mrm::repro
