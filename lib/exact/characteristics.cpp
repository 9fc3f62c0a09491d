/// @file characteristics.cpp
/// @brief The exact solution for any initial data, by characteristics: mathematics.md §10.
///
/// Two waves. For f = 0 every solution of u_tt = u_xx on (0, L) is u(x, t) = F(x − t) + G(x + t): F moves
/// to the right, G to the left. At t = 0, u⁰ = F + G and v⁰ = −F′ + G′, so with V⁰(x) = ∫₀ˣ v⁰
///
///     F = (u⁰ − V⁰)/2,   G = (u⁰ + V⁰)/2   on [0, L]
///
/// (a constant could move from one to the other; this fixes it). The solution on [0, L] × [0, T] needs F on
/// [−T, L] and G on [0, L + T]: what enters the bar through its two ends.
///
/// The clamp. u(L, t) = 0 for every t: F(L − t) + G(L + t) = 0, i.e. G(η) = −F(2L − η) for η > L. The wave
/// that comes back from the clamp is the outgoing one mirrored at L with its sign changed (odd reflection).
///
/// The contact point. Write g(t) = u(0, t) = F(−t) + G(t) and β(t) = (u_t + u_x)(0, t) = 2G′(t): the Riemann
/// invariant that arrives at x = 0 along x + t = const, known as soon as G is known at t, that is from the
/// past. What leaves, u_t − u_x = −2F′(−t), is decided by Signorini:
///   - free (g > 0): λ = u_x(0, t) = 0, so g′ = u_t = u_t + u_x = β;
///   - held (g = 0): u_t(0, t) = 0, so λ = u_x = β, which Signorini admits (λ ≤ 0) only while β ≤ 0.
/// So g′ = β while g > 0, g stays at 0 while β ≤ 0 and leaves it as soon as β > 0: this is the Skorokhod
/// problem at 0 for the path y(t) = g(t₀) + ∫_{t₀}^t β = g(t₀) + 2(G(t) − G(t₀)). Its only solution (g ≥ 0,
/// g − y non-decreasing and increasing only where g = 0) is the reflection
///
///     g(t) = y(t) − min(0, min_{t₀ ≤ s ≤ t} y(s)).
///
/// Then F(−t) = g(t) − G(t): while free F′(−t) = −G′(t) (a free end reflects evenly), while held
/// F(−t) = −G(t) (a fixed end reflects oddly), and λ(t) = F′(−t) + G′(t) is 0, respectively 2G′(t) ≤ 0. The
/// energy flux through x = 0, u_x u_t = λ g′, vanishes in both cases: E = ½∫(u_t² + u_x²) dx is conserved,
/// and in terms of the waves E(t) = ∫_{−t}^{L−t} F′² + ∫_t^{L+t} G′² (since u_t² + u_x² = 2F′² + 2G′²).
///
/// Windows. G on [L, 2L] is the mirrored initial F. For k ≥ 2, G on [kL, (k + 1)L] is −F(2L − η) with
/// 2L − η ∈ [(1 − k)L, (2 − k)L]: F(−s) for s ∈ [(k − 2)L, (k − 1)L], which the contact point made out of G
/// on that earlier window. So the solution marches in windows of length L: on each, the contact point turns
/// the incoming G into the outgoing s ↦ F(−s), which comes back as G two windows later.
///
/// Exact for piecewise-polynomial data. On one polynomial piece of G, y is a polynomial, and its running
/// minimum can change only where y decreases: between consecutive sign changes of G′ (found to full
/// precision, piecewise_polynomial.cpp), y is monotone. Where G′ > 0 the point is free. Where G′ ≤ 0, a held
/// point stays held (the minimum follows y down), and a free one becomes held where y first reaches the
/// current level min(0, running minimum): one root of y − level, bracketed because y is monotone there and
/// found by bisection. So on each sub-piece g is either 0 (held, F(−t) = −G(t)) or y − level (free,
/// F(−t) = G(t) + constant): the outgoing wave is made of pieces of G with their sign changed or a constant
/// added, and by piecewise_polynomial.cpp no polynomial is ever re-expanded. After any number of windows F
/// and G are, coefficient for coefficient, the data's pieces up to signs and constant terms; the solution
/// is exact up to the round-off of the evaluations and of the event times. The same construction makes
/// the Signorini conditions hold exactly: during contact F(−t) + G(t) is −G(t) + G(t) = 0, in free flight
/// F′(−t) + G′(t) is −G′(t) + G′(t) = 0, bit for bit (the mirror is exact).
///
/// Conventions. A contact interval starts where y reaches its running minimum at or below 0 and ends
/// where β turns positive (with g = 0 and β ≤ 0 the point is held, also when λ = 0). An event within a few
/// ulps of the end of a piece is moved onto it (no slivers). Where F′ or G′ jumps (at a breakpoint, to
/// 1e-12 L) the derivatives take the mean of their one-sided values, as exact_solution.hpp does; so λ at
/// an impact or a release is the mean of its one-sided limits. β counts as positive only above the
/// rounding level of the data's slopes (64ε times the largest sum of |coefficients| of a slope): where the
/// exact β is 0 (a constant wave, as in S1 of mathematics.md §11 after its impact), the computed one is
/// rounding noise of either sign, which would otherwise release and re-take a held point at every
/// breakpoint, with a gap of the order of the noise. Restarting the Skorokhod map at the start
/// of every piece of G with y = g there is the same map (it has the flow property) and keeps y exactly
/// continuous across pieces.
#include "exact/characteristics.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <tuple>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// Initial data.

namespace {

const InitialDataPiece& data_piece(const InitialData& data, double x) {
  if (data.pieces.empty()) throw std::invalid_argument("initial data: no pieces");
  if (!(x >= 0.0 && x <= data.length()))
    throw std::out_of_range("initial data: x = " + std::to_string(x) + " outside [0, L]");
  const auto it = std::upper_bound(data.pieces.begin(), data.pieces.end(), x,
                                   [](double value, const InitialDataPiece& p) { return value < p.a; });
  return it == data.pieces.begin() ? data.pieces.front() : *(it - 1);
}

double local_variable(const InitialDataPiece& p, double x) { return (x - 0.5 * (p.a + p.b)) / (0.5 * (p.b - p.a)); }

// The shortest text that reads back as the same double ("0.4", not "0.40000000000000002").
std::string number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

double InitialData::displacement(double x) const {
  const InitialDataPiece& p = data_piece(*this, x);
  return poly::evaluate(p.displacement, local_variable(p, x));
}

double InitialData::velocity(double x) const {
  const InitialDataPiece& p = data_piece(*this, x);
  return poly::evaluate(p.velocity, local_variable(p, x));
}

void InitialData::validate() const {
  if (pieces.empty()) throw std::invalid_argument("initial data: no pieces");
  double scale = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const InitialDataPiece& p = pieces[k];
    const std::string where = "initial data, piece " + std::to_string(k) + ": ";
    if (!(std::isfinite(p.a) && std::isfinite(p.b) && p.b > p.a))
      throw std::invalid_argument(where + "the interval [a, b] must be finite with b > a");
    if (p.a != (k == 0 ? 0.0 : pieces[k - 1].b))
      throw std::invalid_argument(where + "the pieces must be contiguous and start at x = 0");
    for (const poly::Coefficients* c : {&p.displacement, &p.velocity})
      for (double v : *c)
        if (!std::isfinite(v)) throw std::invalid_argument(where + "every coefficient must be finite");
    for (double s : {-1.0, 1.0}) scale = std::max(scale, std::abs(poly::evaluate(p.displacement, s)));
  }
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const double left = poly::evaluate(pieces[k - 1].displacement, 1.0),
                 right = poly::evaluate(pieces[k].displacement, -1.0);
    if (!(std::abs(left - right) <= 1e-12 * scale))
      throw std::invalid_argument("initial data: u0 must be continuous (jump " + number(right - left) +
                                  " at x = " + number(pieces[k].a) + ")");
  }
  const double at_clamp = poly::evaluate(pieces.back().displacement, 1.0);
  if (at_clamp != 0.0)
    throw std::invalid_argument("initial data: u0(L) must be 0 (the clamp), got " + number(at_clamp));
  const double at_contact = poly::evaluate(pieces.front().displacement, -1.0);
  if (!(at_contact >= 0.0))
    throw std::invalid_argument("initial data: u0(0) must be >= 0 (the obstacle), got " + number(at_contact));
}

Problem InitialData::problem() const {
  Problem p;
  p.length = length();
  const InitialData data = *this;
  p.initial_displacement = [data](double x) { return data.displacement(x); };
  p.initial_velocity = [data](double x) { return data.velocity(x); };
  return p;
}

// Samples (x_k, u_k, v_k) interpolated linearly: on [x_k, x_{k+1}], with σ ∈ [−1, 1], a sample pair
// (f_k, f_{k+1}) is the polynomial (f_k + f_{k+1})/2 + (f_{k+1} − f_k)/2 σ.
InitialData initial_data_from_samples(const std::vector<double>& x, const std::vector<double>& u0,
                                      const std::vector<double>& v0) {
  if (x.size() != u0.size() || x.size() != v0.size())
    throw std::invalid_argument("initial data: the columns x, u0, v0 must have the same length");
  if (x.size() < 2)
    throw SampleError(x.size(), "initial data: at least 2 rows are needed (got " + std::to_string(x.size()) + ")");
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!(std::isfinite(x[k]) && std::isfinite(u0[k]) && std::isfinite(v0[k])))
      throw SampleError(k, "initial data: x, u0 and v0 must be finite numbers");
  if (x[0] != 0.0) throw SampleError(0, "initial data: the first x must be 0 (the contact point), got " + number(x[0]));
  for (std::size_t k = 1; k < x.size(); ++k)
    if (!(x[k] > x[k - 1]))
      throw SampleError(k,
                        "initial data: x must increase strictly (" + number(x[k]) + " after " + number(x[k - 1]) + ")");
  if (u0.back() != 0.0)
    throw SampleError(x.size() - 1, "initial data: u0(L) must be 0 (the clamp), got " + number(u0.back()));
  if (!(u0.front() >= 0.0))
    throw SampleError(0, "initial data: u0(0) must be >= 0 (the obstacle), got " + number(u0.front()));
  InitialData data;
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    data.pieces.push_back({x[k],
                           x[k + 1],
                           {0.5 * (u0[k] + u0[k + 1]), 0.5 * (u0[k + 1] - u0[k])},
                           {0.5 * (v0[k] + v0[k + 1]), 0.5 * (v0[k + 1] - v0[k])}});
  data.validate();
  return data;
}

// u⁰ = a (L − x) on one piece: with x = L/2 + (L/2) σ, u⁰ = aL/2 − (aL/2) σ.
InitialData benchmark_initial_data(double length, double amplitude) {
  if (!(std::isfinite(length) && length > 0))
    throw std::invalid_argument("benchmark data: L must be positive and finite");
  InitialData data;
  data.pieces.push_back({0.0, length, {0.5 * amplitude * length, -0.5 * amplitude * length}, {}});
  data.validate();
  return data;
}

TEST_CASE("sampled initial data are interpolated linearly, and bad samples are refused with their row") {
  const InitialData data = initial_data_from_samples({0.0, 0.5, 2.0}, {0.3, 0.1, 0.0}, {1.0, -1.0, 2.0});
  CHECK(data.length() == 2.0);
  CHECK(std::abs(data.displacement(0.25) - 0.2) < 1e-16);
  CHECK(std::abs(data.displacement(1.25) - 0.05) < 1e-16);
  CHECK(std::abs(data.velocity(0.125) - 0.5) < 1e-16);
  CHECK(std::abs(data.velocity(1.0) - 0.0) < 1e-16);
  const auto row_of = [](const std::vector<double>& x, const std::vector<double>& u, const std::vector<double>& v) {
    try {
      initial_data_from_samples(x, u, v);
    } catch (const SampleError& e) {
      return static_cast<long>(e.row());
    }
    return -1L;
  };
  CHECK(row_of({0.0, 0.5, 0.4, 1.0}, {0.1, 0.1, 0.1, 0.0}, {0, 0, 0, 0}) == 2);  // unsorted
  CHECK(row_of({0.0, 0.5, 0.5, 1.0}, {0.1, 0.1, 0.1, 0.0}, {0, 0, 0, 0}) == 2);  // repeated x
  CHECK(row_of({0.0, 0.5, 1.0}, {0.1, 0.1, 1e-3}, {0, 0, 0}) == 2);              // u⁰(L) ≠ 0
  CHECK(row_of({0.0, 0.5, 1.0}, {-0.1, 0.1, 0.0}, {0, 0, 0}) == 0);              // u⁰(0) < 0
  CHECK(row_of({0.0, 0.5, 1.0}, {0.1, NAN, 0.0}, {0, 0, 0}) == 1);               // not finite
  CHECK(row_of({0.0, 0.5, 1.0}, {0.1, 0.1, 0.0}, {0, INFINITY, 0}) == 1);
  CHECK(row_of({0.0}, {0.0}, {0.0}) == 1);                          // too few rows
  CHECK(row_of({0.1, 0.5, 1.0}, {0.1, 0.1, 0.0}, {0, 0, 0}) == 0);  // x₀ ≠ 0
  CHECK(row_of({0.0, 0.5, 1.0}, {0.1, 0.1, 0.0}, {0, 0, 0}) == -1);
  CHECK_THROWS_AS(initial_data_from_samples({0.0, 1.0}, {0.0}, {0.0, 0.0}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// The solver.

namespace {

// The part of the data's interval where the waves are polynomials: G = (u⁰ + V⁰)/2 and F = (u⁰ − V⁰)/2
// on one data piece, with V⁰(x) = V⁰(a) + ∫_a^x v⁰ = V⁰(a) + r (A(σ) − A(−1)), A the antiderivative of v⁰ in σ.
struct InitialWaves {
  PiecewisePolynomial right, left;
};

InitialWaves initial_waves(const InitialData& data) {
  InitialWaves w;
  double primitive = 0;  // V⁰(a) of the current piece
  for (const InitialDataPiece& p : data.pieces) {
    const double r = 0.5 * (p.b - p.a);
    poly::Coefficients v = poly::antiderivative(p.velocity);
    for (double& c : v) c *= r;
    v[0] += primitive - poly::evaluate(v, -1.0);
    const std::size_t n = std::max(p.displacement.size(), v.size());
    poly::Coefficients f(n, 0.0), g(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const double u = k < p.displacement.size() ? p.displacement[k] : 0.0, vk = k < v.size() ? v[k] : 0.0;
      f[k] = 0.5 * (u - vk);
      g[k] = 0.5 * (u + vk);
    }
    w.right.append(PolynomialPiece::on(p.a, p.b, f));
    w.left.append(PolynomialPiece::on(p.a, p.b, g));
    primitive = poly::evaluate(v, 1.0);
  }
  return w;
}

}  // namespace

CharacteristicSolution::CharacteristicSolution(const InitialData& data, double final_time) {
  data.validate();
  if (!(std::isfinite(final_time) && final_time > 0))
    throw std::invalid_argument("characteristic solution: the final time must be positive and finite");
  length_ = data.length();
  tie_ = 1e-12 * length_;
  const double horizon_scale = std::max(length_, final_time + 2 * length_);
  event_snap_ = 16 * std::numeric_limits<double>::epsilon() * horizon_scale;

  // 1. The waves on [0, L], and G on [L, 2L] from the clamp: G(η) = −F(2L − η). The rounding level of
  // their slopes (every later slope has the same coefficients up to sign).
  const InitialWaves waves = initial_waves(data);
  double slope_scale = 0;
  for (const PiecewisePolynomial* w : {&waves.right, &waves.left})
    for (const PolynomialPiece& p : w->pieces()) {
      double sum = 0;
      for (double c : p.slope) sum += std::abs(c);
      slope_scale = std::max(slope_scale, sum);
    }
  slope_noise_ = 64 * std::numeric_limits<double>::epsilon() * slope_scale;
  left_ = waves.left;
  for (std::size_t k = waves.right.pieces().size(); k-- > 0;)
    left_.append(waves.right.pieces()[k].mirrored(2 * length_).negated(), event_snap_);

  // 2. The march: each piece of G through the contact point gives pieces of s ↦ F(−s), which come back
  // from the clamp as G two windows later, until F(−s) is known a little beyond the final time (so that
  // a breakpoint at T has both its sides).
  gap_ = data.displacement(0.0);
  held_ = false;
  horizon_ = final_time;
  std::size_t incoming = 0, returned = 0;
  while (outgoing_.empty() || outgoing_.end() <= horizon_ + tie_) {
    if (incoming >= left_.pieces().size()) throw std::logic_error("characteristic solution: the march ran out of G");
    const PolynomialPiece piece = left_.pieces()[incoming++];
    advance_contact_point(piece);
    for (; returned < outgoing_.pieces().size(); ++returned)
      left_.append(outgoing_.pieces()[returned].translated(2 * length_).negated(), event_snap_);
  }
  // The contact intervals within [0, T]: one that begins after T is dropped, one still open ends at T.
  while (!contact_.empty() && contact_.back().start > horizon_) contact_.pop_back();
  if (!contact_.empty() && contact_.back().end >= horizon_) {
    contact_.back().end = horizon_;
    contact_.back().open = true;
  }

  // 3. F on [−T, L]: s ↦ F(−s) mirrored at 0, then the initial F.
  for (std::size_t k = outgoing_.pieces().size(); k-- > 0;)
    right_.append(outgoing_.pieces()[k].mirrored(0.0), event_snap_);
  first_initial_piece_ = right_.pieces().size();
  for (const PolynomialPiece& p : waves.right.pieces()) right_.append(p, event_snap_);
  outgoing_ = PiecewisePolynomial();
  energy_ = energy_at(0.0);
}

// One piece of G through the contact point: the Skorokhod reflection of y = g(a) + 2(G − G(a)) on it
// (derivation above). In the piece's variable σ, y(σ) = 2G(σ) + d with d = g(a) − 2G(σ_a); `level` is
// min(0, running minimum of y) since a.
void CharacteristicSolution::advance_contact_point(const PolynomialPiece& incoming) {
  const double sa = incoming.sigma(incoming.a), sb = incoming.sigma(incoming.b);
  std::vector<double> knots{sa};
  for (double s : poly::sign_changes(incoming.slope, sa, sb)) knots.push_back(s);
  knots.push_back(sb);
  const double d = gap_ - 2 * poly::evaluate(incoming.value, sa);
  const auto y = [&](double s) { return 2 * poly::evaluate(incoming.value, s) + d; };
  // The time of σ, an event moved onto the piece's start or end (or the last event) when within a few ulps.
  double start = incoming.a, level = 0;
  const auto time_of = [&](double s) {
    const double t = incoming.centre + incoming.radius * s;
    if (t - start <= event_snap_) return start;
    if (incoming.b - t <= event_snap_) return incoming.b;
    return t;
  };
  // Closes the sub-piece [start, end] of F(−s) with the current state: held, F(−s) = −G; free,
  // F(−s) = g − G = y − level − G = G + d − level.
  const auto close = [&](double end) {
    if (!(end > start)) return;
    const PolynomialPiece cut = incoming.restricted(start, end);
    outgoing_.append(held_ ? cut.negated() : cut.plus(d - level));
    start = end;
  };
  for (std::size_t j = 0; j + 1 < knots.size(); ++j) {
    const double s0 = knots[j], s1 = knots[j + 1];
    const bool decreasing = poly::evaluate(incoming.slope, 0.5 * (s0 + s1)) <= slope_noise_;
    if (!decreasing) {
      if (held_) {  // release: β turns positive
        close(j == 0 ? incoming.a : time_of(s0));
        held_ = false;
        contact_.back().end = start;
        contact_.back().open = false;
      }
      continue;
    }
    if (!held_) {
      if (y(s1) > level) continue;  // stays above the level on this monotone stretch
      const double root = y(s0) <= level ? s0 : [&] {
        double u = s0, v = s1;  // y − level > 0 at u, ≤ 0 at v
        for (;;) {
          const double mid = 0.5 * (u + v);
          if (!(mid > u && mid < v)) return v;
          (y(mid) - level > 0 ? u : v) = mid;
        }
      }();
      close(root == s0 && j == 0 ? incoming.a : time_of(root));
      held_ = true;
      // An impact at the end of the last contact interval (a sliver of free flight moved away) continues it.
      if (!contact_.empty() && start - contact_.back().end <= event_snap_ && !contact_.back().open)
        contact_.back().open = true;
      else
        contact_.push_back({start, start, true});
    }
    level = y(s1);
  }
  close(incoming.b);
  gap_ = held_ ? 0.0 : y(sb) - level;
  if (held_) contact_.back().end = incoming.b;
}

void CharacteristicSolution::check(double x, double t) const {
  if (!(x >= 0.0 && x <= length_))
    throw std::out_of_range("characteristic solution: x = " + number(x) + " outside [0, L] = [0, " + number(length_) +
                            "]");
  if (!(t >= 0.0 && t <= horizon_))
    throw std::out_of_range("characteristic solution: t = " + number(t) + " outside the computed [0, " +
                            number(horizon_) + "]");
}

double CharacteristicSolution::displacement(double x, double t) const {
  check(x, t);
  return right_.value(x - t) + left_.value(x + t);
}

// F′(x − t) with the mean of the one-sided values at a breakpoint, except at the corner x = 0, t = 0:
// there the solution is the data, u_x = u⁰′(0) and u_t = v⁰(0), so F′ is the initial one (ξ ≥ 0 side).
// (The outgoing side belongs to t > 0, where the contact law holds; the data need not satisfy it.)
double CharacteristicSolution::right_slope(double x, double t, std::size_t* hint) const {
  if (t <= tie_ && x <= tie_) return right_.pieces()[first_initial_piece_].derivative_at(x - t);
  return right_.derivative(x - t, tie_, hint);
}

double CharacteristicSolution::strain(double x, double t) const {
  check(x, t);
  return right_slope(x, t) + left_.derivative(x + t, tie_);
}

double CharacteristicSolution::velocity(double x, double t) const {
  check(x, t);
  return -right_slope(x, t) + left_.derivative(x + t, tie_);
}

double CharacteristicSolution::contact_displacement(double t) const { return displacement(0.0, t); }
// λ(t) = u_x(0, t) = F′(−t) + G′(t): exactly 0 in free flight, 2G′(t) = β ≤ 0 while held, where a
// positive value can only be the rounding noise of a β that is exactly 0 (see the conventions above): it
// is returned as 0. At t = 0 the data need not satisfy the contact law (a free end with u⁰′(0) ≠ 0, as in
// the benchmark): λ(0) is the limit from t > 0, with F′ taken on the outgoing side of ξ = 0 (the last
// piece before the initial F).
double CharacteristicSolution::contact_multiplier(double t) const {
  check(0.0, t);
  const double lambda =
      t > tie_ ? strain(0.0, t)
               : right_.pieces()[first_initial_piece_ - 1].derivative_at(-t) + left_.pieces().front().derivative_at(t);
  return std::min(0.0, lambda);
}

double CharacteristicSolution::energy_at(double t) const {
  check(0.0, t);
  return right_.integral_of_squared_derivative(-t, length_ - t) + left_.integral_of_squared_derivative(t, length_ + t);
}

// Sorted points: x − t and x + t increase with x, so the pieces are found by a walk from the last one.
void CharacteristicSolution::displacement_at_points(double t, const double* x, long count, double* u) const {
  std::size_t hr = 0, hl = 0;
  for (long i = 0; i < count; ++i) {
    check(x[i], t);
    u[i] = right_.value(x[i] - t, &hr) + left_.value(x[i] + t, &hl);
  }
}

void CharacteristicSolution::velocity_at_points(double t, const double* x, long count, double* v) const {
  std::size_t hr = 0, hl = 0;
  for (long i = 0; i < count; ++i) {
    check(x[i], t);
    v[i] = -right_slope(x[i], t, &hr) + left_.derivative(x[i] + t, tie_, &hl);
  }
}

// ---------------------------------------------------------------------------------------------------
// Tabulation on a lattice. A measure samples u and u_t at every node of every level: N = 3200 nodes over
// 12800 levels is 4·10⁷ evaluations of two polynomials of degree up to 14 each, seconds per run. On the
// lattice x = jδ, t = nδ the arguments x ∓ t are lattice points (j ∓ n)δ, so four tables over [−T, L] and
// [0, L + T], filled once, give every value by two look-ups.

/// The sets of points whose lattice indices were checked: each set's bits, and j₀ and s if they lie on the
/// lattice at j₀ + i s (a set that does not is remembered too). A run asks at the same nodes at every level,
/// so the check is made once per mesh, and a later set is compared with the remembered ones by memcmp. At
/// most 16 sets are remembered (a reference serves the runs of one mesh); beyond, a set is checked at
/// every call.
struct TabulatedSolution::PointSets {
  /// One set of points checked.
  struct Set {
    std::vector<double> points;  ///< the points x_0 … x_{count−1}, as asked
    bool on_lattice;             ///< whether x_i lies on the lattice at j₀ + i s for every i
    long first;                  ///< j₀
    long step;                   ///< s
  };
  std::mutex mutex;       ///< guards `sets` (a reference is shared by the runs on several threads)
  std::vector<Set> sets;  ///< the sets checked so far, at most 16
};

TabulatedSolution::TabulatedSolution(CharacteristicSolution solution, double spacing)
    : solution_(std::move(solution)),
      spacing_(spacing),
      inverse_spacing_(1.0 / spacing),
      point_sets_(std::make_shared<PointSets>()) {
  if (!(std::isfinite(spacing) && spacing > 0))
    throw std::invalid_argument("tabulated solution: the spacing must be positive and finite");
  const double length = solution_.length(), horizon = solution_.horizon();
  right_first_ = static_cast<long>(std::ceil(-horizon / spacing - 1e-9));
  const long right_last = static_cast<long>(std::floor(length / spacing + 1e-9));
  const long left_last = static_cast<long>(std::floor((length + horizon) / spacing + 1e-9));
  if (right_last - right_first_ + left_last > 100000000L)
    throw std::invalid_argument("tabulated solution: the spacing is too small for the horizon (over 1e8 entries)");
  const double tie = 1e-12 * length;
  std::size_t hint = 0;
  for (long k = right_first_; k <= right_last; ++k) {
    const double xi = std::min(length, std::max(-horizon, static_cast<double>(k) * spacing));
    right_value_.push_back(solution_.right_going().value(xi, &hint));
    right_slope_.push_back(solution_.right_going().derivative(xi, tie, &hint));
  }
  hint = 0;
  for (long k = 0; k <= left_last; ++k) {
    const double eta = std::min(length + horizon, static_cast<double>(k) * spacing);
    left_value_.push_back(solution_.left_going().value(eta, &hint));
    left_slope_.push_back(solution_.left_going().derivative(eta, tie, &hint));
  }
}

// For 0 ≤ x ≤ L + T (checked by the callers): the nearest lattice index by truncation of x/δ + ½.
bool TabulatedSolution::on_lattice(double x, long& index) const {
  index = static_cast<long>(x * inverse_spacing_ + 0.5);
  return std::abs(x - static_cast<double>(index) * spacing_) <= 1e-9 * spacing_;
}

// The points of a uniform mesh whose h is a multiple of δ, at a level n on the lattice (the error
// measures' every call): x_i = iL/N lies on the lattice at j_i = j₀ + i s, s = h/δ, and the look-ups of
// entry i are r₀ + i s and l₀ + i s, r₀ = j₀ − n − k₀ (k₀ = right_first_) and l₀ = j₀ + n. The indices are
// predicted from the first two points and checked as on_lattice checks them, point by point, with the
// same operations and no conversion to an integer: on_lattice takes the index j = ⌊x/δ + ½⌋ (a
// truncation of a positive double) and accepts |x − jδ| ≤ 10⁻⁹ δ; ⌊z⌋ = j for the integer j (exact in
// a double below 2⁵³) iff j ≤ z < j + 1, so the check accepts exactly the points that on_lattice maps to
// the predicted j and that lie in [0, L], as the per-point path requires. The check does not depend on
// the level: it is made once per set of points (lattice_points). The table bounds hold at both ends of
// the affine j at level n, hence everywhere. If the points are not on the lattice so, the per-point path
// below evaluates all of them. The corner x = 0, t = 0 is taken from the solution as there. So both
// paths give the same bits at every point (the doctest below compares them).
bool TabulatedSolution::lattice_points(const double* x, long count, long& first, long& step) const {
  const std::size_t size = static_cast<std::size_t>(count);
  PointSets& known = *point_sets_;
  {
    std::lock_guard<std::mutex> lock(known.mutex);
    for (const PointSets::Set& set : known.sets)
      if (set.points.size() == size && std::memcmp(set.points.data(), x, size * sizeof(double)) == 0) {
        first = set.first, step = set.step;
        return set.on_lattice;
      }
  }
  const double length = solution_.length();
  long j0 = 0, j1 = 0;
  bool lattice = count >= 2 && x[0] >= 0.0 && x[0] <= length && x[1] >= 0.0 && x[1] <= length && on_lattice(x[0], j0) &&
                 on_lattice(x[1], j1);
  if (lattice) {
    const double j_first = static_cast<double>(j0), j_step = static_cast<double>(j1 - j0), tolerance = 1e-9 * spacing_;
    for (long i = 0; i < count && lattice; ++i) {
      const double xi = x[i], j = j_first + static_cast<double>(i) * j_step, z = xi * inverse_spacing_ + 0.5;
      lattice = xi >= 0.0 && xi <= length && z >= j && z < j + 1.0 && std::abs(xi - j * spacing_) <= tolerance;
    }
  }
  first = j0, step = j1 - j0;
  std::lock_guard<std::mutex> lock(known.mutex);
  if (known.sets.size() < 16) known.sets.push_back({std::vector<double>(x, x + count), lattice, first, step});
  return lattice;
}

template <bool derivative>
bool TabulatedSolution::lattice_run(long n, const double* x, long count, double* out) const {
  long j0 = 0, s = 0;
  if (count < 2 || !lattice_points(x, count, j0, s)) return false;
  const long j_last = j0 + (count - 1) * s;
  const long right_size = static_cast<long>(right_value_.size()), left_size = static_cast<long>(left_value_.size());
  for (const long j : {j0, j_last})
    if (j < 0 || j - n - right_first_ < 0 || j - n - right_first_ >= right_size || j + n >= left_size) return false;
  const double* right = (derivative ? right_slope_.data() : right_value_.data()) + (j0 - n - right_first_);
  const double* left = (derivative ? left_slope_.data() : left_value_.data()) + (j0 + n);
  if (s == 1)  // δ = h: contiguous entries
    for (long i = 0; i < count; ++i) out[i] = derivative ? -right[i] + left[i] : right[i] + left[i];
  else
    for (long i = 0; i < count; ++i) out[i] = derivative ? -right[i * s] + left[i * s] : right[i * s] + left[i * s];
  if (n == 0)  // the corner x = 0, t = 0: j = 0
    for (long i = 0; i < count; ++i)
      if (j0 + i * s == 0) out[i] = derivative ? solution_.velocity(x[i], 0.0) : solution_.displacement(x[i], 0.0);
  return true;
}

bool TabulatedSolution::takes_lattice_run(double t, const double* x, long count) const {
  long n = 0;
  std::vector<double> scratch(static_cast<std::size_t>(std::max(count, 0L)));
  return t >= 0.0 && t <= solution_.horizon() && on_lattice(t, n) && lattice_run<false>(n, x, count, scratch.data());
}

template <bool derivative>
void TabulatedSolution::at_points(double t, const double* x, long count, double* out) const {
  long n = 0;
  const bool level_on_lattice = t >= 0.0 && t <= solution_.horizon() && on_lattice(t, n);
  if (level_on_lattice && lattice_run<derivative>(n, x, count, out)) return;
  const long right_size = static_cast<long>(right_value_.size()), left_size = static_cast<long>(left_value_.size());
  for (long i = 0; i < count; ++i) {
    long j = 0;
    const bool tabulated = level_on_lattice && x[i] >= 0.0 && x[i] <= solution_.length() && on_lattice(x[i], j) &&
                           j - n - right_first_ >= 0 && j - n - right_first_ < right_size && j + n < left_size;
    if (!tabulated || (n == 0 && j == 0)) {  // off the lattice, or the corner x = 0, t = 0
      out[i] = derivative ? solution_.velocity(x[i], t) : solution_.displacement(x[i], t);
      continue;
    }
    const std::size_t r = static_cast<std::size_t>(j - n - right_first_), l = static_cast<std::size_t>(j + n);
    out[i] = derivative ? -right_slope_[r] + left_slope_[l] : right_value_[r] + left_value_[l];
  }
}

void TabulatedSolution::displacement_at_points(double t, const double* x, long count, double* u) const {
  at_points<false>(t, x, count, u);
}

void TabulatedSolution::velocity_at_points(double t, const double* x, long count, double* v) const {
  at_points<true>(t, x, count, v);
}

// ---------------------------------------------------------------------------------------------------
// The closed form against the characteristics: two independent derivations of the benchmark's solution
// (exact_solution.cpp by phases, this file by windows), compared where both are defined.
//
// How far apart round-off can put them. For u⁰ = a (L − x), v⁰ = 0, F and G are piecewise linear with
// slopes ±a/2 and breakpoints at multiples of L (the impacts and releases t = kL, k ≢ 0 mod 3), and W =
// T/L windows build the horizon. Three sources, relative to aL:
//   (i) the evaluations. ξ = x − t and η = x + t are rounded by at most ½ulp(T + L) ≤ (T + L) ε/2 each, and
//       the slope a/2 turns this into a (T + L) ε/4 per wave; the constant terms, copied with a change of
//       sign or of constant once per window, carry at most W ε aL/2; the closed form reduces t to its
//       phase with an error of a few ulps of T, worth about a T ε (its slopes are at most a). Together
//       about 2 (W + 1) ε; allowed: 8 (W + 1) ε, for the local variables and the few operations after them.
//  (ii) the breakpoints. An outgoing piece comes back as an incoming one two windows later translated by
//       2L (translated(2L) above), which rounds its ends at the ulp of their new position, at most ε kL/2
//       in window k; the contact point then starts its events (t = kL, where y reaches 0) from these ends.
//       The errors of successive returns add: after W windows an event has moved by at most
//       Σ_{k ≤ W} ε kL/2 ≤ ε L W(W + 1)/4, and u, whose slope is at most a, by a times that; allowed:
//       ε W(W + 1)/2. Where every kL is a double (L = 1, L = 2.5), the translations are exact and this
//       term is 0; for L = 0.7 it dominates beyond a few tens of periods (measured against a long-double
//       evaluation of the closed form: the events of the characteristics drift, the closed form does
//       not; the first version of this bound, (i) alone, failed at 100 periods there).
// (iii) the derivatives. u_x, u_t and λ are sums of two slopes ±a/2, copied exactly (a change of sign):
//       off the kinks the two solutions agree exactly; on a kink both return the mean of the one-sided
//       values, which needs each to place the point on the kink; both snap a point within a few ulps of
//       a breakpoint onto it (event_snap_ here, 16 ε (T + 2L), the phase boundary there). So a difference
//       in a derivative is 0, or a half jump a/2 (the point put on different sides of a kink): not
//       round-off, and far above the bound.
// The bound of every entry is therefore ε (W(W + 1)/2 + 8 (W + 1)); over 10 periods (W = 30), 713 ε.

double ClosedFormDifference::largest() const {
  return std::max({displacement, strain, velocity, contact_displacement, contact_multiplier});
}

double closed_form_round_off_bound(double periods) {
  const double windows = 3 * periods;
  return std::numeric_limits<double>::epsilon() * (windows * (windows + 1) / 2 + 8 * (windows + 1));
}

ClosedFormDifference closed_form_difference(double length, double amplitude, double periods) {
  if (!(std::isfinite(length) && length > 0 && std::isfinite(amplitude) && amplitude > 0))
    throw std::invalid_argument("closed_form_difference: L > 0 and a > 0 must be finite");
  if (!(periods >= 1 && periods <= 1000))
    throw std::invalid_argument("closed_form_difference: periods must be in [1, 1000]");
  ClosedFormDifference d;
  d.length = length, d.amplitude = amplitude, d.periods = periods;
  const double horizon = 3 * length * periods, scale_u = amplitude * length, scale = amplitude;
  const CharacteristicSolution solution(benchmark_initial_data(length, amplitude), horizon);
  const ExactSolution exact(length, amplitude);
  const auto keep = [](double& largest, double difference, double s) {
    largest = std::max(largest, std::abs(difference) / s);
  };
  const auto compare = [&](double x, double t, bool derivatives) {
    keep(d.displacement, solution.displacement(x, t) - exact.displacement(x, t), scale_u);
    if (!derivatives) return;
    keep(d.strain, solution.strain(x, t) - exact.strain(x, t), scale);
    keep(d.velocity, solution.velocity(x, t) - exact.velocity(x, t), scale);
  };
  // (1) The lattice on the characteristics, the kinks among them.
  const int per_length = 40;
  const long levels = std::lround(3 * periods * per_length);
  for (long n = 0; n <= levels; ++n) {
    const double t = length * static_cast<double>(n) / per_length;
    if (t > horizon) break;  // the last level may round above T = 3L × periods
    for (int i = 0; i <= per_length; ++i)
      compare(length * i / per_length, t, !((i == 0 || i == per_length) && n % per_length == 0));
  }
  // (2) Points off the characteristics.
  const long off_levels = std::lround(300 * periods);
  for (int i = 0; i <= 40; ++i)
    for (long n = 0; n <= off_levels; n += 7)
      compare(length * (i + 0.37) / 41.3, horizon * (static_cast<double>(n) + 0.123) / (off_levels + 0.5), true);
  // (3) The contact point.
  const long instants = std::lround(3000 * periods);
  for (long n = 0; n <= instants; ++n) {
    const double t = horizon * static_cast<double>(n) / static_cast<double>(instants);
    keep(d.contact_displacement, solution.contact_displacement(t) - exact.contact_displacement(t), scale_u);
    keep(d.contact_multiplier, solution.contact_multiplier(t) - exact.contact_multiplier(t), scale);
  }
  return d;
}

TEST_CASE("the characteristic solution reproduces the closed-form benchmark to round-off over 10 periods") {
  // Any L and amplitude: every difference within the round-off bound derived above (W = 30 windows), and
  // the bound's growth with the number of windows: over 100 periods (W = 300) too, for one bar.
  for (const auto& [length, amplitude, periods] : {std::tuple<double, double, double>{1.0, 0.5, 10},
                                                   {2.5, 1e-3, 10},
                                                   {0.7, 1.7, 10},
                                                   {2.5, 0.3, 10},
                                                   {0.7, 1.7, 100}}) {
    CAPTURE(length);
    CAPTURE(amplitude);
    CAPTURE(periods);
    const double bound = closed_form_round_off_bound(periods);
    const ClosedFormDifference d = closed_form_difference(length, amplitude, periods);
    CAPTURE(bound);
    CAPTURE(d.displacement);
    CAPTURE(d.strain);
    CAPTURE(d.velocity);
    CAPTURE(d.contact_displacement);
    CAPTURE(d.contact_multiplier);
    CHECK(d.largest() <= bound);
    // The contact intervals [L, 2L] + 3kL and the energy a²L/2.
    const CharacteristicSolution solution(benchmark_initial_data(length, amplitude), 3 * length * periods);
    const std::size_t count = static_cast<std::size_t>(periods);
    REQUIRE(solution.contact_intervals().size() == count);
    for (std::size_t k = 0; k < count; ++k) {
      CAPTURE(k);
      CHECK(std::abs(solution.contact_intervals()[k].start - (3.0 * k + 1) * length) <= bound * length);
      CHECK(std::abs(solution.contact_intervals()[k].end - (3.0 * k + 2) * length) <= bound * length);
      CHECK_FALSE(solution.contact_intervals()[k].open);
    }
    const double energy = ExactSolution(length, amplitude).energy();
    CHECK(std::abs(solution.energy() - energy) <= bound * energy);
  }
}

TEST_CASE("the comparison with the closed form refuses bad bars and horizons") {
  CHECK_THROWS_AS(closed_form_difference(0.0, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(closed_form_difference(1.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(closed_form_difference(1.0, -0.5), std::invalid_argument);
  CHECK_THROWS_AS(closed_form_difference(1.0, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(closed_form_difference(1.0, 0.5, 0.5), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Checks for other data: the free-end formula, a brute-force running minimum and a grid scheme.

namespace {

// Sampled data on 81 points of [0, L] with a few contacts per period (u⁰(L) = 0 exactly).
InitialData wavy_samples(double length, double scale_u, double scale_v, double shift_v) {
  std::vector<double> x, u, v;
  for (int k = 0; k <= 80; ++k) {
    const double s = k / 80.0;
    x.push_back(length * s);
    u.push_back(k == 80 ? 0.0 : scale_u * (1 - s) * (1 + 0.5 * std::sin(7 * s)));
    v.push_back(scale_v * std::cos(5 * s) + shift_v);
  }
  return initial_data_from_samples(x, u, v);
}

// V⁰(x) = ∫₀ˣ v⁰ for linearly interpolated samples, exactly: the trapezoidal sums to the cell, then the
// quadratic inside it (independent of the solver's antiderivatives).
double primitive_of_velocity(const InitialData& data, double x) {
  double sum = 0;
  for (const InitialDataPiece& p : data.pieces) {
    const double v0 = data.velocity(p.a), v1 = poly::evaluate(p.velocity, 1.0), w = p.b - p.a;
    if (x >= p.b) {
      sum += 0.5 * w * (v0 + v1);
      continue;
    }
    const double d = x - p.a;
    return sum + v0 * d + 0.5 * (v1 - v0) * d * d / w;
  }
  return sum;
}

}  // namespace

TEST_CASE("the characteristic solution keeps the energy and satisfies the clamp, Signorini and d'Alembert") {
  for (const double length : {1.0, 1.7}) {
    const InitialData data = wavy_samples(length, 0.2, 0.3, -0.1);
    const double horizon = 12.0 * length;
    const CharacteristicSolution solution(data, horizon);
    CAPTURE(length);
    // Some contacts, and some releases: the data are not trivial.
    CHECK(solution.contact_intervals().size() >= 3);
    const double e0 = solution.energy(), scale_u = 0.3 * length;
    REQUIRE(e0 > 0);
    for (int n = 0; n <= 1200; ++n) {
      const double t = horizon * n / 1200.0 * (1 - 1e-12);
      CAPTURE(t);
      CHECK(std::abs(solution.energy_at(t) - e0) <= 1e-13 * e0);
      const double g = solution.contact_displacement(t), lambda = solution.contact_multiplier(t);
      CHECK(g >= -1e-15 * scale_u);
      CHECK(lambda <= 0.0);
      CHECK(g * lambda == 0.0);  // exactly: g is 0 in contact, λ is 0 in free flight (see above)
      CHECK(std::abs(solution.displacement(length, t)) <= 1e-15 * scale_u * 8);
      // The parallelogram rule of d'Alembert, at a point and a step that keep the rhombus inside.
      const double x = length * (0.2 + 0.6 * std::fmod(n * 0.618034, 1.0)), delta = 0.1 * length;
      if (t >= delta && t + delta <= horizon)
        CHECK(std::abs(solution.displacement(x, t + delta) + solution.displacement(x, t - delta) -
                       solution.displacement(x + delta, t) - solution.displacement(x - delta, t)) <= 1e-14 * scale_u);
    }
    // The contact intervals are where g = 0 and λ ≤ 0, and nowhere else (g > 0 between them).
    for (const ContactInterval& c : solution.contact_intervals()) {
      CAPTURE(c.start);
      CAPTURE(c.end);
      CHECK(c.end >= c.start);
      const double mid = 0.5 * (c.start + c.end);
      CHECK(solution.contact_displacement(mid) == 0.0);
    }
    for (std::size_t k = 0; k + 1 < solution.contact_intervals().size(); ++k) {
      const double free_mid = 0.5 * (solution.contact_intervals()[k].end + solution.contact_intervals()[k + 1].start);
      CHECK(solution.contact_displacement(free_mid) > 0.0);
      CHECK(solution.contact_multiplier(free_mid) == 0.0);
    }
  }
}

TEST_CASE(
    "the contact point is the Skorokhod reflection of the incoming wave (against a brute-force running minimum)") {
  // In the first window, y(t) = u⁰(0) + 2(G(t) − G(0)) with G = (u⁰ + V⁰)/2 straight from the data;
  // g = y − min(0, running minimum of y) on a fine grid. The grid misses the true minimum between two
  // grid points by at most max|y″| δ²/8: δ = 1/200000 gives ≤ 1e-10 here.
  const InitialData data = wavy_samples(1.0, 0.2, 0.3, -0.1);
  const CharacteristicSolution solution(data, 1.0);
  const auto incoming = [&](double t) { return 0.5 * (data.displacement(t) + primitive_of_velocity(data, t)); };
  const double g0 = data.displacement(0.0), G0 = incoming(0.0);
  double running_minimum = 0, largest = 0;
  const int steps = 200000;
  int held = 0;
  for (int j = 0; j <= steps; ++j) {
    const double t = static_cast<double>(j) / steps;
    const double y = g0 + 2 * (incoming(t) - G0);
    running_minimum = std::min(running_minimum, y);
    const double g = y - running_minimum;
    held += g == 0.0;
    largest = std::max(largest, std::abs(solution.contact_displacement(t) - g));
  }
  CHECK(held > steps / 50);  // the first window has contact
  CHECK(largest <= 1e-10);
}

TEST_CASE("used as a grid scheme with dt = h, the characteristics are exact at the nodes") {
  // The characteristic scheme on x_i = ih, t_n = nh: the right-going values Fᵢⁿ = F(xᵢ − tₙ) move one node
  // to the right per step and the left-going ones Gᵢⁿ = G(xᵢ + tₙ) one node to the left; at the clamp
  // G_N = −F_N; at the contact point gⁿ⁺¹ = max(0, gⁿ + 2(G₀ⁿ⁺¹ − G₀ⁿ)) and F₀ⁿ⁺¹ = gⁿ⁺¹ − G₀ⁿ⁺¹ (one
  // step of the Skorokhod reflection, exact when y is monotone over the step: contact events on the grid).
  // Started from F = (u⁰ − V⁰)/2, G = (u⁰ + V⁰)/2 at the nodes, computed here from the data directly.
  struct Case {
    InitialData data;
    double horizon;
    const char* name;
  };
  std::vector<Case> cases;
  cases.push_back({benchmark_initial_data(1.0, 0.5), 30.0, "benchmark, L = 1"});
  cases.push_back({benchmark_initial_data(2.0, 0.3), 20.0, "benchmark, L = 2"});
  // Sampled data on the grid's own nodes that move away from the obstacle (no contact before T).
  {
    std::vector<double> x, u, v;
    for (int k = 0; k <= 32; ++k) {
      const double s = k / 32.0;
      x.push_back(s);
      u.push_back(k == 32 ? 0.0 : 0.1 * (1 - s) * (1 + 0.3 * s * s));
      v.push_back(1.0 + 0.3 * std::sin(5 * s));
    }
    cases.push_back({initial_data_from_samples(x, u, v), 1.75, "free flight"});
  }
  for (const Case& c : cases) {
    const CharacteristicSolution solution(c.data, c.horizon);
    const double length = c.data.length();
    for (const long elements : {8L, 32L}) {
      if (std::string(c.name) == "free flight" && elements != 32) continue;  // samples on this grid only
      CAPTURE(c.name);
      CAPTURE(elements);
      const double h = length / static_cast<double>(elements);
      std::vector<double> right(static_cast<std::size_t>(elements) + 1), left(right.size());
      for (std::size_t i = 0; i < right.size(); ++i) {
        const double x = length * static_cast<double>(i) / static_cast<double>(elements);
        const double u0 = c.data.displacement(x), v0 = primitive_of_velocity(c.data, x);
        right[i] = 0.5 * (u0 - v0);
        left[i] = 0.5 * (u0 + v0);
      }
      double gap = c.data.displacement(0.0), largest = 0;
      const long steps = std::lround(c.horizon / h);
      for (long n = 1; n <= steps; ++n) {
        const double incoming_before = left[0];
        for (std::size_t i = right.size() - 1; i > 0; --i) right[i] = right[i - 1];
        for (std::size_t i = 0; i + 1 < left.size(); ++i) left[i] = left[i + 1];
        left.back() = -right.back();
        gap = std::max(0.0, gap + 2 * (left[0] - incoming_before));
        right[0] = gap - left[0];
        const double t = std::min(static_cast<double>(n) * h, solution.horizon());
        for (std::size_t i = 0; i < right.size(); ++i) {
          const double x = length * static_cast<double>(i) / static_cast<double>(elements);
          largest = std::max(largest, std::abs(solution.displacement(x, t) - (right[i] + left[i])));
        }
      }
      CHECK(largest <= 1e-14 * length);
    }
  }
}

TEST_CASE("data that never touch the obstacle give the free-end solution") {
  // The bar free at 0 and clamped at L: d'Alembert with the data extended evenly about 0 and oddly
  // about L (period 4L), u = ½(ũ(x − t) + ũ(x + t)) + ½(Ṽ(x + t) − Ṽ(x − t)), Ṽ the matching extension of
  // V⁰ (odd about 0, even about L). The data move away from the obstacle: u(0, t) = ũ(t) + Ṽ(t) > 0 on
  // (0, T] (checked first), T = 1.8 L.
  std::vector<double> xs, us, vs;
  for (int k = 0; k <= 50; ++k) {
    const double s = k / 50.0;
    xs.push_back(s);
    us.push_back(k == 50 ? 0.0 : 0.1 * (1 - s) * (1 + 0.3 * s * s));
    vs.push_back(1.0 + 0.3 * std::sin(5 * s));
  }
  const InitialData data = initial_data_from_samples(xs, us, vs);
  const double length = 1.0, horizon = 1.8;
  const auto extended = [&](double xi, double& u, double& v) {
    xi = std::fmod(xi, 4 * length);
    if (xi >= 2 * length) xi -= 4 * length;
    if (xi < -2 * length) xi += 4 * length;
    const double sign_v = xi < 0 ? -1.0 : 1.0;
    xi = std::abs(xi);
    if (xi <= length) {
      u = data.displacement(xi);
      v = sign_v * primitive_of_velocity(data, xi);
    } else {
      u = -data.displacement(2 * length - xi);
      v = sign_v * primitive_of_velocity(data, 2 * length - xi);
    }
  };
  const auto free_end = [&](double x, double t) {
    double ul, vl, ur, vr;
    extended(x - t, ul, vl);
    extended(x + t, ur, vr);
    return 0.5 * (ul + ur) + 0.5 * (vr - vl);
  };
  for (int n = 1; n <= 1000; ++n) REQUIRE(free_end(0.0, horizon * n / 1000.0) > 0.0);
  const CharacteristicSolution solution(data, horizon);
  CHECK(solution.contact_intervals().empty());
  double largest = 0;
  for (int i = 0; i <= 50; ++i)
    for (int n = 0; n <= 900; ++n) {
      const double x = length * i / 50.0, t = horizon * n / 900.0;
      largest = std::max(largest, std::abs(solution.displacement(x, t) - free_end(x, t)));
    }
  CHECK(largest <= 1e-14);
  // The free end's stress is zero throughout.
  for (int n = 0; n <= 900; ++n) CHECK(solution.contact_multiplier(horizon * n / 900.0) == 0.0);
}

TEST_CASE("the tabulated solution gives the solver's values on the lattice and evaluates directly elsewhere") {
  const InitialData data = wavy_samples(1.0, 0.2, 0.3, -0.1);
  const CharacteristicSolution solution(data, 3.0);
  for (const long elements : {10L, 64L}) {
    const double h = 1.0 / static_cast<double>(elements);
    const TabulatedSolution tabulated(solution, 0.5 * h);
    std::vector<double> x(static_cast<std::size_t>(elements)), u(x.size()), v(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<double>(i) / static_cast<double>(elements);
    CAPTURE(elements);
    // Levels on the lattice (Δt = h/2 and h), and off it (Δt = 0.37 h): the same values to round-off.
    for (const double dt : {0.5 * h, h, 0.37 * h}) {
      double largest_u = 0, largest_v = 0;
      for (long n = 0; static_cast<double>(n) * dt <= 3.0; ++n) {
        const double t = static_cast<double>(n) * dt;
        tabulated.displacement_at_points(t, x.data(), static_cast<long>(x.size()), u.data());
        tabulated.velocity_at_points(t, x.data(), static_cast<long>(x.size()), v.data());
        for (std::size_t i = 0; i < x.size(); ++i) {
          largest_u = std::max(largest_u, std::abs(u[i] - solution.displacement(x[i], t)));
          largest_v = std::max(largest_v, std::abs(v[i] - solution.velocity(x[i], t)));
        }
      }
      CAPTURE(dt);
      CHECK(largest_u <= 1e-15);
      CHECK(largest_v <= 1e-13);
    }
  }
  CHECK_THROWS_AS(TabulatedSolution(solution, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(TabulatedSolution(solution, 1e-12), std::invalid_argument);
}

TEST_CASE("the tabulated solution's straight loop over a mesh on the lattice gives the per-point path's bits") {
  // Prediction: lattice_run reads the entries the per-point path reads, at the points on_lattice maps
  // to the predicted indices, and leaves every other set of points to that path: the same bits at every
  // point, on and off the lattice. A call with one point always takes the per-point path, so it is the
  // reference; takes_lattice_run says which path the call took, so the comparison cannot pass by
  // falling back.
  const InitialData data = wavy_samples(1.0, 0.2, 0.3, -0.1);
  const CharacteristicSolution solution(data, 1.5);
  const auto bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  long fast = 0, per_point = 0;
  const auto compare = [&](const TabulatedSolution& tabulated, double t, const std::vector<double>& x, bool lattice) {
    const long count = static_cast<long>(x.size());
    std::vector<double> u(x.size()), v(x.size()), u1(x.size()), v1(x.size());
    tabulated.displacement_at_points(t, x.data(), count, u.data());
    tabulated.velocity_at_points(t, x.data(), count, v.data());
    for (std::size_t i = 0; i < x.size(); ++i) {
      tabulated.displacement_at_points(t, &x[i], 1, &u1[i]);
      tabulated.velocity_at_points(t, &x[i], 1, &v1[i]);
    }
    CAPTURE(t);
    CAPTURE(count);
    CHECK(bits(u, u1));
    CHECK(bits(v, v1));
    const bool took = tabulated.takes_lattice_run(t, x.data(), count);
    CHECK(took == lattice);
    (took ? fast : per_point) += 1;
  };
  for (const long elements : {8L, 25L, 64L}) {
    const double h = 1.0 / static_cast<double>(elements);
    CAPTURE(elements);
    for (const long ratio : {1L, 2L, 3L}) {  // δ = h/ratio: the nodes at j = ratio·i
      const TabulatedSolution tabulated(solution, h / static_cast<double>(ratio));
      const double delta = h / static_cast<double>(ratio);
      CAPTURE(ratio);
      std::vector<double> nodes(static_cast<std::size_t>(elements));  // x_i = iL/N, node N clamped
      for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = static_cast<double>(i) / static_cast<double>(elements);
      std::vector<double> closed = nodes;  // with x = L, the last entry of the tables at t = T
      closed.push_back(1.0);
      const long last_level = static_cast<long>(std::floor(solution.horizon() / delta + 1e-9));
      // Levels on the lattice: t = 0 (the corner x = 0), the first ones, the middle, the last one (t = T).
      for (const long n : {0L, 1L, 2L, last_level / 2, last_level - 1, last_level}) {
        const double t = static_cast<double>(n) * delta;
        compare(tabulated, t, nodes, true);
        compare(tabulated, t, closed, true);
        // Without the first node (no corner), every other node, the nodes backwards (s < 0): still affine.
        compare(tabulated, t, std::vector<double>(nodes.begin() + 1, nodes.end()), true);
        std::vector<double> every_other;
        for (std::size_t i = 0; i < nodes.size(); i += 2) every_other.push_back(nodes[i]);
        compare(tabulated, t, every_other, true);
        compare(tabulated, t, std::vector<double>(closed.rbegin(), closed.rend()), true);
        // A node moved within on_lattice's tolerance (10⁻⁹ δ): the same index, the fast path.
        std::vector<double> near = nodes;
        near[nodes.size() / 2] += 1e-11 * delta;
        compare(tabulated, t, near, true);
        // A node moved off the lattice (in the middle, at the ends), a node skipped (not affine), a
        // node beyond the bar: the per-point path, for all of them.
        for (const std::size_t at : {std::size_t{0}, nodes.size() / 2, nodes.size() - 1}) {
          std::vector<double> moved = nodes;
          moved[at] += 1e-6 * delta;
          compare(tabulated, t, moved, false);
          moved[at] = nodes[at] + 0.5 * delta;  // half-way between two lattice points
          compare(tabulated, t, moved, false);
        }
        std::vector<double> skipped = nodes;
        skipped.erase(skipped.begin() + static_cast<std::ptrdiff_t>(nodes.size() / 2));
        compare(tabulated, t, skipped, false);
      }
      // Instants off the lattice: the per-point path (direct evaluation), the same bits as one point.
      for (const double t : {0.37 * delta, (static_cast<double>(last_level / 2) + 0.37) * delta})
        compare(tabulated, t, nodes, false);
      // Beyond the bar or the horizon: neither path evaluates, both refuse.
      std::vector<double> beyond = closed;
      beyond.back() = 1.0 + delta;
      std::vector<double> u(beyond.size());
      CHECK(!tabulated.takes_lattice_run(0.5, beyond.data(), static_cast<long>(beyond.size())));
      CHECK_THROWS_AS(tabulated.displacement_at_points(0.5, beyond.data(), static_cast<long>(beyond.size()), u.data()),
                      std::out_of_range);
      CHECK_THROWS_AS(tabulated.velocity_at_points(solution.horizon() + delta, nodes.data(),
                                                   static_cast<long>(nodes.size()), u.data()),
                      std::out_of_range);
    }
  }
  // A mesh whose h is not a multiple of δ (δ = 2h/3): every third point is on the lattice, the rest not.
  {
    const TabulatedSolution tabulated(solution, 2.0 / 30.0);
    std::vector<double> x(20);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<double>(i) / 20.0;
    compare(tabulated, 0.0, x, false);
    compare(tabulated, 10 * 2.0 / 30.0, x, false);
  }
  CHECK(fast > 0);
  CHECK(per_point > 0);
}

TEST_CASE("the characteristic solution refuses bad data and points outside its domain") {
  InitialData data = benchmark_initial_data(1.0, 0.5);
  CHECK_THROWS_AS(CharacteristicSolution(data, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(CharacteristicSolution(data, NAN), std::invalid_argument);
  const CharacteristicSolution solution(data, 2.0);
  CHECK(solution.horizon() >= 2.0);
  CHECK_THROWS_AS(solution.displacement(1.5, 0.5), std::out_of_range);
  CHECK_THROWS_AS(solution.displacement(0.5, -0.1), std::out_of_range);
  CHECK_THROWS_AS(solution.velocity(0.5, solution.horizon() + 1.0), std::out_of_range);
  data.pieces[0].displacement = {0.25, 0.25};  // u⁰(L) = 0.5 ≠ 0
  CHECK_THROWS_WITH_AS(CharacteristicSolution(data, 1.0), doctest::Contains("u0(L) must be 0"), std::invalid_argument);
  data.pieces[0].displacement = {-0.5, 0.5};  // u⁰(0) = −1 < 0
  CHECK_THROWS_WITH_AS(CharacteristicSolution(data, 1.0), doctest::Contains("u0(0) must be >= 0"),
                       std::invalid_argument);
}

}  // namespace mrm
