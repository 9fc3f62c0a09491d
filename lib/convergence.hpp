/// @file convergence.hpp
/// @brief Observed orders of convergence (least-squares fit of log error against log step, with GSL)
/// and the comparison of a run with a reference run of the same mesh at their common time levels
/// (mathematics.md §5).
#pragma once

#include <array>
#include <vector>

#include "errors.hpp"
#include "p1.hpp"
#include "schemes.hpp"

namespace mrm {

/// The straight line log e = log C + p log s fitted by least squares to points (s_k, e_k).
struct OrderFit {
  double order;            ///< p, the observed order
  double log_constant;     ///< log C
  double order_std_error;  ///< the standard error of p from the residuals (0 for two points)
  std::size_t points;      ///< the number of points fitted
};

/// Fits e ≈ C s^p by least squares on (log s, log e) with GSL's gsl_fit_linear. Throws
/// std::invalid_argument for fewer than two points, sizes that differ, a non-positive or non-finite
/// value, or steps that are all equal; std::runtime_error if GSL reports an error.
OrderFit fit_order(const std::vector<double>& steps, const std::vector<double>& errors);

/// Relative differences ‖U − U_ref‖ / ‖U_ref‖ between a run and a reference run on the same mesh, in
/// the norms of mathematics.md §5 (the eight measures of ErrorNorms, in the same order and with the same
/// names), taken at the instants the two runs share. The reference plays the part of the exact
/// solution: this measures the error of the time discretisation alone.
class ReferenceComparison {
 public:
  /// Compares runs on `mesh` (both the run and the reference use it).
  explicit ReferenceComparison(const UniformMesh& mesh);
  /// Adds one common instant. Throws std::invalid_argument unless both samples are at the same
  /// instant (displacement, velocity and multiplier times agree to 1e-9 Δt-independent absolute
  /// tolerance), which holds for the two-level schemes (Crank–Nicolson, backward Euler).
  void add(const Sample& run, const Sample& reference);
  /// The eight relative differences, in the order of ErrorAccumulator::names.
  std::array<double, 8> relative() const;

 private:
  Tridiagonal mass_, stiffness_;
  Eigen::VectorXd difference_;
  TimeHistory u_l2_, u_h1_, v_l2_, u0_, lambda_;
};

}  // namespace mrm
