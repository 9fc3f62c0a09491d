/// @file piecewise_polynomial.hpp
/// @brief Polynomials in a local variable and piecewise polynomials of one variable: the
/// representation of the travelling waves of the characteristic solution (mathematics.md §10).
#pragma once

#include <cstddef>
#include <vector>

namespace mrm {

/// Polynomials Σ_k c_k σ^k stored by their coefficients in increasing degree.
namespace poly {

/// The coefficients c_0, c_1, … of Σ_k c_k σ^k.
using Coefficients = std::vector<double>;

/// p(σ) by Horner's rule (0 for the empty polynomial).
double evaluate(const Coefficients& c, double s);
/// dp/dσ.
Coefficients derivative(const Coefficients& c);
/// The antiderivative that vanishes at σ = 0.
Coefficients antiderivative(const Coefficients& c);
/// p q.
Coefficients product(const Coefficients& p, const Coefficients& q);
/// p^k (k ≥ 0).
Coefficients power(const Coefficients& p, int k);
/// Drops the trailing coefficients that are exactly zero.
void trim(Coefficients& c);
/// The points of the open interval (lo, hi) where p changes sign, in increasing order: the roots of
/// odd multiplicity, each to full floating-point precision (see the derivation in the .cpp file).
std::vector<double> sign_changes(const Coefficients& c, double lo, double hi);

}  // namespace poly

/// One polynomial piece on [a, b], written in the local variable σ = (x − centre)/radius.
///
/// The local variable need not map [a, b] onto [−1, 1]: a piece cut out of a larger one keeps the
/// larger one's variable, and moving a piece (x → x + s) or mirroring it (x → c − x) changes only the
/// centre and the signs of the coefficients. These operations are therefore exact in floating point,
/// which is what makes the characteristic solution exact to round-off (mathematics.md §10).
struct PolynomialPiece {
  double a = 0;              ///< the start of the piece's interval
  double b = 0;              ///< its end
  double centre = 0;         ///< the centre of the local variable σ = (x − centre)/radius
  double radius = 1;         ///< its scale
  poly::Coefficients value;  ///< p in σ
  poly::Coefficients slope;  ///< dp/dx in σ: (1/radius) dp/dσ

  /// The piece p(x) = Σ c_k σ^k on [a, b] with σ = (x − (a + b)/2)/((b − a)/2).
  static PolynomialPiece on(double a, double b, poly::Coefficients c);
  double sigma(double x) const { return (x - centre) / radius; }                    ///< σ(x)
  double at(double x) const { return poly::evaluate(value, sigma(x)); }             ///< p(x)
  double derivative_at(double x) const { return poly::evaluate(slope, sigma(x)); }  ///< p′(x)
  /// x ↦ p(x) restricted to [a', b'] ⊂ [a, b] (same variable).
  PolynomialPiece restricted(double a_new, double b_new) const;
  /// x ↦ p(x − shift) on [a + shift, b + shift].
  PolynomialPiece translated(double shift) const;
  /// x ↦ p(mirror − x) on [mirror − b, mirror − a].
  PolynomialPiece mirrored(double mirror) const;
  /// x ↦ −p(x).
  PolynomialPiece negated() const;
  /// x ↦ p(x) + d.
  PolynomialPiece plus(double d) const;
};

/// A continuous piecewise polynomial on [begin, end]: contiguous pieces in increasing order.
class PiecewisePolynomial {
 public:
  /// Appends a piece that starts where the last one ends (its start is set to the current end, which
  /// absorbs round-off in the caller's arithmetic); throws std::invalid_argument if it would be empty
  /// or start elsewhere by more than `tolerance`.
  void append(PolynomialPiece piece, double tolerance = 0.0);
  const std::vector<PolynomialPiece>& pieces() const { return pieces_; }  ///< the pieces, in increasing order
  bool empty() const { return pieces_.empty(); }                          ///< whether there is no piece
  double begin() const { return pieces_.front().a; }                      ///< the start of the first piece
  double end() const { return pieces_.back().b; }                         ///< the end of the last piece

  /// The index of the piece with a ≤ x < b (the last piece for x = end), starting the search at `hint`
  /// (a walk for nearby points, a bisection otherwise). x must lie in [begin, end].
  std::size_t locate(double x, std::size_t hint = 0) const;
  /// p(x); `hint` (if given) is the piece to start the search from, and receives the piece found.
  double value(double x, std::size_t* hint = nullptr) const;
  /// p′(x); within `tie` of a breakpoint, the mean of the one-sided derivatives there (`hint` as for value).
  double derivative(double x, double tie, std::size_t* hint = nullptr) const;
  /// ∫_{x0}^{x1} p′(x)² dx, x0 ≤ x1 in [begin, end], exact up to round-off.
  double integral_of_squared_derivative(double x0, double x1) const;
  /// ∫_{x0}^{x1} p(x) dx, exact up to round-off.
  double integral(double x0, double x1) const;

 private:
  std::vector<PolynomialPiece> pieces_;
};

}  // namespace mrm
