/// @file errors.hpp
/// @brief The error measures of mathematics.md §5, accumulated while a scheme runs.
#pragma once

#include <array>
#include <cstddef>
#include <memory>

#include "exact/exact_solution.hpp"
#include "exact/reference_solution.hpp"
#include "fem/p1.hpp"
#include "core/problem.hpp"

namespace mrm {

/// A quantity sampled in time: its maximum and its integral by the trapezoidal rule over the
/// instants at which it was sampled; `error` and `exact` are squared norms at one instant.
struct TimeHistory {
  bool started = false;       ///< whether a sample has been added
  double time = 0;            ///< the instant of the last sample
  double error = 0;           ///< the last squared error norm
  double exact = 0;           ///< the last squared exact norm
  double error_max = 0;       ///< the largest squared error norm so far
  double exact_max = 0;       ///< the largest squared exact norm so far
  double error_integral = 0;  ///< the trapezoidal integral of the squared error norm so far
  double exact_integral = 0;  ///< the trapezoidal integral of the squared exact norm so far
  /// Adds the sample at instant t (≥ the previous one) of the squared norms of the error and the exact solution.
  void add(double t, double error_squared, double exact_squared);
};

/// Relative errors ‖error‖ / ‖exact‖ in the norms of mathematics.md §5.
struct ErrorNorms {
  double u0_L2;      ///< L²(0,T) of the contact-point displacement u(0, ·)
  double lambda_L2;  ///< L²(0,T) of the contact stress λ
  double u_LinfL2;   ///< L∞(0,T; L²) of u
  double u_LinfH1;   ///< L∞(0,T; H¹) of u (the H¹ seminorm: ‖u_x‖_L², a norm on the clamped space)
  double v_LinfL2;   ///< L∞(0,T; L²) of u_t
  double u_L2L2;     ///< L²(0,T; L²) of u
  double u_L2H1;     ///< L²(0,T; H¹) of u
  double v_L2L2;     ///< L²(0,T; L²) of u_t
};

/// The eight relative measures of ErrorNorms from the histories of the squared norms of the error and
/// of the exact (or reference) solution: L²(0,T) of u(0,·) and λ, L∞ and L² in time of the L² and H¹
/// norms of u and of the L² norm of u_t.
ErrorNorms relative_norms(const TimeHistory& u0, const TimeHistory& lambda, const TimeHistory& u_l2,
                          const TimeHistory& u_h1, const TimeHistory& v_l2);

/// A sample's vectors where a batch of runs keeps them (lib/batched/batched_step.hpp's lane layout): entry i of
/// the run's displacement at displacement[i·stride], of its velocity at velocity[i·stride].
struct LaneVectors {
  const double* displacement;  ///< Uⁿ, entry i at displacement[i·stride]
  const double* velocity;      ///< the sample's velocity, entry i at velocity[i·stride]
  std::size_t stride;          ///< the distance between two entries (the batch's lanes; 1: a vector of its own)
  std::size_t lane = 0;        ///< the run's lane: node i of lane 0 is at displacement[i·stride − lane]
};

/// A sample's own vectors seen as lanes of stride 1 (a run stepped alone, or copied out of its batch).
inline LaneVectors own_lanes(const Sample& sample) { return {sample.displacement->data(), sample.velocity->data(), 1}; }

/// Accumulates the errors of a run against an exact solution, one sample at a time, in O(N) memory.
/// The reference is the closed form of the benchmark (mathematics.md §2) or any other ReferenceSolution,
/// such as the characteristic solution for any data (mathematics.md §10). The squared norms are taken
/// as they are: the runs are those of the dimensionless problem (L = 1, data of order one), to which
/// the harness maps every run (repro/configurations/scaling.cpp); the relative measures do not change under
/// that scaling.
class ErrorAccumulator {
 public:
  /// Against the closed form (copied). Throws std::invalid_argument unless the exact solution and the
  /// mesh have the same length L. `add` expects samples of a simulation on the same mesh (vectors of
  /// size mesh.unknowns()).
  ErrorAccumulator(const UniformMesh& mesh, const ExactSolution& exact);
  /// Against any reference solution (shared, read only: accumulators of runs in parallel may share
  /// one). Throws std::invalid_argument for a null reference or one of another length than the mesh's.
  ErrorAccumulator(const UniformMesh& mesh, std::shared_ptr<const ReferenceSolution> reference);
  /// Adds one time level of a run (its displacement, velocity and multiplier at their own instants).
  void add(const Sample& sample);
  /// The same, with the sample's displacement and velocity read from `lanes` instead of its vectors
  /// (which are not read: in a batch they may be older than the lanes); the same bits as add(sample)
  /// on a sample whose vectors hold those entries (the same sums in the same order).
  void add(const Sample& sample, const LaneVectors& lanes);
  /// One level of one run of a batch, for add_lanes: its accumulator, its sample and where its vectors are.
  struct Lane {
    ErrorAccumulator* errors;  ///< the run's accumulator
    const Sample* sample;      ///< the run's sample (its vectors are not read)
    LaneVectors lanes;         ///< where the run's displacement and velocity are
  };
  /// Adds one level of each of `count` runs, each as `errors->add(*sample, lanes)` would: the same bits.
  /// Runs that lie in the lanes of one batch (the same vectors, stride and mesh) and whose interpolants
  /// are the same affine runs of the closed form (the same instants) are summed together, in one pass
  /// over the nodes with their lanes side by side in vector registers (batched/lane_errors.cpp); so are runs against
  /// the same other reference object (ReferenceCache shares one: the characteristic solution) at the
  /// same instants on the same nodes, its values at the nodes and contact point evaluated once for all
  /// of them. Runs against such a reference that cannot be summed so (on their own vectors, on a mesh
  /// whose matrices are not Toeplitz) share its values at the nodes too, and each adds its level from
  /// them alone; any other run alone. The runs must be distinct (one lane each). Returns the number of
  /// runs summed together (in one pass).
  static std::size_t add_lanes(const Lane* level, std::size_t count);
  /// The relative errors of the samples added so far.
  ErrorNorms relative() const;
  /// The names of the measures in the order of `values(ErrorNorms)`: err_u0_L2, err_lambda_L2, …
  static const char* const names[8];
  /// The eight measures of `e` in the order of `names`.
  static std::array<double, 8> values(const ErrorNorms& e);

 private:
  // The sums of the quadratic forms of one level (errors.cpp): D, Q, the first and last entries, for
  // the error e = W − w_I and for the interpolant w_I.
  struct Sums {
    double e0, e_last, e_differences, e_squares, i0, i_last, i_differences, i_squares;
  };
  // The level from the vectors U and V seen with their stride; `evaluated`: a reference other than the
  // closed form has been evaluated at the sample's instants into interpolant_ and velocity_interpolant_.
  template <typename Stride>
  void add_vectors(const Sample& sample, const double* u, const double* v, Stride stride, bool evaluated = false);
  // The level from its sums (u_first: the displacement's first entry): the forms and the histories,
  // with the reference's u(0, t) and λ at the sample's instants (λ: 0 if the sample has no multiplier)
  // given, or evaluated.
  void add_sums(const Sample& sample, double u_first, const Sums& su, const Sums& sv, double u0, double lambda);
  void add_sums(const Sample& sample, double u_first, const Sums& su, const Sums& sv);
  UniformMesh mesh_;
  std::shared_ptr<const ReferenceSolution> exact_;
  const ExactSolution* closed_form_ = nullptr;                  // exact_ when it is the paper's closed form (its runs)
  Tridiagonal mass_, stiffness_;                                // the P1 mass and stiffness of the mesh
  Eigen::VectorXd nodes_, interpolant_, velocity_interpolant_;  // x_i; u_I and (u_t)_I at one level
  Eigen::VectorXd error_;                                       // e = W − w_I (a mesh that is not Toeplitz)
  bool general_ = false;  // the mesh's P1 matrices are not Toeplitz: the forms by Tridiagonal::bilinear
  TimeHistory u_l2_, u_h1_, v_l2_, u0_, lambda_;
};

}  // namespace mrm
