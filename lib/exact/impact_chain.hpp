/// @file impact_chain.hpp
/// @brief The exact solution of a chain of bar segments (doc/benchmarks.md §2–§7): piecewise-constant E
/// and ρ, a piecewise-polynomial load f(x), a clamped or free far end, initial gaps, and unilateral
/// contact with a rigid obstacle or between two bars — by characteristics in time and the Skorokhod
/// reflection at every contact (derivation in impact_chain.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include "exact/characteristics.hpp"
#include "exact/piecewise_polynomial.hpp"
#include "fem/p1.hpp"

namespace mrm {

/// One homogeneous segment of the chain, in any consistent units.
struct BarSegment {
  double length = 1;        ///< ℓ > 0
  double modulus = 1;       ///< E > 0 (for a uniaxial-strain bar, the oedometric modulus)
  double density = 1;       ///< ρ > 0
  poly::Coefficients load;  ///< f (force per unit volume) in σ = (x − centre)/(ℓ/2) of the segment; empty: 0
};

/// A segment of constant modulus, density and load (f = `load`; 0: none).
BarSegment uniform_segment(double length, double modulus, double density, double load = 0.0);

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

/// Whether a chain is two bodies in contact with each other (two segments, one contact junction, no
/// rigid obstacle): the configurations TwoBodySimulation (lib/time/two_bodies.hpp) runs.
bool is_two_body_chain(const ImpactConfiguration& configuration);

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

/// The exact contact windows [t_start, t_end] of contact k (0: the obstacle) over [0, T].
std::vector<ContactInterval> exact_contact_windows(const ImpactConfiguration& configuration, const InitialData& data,
                                                   double final_time, std::size_t contact = 0);

}  // namespace mrm
