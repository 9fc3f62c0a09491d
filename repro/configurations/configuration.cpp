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

const ImpactBenchmark* configuration_field(const Configuration& c) {
  if (c.data) return nullptr;
  if (c.field) return c.field.get();
  for (const ImpactBenchmark& b : impact_benchmarks())
    if (b.id == c.benchmark) return &b;
  return nullptr;
}

double Configuration::bar_length() const {
  if (data) return data->length();
  if (const ImpactBenchmark* b = configuration_field(*this)) return b->configuration.length();
  return benchmark == "paper" ? length : 1.0;
}

namespace {
// The wave speed √(E/ρ) of a field benchmark's contact segment (1 for any other configuration).
double contact_wave_speed(const Configuration& c) {
  const ImpactBenchmark* b = configuration_field(c);
  if (!b) return 1.0;
  const BarSegment& s = b->configuration.segments.front();
  return std::sqrt(s.modulus / s.density);
}
}  // namespace

double Configuration::step() const {
  if (dt > 0) return dt;
  const ImpactBenchmark* b = configuration_field(*this);
  if (!b)
    return courant * (grading == 1.0 ? UniformMesh(bar_length(), elements).h()
                                     : graded_mesh(bar_length(), elements, grading).h(0));
  if (is_two_body_chain(b->configuration))  // h = ℓ/N of the left body (N elements on each body)
    return courant * (UniformMesh(b->configuration.segments.front().length, elements).h() / contact_wave_speed(*this));
  return courant * (UniformMesh(bar_length(), elements).h() / contact_wave_speed(*this));
}

bool is_two_body_configuration(const Configuration& c) {
  const ImpactBenchmark* b = configuration_field(c);
  return b && is_two_body_chain(b->configuration);
}

InitialData configuration_data(const Configuration& c) {
  if (c.data) return *c.data;
  if (const ImpactBenchmark* b = configuration_field(c)) return b->data;
  if (c.benchmark == "paper") return benchmark_initial_data(c.length, c.amplitude);
  if (c.benchmark == "smooth-impact") return smooth_benchmark(SmoothBenchmark::generic_impact).data;
  if (c.benchmark == "grazing") return smooth_benchmark(SmoothBenchmark::grazing).data;
  throw std::invalid_argument("unknown benchmark '" + c.benchmark + "' (allowed: paper, smooth-impact, grazing)");
}

bool is_impact_benchmark(const std::string& benchmark) {
  for (const ImpactBenchmark& b : impact_benchmarks())
    if (b.id == benchmark) return true;
  return false;
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
  CHECK(is_impact_benchmark("bouncing"));
  CHECK_FALSE(is_impact_benchmark("paper"));
  CHECK(configuration_contact_windows(c, 8.0).size() == 3);
}

// The paper's benchmark keeps its own problem (the closed-form data as functions), so that its runs are
// the same bits as before the benchmarks became a choice. At the configuration's own scale (the
// harness runs unit_configuration's).
Problem configuration_problem(const Configuration& c) {
  if (!c.data && c.benchmark == "paper") return benchmark_problem(c.length, c.amplitude);
  const ImpactBenchmark* b = configuration_field(c);
  if (b && is_two_body_chain(b->configuration))
    throw InvalidParameter("benchmark", b->id +
                                            ": two bodies have no one-body problem (run_configuration runs "
                                            "them with lib/time/two_bodies.hpp)");
  Problem problem = configuration_data(c).problem();
  if (!b) return problem;
  configuration_mesh(c);  // refuses what the finite element runs do not take
  // The chain's load f (a polynomial in each segment's σ = (x − centre)/(ℓ/2)) and the obstacle's gap.
  const ImpactConfiguration& chain = b->configuration;
  problem.length = chain.length();
  problem.gap = chain.obstacle_gap;
  bool loaded = false;
  for (const BarSegment& segment : chain.segments)
    for (const double v : segment.load) loaded = loaded || v != 0.0;
  if (loaded) {
    // f(x) only: the run forms its load vector once (Problem::steady_load).
    problem.steady_load = true;
    problem.load = [segments = chain.segments](double x, double) {
      double origin = 0;
      std::size_t j = 0;
      while (j + 1 < segments.size() && x > origin + segments[j].length) origin += segments[j++].length;
      const BarSegment& s = segments[j];
      return s.load.empty() ? 0.0 : poly::evaluate(s.load, (x - origin) / (0.5 * s.length) - 1);
    };
  }
  return problem;
}

// The mesh of a field benchmark. The material is constant on each element (the midpoint's segment), so
// an interface must be a node: x_j/L = k/N for an integer k, that is N a multiple of the denominator q_j
// of x_j/L (found as the least q ≤ 10⁴ with q x_j/L within 1e-9 of an integer); the allowed N are the
// multiples of the least common multiple of the q_j.
UniformMesh configuration_mesh(const Configuration& c, int body) {
  const ImpactBenchmark* b = configuration_field(c);
  if (c.grading != 1.0) {
    if (b)
      throw InvalidParameter("grading",
                             "a graded mesh is for the paper's benchmark, the smooth ones and data of "
                             "one's own (allowed on " +
                                 b->id + ": 1, the uniform mesh)");
    return graded_mesh(c.bar_length(), c.elements, c.grading);
  }
  UniformMesh mesh(c.bar_length(), c.elements);
  if (!b) return mesh;
  const ImpactConfiguration& chain = b->configuration;
  if (is_two_body_chain(chain)) {
    // Body k in its own frame (lib/time/two_bodies.hpp): its segment, N elements, its far end (the left
    // body's is x = 0, free: no obstacle; the right body's is the chain's far end).
    const BarSegment& s = chain.segments.at(static_cast<std::size_t>(body));
    UniformMesh own(s.length, c.elements);
    if (s.modulus != 1.0 || s.density != 1.0)
      own = with_material(own, std::vector<double>(static_cast<std::size_t>(c.elements), s.modulus),
                          std::vector<double>(static_cast<std::size_t>(c.elements), s.density));
    return with_far_end(own, body == 0 ? FarEnd::free : chain.far_end);
  }
  bool two_bodies = !chain.obstacle;
  for (const SegmentJunction& j : chain.junctions) two_bodies = two_bodies || j.contact;
  if (two_bodies)
    throw InvalidParameter("benchmark", b->id +
                                            ": the finite element runs take one body against a rigid obstacle, "
                                            "or two bodies in contact with each other (allowed: bouncing, "
                                            "impacting, gravity-paper, two-bars, layered, paper, smooth-impact, "
                                            "grazing)");
  const double length = chain.length(), n = static_cast<double>(c.elements);
  long multiple = 1;
  bool misplaced = false;
  std::string interface;
  double x = 0;
  for (std::size_t j = 0; j + 1 < chain.segments.size(); ++j) {
    x += chain.segments[j].length;
    const double fraction = x / length;
    long q = 1;
    while (q < 10000 && std::abs(q * fraction - std::round(q * fraction)) > 1e-9 * q) ++q;
    multiple = std::lcm(multiple, q);
    const double k = fraction * n;
    if (std::abs(k - std::round(k)) > 1e-9 * n) misplaced = true, interface = cli::format_real(x);
  }
  if (misplaced)
    throw InvalidParameter("elements", "the interface at x = " + interface + " of benchmark " + b->id +
                                           " must be a node (allowed: N a multiple of " + std::to_string(multiple) +
                                           ")");
  bool homogeneous = true;
  for (const BarSegment& s : chain.segments) homogeneous = homogeneous && s.modulus == 1.0 && s.density == 1.0;
  if (!homogeneous) {
    std::vector<double> young(static_cast<std::size_t>(c.elements)), density(young.size());
    for (Index e = 0; e < c.elements; ++e) {
      const double middle = 0.5 * (mesh.x(e) + mesh.x(e + 1));
      double origin = 0;
      std::size_t j = 0;
      while (j + 1 < chain.segments.size() && middle > origin + chain.segments[j].length)
        origin += chain.segments[j++].length;
      young[static_cast<std::size_t>(e)] = chain.segments[j].modulus;
      density[static_cast<std::size_t>(e)] = chain.segments[j].density;
    }
    mesh = with_material(mesh, young, density);
  }
  return with_far_end(mesh, chain.far_end);
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
  try {
    if (massless && spec == "consistent")
      throw std::invalid_argument(cli::quoted_text(spec) + ": this program needs a massless contact node (allowed: " +
                                  mass_redistribution_forms() + ", except consistent)");
    return mass_redistribution_from_spec(spec, mesh, blend);
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
