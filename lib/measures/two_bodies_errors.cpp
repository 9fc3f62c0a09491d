/// @file two_bodies_errors.cpp
/// @brief The two-bodies run (two_bodies.hpp) measured against the exact two-bars solution
/// (impact_solution.hpp): its error and its release time converge at the observed orders.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include <doctest/doctest.h>

#include "exact/impact_solution.hpp"
#include "measures/errors.hpp"
#include "time/two_bodies.hpp"

namespace mrm {

namespace {

// Body k of length ℓ with N elements, free far end, the redistribution `mass`, data in its own frame at
// rest and undeformed with velocity ẇ = `velocity` (negative: toward the contact).
[[maybe_unused]] TwoBodyPart free_body(double length, Index elements, const MassRedistribution& mass, double velocity) {
  TwoBodyPart p;
  p.mesh = with_far_end(UniformMesh(length, elements), FarEnd::free);
  p.redistribution = mass;
  p.displacement = Eigen::VectorXd::Zero(p.mesh.unknowns());
  p.velocity = Eigen::VectorXd::Constant(p.mesh.unknowns(), velocity);
  return p;
}

// The two-bars benchmark (impact_benchmark: two free bars ℓ = 10, E = ρ = 1, ±0.1, touching at t = 0) on N
// elements per bar, Crank–Nicolson with `mass`, Δt = h/2, to T = 40: the larger of the two bodies'
// relative error of u in L²(0,T; L²) and the release time (the indicator's crossing to s > 0).
struct TwoBarsRun {
  double error, release;
};
[[maybe_unused]] TwoBarsRun two_bars_run(Index elements, const MassRedistribution& mass) {
  const ImpactBenchmark& bench = impact_benchmark("two-bars");
  const double length = bench.configuration.segments[0].length, dt = 0.5 * length / static_cast<double>(elements);
  const Index steps = std::lround(bench.final_time / dt);
  const auto chain = std::make_shared<const ImpactSolution>(bench.configuration, bench.data, bench.final_time + dt);
  std::array<TwoBodyPart, 2> parts;
  std::array<std::shared_ptr<const TwoBodyReference>, 2> exact;
  for (int k = 0; k < 2; ++k) {
    exact[k] = std::make_shared<const TwoBodyReference>(chain, k);
    parts[k] = free_body(length, elements, mass, 0.0);
    for (Index i = 0; i < parts[k].mesh.unknowns(); ++i) {
      parts[k].displacement[i] = exact[k]->displacement(parts[k].mesh.x(i), 0.0);
      parts[k].velocity[i] = exact[k]->velocity(parts[k].mesh.x(i), 0.0);
    }
  }
  TwoBodySimulation run(parts, 0.0, dt);
  std::array<ErrorAccumulator, 2> errors{ErrorAccumulator(run.mesh(0), exact[0]),
                                         ErrorAccumulator(run.mesh(1), exact[1])};
  double release = -1, previous = run.indicator();
  for (Index n = 0; n <= steps; ++n) {
    for (int k = 0; k < 2; ++k) {
      const double t = run.time();
      errors[k].add(
          Sample{n, t, &run.displacement(k), t, &run.velocity(k), true, t, run.multiplier(), t, run.energy()});
    }
    const double s = run.indicator();
    if (release < 0 && n > 0 && previous <= 0 && s > 0) release = run.time() - dt * s / (s - previous);
    previous = s;
    if (n < steps) run.step();
  }
  return {std::max(errors[0].relative().u_L2L2, errors[1].relative().u_L2L2), release};
}
}  // namespace

TEST_CASE("two bodies: agreement with the exact two-bars solution at the observed order") {
  // The prediction: the run converges to the chain's exact solution (lib/exact/impact_solution.cpp), the error
  // of u in L²(0,T; L²) and the release time's (exact: 2ℓ/c = 20) at some orders p. The tolerance comes
  // from the observed orders: p̂ from N = 80, 160; the error at N = 320 must lie within the extrapolation
  // e₁₆₀ 2^(−p̂), widened by the observed change of the local order, 2^|p₀ − p̂| (p₀ from N = 40, 80),
  // and p̂ must be positive. Measured (bar1d --benchmark two-bars, N = 10 … 640): Mod 1 and Mod 2 are in
  // their regime from N = 40 on for u (orders 0.2–0.5 and 0.7), Mod 1 for the release (0.5–0.7, near the
  // h^{2/3} of a front smeared over (h²t)^{1/3} that triggers it: fig_benchmark_convergence's conjecture).
  // Mod 3 is pre-asymptotic up to N = 320 (its u error 0.0015, 0.0029, 0.0042, 0.0037 at N = 40 … 320;
  // its release error changes sign between N = 20 and 40, an O(h) lead and a later negative term), and
  // Mod 2's release likewise (0.025, 0.024, 0.022 at N = 80 … 320): they are checked by the symmetry
  // test above (the one body against a wall, step for step) and shown in fig_benchmark_convergence.
  struct Case {
    MassRedistribution mass;
    bool release;  // whether the release time is in its regime over these meshes
  };
  for (const Case& c : {Case{mod1(), true}, Case{mod2(), false}}) {
    std::array<TwoBarsRun, 4> r{};
    for (int l = 0; l < 4; ++l) r[l] = two_bars_run(Index{40} << l, c.mass);
    const auto check = [&](const char* what, double e0, double e1, double e2, double e3) {
      const double p0 = std::log2(e0 / e1), p = std::log2(e1 / e2);
      const double bound = e2 * std::exp2(-p) * std::exp2(std::abs(p0 - p));
      CAPTURE(c.mass.name);
      CAPTURE(what);
      CAPTURE(p0);
      CAPTURE(p);
      CAPTURE(e3);
      CAPTURE(bound);
      CHECK(p > 0.25);
      CHECK(e3 <= bound);
    };
    check("u in L2(L2)", r[0].error, r[1].error, r[2].error, r[3].error);
    if (c.release)
      check("release time", std::abs(r[0].release - 20), std::abs(r[1].release - 20), std::abs(r[2].release - 20),
            std::abs(r[3].release - 20));
  }
}

}  // namespace mrm
