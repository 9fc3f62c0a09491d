// The error measures: problem.md §5.
//
// The discrete solution is compared with the nodal interpolant u_I of the exact solution on the same
// mesh, in the consistent P1 norms of the full mesh (node N carries zero on both sides):
//
//     ‖e‖²_L² = eᵀ M e,    |e|²_H¹ = eᵀ S e,
//
// and in time on the scheme's own instants (each quantity at the instant it approximates, see
// Sample): L∞(0,T; X) is the maximum over the instants, L²(0,T; X) the trapezoidal rule over them.
// Every error is relative, ‖error‖ / ‖exact‖ in the same norm, the exact solution also being taken
// through its interpolant and the same instants. Derivatives of the exact solution that jump are
// given their symmetric value (exact_solution.hpp).
#include "errors.hpp"

#include <cmath>

#include <doctest/doctest.h>

namespace mrm {

const char* const ErrorAccumulator::names[8] = {"err_u0_L2",    "err_lambda_L2", "err_u_LinfL2", "err_u_LinfH1",
                                                "err_v_LinfL2", "err_u_L2L2",    "err_u_L2H1",   "err_v_L2L2"};

std::array<double, 8> ErrorAccumulator::values(const ErrorNorms& e) {
  return {e.u0_L2, e.lambda_L2, e.u_LinfL2, e.u_LinfH1, e.v_LinfL2, e.u_L2L2, e.u_L2H1, e.v_L2L2};
}

void ErrorAccumulator::History::add(double t, double error_squared, double exact_squared) {
  if (started) {
    const double dt = t - time;
    error_integral += 0.5 * dt * (error + error_squared);
    exact_integral += 0.5 * dt * (exact + exact_squared);
  }
  started = true;
  time = t;
  error = error_squared;
  exact = exact_squared;
  error_max = std::max(error_max, error_squared);
  exact_max = std::max(exact_max, exact_squared);
}

ErrorAccumulator::ErrorAccumulator(const UniformMesh& mesh, const ExactSolution& exact)
    : mesh_(mesh), exact_(exact), mass_(p1_mass(mesh)), stiffness_(p1_stiffness(mesh)),
      interpolant_(mesh.unknowns()), difference_(mesh.unknowns()) {}

void ErrorAccumulator::add(const Sample& sample) {
  const Index n = mesh_.unknowns();
  for (Index i = 0; i < n; ++i) interpolant_[i] = exact_.displacement(mesh_.x(i), sample.time);
  difference_ = *sample.displacement - interpolant_;
  u_l2_.add(sample.time, mass_.bilinear(difference_, difference_), mass_.bilinear(interpolant_, interpolant_));
  u_h1_.add(sample.time, stiffness_.bilinear(difference_, difference_),
            stiffness_.bilinear(interpolant_, interpolant_));
  const double u0 = exact_.contact_displacement(sample.time);
  u0_.add(sample.time, std::pow((*sample.displacement)[0] - u0, 2), u0 * u0);

  for (Index i = 0; i < n; ++i) interpolant_[i] = exact_.velocity(mesh_.x(i), sample.velocity_time);
  difference_ = *sample.velocity - interpolant_;
  v_l2_.add(sample.velocity_time, mass_.bilinear(difference_, difference_), mass_.bilinear(interpolant_, interpolant_));

  if (sample.has_multiplier) {
    const double lambda = exact_.contact_multiplier(sample.multiplier_time);
    lambda_.add(sample.multiplier_time, std::pow(sample.multiplier - lambda, 2), lambda * lambda);
  }
}

namespace {
double ratio(double error, double exact) { return exact > 0 ? std::sqrt(error / exact) : std::sqrt(error); }
}  // namespace

ErrorNorms ErrorAccumulator::relative() const {
  return {ratio(u0_.error_integral, u0_.exact_integral),
          ratio(lambda_.error_integral, lambda_.exact_integral),
          ratio(u_l2_.error_max, u_l2_.exact_max),
          ratio(u_h1_.error_max, u_h1_.exact_max),
          ratio(v_l2_.error_max, v_l2_.exact_max),
          ratio(u_l2_.error_integral, u_l2_.exact_integral),
          ratio(u_h1_.error_integral, u_h1_.exact_integral),
          ratio(v_l2_.error_integral, v_l2_.exact_integral)};
}

}  // namespace mrm
