/// @file convergence.cpp
/// @brief Observed orders of convergence and the comparison with a reference run: mathematics.md §5.
///
/// Observed order. If an error behaves like e(s) ≈ C s^p in a step s (the mesh size h, or the time
/// step Δt), then log e = log C + p log s is a straight line, and the observed order p is the slope of
/// the least-squares line through the points (log s_k, log e_k). With more than two points this
/// averages out the wobble of the individual ratios log(e_k/e_{k+1}) / log(s_k/s_{k+1}) (in contact
/// problems the errors are rarely monotone in h), and the residuals give a standard error of the slope:
/// a large one says that the errors do not follow a power law on the range fitted. GSL's
/// gsl_fit_linear does the fit; its error handler, which aborts by default, is switched off and its
/// return code checked.
#include "studies/convergence.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include <doctest/doctest.h>

#include "batched/batched_step.hpp"

namespace mrm {

OrderFit fit_order(const std::vector<double>& steps, const std::vector<double>& errors) {
  if (steps.size() != errors.size()) throw std::invalid_argument("fit_order: steps and errors differ in size");
  const std::size_t n = steps.size();
  if (n < 2) throw std::invalid_argument("fit_order: at least two points are needed");
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(std::isfinite(steps[k]) && steps[k] > 0) || !(std::isfinite(errors[k]) && errors[k] > 0))
      throw std::invalid_argument("fit_order: steps and errors must be positive and finite (point " +
                                  std::to_string(k) + ")");
    x[k] = std::log(steps[k]);
    y[k] = std::log(errors[k]);
  }
  bool distinct = false;
  for (std::size_t k = 1; k < n; ++k) distinct = distinct || x[k] != x[0];
  if (!distinct) throw std::invalid_argument("fit_order: the steps are all equal");

  gsl_set_error_handler_off();
  double c0 = 0, c1 = 0, cov00 = 0, cov01 = 0, cov11 = 0, sumsq = 0;
  const int status = gsl_fit_linear(x.data(), 1, y.data(), 1, n, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
  if (status != GSL_SUCCESS)
    throw std::runtime_error(std::string("fit_order: gsl_fit_linear failed: ") + gsl_strerror(status));
  // gsl_fit_linear estimates the variance of the residuals as sumsq/(n − 2); with two points the
  // line is exact and the standard error is zero.
  return {c1, c0, n > 2 ? std::sqrt(cov11) : 0.0, n};
}

TEST_CASE("the least-squares fit recovers a known order") {
  // Exact power laws: the slope and the constant come back to round-off.
  for (const double p : {0.5, 1.0, 1.5, 2.0}) {
    std::vector<double> s, e;
    for (double h = 1.0 / 8; h > 1.0 / 5000; h /= 2) {
      s.push_back(h);
      e.push_back(3.0 * std::pow(h, p));
    }
    const OrderFit fit = fit_order(s, e);
    CAPTURE(p);
    CHECK(std::abs(fit.order - p) < 1e-12);
    CHECK(std::abs(fit.log_constant - std::log(3.0)) < 1e-11);
    CHECK(fit.order_std_error < 1e-12);
    CHECK(fit.points == s.size());
  }
  // A power law times a factor alternating 1.2, 1/1.2 (an error that wobbles around its trend): the
  // fitted slope is the textbook one, cov(log s, log e)/var(log s), computed here directly, and it is
  // off the trend's slope 1 with a non-zero standard error.
  std::vector<double> s, e;
  for (int k = 0; k < 4; ++k) {
    s.push_back(std::pow(2.0, -k));
    e.push_back(std::pow(2.0, -k) * (k % 2 == 0 ? 1.2 : 1 / 1.2));
  }
  double mx = 0, my = 0;
  for (int k = 0; k < 4; ++k) mx += std::log(s[k]) / 4, my += std::log(e[k]) / 4;
  double sxy = 0, sxx = 0;
  for (int k = 0; k < 4; ++k) {
    sxy += (std::log(s[k]) - mx) * (std::log(e[k]) - my);
    sxx += (std::log(s[k]) - mx) * (std::log(s[k]) - mx);
  }
  const OrderFit wobbly = fit_order(s, e);
  CHECK(std::abs(wobbly.order - sxy / sxx) < 1e-12);
  CHECK(std::abs(wobbly.order - 1.0) > 0.08);  // the wobble is seen (0.4 log 1.2 / log 2 = 0.105) ...
  CHECK(wobbly.order_std_error > 0.05);        // ... and reported
}

TEST_CASE("the order fit rejects data it cannot fit") {
  CHECK_THROWS_AS(fit_order({0.1}, {0.2}), std::invalid_argument);
  CHECK_THROWS_AS(fit_order({0.1, 0.05}, {0.2}), std::invalid_argument);
  CHECK_THROWS_AS(fit_order({0.1, 0.05}, {0.2, 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(fit_order({0.1, -0.05}, {0.2, 0.1}), std::invalid_argument);
  CHECK_THROWS_AS(fit_order({0.1, 0.1}, {0.2, 0.1}), std::invalid_argument);
  CHECK_THROWS_AS(fit_order({0.1, 0.05}, {0.2, std::nan("")}), std::invalid_argument);
}

// Comparison with a reference run. To isolate the error of the time discretisation at a fixed mesh,
// a run with step Δt is compared with a reference run of the same mesh, mass and scheme with a much
// smaller step Δt_ref = Δt/m (m an integer), at the instants t_n = nΔt the two share. The measures
// are those of mathematics.md §5 with the reference in place of the interpolant of the exact solution:
// ‖e‖²_L² = eᵀMe and |e|²_H¹ = eᵀSe with the consistent P1 matrices, the maximum over the common
// instants for L∞ in time and the trapezoidal rule over them for L² in time; every measure relative to
// the same norm of the reference.

ReferenceComparison::ReferenceComparison(const UniformMesh& mesh)
    : mass_(p1_mass(mesh)), stiffness_(p1_stiffness(mesh)), difference_(mesh.unknowns()) {}

ReferenceComparison::Level ReferenceComparison::measure(const Sample& run, const Sample& reference) {
  return measure(run, own_lanes(run), reference, own_lanes(reference));
}

ReferenceComparison::Level ReferenceComparison::measure(const Sample& run, const LaneVectors& run_lanes,
                                                        const Sample& reference, const LaneVectors& reference_lanes) {
  constexpr double tolerance = 1e-9;
  if (std::abs(run.time - reference.time) > tolerance ||
      std::abs(run.velocity_time - reference.velocity_time) > tolerance ||
      (run.has_multiplier && reference.has_multiplier &&
       std::abs(run.multiplier_time - reference.multiplier_time) > tolerance))
    throw std::invalid_argument("ReferenceComparison: the two samples are not at the same instant (t = " +
                                std::to_string(run.time) + " and " + std::to_string(reference.time) + ")");
  if (run.displacement->size() != mass_.size() || reference.displacement->size() != mass_.size())
    throw std::invalid_argument("ReferenceComparison: the runs are not on the comparison's mesh");
  Level level;
  level.time = run.time;
  level.velocity_time = run.velocity_time;
  level.multiplier_time = run.multiplier_time;
  level.has_multiplier = run.has_multiplier && reference.has_multiplier;
  // xᵀAx by Tridiagonal::form (Tridiagonal::bilinear(x, x)'s arithmetic, bit for bit, in one pass without
  // a product vector) on the difference, formed entry by entry, and on the reference where it is (with
  // its stride: the same bits).
  const Index n = mass_.size();
  const std::size_t rs = run_lanes.stride, fs = reference_lanes.stride;
  const auto difference = [&](const double* a, const double* b) {
    for (Index i = 0; i < n; ++i)
      difference_[i] = a[static_cast<std::size_t>(i) * rs] - b[static_cast<std::size_t>(i) * fs];
  };
  const double* u_ref = reference_lanes.displacement;
  difference(run_lanes.displacement, u_ref);
  level.u_l2 = {mass_.form(difference_.data(), 1), mass_.form(u_ref, fs)};
  level.u_h1 = {stiffness_.form(difference_.data(), 1), stiffness_.form(u_ref, fs)};
  level.u0 = {std::pow(difference_[0], 2), u_ref[0] * u_ref[0]};
  const double* v_ref = reference_lanes.velocity;
  difference(run_lanes.velocity, v_ref);
  level.v_l2 = {mass_.form(difference_.data(), 1), mass_.form(v_ref, fs)};
  if (level.has_multiplier)
    level.lambda = {std::pow(run.multiplier - reference.multiplier, 2), reference.multiplier * reference.multiplier};
  return level;
}

void ReferenceComparison::add(const Level& level) {
  u_l2_.add(level.time, level.u_l2[0], level.u_l2[1]);
  u_h1_.add(level.time, level.u_h1[0], level.u_h1[1]);
  u0_.add(level.time, level.u0[0], level.u0[1]);
  v_l2_.add(level.velocity_time, level.v_l2[0], level.v_l2[1]);
  if (level.has_multiplier) lambda_.add(level.multiplier_time, level.lambda[0], level.lambda[1]);
}

std::array<double, 8> ReferenceComparison::relative() const {
  return ErrorAccumulator::values(relative_norms(u0_, lambda_, u_l2_, u_h1_, v_l2_));
}

namespace {

// Runs Crank–Nicolson with Δt = m Δt_ref in lockstep with a reference run of step Δt_ref on the
// benchmark and returns the relative differences at the common instants.
[[maybe_unused]] std::array<double, 8> crank_nicolson_against_reference(Index elements, double dt_ref, Index ratio_m,
                                                                        double final_time) {
  const UniformMesh mesh(1.0, elements);
  SchemeParameters p;
  p.scheme = Scheme::crank_nicolson;
  BarSimulation reference(benchmark_problem(), mesh, mod3(), p, dt_ref);
  BarSimulation run_coarse(benchmark_problem(), mesh, mod3(), p, static_cast<double>(ratio_m) * dt_ref);
  ReferenceComparison comparison(mesh);
  comparison.add(run_coarse.sample(), reference.sample());
  const Index steps = steps_to_reach(final_time, static_cast<double>(ratio_m) * dt_ref);
  for (Index n = 0; n < steps; ++n) {
    for (Index k = 0; k < ratio_m; ++k) reference.step();
    run_coarse.step();
    comparison.add(run_coarse.sample(), reference.sample());
  }
  return comparison.relative();
}

}  // namespace

TEST_CASE("a run compared with itself as reference has no error, and the error shrinks with the step") {
  const double dt_ref = 1.0 / 32 / 128;
  const std::array<double, 8> same = crank_nicolson_against_reference(32, dt_ref, 1, 3.0);
  for (double e : same) CHECK(e == 0.0);
  // Before the first impact (t < 1) the solution of the semi-discrete problem is smooth in time and
  // Crank–Nicolson is second order once Δt resolves the highest frequency of the mesh, about 2/h:
  // from Δt = h/8 to h/16 every difference is divided by about 4 (at least 3 here).
  const std::array<double, 8> coarse = crank_nicolson_against_reference(32, dt_ref, 16, 0.75);
  const std::array<double, 8> fine = crank_nicolson_against_reference(32, dt_ref, 8, 0.75);
  for (std::size_t k = 0; k < 8; ++k) {
    if (k == 1) continue;  // λ ≡ 0 before the impact: both differences are zero
    CAPTURE(k);
    CAPTURE(coarse[k]);
    CAPTURE(fine[k]);
    CHECK(coarse[k] > 0.0);
    CHECK(fine[k] < coarse[k] / 3);
  }
  // Samples of different instants are refused.
  const UniformMesh mesh(1.0, 4);
  ReferenceComparison comparison(mesh);
  const Eigen::VectorXd u = Eigen::VectorXd::Ones(4);
  CHECK_THROWS_AS(comparison.add({1, 0.5, &u, 0.5, &u, true, 0.5, 0.0, 0.5, 0.1},
                                 {1, 0.25, &u, 0.25, &u, true, 0.25, 0.0, 0.25, 0.1}),
                  std::invalid_argument);
}

// Crank–Nicolson's error estimate in time for the velocity (mathematics.md §7, §9). At fixed h the
// semi-discrete problem is a Lipschitz ODE whose right-hand side switches at the impact and the
// release; the trapezoidal rule keeps its second order across them, and with the massless node's
// velocity from its algebraic row (schemes.cpp) nothing but that order is left: from Δt = h/64 to
// h/128 (h = 1/32, one period, reference h/2048) the velocity errors in L∞(L²) and L²(L²) are divided
// by 4, local order 2 within ±0.25. (The recovery V₀ⁿ⁺¹ = 2(u₀ⁿ⁺¹ − u₀ⁿ)/Δt − V₀ⁿ stalled them at
// 0.1 to 0.2 whatever Δt.) Coarser steps can land a level of both runs inside the window between
// their impacts (the first impact falls at t = L + O(h²) for Mod 3, a level of every run): there V₀
// is V₁ in one run and 0 in the other, and the sampled norm sees an O(1) jump at that level.
TEST_CASE("Crank-Nicolson's velocity converges at order 2 in dt at fixed h") {
  const double h = 1.0 / 32, dt_ref = h / 2048;
  const std::array<double, 8> coarse = crank_nicolson_against_reference(32, dt_ref, 32, 3.0);
  const std::array<double, 8> fine = crank_nicolson_against_reference(32, dt_ref, 16, 3.0);
  for (const std::size_t k : {std::size_t{4}, std::size_t{7}}) {
    CAPTURE(ErrorAccumulator::names[k]);
    CAPTURE(coarse[k]);
    CAPTURE(fine[k]);
    CHECK(std::abs(std::log2(coarse[k] / fine[k]) - 2) < 0.25);
    CHECK(fine[k] < 1e-3);
  }
}

/// @file convergence.cpp
/// ## A comparison read in the lanes
///
/// measure(run, run_lanes, reference, reference_lanes) forms the same differences entry by entry and the
/// same quadratic forms (Tridiagonal::form with a stride: the same bits), so it gives the bits of
/// measure(run, reference) on the vectors copied out. Checked on two runs of a batch (Δt and Δt/2, the
/// coarser at every other batch step, as repro/time_family.cpp steps them), past the first impact, on
/// every vector target, and on a run stepped alone (stride 1) against the finer lane: every field of every
/// level the same bits; and the lanes are really strided.
TEST_CASE("a comparison read in a batch's lanes is bitwise the comparison of the copied-out vectors") {
  const UniformMesh mesh(1.0, 20);
  SchemeParameters p;
  const auto bits = [](const ReferenceComparison::Level& a, const ReferenceComparison::Level& b) {
    return std::memcmp(&a.u_l2, &b.u_l2, sizeof a.u_l2) == 0 && std::memcmp(&a.u_h1, &b.u_h1, sizeof a.u_h1) == 0 &&
           std::memcmp(&a.u0, &b.u0, sizeof a.u0) == 0 && std::memcmp(&a.v_l2, &b.v_l2, sizeof a.v_l2) == 0 &&
           std::memcmp(&a.lambda, &b.lambda, sizeof a.lambda) == 0 && a.has_multiplier == b.has_multiplier;
  };
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    std::vector<BarSimulation> two;
    const double dt = 0.25 * mesh.h();
    two.emplace_back(benchmark_problem(), mesh, mod3(), p, dt);
    two.emplace_back(benchmark_problem(), mesh, mod3(), p, 2 * dt);
    BatchedSimulation pair(std::move(two));
    REQUIRE(pair.batched_runs() == 2);
    // And a run on its own vectors (stride 1) against the lane of the finer one.
    BarSimulation alone(benchmark_problem(), mesh, mod1(), p, 2 * dt);
    ReferenceComparison lanes_way(mesh), copy_way(mesh), alone_lanes(mesh), alone_copy(mesh);
    bool same = true, strided = false;
    for (Index k = 1; k <= 240; ++k) {  // to t = 1.2, past the first impact
      pair.step(k % 2 != 0 ? std::vector<char>{1, 0} : std::vector<char>{1, 1});
      if (k % 2 != 0) continue;
      alone.step();
      LaneVectors fine{}, coarse{};
      const Sample a = pair.sample(0, fine), b = pair.sample(1, coarse), c = alone.sample();
      strided = strided || (fine.stride > 1 && coarse.stride > 1);
      const ReferenceComparison::Level in_lanes = lanes_way.measure(b, coarse, a, fine);
      const ReferenceComparison::Level own = alone_lanes.measure(c, own_lanes(c), a, fine);
      const Sample ca = pair.run(0).sample(), cb = pair.run(1).sample();
      same = same && bits(in_lanes, copy_way.measure(cb, ca)) && bits(own, alone_copy.measure(c, ca));
    }
    CHECK(strided);
    CHECK(same);
  }
  use_batch_target(0);
}

}  // namespace mrm
