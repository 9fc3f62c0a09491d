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
  c.mass = mass_redistribution_from_spec(mass);
  c.elements = elements;
  c.courant = courant;
  c.final_time = final_time;
  return c;
}

MassRedistribution mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                    bool massless) {
  try {
    if (massless && spec == "consistent")
      throw std::invalid_argument("\"consistent\": this program needs a massless contact node (allowed: " +
                                  mass_redistribution_forms() + ", except consistent)");
    return mass_redistribution_from_spec(spec, mesh);
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(option + ": " + e.what());
  }
}

ContactVelocity contact_velocity_by_name(const std::string& name) {
  if (name == "scheme") return ContactVelocity::scheme;
  if (name == "backward-difference") return ContactVelocity::backward_difference;
  throw std::invalid_argument("unknown contact velocity \"" + name + "\" (allowed: scheme, backward-difference)");
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
  // The backward difference replaces the contact node's entry of a copy of the velocity (level ≥ 1).
  const bool difference = c.contact_velocity == ContactVelocity::backward_difference && simulation.massless_contact_node();
  Eigen::VectorXd velocity;
  double u0_previous = 0;
  run(simulation, m.steps, [&](const Sample& s) {
    if (difference && s.level >= 1) {
      velocity = *s.velocity;
      velocity[0] = ((*s.displacement)[0] - u0_previous) / dt;
      Sample differenced = s;
      differenced.velocity = &velocity;
      errors.add(differenced);
    } else {
      errors.add(s);
    }
    u0_previous = (*s.displacement)[0];
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

TEST_CASE("a bad mass option names the option and the allowed forms") {
  const UniformMesh mesh(1.0, 20);
  CHECK(mass_from_option("--mass", "node1:7/6", mesh).name == "node1:7/6");
  CHECK_THROWS_WITH_AS(
      mass_from_option("--mass", "node1:x", mesh),
      doctest::Contains("--mass: \"node1:x\": \"x\" is not a decimal or a fraction (allowed: consistent"),
      cli::UsageError);
  CHECK_THROWS_WITH_AS(mass_from_option("--mass", "spread:20", mesh), doctest::Contains("at most N - 1 = 19"),
                       cli::UsageError);
  CHECK_NOTHROW(mass_from_option("--mass", "consistent", mesh));
  CHECK_THROWS_WITH_AS(mass_from_option("--mass", "consistent", mesh, true), doctest::Contains("except consistent"),
                       cli::UsageError);
}

TEST_CASE("the backward-difference contact velocity changes the velocity measures only") {
  // The prediction: the displacement, stress and H¹ measures do not read the velocity, so they stay
  // bit for bit; the two velocity measures equal those accumulated by hand with V₀ⁿ replaced by
  // (u₀ⁿ − u₀ⁿ⁻¹)/Δt, and differ from the scheme's (Crank–Nicolson's recovered V₀ alternates after an
  // impact). A mass with inertia at the contact node is left alone.
  Configuration c = paper_configuration("cn", "algebraic", "node1:7/6", 20, 0.5, 6.0);
  const Measures plain = run_configuration(c);
  c.contact_velocity = contact_velocity_by_name("backward-difference");
  const Measures differenced = run_configuration(c);
  const UniformMesh mesh(1.0, 20);
  const double dt = 0.5 * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, node1(7.0 / 6.0), c.scheme, dt);
  ErrorAccumulator errors(mesh, ExactSolution());
  double previous = 0;
  run(simulation, steps_to_reach(6.0, dt), [&](const Sample& s) {
    Eigen::VectorXd v = *s.velocity;
    if (s.level >= 1) v[0] = ((*s.displacement)[0] - previous) / dt;
    previous = (*s.displacement)[0];
    Sample d = s;
    d.velocity = &v;
    errors.add(d);
  });
  const auto a = ErrorAccumulator::values(plain.errors), b = ErrorAccumulator::values(differenced.errors),
             hand = ErrorAccumulator::values(errors.relative());
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::string name = ErrorAccumulator::names[k];
    CAPTURE(name);
    CHECK(b[k] == hand[k]);
    if (name.find("_v_") == std::string::npos) CHECK(a[k] == b[k]);
    else CHECK(std::abs(a[k] - b[k]) > 1e-6);
  }
  Configuration consistent = paper_configuration("cn", "literal", "consistent", 20, 0.5, 3.0);
  const auto scheme_velocity = ErrorAccumulator::values(run_configuration(consistent).errors);
  consistent.contact_velocity = ContactVelocity::backward_difference;
  CHECK(ErrorAccumulator::values(run_configuration(consistent).errors) == scheme_velocity);
  CHECK_THROWS_AS(contact_velocity_by_name("forward"), std::invalid_argument);
}

}  // namespace mrm::repro
