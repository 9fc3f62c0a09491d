// Phase diagnostics: the impact times of a run and their drift (mathematics.md §8).
//
// The period law predicts that a redistribution shifts the period of the benchmark by
// ΔP = 2δm_loc + (3/2)δm_glob (period_law.cpp): the impacts drift linearly in time, by −4h/3 (Mod 1),
// −h/3 (Mod 2) and 0 (Mod 3) per period. This file measures that drift on any run.
//
// The contact indicator. A level is in contact when its contact constraint is active. With a
// massless contact node the contact row gives u₀ = max(0, u₁ + hF₀), λ = min(0, F₀ + u₁/h)
// (contact.cpp), so
//
//     g := u₀ + h λ = u₁ + h F₀          (free: λ = 0, u₀ = u₁ + hF₀; contact: u₀ = 0, hλ = u₁ + hF₀),
//
// one continuous function of the state that is positive exactly while the gap is open and ≤ 0
// exactly while the contact is active: the gap the node would have without the obstacle. This holds
// for every scheme whose λ belongs to the displacement's instant (the algebraic contact row). For a
// multiplier of another instant (the literal Paoli–Schatzman row, λⁿ beside Uⁿ⁺¹) the indicator is
// u₀ alone, which is 0 at a contact level: the estimator below then returns the first contact level,
// late by less than one step.
//
// The estimator. An impact is a level n with gₙ ≤ 0 that follows a level with gₙ₋₁ > 0; its time is
// the zero of the line through (tₙ₋₁, gₙ₋₁) and (tₙ, gₙ),
//
//     t̂ = tₙ₋₁ + (tₙ − tₙ₋₁) gₙ₋₁ / (gₙ₋₁ − gₙ),
//
// exact when g is affine between the two levels (the free flight before an impact moves the end at a
// constant speed on the benchmark), and in general within the step. A release is located the same
// way. Some discretisations chatter (the contact opens for a step or two and closes again, e.g. the
// consistent mass): a contact that starts less than a given interval after the previous one was
// released belongs to that contact and is not a new impact (the benchmark's free flights last 2L
// between contacts; the programs pass L).
//
// The drift. Pair the k-th measured impact t̂ₖ with the k-th exact one tₖ (in order, so that a drift
// of more than half a period is still followed) and write eₖ = t̂ₖ − tₖ: negative means early. The
// first impact error is e₀; the drift per period is P times the least-squares slope of eₖ against tₖ,
//
//     drift = P · Σ (tₖ − t̄)(eₖ − ē) / Σ (tₖ − t̄)²,
//
// in time units per period: a run whose impacts recur with the period P_h has eₖ = e₀ + k (P_h − P),
// tₖ = t₀ + kP, and drift = P_h − P exactly. It needs two impacts at least.
#include "phase.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

#include "mass_redistribution.hpp"
#include "period_law.hpp"

namespace mrm {

double contact_indicator(const Sample& sample, double h) {
  const double u0 = (*sample.displacement)[0];
  if (sample.has_multiplier && sample.multiplier_time == sample.time) return u0 + h * sample.multiplier;
  return u0;
}

ImpactDetector::ImpactDetector(double minimum_free_interval) : minimum_free_interval_(minimum_free_interval) {
  if (!(std::isfinite(minimum_free_interval) && minimum_free_interval >= 0))
    throw std::invalid_argument("impact detector: the minimum free interval must be finite and >= 0");
}

void ImpactDetector::add(double time, double indicator) {
  if (!std::isfinite(time) || !std::isfinite(indicator))
    throw std::invalid_argument("impact detector: non-finite time or contact indicator at t = " + std::to_string(time));
  if (started_ && !(time > time_))
    throw std::invalid_argument("impact detector: the times must increase (got " + std::to_string(time) + " after " +
                                std::to_string(time_) + ")");
  const bool contact = indicator <= 0;
  if (!started_) {
    in_contact_ = contact_seen_ = contact;
  } else if (contact != in_contact_) {
    const double crossing = time_ + (time - time_) * indicator_ / (indicator_ - indicator);
    if (contact) {
      if (!contact_seen_ || crossing - release_ >= minimum_free_interval_) impacts_.push_back(crossing);
      contact_seen_ = true;
    } else {
      release_ = crossing;
    }
    in_contact_ = contact;
  }
  started_ = true;
  time_ = time;
  indicator_ = indicator;
}

PhaseMeasures phase_measures(const std::vector<double>& impacts, const std::vector<double>& exact_impacts,
                             double period) {
  if (!(std::isfinite(period) && period > 0)) throw std::invalid_argument("phase measures: the period must be > 0");
  for (std::size_t k = 1; k < exact_impacts.size(); ++k)
    if (!(exact_impacts[k] > exact_impacts[k - 1]))
      throw std::invalid_argument("phase measures: the exact impact times must increase");
  const std::size_t n = std::min(impacts.size(), exact_impacts.size());
  if (n == 0)
    throw std::invalid_argument("phase measures: no impact to compare (measured " + std::to_string(impacts.size()) +
                                ", exact " + std::to_string(exact_impacts.size()) + ")");
  PhaseMeasures m{n, impacts[0] - exact_impacts[0], std::nullopt};
  if (n >= 2) {
    double t_mean = 0, e_mean = 0;
    for (std::size_t k = 0; k < n; ++k) {
      t_mean += exact_impacts[k];
      e_mean += impacts[k] - exact_impacts[k];
    }
    t_mean /= static_cast<double>(n);
    e_mean /= static_cast<double>(n);
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double dt = exact_impacts[k] - t_mean;
      sxy += dt * (impacts[k] - exact_impacts[k] - e_mean);
      sxx += dt * dt;
    }
    m.drift_per_period = period * sxy / sxx;
  }
  return m;
}

std::vector<double> benchmark_impact_times(const ExactSolution& exact, std::size_t count) {
  std::vector<double> t(count);
  for (std::size_t k = 0; k < count; ++k) t[k] = exact.length() + exact.period() * static_cast<double>(k);
  return t;
}

// ---------------------------------------------------------------------------------------------------

namespace {

// A synthetic indicator with contacts [aₖ, bₖ]: −(distance to the nearest end) inside a contact,
// +(distance to the nearest contact) outside, affine with slope ±1 near every end.
[[maybe_unused]] double synthetic_indicator(double t, const std::vector<double>& a, const std::vector<double>& b) {
  double g = 1e300;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (t >= a[k] && t <= b[k]) return -std::min(t - a[k], b[k] - t);
    g = std::min({g, std::abs(t - a[k]), std::abs(t - b[k])});
  }
  return g;
}

}  // namespace

TEST_CASE("the phase diagnostics recover a known first-impact error and drift from a synthetic series") {
  // Impacts at t̂ₖ = 1 + e₀ + k(3 + d), contacts of length 0.9, sampled with a step that does not
  // divide them; the indicator is affine across each crossing, so the estimator is exact to round-off.
  for (const double e0 : {-0.01, 0.0, 0.013}) {
    for (const double d : {-0.02, 0.0, 0.005}) {
      std::vector<double> a, b;
      for (int k = 0; k < 8; ++k) {
        a.push_back(1 + e0 + k * (3 + d));
        b.push_back(a.back() + 0.9);
      }
      ImpactDetector detector;
      const double dt = 0.0173;
      for (int n = 0; n * dt <= 24.5; ++n) detector.add(n * dt, synthetic_indicator(n * dt, a, b));
      const std::vector<double>& impacts = detector.impacts();
      REQUIRE(impacts.size() == 8);
      const PhaseMeasures m = phase_measures(impacts, benchmark_impact_times(ExactSolution(), 8), 3.0);
      CAPTURE(e0);
      CAPTURE(d);
      CHECK(m.matched == 8);
      CHECK(std::abs(m.first_impact_error - e0) < 1e-12);
      REQUIRE(m.drift_per_period.has_value());
      CHECK(std::abs(*m.drift_per_period - d) < 1e-12);
      for (std::size_t k = 0; k < 8; ++k) CHECK(std::abs(impacts[k] - a[k]) < 1e-12);
    }
  }
}

TEST_CASE(
    "the drift is the least-squares slope: early impacts give a negative drift, scattered ones their mean trend") {
  // Errors e = (−0.1, 0.05, −0.2, −0.15) at t = 1, 4, 7, 10: t̄ = 5.5, ē = −0.1,
  // Σ(t − t̄)(e − ē) = −4.5·0 − 1.5·0.15 + 1.5·(−0.1) + 4.5·(−0.05) = −0.6, Σ(t − t̄)² = 45, so the
  // slope is −1/75 and the drift over a period of 3 is −0.04.
  const std::vector<double> exact = benchmark_impact_times(ExactSolution(), 4);
  const std::vector<double> measured = {0.9, 4.05, 6.8, 9.85};
  const PhaseMeasures m = phase_measures(measured, exact, 3.0);
  REQUIRE(m.drift_per_period.has_value());
  CHECK(std::abs(*m.drift_per_period + 0.04) < 1e-14);
  CHECK(std::abs(m.first_impact_error + 0.1) < 1e-14);
  // One impact: no drift; none: an error.
  CHECK_FALSE(phase_measures({0.95}, exact, 3.0).drift_per_period.has_value());
  CHECK_THROWS_AS(phase_measures({}, exact, 3.0), std::invalid_argument);
  CHECK_THROWS_AS(phase_measures({1.0}, exact, 0.0), std::invalid_argument);
}

TEST_CASE("a contact that reopens for a moment is one impact when the free interval is short") {
  // Contact [1, 2] with a one-sample opening at 1.5; then a real impact at 4.
  ImpactDetector strict, chatter_aware(0.5);
  for (int n = 0; n <= 500; ++n) {
    const double t = n * 0.01;
    double g = synthetic_indicator(t, {1.0, 4.0}, {2.0, 4.5});
    if (n == 150) g = 0.001;
    strict.add(t, g);
    chatter_aware.add(t, g);
  }
  CHECK(strict.impacts().size() == 3);
  REQUIRE(chatter_aware.impacts().size() == 2);
  CHECK(std::abs(chatter_aware.impacts()[0] - 1.0) < 1e-12);
  CHECK(std::abs(chatter_aware.impacts()[1] - 4.0) < 1e-12);
  ImpactDetector d;
  d.add(0.0, 1.0);
  CHECK_THROWS_AS(d.add(0.0, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(ImpactDetector(-1.0), std::invalid_argument);
}

TEST_CASE("with the algebraic contact row the contact indicator is u1 at every level") {
  const UniformMesh mesh(1.0, 30);
  SchemeParameters p;
  BarSimulation simulation(benchmark_problem(), mesh, mod2(), p, 0.5 * mesh.h());
  double worst = 0;
  run(simulation, 300, [&](const Sample& s) {
    worst = std::max(worst, std::abs(contact_indicator(s, mesh.h()) - (*s.displacement)[1]));
  });
  CHECK(worst < 1e-14);
}

// The period law on real runs: Crank–Nicolson, Δt = h/2, N = 40, 30 periods. The law predicts the
// mass-dependent part of the drift (period_law.cpp: −4h/3, −h/3, 0 + O(h²)); the scheme adds a drift of
// its own, the same for every mass (the release of a smeared front; measured within ±0.1h at
// Δt = h/2 on N = 20 … 200 when this test was written). Hence two criteria: each drift within 0.15h of
// the law, and the differences between the masses, where the scheme's share cancels, within 0.05h.
// The first impact is at ℓ_f: −2h/3, −h/3, 0, within 0.05h (nothing of the scheme accumulates yet).
TEST_CASE("the impact times of Crank-Nicolson drift by -4h/3, -h/3 and 0 per period as the period law predicts") {
  const UniformMesh mesh(1.0, 40);
  const double h = mesh.h(), dt = 0.5 * h;
  const ExactSolution exact;
  std::vector<double> drift, predicted;
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    BarSimulation simulation(benchmark_problem(), mesh, mass, SchemeParameters(), dt);
    ImpactDetector detector(exact.length());
    run(simulation, steps_to_reach(30 * exact.period(), dt),
        [&](const Sample& s) { detector.add(s.time, contact_indicator(s, h)); });
    const PhaseMeasures m =
        phase_measures(detector.impacts(), benchmark_impact_times(exact, detector.impacts().size()), exact.period());
    const PeriodPrediction law = predict_period(mesh, mass);
    CAPTURE(mass.name);
    CAPTURE(m.first_impact_error / h);
    CAPTURE(law.first_impact_error / h);
    REQUIRE(m.drift_per_period.has_value());
    CAPTURE(*m.drift_per_period / h);
    CAPTURE(law.period_error / h);
    CHECK(m.matched >= 30);
    CHECK(std::abs(m.first_impact_error - law.first_impact_error) < 0.05 * h);
    CHECK(std::abs(*m.drift_per_period - law.period_error) < 0.15 * h);
    drift.push_back(*m.drift_per_period);
    predicted.push_back(law.period_error);
  }
  for (std::size_t k = 0; k < 2; ++k) {
    CAPTURE(k);
    CHECK(std::abs((drift[k] - drift[2]) - (predicted[k] - predicted[2])) < 0.05 * h);
  }
}

}  // namespace mrm
