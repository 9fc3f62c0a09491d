/// @file problem.hpp
/// @brief The ground floor of the library: the continuous problem (mathematics.md §1), what a scheme
/// knows at one time level, and the error every constructor throws for a bad input. It includes nothing
/// of the library, so that every other part (the meshes and masses, the exact solutions, the schemes and
/// the measures) can name the problem without seeing the time schemes.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace mrm {

/// The index type of vectors, matrices and meshes (Eigen's signed index).
using Index = Eigen::Index;

/// A bad value or combination of a simulation's inputs: `parameter` names it ("dt", "beta",
/// "restitution", "contact_row", "switch_theta", "scheme", "mass" or "problem"), and what() is
/// "parameter: what is wrong (allowed: …)". The programs turn it into their usage error (exit 2,
/// naming the option that sets the parameter).
class InvalidParameter : public std::invalid_argument {
 public:
  /// what() is "parameter: message".
  InvalidParameter(const std::string& parameter, const std::string& message);
  std::string parameter;  ///< the parameter at fault
};

/// The continuous problem (mathematics.md §1): bar (0, L), data u⁰, v⁰, load f (may be empty: f = 0).
struct Problem {
  double length = 1.0;                                   ///< L
  std::function<double(double x)> initial_displacement;  ///< u⁰(x)
  std::function<double(double x)> initial_velocity;      ///< v⁰(x)
  std::function<double(double x, double t)> load;        ///< f(x, t); empty for f = 0
  /// Whether f does not depend on t: f(x, t) = f(x, 0). BarSimulation then forms the load vector F and
  /// its contact entry F₀ once, at t = 0, and reads them at every level, where a load that depends on t
  /// is formed again by quadrature at every step: the same bits, since the quadrature sees the same
  /// values. The constructor checks F(Δt) = F(0) bit for bit and refuses the problem otherwise.
  bool steady_load = false;
  /// The initial gap between the contact end and the obstacle: the constraint is u(0, t) + gap ≥ 0
  /// (finite, ≥ 0; 0 is the paper's u(0, t) ≥ 0). Not with EC (refused).
  double gap = 0.0;
};
/// The benchmark of mathematics.md §2: u⁰(x) = a (L − x), v⁰ = 0, f = 0.
Problem benchmark_problem(double length = 1.0, double amplitude = 0.5);

/// What a scheme knows at one time level, each quantity with the instant it approximates.
struct Sample {
  Index level;                          ///< n
  double time;                          ///< t_n, the instant of `displacement`
  const Eigen::VectorXd* displacement;  ///< Uⁿ on nodes 0..N−1
  double velocity_time;                 ///< t_n (two-level schemes, n ≤ 1) or t_{n−½} (Paoli–Schatzman)
  const Eigen::VectorXd* velocity;      ///< Vⁿ, or (Uⁿ − Uⁿ⁻¹)/Δt for Paoli–Schatzman (n ≥ 2)
  bool has_multiplier;                  ///< false where the level has no multiplier yet
  double multiplier_time;               ///< the instant of `multiplier`
  double multiplier;                    ///< λ ≤ 0
  double energy_time;                   ///< the instant of `energy`
  double energy;                        ///< the scheme's discrete energy
};

}  // namespace mrm
