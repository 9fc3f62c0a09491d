/// @file piecewise_polynomial.cpp
/// @brief Polynomials in a local variable and piecewise polynomials (mathematics.md §10).
///
/// The characteristic solution (characteristics.cpp) writes the displacement as two travelling waves
/// F(x − t) and G(x + t), and both are piecewise polynomials when the data are. Everything it does to
/// them is one of four operations: cut a piece at a point, move it (the clamp's reflection and the
/// march from one window to the next), mirror it (x → 2L − x) and add a constant or change its sign
/// (the contact point). Each piece is written in its own local variable σ = (x − centre)/radius, and
/// none of these operations re-expands a polynomial about a new point:
///
///   - a cut keeps the parent's variable (the piece [a′, b′] ⊂ [a, b] is the same polynomial in the same σ);
///   - a move x → x + s moves the centre: the coefficients do not change;
///   - a mirror x → c − x maps σ to −σ' with centre' = c − centre: the coefficient of σ^k changes sign
///     for odd k, and nothing else;
///   - p + d changes c₀ only, −p every sign.
///
/// So the coefficients of every wave the solution ever uses are, up to signs and constant terms, those
/// of the data, however many reflections they went through: no error accumulates. (Re-expanding a
/// degree-14 polynomial about a new point, as a monomial representation x^k would force at every
/// reflection, loses several digits each time.) Evaluations use Horner's rule in σ with |σ| ≤ 1 on the
/// data's pieces.
///
/// Mirroring is exact in floating point: with σ' = −σ (the subtraction x − c is sign-symmetric) and
/// c'_k = (−1)^k c_k, every partial sum of Horner's rule for (c', σ') is (−1)^k times the one for (c, σ),
/// so p'(σ') = p(σ) bit for bit, and likewise the slope with the opposite sign. characteristics.cpp
/// relies on it: at the contact point, F(−t) + G(t) is exactly 0 during contact and F′(−t) + G′(t)
/// exactly 0 in free flight.
///
/// Sign changes. The contact point needs the points where a polynomial changes sign (the extrema of the
/// incoming wave). Between two consecutive sign changes of p′, p is monotone, so each of its sign changes
/// is bracketed by two consecutive extrema and found by bisection to the last bit; the sign changes of
/// p′ come from those of p″ the same way, down to degree 1. A root of even multiplicity (p touches 0
/// without crossing) is not a sign change and is not reported; a root of odd multiplicity m ≥ 3 is a
/// sign change of p (p′ has a root of even multiplicity there, so the bracket spans it) and is found to
/// the precision its conditioning allows, ε^{1/m} relative, which is the best any method can do. Near a
/// multiple root the computed p is rounding noise over a small interval; a sign is trusted only where |p|
/// exceeds the bound of Horner's rounding error, so that noise does not create pairs of sign changes.
#include "exact/piecewise_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

namespace mrm {

namespace poly {

double evaluate(const Coefficients& c, double s) {
  double r = 0;
  for (std::size_t k = c.size(); k-- > 0;) r = r * s + c[k];
  return r;
}

Coefficients derivative(const Coefficients& c) {
  Coefficients d(c.size() > 1 ? c.size() - 1 : 0);
  for (std::size_t k = 1; k < c.size(); ++k) d[k - 1] = static_cast<double>(k) * c[k];
  return d;
}

Coefficients antiderivative(const Coefficients& c) {
  Coefficients a(c.size() + 1, 0.0);
  for (std::size_t k = 0; k < c.size(); ++k) a[k + 1] = c[k] / static_cast<double>(k + 1);
  return a;
}

Coefficients product(const Coefficients& p, const Coefficients& q) {
  if (p.empty() || q.empty()) return {};
  Coefficients r(p.size() + q.size() - 1, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j) r[i + j] += p[i] * q[j];
  return r;
}

Coefficients power(const Coefficients& p, int k) {
  if (k < 0) throw std::invalid_argument("poly::power: the exponent must be >= 0");
  Coefficients r{1.0};
  for (int i = 0; i < k; ++i) r = product(r, p);
  return r;
}

void trim(Coefficients& c) {
  while (!c.empty() && c.back() == 0.0) c.pop_back();
}

namespace {

// A root of p in (u, v) where p(u) and p(v) have strictly opposite signs, by bisection until the
// interval has no floating-point number inside.
double bisect(const Coefficients& c, double u, double v, double pu) {
  for (;;) {
    const double mid = 0.5 * (u + v);
    if (!(mid > u && mid < v)) return mid;
    const double pm = evaluate(c, mid);
    if (pm == 0.0) return mid;
    if ((pm < 0) == (pu < 0)) {
      u = mid;
      pu = pm;
    } else {
      v = mid;
    }
  }
}

}  // namespace

std::vector<double> sign_changes(const Coefficients& coefficients, double lo, double hi) {
  Coefficients c = coefficients;
  trim(c);
  if (c.size() <= 1 || !(lo < hi)) return {};
  if (c.size() == 2) {
    const double r = -c[0] / c[1];
    if (r > lo && r < hi) return {r};
    return {};
  }
  std::vector<double> points{lo};
  for (double e : sign_changes(derivative(c), lo, hi)) points.push_back(e);
  points.push_back(hi);
  // The sign of p at each point, 0 where |p| is within the bound of its rounding error
  // 2 (n + 1) ε Σ|c_k||σ|^k (Horner's rule): near a multiple root, p is noise over a small interval, and
  // an extremum inside it must not produce a pair of sign changes that are not there.
  Coefficients magnitude(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) magnitude[k] = std::abs(c[k]);
  const double unit = 2.0 * static_cast<double>(c.size() + 1) * std::numeric_limits<double>::epsilon();
  std::vector<double> roots;
  std::size_t last = 0;  // the last point with a certain sign
  int last_sign = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double p = evaluate(c, points[k]), noise = unit * evaluate(magnitude, std::abs(points[k]));
    const int sign = std::abs(p) <= noise ? 0 : (p > 0 ? 1 : -1);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) {
      // A sign change between two points of certain signs; bisection finds a point where p changes sign.
      roots.push_back(bisect(c, points[last], points[k], last_sign < 0 ? -1.0 : 1.0));
    }
    last = k;
    last_sign = sign;
  }
  return roots;
}

}  // namespace poly

TEST_CASE("the sign changes of a polynomial are its roots of odd multiplicity, to full precision") {
  // p(σ) = (σ + 0.7)³ (σ − 0.1)² (σ − 0.45) (σ − 0.9)⁴ (σ − 0.95): sign changes at −0.7 (triple),
  // 0.45 and 0.95 (simple); 0.1 and 0.9 are roots of even multiplicity (no sign change).
  using poly::Coefficients;
  Coefficients p{1.0};
  const std::vector<std::pair<double, int>> factors{{-0.7, 3}, {0.1, 2}, {0.45, 1}, {0.9, 4}, {0.95, 1}};
  for (const auto& [root, multiplicity] : factors) p = poly::product(p, poly::power({-root, 1.0}, multiplicity));
  const std::vector<double> roots = poly::sign_changes(p, -1.0, 1.0);
  REQUIRE(roots.size() == 3);
  // The precision a root can have: p is known to δ = 2(n + 1)ε Σ|c_k||σ|^k, so a simple root r to
  // δ/|p′(r)| and a triple one to (6δ/|p‴(r)|)^{1/3} (a factor 2 of margin on each).
  const auto rounding = [&](double r) {
    double sum = 0;
    for (std::size_t k = 0; k < p.size(); ++k) sum += std::abs(p[k]) * std::pow(std::abs(r), static_cast<double>(k));
    return 2.0 * static_cast<double>(p.size() + 1) * 2.220446049250313e-16 * sum;
  };
  const poly::Coefficients d1 = poly::derivative(p), d3 = poly::derivative(poly::derivative(d1));
  const double triple = 2 * std::cbrt(6 * rounding(-0.7) / std::abs(poly::evaluate(d3, -0.7)));
  CAPTURE(triple);
  CHECK(triple < 1e-4);
  CHECK(std::abs(roots[0] + 0.7) <= triple);
  for (const auto& [k, root] : {std::pair<int, double>{1, 0.45}, {2, 0.95}}) {
    const double bound = 2 * rounding(root) / std::abs(poly::evaluate(d1, root));
    CAPTURE(root);
    CAPTURE(bound);
    CHECK(std::abs(roots[static_cast<std::size_t>(k)] - root) <= bound);
  }
  // The open interval: a root at an end is not reported; outside roots neither.
  CHECK(poly::sign_changes({-0.5, 1.0}, 0.5, 1.0).empty());
  CHECK(poly::sign_changes(p, 0.5, 0.94).empty());
  CHECK(poly::sign_changes({3.0}, -1.0, 1.0).empty());
}

// ---------------------------------------------------------------------------------------------------
// Pieces.

PolynomialPiece PolynomialPiece::on(double a, double b, poly::Coefficients c) {
  if (!(b > a)) throw std::invalid_argument("polynomial piece: the interval [a, b] must have b > a");
  PolynomialPiece p;
  p.a = a;
  p.b = b;
  p.centre = 0.5 * (a + b);
  p.radius = 0.5 * (b - a);
  poly::trim(c);
  p.value = c;
  p.slope = poly::derivative(c);
  for (double& s : p.slope) s /= p.radius;
  return p;
}

PolynomialPiece PolynomialPiece::restricted(double a_new, double b_new) const {
  PolynomialPiece p = *this;
  p.a = a_new;
  p.b = b_new;
  return p;
}

PolynomialPiece PolynomialPiece::translated(double shift) const {
  PolynomialPiece p = *this;
  p.a += shift;
  p.b += shift;
  p.centre += shift;
  return p;
}

PolynomialPiece PolynomialPiece::mirrored(double mirror) const {
  PolynomialPiece p = *this;
  p.a = mirror - b;
  p.b = mirror - a;
  p.centre = mirror - centre;
  for (std::size_t k = 1; k < p.value.size(); k += 2) p.value[k] = -p.value[k];
  for (std::size_t k = 0; k < p.slope.size(); k += 2) p.slope[k] = -p.slope[k];
  return p;
}

PolynomialPiece PolynomialPiece::negated() const {
  PolynomialPiece p = *this;
  for (double& c : p.value) c = -c;
  for (double& c : p.slope) c = -c;
  return p;
}

PolynomialPiece PolynomialPiece::plus(double d) const {
  PolynomialPiece p = *this;
  if (p.value.empty()) p.value.push_back(0.0);
  p.value[0] += d;
  return p;
}

TEST_CASE("moving, mirroring and negating a piece are exact in floating point") {
  const PolynomialPiece p = PolynomialPiece::on(0.1, 0.9, {0.3, -1.7, 0.2, 2.9, -0.4, 1.1});
  const PolynomialPiece m = p.mirrored(2.0), t = p.translated(3.25), n = p.negated();
  CHECK(m.a == 2.0 - 0.9);
  CHECK(m.b == 2.0 - 0.1);
  int checked = 0;
  for (int k = 0; k <= 100; ++k) {
    const double x = 0.1 + 0.008 * k;
    CAPTURE(x);
    // At the mirrored point 2 − x (rounded, and with the rounded centre 2 − c) the values agree to
    // round-off; with the mirrored variable −σ itself they agree bit for bit (below).
    const double y = 2.0 - x;
    CHECK(std::abs(m.at(y) - p.at(x)) <= 1e-14);
    CHECK(std::abs(m.derivative_at(y) + p.derivative_at(x)) <= 1e-13);
    CHECK(n.at(x) == -p.at(x));
    CHECK(n.derivative_at(x) == -p.derivative_at(x));
    const double s = p.sigma(x);
    CHECK(poly::evaluate(m.value, -s) == p.at(x));
    CHECK(poly::evaluate(m.slope, -s) == -p.derivative_at(x));
    // A move rounds the moved point x + 3.25 (to 4.4e-16 of 4), not the coefficients.
    CHECK(std::abs(t.at(x + 3.25) - p.at(x)) <= 1e-13);
    ++checked;
  }
  CHECK(checked == 101);
  // The slope is the derivative: against a central difference.
  for (double x : {0.15, 0.4, 0.77}) {
    const double d = 1e-6, fd = (p.at(x + d) - p.at(x - d)) / (2 * d);
    CAPTURE(x);
    CHECK(std::abs(fd - p.derivative_at(x)) < 1e-7);
  }
}

// ---------------------------------------------------------------------------------------------------
// Piecewise polynomials.

void PiecewisePolynomial::append(PolynomialPiece piece, double tolerance) {
  if (!pieces_.empty()) {
    const double end = pieces_.back().b;
    if (!(std::abs(piece.a - end) <= tolerance))
      throw std::invalid_argument("piecewise polynomial: a piece must start where the last one ends (at " +
                                  std::to_string(end) + ", got " + std::to_string(piece.a) + ")");
    piece.a = end;
  }
  if (!(piece.b > piece.a)) throw std::invalid_argument("piecewise polynomial: a piece must not be empty");
  pieces_.push_back(std::move(piece));
}

std::size_t PiecewisePolynomial::locate(double x, std::size_t hint) const {
  const std::size_t n = pieces_.size();
  if (n == 0 || !(x >= pieces_.front().a && x <= pieces_.back().b))
    throw std::out_of_range("piecewise polynomial: x = " + std::to_string(x) + " outside [" +
                            (n ? std::to_string(begin()) + ", " + std::to_string(end()) : std::string("empty")) + "]");
  if (hint >= n) hint = n - 1;
  // A short walk from the hint (sorted points move by a few pieces at most), then a bisection.
  for (int steps = 0; steps < 4; ++steps) {
    const PolynomialPiece& p = pieces_[hint];
    if (x < p.a) {
      if (hint == 0) break;
      --hint;
    } else if (x >= p.b && hint + 1 < n) {
      ++hint;
    } else {
      return hint;
    }
  }
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), x,
                                   [](double value, const PolynomialPiece& p) { return value < p.a; });
  const std::size_t k = static_cast<std::size_t>(it - pieces_.begin());
  return k == 0 ? 0 : k - 1;
}

double PiecewisePolynomial::value(double x, std::size_t* hint) const {
  const std::size_t k = locate(x, hint ? *hint : 0);
  if (hint) *hint = k;
  return pieces_[k].at(x);
}

double PiecewisePolynomial::derivative(double x, double tie, std::size_t* hint) const {
  const std::size_t k = locate(x, hint ? *hint : 0);
  if (hint) *hint = k;
  const PolynomialPiece& p = pieces_[k];
  const double here = p.derivative_at(x);
  if (k > 0 && x - p.a <= tie) return 0.5 * (pieces_[k - 1].derivative_at(x) + here);
  if (k + 1 < pieces_.size() && p.b - x <= tie) return 0.5 * (here + pieces_[k + 1].derivative_at(x));
  return here;
}

namespace {

// ∫ over [x0, x1] ∩ each piece of q(piece)(σ) dx, with q a polynomial built from the piece.
template <class Integrand>
double integrate_pieces(const std::vector<PolynomialPiece>& pieces, double x0, double x1, Integrand&& integrand) {
  if (!(x0 <= x1)) throw std::invalid_argument("piecewise polynomial: an integral needs x0 <= x1");
  double sum = 0;
  for (const PolynomialPiece& p : pieces) {
    const double lo = std::max(x0, p.a), hi = std::min(x1, p.b);
    if (!(hi > lo)) continue;
    const poly::Coefficients q = poly::antiderivative(integrand(p));
    sum += p.radius * (poly::evaluate(q, p.sigma(hi)) - poly::evaluate(q, p.sigma(lo)));
  }
  return sum;
}

}  // namespace

double PiecewisePolynomial::integral_of_squared_derivative(double x0, double x1) const {
  return integrate_pieces(pieces_, x0, x1, [](const PolynomialPiece& p) { return poly::product(p.slope, p.slope); });
}

double PiecewisePolynomial::integral(double x0, double x1) const {
  return integrate_pieces(pieces_, x0, x1, [](const PolynomialPiece& p) { return p.value; });
}

TEST_CASE("a piecewise polynomial gives the mean of the one-sided derivatives at a breakpoint") {
  // |x − 1| on [0, 3] as two affine pieces: the derivative is −1, +1, and 0 at x = 1.
  PiecewisePolynomial f;
  f.append(PolynomialPiece::on(0.0, 1.0, {0.5, -0.5}));  // 1 − x with σ = 2x − 1
  f.append(PolynomialPiece::on(1.0, 3.0, {1.0, 1.0}));   // x − 1 with σ = x − 2
  CHECK(f.value(0.25) == 0.75);
  CHECK(f.value(2.5) == 1.5);
  CHECK(f.derivative(0.5, 1e-12) == -1.0);
  CHECK(f.derivative(2.0, 1e-12) == 1.0);
  CHECK(f.derivative(1.0, 1e-12) == 0.0);
  CHECK(f.derivative(1.0 - 1e-13, 1e-12) == 0.0);
  CHECK(f.derivative(1.0 - 1e-10, 1e-12) == -1.0);
  CHECK(f.derivative(3.0, 1e-12) == 1.0);  // at the end: the one-sided derivative
  // ∫ f′² = 3, ∫ f = ½ + 2, by pieces and across the breakpoint.
  CHECK(std::abs(f.integral_of_squared_derivative(0.0, 3.0) - 3.0) < 1e-15);
  CHECK(std::abs(f.integral(0.0, 3.0) - 2.5) < 1e-15);
  CHECK(std::abs(f.integral(0.5, 2.0) - (0.125 + 0.5)) < 1e-15);
  CHECK_THROWS_AS(f.value(3.5), std::out_of_range);
  CHECK_THROWS_AS(f.append(PolynomialPiece::on(3.5, 4.0, {1.0})), std::invalid_argument);
  // Locating from any hint gives the same piece.
  for (std::size_t hint : {std::size_t{0}, std::size_t{1}, std::size_t{7}}) {
    CHECK(f.locate(0.999, hint) == 0);
    CHECK(f.locate(1.0, hint) == 1);
    CHECK(f.locate(3.0, hint) == 1);
  }
}

TEST_CASE("the integral of a squared derivative of a piece is exact") {
  // p(x) = x³ on [0.2, 1.3]: ∫ 9x⁴ = 9/5 (1.3⁵ − 0.2⁵).
  const double a = 0.2, b = 1.3, m = 0.5 * (a + b), r = 0.5 * (b - a);
  // x = m + rσ: x³ = m³ + 3m²r σ + 3m r² σ² + r³ σ³.
  PiecewisePolynomial f;
  f.append(PolynomialPiece::on(a, b, {m * m * m, 3 * m * m * r, 3 * m * r * r, r * r * r}));
  const double exact = 9.0 / 5.0 * (std::pow(b, 5) - std::pow(a, 5));
  CHECK(std::abs(f.integral_of_squared_derivative(a, b) - exact) < 1e-14 * exact);
  CHECK(std::abs(f.value(0.7) - 0.343) < 1e-15);
}

}  // namespace mrm
