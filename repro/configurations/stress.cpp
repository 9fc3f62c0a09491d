/// @file configurations/stress.cpp
/// @brief The histories a run keeps for the contact stresses, and their measures (TV ratio, errors).
#include "configurations/stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <utility>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "parallel.hpp"
#include "time/two_bodies.hpp"
#include "configurations.hpp"

namespace mrm::repro {

// The window stresses average the multiplier over width_factor · W(h, t_n) at each instant
// (contact_stress.cpp §2; 8 W for the registry's stresses);
// the multiplier's instants are uniformly spaced by Δt (one per level, or per step for the staggered
// schemes). The recovered strain is projected onto λ ≤ 0 when it is recorded.
std::vector<double> StressHistory::values(ContactStress stress) const {
  if (stress == ContactStress::multiplier) return multiplier;
  if (stress == ContactStress::recovered) return recovered;
  if (stress == ContactStress::gated) return gated_stress(multiplier, values(ContactStress::window));
  std::vector<double> clamped(time.size());
  std::transform(time.begin(), time.end(), clamped.begin(), [](double t) { return std::max(0.0, t); });
  return window_average(multiplier, spacing, smearing_widths(h, std::move(clamped), order, width_factor),
                        stress == ContactStress::box ? WindowKernel::box : WindowKernel::spline);
}
const std::vector<double>& StressHistory::instants(ContactStress stress) const {
  return stress == ContactStress::recovered ? recovered_time : time;
}
const std::vector<double>& StressHistory::exact_values(ContactStress stress) const {
  return stress == ContactStress::recovered ? exact_at_levels : exact;
}

StressMeasures stress_measures(const StressHistory& history, ContactStress stress) {
  const std::vector<double> v = history.values(stress);
  const std::vector<double>& t = history.instants(stress);
  const std::vector<double>& e = history.exact_values(stress);
  StressMeasures m;
  const double tv_exact = total_variation(e);
  if (!(tv_exact > 0)) throw std::invalid_argument("stress_measures: the exact stress does not vary over the run");
  m.tv_ratio = total_variation(v) / tv_exact;
  double error = 0, norm = 0, largest = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double dt = t[i] - t[i - 1];
    error += 0.5 * dt * ((v[i] - e[i]) * (v[i] - e[i]) + (v[i - 1] - e[i - 1]) * (v[i - 1] - e[i - 1]));
    norm += 0.5 * dt * (e[i] * e[i] + e[i - 1] * e[i - 1]);
  }
  for (double x : e) largest = std::max(largest, std::abs(x));
  m.l2_error = std::sqrt(error / norm);
  // The exact status changes: the ends of the maximal runs of instants where λ < 0.
  std::vector<double> changes;
  double shortest = std::numeric_limits<double>::infinity(), start = 0;
  const double tiny = 1e-12 * largest;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const bool in = e[i]<-tiny, before = i> 0 && e[i - 1] < -tiny;
    if (in && !before) start = t[i], changes.push_back(t[i]);
    if (!in && before) changes.push_back(t[i]), shortest = std::min(shortest, t[i] - start);
  }
  if (!changes.empty() && e.back() < -tiny) shortest = std::min(shortest, t.back() - start);
  const double away = 0.25 * shortest;
  std::size_t next = 0;  // the first change at or after t[i] − away
  for (std::size_t i = 0; i < v.size(); ++i) {
    while (next < changes.size() && changes[next] < t[i] - away) ++next;
    if (next < changes.size() && changes[next] <= t[i] + away) continue;
    m.max_error_away = std::max(m.max_error_away, std::abs(v[i] - e[i]) / largest);
  }
  return m;
}

TEST_CASE("stress_measures: an exact history scores 1, 0, 0, and an error next to a jump is not away from it") {
  // λ = −½ on [1, 2), 0 elsewhere, sampled at τ = 0.01 on [0, 3]: the shortest window is 1, so ε = ¼.
  StressHistory h;
  h.h = 0.02, h.spacing = 0.01;
  for (int n = 0; n <= 300; ++n) {
    const double t = 0.01 * n;
    h.time.push_back(t);
    h.exact.push_back(t >= 1 && t < 2 ? -0.5 : 0.0);
  }
  h.multiplier = h.exact;
  StressMeasures m = stress_measures(h, ContactStress::multiplier);
  CHECK(m.tv_ratio == 1.0);
  CHECK(m.l2_error == 0.0);
  CHECK(m.max_error_away == 0.0);
  h.multiplier[110] -= 0.1;  // t = 1.1: within ¼ of the jump at 1
  m = stress_measures(h, ContactStress::multiplier);
  CHECK(m.tv_ratio == doctest::Approx(1.2));  // TV 1 + 2 · 0.1 against 1
  CHECK(m.max_error_away == 0.0);
  h.multiplier[150] -= 0.1;  // t = 1.5: away from both jumps; relative to max|λ| = ½
  CHECK(stress_measures(h, ContactStress::multiplier).max_error_away == doctest::Approx(0.2));
}

TEST_CASE("a run reports the stress it is asked for: the window bounds what the multiplier does not") {
  // One run, two stresses: the multiplier's ratio is the one run_configuration has always measured, the
  // window's is its own (contact_stress.cpp §2: bounded, so below the multiplier's wake-dominated one),
  // and the window's L² error is the same order as the multiplier's.
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 100, 0.5, 30.0);
  const Measures raw = run_configuration(c);
  c.stress = ContactStress::window;
  const Measures windowed = run_configuration(c);
  REQUIRE(raw.lambda_tv_ratio);
  REQUIRE(windowed.lambda_tv_ratio);
  CHECK(!raw.stress_history);
  REQUIRE(windowed.stress_history);
  CHECK(windowed.stress == ContactStress::window);
  CHECK(stress_measures(*windowed.stress_history, ContactStress::multiplier).tv_ratio ==
        doctest::Approx(*raw.lambda_tv_ratio).epsilon(1e-12));
  CHECK(*windowed.lambda_tv_ratio < 0.5 * *raw.lambda_tv_ratio);
  const StressMeasures w = stress_measures(*windowed.stress_history, ContactStress::window);
  const double raw_l2 = stress_measures(*windowed.stress_history, ContactStress::multiplier).l2_error;
  CHECK(w.l2_error < 2 * raw_l2);  // the same order W^{1/2}
  CHECK(w.l2_error > 0.25 * raw_l2);
  CHECK(windowed.errors.lambda_L2 == raw.errors.lambda_L2);  // the scheme's measures are unchanged
  // Each run's stress error is its own stress's: the multiplier's is the error accumulator's λ error,
  // the same trapezoidal sum over the same samples as the history's (to round-off in the sums' order).
  REQUIRE(raw.stress_l2_error);
  REQUIRE(windowed.stress_l2_error);
  CHECK(*raw.stress_l2_error == raw.errors.lambda_L2);
  CHECK(*raw.stress_l2_error == doctest::Approx(raw_l2).epsilon(1e-12));
  CHECK(*windowed.stress_l2_error == w.l2_error);
}

}  // namespace mrm::repro
