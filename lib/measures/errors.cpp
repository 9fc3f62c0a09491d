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
///
/// Scale. The measures are computed on the dimensionless problem (L = 1, amplitude of order one: the
/// harness maps any run to it, repro/configurations/scaling.cpp), where every squared norm is of order one;
/// the measures are ratios of two norms of the same kind, so they do not change under the scaling.
#include "measures/errors.hpp"

#include <algorithm>
#include <cstddef>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "measures/error_sums.hpp"
#include "exact/characteristics.hpp"
#include "time/schemes.hpp"

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

// One level costs one pass over the nodes. For a general reference the interpolants come from its
// evaluation at many points (characteristics.cpp: two table look-ups per node on a lattice of the mesh
// and the time step). For the paper's closed form no array of values is formed: u(·, t) and u_t(·, t)
// are a few runs of one affine function each between the kinks (exact_solution.cpp: the phase located
// once), so the error e_i = W_i − (α + β x_i) is formed in the pass over W, and the interpolant's own
// sums over a run of m nodes with spacing h are closed forms: Σ z_i² = m z̄² + (βh)² m(m² − 1)/12 (z̄
// the mean of the run's values) and Σ (z_i − z_{i−1})² = m (βh)², two positive terms with no
// cancellation. The six quadratic forms eᵀMe and eᵀSe of the errors and of the interpolants are
// accumulated together. M and
// S are the P1 matrices of a uniform mesh: row 0 has its own diagonal entry a₀₀, and every other row
// the same entries (d, l) = (A_ii, A_{i,i−1}) (checked when the accumulator is built). Expanding
// −l (z_i − z_{i−1})² and telescoping, with D = Σ_{i≥1} (z_i − z_{i−1})² and Q = Σ_{i≥1} z_i²,
//
//     zᵀAz = a₀₀ z₀² + Σ_{i=1}^{n−1} (d z_i² + 2l z_{i−1} z_i) = a₀₀ z₀² − l D + (d + 2l) Q − l z_{n−1}² + l z₀².
//
// For S, d + 2l = 0 and −l = 1/h: |z|²_H¹ = (D + z_{n−1}²)/h, a sum of squares with no cancellation
// (the same form written as Σ z_i² against Σ z_{i−1} z_i loses O(N²) in relative accuracy).
ErrorAccumulator::ErrorAccumulator(const UniformMesh& mesh, const ExactSolution& exact)
    : ErrorAccumulator(mesh, std::make_shared<const ExactSolution>(exact)) {}

ErrorAccumulator::ErrorAccumulator(const UniformMesh& mesh, std::shared_ptr<const ReferenceSolution> reference)
    : mesh_(mesh),
      exact_(std::move(reference)),
      mass_(p1_mass(mesh)),
      stiffness_(p1_stiffness(mesh)),
      nodes_(mesh.unknowns()),
      interpolant_(mesh.unknowns()),
      velocity_interpolant_(mesh.unknowns()) {
  if (!exact_) throw std::invalid_argument("error measures: no reference solution");
  const ReferenceSolution& exact = *exact_;
  closed_form_ = dynamic_cast<const ExactSolution*>(exact_.get());
  const Index n = mesh.unknowns();
  for (Index i = 0; i < n; ++i) nodes_[i] = mesh.x(i);
  // The sums below need Toeplitz matrices (a uniform mesh of a homogeneous bar clamped at L); any other
  // mesh (graded, layered, a free far end) takes the quadratic forms eᵀMe, eᵀSe of its own P1
  // matrices, ρ and E included (the energy norms of the layered bar), by Tridiagonal::bilinear.
  // A graded mesh is general whatever its matrices show (with two elements they have no row to compare).
  general_ = !mesh.uniform();
  for (const Tridiagonal* a : {&mass_, &stiffness_})
    for (Index i = 2; i < n; ++i)
      if (a->diag[i] != a->diag[1] || a->lower[i] != a->lower[1]) general_ = true;
  if (general_ && closed_form_)
    throw std::logic_error("error measures: the closed form is the paper's, on a uniform homogeneous mesh");
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
  add_vectors(sample, sample.displacement->data(), sample.velocity->data(), std::integral_constant<long, 1>());
}

void ErrorAccumulator::add(const Sample& sample, const LaneVectors& lanes) {
  if (lanes.stride < 1) throw std::invalid_argument("error measures: a lane layout's stride must be >= 1");
  add_vectors(sample, lanes.displacement, lanes.velocity, static_cast<long>(lanes.stride));
}

using namespace error_sums;

template <typename Stride>
void ErrorAccumulator::add_vectors(const Sample& sample, const double* u, const double* v, Stride stride,
                                   bool evaluated) {
  const Index n = mesh_.unknowns();
  const double* x = nodes_.data();

  // D and Q for the vectors e = W − w_I and w_I, W = U or V: four independent sums, each a short chain
  // of additions (one loop per W keeps them all in registers).
  const auto sums = [n, stride](const double* w, const double* wi) {
    Sums r{w[0] - wi[0], 0, 0, 0, wi[0], 0, 0, 0};
    double e_prev = r.e0, i_prev = r.i0;
    for (Index i = 1; i < n; ++i) {
      const double e = w[i * stride] - wi[i], z = wi[i], de = e - e_prev, dz = z - i_prev;
      r.e_differences += de * de;
      r.e_squares += e * e;
      r.i_differences += dz * dz;
      r.i_squares += z * z;
      e_prev = e, i_prev = z;
    }
    r.e_last = e_prev, r.i_last = i_prev;
    return r;
  };
  // The same sums from the closed form's runs (see above).
  const double h = general_ ? 0.0 : mesh_.h();  // the closed form's runs (uniform mesh only)
  const auto run_sums = [x, h, stride](const double* w, const ExactSolution::AffineRun* runs, int count) {
    const ErrorRunSums e = error_run_sums(w, stride, x, runs, count);
    const InterpolantSums z = interpolant_run_sums(x, h, runs, count);
    return Sums{e.e0, e.e_last, e.differences, e.squares, z.z0, z.z_last, z.differences, z.squares};
  };
  if (general_) {
    // The quadratic forms of the mesh's own matrices, on the sample's vectors seen with their stride (no
    // copy: the differences below are formed entry by entry, as from contiguous vectors).
    using Strided = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>;
    const Strided uc(u, n, Eigen::InnerStride<>(static_cast<long>(stride)));
    const Strided vc(v, n, Eigen::InnerStride<>(static_cast<long>(stride)));
    if (!evaluated) {
      exact_->displacement_at_points(sample.time, x, static_cast<long>(n), interpolant_.data());
      exact_->velocity_at_points(sample.velocity_time, x, static_cast<long>(n), velocity_interpolant_.data());
    }
    error_ = uc - interpolant_;
    const double t = sample.time;
    u_l2_.add(t, mass_.bilinear(error_, error_), mass_.bilinear(interpolant_, interpolant_));
    u_h1_.add(t, stiffness_.bilinear(error_, error_), stiffness_.bilinear(interpolant_, interpolant_));
    const double u0 = exact_->contact_displacement(sample.time);
    u0_.add(t, std::pow(u[0] - u0, 2), u0 * u0);
    error_ = vc - velocity_interpolant_;
    v_l2_.add(sample.velocity_time, mass_.bilinear(error_, error_),
              mass_.bilinear(velocity_interpolant_, velocity_interpolant_));
    if (sample.has_multiplier) {
      const double lambda = exact_->contact_multiplier(sample.multiplier_time);
      lambda_.add(sample.multiplier_time, std::pow(sample.multiplier - lambda, 2), lambda * lambda);
    }
    return;
  }
  Sums su, sv;
  if (closed_form_) {
    ExactSolution::AffineRun u_runs[32], v_runs[32];
    const int u_count = closed_form_->displacement_runs(sample.time, x, static_cast<long>(n), u_runs, 32);
    const int v_count = closed_form_->velocity_runs(sample.velocity_time, x, static_cast<long>(n), v_runs, 32);
    su = run_sums(u, u_runs, u_count);
    sv = run_sums(v, v_runs, v_count);
  } else {
    double* ui = interpolant_.data();
    double* vi = velocity_interpolant_.data();
    if (!evaluated) {
      exact_->displacement_at_points(sample.time, x, static_cast<long>(n), ui);
      exact_->velocity_at_points(sample.velocity_time, x, static_cast<long>(n), vi);
    }
    su = sums(u, ui);
    sv = sums(v, vi);
  }
  add_sums(sample, u[0], su, sv);
}

// The layout of add(sample, lanes), also taken by add_lanes for a run added alone (batched/lane_errors.cpp).
template void ErrorAccumulator::add_vectors<long>(const Sample&, const double*, const double*, long, bool);

void ErrorAccumulator::add_sums(const Sample& sample, double u_first, const Sums& su, const Sums& sv) {
  add_sums(sample, u_first, su, sv, exact_->contact_displacement(sample.time),
           sample.has_multiplier ? exact_->contact_multiplier(sample.multiplier_time) : 0.0);
}

void ErrorAccumulator::add_sums(const Sample& sample, double u_first, const Sums& su, const Sums& sv, double u0,
                                double lambda) {
  const Index n = mesh_.unknowns();
  const auto error_form = [](const Sums& r, double a00, double d, double l) {
    return form(r.e0, r.e_last, r.e_differences, r.e_squares, a00, d, l);
  };
  const auto exact_form = [](const Sums& r, double a00, double d, double l) {
    return form(r.i0, r.i_last, r.i_differences, r.i_squares, a00, d, l);
  };
  const double m00 = mass_.diag[0], m = n > 1 ? mass_.diag[1] : 0, ml = n > 1 ? mass_.lower[1] : 0;
  const double s00 = stiffness_.diag[0], s = n > 1 ? stiffness_.diag[1] : 0, sl = n > 1 ? stiffness_.lower[1] : 0;
  const double t = sample.time;
  u_l2_.add(t, error_form(su, m00, m, ml), exact_form(su, m00, m, ml));
  u_h1_.add(t, error_form(su, s00, s, sl), exact_form(su, s00, s, sl));
  u0_.add(t, std::pow(u_first - u0, 2), u0 * u0);
  v_l2_.add(sample.velocity_time, error_form(sv, m00, m, ml), exact_form(sv, m00, m, ml));
  if (sample.has_multiplier)
    lambda_.add(sample.multiplier_time, std::pow(sample.multiplier - lambda, 2), lambda * lambda);
}

// Each measure relative to the same norm of the exact solution (the absolute value where that norm
// vanishes, which never happens over a time interval that contains a contact).
namespace {
double ratio(double error, double exact) { return exact > 0 ? std::sqrt(error / exact) : std::sqrt(error); }
}  // namespace

ErrorNorms relative_norms(const TimeHistory& u0, const TimeHistory& lambda, const TimeHistory& u_l2,
                          const TimeHistory& u_h1, const TimeHistory& v_l2) {
  return {ratio(u0.error_integral, u0.exact_integral),     ratio(lambda.error_integral, lambda.exact_integral),
          ratio(u_l2.error_max, u_l2.exact_max),           ratio(u_h1.error_max, u_h1.exact_max),
          ratio(v_l2.error_max, v_l2.exact_max),           ratio(u_l2.error_integral, u_l2.exact_integral),
          ratio(u_h1.error_integral, u_h1.exact_integral), ratio(v_l2.error_integral, v_l2.exact_integral)};
}

ErrorNorms ErrorAccumulator::relative() const { return relative_norms(u0_, lambda_, u_l2_, u_h1_, v_l2_); }

}  // namespace mrm

// ---------------------------------------------------------------------------------------------------

namespace mrm {
namespace {

[[maybe_unused]] ErrorNorms benchmark_errors(Scheme scheme, const MassRedistribution& mass, Index elements,
                                             double courant, double final_time) {
  const UniformMesh mesh(1.0, elements);
  SchemeParameters p;
  p.scheme = scheme;
  if (scheme == Scheme::paoli_schatzman && !contact_node_is_massless(modified_mass(mesh, mass)))
    p.contact_row = ContactRow::literal;
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

TEST_CASE("the error measures do not change when the bar and the amplitude are scaled") {
  // The same relative field at several scales (the measures are ratios: scale-invariant, see Scale):
  // the interpolant of the exact solution times
  //    (1 + g(x/L)), g a fixed wiggle of size 0.01, and the same for the velocity and λ; its relative
  //    errors do not depend on L and a but through the rounding of the nodes and instants (relative
  //    1e-16), so they agree with those at L = a = 1 to 1e-12; the interpolant itself gives 0 up to
  //    the rounding of the two evaluations of the exact solution (the generic one here, the one per
  //    mesh in the accumulator: 1e-16 relative at each node), 1e-13.
  const Index elements = 16;
  const auto measures = [&](double length, double amplitude, double wiggle) {
    const UniformMesh mesh(length, elements);
    const ExactSolution exact(length, amplitude);
    ErrorAccumulator errors(mesh, exact);
    Eigen::VectorXd u(elements), v(elements);
    for (int n = 0; n <= 48; ++n) {
      const double t = n * 0.0625 * length;
      for (Index i = 0; i < elements; ++i) {
        const double g = wiggle * std::sin(7.0 * static_cast<double>(i) / elements + n);
        u[i] = exact.displacement(mesh.x(i), t) * (1 + g);
        v[i] = exact.velocity(mesh.x(i), t) * (1 - g);
      }
      const double lambda = exact.contact_multiplier(t) * (1 + wiggle * std::cos(n));
      errors.add({n, t, &u, t, &v, true, t, lambda, t, 0.0});
    }
    return ErrorAccumulator::values(errors.relative());
  };
  const auto reference = measures(1.0, 1.0, 0.01);
  for (const double length : {0.3, 1.0, 7.0})
    for (const double amplitude : {0.01, 1.0, 50.0}) {
      CAPTURE(length);
      CAPTURE(amplitude);
      const auto wiggled = measures(length, amplitude, 0.01), exact = measures(length, amplitude, 0.0);
      for (std::size_t k = 0; k < 8; ++k) {
        CAPTURE(std::string(ErrorAccumulator::names[k]));
        CHECK(reference[k] > 1e-3);
        CHECK(std::abs(wiggled[k] - reference[k]) <= 1e-12 * reference[k]);
        CHECK(exact[k] <= 1e-13);
      }
    }
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

TEST_CASE(
    "on the paper's benchmark, the measures against the characteristic solution are those against the closed form") {
  // The two references agree to round-off wherever u_x and u_t have a limit (characteristics.cpp) and
  // at t = 0 (both give the data); the corners x = 0, t = kL, k ≥ 1, are avoided by a step that never
  // reaches them (Δt = 0.37 h, N = 40: t_n = kL would need n = 108.1… k), and so the eight measures must
  // agree to round-off.
  const UniformMesh mesh(1.0, 40);
  const double dt = 0.37 * mesh.h(), final_time = 9.0;
  const Index steps = steps_to_reach(final_time, dt);
  const auto characteristic = std::make_shared<const CharacteristicSolution>(benchmark_initial_data(1.0, 0.5),
                                                                             static_cast<double>(steps + 1) * dt);
  for (const MassRedistribution& mass : {mod1(), mod3()}) {
    SchemeParameters p;
    BarSimulation simulation(benchmark_problem(), mesh, mass, p, dt);
    ErrorAccumulator closed_form(mesh, ExactSolution()), characteristics(mesh, characteristic);
    run(simulation, steps, [&](const Sample& s) {
      closed_form.add(s);
      characteristics.add(s);
    });
    const auto a = ErrorAccumulator::values(closed_form.relative()),
               b = ErrorAccumulator::values(characteristics.relative());
    for (std::size_t k = 0; k < a.size(); ++k) {
      CAPTURE(mass.name);
      CAPTURE(std::string(ErrorAccumulator::names[k]));
      CHECK(a[k] > 1e-4);
      CHECK(std::abs(a[k] - b[k]) <= 1e-11 * a[k]);
    }
  }
  CHECK_THROWS_AS(ErrorAccumulator(mesh, std::shared_ptr<const ReferenceSolution>()), std::invalid_argument);
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

namespace mrm {
TEST_CASE("the closed form's runs give the same measures as its values at the nodes") {
  // The prediction: both paths sum the same quadratic forms, in another order and with the interpolant's
  // sums over a run in closed form, so the eight measures agree to round-off. Each sum has at most N + 1
  // positive terms with one rounding each, and the closed forms a few: relative 64 N ε bounds the
  // difference of two sums and so of their square roots. Meshes and steps that put levels on the kinks
  // (Δt = h/2, h) and off them (Δt = 0.37h), with L ≠ 1 and amplitudes far from 1 (the scaling).
  for (const double length : {1.0, 2.5}) {
    for (const double amplitude : {0.5, 1e-30}) {
      for (const Index elements : {7L, 64L, 100L}) {
        for (const double courant : {0.5, 1.0, 0.37}) {
          const UniformMesh mesh(length, elements);
          const ExactSolution exact(length, amplitude);
          ErrorAccumulator runs(mesh, exact),
              values(mesh, std::make_shared<const error_sums::ForwardedSolution>(exact));
          SchemeParameters p;
          p.contact_row = ContactRow::algebraic;
          const double dt = courant * mesh.h();
          BarSimulation simulation(benchmark_problem(length, amplitude), mesh, mod2(), p, dt);
          run(simulation, steps_to_reach(4 * length, dt), [&](const Sample& s) {
            runs.add(s);
            values.add(s);
          });
          const auto a = ErrorAccumulator::values(runs.relative()), b = ErrorAccumulator::values(values.relative());
          const double tolerance = 64 * static_cast<double>(elements) * 0x1p-52;
          for (std::size_t k = 0; k < a.size(); ++k) {
            CAPTURE(length);
            CAPTURE(amplitude);
            CAPTURE(elements);
            CAPTURE(courant);
            CAPTURE(ErrorAccumulator::names[k]);
            CHECK(a[k] > 0);
            CHECK(std::abs(a[k] - b[k]) <= tolerance * b[k]);
          }
        }
      }
    }
  }
}

TEST_CASE("the error measures read from a lane layout are those of the run's own vectors, bit for bit") {
  // Prediction: add(sample, lanes) sums the same terms in the same order as add(sample) (pair_sums and
  // the same closed forms), so the eight measures have the same bits. Three runs of a scheme on one mesh
  // interleaved as a batch keeps them (entry i of lane j at i·3 + j), at levels that put nodes on the
  // closed form's kinks and off them, and against a general reference (the characteristic solution).
  const UniformMesh mesh(1.0, 37);
  const Index n = mesh.unknowns();
  for (const double courant : {0.5, 0.37}) {
    const double dt = courant * mesh.h();
    const Index steps = steps_to_reach(3.0, dt);
    const auto characteristic = std::make_shared<const CharacteristicSolution>(benchmark_initial_data(1.0, 0.5),
                                                                               static_cast<double>(steps + 1) * dt);
    for (const bool closed : {true, false}) {
      const auto reference = closed ? std::shared_ptr<const ReferenceSolution>(std::make_shared<const ExactSolution>())
                                    : std::shared_ptr<const ReferenceSolution>(characteristic);
      std::vector<BarSimulation> runs;
      std::vector<ErrorAccumulator> own, strided;
      SchemeParameters ps;
      ps.scheme = Scheme::paoli_schatzman;
      for (const MassRedistribution& mass : {mod1(), mod3()})
        runs.emplace_back(benchmark_problem(), mesh, mass, SchemeParameters{}, dt);
      runs.emplace_back(benchmark_problem(), mesh, mod2(), ps, dt);
      for (std::size_t j = 0; j < runs.size(); ++j)
        own.emplace_back(mesh, reference), strided.emplace_back(mesh, reference);
      const std::size_t W = runs.size();
      std::vector<double> u(static_cast<std::size_t>(n) * W), v(u.size());
      for (Index level = 0; level <= steps; ++level) {
        for (std::size_t j = 0; j < W; ++j) {
          if (level > 0) runs[j].step();
          const Sample s = runs[j].sample();
          for (Index i = 0; i < n; ++i) {
            u[static_cast<std::size_t>(i) * W + j] = (*s.displacement)[i];
            v[static_cast<std::size_t>(i) * W + j] = (*s.velocity)[i];
          }
          own[j].add(s);
          strided[j].add(s, LaneVectors{&u[j], &v[j], W});
        }
      }
      for (std::size_t j = 0; j < W; ++j) {
        const auto a = ErrorAccumulator::values(own[j].relative()), b = ErrorAccumulator::values(strided[j].relative());
        for (std::size_t k = 0; k < a.size(); ++k) {
          CAPTURE(courant);
          CAPTURE(closed);
          CAPTURE(j);
          CAPTURE(ErrorAccumulator::names[k]);
          CHECK(a[k] > 0);
          CHECK(std::memcmp(&a[k], &b[k], sizeof(double)) == 0);
        }
      }
    }
  }
  Eigen::VectorXd z = Eigen::VectorXd::Zero(4);
  ErrorAccumulator errors(UniformMesh(1.0, 4), ExactSolution());
  CHECK_THROWS_AS(errors.add({0, 0.0, &z, 0.0, &z, false, 0.0, 0.0, 0.0, 0.0}, LaneVectors{z.data(), z.data(), 0}),
                  std::invalid_argument);
}

}  // namespace mrm
