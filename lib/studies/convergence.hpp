/// @file convergence.hpp
/// @brief Observed orders of convergence (least-squares fit of log error against log step, with GSL)
/// and the comparison of a run with a reference run of the same mesh at their common time levels
/// (mathematics.md §5).
#pragma once

#include <array>
#include <vector>

#include "measures/errors.hpp"
#include "fem/p1.hpp"
#include "core/problem.hpp"

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
  /// One common instant measured: its instants and, per history, the squared norm of the difference
  /// and of the reference (first and second of each pair).
  struct Level {
    double time = 0;                 ///< the displacement's instant
    double velocity_time = 0;        ///< the velocity's instant
    double multiplier_time = 0;      ///< the multiplier's instant
    bool has_multiplier = false;     ///< whether both runs have a multiplier at this level
    std::array<double, 2> u_l2{};    ///< ‖U − U_ref‖², ‖U_ref‖² in L² (the P1 mass)
    std::array<double, 2> u_h1{};    ///< |U − U_ref|², |U_ref|² in H¹ (the P1 stiffness)
    std::array<double, 2> u0{};      ///< (U₀ − U_ref,₀)², U_ref,₀²
    std::array<double, 2> v_l2{};    ///< ‖V − V_ref‖², ‖V_ref‖² in L²
    std::array<double, 2> lambda{};  ///< (λ − λ_ref)², λ_ref² (if has_multiplier)
  };
  /// Measures one common instant without adding it (so that one measurement can go to several
  /// comparisons of the same mesh: repro/time_family.cpp's all-levels and matched-levels ones). Throws
  /// std::invalid_argument unless both samples are at the same instant (displacement, velocity and
  /// multiplier times agree to 1e-9 Δt-independent absolute tolerance), which holds for the two-level
  /// schemes (Crank–Nicolson, backward Euler).
  Level measure(const Sample& run, const Sample& reference);
  /// The same measurement, the two runs' displacement and velocity read where `run_lanes` and
  /// `reference_lanes` say (BatchedSimulation::sample: in a batch's vector lanes, nothing copied out; the
  /// samples give the instants, λ and the sizes): the same bits as measure(run, reference) on the same values.
  Level measure(const Sample& run, const LaneVectors& run_lanes, const Sample& reference,
                const LaneVectors& reference_lanes);
  /// Adds a measured instant.
  void add(const Level& level);
  /// Adds one common instant: add(measure(run, reference)).
  void add(const Sample& run, const Sample& reference) { add(measure(run, reference)); }
  /// The eight relative differences, in the order of ErrorAccumulator::names.
  std::array<double, 8> relative() const;

 private:
  Tridiagonal mass_, stiffness_;
  Eigen::VectorXd difference_;  // work vector (no allocation per instant)
  TimeHistory u_l2_, u_h1_, v_l2_, u0_, lambda_;
};

}  // namespace mrm
