// The one function that runs a configuration and returns its measures; see configurations.hpp.
#include "configurations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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

Measures run_configuration(const Configuration& c, const std::function<void(const Sample&)>& observe,
                           const ExactSolution* reference) {
  const UniformMesh mesh(c.length, c.elements);
  const double dt = c.step();
  BarSimulation simulation(benchmark_problem(c.length, c.amplitude), mesh, c.mass, c.scheme, dt, c.initial);
  ErrorAccumulator errors(mesh, reference ? *reference : ExactSolution(c.length, c.amplitude));
  Measures m;
  m.steps = c.steps >= 0 ? c.steps : steps_to_reach(c.final_time, dt);
  m.energy_min = std::numeric_limits<double>::infinity();
  m.energy_max = -m.energy_min;
  run(simulation, m.steps, [&](const Sample& s) {
    errors.add(s);
    if (s.level == 0) m.energy_initial = s.energy;
    m.energy_final = s.energy;
    m.energy_min = std::min(m.energy_min, s.energy);
    m.energy_max = std::max(m.energy_max, s.energy);
    if (!std::isfinite(s.energy)) throw std::runtime_error("the run produced a non-finite energy");
    if (observe) observe(s);
  });
  m.errors = errors.relative();
  return m;
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

TEST_CASE("a configuration run for a given number of steps is measured against the reference given") {
  // The prediction: with steps = 7 the observer sees the levels 0..7 whatever T says, and the errors
  // against a reference that is not the data's solution (amplitude 0.4 for data of amplitude 0.5) are,
  // bit for bit, those of the same 7 steps accumulated by hand against that reference.
  Configuration c = paper_configuration("be", "algebraic", "mod1", 16, 0.5, 3.0);
  c.steps = 7;
  const ExactSolution other(1.0, 0.4);
  Index observed = 0;
  const Measures m = run_configuration(c, [&](const Sample&) { ++observed; }, &other);
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
