/// @file reference_solution.hpp
/// @brief What the error measures need from an exact solution of the Signorini wave problem
/// (mathematics.md §5): values and derivatives anywhere, the contact point, the energy.
#pragma once

namespace mrm {

/// An exact solution of u_tt = u_xx on (0, L) with u(L, ·) = 0 and the Signorini condition at x = 0
/// (mathematics.md §1), used as the reference of the error measures (mathematics.md §5).
///
/// Derivatives jump across characteristics for kinked data; where one does, an implementation returns
/// the mean of its one-sided limits, so that points exactly on a characteristic (grid points with
/// Δt = h or h/2) get a definite value.
class ReferenceSolution {
 public:
  virtual ~ReferenceSolution() = default;
  virtual double length() const = 0;                          ///< L
  virtual double displacement(double x, double t) const = 0;  ///< u(x, t)
  virtual double strain(double x, double t) const = 0;        ///< u_x(x, t)
  virtual double velocity(double x, double t) const = 0;      ///< u_t(x, t)
  virtual double contact_displacement(double t) const = 0;    ///< u(0, t) ≥ 0
  virtual double contact_multiplier(double t) const = 0;      ///< λ(t) = u_x(0, t) ≤ 0
  virtual double energy() const = 0;                          ///< E = ½∫(u_t² + u_x²) dx, constant
  /// u(x_k, t) for the points x_0 ≤ … ≤ x_{count−1} (a mesh's nodes): the values of displacement().
  virtual void displacement_at_points(double t, const double* x, long count, double* u) const = 0;
  /// u_t(x_k, t) likewise: the values of velocity().
  virtual void velocity_at_points(double t, const double* x, long count, double* v) const = 0;
};

}  // namespace mrm
