/// @file configurations/configuration.cpp
/// @brief One run of the harness: its scheme, mass, mesh, data and benchmark, and the paper's named configurations.
#include "configurations/configuration.hpp"

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

const Benchmark& configuration_benchmark(const Configuration& c) { return mrm::benchmark(c.benchmark); }

const ImpactBenchmark* configuration_field(const Configuration& c) {
  if (c.data) return nullptr;
  if (c.field) return c.field.get();
  return configuration_benchmark(c).field;
}

bool has_closed_form(const Configuration& c) {
  return !c.data && configuration_benchmark(c).kind == BenchmarkKind::paper;
}

double Configuration::bar_length() const {
  if (data) return data->length();
  if (field) return field->configuration.length();
  return mrm::benchmark(benchmark).bar_length(length);
}

double Configuration::step() const {
  if (dt > 0) return dt;
  const ImpactBenchmark* b = configuration_field(*this);
  if (!b) {
    const double l = bar_length();
    return courant * (grading == 1.0 ? UniformMesh(l, elements).h() : graded_mesh(l, elements, grading).h(0));
  }
  // h/c at the contact end: c = √(E/ρ) of the contact segment, h = L/N, or ℓ/N of the left body on two
  // bodies (N elements on each body).
  const BarSegment& contact = b->configuration.segments.front();
  const double l = is_two_body_chain(b->configuration) ? contact.length : b->configuration.length();
  return courant * (UniformMesh(l, elements).h() / std::sqrt(contact.modulus / contact.density));
}

bool is_two_body_configuration(const Configuration& c) {
  const ImpactBenchmark* b = configuration_field(c);
  return b && is_two_body_chain(b->configuration);
}

InitialData configuration_data(const Configuration& c) {
  if (c.data) return *c.data;
  if (const ImpactBenchmark* b = configuration_field(c)) return b->data;
  return configuration_benchmark(c).data(c.length, c.amplitude);
}

std::vector<ContactInterval> configuration_contact_windows(const Configuration& c, double final_time) {
  if (const ImpactBenchmark* b = configuration_field(c))
    return exact_contact_windows(b->configuration, b->data, final_time);
  const InitialData data = configuration_data(c);
  ImpactConfiguration bar;
  BarSegment segment;
  segment.length = data.length();
  bar.segments = {segment};
  return exact_contact_windows(bar, data, final_time);
}

TEST_CASE("the exact contact windows of the paper's benchmark are [1 + 3k, 2 + 3k], scaled by L") {
  Configuration c;
  for (const double length : {1.0, 2.5}) {
    c.length = length;
    const std::vector<ContactInterval> w = configuration_contact_windows(c, 6.5 * length);
    REQUIRE(w.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
      CHECK(std::abs(w[k].start - (1 + 3.0 * k) * length) <= 1e-12 * length);
      CHECK(std::abs(w[k].end - (2 + 3.0 * k) * length) <= 1e-12 * length);
    }
  }
  c.benchmark = "bouncing";
  CHECK(configuration_field(c) == benchmark("bouncing").field);
  CHECK(configuration_contact_windows(c, 8.0).size() == 3);
}

// The problem of the configuration's benchmark (lib/exact/benchmarks.hpp), or of its chain scaled to unit
// size (unit_configuration), or of its data of one's own. At the configuration's own scale (the
// harness runs unit_configuration's).
Problem configuration_problem(const Configuration& c) {
  if (c.data) return c.data->problem();
  const Benchmark& entry = configuration_benchmark(c);
  if (!entry.field) return entry.problem(c.length, c.amplitude);
  // The mesh refuses what the finite element runs do not take (a grading, an interface that is not a
  // node; the unit chain's interfaces are the registry's, scaled).
  if (!entry.two_bodies()) (void)entry.mesh(c.elements, c.grading);
  return chain_problem(c.field ? *c.field : *entry.field);
}

UniformMesh configuration_mesh(const Configuration& c, int body) {
  if (!c.data) {
    const Benchmark& entry = configuration_benchmark(c);
    // The chain unit_configuration scaled to unit size, or the registry's entry's.
    if (c.field && c.grading == 1.0) return chain_mesh(*c.field, c.elements, body);
    return entry.mesh(c.elements, c.grading, c.length, body);
  }
  const double l = c.data->length();
  return c.grading == 1.0 ? UniformMesh(l, c.elements) : graded_mesh(l, c.elements, c.grading);
}

TEST_CASE("a configuration builds its benchmark's problem, mesh and data: those of the registry's entry") {
  for (const Benchmark& entry : benchmarks()) {
    CAPTURE(entry.id);
    Configuration c;
    c.benchmark = entry.id;
    c.elements = 20;
    CHECK(c.bar_length() == entry.bar_length(c.length));
    CHECK(configuration_mesh(c).h() == entry.mesh(20, 1.0, c.length).h());
    CHECK(configuration_data(c).pieces.size() == entry.data(c.length, c.amplitude).pieces.size());
    CHECK(configuration_field(c) == entry.field);
    if (entry.two_bodies()) {
      CHECK(is_two_body_configuration(c));
      CHECK_THROWS_AS(configuration_problem(c), InvalidParameter);
      continue;
    }
    const Problem a = configuration_problem(c), b = entry.problem(c.length, c.amplitude);
    for (int k = 0; k <= 8; ++k) {
      const double x = c.bar_length() * k / 8.0;
      CHECK(a.initial_displacement(x) == b.initial_displacement(x));
      CHECK(a.initial_velocity(x) == b.initial_velocity(x));
    }
    CHECK(a.gap == b.gap);
    CHECK(static_cast<bool>(a.load) == static_cast<bool>(b.load));
  }
}

Configuration paper_configuration(Scheme scheme, const std::string& ps_form, const std::string& mass, Index elements,
                                  double courant, double final_time) {
  Configuration c;
  c.scheme = scheme_parameters(scheme, ps_form, mass);
  c.mass = mass_redistribution_from_spec(mass);
  c.elements = elements;
  c.courant = courant;
  c.final_time = final_time;
  return c;
}

Configuration paper_configuration(const std::string& scheme, const std::string& ps_form, const std::string& mass,
                                  Index elements, double courant, double final_time) {
  return paper_configuration(scheme_by_name(scheme), ps_form, mass, elements, courant, final_time);
}

Configuration study_configuration(const std::string& benchmark, Scheme scheme, const MassRedistribution& mass,
                                  Index elements, double courant, double final_time) {
  Configuration c;
  c.scheme.scheme = scheme;
  c.mass = mass;
  c.elements = elements;
  c.courant = courant;
  c.final_time = final_time;
  c.benchmark = benchmark;
  return c;
}

double run_cost(const Configuration& c) {
  const double steps = static_cast<double>(c.steps >= 0 ? c.steps : steps_to_reach(c.final_time, c.step()));
  return static_cast<double>(c.elements) * steps;
}

TEST_CASE("study_configuration and run_cost: the fields given, the defaults kept, elements x steps") {
  const Configuration c = study_configuration("bouncing", Scheme::switching, mod3(0.25), 40, 0.5, 8.0);
  CHECK(c.benchmark == "bouncing");
  CHECK(c.scheme.scheme == Scheme::switching);
  CHECK(c.mass.interior_blend == 0.25);
  CHECK(c.elements == 40);
  CHECK(c.stress == Configuration().stress);
  // bouncing: L = 10, c = 30, so h = 1/4, dt = 1/240 and T = 8 takes 1920 steps.
  CHECK(run_cost(c) == doctest::Approx(40.0 * 1920));
  CHECK(run_cost(study_configuration("paper", Scheme::crank_nicolson, mod3(), 100, 0.5, 3.0)) ==
        doctest::Approx(100.0 * 600));
}

MassRedistribution mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                    bool massless, double blend) {
  return assembled_mass_from_option(option, spec, mesh, massless, blend).redistribution;
}

AssembledMass assembled_mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                         bool massless, double blend) {
  try {
    if (massless && spec == "consistent")
      throw std::invalid_argument(cli::quoted_text(spec) + ": this program needs a massless contact node (allowed: " +
                                  mass_redistribution_forms() + ", except consistent)");
    return assembled_mass_from_spec(spec, mesh, blend);
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(option + ": " + e.what());
  }
}

ContactVelocity contact_velocity_by_name(const std::string& name) {
  if (name == "algebraic") return ContactVelocity::algebraic;
  if (name == "backward-difference") return ContactVelocity::backward_difference;
  throw std::invalid_argument("unknown contact velocity " + cli::quoted_text(name) +
                              " (allowed: algebraic, backward-difference)");
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
  // (u₀ⁿ − u₀ⁿ⁻¹)/Δt. The L² one differs from the library's (V₀ from the algebraic row, mathematics.md
  // §7: V₁ in flight, 0 in contact, where the difference quotient jumps at each impact); the L∞ one is a
  // maximum over the levels and may be reached where both give V₀ = 0 (in contact), so only its
  // equality with the hand computation is required. A mass with inertia at the contact node is left alone.
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "node1:7/6", 20, 0.5, 6.0);
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
    if (name == "err_v_L2L2") CHECK(std::abs(a[k] - b[k]) > 1e-4 * a[k]);
  }
  Configuration consistent = paper_configuration(Scheme::crank_nicolson, "literal", "consistent", 20, 0.5, 3.0);
  const auto own_velocity = ErrorAccumulator::values(run_configuration(consistent).errors);
  consistent.contact_velocity = ContactVelocity::backward_difference;
  CHECK(ErrorAccumulator::values(run_configuration(consistent).errors) == own_velocity);
  CHECK(contact_velocity_by_name("algebraic") == ContactVelocity::algebraic);
  CHECK_THROWS_AS(contact_velocity_by_name("forward"), std::invalid_argument);
}

}  // namespace mrm::repro
