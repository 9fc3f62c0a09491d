/// @file impact_benchmarks.cpp
/// @brief The field's impact benchmarks (doc/benchmarks.md §3–§7) as chains of segments, their
/// registry, and the words that name what a chain needs beyond the paper's problem.
///
/// Each benchmark is a chain of impact_chain.cpp with its initial data (breakpoints at every junction)
/// and its default horizon; the data and their sources are derived above each entry of
/// make_benchmarks. The closed forms the chain solver is checked against are derived in
/// impact_closed_forms.cpp, the contact windows of the named benchmarks in impact_lattice.cpp.
#include "exact/impact_benchmarks.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "core/problem.hpp"

namespace mrm {

std::string configuration_features(const ImpactConfiguration& c) {
  std::vector<std::string> features;
  bool load = false, layers = false, contact_junction = false;
  for (const BarSegment& s : c.segments) {
    for (double v : s.load) load = load || v != 0.0;
    layers = layers || s.modulus != c.segments.front().modulus || s.density != c.segments.front().density;
  }
  for (const SegmentJunction& j : c.junctions) contact_junction = contact_junction || j.contact;
  if (load) features.push_back("a load f");
  if (c.far_end == FarEnd::free) features.push_back("a free far end");
  bool gap = c.obstacle_gap != 0;
  for (const SegmentJunction& j : c.junctions) gap = gap || j.gap != 0;
  if (gap) features.push_back("an initial gap");
  if (layers) features.push_back("segments of different E or rho");
  if (contact_junction) features.push_back("two bodies in contact");
  if (!c.obstacle) features.push_back("no rigid obstacle");
  std::string text;
  for (const std::string& f : features) text += (text.empty() ? "" : ", ") + f;
  return text;
}

namespace {

std::vector<ImpactBenchmark> make_impact_benchmarks() {
  std::vector<ImpactBenchmark> list;
  {
    // Doyen–Ern–Piperno's bouncing bar: L = 10, E = 900, ρ = 1 (c = 30), g = 10 (f = −ρg), at rest,
    // undeformed, lower end h₀ = 5 above the floor (free fall √(2h₀/g) = 1 = three transits), free at
    // both ends. Three contacts: [1, 5/3], [11/3, 13/3], [19/3, 7] (impact_closed_forms.cpp derives them).
    ImpactBenchmark b{"bouncing",
                      "Doyen-Ern-Piperno's bouncing bar (free bar falling under gravity onto a floor)",
                      "Doyen, Ern, Piperno, SIAM J. Sci. Comput. 33 (2011); NLstep EXAMPLES/01_bouncingBar",
                      "",
                      {},
                      {},
                      8.0};
    b.configuration.segments = {uniform_segment(10.0, 900.0, 1.0, -10.0)};
    b.configuration.far_end = FarEnd::free;
    b.configuration.obstacle_gap = 5.0;
    b.data.pieces = {{0.0, 10.0, {0.0}, {0.0}}};
    list.push_back(b);
  }
  {
    // Code_Aster SDNV100 in uniaxial strain: L = 0.2 m, ρ = 8000 kg/m³, the oedometric modulus of
    // E = 2e11 Pa, ν = 0.3, gap 2 mm, v⁰ = −100 m/s (toward the wall), free far end; SI units.
    const double nu = 0.3, modulus = 2e11 * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
    ImpactBenchmark b{"impacting",
                      "Code_Aster SDNV100: a bar at 100 m/s hitting a rigid wall across a 2 mm gap (SI units)",
                      "Code_Aster V5.03.100 (SDNV100)",
                      "s",
                      {},
                      {},
                      2e-4};
    b.configuration.segments = {uniform_segment(0.2, modulus, 8000.0)};
    b.configuration.far_end = FarEnd::free;
    b.configuration.obstacle_gap = 2e-3;
    b.data.pieces = {{0.0, 0.2, {0.0}, {-100.0}}};
    list.push_back(b);
  }
  {
    // The paper's bar (L = 1, c = 1, clamped at L, obstacle at 0) at rest, undeformed and touching,
    // loaded at t = 0 by f = −1 toward the obstacle: a persistent contact around the static state
    // (λ oscillates between 0 and −1 with period 2, mean −½ = the static λ).
    ImpactBenchmark b{"gravity-paper",
                      "the paper's bar suddenly pressed onto the obstacle by f = -1 (persistent contact)",
                      "this project's choice (doc/benchmarks.md sec. 5)",
                      "",
                      {},
                      {},
                      4.0};
    b.configuration.segments = {uniform_segment(1.0, 1.0, 1.0, -1.0)};
    b.data.pieces = {{0.0, 1.0, {0.0}, {0.0}}};
    list.push_back(b);
  }
  {
    // Two identical free bars, L = 10, E = ρ = 1, touching at t = 0 with velocities ±0.1 toward each
    // other: in contact for 2L/c = 20.
    ImpactBenchmark b{"two-bars",
                      "two identical free bars colliding at +-0.1 (contact between them)",
                      "Tkachuk et al., IJNME 2013, among others",
                      "",
                      {},
                      {},
                      40.0};
    b.configuration.segments = {uniform_segment(10.0, 1.0, 1.0), uniform_segment(10.0, 1.0, 1.0)};
    b.configuration.junctions = {{true, 0.0}};
    b.configuration.obstacle = false;
    b.configuration.far_end = FarEnd::free;
    b.data.pieces = {{0.0, 10.0, {0.0}, {0.1}}, {10.0, 20.0, {0.0}, {-0.1}}};
    list.push_back(b);
  }
  {
    // A two-layer bar hitting the wall: Z₁ = 2 (E = 4, ρ = 1, ℓ = 1) at the wall, Z₂ = 1 (E = ρ = 1,
    // ℓ = 1.5), free far end, gap 0.1, v⁰ = −1.
    ImpactBenchmark b{"layered",
                      "a two-layer bar (impedances 2 and 1) hitting a rigid wall across a gap",
                      "classical (transmission and reflection at an interface)",
                      "",
                      {},
                      {},
                      10.0};
    b.configuration.segments = {uniform_segment(1.0, 4.0, 1.0), uniform_segment(1.5, 1.0, 1.0)};
    b.configuration.far_end = FarEnd::free;
    b.configuration.obstacle_gap = 0.1;
    b.data.pieces = {{0.0, 1.0, {0.0}, {-1.0}}, {1.0, 2.5, {0.0}, {-1.0}}};
    list.push_back(b);
  }
  return list;
}

}  // namespace

const std::vector<ImpactBenchmark>& impact_benchmarks() {
  static const std::vector<ImpactBenchmark> list = make_impact_benchmarks();
  return list;
}

const ImpactBenchmark& impact_benchmark(const std::string& id) {
  std::string allowed;
  for (const ImpactBenchmark& b : impact_benchmarks()) {
    if (b.id == id) return b;
    allowed += (allowed.empty() ? "" : ", ") + b.id;
  }
  throw InvalidParameter("benchmark", "unknown benchmark '" + id + "' (allowed: " + allowed + ")");
}

// Prediction: at_points gives displacement's and velocity's bits at every point, whatever the order of
// the points (sorted, reversed, shuffled: the hints then start far from the piece) and at the junctions
// of a layered bar, the ends and instants on and off the breakpoints.
TEST_CASE("the field benchmarks' solution at many points: the numbers of the pointwise evaluation, bit for bit") {
  const auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  long points_checked = 0;
  for (const std::string id : {"bouncing", "impacting", "gravity-paper", "layered"}) {
    CAPTURE(id);
    const ImpactBenchmark& b = impact_benchmark(id);
    const ImpactSolution solution(b.configuration, b.data, b.final_time);
    const double length = b.configuration.length();
    std::vector<double> x;
    for (int i = 0; i <= 97; ++i) x.push_back(length * i / 97.0);
    for (const BarSegment& segment : b.configuration.segments) x.push_back(std::min(length, segment.length));
    std::vector<double> reversed(x.rbegin(), x.rend()), shuffled = x;
    std::mt19937 random(7);
    std::shuffle(shuffled.begin(), shuffled.end(), random);
    for (int n = 0; n <= 40; ++n) {
      const double t = b.final_time * n / 40.0;
      for (const std::vector<double>* points : {&x, &reversed, &shuffled}) {
        const long count = static_cast<long>(points->size());
        std::vector<double> u(points->size()), v(points->size()), u_only(points->size()), v_only(points->size());
        solution.at_points(t, points->data(), count, u.data(), v.data());
        solution.at_points(t, points->data(), count, u_only.data(), nullptr);
        solution.at_points(t, points->data(), count, nullptr, v_only.data());
        for (long k = 0; k < count; ++k) {
          const double xk = (*points)[static_cast<std::size_t>(k)];
          const double uk = solution.displacement(xk, t), vk = solution.velocity(xk, t);
          const bool ok = same(u[static_cast<std::size_t>(k)], uk) && same(v[static_cast<std::size_t>(k)], vk) &&
                          same(u_only[static_cast<std::size_t>(k)], uk) &&
                          same(v_only[static_cast<std::size_t>(k)], vk);
          if (!ok) {
            CAPTURE(xk);
            CAPTURE(t);
            CHECK(ok);
          }
          ++points_checked;
        }
      }
    }
  }
  CHECK(points_checked > 4 * 41 * 3 * 98);
}

}  // namespace mrm
