/// @file errors.cpp
/// @brief The error measures: mathematics.md §5.
///
/// The discrete solution is compared with the nodal interpolant u_I of the exact solution on the same
/// mesh, in the consistent P1 norms of the full mesh (node N carries zero on both sides):
///
///     ‖e‖²_L² = eᵀ M e,    |e|²_H¹ = eᵀ S e,
///
/// and in time on the scheme's own instants (each quantity at the instant it approximates, see
/// Sample): L∞(0,T; X) is the maximum over the instants, L²(0,T; X) the trapezoidal rule over them.
/// Every error is relative, ‖error‖ / ‖exact‖ in the same norm, the exact solution also being taken
/// through its interpolant and the same instants. Derivatives of the exact solution that jump are
/// given their symmetric value (exact_solution.hpp).
#include "errors.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

namespace mrm {

const char* const ErrorAccumulator::names[8] = {"err_u0_L2",    "err_lambda_L2", "err_u_LinfL2", "err_u_LinfH1",
                                                "err_v_LinfL2", "err_u_L2L2",    "err_u_L2H1",   "err_v_L2L2"};

std::array<double, 8> ErrorAccumulator::values(const ErrorNorms& e) {
  return {e.u0_L2, e.lambda_L2, e.u_LinfL2, e.u_LinfH1, e.v_LinfL2, e.u_L2L2, e.u_L2H1, e.v_L2L2};
}

void TimeHistory::add(double t, double error_squared, double exact_squared) {
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

// One level costs one pass over the nodes. The interpolants come from the exact solution's evaluation
// at many points (exact_solution.cpp: the phase located once, one affine function per node); the six
// quadratic forms eᵀMe and eᵀSe of the errors and of the interpolants are accumulated together. M and
// S are the P1 matrices of a uniform mesh: row 0 has its own diagonal entry a₀₀, and every other row
// the same entries (d, l) = (A_ii, A_{i,i−1}) (checked when the accumulator is built). Expanding
// −l (z_i − z_{i−1})² and telescoping, with D = Σ_{i≥1} (z_i − z_{i−1})² and Q = Σ_{i≥1} z_i²,
//
//     zᵀAz = a₀₀ z₀² + Σ_{i=1}^{n−1} (d z_i² + 2l z_{i−1} z_i) = a₀₀ z₀² − l D + (d + 2l) Q − l z_{n−1}² + l z₀².
//
// For S, d + 2l = 0 and −l = 1/h: |z|²_H¹ = (D + z_{n−1}²)/h, a sum of squares with no cancellation
// (the same form written as Σ z_i² against Σ z_{i−1} z_i loses O(N²) in relative accuracy).
ErrorAccumulator::ErrorAccumulator(const UniformMesh& mesh, const ExactSolution& exact)
    : mesh_(mesh), exact_(exact), mass_(p1_mass(mesh)), stiffness_(p1_stiffness(mesh)), nodes_(mesh.unknowns()),
      interpolant_(mesh.unknowns()), velocity_interpolant_(mesh.unknowns()) {
  const Index n = mesh.unknowns();
  for (Index i = 0; i < n; ++i) nodes_[i] = mesh.x(i);
  for (const Tridiagonal* a : {&mass_, &stiffness_})
    for (Index i = 2; i < n; ++i)
      if (a->diag[i] != a->diag[1] || a->lower[i] != a->lower[1])
        throw std::logic_error("error measures: the P1 matrices of a uniform mesh are expected to be Toeplitz");
  if (exact.length() != mesh.length)
    throw std::invalid_argument("error measures: the exact solution's bar has L = " + std::to_string(exact.length()) +
                                ", the mesh's L = " + std::to_string(mesh.length) + " (allowed: the same L)");
}

namespace {

// zᵀAz from z₀, z_{n−1} and the sums D and Q (see above).
double form(double z0, double z_last, double differences, double squares, double a00, double d, double l) {
  return a00 * z0 * z0 - l * differences + (d + 2 * l) * squares - l * z_last * z_last + l * z0 * z0;
}

}  // namespace

void ErrorAccumulator::add(const Sample& sample) {
  const Index n = mesh_.unknowns();
  if (sample.displacement->size() != n || sample.velocity->size() != n)
    throw std::invalid_argument("error measures: the sample's vectors must have the mesh's N = " + std::to_string(n) +
                                " entries (allowed: samples of a run on the same mesh)");
  const double* x = nodes_.data();
  double* ui = interpolant_.data();
  double* vi = velocity_interpolant_.data();
  exact_.displacement_at_points(sample.time, x, static_cast<long>(n), ui);
  exact_.velocity_at_points(sample.velocity_time, x, static_cast<long>(n), vi);

  // D and Q for the vectors e = W − w_I and w_I, W = U or V: four independent sums, each a short chain
  // of additions (one loop per W keeps them all in registers).
  struct Sums {
    double e0, e_last, e_differences, e_squares, i0, i_last, i_differences, i_squares;
  };
  const auto sums = [n](const double* w, const double* wi) {
    Sums r{w[0] - wi[0], 0, 0, 0, wi[0], 0, 0, 0};
    double e_prev = r.e0, i_prev = r.i0;
    for (Index i = 1; i < n; ++i) {
      const double e = w[i] - wi[i], z = wi[i], de = e - e_prev, dz = z - i_prev;
      r.e_differences += de * de;
      r.e_squares += e * e;
      r.i_differences += dz * dz;
      r.i_squares += z * z;
      e_prev = e, i_prev = z;
    }
    r.e_last = e_prev, r.i_last = i_prev;
    return r;
  };
  const double* u = sample.displacement->data();
  const Sums su = sums(u, ui), sv = sums(sample.velocity->data(), vi);
  const auto error_form = [](const Sums& r, double a00, double d, double l) {
    return form(r.e0, r.e_last, r.e_differences, r.e_squares, a00, d, l);
  };
  const auto exact_form = [](const Sums& r, double a00, double d, double l) {
    return form(r.i0, r.i_last, r.i_differences, r.i_squares, a00, d, l);
  };
  const double m00 = mass_.diag[0], m = n > 1 ? mass_.diag[1] : 0, ml = n > 1 ? mass_.lower[1] : 0;
  const double s00 = stiffness_.diag[0], s = n > 1 ? stiffness_.diag[1] : 0, sl = n > 1 ? stiffness_.lower[1] : 0;
  u_l2_.add(sample.time, error_form(su, m00, m, ml), exact_form(su, m00, m, ml));
  u_h1_.add(sample.time, error_form(su, s00, s, sl), exact_form(su, s00, s, sl));
  const double u0 = exact_.contact_displacement(sample.time);
  u0_.add(sample.time, std::pow(u[0] - u0, 2), u0 * u0);
  v_l2_.add(sample.velocity_time, error_form(sv, m00, m, ml), exact_form(sv, m00, m, ml));

  if (sample.has_multiplier) {
    const double lambda = exact_.contact_multiplier(sample.multiplier_time);
    lambda_.add(sample.multiplier_time, std::pow(sample.multiplier - lambda, 2), lambda * lambda);
  }
}

// Each measure relative to the same norm of the exact solution (the absolute value where that norm
// vanishes, which never happens over a time interval that contains a contact).
namespace {
double ratio(double error, double exact) { return exact > 0 ? std::sqrt(error / exact) : std::sqrt(error); }
}  // namespace

ErrorNorms relative_norms(const TimeHistory& u0, const TimeHistory& lambda, const TimeHistory& u_l2,
                          const TimeHistory& u_h1, const TimeHistory& v_l2) {
  return {ratio(u0.error_integral, u0.exact_integral),
          ratio(lambda.error_integral, lambda.exact_integral),
          ratio(u_l2.error_max, u_l2.exact_max),
          ratio(u_h1.error_max, u_h1.exact_max),
          ratio(v_l2.error_max, v_l2.exact_max),
          ratio(u_l2.error_integral, u_l2.exact_integral),
          ratio(u_h1.error_integral, u_h1.exact_integral),
          ratio(v_l2.error_integral, v_l2.exact_integral)};
}

ErrorNorms ErrorAccumulator::relative() const { return relative_norms(u0_, lambda_, u_l2_, u_h1_, v_l2_); }

}  // namespace mrm

// ---------------------------------------------------------------------------------------------------

namespace mrm {
namespace {

[[maybe_unused]] ErrorNorms benchmark_errors(Scheme scheme, const MassRedistribution& mass, Index elements, double courant,
                            double final_time) {
  const UniformMesh mesh(1.0, elements);
  SchemeParameters p;
  p.scheme = scheme;
  p.contact_row = contact_node_is_massless(modified_mass(mesh, mass)) ? ContactRow::algebraic : ContactRow::literal;
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, p, dt);
  ErrorAccumulator errors(mesh, ExactSolution());
  run(simulation, steps_to_reach(final_time, dt), [&](const Sample& s) { errors.add(s); });
  return errors.relative();
}

}  // namespace

TEST_CASE("the error measures vanish for the exact interpolant and are relative") {
  const UniformMesh mesh(1.0, 16);
  const ExactSolution exact;
  ErrorAccumulator perfect(mesh, exact), doubled(mesh, exact);
  Eigen::VectorXd u(16), v(16), u2(16), v2(16);
  for (int n = 0; n <= 48; ++n) {
    const double t = n * 0.0625;
    for (Index i = 0; i < 16; ++i) {
      u[i] = exact.displacement(mesh.x(i), t);
      v[i] = exact.velocity(mesh.x(i), t);
    }
    u2 = 2 * u;
    v2 = 2 * v;
    const double lambda = exact.contact_multiplier(t);
    perfect.add({n, t, &u, t, &v, true, t, lambda, t, 0.125});
    doubled.add({n, t, &u2, t, &v2, true, t, 2 * lambda, t, 0.5});
  }
  for (double e : ErrorAccumulator::values(perfect.relative())) CHECK(e == 0.0);
  for (double e : ErrorAccumulator::values(doubled.relative())) CHECK(e == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("the one-pass error forms equal the matrix forms of the generic evaluation") {
  // One sample, so that each L∞ measure is the ratio of two forms at that level; the reference takes
  // the interpolants node by node from ExactSolution's generic functions and the forms from
  // Tridiagonal::bilinear. Random discrete fields, instants in each phase and on a phase change.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-0.6, 0.6);
  for (const Index elements : {2, 9, 64, 1000}) {
    const UniformMesh mesh(1.0, elements);
    const ExactSolution exact;
    const Tridiagonal m = p1_mass(mesh), s = p1_stiffness(mesh);
    for (const double t : {0.3, 1.45, 2.7, 3.0, 4.0 + 1.0 / static_cast<double>(elements)}) {
      Eigen::VectorXd u(elements), v(elements), ui(elements), vi(elements);
      const double tv = t - 0.25 / static_cast<double>(elements);  // a staggered velocity instant
      for (Index i = 0; i < elements; ++i) {
        ui[i] = exact.displacement(mesh.x(i), t);
        vi[i] = exact.velocity(mesh.x(i), tv);
        u[i] = ui[i] + 0.01 * uniform(random);
        v[i] = vi[i] + 0.01 * uniform(random);
      }
      ErrorAccumulator errors(mesh, exact);
      errors.add({0, t, &u, tv, &v, true, t, -0.5, t, 0.125});
      const ErrorNorms e = errors.relative();
      const Eigen::VectorXd du = u - ui, dv = v - vi;
      CAPTURE(elements);
      CAPTURE(t);
      CHECK(std::abs(e.u_LinfL2 - std::sqrt(m.bilinear(du, du) / m.bilinear(ui, ui))) < 1e-12 * e.u_LinfL2);
      CHECK(std::abs(e.u_LinfH1 - std::sqrt(s.bilinear(du, du) / s.bilinear(ui, ui))) < 1e-12 * e.u_LinfH1);
      CHECK(std::abs(e.v_LinfL2 - std::sqrt(m.bilinear(dv, dv) / m.bilinear(vi, vi))) < 1e-12 * e.v_LinfL2);
    }
  }
}

TEST_CASE("the error measures refuse an exact solution or a sample of another bar than the mesh's") {
  Eigen::VectorXd wrong = Eigen::VectorXd::Zero(5);
  ErrorAccumulator on_eight(UniformMesh(1.0, 8), ExactSolution());
  CHECK_THROWS_WITH_AS(on_eight.add({0, 0.0, &wrong, 0.0, &wrong, true, 0.0, 0.0, 0.0, 0.0}),
                       doctest::Contains("N = 8"), std::invalid_argument);
  CHECK_NOTHROW(ErrorAccumulator(UniformMesh(2.0, 8), ExactSolution(2.0, 0.5)));
  CHECK_THROWS_WITH_AS(ErrorAccumulator(UniformMesh(2.0, 8), ExactSolution(1.0, 0.5)),
                       doctest::Contains("(allowed: the same L)"), std::invalid_argument);
}

TEST_CASE("each scheme approaches the exact solution on a coarse mesh and improves under refinement") {
  // Two periods on N = 40 and N = 80 with Δt = h/2. The bounds are a factor 1.5 to 2 above the
  // values measured when this test was written (err_u_L2L2 at N = 40: 0.021 to 0.075 for CN and PS,
  // about 0.2 for BE; halving h divides it by 1.4 to 2); a wrong sign, a wrong coefficient or a lost contact force costs far more.
  struct Case {
    Scheme scheme;
    double bound_u, bound_u0, ratio;
  };
  for (const Case c : {Case{Scheme::crank_nicolson, 0.12, 0.12, 0.8}, Case{Scheme::paoli_schatzman, 0.12, 0.12, 0.8},
                       Case{Scheme::backward_euler, 0.35, 0.35, 0.85}}) {
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
      const ErrorNorms coarse = benchmark_errors(c.scheme, mass, 40, 0.5, 6.0);
      const ErrorNorms fine = benchmark_errors(c.scheme, mass, 80, 0.5, 6.0);
      CAPTURE(to_string(c.scheme));
      CAPTURE(mass.name);
      CAPTURE(coarse.u_L2L2);
      CAPTURE(fine.u_L2L2);
      CHECK(coarse.u_L2L2 < c.bound_u);
      CHECK(coarse.u0_L2 < c.bound_u0);
      CHECK(fine.u_L2L2 < c.ratio * coarse.u_L2L2);
      CHECK(fine.u0_L2 < c.ratio * coarse.u0_L2);
      CHECK(fine.lambda_L2 < coarse.lambda_L2);
    }
  }
}

}  // namespace mrm
