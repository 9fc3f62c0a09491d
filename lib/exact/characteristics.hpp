/// @file characteristics.hpp
/// @brief The exact solution of the Signorini wave problem for any initial data, by characteristics
/// and the Skorokhod reflection at the contact point (mathematics.md §10).
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/piecewise_polynomial.hpp"
#include "exact/reference_solution.hpp"
#include "core/problem.hpp"

namespace mrm {

/// One piece [a, b] of initial data: u⁰ and v⁰ are polynomials in σ = (x − (a + b)/2)/((b − a)/2).
struct InitialDataPiece {
  double a;                         ///< the start of the piece
  double b;                         ///< its end (> a)
  poly::Coefficients displacement;  ///< u⁰ in σ
  poly::Coefficients velocity;      ///< v⁰ in σ
};

/// Initial data (u⁰, v⁰) on [0, L] as piecewise polynomials with common breakpoints. The problem's
/// assumptions (mathematics.md §1): u⁰ continuous, u⁰(L) = 0 (the clamp), u⁰(0) ≥ 0 (the obstacle);
/// v⁰ may jump.
struct InitialData {
  std::vector<InitialDataPiece> pieces;  ///< contiguous pieces from x = 0 to x = L

  double length() const { return pieces.back().b; }  ///< L, the end of the last piece
  double displacement(double x) const;               ///< u⁰(x), x ∈ [0, L]
  double velocity(double x) const;                   ///< v⁰(x), x ∈ [0, L] (the right-hand piece at a breakpoint)
  /// Throws std::invalid_argument unless the pieces are contiguous from 0 with b > a, every
  /// coefficient is finite, u⁰ is continuous (to 1e-12 of its largest value), u⁰(L) = 0 exactly and
  /// u⁰(0) ≥ 0.
  void validate() const;
  /// The problem of the schemes (schemes.hpp) with these data and f = 0.
  Problem problem() const;
};

/// A bad row of sampled initial data: `row()` is its 0-based index among the samples.
class SampleError : public std::invalid_argument {
 public:
  /// The error `what` about row `row`.
  SampleError(std::size_t row, const std::string& what) : std::invalid_argument(what), row_(row) {}
  std::size_t row() const { return row_; }  ///< the 0-based index of the bad row (the count for too few rows)

 private:
  std::size_t row_;
};

/// The initial data that interpolate samples (x_k, u⁰_k, v⁰_k) linearly: L = x_last. Throws
/// SampleError (naming the row) for fewer than 2 rows, a value that is not finite, x_0 ≠ 0, x not
/// strictly increasing, u⁰(L) ≠ 0 or u⁰(0) < 0; std::invalid_argument if the columns differ in length.
InitialData initial_data_from_samples(const std::vector<double>& x, const std::vector<double>& u0,
                                      const std::vector<double>& v0);

/// The data of the closed-form benchmark (mathematics.md §2): u⁰ = a (L − x), v⁰ = 0.
InitialData benchmark_initial_data(double length = 1.0, double amplitude = 0.5);

/// A time interval during which the contact point is held (u(0, t) = 0). One still held at the end of
/// the computed horizon T ends there and is `open`.
struct ContactInterval {
  double start;  ///< the instant the point is first held
  double end;    ///< the instant it is released (or T)
  bool open;     ///< whether it is still held at T
};

/// The solution for f = 0 and any data, exact to round-off for piecewise-polynomial data
/// (mathematics.md §10), on [0, L] × [0, T].
class CharacteristicSolution : public ReferenceSolution {
 public:
  /// Computes the two travelling waves for the horizon T = `final_time`. Throws
  /// std::invalid_argument for invalid data (InitialData::validate) or T not positive and finite.
  CharacteristicSolution(const InitialData& data, double final_time);

  double length() const override { return length_; }
  double displacement(double x, double t) const override;
  double strain(double x, double t) const override;
  double velocity(double x, double t) const override;
  double contact_displacement(double t) const override;
  double contact_multiplier(double t) const override;
  /// E(0); energy_at(t) computes E(t) from the waves (the same to round-off).
  double energy() const override { return energy_; }
  /// E(t) = ∫_{−t}^{L−t} F′² + ∫_t^{L+t} G′², exact for polynomial pieces.
  double energy_at(double t) const;
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  void velocity_at_points(double t, const double* x, long count, double* v) const override;

  /// The intervals of contact in [0, T], in increasing order.
  const std::vector<ContactInterval>& contact_intervals() const { return contact_; }
  /// T, the end of the computed horizon (the final time asked for).
  double horizon() const { return horizon_; }
  /// The right-going wave F on [−T, L] (u = F(x − t) + G(x + t)).
  const PiecewisePolynomial& right_going() const { return right_; }
  /// The left-going wave G on [0, T + L].
  const PiecewisePolynomial& left_going() const { return left_; }

 private:
  void check(double x, double t) const;
  double right_slope(double x, double t, std::size_t* hint = nullptr) const;
  void advance_contact_point(const PolynomialPiece& incoming);

  double length_, horizon_, tie_, event_snap_, slope_noise_ = 0, energy_ = 0;
  std::size_t first_initial_piece_ = 0;          // the index in F of the first piece of the initial F (ξ ≥ 0)
  PiecewisePolynomial right_, left_, outgoing_;  // F, G and s ↦ F(−s) while it is built
  std::vector<ContactInterval> contact_;
  double gap_ = 0;     // g at the start of the next incoming piece
  bool held_ = false;  // whether the contact point is held there
};

/// The characteristic solution tabulated on a lattice of spacing δ, for the error measures: F and F′ at
/// ξ = kδ in [−T, L], G and G′ at η = kδ in [0, L + T]. At points x = jδ and instants t = nδ (the nodes
/// and levels of a mesh whose h and Δt are multiples of δ), u = F(x − t) + G(x + t) and
/// u_t = −F′(x − t) + G′(x + t) are two table entries each; anywhere else the solution is evaluated
/// directly. The tables hold the solver's own values (the same means at breakpoints), so the two paths
/// differ only by the rounding of x − t.
class TabulatedSolution : public ReferenceSolution {
 public:
  /// Throws std::invalid_argument unless δ > 0 is finite and the tables have at most 10⁸ entries.
  TabulatedSolution(CharacteristicSolution solution, double spacing);

  double length() const override { return solution_.length(); }
  double displacement(double x, double t) const override { return solution_.displacement(x, t); }
  double strain(double x, double t) const override { return solution_.strain(x, t); }
  double velocity(double x, double t) const override { return solution_.velocity(x, t); }
  double contact_displacement(double t) const override { return solution_.contact_displacement(t); }
  double contact_multiplier(double t) const override { return solution_.contact_multiplier(t); }
  double energy() const override { return solution_.energy(); }
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  void velocity_at_points(double t, const double* x, long count, double* v) const override;
  const CharacteristicSolution& solution() const { return solution_; }  ///< the solution tabulated
  /// Whether *_at_points(t, x, count, ·) take the straight loop of table look-ups (points of a uniform
  /// mesh on the lattice at a level on it, characteristics.cpp) rather than the per-point path; both
  /// give the same bits.
  bool takes_lattice_run(double t, const double* x, long count) const;

 private:
  // The lattice index of a point (−1 if it is not on the lattice to 1e-9 δ).
  bool on_lattice(double x, long& index) const;
  template <bool derivative>
  void at_points(double t, const double* x, long count, double* out) const;
  // The straight loop for the points x_i on the lattice at j₀ + i s at level n; false (out unspecified)
  // if a point is not where that predicts.
  template <bool derivative>
  bool lattice_run(long n, const double* x, long count, double* out) const;
  // Whether x_0 … x_{count−1} lie on the lattice at j₀ + i s (j₀, s set): checked point by point once per
  // set of points (by their bits) and remembered (characteristics.cpp).
  bool lattice_points(const double* x, long count, long& first, long& step) const;
  struct PointSets;  // the sets of points checked so far (shared by copies: the same δ and L)

  CharacteristicSolution solution_;
  double spacing_, inverse_spacing_;
  long right_first_;  // ξ = (right_first_ + k) δ is entry k of the tables of F
  std::vector<double> right_value_, right_slope_, left_value_, left_slope_;
  std::shared_ptr<PointSets> point_sets_;
};

/// The largest differences between the characteristic solution of the benchmark's data
/// (benchmark_initial_data) and the closed form (mathematics.md §2), two independent derivations of
/// the same solution: u and u(0, ·) relative to aL, u_x, u_t and λ relative to a.
struct ClosedFormDifference {
  double length = 0;                ///< L
  double amplitude = 0;             ///< a
  double periods = 0;               ///< the horizon T = 3L × periods
  double displacement = 0;          ///< max |Δu|/(aL) over the points of the (x, t) grids
  double strain = 0;                ///< max |Δu_x|/a (the corners x ∈ {0, L}, t = kL left out)
  double velocity = 0;              ///< max |Δu_t|/a (likewise)
  double contact_displacement = 0;  ///< max |Δu(0, t)|/(aL) over the instants
  double contact_multiplier = 0;    ///< max |Δλ(t)|/a over the instants
  double largest() const;           ///< the largest of the five
};

/// Compares the two solutions on [0, L] × [0, T], T = 3L × `periods`, at (1) the lattice
/// x_i = iL/40, t_n = nL/40, whose points lie on characteristics x ± t = jL/40, the kinks x ± t = kL
/// among them (the derivatives there are the means of their one-sided values in both); (2) 41 × 429
/// points off the characteristics; (3) 3000 instants per period at the contact point (u(0, t), λ),
/// the impacts and releases t = kL among them. At the corners x ∈ {0, L}, t = kL, u_x and u_t have no
/// limit and the two conventions differ: only u is compared there. Throws std::invalid_argument unless
/// L > 0 and a > 0 are finite and periods ∈ [1, 1000].
ClosedFormDifference closed_form_difference(double length, double amplitude, double periods = 10);

/// The size that round-off alone explains for every entry of closed_form_difference, derived in
/// characteristics.cpp: ε (W(W + 1)/2 + 8 (W + 1)), with ε the machine epsilon and W = 3 × periods the
/// number of windows of length L the solution is built in (the quadratic term: the drift of the event
/// times when the multiples of L are not doubles; the linear one: the evaluations).
double closed_form_round_off_bound(double periods);

}  // namespace mrm
