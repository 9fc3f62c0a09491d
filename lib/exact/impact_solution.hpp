/// @file impact_solution.hpp
/// @brief The exact solution of the field's 1D impact benchmarks (doc/benchmarks.md): a chain of bar segments
/// with piecewise-constant E and ρ, a piecewise-polynomial load f(x), a clamped or free far end, an
/// initial gap, and unilateral contact with a rigid obstacle or between two bars — by characteristics
/// in time and the Skorokhod reflection at every contact (derivation in impact_solution.cpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "exact/characteristics.hpp"
#include "fem/p1.hpp"
#include "exact/piecewise_polynomial.hpp"
#include "exact/reference_solution.hpp"

namespace mrm {

/// One homogeneous segment of the chain, in any consistent units.
struct BarSegment {
  double length = 1;        ///< ℓ > 0
  double modulus = 1;       ///< E > 0 (for a uniaxial-strain bar, the oedometric modulus)
  double density = 1;       ///< ρ > 0
  poly::Coefficients load;  ///< f (force per unit volume) in σ = (x − centre)/(ℓ/2) of the segment; empty: 0
};

/// Where two consecutive segments meet.
struct SegmentJunction {
  bool contact = false;  ///< false: welded (u and the stress continuous); true: unilateral contact
  double gap = 0;        ///< for a contact: the initial distance g₀ ≥ 0 (z = u_right − u_left + g₀ ≥ 0)
};

/// The far (right) end of the chain: mrm::FarEnd of p1.hpp (clamped or free), shared with the mesh.

/// A chain of segments on [0, Σℓ] (x = 0 is the left end): its left end is held off a rigid obstacle at
/// distance `obstacle_gap` (u(0, t) + g₀ ≥ 0) when `obstacle`, otherwise free; consecutive segments are
/// welded or in unilateral contact; the right end is clamped or free. The segments between two contacts
/// form one body.
struct ImpactConfiguration {
  std::vector<BarSegment> segments;        ///< from left to right
  std::vector<SegmentJunction> junctions;  ///< segments.size() − 1 of them (empty: all welded)
  bool obstacle = true;                    ///< a rigid obstacle at the left end
  double obstacle_gap = 0;                 ///< its initial distance g₀ ≥ 0
  FarEnd far_end = FarEnd::clamped;        ///< the right end's condition

  double length() const;  ///< Σℓ
  /// Throws InvalidParameter ("configuration") for what the solver cannot treat exactly or at all.
  void validate() const;
};

/// The exact solution on [0, Σℓ] × [0, T] for initial data given as pieces (u⁰, v⁰ polynomials in each
/// piece's σ) whose breakpoints include every junction. Exact to round-off: every wave is a piecewise
/// polynomial in time, and the number of wave fronts is finite over [0, T] (it is counted: more than
/// `max_pieces` is refused).
class ImpactSolution {
 public:
  /// Throws InvalidParameter for a bad configuration, data (not contiguous, u⁰ discontinuous inside a
  /// body, u⁰ ≠ 0 at a clamp, a contact initially violated), T, or too many wave fronts.
  ImpactSolution(ImpactConfiguration configuration, const InitialData& data, double final_time,
                 std::size_t max_pieces = 2000000);

  double horizon() const { return horizon_; }                           ///< T
  const ImpactConfiguration& configuration() const { return config_; }  ///< the chain
  double displacement(double x, double t) const;                        ///< u(x, t) (the left segment's at a junction)
  double velocity(double x, double t) const;                            ///< u_t(x, t)
  /// u(x_k, t) and u_t(x_k, t) at `count` points (u or v may be null): the numbers of displacement and
  /// velocity, point by point, with the search of each wave's piece started from the previous point's
  /// (the same piece, found in a step or two for sorted points instead of a bisection).
  void at_points(double t, const double* x, long count, double* u, double* v) const;
  double stress(double x, double t) const;  ///< E u_x(x, t)

  /// The contacts: index 0 is the obstacle (if any), then the contact junctions from left to right.
  std::size_t contact_count() const { return contacts_.size(); }
  /// The gap z(t) ≥ 0 of contact k (for the obstacle, u(0, t) + g₀).
  double gap(std::size_t k, double t) const;
  /// The contact stress λ(t) ≤ 0 of contact k: E u_x on the right side of the contact point.
  double contact_stress(std::size_t k, double t) const;
  /// The intervals of [0, T] during which contact k is closed, in increasing order.
  const std::vector<ContactInterval>& contact_windows(std::size_t k) const;
  /// The number of polynomial pieces of all the waves (a measure of the wave fronts).
  std::size_t piece_count() const;

 private:
  void process(std::size_t node, double t0, double t1);
  std::size_t segment_of(double x) const;

  ImpactConfiguration config_;
  double horizon_, snap_, tie_;
  std::vector<double> origin_;                           // x_j, the left end of segment j
  std::vector<double> travel_;                           // τ_j = ℓ_j / c_j
  std::vector<double> impedance_;                        // Z_j = ρ_j c_j
  std::vector<double> acceleration_;                     // α of the body of segment j
  std::vector<PolynomialPiece> static_, static_stress_;  // q and E q′ on segment j (in x)
  std::vector<PiecewisePolynomial> right_, left_;        // F_j on [−τ_j, T], G_j on [0, T + τ_j]
  struct ContactState {
    std::size_t node;  // the junction node (0 = the left end)
    double gap;        // z at the end of the last window
    bool held;
    std::vector<ContactInterval> windows;
  };
  std::vector<ContactState> contacts_;
  std::vector<double> last_right_, last_left_;  // the last emitted value into G_{j−1} / F_j at node j
};

/// The exact solution of a chain with a rigid obstacle as the reference of the error measures
/// (errors.hpp): u, u_t, u_x = σ/E, the contact point's u(0, t) and λ(t) = σ(0, t) (the stress on the
/// obstacle, the multiplier of the finite element runs, whose contact row is S₀·U = F₀ − λ with the
/// stiffness E/h), and the energy. With a load the energy ½∫(ρu_t² + E u_x²) is not constant; energy()
/// is the conserved one, ½∫(ρu_t² + E u_x²) − ∫ f u (the contact does no work: u(0, ·) is constant
/// while λ ≠ 0), taken at t = 0. Throws InvalidParameter ("configuration") for a chain without an
/// obstacle (two-bars: its contact is between two bars).
class ImpactReference : public ReferenceSolution {
 public:
  /// The solution of ImpactSolution(configuration, data, final_time).
  ImpactReference(const ImpactConfiguration& configuration, const InitialData& data, double final_time);
  double length() const override { return solution_.configuration().length(); }
  double displacement(double x, double t) const override { return solution_.displacement(x, t); }
  double strain(double x, double t) const override;
  double velocity(double x, double t) const override { return solution_.velocity(x, t); }
  /// u(0, t): −g₀ exactly inside a contact window (the Skorokhod reflection holds z = 0 there), the
  /// waves' value outside.
  double contact_displacement(double t) const override;
  double contact_multiplier(double t) const override { return solution_.contact_stress(0, t); }
  double energy() const override { return energy_; }
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  void velocity_at_points(double t, const double* x, long count, double* v) const override;
  /// The contact windows with the obstacle over [0, T].
  const std::vector<ContactInterval>& contact_windows() const { return solution_.contact_windows(0); }
  const ImpactSolution& solution() const { return solution_; }  ///< the chain's solution

 private:
  ImpactSolution solution_;
  double energy_ = 0;
};

/// What a configuration needs beyond the paper's problem (f = 0, clamped far end, no gap, one
/// homogeneous bar), in words: "a load f", "a free far end", "an initial gap", "segments of different
/// E or rho", "two bodies in contact", joined by ", "; empty for the paper's problem.
std::string configuration_features(const ImpactConfiguration& configuration);

/// A named benchmark of the field (doc/benchmarks.md): its chain, its initial data and its default horizon
/// (the first two periods or the first three contacts), in its own units.
struct ImpactBenchmark {
  std::string id;                     ///< the name on the command line
  std::string summary;                ///< one line: what it is
  std::string source;                 ///< where its data come from
  std::string time_unit;              ///< "s" for SI data, empty for dimensionless ones
  ImpactConfiguration configuration;  ///< the chain
  InitialData data;                   ///< u⁰, v⁰ (breakpoints at every junction)
  double final_time;                  ///< the default horizon T
};
/// bouncing, impacting, gravity-paper, two-bars, layered (data in impact_solution.cpp, derived there).
const std::vector<ImpactBenchmark>& impact_benchmarks();
/// The benchmark named `id`; throws InvalidParameter("benchmark", … the allowed names) otherwise.
const ImpactBenchmark& impact_benchmark(const std::string& id);

/// The exact contact windows [t_start, t_end] of contact k (0: the obstacle) over [0, T].
std::vector<ContactInterval> exact_contact_windows(const ImpactConfiguration& configuration, const InitialData& data,
                                                   double final_time, std::size_t contact = 0);

}  // namespace mrm
