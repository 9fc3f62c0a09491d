/// @file impact_chain.cpp
/// @brief The exact solution of a chain of bar segments: loads, a free far end, gaps, layered bars and
/// two bars in contact (doc/benchmarks.md §2–§7), by characteristics in time and Skorokhod reflections.
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
#include "exact/impact_chain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

#include "core/constants.hpp"
#include "core/problem.hpp"
#include "exact/exact_solution.hpp"

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

// A double in full (17 significant digits), for the messages of the exceptions.
std::string digits17(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

BarSegment uniform_segment(double length, double modulus, double density, double load) {
  BarSegment s;
  s.length = length;
  s.modulus = modulus;
  s.density = density;
  if (load != 0.0) s.load = {load};
  return s;
}

double ImpactConfiguration::length() const {
  double sum = 0;
  for (const BarSegment& s : segments) sum += s.length;
  return sum;
}

bool is_two_body_chain(const ImpactConfiguration& c) {
  return !c.obstacle && c.segments.size() == 2 && c.junctions.size() == 1 && c.junctions[0].contact;
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
    throw InvalidParameter("initial_data", "the pieces must end at the chain's length " + digits17(total));
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
      throw InvalidParameter("initial_data", "every junction (x = " + digits17(origin_[j]) + ") must be a breakpoint");
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
                             "every junction (x = " + digits17(origin_[j + 1]) + ") must be a breakpoint");
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
                             "u0 must be continuous at the welded junction x = " + digits17(origin_[j + 1]));
    if (config_.junctions[j].contact && jump + config_.junctions[j].gap < -tol)
      throw InvalidParameter("initial_data", "the contact at x = " + digits17(origin_[j + 1]) +
                                                 " is violated at t = 0 (u_B - u_A + gap < 0)");
  }
  if (config_.far_end == FarEnd::clamped && std::abs(u_left(n - 1)) > tol)
    throw InvalidParameter("initial_data", "u0 must be 0 at the clamped end, got " + digits17(u_left(n - 1)));
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
    throw InvalidParameter("final_time", "the horizon " + digits17(horizon_) + " is more than 1e5 transit times (" +
                                             digits17(max_windows * window) +
                                             ") of the shortest segment: too many wave fronts to solve exactly");
  for (long w = 0;; ++w) {
    const double t0 = static_cast<double>(w) * window, t1 = static_cast<double>(w + 1) * window;
    for (std::size_t node = 0; node <= n; ++node) process(node, t0, t1);
    if (piece_count() > max_pieces)
      throw InvalidParameter("final_time", "more than " + std::to_string(max_pieces) +
                                               " wave pieces before t = " + digits17(t1) +
                                               ": too many wave fronts over the horizon to solve exactly");
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
    throw std::out_of_range("impact solution: x = " + digits17(x) + " outside [0, " + digits17(origin_.back()) + "]");
  const auto it = std::upper_bound(origin_.begin() + 1, origin_.end() - 1, x);
  std::size_t j = static_cast<std::size_t>(it - origin_.begin()) - 1;
  if (j > 0 && x == origin_[j]) --j;  // a junction belongs to the segment on its left
  return j;
}

namespace {
void check_time(double t, double horizon) {
  if (!(t >= 0.0 && t <= horizon))
    throw std::out_of_range("impact solution: t = " + digits17(t) + " outside [0, " + digits17(horizon) + "]");
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

// ---------------------------------------------------------------------------------------------------
// Checks against the paper's closed form and the clamped solver, and the refusals.

namespace {

// Data u⁰ = u0 + u1 (x − a)/(b − a)·2 − …: one piece per segment with u⁰ affine and v⁰ constant on it.
InitialDataPiece affine_piece(double a, double b, double ua, double ub, double v) {
  return {a, b, {0.5 * (ua + ub), 0.5 * (ub - ua)}, {v}};
}

}  // namespace

TEST_CASE("the chain solver reproduces the paper's closed form, also cut into welded pieces") {
  // L = 1, c = 1, u⁰ = (1 − x)/2, v⁰ = 0, clamped, obstacle at 0: mathematics.md §2, over 10 periods.
  const ExactSolution exact(1.0, 0.5);
  for (int cuts : {1, 3}) {
    ImpactConfiguration config;
    InitialData data;
    for (int j = 0; j < cuts; ++j) {
      config.segments.push_back(uniform_segment(1.0 / cuts, 1.0, 1.0));
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
  config.segments = {uniform_segment(1.3, 1.0, 1.0)};
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
TEST_CASE("the chain solver refuses what it cannot do, naming the problem") {
  InitialData data;
  data.pieces = {{0.0, 1.0, {0.25, -0.25}, {0.0}}};
  ImpactConfiguration good;
  good.segments = {uniform_segment(1.0, 1.0, 1.0)};
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
  c.segments.push_back(uniform_segment(1.0, 1.0, 1.0));
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
  two.segments = {uniform_segment(0.5, 1.0, 1.0), uniform_segment(0.5, 1.0, 1.0)};
  refused(two, data, 1.0, "must be a breakpoint");  // the junction x = 0.5 is inside a data piece
  InitialData jump;
  jump.pieces = {{0.0, 0.5, {0.3, -0.1}, {0.0}}, {0.5, 1.0, {0.125, -0.125}, {0.0}}};
  refused(two, jump, 1.0, "u0 must be continuous at the welded junction");
  // Incommensurate layers: the fronts multiply; a small budget is refused rather than exceeded.
  ImpactConfiguration layered;
  layered.segments = {uniform_segment(1.0, 1.0, 1.0), uniform_segment(std::sqrt(2.0), 3.0, 1.0),
                      uniform_segment(pi / 3, 0.5, 2.0)};
  layered.far_end = FarEnd::free;
  InitialData v;
  v.pieces = {{0.0, 1.0, {0.0}, {-1.0}},
              {1.0, 1.0 + std::sqrt(2.0), {0.0}, {-1.0}},
              {1.0 + std::sqrt(2.0), 1.0 + std::sqrt(2.0) + pi / 3, {0.0}, {-1.0}}};
  CHECK_THROWS_WITH_AS(ImpactSolution(layered, v, 200.0, 2000), doctest::Contains("too many wave fronts"),
                       InvalidParameter);
}

}  // namespace mrm
