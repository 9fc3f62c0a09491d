/// @file smooth_benchmarks.cpp
/// @brief Smooth benchmarks: mathematics.md §11.
///
/// Purely left-going data. Take u⁰ = P and v⁰ = P′ on [0, L], L = 1, with P constant near 0 and zero near
/// 1. Then V⁰ = ∫₀ˣ P′ = P − P(0), and the waves of characteristics.cpp are
///
///     F = (u⁰ − V⁰)/2 = P(0)/2 (constant),   G = (u⁰ + V⁰)/2 = P − P(0)/2:
///
/// only a left-going wave, u_t − u_x = 0 at t = 0. Near x = 0 the data are at rest with u_x = 0 (a free
/// end's condition) and near x = 1 they vanish identically, so every compatibility condition holds at both
/// ends and the solution is as smooth as P until the first contact. Before t = L the contact point sees
/// y(t) = P(0) + 2(G(t) − G(0)) = 2P(t) − P(0), so it reaches the obstacle where P(t) = P(0)/2.
///
/// The shape. P′ = −K q with q ≥ 0 a polynomial on a support [α, ω] ⊂ (0, 1) (zero outside),
/// P(x) = −∫ₓ¹ P′ = K ∫ₓ^ω q, and K = P(0) / ∫_α^ω q so that P(0) = ¼.
///
/// S1, generic impact: q = ((x − 0.2)(0.8 − x))⁴ on [0.2, 0.8] (C³ data). q is symmetric about ½, so
/// P(½) = ½ K ∫q = P(0)/2: y(½) = 0, t* = ½, and there y′ = 2P′(½) = −2K·0.09⁴ ≠ 0: the end hits the
/// obstacle with non-zero velocity, and u_t, u_x jump along the characteristic leaving (0, ½). It stays
/// held: β = 2P′ ≤ 0 up to t = 1 (λ = 0 from 0.8 on), G is the constant −P(0)/2 on [1, 2] (the reflection
/// of the constant F), and the reflected wave releases it only at t = 2.2 (β > 0 where P decreases again,
/// mirrored), after T = 2. So S1 has no release time within T (NaN below).
///
/// S2, grazing impact: q = ((x − 0.1)(0.9 − x))⁴ (x − t*)² (t_r − x)³ on [0.1, 0.9], t* = 0.35. On
/// [0.1, t_r], q ≥ 0 and y decreases, with y′ = 2P′ = 0 at t* (double root). Choose t_r so that y(t*) = 0:
///
///     ∫_{t*}^{0.9} q = ½ ∫_{0.1}^{0.9} q        (an equation for t_r alone, K cancels),
///
/// then y ≈ −c (t − t*)³ near t*: the end arrives with zero velocity and acceleration, u(0, t) ~ (t* − t)³.
/// It is held while β = 2P′ ≤ 0, i.e. until t_r, where q changes sign with a triple root: released at t_r
/// with u(0, t) ~ (t − t_r)⁴. As t_r → t*, q ≤ 0 on [t*, 0.9] and ≥ 0 before, so the difference of the
/// two sides is negative; at t_r = 0.9 it is positive (both checked at run time): GSL's Brent solver finds
/// the root in between.
/// S3 is S2 with (x − t*)⁴ (a grazing of higher order).
///
/// Representation. q is built on 16 equal sub-pieces of its support, each as a product of its linear
/// factors in the sub-piece's own variable σ ∈ [−1, 1]: a degree-14 polynomial written about the middle
/// of a short piece has coefficients of the size of its values, where one expansion over the whole support
/// would lose several digits to cancellation. P on each sub-piece is K r (Q(1) − Q(σ)) + P(b), Q the
/// antiderivative of q in σ and r the half-width, accumulated from the right end (P(ω) = 0).
#include "exact/smooth_benchmarks.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <doctest/doctest.h>

namespace mrm {

std::string to_string(SmoothBenchmark b) {
  switch (b) {
    case SmoothBenchmark::generic_impact:
      return "s1";
    case SmoothBenchmark::grazing:
      return "s2";
    case SmoothBenchmark::grazing_quartic:
      return "s3";
  }
  return "?";
}

SmoothBenchmark smooth_benchmark_by_name(const std::string& name) {
  for (SmoothBenchmark b :
       {SmoothBenchmark::generic_impact, SmoothBenchmark::grazing, SmoothBenchmark::grazing_quartic})
    if (to_string(b) == name) return b;
  throw std::invalid_argument("unknown smooth benchmark '" + name + "' (allowed: s1, s2, s3)");
}

namespace {

constexpr double contact_height = 0.25;  // P(0)
constexpr int sub_pieces = 16;

// (x − root)^power (or (root − x)^power when `reversed`).
struct Factor {
  double root;
  int power;
  bool reversed;
};

// q = Π factors on `sub_pieces` equal pieces of [begin, end], each in its own σ (x = m + rσ).
PiecewisePolynomial weight(double begin, double end, const std::vector<Factor>& factors) {
  PiecewisePolynomial q;
  for (int k = 0; k < sub_pieces; ++k) {
    const double a = begin + (end - begin) * k / sub_pieces;
    const double b = k + 1 == sub_pieces ? end : begin + (end - begin) * (k + 1) / sub_pieces;
    const double m = 0.5 * (a + b), r = 0.5 * (b - a);
    poly::Coefficients c{1.0};
    for (const Factor& f : factors) {
      const poly::Coefficients linear =
          f.reversed ? poly::Coefficients{f.root - m, -r} : poly::Coefficients{m - f.root, r};
      c = poly::product(c, poly::power(linear, f.power));
    }
    q.append(PolynomialPiece::on(a, b, c));
  }
  return q;
}

std::vector<Factor> grazing_factors(double touch, double release, int touch_power) {
  return {{0.1, 4, false}, {0.9, 4, true}, {touch, touch_power, false}, {release, 3, true}};
}

// t_r solves ∫_{t*}^{0.9} q − ½ ∫_{0.1}^{0.9} q = 0; the residual is divided by ∫|q| (by pieces) so that
// its scale is 1 whatever the size of q.
double release_time(double touch, int touch_power) {
  struct Parameters {
    double touch;
    int touch_power;
  } parameters{touch, touch_power};
  gsl_function f;
  f.function = [](double release, void* p) {
    const auto* e = static_cast<const Parameters*>(p);
    const PiecewisePolynomial q = weight(0.1, 0.9, grazing_factors(e->touch, release, e->touch_power));
    double magnitude = 0;
    for (const PolynomialPiece& piece : q.pieces()) {
      // ∫|q| ≥ |∫q| over the pieces: the scale of the residual.
      magnitude += std::abs(q.integral(piece.a, piece.b));
    }
    return (q.integral(e->touch, 0.9) - 0.5 * q.integral(0.1, 0.9)) / magnitude;
  };
  f.params = &parameters;
  gsl_set_error_handler_off();
  double lo = touch + 1e-6, hi = 0.9;
  const double f_lo = GSL_FN_EVAL(&f, lo), f_hi = GSL_FN_EVAL(&f, hi);
  if (!(f_lo < 0 && f_hi > 0))
    throw std::runtime_error("smooth benchmark: the release time is not bracketed in (t*, 0.9)");
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!solver) throw std::runtime_error("smooth benchmark: gsl_root_fsolver_alloc failed");
  int status = gsl_root_fsolver_set(solver, &f, lo, hi);
  double root = 0.5 * (lo + hi);
  for (int iteration = 0; status == GSL_SUCCESS && iteration < 200; ++iteration) {
    status = gsl_root_fsolver_iterate(solver);
    if (status != GSL_SUCCESS) break;
    root = gsl_root_fsolver_root(solver);
    lo = gsl_root_fsolver_x_lower(solver);
    hi = gsl_root_fsolver_x_upper(solver);
    status = gsl_root_test_interval(lo, hi, 0.0, 4e-16);
    if (status == GSL_SUCCESS) break;
    if (status != GSL_CONTINUE) break;
    status = GSL_SUCCESS;
  }
  gsl_root_fsolver_free(solver);
  if (status != GSL_SUCCESS)
    throw std::runtime_error(std::string("smooth benchmark: Brent's method failed for the release time: ") +
                             gsl_strerror(status));
  return root;
}

}  // namespace

SmoothBenchmarkData smooth_benchmark(SmoothBenchmark which) {
  SmoothBenchmarkData s;
  s.which = which;
  s.contact_height = contact_height;
  s.final_time = 2.0;
  PiecewisePolynomial q;
  if (which == SmoothBenchmark::generic_impact) {
    s.support_begin = 0.2;
    s.support_end = 0.8;
    s.touch_time = 0.5;  // the symmetry of q about ½ (above)
    s.release_time = NAN;
    q = weight(0.2, 0.8, {{0.2, 4, false}, {0.8, 4, true}});
  } else {
    const int touch_power = which == SmoothBenchmark::grazing ? 2 : 4;
    s.support_begin = 0.1;
    s.support_end = 0.9;
    s.touch_time = 0.35;
    s.release_time = release_time(s.touch_time, touch_power);
    q = weight(0.1, 0.9, grazing_factors(s.touch_time, s.release_time, touch_power));
  }
  s.scale = contact_height / q.integral(s.support_begin, s.support_end);

  // u⁰ = P and v⁰ = −K q on the sub-pieces, from the right: P(x) = P(b) + K r (Q(1) − Q(σ)).
  std::vector<InitialDataPiece> middle;
  double right_value = 0.0;
  for (std::size_t k = q.pieces().size(); k-- > 0;) {
    const PolynomialPiece& piece = q.pieces()[k];
    const poly::Coefficients antiderivative = poly::antiderivative(piece.value);
    poly::Coefficients u(antiderivative.size()), v(piece.value.size());
    for (std::size_t j = 0; j < u.size(); ++j) u[j] = -s.scale * piece.radius * antiderivative[j];
    u[0] += right_value + s.scale * piece.radius * poly::evaluate(antiderivative, 1.0);
    for (std::size_t j = 0; j < v.size(); ++j) v[j] = -s.scale * piece.value[j];
    middle.push_back({piece.a, piece.b, u, v});
    right_value = poly::evaluate(u, -1.0);
  }
  s.data.pieces.push_back({0.0, s.support_begin, {contact_height}, {}});
  for (std::size_t k = middle.size(); k-- > 0;) s.data.pieces.push_back(middle[k]);
  s.data.pieces.push_back({s.support_end, 1.0, {0.0}, {}});
  s.data.validate();
  return s;
}

// ---------------------------------------------------------------------------------------------------

TEST_CASE("the smooth benchmarks are purely left-going, with P(0) = 1/4, constant near 0 and zero near 1") {
  for (SmoothBenchmark which :
       {SmoothBenchmark::generic_impact, SmoothBenchmark::grazing, SmoothBenchmark::grazing_quartic}) {
    const SmoothBenchmarkData s = smooth_benchmark(which);
    CAPTURE(to_string(which));
    CHECK(s.scale > 0);
    CHECK(s.data.displacement(0.0) == 0.25);
    CHECK(s.data.displacement(0.5 * s.support_begin) == 0.25);
    CHECK(s.data.displacement(0.5 * (1 + s.support_end)) == 0.0);
    // P(α) from the pieces (the right end accumulated leftwards) meets P(0) = ¼: K is right.
    CHECK(std::abs(s.data.displacement(s.support_begin * (1 + 1e-15)) - 0.25) <= 1e-15);
    // v⁰ = P′ against a central difference of u⁰, and F = (u⁰ − V⁰)/2 constant.
    for (int k = 1; k < 50; ++k) {
      const double x = s.support_begin + (s.support_end - s.support_begin) * (k + 0.3) / 50.3, d = 1e-6;
      CAPTURE(x);
      const double slope = (s.data.displacement(x + d) - s.data.displacement(x - d)) / (2 * d);
      CHECK(std::abs(slope - s.data.velocity(x)) <= 1e-8);
      const bool pulls_towards_obstacle = s.data.velocity(x) < 0.0;
      CHECK(pulls_towards_obstacle == (which == SmoothBenchmark::generic_impact || x < s.release_time));
    }
    const CharacteristicSolution solution(s.data, 0.5);
    for (const PolynomialPiece& p : solution.right_going().pieces()) {
      if (p.a < 0) continue;
      CHECK(std::abs(p.at(0.5 * (p.a + p.b)) - 0.125) <= 1e-15);
      CHECK(std::abs(p.derivative_at(0.5 * (p.a + p.b))) <= 1e-13);
    }
  }
}

TEST_CASE("S1 hits the obstacle at t* = 1/2 with non-zero velocity and stays held until T") {
  const SmoothBenchmarkData s = smooth_benchmark(SmoothBenchmark::generic_impact);
  const CharacteristicSolution solution(s.data, s.final_time);
  REQUIRE(solution.contact_intervals().size() == 1);
  const ContactInterval contact = solution.contact_intervals().front();
  CHECK(std::abs(contact.start - 0.5) <= 1e-14);
  CHECK(contact.open);
  CHECK(contact.end == s.final_time);
  // The arrival velocity is y′(½) = 2P′(½) = −2K·0.09⁴, and the pressure just after it is the same
  // (λ = β = 2P′): the momentum the obstacle takes.
  const double arrival = 2 * s.data.velocity(0.5), expected = -2 * s.scale * std::pow(0.09, 4);
  CHECK(std::abs(arrival - expected) <= 1e-13 * std::abs(expected));
  const double d = 1e-7;
  CHECK(std::abs(solution.velocity(0.0, 0.5 - d) - arrival) <= 1e-4 * std::abs(arrival));
  CHECK(std::abs(solution.contact_multiplier(0.5 + d) - arrival) <= 1e-4 * std::abs(arrival));
  CHECK(solution.velocity(0.0, 0.5 + d) == 0.0);
  CHECK(std::abs(arrival) > 0.1);
  // λ = 0 once the wave has passed (t > 0.8), still held.
  CHECK(solution.contact_multiplier(1.5) == 0.0);
  CHECK(solution.contact_displacement(1.5) == 0.0);
}

TEST_CASE("S2 and S3 touch at t* with zero velocity and acceleration and are released at t_r") {
  for (SmoothBenchmark which : {SmoothBenchmark::grazing, SmoothBenchmark::grazing_quartic}) {
    const SmoothBenchmarkData s = smooth_benchmark(which);
    CAPTURE(to_string(which));
    CAPTURE(s.release_time);
    // t_r makes y(t*) = 2P(t*) − P(0) vanish (mathematics.md §11: t_r ≈ 0.66 for S2, ≈ 0.68 for S3).
    CHECK(std::abs(2 * s.data.displacement(s.touch_time) - 0.25) <= 1e-15);
    CHECK(std::abs(s.release_time - (which == SmoothBenchmark::grazing ? 0.6597 : 0.6786)) <= 1e-4);
    const CharacteristicSolution solution(s.data, s.final_time);
    REQUIRE(solution.contact_intervals().size() == 1);
    const ContactInterval contact = solution.contact_intervals().front();
    // A start at a root of multiplicity m of y (3 for S2, 5 for S3) and an end at a triple sign change
    // of β are located to ~(ε/c)^{1/m} only (piecewise_polynomial.cpp): 1e-4 and 2e-3 with margin.
    CHECK(std::abs(contact.start - s.touch_time) <= (which == SmoothBenchmark::grazing ? 1e-4 : 2e-3));
    CHECK(std::abs(contact.end - s.release_time) <= 1e-4);
    CHECK_FALSE(contact.open);
    // Zero velocity at the touch: u_t(0, t*⁻) = 2P′(t*) = 0, to round-off of the largest |2P′|.
    double largest_slope = 0;
    for (int k = 0; k <= 1000; ++k) largest_slope = std::max(largest_slope, std::abs(2 * s.data.velocity(k / 1000.0)));
    CHECK(std::abs(2 * s.data.velocity(s.touch_time)) <= 1e-13 * largest_slope);
    // u(0, t) ~ c (t* − t)^{p+1} before the touch, p the power of (x − t*): the ratio at δ and δ/2 is 2^{p+1}.
    const double order = which == SmoothBenchmark::grazing ? 3 : 5, delta = 0.02;
    const double ratio =
        solution.contact_displacement(s.touch_time - delta) / solution.contact_displacement(s.touch_time - 0.5 * delta);
    CHECK(std::abs(ratio / std::pow(2.0, order) - 1) <= 0.05);
    // Held in between with λ ≤ 0, released after t_r (u(0, ·) > 0 again), λ = 0 after.
    CHECK(solution.contact_displacement(0.5 * (s.touch_time + s.release_time)) == 0.0);
    CHECK(solution.contact_multiplier(0.5 * (s.touch_time + s.release_time)) < 0.0);
    CHECK(solution.contact_displacement(s.release_time + 0.05) > 0.0);
    CHECK(solution.contact_multiplier(s.release_time + 0.05) == 0.0);
    // The energy is constant over [0, T].
    for (int k = 0; k <= 40; ++k) {
      const double t = s.final_time * k / 40.0;
      CAPTURE(t);
      CHECK(std::abs(solution.energy_at(t) - solution.energy()) <= 1e-13 * solution.energy());
    }
  }
}

TEST_CASE("an unknown smooth benchmark name is refused with the allowed names") {
  CHECK(smooth_benchmark_by_name("s2") == SmoothBenchmark::grazing);
  CHECK_THROWS_WITH_AS(smooth_benchmark_by_name("s4"), doctest::Contains("allowed: s1, s2, s3"), std::invalid_argument);
}

}  // namespace mrm
