/// @file impact_lattice.cpp
/// @brief An independent solver of the chain for f = 0, the characteristic lattice, and the named
/// benchmarks' contact windows checked against it and against the closed forms.
///
/// An independent solver for f = 0: the characteristic lattice. Every segment's transit time is a
/// whole number of steps δ; the right- and left-going values at the nodes θ_i = iδ move one node per
/// step; the junctions update the emitted values by the increments of the arriving ones (welded:
/// Δr = R_A Δp + T_B Δq, Δs = T_A Δp + R_B Δq; free: Δr = Δp; clamp: r = −p); a contact updates its gap
/// by Δy = 2Δq − 2Δp and, held, emits r by the welded rule and s = p + r − g₀ − q (obstacle: s = z − g₀ − q).
/// Exact at the nodes as long as every contact event falls on a level (checked: a gap that would turn
/// negative inside a step makes the lattice inexact, and the test requires that it never happens).
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "core/problem.hpp"
#include "exact/impact_benchmarks.hpp"
#include "exact/impact_chain.hpp"

namespace mrm {

namespace {

struct Lattice {
  std::vector<double> gaps;   // z at every level, for contact 0
  std::vector<double> level;  // t_n
  bool exact = true;
};

Lattice lattice_solution(const ImpactConfiguration& config, const InitialData& data, double delta, long steps) {
  const std::size_t n = config.segments.size();
  std::vector<std::vector<double>> F(n), G(n);
  std::vector<double> z0(n, 0.0), Z(n), origin(n + 1, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const BarSegment& s = config.segments[j];
    const double c = std::sqrt(s.modulus / s.density);
    Z[j] = s.density * c;
    origin[j + 1] = origin[j] + s.length;
    const long cells = std::lround(s.length / c / delta);
    double primitive = 0;
    for (long i = 0; i <= cells; ++i) {
      const double x = origin[j] + c * delta * static_cast<double>(i);
      // u⁰ and v⁰ from the data's pieces (inside segment j: the piece containing x, the left one at its end).
      const InitialDataPiece* piece = nullptr;
      for (const InitialDataPiece& p : data.pieces)
        if (p.a <= x + 1e-12 && x <= p.b + 1e-12 && p.a >= origin[j] - 1e-12 && p.b <= origin[j + 1] + 1e-12) {
          piece = &p;
          break;
        }
      const double sigma = (x - 0.5 * (piece->a + piece->b)) / (0.5 * (piece->b - piece->a));
      const double u0 = poly::evaluate(piece->displacement, sigma);
      if (i > 0) primitive += delta * poly::evaluate(piece->velocity, 0.0);  // v⁰ constant on the piece
      F[j].push_back(0.5 * (u0 - primitive));
      G[j].push_back(0.5 * (u0 + primitive));
    }
  }
  Lattice result;
  struct Contact {
    std::size_t node;
    double gap0, z;
    bool held;
  };
  std::vector<Contact> contacts;
  if (config.obstacle) contacts.push_back({0, config.obstacle_gap, F[0][0] + G[0][0] + config.obstacle_gap, false});
  for (std::size_t j = 0; j + 1 < n && !config.junctions.empty(); ++j)
    if (config.junctions[j].contact)
      contacts.push_back({j + 1, config.junctions[j].gap,
                          F[j + 1][0] + G[j + 1][0] - F[j].back() - G[j].back() + config.junctions[j].gap, false});
  for (Contact& c : contacts) c.held = c.z <= 0.0;  // touching at t = 0: held while β ≤ 0
  result.gaps.push_back(contacts.front().z);
  result.level.push_back(0.0);
  for (long step = 1; step <= steps; ++step) {
    std::vector<double> p_old(n + 1), q_old(n + 1), r_old(n + 1), s_old(n + 1);
    for (std::size_t J = 0; J <= n; ++J) {
      if (J > 0) p_old[J] = F[J - 1].back(), r_old[J] = G[J - 1].back();
      if (J < n) q_old[J] = G[J][0], s_old[J] = F[J][0];
    }
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t i = F[j].size() - 1; i > 0; --i) F[j][i] = F[j][i - 1];
      for (std::size_t i = 0; i + 1 < G[j].size(); ++i) G[j][i] = G[j][i + 1];
    }
    for (std::size_t J = 0; J <= n; ++J) {
      const bool has_a = J > 0, has_b = J < n;
      const double p = has_a ? F[J - 1].back() : 0.0, q = has_b ? G[J][0] : 0.0;
      const double dp = has_a ? p - p_old[J] : 0.0, dq = has_b ? q - q_old[J] : 0.0;
      const double za = has_a ? Z[J - 1] : 0.0, zb = has_b ? Z[J] : 0.0;
      double r = 0, s = 0;
      Contact* contact = nullptr;
      for (Contact& c : contacts)
        if (c.node == J) contact = &c;
      if (!contact) {
        if (has_a && has_b) {
          r = r_old[J] + ((za - zb) * dp + 2 * zb * dq) / (za + zb);
          s = s_old[J] + (2 * za * dp + (zb - za) * dq) / (za + zb);
        } else if (has_a) {
          r = config.far_end == FarEnd::clamped ? -p : r_old[J] + dp;
        } else {
          s = s_old[J] + dq;
        }
      } else {
        const double dy = 2 * dq - 2 * dp, scale = 1e-13 * (std::abs(contact->z) + std::abs(dy) + 1e-300);
        bool held = contact->held && dy <= scale;  // stays held while β ≤ 0
        if (!held) {                               // free over the step (reaching 0 at its end at most)
          double z = contact->z + dy;
          if (std::abs(z) <= scale) z = 0.0;
          if (z < 0) result.exact = false;  // an event inside the step: the lattice stops being exact
          contact->z = std::max(0.0, z);
        }
        if (held) {
          r = has_a ? r_old[J] + ((za - zb) * dp + 2 * zb * dq) / (za + zb) : 0.0;
          s = (has_a ? p + r : 0.0) - contact->gap0 - q;
          contact->z = 0.0;
        } else {
          r = r_old[J] + dp;
          s = s_old[J] + dq;
          if (!has_a) s = contact->z - contact->gap0 - q;
        }
        contact->held = contact->z == 0.0;
      }
      if (has_a) G[J - 1].back() = r;
      if (has_b) F[J][0] = s;
    }
    if (!result.exact) break;  // the levels before this one are exact
    result.gaps.push_back(contacts.front().z);
    result.level.push_back(delta * static_cast<double>(step));
  }
  return result;
}

}  // namespace

TEST_CASE("the named benchmarks' contact windows against the closed forms and the characteristic lattice") {
  // Closed forms (derived in impact_closed_forms.cpp): bouncing [1, 5/3] + 8k/3; impacting [g₀/v, g₀/v + 2L/c];
  // gravity-paper held throughout; two-bars [0, 2L/c]; layered: from g₀/v = 0.1, the release from the lattice.
  const double c_sdnv = std::sqrt(2e11 * 0.7 / (1.3 * 0.4) / 8000);
  const std::vector<std::pair<std::string, std::vector<std::array<double, 2>>>> expected{
      {"bouncing", {{1.0, 5.0 / 3}, {11.0 / 3, 13.0 / 3}, {19.0 / 3, 7.0}}},
      {"impacting", {{2e-5, 2e-5 + 0.4 / c_sdnv}}},
      {"gravity-paper", {{0.0, 4.0}}},
      {"two-bars", {{0.0, 20.0}}}};
  for (const auto& [id, windows] : expected) {
    CAPTURE(id);
    const ImpactBenchmark& b = impact_benchmark(id);
    const std::vector<ContactInterval> w = exact_contact_windows(b.configuration, b.data, b.final_time);
    REQUIRE(w.size() == windows.size());
    for (std::size_t k = 0; k < w.size(); ++k) {
      CHECK(std::abs(w[k].start - windows[k][0]) <= 1e-12 * b.final_time);
      CHECK(std::abs(w[k].end - windows[k][1]) <= 1e-12 * b.final_time);
    }
  }
  CHECK_THROWS_WITH_AS(impact_benchmark("nope"), doctest::Contains("allowed: bouncing, impacting"), InvalidParameter);
  CHECK(configuration_features(impact_benchmark("bouncing").configuration) ==
        "a load f, a free far end, an initial gap");
  CHECK(configuration_features(impact_benchmark("two-bars").configuration) ==
        "a free far end, two bodies in contact, no rigid obstacle");
  // The lattice (δ = 0.1 for layered and two-bars, whose transit times are multiples of it): the gap at
  // every level, hence the windows, agree.
  for (const std::string id : {"layered", "two-bars"}) {
    CAPTURE(id);
    const ImpactBenchmark& b = impact_benchmark(id);
    const ImpactSolution solution(b.configuration, b.data, b.final_time);
    const Lattice lattice = lattice_solution(b.configuration, b.data, 0.1, std::lround(b.final_time / 0.1));
    CHECK(lattice.exact);
    double d = 0;
    for (std::size_t n = 0; n < lattice.level.size(); ++n)
      d = std::max(d, std::abs(solution.gap(0, std::min(b.final_time, lattice.level[n])) - lattice.gaps[n]));
    CAPTURE(d);
    CHECK(d <= 1e-12);
  }
  // Three layers clamped at the far end hitting the wall (the lattice is exact up to the second impact,
  // which falls between levels), and two bars of unequal impedances with a gap between them.
  ImpactConfiguration three;
  three.segments = {uniform_segment(0.4, 4.0, 1.0), uniform_segment(0.3, 1.0, 1.0), uniform_segment(0.5, 1.0, 4.0)};
  three.obstacle_gap = 0.1;
  InitialData layered_data;
  layered_data.pieces = {{0.0, 0.4, {0.0}, {-1.0}}, {0.4, 0.7, {0.0}, {-1.0}}, {0.7, 1.2, {0.0}, {-1.0}}};
  ImpactConfiguration unequal;
  unequal.segments = {uniform_segment(1.0, 1.0, 1.0), uniform_segment(3.0, 9.0, 1.0)};
  unequal.junctions = {{true, 0.05}};
  unequal.obstacle = false;
  unequal.far_end = FarEnd::free;
  InitialData unequal_data;
  unequal_data.pieces = {{0.0, 1.0, {0.0}, {0.2}}, {1.0, 4.0, {0.0}, {-0.05}}};
  for (const auto& [config, data, horizon, windows] :
       {std::tuple<ImpactConfiguration, InitialData, double, double>{three, layered_data, 20.0, 4.0},
        {unequal, unequal_data, 20.0, 20.0}}) {
    const ImpactSolution solution(config, data, horizon);
    const Lattice lattice = lattice_solution(config, data, 0.1, std::lround(horizon / 0.1));
    CAPTURE(lattice.level.back());
    CHECK(lattice.level.back() >= windows - 1e-9);  // exact at least that far
    CHECK(solution.contact_windows(0).at(0).end < windows);
    double d = 0;
    for (std::size_t n = 0; n < lattice.level.size(); ++n)
      d = std::max(d, std::abs(solution.gap(0, std::min(horizon, lattice.level[n])) - lattice.gaps[n]));
    CAPTURE(d);
    CHECK(d <= 1e-12);
  }
}

}  // namespace mrm
