/// @file exact_solution.hpp
/// @brief The closed-form solution of the benchmark (mathematics.md §2).
#pragma once

#include "exact/reference_solution.hpp"

namespace mrm {

/// The bar (0, L) released at rest from u⁰(x) = a (L − x) against the obstacle at x = 0, f = 0.
/// Periodic in time with period 3L: free flight, contact, free flight back (mathematics.md §2).
///
/// Derivatives are piecewise constant and jump across characteristics; where a derivative jumps,
/// the functions here return the mean of the one-sided limits (the symmetric derivative), so that
/// a point that sits exactly on a characteristic (as grid points do when Δt = h) gets a definite,
/// convention-free value. The same holds for λ at the instants of impact and release.
class ExactSolution : public ReferenceSolution {
 public:
  /// Throws std::invalid_argument unless L > 0 and a are finite (a = 1/2, L = 1 is the paper's case).
  explicit ExactSolution(double length = 1.0, double amplitude = 0.5);

  double displacement(double x, double t) const override;  ///< u(x, t)
  double strain(double x, double t) const override;        ///< u_x(x, t)
  double velocity(double x, double t) const override;      ///< u_t(x, t)
  double contact_displacement(double t) const override;    ///< u(0, t)
  double contact_multiplier(double t) const override;      ///< λ(t) = u_x(0, t) ≤ 0
  double energy() const override;                          ///< E = ½∫(u_t² + u_x²) dx = a² L / 2

  /// u(x_k, t), k < count, at points sorted in increasing order (a mesh's nodes), with the values of
  /// displacement(x_k, t) at the cost of a few operations per point: the phase is located once, and
  /// between the kinks of u(·, t) the value is one affine function.
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  /// u_t(x_k, t) likewise, with the values of velocity(x_k, t), the symmetric derivative at a kink.
  void velocity_at_points(double t, const double* x, long count, double* v) const override;
  /// A run of consecutive points on which a field of the exact solution is one affine function:
  /// value(x_i) = intercept + slope · x_i for first ≤ i < end.
  struct AffineRun {
    long first;        ///< the first point of the run
    long end;          ///< one past the last point
    double intercept;  ///< the value at x = 0 of the run's affine function
    double slope;      ///< its slope in x
  };
  /// u(·, t) on the sorted points as runs between the kinks (a point within 1e-9 L of a kink gets a run
  /// of its own with the value of displacement()); returns the number of runs written (at most
  /// `capacity`; 32 always suffice). Throws std::length_error if `capacity` is too small.
  int displacement_runs(double t, const double* x, long count, AffineRun* runs, int capacity) const;
  /// u_t(·, t) likewise (constant on each run: slope 0; the symmetric derivative at a kink).
  int velocity_runs(double t, const double* x, long count, AffineRun* runs, int capacity) const;
  double period() const { return 3.0 * length_; }     ///< the period 3L of the motion
  double length() const override { return length_; }  ///< L
  double amplitude() const { return amplitude_; }     ///< a

 private:
  double length_, amplitude_;
};

}  // namespace mrm
