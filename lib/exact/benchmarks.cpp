/// @file benchmarks.cpp
/// @brief The registry of benchmarks (benchmarks.hpp): the paper's, the smooth S1 and S2 and the field's,
/// each entry building its problem, mesh and exact solution; the problem and mesh of a field chain.
///
/// The paper's benchmark (mathematics.md §2) keeps its own problem (the closed-form data as functions,
/// benchmark_problem) and its closed form as the exact solution; the smooth ones (mathematics.md §11)
/// and the field's (doc/benchmarks.md §3–§7) run their data as piecewise polynomials against the
/// characteristic solution (mathematics.md §10) or the chain's exact solution (impact_reference.hpp).
#include "exact/benchmarks.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <system_error>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_reference.hpp"

namespace mrm {

namespace {

// The shortest decimal that reads back to x (as the harness writes its numbers).
std::string shortest(double x) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, x);
  if (error != std::errc()) throw std::logic_error("benchmarks: buffer too small");
  return std::string(buffer, end);
}

std::vector<Benchmark> make_benchmarks() {
  // The smooth benchmarks' horizon is SmoothBenchmarkData::final_time, T = 2 (the doctest below checks it).
  std::vector<Benchmark> list{{"paper", "the paper's benchmark (closed-form solution)",
                               "the paper (Dabaghi et al. 2015), mathematics.md sec. 2", "", 6.0, BenchmarkKind::paper,
                               SmoothBenchmark::generic_impact, nullptr},
                              {"smooth-impact", "S1, a smooth impact", "mathematics.md sec. 11 (S1)", "", 2.0,
                               BenchmarkKind::smooth, SmoothBenchmark::generic_impact, nullptr},
                              {"grazing", "S2, a grazing contact", "mathematics.md sec. 11 (S2)", "", 2.0,
                               BenchmarkKind::smooth, SmoothBenchmark::grazing, nullptr}};
  // The field's (impact_benchmarks.cpp: their chains, data and horizons), each with the one line of the
  // help texts.
  const std::vector<std::pair<std::string, std::string>> summaries{
      {"bouncing", "Doyen-Ern-Piperno's bouncing bar (falling under gravity)"},
      {"impacting", "Code_Aster SDNV100's impacting bar, SI units"},
      {"gravity-paper", "the paper's bar pressed by f = -1"},
      {"two-bars", "two free bars colliding, N elements each (cn only)"},
      {"layered", "a two-layer bar hitting a wall"}};
  for (const auto& [id, summary] : summaries) {
    const ImpactBenchmark& b = impact_benchmark(id);
    list.push_back({b.id, summary, b.source, b.time_unit, b.final_time, BenchmarkKind::field,
                    SmoothBenchmark::generic_impact, &b});
  }
  return list;
}

}  // namespace

const std::vector<Benchmark>& benchmarks() {
  static const std::vector<Benchmark> list = make_benchmarks();
  return list;
}

std::string benchmark_ids() {
  std::string ids;
  for (const Benchmark& b : benchmarks()) ids += (ids.empty() ? "" : ", ") + b.id;
  return ids;
}

const Benchmark& benchmark(const std::string& id) {
  for (const Benchmark& b : benchmarks())
    if (b.id == id) return b;
  throw InvalidParameter("benchmark", "unknown benchmark '" + id + "' (allowed: " + benchmark_ids() + ")");
}

bool Benchmark::two_bodies() const { return field && is_two_body_chain(field->configuration); }

double Benchmark::wave_speed() const {
  if (!field) return 1.0;
  const BarSegment& s = field->configuration.segments.front();
  return std::sqrt(s.modulus / s.density);
}

double Benchmark::bar_length(double length) const {
  if (field) return field->configuration.length();
  return takes_length() ? length : 1.0;
}

InitialData Benchmark::data(double length, double amplitude) const {
  switch (kind) {
    case BenchmarkKind::paper:
      return benchmark_initial_data(length, amplitude);
    case BenchmarkKind::smooth:
      return smooth_benchmark(smooth).data;
    case BenchmarkKind::field:
      break;
  }
  return field->data;
}

Problem Benchmark::problem(double length, double amplitude) const {
  switch (kind) {
    case BenchmarkKind::paper:
      return benchmark_problem(length, amplitude);
    case BenchmarkKind::smooth:
      return data().problem();
    case BenchmarkKind::field:
      break;
  }
  return chain_problem(*field);
}

UniformMesh Benchmark::mesh(Index elements, double grading, double length, int body) const {
  if (grading != 1.0) {
    if (field)
      throw InvalidParameter("grading",
                             "a graded mesh is for the paper's benchmark, the smooth ones and data of "
                             "one's own (allowed on " +
                                 id + ": 1, the uniform mesh)");
    return graded_mesh(bar_length(length), elements, grading);
  }
  if (field) return chain_mesh(*field, elements, body);
  return UniformMesh(bar_length(length), elements);
}

std::shared_ptr<const ReferenceSolution> Benchmark::reference(double horizon, double length, double amplitude) const {
  switch (kind) {
    case BenchmarkKind::paper:
      return std::make_shared<const ExactSolution>(length, amplitude);
    case BenchmarkKind::smooth:
      return std::make_shared<const CharacteristicSolution>(data(), horizon);
    case BenchmarkKind::field:
      break;
  }
  return std::make_shared<const ImpactReference>(field->configuration, field->data, horizon);
}

Problem chain_problem(const ImpactBenchmark& b) {
  const ImpactConfiguration& chain = b.configuration;
  if (is_two_body_chain(chain))
    throw InvalidParameter("benchmark", b.id +
                                            ": two bodies have no one-body problem (TwoBodySimulation runs "
                                            "them: lib/time/two_bodies.hpp)");
  Problem problem = b.data.problem();
  // The chain's load f (a polynomial in each segment's σ = (x − centre)/(ℓ/2)) and the obstacle's gap.
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
UniformMesh chain_mesh(const ImpactBenchmark& b, Index elements, int body) {
  const ImpactConfiguration& chain = b.configuration;
  if (is_two_body_chain(chain)) {
    // Body k in its own frame (lib/time/two_bodies.hpp): its segment, N elements, its far end (the left
    // body's is x = 0, free: no obstacle; the right body's is the chain's far end).
    const BarSegment& s = chain.segments.at(static_cast<std::size_t>(body));
    UniformMesh own(s.length, elements);
    if (s.modulus != 1.0 || s.density != 1.0)
      own = with_material(own, std::vector<double>(static_cast<std::size_t>(elements), s.modulus),
                          std::vector<double>(static_cast<std::size_t>(elements), s.density));
    return with_far_end(own, body == 0 ? FarEnd::free : chain.far_end);
  }
  UniformMesh mesh(chain.length(), elements);
  bool two_bodies = !chain.obstacle;
  for (const SegmentJunction& j : chain.junctions) two_bodies = two_bodies || j.contact;
  if (two_bodies)
    throw InvalidParameter("benchmark", b.id +
                                            ": the finite element runs take one body against a rigid obstacle, "
                                            "or two bodies in contact with each other (allowed: " +
                                            benchmark_ids() + ")");
  const double length = chain.length(), n = static_cast<double>(elements);
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
    if (std::abs(k - std::round(k)) > 1e-9 * n) misplaced = true, interface = shortest(x);
  }
  if (misplaced)
    throw InvalidParameter("elements", "the interface at x = " + interface + " of benchmark " + b.id +
                                           " must be a node (allowed: N a multiple of " + std::to_string(multiple) +
                                           ")");
  bool homogeneous = true;
  for (const BarSegment& s : chain.segments) homogeneous = homogeneous && s.modulus == 1.0 && s.density == 1.0;
  if (!homogeneous) {
    std::vector<double> young(static_cast<std::size_t>(elements)), density(young.size());
    for (Index e = 0; e < elements; ++e) {
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

// ---------------------------------------------------------------------------------------------------

TEST_CASE("every benchmark id reads back to its entry, and an unknown one is refused with the allowed ids") {
  REQUIRE(benchmarks().size() == 3 + impact_benchmarks().size());
  for (const Benchmark& b : benchmarks()) {
    CAPTURE(b.id);
    CHECK(&benchmark(b.id) == &b);
    CHECK(!b.summary.empty());
    CHECK(!b.source.empty());
    CHECK(b.summary.size() <= 80);  // one line of a help text
  }
  CHECK(benchmark_ids() == "paper, smooth-impact, grazing, bouncing, impacting, gravity-paper, two-bars, layered");
  CHECK_THROWS_WITH_AS(benchmark("s2"),
                       "benchmark: unknown benchmark 's2' (allowed: paper, smooth-impact, grazing, bouncing, "
                       "impacting, gravity-paper, two-bars, layered)",
                       InvalidParameter);
}

// Prediction: each entry builds what its source builds: the paper's closed-form data and solution, S1's
// and S2's data of smooth_benchmarks.cpp with their horizon T = 2, each field benchmark's chain, data,
// horizon and unit; the same values at every point (bit for bit).
TEST_CASE("each benchmark's problem, mesh, horizon and exact solution are those of its source") {
  const auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  const Benchmark& paper = benchmark("paper");
  CHECK(paper.takes_length());
  CHECK(paper.final_time == 6.0);  // two periods of 3L
  const Problem p = paper.problem(2.0, 0.3), q = benchmark_problem(2.0, 0.3);
  CHECK(p.length == q.length);
  for (const double x : {0.0, 0.7, 2.0}) CHECK(same(p.initial_displacement(x), q.initial_displacement(x)));
  CHECK(paper.mesh(10, 1.0, 2.0).h() == UniformMesh(2.0, 10).h());
  CHECK(paper.mesh(10, 1.05, 2.0).h(0) == graded_mesh(2.0, 10, 1.05).h(0));
  const auto closed = paper.reference(6.0, 2.0, 0.3);
  const ExactSolution exact(2.0, 0.3);
  CHECK(same(closed->contact_multiplier(2.5), exact.contact_multiplier(2.5)));
  for (const std::string id : {"smooth-impact", "grazing"}) {
    CAPTURE(id);
    const Benchmark& b = benchmark(id);
    const SmoothBenchmark which = id == "grazing" ? SmoothBenchmark::grazing : SmoothBenchmark::generic_impact;
    CHECK(b.smooth == which);
    const SmoothBenchmarkData s = smooth_benchmark(which);
    CHECK(!b.takes_length());
    CHECK(b.final_time == s.final_time);
    CHECK(b.bar_length(3.0) == 1.0);
    const Problem problem = b.problem();
    for (const double x : {0.05, 0.3, 0.5, 0.95}) {
      CHECK(same(problem.initial_displacement(x), s.data.displacement(x)));
      CHECK(same(problem.initial_velocity(x), s.data.velocity(x)));
    }
    CHECK(same(b.reference(2.0)->contact_displacement(0.4),
               CharacteristicSolution(s.data, 2.0).contact_displacement(0.4)));
  }
  for (const ImpactBenchmark& chain : impact_benchmarks()) {
    CAPTURE(chain.id);
    const Benchmark& b = benchmark(chain.id);
    CHECK(b.field == &chain);
    CHECK(b.final_time == chain.final_time);
    CHECK(b.time_unit == chain.time_unit);
    CHECK(b.bar_length() == chain.configuration.length());
    CHECK(b.two_bodies() == (chain.id == "two-bars"));
    CHECK_THROWS_AS(b.mesh(10, 1.05), InvalidParameter);
    if (b.two_bodies()) {
      CHECK_THROWS_AS(b.problem(), InvalidParameter);
      CHECK(b.mesh(10, 1.0, 1.0, 1).length == chain.configuration.segments[1].length);
      continue;
    }
    const Problem problem = b.problem();
    CHECK(problem.gap == chain.configuration.obstacle_gap);
    CHECK(static_cast<bool>(problem.load) == (chain.id == "bouncing" || chain.id == "gravity-paper"));
    for (int k = 0; k <= 10; ++k) {
      const double x = chain.configuration.length() * k / 10.0;
      CHECK(same(problem.initial_velocity(x), chain.data.velocity(x)));
    }
    const UniformMesh mesh = b.mesh(20);
    CHECK(mesh.length == chain.configuration.length());
    CHECK(b.wave_speed() ==
          std::sqrt(chain.configuration.segments.front().modulus / chain.configuration.segments.front().density));
    const ImpactReference own(chain.configuration, chain.data, chain.final_time);
    CHECK(same(b.reference(chain.final_time)->contact_displacement(0.3 * chain.final_time),
               own.contact_displacement(0.3 * chain.final_time)));
  }
  CHECK(benchmark("impacting").time_unit == "s");
  CHECK_THROWS_WITH_AS(benchmark("layered").mesh(42), doctest::Contains("x = 1 of benchmark layered must be a node"),
                       InvalidParameter);
}

}  // namespace mrm
