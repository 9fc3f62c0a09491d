/// @file impact_solution.cpp
/// @brief The exact solution of the field's impact benchmarks: loads, a free far end, gaps, layered
/// bars and two bars in contact (doc/benchmarks.md), by characteristics in time and Skorokhod reflections.
///
/// The problem. A chain of segments [x_j, x_{j+1}], each homogeneous (E_j, ρ_j, wave speed
/// c_j = √(E_j/ρ_j), impedance Z_j = ρ_j c_j, transit time τ_j = ℓ_j/c_j), with
///
///     ρ u_tt − (E u_x)_x = f(x)                                  in each segment,
///
/// f a polynomial in each segment. A junction is welded (u and the stress σ = E u_x continuous) or a
/// unilateral contact between the segment A on its left and B on its right: with the initial distance
/// g₀ ≥ 0, the gap z = u_B − u_A + g₀ ≥ 0, the stresses on both sides equal, σ ≤ 0 (compression) and
/// zσ = 0. The left end x = 0 is free or held off a rigid obstacle (the same law with u_A ≡ 0:
/// z = u(0, t) + g₀, λ = σ(0, t) = E u_x(0, t), the project's λ for E = 1); the right end is clamped or
/// free. The segments between two contacts form a body.
///
/// 1. The load (d'Alembert–Duhamel with a polynomial particular solution). In each body take
/// u_p(x, t) = α t²/2 + q(x) with ρα − (E q′)′ = f, so that u_p solves the equation, and choose its
/// stress E q′ to vanish at every end of the body that is a contact or free:
///   - a body with a clamped end: α = 0, E q′(x) = −∫_{a}^{x} f (zero at its left end a, a contact),
///     q(clamp) = 0;
///   - a free body (no clamp): α = ∫f / ∫ρ (the rigid acceleration of the total force), and then
///     E q′(x) = ∫_a^x (ρα − f) vanishes at both ends; q(a) = 0.
/// E q′ is continuous across welded junctions (it is an integral), and q is continuous (integrated once
/// more, piecewise, with 1/E_j). Then w = u − u_p solves the homogeneous equation with the homogeneous
/// end conditions (w = 0 at a clamp since u_p = 0 there, σ_w = σ at a free end or a contact since E q′ = 0
/// there), the data w⁰ = u⁰ − q, v⁰, and the contact law with a moved barrier:
///     z = w_B − w_A − ℓ(t) ≥ 0,   ℓ(t) = −g₀ − (q_B − q_A)(x_J) − (α_B − α_A) t²/2,
/// a polynomial of degree 2 in t (u_pA ≡ 0 for the obstacle). A free body falling under gravity, the
/// bouncing bar, has α = −g, q = 0: w is the motion seen from the falling frame and the floor rises
/// towards it as ℓ(t) = −g₀ + g t²/2. For f = 0 everything reduces to u_p = 0, ℓ = −g₀.
///
/// 2. Waves in time. In segment j with θ = (x − x_j)/c_j ∈ [0, τ_j],
///     w = F_j(t − θ) + G_j(t + θ):   w_t = F_j′ + G_j′,   σ_w = E_j w_x = Z_j (G_j′ − F_j′).
/// F_j(t) is what enters the segment at its left end at time t, G_j(t) what arrives there; F_j(t − τ_j)
/// arrives at the right end and G_j(t + τ_j) leaves it. At t = 0 (w⁰ = F_j(−θ) + G_j(θ),
/// v⁰ = F_j′(−θ) + G_j′(θ)), with V(θ) = ∫_0^θ v⁰ dθ′ = (1/c_j) ∫_{x_j}^{x} v⁰:
///     G_j(θ) = (w⁰ + V)/2,  F_j(−θ) = (w⁰ − V)/2    for θ ∈ [0, τ_j]
/// (the constant that could move between F and G is fixed by V(0) = 0). A data piece in its variable
/// σ = (x − m)/r is, in θ, the same polynomial with centre (m − x_j)/c_j and radius r/c_j: no
/// re-expansion. w is continuous in t, so every wave is continuous where it starts to be emitted.
///
/// 3. Junctions. At a junction at time t write p = F_A(t − τ_A) and q = G_B(t) (arriving from the left and
/// from the right), r = G_A(t + τ_A) and s = F_B(t) (leaving to the left and to the right):
/// w_A = p + r, w_B = q + s, σ_A = Z_A(r′ − p′), σ_B = Z_B(q′ − s′).
///   - clamped right end: w = 0, so r = −p (odd reflection);
///   - free end: σ = 0, so r′ = p′ (even reflection), r = p + constant (and s = q + constant at a free
///     left end);
///   - welded: w_A = w_B and σ_A = σ_B give, by eliminating s, Z_A(r′ − p′) = Z_B(2q′ − p′ − r′):
///         r′ = R_A p′ + T_B q′,  s′ = T_A p′ + R_B q′,
///         R_A = (Z_A − Z_B)/(Z_A + Z_B) = −R_B,  T_A = 2Z_A/(Z_A + Z_B),  T_B = 2Z_B/(Z_A + Z_B),
///     the classical reflection and transmission of a displacement (or velocity) wave; a strain wave
///     transmits (Z_A/Z_B)·(c_B/c_A)… no need: everything here is in displacement and time.
///   - contact. Separated, both ends are free: r′ = p′, s′ = q′, and the gap moves with
///         z′ = w_B′ − w_A′ − ℓ′ = 2q′ − 2p′ − ℓ′ =: β(t),
///     known from the past (what arrives). Closed (z = 0): w_B = w_A + ℓ and σ_A = σ_B. Eliminating
///     s = p + r + ℓ − q as in the welded case, Z_A(r′ − p′) = Z_B(2q′ − p′ − r′ − ℓ′):
///         r′ = R_A p′ + T_B q′ − Z_B/(Z_A + Z_B) ℓ′,
///     and then the common stress is
///         σ = Z_A(r′ − p′) = μ (2q′ − 2p′ − ℓ′) = μ β,   μ = Z_A Z_B/(Z_A + Z_B)
///     (the obstacle is Z_A → ∞ with p = 0: s = ℓ − q, σ = Z_B β). Signorini admits it (σ ≤ 0) exactly
///     while β ≤ 0. So, for any impedances, the contact is the one of mathematics.md §10 for the path
///     y(t) = z(t₀) + ∫_{t₀}^t β: z is its Skorokhod reflection at 0,
///         z(t) = y(t) − min(0, min_{t₀ ≤ s ≤ t} y(s)),
///     free while z > 0 or β > 0, closed otherwise, and λ = σ = μβ ≤ 0 while closed, 0 while open.
///     With equal impedances the closed contact is transparent (R = 0, T = 1), and two equal bars with
///     opposite velocities are symmetric about the contact plane: each is one bar on a rigid wall.
///
/// 4. Exactness and the march. On a stretch where p, q are single polynomial pieces, β is a polynomial
/// (degree ≤ max(deg p, deg q, 2)); its sign changes are found to full precision (piecewise_polynomial.cpp)
/// and y is monotone between them, so the Skorokhod map reduces to one bracketed root of y − level per
/// impact, found by bisection, and every outgoing wave is a fixed linear combination of the incoming ones
/// plus ℓ and a constant. A junction at time t needs F_A before t − τ_A and G_B at t, which the
/// neighbouring junctions emitted before t − τ: the march proceeds in windows of length min_j τ_j, each
/// junction turning its incoming pieces over the window into outgoing ones. Unlike the clamped,
/// homogeneous solver (characteristics.cpp: only sign changes and constants, bit-exact mirrors) a
/// junction here combines two pieces in a common local variable (the window's stretch), so each
/// reflection re-expands a polynomial about a nearby centre: round-off per reflection, of order ε times
/// the size of the waves, adding up linearly with the number of reflections. The constants are fixed by
/// continuity in time of every wave at the start of each stretch (w is continuous), which keeps the
/// waves continuous and the displacement exact to the same round-off. The number of pieces grows with
/// the number of wave fronts: linearly for one homogeneous body, and geometrically with the number of
/// interfaces for a layered bar whose transit times are incommensurate; the solver counts its pieces
/// and refuses a horizon that would need more than a given number (it is then not computable exactly
/// in reasonable memory).
///
/// Conventions (as in characteristics.cpp): an event within a few ulps of a stretch's end is moved onto
/// it; a derivative at a breakpoint (to 1e-12 of the time scale) is the mean of its one-sided values; a
/// β counts as positive only above the rounding level of its coefficients.
#include "exact/impact_solution.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "core/problem.hpp"

namespace mrm {

namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon();

[[noreturn]] void refuse(const std::string& what) { throw InvalidParameter("configuration", what); }

// p(α + βσ) as a polynomial in σ (Horner's rule on polynomials).
poly::Coefficients composed(const poly::Coefficients& c, double alpha, double beta) {
  poly::Coefficients r;
  for (std::size_t k = c.size(); k-- > 0;) {
    r = poly::product(r, {alpha, beta});
    if (r.empty()) r.push_back(0.0);
    r[0] += c[k];
  }
  return r;
}

// The piece with the given interval, local variable and coefficients.
PolynomialPiece piece_in(double a, double b, double centre, double radius, poly::Coefficients c) {
  PolynomialPiece p;
  p.a = a;
  p.b = b;
  p.centre = centre;
  p.radius = radius;
  poly::trim(c);
  p.value = c;
  p.slope = poly::derivative(c);
  for (double& s : p.slope) s /= radius;
  return p;
}

// A piece's polynomial written in the variable (t − centre)/radius.
poly::Coefficients in_variable(const PolynomialPiece& p, double centre, double radius) {
  return composed(p.value, (centre - p.centre) / p.radius, radius / p.radius);
}

poly::Coefficients combination(double a, const poly::Coefficients& p, double b, const poly::Coefficients& q) {
  poly::Coefficients r(std::max(p.size(), q.size()), 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) r[k] += a * p[k];
  for (std::size_t k = 0; k < q.size(); ++k) r[k] += b * q[k];
  return r;
}

poly::Coefficients plus_constant(poly::Coefficients p, double d) {
  if (p.empty()) p.push_back(0.0);
  p[0] += d;
  return p;
}

// A wave's argument moved into its domain: the ends of F_j (−τ_j) and G_j (τ_j) are computed from the data's
// breakpoints, the arguments from τ_j = ℓ_j/c_j, which may differ in the last bit.
double inside(const PiecewisePolynomial& wave, double x) { return std::min(wave.end(), std::max(wave.begin(), x)); }

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

double ImpactConfiguration::length() const {
  double sum = 0;
  for (const BarSegment& s : segments) sum += s.length;
  return sum;
}

void ImpactConfiguration::validate() const {
  if (segments.empty()) refuse("at least one bar segment is needed");
  for (std::size_t j = 0; j < segments.size(); ++j) {
    const BarSegment& s = segments[j];
    const std::string where = "segment " + std::to_string(j) + ": ";
    for (double v : {s.length, s.modulus, s.density})
      if (!(std::isfinite(v) && v > 0)) refuse(where + "length, E and rho must be positive and finite");
    for (double c : s.load)
      if (!std::isfinite(c)) refuse(where + "the load's coefficients must be finite");
  }
  if (!junctions.empty() && junctions.size() + 1 != segments.size())
    refuse("there must be one junction per pair of consecutive segments (or none: all welded)");
  bool any_contact = obstacle;
  for (const SegmentJunction& j : junctions) {
    if (!(std::isfinite(j.gap) && j.gap >= 0)) refuse("a junction's gap must be finite and >= 0");
    if (!j.contact && j.gap != 0) refuse("a welded junction has no gap (allowed: gap 0, or a contact junction)");
    any_contact = any_contact || j.contact;
  }
  if (!(std::isfinite(obstacle_gap) && obstacle_gap >= 0)) refuse("the obstacle gap must be finite and >= 0");
  if (!obstacle && obstacle_gap != 0) refuse("an obstacle gap needs the obstacle");
  if (!any_contact) refuse("no contact: an obstacle or a contact junction is needed");
}

ImpactSolution::ImpactSolution(ImpactConfiguration configuration, const InitialData& data, double final_time,
                               std::size_t max_pieces)
    : config_(std::move(configuration)) {
  config_.validate();
  const std::size_t n = config_.segments.size();
  if (config_.junctions.empty()) config_.junctions.assign(n - 1, SegmentJunction{});
  if (!(std::isfinite(final_time) && final_time > 0))
    throw InvalidParameter("final_time", "the final time must be positive and finite");
  horizon_ = final_time;
  const double total = config_.length();

  // Geometry and the waves' constants.
  origin_.assign(n + 1, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const BarSegment& s = config_.segments[j];
    origin_[j + 1] = origin_[j] + s.length;
    const double c = std::sqrt(s.modulus / s.density);
    travel_.push_back(s.length / c);
    impedance_.push_back(s.density * c);
  }
  const double longest = *std::max_element(travel_.begin(), travel_.end());
  const double scale_t = final_time + 2 * std::accumulate(travel_.begin(), travel_.end(), 0.0) + longest;
  snap_ = 64 * epsilon * scale_t;
  tie_ = 1e-12 * scale_t;

  // 1. The particular solution, body by body (derivation §1).
  acceleration_.assign(n, 0.0);
  static_.resize(n);
  static_stress_.resize(n);
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first;
    while (last + 1 < n && !config_.junctions[last].contact) ++last;
    const bool clamped = last + 1 == n && config_.far_end == FarEnd::clamped;
    double mass = 0, force = 0;
    for (std::size_t j = first; j <= last; ++j) {
      const BarSegment& s = config_.segments[j];
      const poly::Coefficients a = poly::antiderivative(s.load);
      mass += s.density * s.length;
      force += 0.5 * s.length * (poly::evaluate(a, 1.0) - poly::evaluate(a, -1.0));
    }
    const double alpha = clamped ? 0.0 : force / mass;
    double stress = 0, value = 0;
    for (std::size_t j = first; j <= last; ++j) {
      const BarSegment& s = config_.segments[j];
      const double r = 0.5 * s.length, m = origin_[j] + r;
      // E q′(σ) = E q′(x_j) + r ∫_{−1}^{σ} (ρα − f), q(σ) = q(x_j) + (r/E) ∫_{−1}^{σ} E q′.
      poly::Coefficients integrand = combination(-1.0, s.load, 1.0, {s.density * alpha});
      poly::Coefficients sp = poly::antiderivative(integrand);
      for (double& c : sp) c *= r;
      sp = plus_constant(sp, stress - poly::evaluate(sp, -1.0));
      poly::Coefficients q = poly::antiderivative(sp);
      for (double& c : q) c *= r / s.modulus;
      q = plus_constant(q, value - poly::evaluate(q, -1.0));
      stress = poly::evaluate(sp, 1.0);
      value = poly::evaluate(q, 1.0);
      static_stress_[j] = piece_in(origin_[j], origin_[j + 1], m, r, sp);
      static_[j] = piece_in(origin_[j], origin_[j + 1], m, r, q);
      acceleration_[j] = alpha;
    }
    if (clamped)
      for (std::size_t j = first; j <= last; ++j) static_[j] = static_[j].plus(-value);
    first = last + 1;
  }

  // 2. The data: contiguous pieces from 0 to Σℓ, each inside one segment.
  const auto& pieces = data.pieces;
  if (pieces.empty()) throw InvalidParameter("initial_data", "no pieces");
  double scale_u = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const InitialDataPiece& p = pieces[k];
    if (!(std::isfinite(p.a) && std::isfinite(p.b) && p.b > p.a))
      throw InvalidParameter("initial_data", "piece " + std::to_string(k) + ": [a, b] must be finite with b > a");
    if (p.a != (k == 0 ? 0.0 : pieces[k - 1].b))
      throw InvalidParameter("initial_data", "the pieces must be contiguous and start at x = 0");
    for (const poly::Coefficients* c : {&p.displacement, &p.velocity})
      for (double v : *c)
        if (!std::isfinite(v)) throw InvalidParameter("initial_data", "every coefficient must be finite");
    for (double s : {-1.0, 1.0}) scale_u = std::max(scale_u, std::abs(poly::evaluate(p.displacement, s)));
  }
  if (std::abs(pieces.back().b - total) > 1e-12 * total)
    throw InvalidParameter("initial_data", "the pieces must end at the chain's length " + number(total));
  const double tie_x = 1e-12 * total;
  right_.resize(n);
  left_.resize(n);
  std::size_t k = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double c = config_.segments[j].length / travel_[j];
    std::vector<PolynomialPiece> rights;
    double primitive = 0;  // V at the start of the current piece
    bool first_piece = true;
    if (k >= pieces.size() || std::abs(pieces[k].a - origin_[j]) > tie_x)
      throw InvalidParameter("initial_data", "every junction (x = " + number(origin_[j]) + ") must be a breakpoint");
    while (k < pieces.size() && pieces[k].b <= origin_[j + 1] + tie_x) {
      const InitialDataPiece& p = pieces[k++];
      const double r = 0.5 * (p.b - p.a), m = 0.5 * (p.a + p.b);
      // w⁰ = u⁰ − q in the piece's variable; V = V(a) + (r/c)(A(σ) − A(−1)).
      const poly::Coefficients q =
          composed(static_[j].value, (m - static_[j].centre) / static_[j].radius, r / static_[j].radius);
      const poly::Coefficients w = combination(1.0, p.displacement, -1.0, q);
      poly::Coefficients v = poly::antiderivative(p.velocity);
      for (double& x : v) x *= r / c;
      v = plus_constant(v, primitive - poly::evaluate(v, -1.0));
      primitive = poly::evaluate(v, 1.0);
      const double lo = (p.a - origin_[j]) / c, hi = (p.b - origin_[j]) / c;
      const double centre = (m - origin_[j]) / c, radius = r / c;
      left_[j].append(piece_in(first_piece ? 0.0 : lo, hi, centre, radius, combination(0.5, w, 0.5, v)), snap_);
      rights.push_back(
          piece_in(first_piece ? 0.0 : lo, hi, centre, radius, combination(0.5, w, -0.5, v)).mirrored(0.0));
      first_piece = false;
    }
    if (left_[j].empty() || std::abs(left_[j].end() - travel_[j]) > 1e-12 * travel_[j])
      throw InvalidParameter("initial_data",
                             "every junction (x = " + number(origin_[j + 1]) + ") must be a breakpoint");
    for (std::size_t i = rights.size(); i-- > 0;) right_[j].append(rights[i], snap_);
  }
  // Continuity of u⁰ inside each body, the clamp, and the contacts not violated at t = 0.
  const auto u_left = [&](std::size_t j) {  // w at x_{j+1} from segment j, plus q: u⁰(x_{j+1}⁻)
    return right_[j].value(right_[j].begin()) + left_[j].value(left_[j].end()) + static_[j].at(origin_[j + 1]);
  };
  const auto u_right = [&](std::size_t j) {  // u⁰(x_j⁺)
    return right_[j].value(0.0) + left_[j].value(0.0) + static_[j].at(origin_[j]);
  };
  const double tol = 1e-12 * std::max(scale_u, 1e-300);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double jump = u_right(j + 1) - u_left(j);
    if (!config_.junctions[j].contact && std::abs(jump) > tol)
      throw InvalidParameter("initial_data",
                             "u0 must be continuous at the welded junction x = " + number(origin_[j + 1]));
    if (config_.junctions[j].contact && jump + config_.junctions[j].gap < -tol)
      throw InvalidParameter("initial_data", "the contact at x = " + number(origin_[j + 1]) +
                                                 " is violated at t = 0 (u_B - u_A + gap < 0)");
  }
  if (config_.far_end == FarEnd::clamped && std::abs(u_left(n - 1)) > tol)
    throw InvalidParameter("initial_data", "u0 must be 0 at the clamped end, got " + number(u_left(n - 1)));
  if (config_.obstacle && u_right(0) + config_.obstacle_gap < -tol)
    throw InvalidParameter("initial_data", "u0(0) + gap must be >= 0 (the obstacle)");

  // 3. The contacts and the last emitted values (the waves' values where emission starts).
  last_right_.assign(n + 1, 0.0);
  last_left_.assign(n + 1, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    last_left_[j] = right_[j].value(0.0);                 // F_j(0)
    last_right_[j + 1] = left_[j].value(left_[j].end());  // G_j(τ_j)
  }
  if (config_.obstacle) contacts_.push_back({0, std::max(0.0, u_right(0) + config_.obstacle_gap), false, {}});
  for (std::size_t j = 0; j + 1 < n; ++j)
    if (config_.junctions[j].contact)
      contacts_.push_back({j + 1, std::max(0.0, u_right(j + 1) - u_left(j) + config_.junctions[j].gap), false, {}});

  // 4. The march in windows of length min τ (derivation §4).
  const double window = *std::min_element(travel_.begin(), travel_.end());
  constexpr double max_windows = 1e5;  // each window adds at least one piece per wave: bounded before any work
  if (!(horizon_ <= max_windows * window))
    throw InvalidParameter("final_time", "the horizon " + number(horizon_) + " is more than 1e5 transit times (" +
                                             number(max_windows * window) +
                                             ") of the shortest segment: too many wave fronts to solve exactly");
  for (long w = 0;; ++w) {
    const double t0 = static_cast<double>(w) * window, t1 = static_cast<double>(w + 1) * window;
    for (std::size_t node = 0; node <= n; ++node) process(node, t0, t1);
    if (piece_count() > max_pieces)
      throw InvalidParameter("final_time", "more than " + std::to_string(max_pieces) + " wave pieces before t = " +
                                               number(t1) + ": too many wave fronts over the horizon to solve exactly");
    if (t1 >= horizon_ + tie_) break;
  }
  for (ContactState& c : contacts_) {
    while (!c.windows.empty() && c.windows.back().start > horizon_) c.windows.pop_back();
    if (!c.windows.empty() && c.windows.back().end >= horizon_) {
      c.windows.back().end = horizon_;
      c.windows.back().open = true;
    }
  }
}

std::size_t ImpactSolution::piece_count() const {
  std::size_t count = 0;
  for (std::size_t j = 0; j < right_.size(); ++j) count += right_[j].pieces().size() + left_[j].pieces().size();
  return count;
}

// One junction over [t0, t1] (derivation §3).
void ImpactSolution::process(std::size_t node, double t0, double t1) {
  const std::size_t n = config_.segments.size();
  const bool has_a = node > 0, has_b = node < n;
  const std::size_t a = node - 1, b = node;  // the segments on the left and on the right (when they exist)
  const double tau_a = has_a ? travel_[a] : 0.0;
  // The stretches: [t0, t1] cut at the breakpoints of what arrives (closer than snap_ merged).
  std::vector<double> cuts{t0};
  // The breakpoints of a wave in (lo, hi), shifted: from the piece that holds lo on (not a scan of all).
  const auto breakpoints = [&](const PiecewisePolynomial& wave, double lo, double hi, double shift) {
    const auto& pieces = wave.pieces();
    for (std::size_t k = wave.locate(inside(wave, lo)); k < pieces.size() && pieces[k].a < hi; ++k)
      if (pieces[k].a > lo) cuts.push_back(pieces[k].a + shift);
  };
  if (has_a) breakpoints(right_[a], t0 - tau_a, t1 - tau_a, tau_a);
  if (has_b) breakpoints(left_[b], t0, t1, 0.0);
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> stretches{t0};
  for (double c : cuts)
    if (c - stretches.back() > snap_ && t1 - c > snap_) stretches.push_back(c);
  stretches.push_back(t1);

  const bool is_contact =
      (node == 0 && config_.obstacle) || (node > 0 && node < n && config_.junctions[node - 1].contact);
  ContactState* contact = nullptr;
  if (is_contact)
    for (ContactState& c : contacts_)
      if (c.node == node) contact = &c;
  // ℓ(t) = ℓ₀ + ℓ₂ t² for a contact (derivation §1).
  double l0 = 0, l2 = 0;
  if (contact) {
    const double gap = node == 0 ? config_.obstacle_gap : config_.junctions[node - 1].gap;
    const double qa = has_a ? static_[a].at(origin_[node]) : 0.0, aa = has_a ? acceleration_[a] : 0.0;
    l0 = -gap - (static_[b].at(origin_[node]) - qa);
    l2 = -0.5 * (acceleration_[b] - aa);
  }
  const double za = has_a ? impedance_[a] : 0.0, zb = has_b ? impedance_[b] : 0.0;

  for (std::size_t i = 0; i + 1 < stretches.size(); ++i) {
    const double lo = stretches[i], hi = stretches[i + 1], m = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
    poly::Coefficients P, Q;
    if (has_a) {
      const PolynomialPiece& p = right_[a].pieces()[right_[a].locate(inside(right_[a], m - tau_a))];
      P = in_variable(p.translated(tau_a), m, r);
    }
    if (has_b) Q = in_variable(left_[b].pieces()[left_[b].locate(inside(left_[b], m))], m, r);
    // Emits r (into G_a, delayed by τ_a) and s (into F_b) on [from, to], continuous with the last values.
    const auto emit = [&](double from, double to, const poly::Coefficients* rc, const poly::Coefficients* sc,
                          bool fix_r, bool fix_s) {
      if (!(to > from)) return;
      const double sf = (from - m) / r, st = (to - m) / r;
      if (rc && has_a) {
        poly::Coefficients c = *rc;
        if (fix_r) c = plus_constant(c, last_right_[node] - poly::evaluate(c, sf));
        left_[a].append(piece_in(from + tau_a, to + tau_a, m + tau_a, r, c), snap_);
        last_right_[node] = poly::evaluate(c, st);
      }
      if (sc && has_b) {
        poly::Coefficients c = *sc;
        if (fix_s) c = plus_constant(c, last_left_[node] - poly::evaluate(c, sf));
        right_[b].append(piece_in(from, to, m, r, c), snap_);
        last_left_[node] = poly::evaluate(c, st);
      }
    };
    if (!contact) {
      if (has_a && has_b) {  // welded
        const double s = za + zb;
        const poly::Coefficients rc = combination((za - zb) / s, P, 2 * zb / s, Q),
                                 sc = combination(2 * za / s, P, (zb - za) / s, Q);
        emit(lo, hi, &rc, &sc, true, true);
      } else if (has_a) {  // the right end
        const poly::Coefficients rc = combination(config_.far_end == FarEnd::clamped ? -1.0 : 1.0, P, 0.0, {});
        emit(lo, hi, &rc, nullptr, config_.far_end == FarEnd::free, false);
      } else {  // a free left end
        emit(lo, hi, nullptr, &Q, false, true);
      }
      continue;
    }
    // The contact: the Skorokhod reflection of y = z(lo) + ∫β on this stretch (derivation §3).
    const poly::Coefficients L = {l0 + l2 * m * m, 2 * l2 * m * r, l2 * r * r};
    poly::Coefficients y = combination(2.0, Q, -2.0, P);
    y = combination(1.0, y, -1.0, L);
    y = plus_constant(y, contact->gap - poly::evaluate(y, -1.0));
    const poly::Coefficients slope = poly::derivative(y);
    double noise = 0;
    for (double c : slope) noise += std::abs(c);
    noise *= 64 * epsilon;
    std::vector<double> knots{-1.0};
    for (double s : poly::sign_changes(slope, -1.0, 1.0)) knots.push_back(s);
    knots.push_back(1.0);
    double start = lo, level = 0;
    const auto time_of = [&](double s) {
      const double t = m + r * s;
      if (t - start <= snap_) return start;
      if (hi - t <= snap_) return hi;
      return t;
    };
    const auto close = [&](double end) {
      if (!(end > start)) return;
      if (contact->held) {
        if (has_a) {
          // r = R_A p + T_B q − Z_B/(Z_A + Z_B) ℓ + constant (continuous), s = p + r + ℓ − q (so that z = 0).
          const double s = za + zb, sf = (start - m) / r;
          poly::Coefficients rc = combination(1.0, combination((za - zb) / s, P, 2 * zb / s, Q), -zb / s, L);
          rc = plus_constant(rc, last_right_[node] - poly::evaluate(rc, sf));
          const poly::Coefficients sc =
              combination(1.0, combination(1.0, P, 1.0, rc), 1.0, combination(1.0, L, -1.0, Q));
          emit(start, end, &rc, &sc, false, false);
        } else {
          const poly::Coefficients sc = combination(1.0, L, -1.0, Q);
          emit(start, end, nullptr, &sc, false, false);
        }
      } else {
        emit(start, end, &P, &Q, true, true);
      }
      start = end;
    };
    for (std::size_t j = 0; j + 1 < knots.size(); ++j) {
      const double s0 = knots[j], s1 = knots[j + 1];
      const bool decreasing = poly::evaluate(slope, 0.5 * (s0 + s1)) <= noise;
      if (!decreasing) {
        if (contact->held) {  // release: β turns positive
          close(j == 0 ? lo : time_of(s0));
          contact->held = false;
          contact->windows.back().end = start;
          contact->windows.back().open = false;
        }
        continue;
      }
      if (!contact->held) {
        const auto yv = [&](double s) { return poly::evaluate(y, s); };
        if (yv(s1) > level) continue;
        const double root = yv(s0) <= level ? s0 : [&] {
          double u = s0, v = s1;
          for (;;) {
            const double mid = 0.5 * (u + v);
            if (!(mid > u && mid < v)) return v;
            (yv(mid) - level > 0 ? u : v) = mid;
          }
        }();
        close(root == s0 && j == 0 ? lo : time_of(root));
        contact->held = true;
        if (!contact->windows.empty() && start - contact->windows.back().end <= snap_ && !contact->windows.back().open)
          contact->windows.back().open = true;
        else
          contact->windows.push_back({start, start, true});
      }
      level = poly::evaluate(y, s1);
    }
    close(hi);
    contact->gap = contact->held ? 0.0 : std::max(0.0, poly::evaluate(y, 1.0) - level);
    if (contact->held) contact->windows.back().end = hi;
  }
}

std::size_t ImpactSolution::segment_of(double x) const {
  if (!(x >= 0.0 && x <= origin_.back()))
    throw std::out_of_range("impact solution: x = " + number(x) + " outside [0, " + number(origin_.back()) + "]");
  const auto it = std::upper_bound(origin_.begin() + 1, origin_.end() - 1, x);
  std::size_t j = static_cast<std::size_t>(it - origin_.begin()) - 1;
  if (j > 0 && x == origin_[j]) --j;  // a junction belongs to the segment on its left
  return j;
}

namespace {
void check_time(double t, double horizon) {
  if (!(t >= 0.0 && t <= horizon))
    throw std::out_of_range("impact solution: t = " + number(t) + " outside [0, " + number(horizon) + "]");
}
}  // namespace

double ImpactSolution::displacement(double x, double t) const {
  check_time(t, horizon_);
  const std::size_t j = segment_of(x);
  const double theta = std::min(travel_[j], (x - origin_[j]) / (config_.segments[j].length / travel_[j]));
  return right_[j].value(inside(right_[j], t - theta)) + left_[j].value(inside(left_[j], t + theta)) +
         0.5 * acceleration_[j] * t * t + static_[j].at(x);
}

double ImpactSolution::velocity(double x, double t) const {
  check_time(t, horizon_);
  const std::size_t j = segment_of(x);
  const double theta = std::min(travel_[j], (x - origin_[j]) / (config_.segments[j].length / travel_[j]));
  return right_[j].derivative(inside(right_[j], t - theta), tie_) +
         left_[j].derivative(inside(left_[j], t + theta), tie_) + acceleration_[j] * t;
}

// The same operations as displacement and velocity above, point by point; only the search of the pieces
// starts from the previous point's (PiecewisePolynomial::locate finds the same piece from any start: the
// pieces are contiguous), and a segment's hints start afresh when the points enter it.
void ImpactSolution::at_points(double t, const double* x, long count, double* u, double* v) const {
  check_time(t, horizon_);
  std::size_t segment = origin_.size(), right_hint = 0, left_hint = 0;
  for (long k = 0; k < count; ++k) {
    const std::size_t j = segment_of(x[k]);
    if (j != segment) segment = j, right_hint = 0, left_hint = 0;
    const double theta = std::min(travel_[j], (x[k] - origin_[j]) / (config_.segments[j].length / travel_[j]));
    const double s_right = inside(right_[j], t - theta), s_left = inside(left_[j], t + theta);
    if (u) {
      std::size_t r = right_hint, l = left_hint;
      u[k] = right_[j].value(s_right, &r) + left_[j].value(s_left, &l) + 0.5 * acceleration_[j] * t * t +
             static_[j].at(x[k]);
      if (!v) right_hint = r, left_hint = l;
    }
    if (v)
      v[k] = right_[j].derivative(s_right, tie_, &right_hint) + left_[j].derivative(s_left, tie_, &left_hint) +
             acceleration_[j] * t;
  }
}

double ImpactSolution::stress(double x, double t) const {
  check_time(t, horizon_);
  const std::size_t j = segment_of(x);
  const double theta = std::min(travel_[j], (x - origin_[j]) / (config_.segments[j].length / travel_[j]));
  return impedance_[j] * (left_[j].derivative(inside(left_[j], t + theta), tie_) -
                          right_[j].derivative(inside(right_[j], t - theta), tie_)) +
         static_stress_[j].at(x);
}

double ImpactSolution::gap(std::size_t k, double t) const {
  check_time(t, horizon_);
  const ContactState& c = contacts_.at(k);
  const std::size_t b = c.node;
  const double ub = right_[b].value(t) + left_[b].value(t) + 0.5 * acceleration_[b] * t * t + static_[b].at(origin_[b]);
  if (b == 0) return ub + config_.obstacle_gap;
  const std::size_t a = b - 1;
  const double ua = right_[a].value(inside(right_[a], t - travel_[a])) +
                    left_[a].value(inside(left_[a], t + travel_[a])) + 0.5 * acceleration_[a] * t * t +
                    static_[a].at(origin_[b]);
  return ub - ua + config_.junctions[a].gap;
}

// λ(t) = Z_B (G_B′ − F_B′)(t) on the right side of the contact point. At t = 0 the data need not satisfy
// the contact law (the paper's u⁰′(0) ≠ 0 at a free end): λ(0) is the limit from t > 0, with F_B′ taken
// on the emitted side of 0 (as characteristics.cpp does).
double ImpactSolution::contact_stress(std::size_t k, double t) const {
  check_time(t, horizon_);
  const std::size_t b = contacts_.at(k).node;
  const double emitted =
      t <= tie_ ? right_[b].pieces()[right_[b].locate(0.0)].derivative_at(t) : right_[b].derivative(t, tie_);
  return impedance_[b] * (left_[b].derivative(t, tie_) - emitted) + static_stress_[b].at(origin_[b]);
}

const std::vector<ContactInterval>& ImpactSolution::contact_windows(std::size_t k) const {
  return contacts_.at(k).windows;
}

std::vector<ContactInterval> exact_contact_windows(const ImpactConfiguration& configuration, const InitialData& data,
                                                   double final_time, std::size_t contact) {
  const ImpactSolution solution(configuration, data, final_time);
  if (contact >= solution.contact_count())
    throw InvalidParameter("contact", "there are only " + std::to_string(solution.contact_count()) + " contacts");
  return solution.contact_windows(contact);
}

// The reference of the error measures. The energy ½∫(ρu_t² + E u_x²) − ∫ f u at t = 0 by the 5-point
// Gauss rule on 64 subintervals of each segment: exact for data and loads of degree ≤ 4 on each
// subinterval (the benchmarks' are constant or affine), a quadrature otherwise.
ImpactReference::ImpactReference(const ImpactConfiguration& configuration, const InitialData& data, double final_time)
    : solution_(configuration, data, final_time) {
  if (!configuration.obstacle)
    throw InvalidParameter("configuration",
                           "the reference of the error measures needs a rigid obstacle at x = 0 (allowed: a chain "
                           "with an obstacle; two bars in contact have none)");
  static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                   0.2369268850561891};
  double x0 = 0;
  for (const BarSegment& segment : configuration.segments) {
    const int parts = 64;
    const double width = segment.length / parts;
    for (int k = 0; k < parts; ++k)
      for (int q = 0; q < 5; ++q) {
        const double x = x0 + width * (k + 0.5 * (1 + node[q]));
        const double v = solution_.velocity(x, 0.0), sigma = solution_.stress(x, 0.0);
        const double f =
            segment.load.empty() ? 0.0 : poly::evaluate(segment.load, (x - x0) / (0.5 * segment.length) - 1);
        energy_ +=
            0.5 * width * weight[q] *
            (0.5 * (segment.density * v * v + sigma * sigma / segment.modulus) - f * solution_.displacement(x, 0.0));
      }
    x0 += segment.length;
  }
}

double ImpactReference::contact_displacement(double t) const {
  const std::vector<ContactInterval>& windows = contact_windows();
  const auto after = std::upper_bound(windows.begin(), windows.end(), t,
                                      [](double s, const ContactInterval& w) { return s < w.start; });
  if (after != windows.begin() && t <= std::prev(after)->end) return -solution_.configuration().obstacle_gap;
  return solution_.displacement(0.0, t);
}

double ImpactReference::strain(double x, double t) const {
  const std::vector<BarSegment>& segments = solution_.configuration().segments;
  double x0 = 0;
  std::size_t j = 0;
  while (j + 1 < segments.size() && x > x0 + segments[j].length) x0 += segments[j++].length;
  return solution_.stress(x, t) / segments[j].modulus;
}

void ImpactReference::displacement_at_points(double t, const double* x, long count, double* u) const {
  solution_.at_points(t, x, count, u, nullptr);
}

void ImpactReference::velocity_at_points(double t, const double* x, long count, double* v) const {
  solution_.at_points(t, x, count, nullptr, v);
}

}  // namespace mrm

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// The named benchmarks (doc/benchmarks.md). Each is a chain as above; the closed forms they are checked
// against are derived in the doctests below.

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

BarSegment bar(double length, double modulus, double density, double load = 0.0) {
  BarSegment s;
  s.length = length;
  s.modulus = modulus;
  s.density = density;
  if (load != 0.0) s.load = {load};
  return s;
}

std::vector<ImpactBenchmark> make_benchmarks() {
  std::vector<ImpactBenchmark> list;
  {
    // Doyen–Ern–Piperno's bouncing bar: L = 10, E = 900, ρ = 1 (c = 30), g = 10 (f = −ρg), at rest,
    // undeformed, lower end h₀ = 5 above the floor (free fall √(2h₀/g) = 1 = three transits), free at
    // both ends. Three contacts: [1, 5/3], [11/3, 13/3], [19/3, 7] (the doctest below derives them).
    ImpactBenchmark b{"bouncing",
                      "Doyen-Ern-Piperno's bouncing bar (free bar falling under gravity onto a floor)",
                      "Doyen, Ern, Piperno, SIAM J. Sci. Comput. 33 (2011); NLstep EXAMPLES/01_bouncingBar",
                      "",
                      {},
                      {},
                      8.0};
    b.configuration.segments = {bar(10.0, 900.0, 1.0, -10.0)};
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
    b.configuration.segments = {bar(0.2, modulus, 8000.0)};
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
    b.configuration.segments = {bar(1.0, 1.0, 1.0, -1.0)};
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
    b.configuration.segments = {bar(10.0, 1.0, 1.0), bar(10.0, 1.0, 1.0)};
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
    b.configuration.segments = {bar(1.0, 4.0, 1.0), bar(1.5, 1.0, 1.0)};
    b.configuration.far_end = FarEnd::free;
    b.configuration.obstacle_gap = 0.1;
    b.data.pieces = {{0.0, 1.0, {0.0}, {-1.0}}, {1.0, 2.5, {0.0}, {-1.0}}};
    list.push_back(b);
  }
  return list;
}

}  // namespace

const std::vector<ImpactBenchmark>& impact_benchmarks() {
  static const std::vector<ImpactBenchmark> list = make_benchmarks();
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

}  // namespace mrm

// ---------------------------------------------------------------------------------------------------
// Checks against closed forms.

namespace mrm {

namespace {

// Data u⁰ = u0 + u1 (x − a)/(b − a)·2 − …: one piece per segment with u⁰ affine and v⁰ constant on it.
InitialDataPiece affine_piece(double a, double b, double ua, double ub, double v) {
  return {a, b, {0.5 * (ua + ub), 0.5 * (ub - ua)}, {v}};
}

BarSegment segment(double length, double modulus, double density, double load = 0.0) {
  BarSegment s;
  s.length = length;
  s.modulus = modulus;
  s.density = density;
  if (load != 0.0) s.load = {load};
  return s;
}

}  // namespace

TEST_CASE("the chain solver reproduces the paper's closed form, also cut into welded pieces") {
  // L = 1, c = 1, u⁰ = (1 − x)/2, v⁰ = 0, clamped, obstacle at 0: mathematics.md §2, over 10 periods.
  const ExactSolution exact(1.0, 0.5);
  for (int cuts : {1, 3}) {
    ImpactConfiguration config;
    InitialData data;
    for (int j = 0; j < cuts; ++j) {
      config.segments.push_back(segment(1.0 / cuts, 1.0, 1.0));
      const double a = static_cast<double>(j) / cuts, b = static_cast<double>(j + 1) / cuts;
      data.pieces.push_back(
          affine_piece(a, j + 1 == cuts ? 1.0 : b, 0.5 * (1 - a), j + 1 == cuts ? 0.0 : 0.5 * (1 - b), 0.0));
    }
    const ImpactSolution solution(config, data, 30.0);
    CAPTURE(cuts);
    double du = 0, dv = 0, ds = 0, dg = 0, dl = 0;
    for (int n = 0; n <= 3000; ++n) {
      const double t = 30.0 * (n + 0.37) / 3001.0;
      for (int i = 0; i <= 40; ++i) {
        const double x = (i + 0.21) / 41.0;
        du = std::max(du, std::abs(solution.displacement(x, t) - exact.displacement(x, t)));
        dv = std::max(dv, std::abs(solution.velocity(x, t) - exact.velocity(x, t)));
        ds = std::max(ds, std::abs(solution.stress(x, t) - exact.strain(x, t)));
      }
      dg = std::max(dg, std::abs(solution.gap(0, t) - exact.contact_displacement(t)));
      dl = std::max(dl, std::abs(solution.contact_stress(0, t) - exact.contact_multiplier(t)));
    }
    CAPTURE(du);
    CAPTURE(dv);
    CAPTURE(ds);
    CAPTURE(dg);
    CAPTURE(dl);
    CHECK(std::max({du, dv, ds, dg, dl}) <= 1e-12);
    const auto& windows = solution.contact_windows(0);
    REQUIRE(windows.size() == 10);
    for (std::size_t k = 0; k < 10; ++k) {
      CHECK(std::abs(windows[k].start - (3.0 * k + 1)) <= 1e-12);
      CHECK(std::abs(windows[k].end - (3.0 * k + 2)) <= 1e-12);
    }
  }
}

TEST_CASE("the chain solver agrees with the clamped solver (characteristics.cpp) on general data") {
  // Two derivations of the same solution (windows in space there, junction signals in time here).
  std::vector<double> x, u, v;
  for (int k = 0; k <= 40; ++k) {
    const double s = k / 40.0;
    x.push_back(1.3 * s);
    u.push_back(k == 40 ? 0.0 : 0.2 * (1 - s) * (1 + 0.5 * std::sin(7 * s)));
    v.push_back(0.3 * std::cos(5 * s) - 0.1);
  }
  const InitialData data = initial_data_from_samples(x, u, v);
  const CharacteristicSolution reference(data, 12.0);
  ImpactConfiguration config;
  config.segments = {segment(1.3, 1.0, 1.0)};
  const ImpactSolution solution(config, data, 12.0);
  double du = 0, dl = 0;
  for (int n = 0; n <= 2400; ++n) {
    const double t = 12.0 * (n + 0.31) / 2401.0;
    for (int i = 0; i <= 20; ++i)
      du = std::max(du, std::abs(solution.displacement(1.3 * (i + 0.4) / 21.0, t) -
                                 reference.displacement(1.3 * (i + 0.4) / 21.0, t)));
    dl = std::max(dl, std::abs(solution.contact_stress(0, t) - reference.contact_multiplier(t)));
    du = std::max(du, std::abs(solution.gap(0, t) - reference.contact_displacement(t)));
  }
  CAPTURE(du);
  CAPTURE(dl);
  CHECK(du <= 1e-13);
  CHECK(dl <= 1e-12);
  const auto& a = solution.contact_windows(0);
  const auto& b = reference.contact_intervals();
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() >= 3);
  for (std::size_t k = 0; k < a.size(); ++k) {
    CHECK(std::abs(a[k].start - b[k].start) <= 1e-12);
    CHECK(std::abs(a[k].end - b[k].end) <= 1e-12);
  }
}

TEST_CASE("the impacting bar (SDNV100): contact from gap/v for 2L/c at stress -rho c v, then rigid rebound") {
  // A free bar with uniform velocity −v toward the wall across a gap g₀: free flight z = g₀ − v t until
  // t₁ = g₀/v; the impact sends a compression wave σ = −Z v up the bar (u_t = 0 behind it); it reflects
  // at the free end as a release wave and brings σ = 0, u_t = +v back to the wall at t₁ + 2L/c, where
  // β = 2v > 0: the bar leaves rigidly with +v, z = v (t − t₁ − 2L/c).
  const double nu = 0.3, modulus = 2e11 * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), rho = 8000, length = 0.2, speed = 100,
               gap = 2e-3;
  ImpactConfiguration config;
  config.segments = {segment(length, modulus, rho)};
  config.far_end = FarEnd::free;
  config.obstacle_gap = gap;
  InitialData data;
  data.pieces = {{0.0, length, {0.0}, {-speed}}};
  const double c = std::sqrt(modulus / rho), t1 = gap / speed, t2 = t1 + 2 * length / c;
  const ImpactSolution solution(config, data, 3 * t2);
  const auto& w = solution.contact_windows(0);
  REQUIRE(w.size() == 1);
  CHECK(std::abs(w[0].start - t1) <= 1e-12 * t2);
  CHECK(std::abs(w[0].end - t2) <= 1e-12 * t2);
  for (int n = 0; n <= 300; ++n) {
    const double t = 3 * t2 * (n + 0.5) / 301.0;
    CAPTURE(t);
    const double z = t < t1 ? gap - speed * t : t < t2 ? 0.0 : speed * (t - t2);
    const double lambda = t > t1 && t < t2 ? -rho * c * speed : 0.0;
    CHECK(std::abs(solution.gap(0, t) - z) <= 1e-12 * gap);
    CHECK(std::abs(solution.contact_stress(0, t) - lambda) <= 1e-12 * rho * c * speed);
    if (t > t2)
      for (int i = 0; i <= 10; ++i)
        CHECK(std::abs(solution.velocity(length * (i + 0.5) / 11, t) - speed) <= 1e-12 * speed);
  }
}

TEST_CASE("the bouncing bar (Doyen-Ern-Piperno): free-fall parabola, contacts of 2L/c every 8L/(3c)") {
  // L = 10, E = 900, ρ = 1 (c = 30, τ = L/c = 1/3), g = 10, h₀ = 5: the bar falls rigidly,
  // z = h₀ − g t²/2, hits at t₁ = √(2h₀/g) = 1 = 3τ with speed g t₁. In the falling frame (α = −g, q = 0)
  // the floor rises as ℓ = −h₀ + g t²/2; held, the end emits s = ℓ, which comes back from the free top
  // after 2τ: β(t) = 2ℓ′(t − 2τ) − ℓ′(t) = g (t − 4τ) for t ≥ t₁ + 2τ, and −ℓ′ = −g t < 0 before. So the
  // contact lasts exactly 2τ = 2/3 (β = g τ > 0 at t₁ + 2τ because t₁ = 3τ) with λ = Z β = −Z g t, Z = 30.
  // After it the motion repeats: contacts every 8τ = 8/3, the state periodic with period 16τ = 16/3
  // (DEP: the motion is periodic; here the period of the state is two contact cycles, measured).
  ImpactConfiguration config;
  config.segments = {segment(10.0, 900.0, 1.0, -10.0)};
  config.far_end = FarEnd::free;
  config.obstacle_gap = 5.0;
  InitialData data;
  data.pieces = {{0.0, 10.0, {0.0}, {0.0}}};
  const double tau = 1.0 / 3.0;
  const ImpactSolution solution(config, data, 24.0);
  for (int n = 0; n <= 100; ++n) {
    const double t = n / 100.0;
    CHECK(std::abs(solution.gap(0, t) - (5.0 - 5.0 * t * t)) <= 1e-12 * 5.0);
  }
  const auto& w = solution.contact_windows(0);
  REQUIRE(w.size() == 9);
  for (std::size_t k = 0; k < w.size(); ++k) {
    CAPTURE(k);
    const double start = 3 * tau + 8 * tau * static_cast<double>(k), end = std::min(24.0, start + 2 * tau);
    CHECK(std::abs(w[k].start - start) <= 1e-12 * 24.0);
    CHECK(std::abs(w[k].end - end) <= 1e-12 * 24.0);
    for (int n = 1; n < 10 && k == 0; ++n) {
      const double t = start + (end - start) * n / 10.0;
      CHECK(std::abs(solution.contact_stress(0, t) + 30.0 * 10.0 * t) <= 1e-12 * 300.0);
    }
  }
  double du = 0, dv = 0;
  for (int n = 0; n <= 100; ++n)
    for (int i = 0; i <= 20; ++i) {
      const double t = 8.0 * n / 100.0, x = 10.0 * i / 20.0;
      du = std::max(du, std::abs(solution.displacement(x, t + 16 * tau) - solution.displacement(x, t)));
      dv = std::max(dv, std::abs(solution.velocity(x, t + 16 * tau) - solution.velocity(x, t)));
    }
  CAPTURE(du);
  CAPTURE(dv);
  CHECK(du <= 1e-12 * 5.0);
  CHECK(dv <= 1e-12 * 300.0);
}

TEST_CASE("gravity on the paper's bar: a sudden load gives a persistent contact around the static state") {
  // The paper's bar (clamped at L, obstacle at 0) at rest, undeformed and touching, loaded at t = 0 by
  // f = −b toward the obstacle. The static state −E u_s″ = f, u_s(0) = u_s(L) = 0 is
  // u_s = (b/2E)(x² − Lx), with λ_s = E u_s′(0) = −bL/2. If the end stays held, u − u_s is the free
  // vibration of the clamped–clamped bar from −u_s at rest: u = u_s − ½(ũ(x − ct) + ũ(x + ct)), ũ the odd
  // 2L-periodic extension of u_s, and λ(t) = λ_s − E ũ′(ct) = −b · dist(ct, 2LZ) ≤ 0 (ũ′ is even): held
  // throughout, grazing (λ = 0) at ct ∈ 2LZ; the time mean of λ over a period 2L/c is the static λ_s.
  // And the paper's data u⁰ = (1 − x)/2 under the same load: the end moves as u(0, t) = (1 − t)/2 − b t²/2
  // until the first reflection (t < L), so the first impact is at t* = (√(1 + 4b) − 1)/(2b).
  for (const auto& [length, modulus, b] : {std::tuple<double, double, double>{1.0, 1.0, 1.0}, {2.0, 4.0, 0.3}}) {
    CAPTURE(length);
    ImpactConfiguration config;
    config.segments = {segment(length, modulus, 1.0, -b)};
    InitialData data;
    data.pieces = {{0.0, length, {0.0}, {0.0}}};
    const double c = std::sqrt(modulus), period = 2 * length / c, horizon = 5 * period;
    const ImpactSolution solution(config, data, horizon);
    const auto static_u = [&](double x) { return b / (2 * modulus) * (x * x - length * x); };
    const auto extended = [&](double xi) {
      xi = std::fmod(xi, 2 * length);
      if (xi < 0) xi += 2 * length;
      return xi <= length ? static_u(xi) : -static_u(2 * length - xi);
    };
    REQUIRE(solution.contact_windows(0).size() == 1);
    CHECK(solution.contact_windows(0)[0].start == 0.0);
    CHECK(solution.contact_windows(0)[0].open);
    double du = 0, dl = 0, mean = 0;
    const int samples = 4000;
    for (int n = 0; n < samples; ++n) {
      const double t = horizon * (n + 0.5) / samples;
      for (int i = 0; i <= 20; ++i) {
        const double x = length * i / 20.0;
        du = std::max(du, std::abs(solution.displacement(x, t) -
                                   (static_u(x) - 0.5 * (extended(x - c * t) + extended(x + c * t)))));
      }
      const double ct = std::fmod(c * t, 2 * length);
      dl = std::max(dl, std::abs(solution.contact_stress(0, t) + b * std::min(ct, 2 * length - ct)));
      mean += solution.contact_stress(0, t) / samples;  // the midpoint rule is exact for the piecewise-linear λ
      CHECK(std::abs(solution.gap(0, t)) <= 1e-14 * b * length * length);
    }
    CAPTURE(du);
    CAPTURE(dl);
    CHECK(du <= 1e-12 * b * length * length / modulus);
    CHECK(dl <= 1e-12 * b * length);
    CHECK(std::abs(mean + b * length / 2) <= 1e-12 * b * length);
  }
  for (const double b : {0.25, 1.0, 4.0}) {
    ImpactConfiguration config;
    config.segments = {segment(1.0, 1.0, 1.0, -b)};
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.25, -0.25}, {0.0}}};
    const ImpactSolution solution(config, data, 3.0);
    CAPTURE(b);
    CHECK(std::abs(solution.contact_windows(0).at(0).start - (std::sqrt(1 + 4 * b) - 1) / (2 * b)) <= 1e-12);
  }
}

TEST_CASE("a static load: a piecewise-polynomial f(x) on a layered bar in static equilibrium stays put") {
  // Two welded segments (E = 2 on [0, 1], E = 5 on [1, 1.5]), f(x) = −(1 + x) on the first and −3x² on
  // the second, clamped at 1.5, held at 0: the static state −(E u′)′ = f with u(0) = u(1.5) = 0 and
  // E u′ continuous at x = 1; started from it at rest, the solution is u(x, t) = u_s(x), λ = E u_s′(0) < 0.
  // u_s: E u′ = λ_s + ∫₀ˣ(1 + s) ds on [0, 1] = λ_s + x + x²/2, then λ_s + 3/2 + (x³ − 1) on [1, 1.5].
  const auto stress = [](double x, double ls) { return x <= 1 ? ls + x + x * x / 2 : ls + 1.5 + (x * x * x - 1); };
  const auto integral = [&](double x, double ls) {  // u_s(x) = ∫₀ˣ (E u′)/E
    if (x <= 1) return (ls * x + x * x / 2 + x * x * x / 6) / 2;
    const double first = (ls + 0.5 + 1.0 / 6) / 2, d = x - 1;
    return first + ((ls + 0.5) * d + (std::pow(x, 4) - 1) / 4) / 5;
  };
  const double ls = -(integral(1.5, 0.0)) / ((1.0 / 2) + (0.5 / 5));  // u_s(1.5) = 0 fixes λ_s (linear in it)
  REQUIRE(ls < 0);
  ImpactConfiguration config;
  config.segments = {segment(1.0, 2.0, 1.0), segment(0.5, 5.0, 3.0)};
  // f in σ: on [0, 1] x = (1 + σ)/2, on [1, 1.5] x = 1.25 + σ/4.
  config.segments[0].load = {-1.5, -0.5};
  config.segments[1].load = composed({0.0, 0.0, -3.0}, 1.25, 0.25);
  // u_s on each segment as a polynomial in σ: interpolate at enough points (degree ≤ 3 and 5).
  InitialData data;
  for (const auto& [a, b, degree] : {std::tuple<double, double, int>{0.0, 1.0, 3}, {1.0, 1.5, 5}}) {
    // The monomial coefficients in σ from values at Chebyshev-like points, by solving a small system.
    const int n = degree + 1;
    std::vector<double> matrix(static_cast<std::size_t>(n * n)), rhs(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double s = std::cos(M_PI * (i + 0.5) / n), x = 0.5 * (a + b) + 0.5 * (b - a) * s;
      for (int k = 0; k < n; ++k) matrix[static_cast<std::size_t>(i * n + k)] = std::pow(s, k);
      rhs[static_cast<std::size_t>(i)] = integral(x, ls);
    }
    for (int col = 0; col < n; ++col)  // Gauss elimination with partial pivoting
      for (int row = col + 1; row < n; ++row) {
        int pivot = col;
        for (int r = col + 1; r < n; ++r)
          if (std::abs(matrix[static_cast<std::size_t>(r * n + col)]) >
              std::abs(matrix[static_cast<std::size_t>(pivot * n + col)]))
            pivot = r;
        if (pivot != col) {
          for (int k = 0; k < n; ++k)
            std::swap(matrix[static_cast<std::size_t>(col * n + k)], matrix[static_cast<std::size_t>(pivot * n + k)]);
          std::swap(rhs[static_cast<std::size_t>(col)], rhs[static_cast<std::size_t>(pivot)]);
        }
        const double factor =
            matrix[static_cast<std::size_t>(row * n + col)] / matrix[static_cast<std::size_t>(col * n + col)];
        for (int k = col; k < n; ++k)
          matrix[static_cast<std::size_t>(row * n + k)] -= factor * matrix[static_cast<std::size_t>(col * n + k)];
        rhs[static_cast<std::size_t>(row)] -= factor * rhs[static_cast<std::size_t>(col)];
      }
    poly::Coefficients coefficients(static_cast<std::size_t>(n));
    for (int row = n; row-- > 0;) {
      double sum = rhs[static_cast<std::size_t>(row)];
      for (int k = row + 1; k < n; ++k)
        sum -= matrix[static_cast<std::size_t>(row * n + k)] * coefficients[static_cast<std::size_t>(k)];
      coefficients[static_cast<std::size_t>(row)] = sum / matrix[static_cast<std::size_t>(row * n + row)];
    }
    data.pieces.push_back({a, b, coefficients, {0.0}});
  }
  data.pieces[0].displacement[0] -= poly::evaluate(data.pieces[0].displacement, -1.0);  // u_s(0) = 0 exactly
  data.pieces[1].displacement[0] -= poly::evaluate(data.pieces[1].displacement, 1.0);   // u_s(1.5) = 0 exactly
  data.pieces[1].displacement[0] += poly::evaluate(data.pieces[0].displacement, 1.0) -
                                    poly::evaluate(data.pieces[1].displacement, -1.0);  // continuity (to round-off)
  const ImpactSolution solution(config, data, 6.0);
  REQUIRE(solution.contact_windows(0).size() == 1);
  CHECK(solution.contact_windows(0)[0].start == 0.0);
  CHECK(solution.contact_windows(0)[0].open);
  double du = 0, ds = 0;
  for (int n = 0; n <= 300; ++n)
    for (int i = 0; i <= 30; ++i) {
      const double t = 6.0 * n / 300.0, x = 1.5 * (i + 0.5) / 31.0;
      du = std::max(du, std::abs(solution.displacement(x, t) - integral(x, ls)));
      ds = std::max(ds, std::abs(solution.stress(x, t) - stress(x, ls)));
    }
  CAPTURE(du);
  CAPTURE(ds);
  CHECK(du <= 1e-12);
  CHECK(ds <= 1e-12);
  CHECK(std::abs(solution.contact_stress(0, 3.0) - ls) <= 1e-12);
}

TEST_CASE("two bars: equal bars meet as one bar on a wall; unequal impedances separate after 2 transits") {
  // Two free bars touching at t = 0 with velocities v_A > v_B. Free flight would close the gap at
  // β = v_B − v_A < 0, so they stay in contact with σ = μ β, μ = Z_A Z_B/(Z_A + Z_B) (derivation §3).
  // With equal transit times τ the free ends send back p′ = r′, q′ = s′ at t = 2τ, so that
  // β = 2(s′ − r′) = 2(p′ − q′)_{before} = −β_before > 0: release at 2τ for any impedances.
  // Equal bars (Z_A = Z_B) are symmetric about the contact plane: bar B is one bar on a rigid wall.
  {
    ImpactConfiguration config;
    config.segments = {segment(10.0, 1.0, 1.0), segment(10.0, 1.0, 1.0)};
    config.junctions = {{true, 0.0}};
    config.obstacle = false;
    config.far_end = FarEnd::free;
    InitialData data;
    data.pieces = {{0.0, 10.0, {0.0}, {0.1}}, {10.0, 20.0, {0.0}, {-0.1}}};
    const ImpactSolution solution(config, data, 60.0);
    ImpactConfiguration wall;
    wall.segments = {segment(10.0, 1.0, 1.0)};
    wall.far_end = FarEnd::free;
    InitialData one;
    one.pieces = {{0.0, 10.0, {0.0}, {-0.1}}};
    const ImpactSolution single(wall, one, 60.0);
    REQUIRE(solution.contact_windows(0).size() == 1);
    CHECK(solution.contact_windows(0)[0].start == 0.0);
    CHECK(std::abs(solution.contact_windows(0)[0].end - 20.0) <= 1e-12 * 20);
    double du = 0;
    for (int n = 0; n <= 600; ++n) {
      const double t = 60.0 * (n + 0.5) / 601.0;
      CHECK(std::abs(solution.contact_stress(0, t) - (t < 20 ? -0.1 : 0.0)) <= 1e-12 * 0.1);
      CHECK(std::abs(solution.contact_stress(0, t) - single.contact_stress(0, t)) <= 1e-12 * 0.1);
      for (int i = 1; i <= 10; ++i)
        du = std::max(du, std::abs(solution.displacement(10.0 + i, t) - single.displacement(i, t)));
      du = std::max(du, std::abs(solution.gap(0, t) - 2 * single.gap(0, t)));
      if (t > 20) {
        CHECK(std::abs(solution.velocity(5.0, t) + 0.1) <= 1e-12 * 0.1);
        CHECK(std::abs(solution.velocity(15.0, t) - 0.1) <= 1e-12 * 0.1);
        CHECK(std::abs(solution.gap(0, t) - 0.2 * (t - 20)) <= 1e-12 * 6);
      }
    }
    CHECK(du <= 1e-12 * 6);
  }
  {
    // Z_A = 1 (E = ρ = 1, ℓ = 1), Z_B = 3 (E = 9, ρ = 1, ℓ = 3): τ = 1 for both, v_A = 0.2, v_B = −0.1.
    ImpactConfiguration config;
    config.segments = {segment(1.0, 1.0, 1.0), segment(3.0, 9.0, 1.0)};
    config.junctions = {{true, 0.0}};
    config.obstacle = false;
    config.far_end = FarEnd::free;
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.0}, {0.2}}, {1.0, 4.0, {0.0}, {-0.1}}};
    const ImpactSolution solution(config, data, 6.0);
    REQUIRE(solution.contact_windows(0).size() >= 1);
    CHECK(std::abs(solution.contact_windows(0)[0].end - 2.0) <= 1e-12);
    for (int n = 1; n < 20; ++n)
      CHECK(std::abs(solution.contact_stress(0, 0.1 * n) - 0.75 * (-0.1 - 0.2)) <= 1e-12 * 0.3);
  }
}

TEST_CASE("layered bars: reflection at an interface, and equal impedances are transparent") {
  // A bar of two welded layers hits the wall with speed v: Z₁ = 2 (E = 4, ρ = 1, c = 2, ℓ = 1, τ₁ = ½),
  // Z₂ = 1 (E = ρ = 1, ℓ = 1.5, τ₂ = 1.5), free far end, gap 0.1. The impact (t₁ = 0.1) leaves σ₀ = −Z₁v
  // at the wall; the interface reflects the stress R = (Z₂ − Z₁)/(Z₁ + Z₂) of it, which doubles at the
  // rigid wall (u_t = 0 there): σ = σ₀(1 + 2R) = σ₀(3Z₂ − Z₁)/(Z₁ + Z₂) = σ₀/3 from t₁ + 2τ₁ until the
  // next arrival, t₁ + min(4τ₁, 2τ₁ + 2τ₂) = 2.1.
  {
    ImpactConfiguration config;
    config.segments = {segment(1.0, 4.0, 1.0), segment(1.5, 1.0, 1.0)};
    config.far_end = FarEnd::free;
    config.obstacle_gap = 0.1;
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.0}, {-1.0}}, {1.0, 2.5, {0.0}, {-1.0}}};
    const ImpactSolution solution(config, data, 10.0);
    CHECK(std::abs(solution.contact_windows(0).at(0).start - 0.1) <= 1e-12);
    for (int n = 1; n < 100; ++n) {
      const double t = 0.1 + 2.0 * n / 100.0;
      if (std::abs(t - 1.1) < 1e-9) continue;
      CHECK(std::abs(solution.contact_stress(0, t) - (t < 1.1 ? -2.0 : -2.0 / 3)) <= 1e-12 * 2);
    }
  }
  {
    // Equal impedances Z = 1 with c = 4 (E = 4, ρ = ¼, ℓ = 2, τ = ½) and c = 1 (ℓ = 1.5, τ = 1.5):
    // no reflection at the interface; the contact point sees a homogeneous bar of transit time 2.
    ImpactConfiguration config;
    config.segments = {segment(2.0, 4.0, 0.25), segment(1.5, 1.0, 1.0)};
    config.far_end = FarEnd::clamped;
    InitialData data;
    // u⁰ = ½(2 − θ), θ the travel time from x = 0: 1 − x/8 on [0, 2], ½(3.5 − x) on [2, 3.5].
    data.pieces = {{0.0, 2.0, {0.875, -0.125}, {0.0}}, {2.0, 3.5, {0.375, -0.375}, {0.0}}};
    const ImpactSolution solution(config, data, 12.0);
    const ExactSolution exact(2.0, 0.5);  // u⁰ = ½(2 − θ) in the travel time θ, period 6
    double d = 0;
    for (int n = 0; n <= 1200; ++n) {
      const double t = 12.0 * (n + 0.5) / 1201.0;
      d = std::max(d, std::abs(solution.gap(0, t) - exact.contact_displacement(t)));
      d = std::max(d, std::abs(solution.contact_stress(0, t) - exact.contact_multiplier(t)));
    }
    CAPTURE(d);
    CHECK(d <= 1e-12);
    const auto& w = solution.contact_windows(0);
    REQUIRE(w.size() == 2);
    CHECK(std::abs(w[0].start - 2.0) <= 1e-12);
    CHECK(std::abs(w[0].end - 4.0) <= 1e-12);
    CHECK(std::abs(w[1].start - 8.0) <= 1e-12);
    CHECK(std::abs(w[1].end - 10.0) <= 1e-12);
  }
}

TEST_CASE("the reference of the error measures: the energy with the load's potential, u(0, t) held at -g0") {
  // Impacting and layered at t = 0: undeformed with uniform v⁰, E = ½∫ρv² = ½ρLv² (8e6 J/m²; 1.25); the
  // bouncing bar at rest and undeformed: 0 (u = 0, so −∫f u = 0 too). Inside a window u(0, t) is −g₀
  // exactly; λ = σ(0, t) is that of the solution.
  const ImpactBenchmark& impacting = impact_benchmark("impacting");
  const ImpactReference a(impacting.configuration, impacting.data, impacting.final_time);
  CHECK(std::abs(a.energy() - 8e6) <= 1e-12 * 8e6);
  const ContactInterval w = a.contact_windows().front();
  CHECK(a.contact_displacement(0.5 * (w.start + w.end)) == -2e-3);
  CHECK(a.contact_multiplier(0.5 * (w.start + w.end)) == a.solution().contact_stress(0, 0.5 * (w.start + w.end)));
  const ImpactBenchmark& layered = impact_benchmark("layered");
  CHECK(std::abs(ImpactReference(layered.configuration, layered.data, 1.0).energy() - 1.25) <= 1e-12);
  const ImpactBenchmark& bouncing = impact_benchmark("bouncing");
  CHECK(ImpactReference(bouncing.configuration, bouncing.data, 1.0).energy() == 0.0);
  // u_x = σ/E in each segment (layered: E = 4 then 1).
  const ImpactReference l(layered.configuration, layered.data, 2.0);
  CHECK(std::abs(l.strain(0.5, 0.3) - l.solution().stress(0.5, 0.3) / 4) <= 1e-15);
  CHECK(std::abs(l.strain(2.0, 1.9) - l.solution().stress(2.0, 1.9)) <= 1e-15);
  const ImpactBenchmark& two = impact_benchmark("two-bars");
  CHECK_THROWS_AS(ImpactReference(two.configuration, two.data, 1.0), InvalidParameter);
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

TEST_CASE("the chain solver refuses what it cannot do, naming the problem") {
  InitialData data;
  data.pieces = {{0.0, 1.0, {0.25, -0.25}, {0.0}}};
  ImpactConfiguration good;
  good.segments = {segment(1.0, 1.0, 1.0)};
  CHECK_NOTHROW(ImpactSolution(good, data, 1.0));
  const auto refused = [&](ImpactConfiguration c, const InitialData& d, double t, const char* what) {
    CAPTURE(what);
    CHECK_THROWS_WITH_AS(ImpactSolution(c, d, t), doctest::Contains(what), InvalidParameter);
  };
  ImpactConfiguration c = good;
  c.segments[0].modulus = -1;
  refused(c, data, 1.0, "length, E and rho must be positive");
  c = good;
  c.obstacle_gap = -0.1;
  refused(c, data, 1.0, "gap must be finite and >= 0");
  c = good;
  c.obstacle = false;
  refused(c, data, 1.0, "no contact");
  c = good;
  c.segments.push_back(segment(1.0, 1.0, 1.0));
  c.junctions = {{false, 0.1}};
  refused(c, data, 1.0, "a welded junction has no gap");
  c.junctions = {{true, 0.0}, {true, 0.0}};
  refused(c, data, 1.0, "one junction per pair");
  c = good;
  c.segments[0].load = {NAN};
  refused(c, data, 1.0, "coefficients must be finite");
  refused(good, data, 0.0, "final time");
  InitialData bad = data;
  bad.pieces[0].displacement = {0.3, -0.25};
  refused(good, bad, 1.0, "u0 must be 0 at the clamped end");
  bad.pieces[0].displacement = {-0.5, 0.5};
  refused(good, bad, 1.0, "u0(0) + gap must be >= 0");
  ImpactConfiguration two = good;
  two.segments = {segment(0.5, 1.0, 1.0), segment(0.5, 1.0, 1.0)};
  refused(two, data, 1.0, "must be a breakpoint");  // the junction x = 0.5 is inside a data piece
  InitialData jump;
  jump.pieces = {{0.0, 0.5, {0.3, -0.1}, {0.0}}, {0.5, 1.0, {0.125, -0.125}, {0.0}}};
  refused(two, jump, 1.0, "u0 must be continuous at the welded junction");
  // Incommensurate layers: the fronts multiply; a small budget is refused rather than exceeded.
  ImpactConfiguration layered;
  layered.segments = {segment(1.0, 1.0, 1.0), segment(std::sqrt(2.0), 3.0, 1.0), segment(M_PI / 3, 0.5, 2.0)};
  layered.far_end = FarEnd::free;
  InitialData v;
  v.pieces = {{0.0, 1.0, {0.0}, {-1.0}},
              {1.0, 1.0 + std::sqrt(2.0), {0.0}, {-1.0}},
              {1.0 + std::sqrt(2.0), 1.0 + std::sqrt(2.0) + M_PI / 3, {0.0}, {-1.0}}};
  CHECK_THROWS_WITH_AS(ImpactSolution(layered, v, 200.0, 2000), doctest::Contains("too many wave fronts"),
                       InvalidParameter);
}

namespace {

// An independent solver for f = 0: the characteristic lattice. Every segment's transit time is a
// whole number of steps δ; the right- and left-going values at the nodes θ_i = iδ move one node per
// step; the junctions update the emitted values by the increments of the arriving ones (welded:
// Δr = R_A Δp + T_B Δq, Δs = T_A Δp + R_B Δq; free: Δr = Δp; clamp: r = −p); a contact updates its gap
// by Δy = 2Δq − 2Δp and, held, emits r by the welded rule and s = p + r − g₀ − q (obstacle: s = z − g₀ − q).
// Exact at the nodes as long as every contact event falls on a level (checked: a gap that would turn
// negative inside a step makes the lattice inexact, and the test requires that it never happens).
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
  // Closed forms (derived in the doctests above): bouncing [1, 5/3] + 8k/3; impacting [g₀/v, g₀/v + 2L/c];
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
  three.segments = {segment(0.4, 4.0, 1.0), segment(0.3, 1.0, 1.0), segment(0.5, 1.0, 4.0)};
  three.obstacle_gap = 0.1;
  InitialData layered_data;
  layered_data.pieces = {{0.0, 0.4, {0.0}, {-1.0}}, {0.4, 0.7, {0.0}, {-1.0}}, {0.7, 1.2, {0.0}, {-1.0}}};
  ImpactConfiguration unequal;
  unequal.segments = {segment(1.0, 1.0, 1.0), segment(3.0, 9.0, 1.0)};
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
