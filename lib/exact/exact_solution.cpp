/// @file exact_solution.cpp
/// @brief The benchmark with a closed-form solution: mathematics.md §2.
///
/// Derivation by characteristics. For f = 0 every solution of u_tt = u_xx is u = P(x + t) + Q(x − t),
/// and for data at rest, u = ½(ũ⁰(x + t) + ũ⁰(x − t)) with ũ⁰ the extension of u⁰ across the ends: an
/// even reflection at an end that is free (u_x = 0 there), an odd one at an end that is held (u = 0).
/// Write the data u⁰(x) = a (L − x); the reference case of the paper is L = 1, a = ½.
///
/// Phase 1, 0 ≤ t < L, free flight. The end x = 0 is free as long as u(0, t) > 0, so ũ⁰ is even about
/// 0: ũ⁰(y) = a (L − |y|); the line a (L − y) is already odd about L, so the clamp adds nothing. Then
/// for x ≥ t, u = a (L − x), and for x < t, u = ½(a(L − x − t) + a(L − t + x)) = a (L − t):
///
///     u = a (L − max(x, t)).
///
/// An unloading wave leaves the free end; behind it the bar moves rigidly with u_t = −a. At t = L it
/// has reached the clamp: u ≡ 0 and u_t ≡ −a, and the end hits the obstacle with speed a.
///
/// Phase 2, t = L + s, 0 ≤ s < L, contact. Now u(0, ·) = 0 is held: both ends are held, ũ is odd at
/// both, and with zero displacement and velocity −a the solution is the tent
///
///     u = −a · min(x, L − x, s, L − s),
///
/// (it vanishes at x = 0 and x = L, has u_t = −a at s = 0⁺, and is a sum of travelling kinks). Its
/// strain at the contact point is u_x(0, t) = −a < 0, so λ = −a: a compressive contact pressure a, as
/// Signorini requires. At s = L the velocity has turned into u_t = +a everywhere and u ≡ 0 again: the
/// obstacle releases the end (λ would otherwise have to pull).
///
/// Phase 3, t = 2L + s, 0 ≤ s < L, free flight back. The end is free again (even reflection), the data
/// are u = 0, u_t = +a, and by the same construction as in phase 1
///
///     u = a · min(s, L − x),
///
/// which at s = L is a (L − x) with u_t = 0: the initial state. The solution is periodic with period
/// 3L. On the contact point: u(0, t) = a(L − t), 0, a s on the three phases, and λ = 0, −a, 0.
/// The energy ½∫(u_t² + u_x²) dx = ½(a² t + a² (L − t)) = a² L / 2 in phase 1, and the same in the
/// others (a = ½, L = 1: E = 1/8).
///
/// Implementation. Scaling x = L ξ, t = L τ reduces every case to L = 1 and a = ½ times 2aL; on each
/// phase the reference solution is c · min_k(α_k + β_k ξ + γ_k s) of a few affine functions, so u is a
/// minimum and its derivatives are the slopes of the active affine function. Where several are active
/// (on a characteristic), the one-sided derivatives are the smallest and the largest of their slopes,
/// and the symmetric derivative is their mean. At an instant where the phase changes, the mean of
/// the two phases' values is taken. Ties are detected with a tolerance of 1e-12 (in the reference
/// scale), so that grid points x_i = i h, t_n = n Δt that lie on a characteristic in exact arithmetic are
/// recognised after round-off.
#include "exact/exact_solution.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>
#include <string>

#include <doctest/doctest.h>

namespace mrm {

namespace {

constexpr double tie_tolerance = 1e-12;

struct Affine {
  double alpha, beta, gamma;  // α + β ξ + γ s
  double at(double xi, double s) const { return alpha + beta * xi + gamma * s; }
};

struct Phase {
  double c;  // u = c · min_k(affine_k)
  int count;
  Affine affine[4];
};

// The three phases of the reference solution (L = 1, a = ½), with s the time since the phase began.
constexpr Phase phases[3] = {
    {0.5, 2, {{1, -1, 0}, {1, 0, -1}, {}, {}}},                 // ½ min(1 − ξ, 1 − s)
    {-0.5, 4, {{0, 1, 0}, {1, -1, 0}, {0, 0, 1}, {1, 0, -1}}},  // −½ min(ξ, 1 − ξ, s, 1 − s)
    {0.5, 2, {{0, 0, 1}, {1, -1, 0}, {}, {}}},                  // ½ min(s, 1 − ξ)
};

struct PhaseTime {
  int phase;
  double s;
  bool at_boundary;  // τ is (to the tolerance) an integer: the previous phase ends here
};

PhaseTime locate(double tau) {
  // A time that is not finite has no phase (its cast to a phase index would be undefined).
  if (!std::isfinite(tau))
    throw std::invalid_argument("exact solution: the time t must be finite (got " + std::to_string(tau) + ")");
  double r = std::fmod(tau, 3.0);
  if (r < 0) r += 3.0;
  const double nearest = std::round(r);
  const bool boundary = std::abs(r - nearest) <= tie_tolerance;
  if (boundary) r = nearest;
  if (r >= 3.0) r -= 3.0;
  const int phase = static_cast<int>(std::floor(r));
  return {phase, r - phase, boundary};
}

double value(const Phase& p, double xi, double s) {
  double m = p.affine[0].at(xi, s);
  for (int k = 1; k < p.count; ++k) m = std::min(m, p.affine[k].at(xi, s));
  return p.c * m;
}

// The symmetric derivative of c · min_k(affine_k) along ξ (which = 0) or s (which = 1).
double symmetric_derivative(const Phase& p, double xi, double s, int which) {
  double m = p.affine[0].at(xi, s);
  for (int k = 1; k < p.count; ++k) m = std::min(m, p.affine[k].at(xi, s));
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < p.count; ++k) {
    if (p.affine[k].at(xi, s) - m <= tie_tolerance) {
      const double slope = which == 0 ? p.affine[k].beta : p.affine[k].gamma;
      lo = std::min(lo, slope);
      hi = std::max(hi, slope);
    }
  }
  return p.c * 0.5 * (lo + hi);
}

// A derivative of the reference solution at (ξ, τ), averaged over the two phases at a phase change;
// τ given by its phase (locate(τ)), which the runs below locate once for all their points.
double reference_derivative(double xi, const PhaseTime& pt, int which) {
  const double here = symmetric_derivative(phases[pt.phase], xi, pt.s, which);
  if (!pt.at_boundary) return here;
  const int previous = (pt.phase + 2) % 3;
  return 0.5 * (here + symmetric_derivative(phases[previous], xi, 1.0, which));
}

double reference_derivative(double xi, double tau, int which) { return reference_derivative(xi, locate(tau), which); }

}  // namespace

ExactSolution::ExactSolution(double length, double amplitude) : length_(length), amplitude_(amplitude) {
  if (!(std::isfinite(length) && length > 0))
    throw std::invalid_argument("exact solution: the length L must be a positive finite number");
  if (!std::isfinite(amplitude)) throw std::invalid_argument("exact solution: the amplitude must be finite");
}

// u(x, t) = 2aL · u₁(x/L, t/L): the reference solution has a = ½, L = 1.
double ExactSolution::displacement(double x, double t) const {
  const PhaseTime pt = locate(t / length_);
  return 2.0 * amplitude_ * length_ * value(phases[pt.phase], x / length_, pt.s);
}

double ExactSolution::strain(double x, double t) const {
  return 2.0 * amplitude_ * reference_derivative(x / length_, t / length_, 0);
}

double ExactSolution::velocity(double x, double t) const {
  return 2.0 * amplitude_ * reference_derivative(x / length_, t / length_, 1);
}

double ExactSolution::contact_displacement(double t) const { return displacement(0.0, t); }

// λ = −a during contact, 0 in free flight; −a/2 at the instants of impact and release.
double ExactSolution::contact_multiplier(double t) const {
  const PhaseTime pt = locate(t / length_);
  if (pt.at_boundary && pt.phase != 0) return -0.5 * amplitude_;  // impact (τ = 1) or release (τ = 2)
  return pt.phase == 1 ? -amplitude_ : 0.0;
}

double ExactSolution::energy() const { return 0.5 * amplitude_ * amplitude_ * length_; }

// ---------------------------------------------------------------------------------------------------
// Evaluation at many points at once (the error measures need u and u_t at every node of every level).
//
// At a fixed instant, with the phase and s located once, the reference solution is c · min_k a_k(ξ)
// with a_k(ξ) = α_k + β_k ξ + γ_k s affine in ξ: it is piecewise affine, and its kinks are among the
// crossings ξ_jk of two of the a_k with different slopes β_j ≠ β_k (functions with equal slopes are
// parallel: they tie everywhere or nowhere). Away from every crossing by more than δ = 1e-9 (in ξ),
// two non-parallel a_k differ by at least δ ≫ the tie tolerance 1e-12, so the set of active functions
// is the same all along each run of points between two crossings: there u is the one active function,
// one affine function of x (intercept and slope computed once per run), and u_t the same constant,
// computed once per run by velocity(). At a phase change u_t averages two phases: the kinks of both count. Points
// within δ of a crossing go through the generic functions, which decide the ties. So the values are
// those of the generic functions (the doctest below checks it at points on the characteristics, at
// the phase changes and elsewhere), at the cost of one affine function per point for u and a copy
// for u_t.
namespace {

constexpr double run_margin = 1e-9;

// The crossings in ξ of the non-parallel pairs of affine functions of phase p at time s, appended to
// `kinks` (at most 6 per phase).
int append_crossings(const Phase& p, double s, double* kinks, int count) {
  for (int j = 0; j < p.count; ++j)
    for (int k = j + 1; k < p.count; ++k) {
      const Affine &a = p.affine[j], &b = p.affine[k];
      if (a.beta != b.beta) kinks[count++] = ((b.alpha + b.gamma * s) - (a.alpha + a.gamma * s)) / (a.beta - b.beta);
    }
  return count;
}

// Splits the sorted points x_0 ≤ … ≤ x_{count−1} (ξ = x/L) into runs that lie between two kinks, more
// than run_margin from each, and single points near a kink: calls run(first, end) or near(i).
template <class Run, class Near>
void split_at_kinks(const double* kinks, int kink_count, double length, const double* x, long count, Run&& run,
                    Near&& near) {
  long i = 0;
  while (i < count) {
    const double xi = x[i] / length;
    double next = INFINITY;  // the first kink above ξ_i, less the margin
    bool close = false;
    for (int k = 0; k < kink_count; ++k) {
      if (std::abs(xi - kinks[k]) <= run_margin) close = true;
      if (kinks[k] > xi) next = std::min(next, kinks[k] - run_margin);
    }
    if (close) {
      near(i);
      ++i;
      continue;
    }
    // The run ends before the first point at or above the kink less the margin: the comparison is made
    // in x (a product, not a quotient per point), which only moves the end by round-off, far from the kink.
    // The points are sorted, so that point is found by bisection (std::lower_bound: the first of
    // x[i+1 … count−1] not below next_x, the same index as a scan), in O(log N) per run, not O(N) per call.
    const double next_x = next * length;
    const long end = std::lower_bound(x + i + 1, x + count, next_x) - x;
    run(i, end);
    i = end;
  }
}

}  // namespace

// The split as runs of one affine function each, for the error measures (errors.cpp), which then
// need no array of values: on a run between kinks u = scale · c · (α + β x/L + γ s), that is
// intercept scale·c·(α + γs) and slope scale·c·β/L, and u_t is the constant that velocity() gives.
int ExactSolution::displacement_runs(double t, const double* x, long count, AffineRun* runs, int capacity) const {
  const PhaseTime pt = locate(t / length_);
  const Phase& p = phases[pt.phase];
  double kinks[12];
  const int kink_count = append_crossings(p, pt.s, kinks, 0);
  const double scale = 2.0 * amplitude_ * length_;
  int n = 0;
  const auto push = [&](AffineRun r) {
    if (n == capacity) throw std::length_error("ExactSolution::displacement_runs: more runs than the capacity");
    runs[n++] = r;
  };
  split_at_kinks(
      kinks, kink_count, length_, x, count,
      [&](long first, long end) {
        const double xi = x[first] / length_;
        int active = 0;
        for (int k = 1; k < p.count; ++k)
          if (p.affine[k].at(xi, pt.s) < p.affine[active].at(xi, pt.s)) active = k;
        const Affine a = p.affine[active];
        push({first, end, scale * p.c * (a.alpha + a.gamma * pt.s), scale * p.c * a.beta / length_});
      },
      [&](long i) {  // displacement(x[i], t), its phase located once above
        push({i, i + 1, scale * value(p, x[i] / length_, pt.s), 0.0});
      });
  return n;
}

int ExactSolution::velocity_runs(double t, const double* x, long count, AffineRun* runs, int capacity) const {
  const PhaseTime pt = locate(t / length_);
  double kinks[12];
  int kink_count = append_crossings(phases[pt.phase], pt.s, kinks, 0);
  if (pt.at_boundary) kink_count = append_crossings(phases[(pt.phase + 2) % 3], 1.0, kinks, kink_count);
  int n = 0;
  const auto push = [&](AffineRun r) {
    if (n == capacity) throw std::length_error("ExactSolution::velocity_runs: more runs than the capacity");
    runs[n++] = r;
  };
  split_at_kinks(
      kinks, kink_count, length_, x, count,
      [&](long first, long end) {  // velocity(x[first], t), its phase located once above
        push({first, end, 2.0 * amplitude_ * reference_derivative(x[first] / length_, pt, 1), 0.0});
      },
      [&](long i) {
        push({i, i + 1, 2.0 * amplitude_ * reference_derivative(x[i] / length_, pt, 1), 0.0});
      });
  return n;
}

// The values at many points from the runs: one affine function (or the generic value, near a kink) per
// point. The doctest below checks them, and so the runs, against the generic functions.
void ExactSolution::displacement_at_points(double t, const double* x, long count, double* u) const {
  AffineRun runs[32];
  const int n = displacement_runs(t, x, count, runs, 32);
  for (int r = 0; r < n; ++r)
    for (long i = runs[r].first; i < runs[r].end; ++i) u[i] = runs[r].intercept + runs[r].slope * x[i];
}

void ExactSolution::velocity_at_points(double t, const double* x, long count, double* v) const {
  AffineRun runs[32];
  const int n = velocity_runs(t, x, count, runs, 32);
  for (int r = 0; r < n; ++r)
    for (long i = runs[r].first; i < runs[r].end; ++i) v[i] = runs[r].intercept;
}

TEST_CASE("the evaluation at many points gives the values of the generic functions, kinks and phase changes included") {
  // Nodes x_i = iL/N and instants t_n = n Δt with Δt = h and h/2 put points exactly on the
  // characteristics and at the phase changes; the odd N and Δt put them near but not on.
  int on_kink = 0;
  for (const double length : {1.0, 2.5}) {
    const ExactSolution exact(length, length == 1.0 ? 0.5 : 0.3);
    for (const long elements : {7L, 40L, 64L, 100L}) {
      std::vector<double> x(static_cast<std::size_t>(elements) + 1), u(x.size()), v(x.size());
      for (long i = 0; i <= elements; ++i)
        x[static_cast<std::size_t>(i)] = length * static_cast<double>(i) / static_cast<double>(elements);
      const double h = length / static_cast<double>(elements);
      for (const double dt : {h, 0.5 * h, 0.37 * h}) {
        for (long n = 0; static_cast<double>(n) * dt <= 7.0 * length; ++n) {
          const double t = static_cast<double>(n) * dt;
          exact.displacement_at_points(t, x.data(), static_cast<long>(x.size()), u.data());
          exact.velocity_at_points(t, x.data(), static_cast<long>(x.size()), v.data());
          for (std::size_t i = 0; i < x.size(); ++i) {
            const double u_generic = exact.displacement(x[i], t), v_generic = exact.velocity(x[i], t);
            CAPTURE(length);
            CAPTURE(elements);
            CAPTURE(t);
            CAPTURE(x[i]);
            CHECK(std::abs(u[i] - u_generic) <= 1e-15 * length);
            CHECK(std::abs(v[i] - v_generic) <= 1e-15);
            // Count the points where u_t is the mean ±a/2 of its one-sided values ±a and 0 (on a kink).
            on_kink += std::abs(std::abs(v_generic) - 0.5 * exact.amplitude()) < 1e-14;
          }
        }
      }
    }
  }
  CHECK(on_kink > 100);
}

// ---------------------------------------------------------------------------------------------------

TEST_CASE("the exact solution refuses L <= 0, a non-finite amplitude and a non-finite time") {
  for (double length : {0.0, -2.0, std::nan(""), HUGE_VAL}) {
    CAPTURE(length);
    CHECK_THROWS_WITH_AS(ExactSolution(length, 0.5), doctest::Contains("the length L must be a positive finite number"),
                         std::invalid_argument);
  }
  CHECK_THROWS_WITH_AS(ExactSolution(1.0, std::nan("")), doctest::Contains("amplitude must be finite"),
                       std::invalid_argument);
  const ExactSolution exact;
  for (double t : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    CAPTURE(t);
    CHECK_THROWS_WITH_AS(exact.displacement(0.5, t), doctest::Contains("the time t must be finite"),
                         std::invalid_argument);
    CHECK_THROWS_AS(exact.velocity(0.5, t), std::invalid_argument);
    CHECK_THROWS_AS(exact.contact_multiplier(t), std::invalid_argument);
  }
}

TEST_CASE("the exact solution satisfies the clamp and the Signorini conditions") {
  const ExactSolution exact;
  for (int k = 0; k <= 6000; ++k) {
    const double t = 9.0 * k / 6000.0 + 1e-4;
    CAPTURE(t);
    CHECK(exact.displacement(1.0, t) == 0.0);
    const double gap = exact.contact_displacement(t), lambda = exact.contact_multiplier(t);
    CHECK(gap >= 0.0);
    CHECK(lambda <= 0.0);
    CHECK(gap * lambda == 0.0);
    CHECK(lambda == exact.strain(0.0, t));
  }
}

TEST_CASE("the exact solution has the contact-point values of each phase and period 3") {
  const ExactSolution exact;
  for (double t : {0.0, 0.25, 0.9}) CHECK(exact.contact_displacement(t) == doctest::Approx((1 - t) / 2).epsilon(1e-14));
  for (double t : {1.1, 1.5, 1.99}) {
    CHECK(exact.contact_displacement(t) == 0.0);
    CHECK(exact.contact_multiplier(t) == -0.5);
  }
  for (double t : {2.01, 2.5, 2.9}) CHECK(exact.contact_displacement(t) == doctest::Approx((t - 2) / 2).epsilon(1e-14));
  CHECK(exact.contact_multiplier(1.0) == -0.25);  // mean of the one-sided limits at impact
  CHECK(exact.contact_multiplier(2.0) == -0.25);  // and at release
  for (int k = 0; k < 200; ++k) {
    const double x = 0.37 + 0.003 * k, t = 0.013 * k;
    CAPTURE(x);
    CAPTURE(t);
    CHECK(std::abs(exact.displacement(x, t + 3.0) - exact.displacement(x, t)) < 1e-14);
    CHECK(std::abs(exact.displacement(x, t + 30.0) - exact.displacement(x, t)) < 1e-13);
  }
  CHECK(exact.displacement(0.3, 0.0) == doctest::Approx(0.35).epsilon(1e-15));  // u⁰ = (1 − x)/2
}

TEST_CASE("the exact solution keeps the energy 1/8") {
  // ½∫(u_t² + u_x²) dx by the midpoint rule on a fine grid: exact except in the cells a kink crosses.
  const ExactSolution exact;
  const int cells = 20000;
  for (double t : {0.0, 0.3, 1.0, 1.31, 1.77, 2.2, 2.95, 4.4}) {
    double e = 0;
    for (int i = 0; i < cells; ++i) {
      const double x = (i + 0.5) / cells;
      e += 0.5 * (std::pow(exact.velocity(x, t), 2) + std::pow(exact.strain(x, t), 2)) / cells;
    }
    CAPTURE(t);
    CHECK(std::abs(e - 0.125) < 1e-4);
  }
  CHECK(exact.energy() == 0.125);
}

TEST_CASE("the exact solution agrees with numerical derivatives of itself and solves the wave equation") {
  const ExactSolution exact(1.0, 0.5);
  const double d = 1e-6;
  int checked = 0;
  for (int i = 1; i < 40; ++i) {
    for (int n = 0; n < 120; ++n) {
      const double x = i / 40.0 + 0.0031, t = n * 0.025 + 0.0017;
      const double ux = (exact.displacement(x + d, t) - exact.displacement(x - d, t)) / (2 * d);
      const double ut = (exact.displacement(x, t + d) - exact.displacement(x, t - d)) / (2 * d);
      CAPTURE(x);
      CAPTURE(t);
      CHECK(std::abs(ux - exact.strain(x, t)) < 1e-8);
      CHECK(std::abs(ut - exact.velocity(x, t)) < 1e-8);
      // d'Alembert's parallelogram rule: u(x, t+δ) + u(x, t−δ) = u(x+δ, t) + u(x−δ, t) for δ < x, 1 − x.
      const double delta = 0.5 * std::min(x, 1 - x);
      CHECK(std::abs(exact.displacement(x, t + delta) + exact.displacement(x, t - delta) -
                     exact.displacement(x + delta, t) - exact.displacement(x - delta, t)) < 1e-14);
      ++checked;
    }
  }
  CHECK(checked == 39 * 120);
}

TEST_CASE("the exact solution scales with the length and the amplitude") {
  const ExactSolution reference, scaled(2.5, 0.3);
  const double L = 2.5, a = 0.3;
  for (int k = 0; k < 100; ++k) {
    const double xi = 0.01 * k, tau = 0.071 * k;
    CHECK(std::abs(scaled.displacement(L * xi, L * tau) - 2 * a * L * reference.displacement(xi, tau)) < 1e-13);
    CHECK(std::abs(scaled.velocity(L * xi, L * tau) - 2 * a * reference.velocity(xi, tau)) < 1e-13);
  }
  CHECK(scaled.contact_multiplier(1.5 * L) == doctest::Approx(-a).epsilon(1e-15));
  CHECK(scaled.energy() == doctest::Approx(a * a * L / 2).epsilon(1e-15));
  CHECK(scaled.period() == 7.5);
}

TEST_CASE("on a characteristic the exact derivatives are the means of the one-sided limits") {
  const ExactSolution exact;
  CHECK(exact.velocity(0.4, 0.4) == -0.25);  // phase 1: u_t jumps from −½ (x < t) to 0 (x > t)
  CHECK(exact.strain(0.4, 0.4) == -0.25);
  CHECK(exact.velocity(0.4, 0.4 + 1e-9) == -0.5);
  CHECK(exact.velocity(0.5, 1.0) == -0.5);  // the impact instant: u_t = −½ on both sides
}

}  // namespace mrm
