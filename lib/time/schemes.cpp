/// @file schemes.cpp
/// @brief A run of a time scheme (BarSimulation, mathematics.md §4, the paper's §3): the checks of its
/// inputs, the initial level, the step its registry entry builds, Paoli–Schatzman's first step, the
/// instants of λ and of the energy; with the doctests that run the paper's schemes.
///
/// The semi-discrete problem is M U'' + S U = −λ e₀ + F, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (5)), with M the
/// consistent mass or a redistributed mass M^mod whose row and column 0 vanish (paper eq. (6)). The step
/// of the paper's schemes, (★) A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀ with its contact condition, is derived in
/// steps/one_step_form.cpp; the other families' steps in steps/explicit_schemes.cpp and lib/classes/.
#include "time/schemes.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <type_traits>
#include <stdexcept>

#include <doctest/doctest.h>

#include "classes/class_step.hpp"
#include "exact/exact_solution.hpp"
#include "steps/energy_step.hpp"
#include "steps/explicit_schemes.hpp"
#include "steps/one_step_form.hpp"

namespace mrm {

// Helpers of the doctests below.
namespace {

[[maybe_unused]] std::vector<double> energy_history(const MassRedistribution& mass, const SchemeParameters& p,
                                                    Index elements, double courant, double final_time) {
  const UniformMesh mesh(1.0, elements);
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, p, dt);
  std::vector<double> energy;
  run(simulation, steps_to_reach(final_time, dt), [&](const Sample& s) { energy.push_back(s.energy); });
  return energy;
}

}  // namespace

// The round-off floor, on the first impact time at N = 8 (Mod 1), Δt = h/4096, h/16384, h/65536
// (4·10⁵ steps at the finest). The increment form's spread is the truncation error: O(Δt²), measured
// 1.2e-9 between h/1024 and h/4096, so at most 1.2e-9/16 ≈ 7e-11 over the three steps, plus its
// round-off, √K ε|U| / |u̇₁| ≈ 1e-13 (K steps, a random walk of the additions Uⁿ + ΔU, u̇₁ ≈ −½). The
// form for Uⁿ⁺¹ loses ε|U|/Δt of velocity per step: ≈ 1e-6 at h/65536 (measured 8e-7; 2e-4 at N = 40).
// The threshold 1e-9 lies an order above the first prediction and three below the second.
TEST_CASE("the increment form keeps the first impact time flat as dt -> 0, and the form for U^{n+1} does not") {
  double increment_low = HUGE_VAL, increment_high = -HUGE_VAL, for_u_low = HUGE_VAL, for_u_high = -HUGE_VAL;
  for (const long ratio : {4096L, 16384L, 65536L}) {
    const double a = first_impact_time(8, mod1(), 0.125 / static_cast<double>(ratio), StepForm::increment),
                 b = first_impact_time(8, mod1(), 0.125 / static_cast<double>(ratio), StepForm::for_u);
    increment_low = std::min(increment_low, a), increment_high = std::max(increment_high, a);
    for_u_low = std::min(for_u_low, b), for_u_high = std::max(for_u_high, b);
  }
  CAPTURE(increment_high - increment_low);
  CAPTURE(for_u_high - for_u_low);
  CHECK(increment_high - increment_low <= 1e-9);
  CHECK(for_u_high - for_u_low > 1e-9);  // the criterion does fail on the form before
}

// ---------------------------------------------------------------------------------------------------
// The checks of a simulation's inputs, all before any work, each naming its parameter.
namespace {

void validate(const SchemeParameters& p, double dt) {
  if (!(std::isfinite(dt) && dt > 0))
    throw InvalidParameter("dt", "the time step dt must be positive and finite (allowed: 0 < dt < inf)");
  if (!(std::isfinite(p.beta) && p.beta >= 0))
    throw InvalidParameter("beta", "beta must be a finite number (allowed: beta >= 0)");
  if (!(p.restitution >= 0 && p.restitution <= 1))
    throw InvalidParameter("restitution", "the restitution coefficient e must lie in [0, 1] (allowed: 0 <= e <= 1)");
  if (!(p.switch_theta >= 0.5 && p.switch_theta <= 1))
    throw InvalidParameter("switch_theta",
                           "the switch theta of cn-switch must lie in [0.5, 1] (allowed: 0.5 <= theta <= 1)");
  // A parameter the scheme does not take keeps its default: another value would be silently ignored.
  for (const ParameterSpec& spec : scheme_parameter_specs())
    if (!takes(p.scheme, spec.parameter) && !is_default(p, spec.parameter))
      throw InvalidParameter(spec.name, "the scheme " + to_string(p.scheme) + " does not take " + spec.name +
                                            " (allowed: its default, or a scheme that takes it)");
}

// M^mod on the mesh, its refusal (weights not symmetric or not finite, a matrix that is not
// positive definite) worded as the mass's.
AssembledMass checked_mass(const UniformMesh& mesh, const MassRedistribution& mass) {
  try {
    return assemble_mass(mesh, mass);
  } catch (const std::invalid_argument& e) {
    throw InvalidParameter("mass", e.what());
  }
}

}  // namespace

// The mass assembled here (after the parameters' checks), then the run as from a mass assembled once.
BarSimulation::BarSimulation(const Problem& problem, const UniformMesh& mesh, const MassRedistribution& mass,
                             const SchemeParameters& parameters, double dt, InitialContactNode initial)
    : BarSimulation(problem, mesh, (validate(parameters, dt), checked_mass(mesh, mass)), parameters, dt, initial) {}

// Setting up (★) for the chosen scheme: the coefficients of the builder above, and the initial level.
BarSimulation::BarSimulation(const Problem& problem, const UniformMesh& mesh, const AssembledMass& mass,
                             const SchemeParameters& parameters, double dt, InitialContactNode initial)
    : problem_(problem),
      mesh_(mesh),
      parameters_((validate(parameters, dt), parameters)),
      dt_(dt),
      mass_(mass.matrix),
      stiffness_(p1_stiffness(mesh)) {
  if (mass_.size() != mesh.unknowns())
    throw InvalidParameter("mass", "the mass was assembled on another mesh (allowed: M^mod on the run's mesh)");
  if (!problem.initial_displacement)
    throw InvalidParameter("problem", "no initial displacement u0 (allowed: a function of x)");
  if (problem.length != mesh.length)
    throw InvalidParameter("problem", "the bar has L = " + std::to_string(problem.length) +
                                          ", the mesh L = " + std::to_string(mesh.length) + " (allowed: the same L)");
  if (!(std::isfinite(problem.gap) && problem.gap >= 0))
    throw InvalidParameter("gap", "the initial gap must be finite and >= 0 (got " + std::to_string(problem.gap) + ")");
  massless_ = mass.massless;
  three_level_ = parameters.scheme == Scheme::paoli_schatzman;
  algebraic_row_ = massless_ && (!three_level_ || parameters.contact_row == ContactRow::algebraic);
  // The scheme's own checks and its step, from its registry entry (scheme_registry.hpp): the paper's form
  // (★) (steps/one_step_form.cpp), central differences (steps/explicit_schemes.cpp) or a contact class
  // (classes/contact_classes.cpp). A step that runs with its own mass (the explicit schemes' row-sum
  // lumped one) makes it the run's.
  const SchemeInfo& scheme = scheme_info(parameters.scheme);
  const StepContext context{mesh,        mass.redistribution,     mass_,     stiffness_, parameters, dt,
                            problem.gap, problem.load != nullptr, massless_, mass};
  scheme.validate(context);
  step_ = scheme.make_step(context);
  if (const Tridiagonal* own = step_->own_mass()) mass_ = *own;
  one_step_form_ = dynamic_cast<OneStepFormStep*>(step_.get());
  class_step_ = dynamic_cast<ContactClassStep*>(step_.get());
  explicit_step_ = dynamic_cast<const ExplicitStep*>(step_.get());

  // The initial level. Uⁿ and V⁰ are the nodal interpolants of u⁰ and v⁰; a massless contact node
  // takes the value its algebraic row gives (mathematics.md §4: otherwise u₀ jumps in the first step and
  // the initial energy is off), unless the interpolant is asked for.
  const Index n = mesh.unknowns();
  state_.u.resize(n);
  state_.u_new.setZero(n);
  state_.x.resize(n);
  if (problem.load) {
    state_.f_now.setZero(n);
    state_.f_next.setZero(n);
  }
  for (Index i = 0; i < n; ++i) {
    state_.u[i] = problem.initial_displacement(mesh.x(i));
    state_.x[i] = problem.initial_velocity ? problem.initial_velocity(mesh.x(i)) : 0.0;
  }
  if (!(state_.u.allFinite() && state_.x.allFinite()))
    throw std::invalid_argument(
        "problem: the initial data u0, v0 are not finite at every node (allowed: finite values)");
  load_at(0.0, state_.f_now);
  if (problem.load && problem.steady_load) {
    // A steady load (Problem::steady_load): F and F₀ are formed here once, and load_at is not called
    // again. Checked on one more instant: a load that changes with t fails here, not silently later.
    load_at(dt, state_.f_next);
    if (std::memcmp(state_.f_next.data(), state_.f_now.data(), sizeof(double) * static_cast<std::size_t>(n)) != 0)
      throw std::invalid_argument(
          "problem: steady_load is set but the load vector at t = dt differs from the one at t = 0 (allowed: "
          "steady_load only for a load f(x) that does not depend on t)");
    steady_contact_load_ = contact_load(0.0);
    steady_load_ = true;
  }
  if (massless_) {
    const double compliance = mesh.contact_compliance();
    const CondensedContact c =
        condense_contact_node(state_.u[1], compliance, problem.load ? state_.f_now[0] : 0.0, -problem.gap);
    if (initial == InitialContactNode::consistent) state_.u[0] = c.u0;
    state_.lambda = c.multiplier;
    state_.active = contact_is_active(state_.u[1] + compliance * (problem.load ? state_.f_now[0] : 0.0) + problem.gap);
  } else {
    state_.lambda = 0.0;  // an inertial contact node starts without contact force
    state_.active = false;
  }
  has_lambda_ = true;
  state_.energy = energy_two_level();

  // W = V⁰ for the two-level schemes. The three-level scheme is started by one Crank–Nicolson step
  // (with the same mass and contact row): then W' = U¹ − U⁰ and Paoli–Schatzman with β = ¼ and the algebraic
  // row reproduces Crank–Nicolson exactly when f = 0 (the elimination of V from Crank–Nicolson gives
  // the three-level formula with β = ¼ on every free row; checked below).
  // The two-level schemes' velocity is W itself: X is not kept.
  state_.w = state_.x;
  if (algebraic_row_ && !three_level_ && initial == InitialContactNode::consistent)
    state_.w[0] = massless_node_velocity(0.0);
  if (three_level_ && parameters.ps_explicit_start) {
    explicit_start_ = true;
  } else if (three_level_) {
    SchemeParameters start;  // Crank–Nicolson takes none of Paoli–Schatzman's parameters
    start.scheme = Scheme::crank_nicolson;
    start.kernel = parameters.kernel;
    start_ = std::make_unique<BarSimulation>(problem, mesh, mass, start, dt, initial);
  } else {
    state_.x = Eigen::VectorXd();
  }
  step_->start(state_);
}

BarSimulation::~BarSimulation() = default;
BarSimulation::BarSimulation(BarSimulation&&) = default;
BarSimulation& BarSimulation::operator=(BarSimulation&&) = default;

TEST_CASE("the massless contact node starts on its algebraic row: E_h(0) = (1 - h)/8") {
  const UniformMesh mesh(1.0, 20);
  const BarSimulation consistent(benchmark_problem(), mesh, mod3(), parameters_of(Scheme::crank_nicolson), 0.025);
  const BarSimulation interpolant(benchmark_problem(), mesh, mod3(), parameters_of(Scheme::crank_nicolson), 0.025,
                                  InitialContactNode::interpolant);
  CHECK(std::abs(consistent.sample().energy - (1 - mesh.h()) / 8) < 1e-15);
  CHECK(std::abs(interpolant.sample().energy - 0.125) < 1e-15);
  CHECK(std::abs((*consistent.sample().displacement)[0] - (1 - mesh.h()) / 2) < 1e-15);
}

TEST_CASE("bad scheme parameters are rejected with a message naming them") {
  const UniformMesh mesh(1.0, 10);
  SchemeParameters p = parameters_of(Scheme::paoli_schatzman);
  p.beta = -0.1;
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("beta"),
                       std::invalid_argument);
  p.beta = 0.25;
  p.restitution = 1.5;
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("restitution"),
                       std::invalid_argument);
  p.restitution = 0;
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.0), doctest::Contains("dt"),
                       std::invalid_argument);
  CHECK_THROWS_AS(BarSimulation(benchmark_problem(), mesh, consistent_mass(), p, 0.1), std::invalid_argument);
  p.contact_row = ContactRow::literal;
  p.beta = 0;
  CHECK_THROWS_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), std::invalid_argument);
  CHECK_NOTHROW(BarSimulation(benchmark_problem(), mesh, consistent_mass(), p, 0.01));  // explicit central differences
  p.beta = 0.2;  // below 1/4 the literal row's defect grows in free flight
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("beta: "),
                       std::invalid_argument);
  CHECK_NOTHROW(BarSimulation(benchmark_problem(), mesh, consistent_mass(), p, 0.01));
  CHECK_THROWS_WITH_AS(scheme_by_name("rk4"), doctest::Contains("allowed: cn, be, ps"), std::invalid_argument);
  p = parameters_of(Scheme::crank_nicolson);
  for (double restitution : {-0.5, std::nan("")}) {
    p.restitution = restitution;
    CAPTURE(restitution);
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("restitution"),
                         std::invalid_argument);
  }
  p.restitution = 0;
  // A parameter the scheme does not take, set to another value than its default, is refused under its
  // own name (InvalidParameter::parameter), as is a mass the scheme cannot run or that is not definite.
  const auto refused = [&](const SchemeParameters& q, const MassRedistribution& mass) {
    try {
      BarSimulation(benchmark_problem(), mesh, mass, q, 0.1);
    } catch (const InvalidParameter& e) {
      CHECK(std::string(e.what()).rfind(e.parameter + ": ", 0) == 0);
      return e.parameter;
    }
    return std::string("accepted");
  };
  SchemeParameters q = parameters_of(Scheme::crank_nicolson);
  q.beta = 0.5;
  CHECK(refused(q, mod3()) == "beta");
  q = parameters_of(Scheme::backward_euler);
  q.restitution = 0.7;
  CHECK(refused(q, mod3()) == "restitution");
  q = parameters_of(Scheme::crank_nicolson, ContactRow::literal);
  CHECK(refused(q, consistent_mass()) == "contact_row");
  q = parameters_of(Scheme::paoli_schatzman);
  q.switch_theta = 0.5;
  CHECK(refused(q, mod3()) == "switch_theta");
  CHECK(refused(parameters_of(Scheme::paoli_schatzman), consistent_mass()) == "contact_row");
  CHECK(refused(parameters_of(Scheme::energy_conserving), consistent_mass()) == "mass");
  CHECK(refused(parameters_of(Scheme::crank_nicolson), node1(0.01)) == "mass");  // not positive definite on N = 10
  q = parameters_of(Scheme::switching);
  q.switch_theta = 0.75;
  CHECK(refused(q, mod3()) == "accepted");
  for (double dt : {-0.1, std::nan(""), HUGE_VAL}) {
    CAPTURE(dt);
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, dt), doctest::Contains("dt"),
                         std::invalid_argument);
  }
}

TEST_CASE("a problem without initial data, with non-finite data or on another bar is rejected") {
  const UniformMesh mesh(1.0, 10);
  const SchemeParameters p = parameters_of(Scheme::crank_nicolson);
  Problem problem = benchmark_problem();
  problem.initial_displacement = {};
  CHECK_THROWS_WITH_AS(BarSimulation(problem, mesh, mod3(), p, 0.1), doctest::Contains("no initial displacement"),
                       std::invalid_argument);
  problem = benchmark_problem();
  problem.initial_velocity = [](double x) { return x > 0.5 ? std::nan("") : 0.0; };
  CHECK_THROWS_WITH_AS(BarSimulation(problem, mesh, mod3(), p, 0.1), doctest::Contains("not finite"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(2.0), mesh, mod3(), p, 0.1),
                       doctest::Contains("(allowed: the same L)"), std::invalid_argument);
  problem = benchmark_problem();
  problem.load = [](double x, double) { return 1.0 / x; };  // singular at x = 0, which no Gauss point is
  CHECK_NOTHROW(BarSimulation(problem, mesh, mod3(), p, 0.1));
  problem.load = [](double, double t) { return t > 0 ? HUGE_VAL : 0.0; };
  // Rejected by the first evaluation after t = 0: the rate of the contact load (the massless node's
  // velocity at level 0) or the load vector of the first step.
  const auto first_step = [&](const MassRedistribution& mass, InitialContactNode initial) {
    BarSimulation simulation(problem, mesh, mass, p, 0.1, initial);
    simulation.step();
  };
  CHECK_THROWS_WITH_AS(first_step(mod3(), InitialContactNode::consistent), doctest::Contains("not finite"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(first_step(mod3(), InitialContactNode::interpolant), doctest::Contains("p1_load"),
                       std::invalid_argument);
}

/// @file schemes.cpp
/// ## The velocity of the massless node (mathematics.md §7)
///
/// Node 0 has no inertia: V₀ is not a state of
/// any scheme, and no equation of the step needs it (row 0 of B₂ vanishes with the algebraic row, and
/// so does M̄'s entry between nodes 0 and 1). Recovering it with a two-level scheme's velocity formula,
/// Crank–Nicolson's V₀ⁿ⁺¹ = 2(u₀ⁿ⁺¹ − u₀ⁿ)/Δt − V₀ⁿ, gives it a memory: the kink of u₀ at an impact
/// leaves an alternation V₀ⁿ = ±c that nothing damps, and the P1 norms weigh node 0 with h/3, so it
/// dominates every velocity error and keeps Crank–Nicolson's velocity from converging in Δt. The
/// consistent definition is the time derivative of the algebraic row at the same level:
///
///     free (u₀ = u₁ + hF₀ > 0):  V₀ = V₁ + h Ḟ₀;        contact (u₀ = 0):  V₀ = 0,
///
/// used by both two-level schemes at every level from level 1 on (at level 0 too when the initial
/// value of u₀ is the consistent one; with the interpolant, V₀(0) is the datum v⁰(0)). Ḟ₀ is the rate
/// of the load's contact entry F₀(t) = ∫ f(x, t) φ₀ dx, by a one-sided second-order difference over
/// half steps (contact_load_rate), second order like the schemes. Paoli–Schatzman's velocity (Uⁿ⁺¹ − Uⁿ)/Δt has no memory:
/// with the algebraic row its entry 0 is already the difference quotient of the row.

void BarSimulation::load_at(double t, Eigen::VectorXd& f) const {
  if (!problem_.load) return;
  p1_load(
      mesh_, [&](double x) { return problem_.load(x, t); }, f);
}

// F₀(t) = ∫₀ʰ f(x, t) φ₀(x) dx by the two-point Gauss rule of p1_load (the same number as its entry 0).
double BarSimulation::contact_load(double t) const {
  if (steady_load_) return steady_contact_load_;
  const double h = mesh_.h(0), g = 0.5 / 1.7320508075688772935;
  double f0 = 0;
  for (double xi : {0.5 - g, 0.5 + g}) f0 += problem_.load(xi * h, t) * 0.5 * h * (1.0 - xi);
  if (!std::isfinite(f0))
    throw std::invalid_argument("the load f(x, t) is not finite near x = 0 at t = " + std::to_string(t) +
                                " (allowed: finite values)");
  return f0;
}

// Ḟ₀ at a level t: the second-order one-sided differences over the half steps d = Δt/2 behind t (so
// that only instants the run has reached are used), ahead of t at t = 0.
double BarSimulation::contact_load_rate(double t) const {
  if (!problem_.load) return 0.0;
  const double d = 0.5 * dt_;
  if (t < 2 * d) return (-3 * contact_load(t) + 4 * contact_load(t + d) - contact_load(t + 2 * d)) / (2 * d);
  return (3 * contact_load(t) - 4 * contact_load(t - d) + contact_load(t - 2 * d)) / (2 * d);
}

// A steady load (Problem::steady_load) is the same run as the same load formed at every step, bit for
// bit, for every scheme of the registry, both masses, both kernels of (★) and the contact classes; a load
// that depends on t is refused as steady.
TEST_CASE("a steady load is formed once, with the bits of the load formed at every step") {
  const UniformMesh mesh(1.0, 20);
  const double dt = 0.5 * mesh.h();
  const auto bits = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
  };
  int runs = 0, contact_runs = 0;
  for (const SchemeInfo& info : scheme_registry()) {
    for (const MassRedistribution& mass : {consistent_mass(), mod3()}) {
      for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
        Problem every_step = benchmark_problem();
        every_step.load = [](double x, double) { return -1.0 + 0.7 * std::sin(3 * x); };
        Problem steady = every_step;
        steady.steady_load = true;
        SchemeParameters p;
        p.scheme = info.scheme;
        p.kernel = kernel;
        if (info.scheme == Scheme::paoli_schatzman && mass.name == "consistent") p.contact_row = ContactRow::literal;
        if (takes(info.scheme, SchemeParameter::newmark_beta)) p.newmark_beta = 0.25;
        std::unique_ptr<BarSimulation> a, b;
        try {
          a = std::make_unique<BarSimulation>(every_step, mesh, mass, p, dt);
        } catch (const InvalidParameter& e) {
          CHECK(e.parameter == "mass");  // a scheme that needs the other kind of contact node
          continue;
        }
        b = std::make_unique<BarSimulation>(steady, mesh, mass, p, dt);
        CAPTURE(info.id);
        CAPTURE(mass.name);
        CAPTURE(to_string(kernel));
        bool same = true, contact = false;
        for (Index k = 0; k <= 300 && same; ++k) {
          if (k > 0) {
            a->step();
            b->step();
          }
          const Sample x = a->sample(), y = b->sample();
          same = bits(*x.displacement, *y.displacement) && bits(*x.velocity, *y.velocity) &&
                 std::memcmp(&x.multiplier, &y.multiplier, sizeof(double)) == 0 &&
                 std::memcmp(&x.energy, &y.energy, sizeof(double)) == 0 && x.has_multiplier == y.has_multiplier;
          contact = contact || x.multiplier < 0;
        }
        CHECK(same);
        ++runs;
        contact_runs += contact;
      }
    }
  }
  CHECK(runs >= 30);  // 12 schemes, two masses, two kernels, less the refused pairs
  CHECK(contact_runs == runs);
  Problem moving = benchmark_problem();
  moving.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
  moving.steady_load = true;
  CHECK_THROWS_WITH_AS(BarSimulation(moving, mesh, mod3(), parameters_of(Scheme::crank_nicolson), dt),
                       doctest::Contains("steady_load"), std::invalid_argument);
}

double BarSimulation::massless_node_velocity(double t) const {
  return state_.u[0] > -problem_.gap ? state_.w[1] + mesh_.contact_compliance() * contact_load_rate(t) : 0.0;
}

// The massless node's velocity (mathematics.md §7): at every level it is the time derivative of the
// algebraic row, V₀ = V₁ + hḞ₀ (free) or 0 (contact), for Crank–Nicolson and backward Euler, both
// kernels, with either initial value of u₀ (from level 1 on with the interpolant). The contrast is
// the recovery by Crank–Nicolson's velocity formula, computed here from the same run's u₀: after the
// first impact it alternates by about the impact speed a = ½ for ever (measured: ±0.5).
TEST_CASE(
    "the massless node's velocity is the time derivative of its algebraic row, without the recovery's alternation") {
  const UniformMesh mesh(1.0, 24);
  const double dt = 0.5 * mesh.h();
  for (const Scheme scheme : {Scheme::crank_nicolson, Scheme::backward_euler}) {
    for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
      for (const InitialContactNode initial : {InitialContactNode::consistent, InitialContactNode::interpolant}) {
        SchemeParameters p = parameters_of(scheme);
        p.kernel = kernel;
        BarSimulation simulation(benchmark_problem(), mesh, mod3(), p, dt, initial);
        double worst = 0, recovered = 0, largest_alternation = 0;
        bool contact_seen = false;
        double u0_previous = 0;
        run(simulation, steps_to_reach(6.0, dt), [&](const Sample& s) {
          const double u0 = (*s.displacement)[0], v0 = (*s.velocity)[0], v1 = (*s.velocity)[1];
          if (s.level >= 1 || initial == InitialContactNode::consistent)
            worst = std::max(worst, std::abs(v0 - (u0 > 0 ? v1 : 0.0)));
          // Crank–Nicolson's recovery V₀ⁿ⁺¹ = 2(u₀ⁿ⁺¹ − u₀ⁿ)/Δt − V₀ⁿ, started from the datum.
          recovered = s.level == 0 ? v0 : 2 * (u0 - u0_previous) / dt - recovered;
          contact_seen = contact_seen || u0 == 0.0;
          if (contact_seen && u0 == 0.0) largest_alternation = std::max(largest_alternation, std::abs(recovered));
          u0_previous = u0;
        });
        CAPTURE(to_string(scheme));
        CAPTURE(to_string(kernel));
        CAPTURE(to_string(initial));
        CHECK(worst == 0.0);
        CHECK(contact_seen);
        CHECK(largest_alternation > 0.4);  // what the old definition measured while V₀ should be 0
      }
    }
  }
  // With a load f = sin t (1 + x): F₀(t) = sin t ∫₀ʰ (1 + x)(1 − x/h) dx = sin t (h/2 + h²/6) and
  // V₀ − V₁ = h cos t (h/2 + h²/6) while free, to O(Δt²) (the difference formula).
  Problem loaded = benchmark_problem();
  loaded.initial_displacement = [](double x) { return 0.5 * (1 - x) + 0.1; };  // keeps the gap open at first
  loaded.load = [](double x, double t) { return std::sin(t) * (1 + x); };
  const double h = mesh.h();
  BarSimulation simulation(loaded, mesh, mod1(), parameters_of(Scheme::crank_nicolson), dt);
  double worst = 0;
  run(simulation, 20, [&](const Sample& s) {
    if ((*s.displacement)[0] > 0)
      worst =
          std::max(worst, std::abs((*s.velocity)[0] - (*s.velocity)[1] - h * std::cos(s.time) * (h / 2 + h * h / 6)));
  });
  CHECK(worst < h * h * dt * dt);
}

/// @file schemes.cpp
/// ## The discrete energies
///
/// Two-level schemes: Eⁿ = ½ VⁿᵀMVⁿ + ½ UⁿᵀSUⁿ; Crank–Nicolson conserves it
/// exactly while the contact status does not change, backward Euler dissipates it. Paoli–Schatzman:
/// the quantity its linear part conserves is, with D = (Uⁿ⁺¹ − Uⁿ)/Δt,
///
///     Eⁿ⁺½ = ½ DᵀMD + ½ (β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ),
///
/// (for β = ¼ the familiar ½DᵀMD + ½ ŪᵀSŪ with Ū = (Uⁿ⁺¹ + Uⁿ)/2), attached to the instant t_{n+½}.
///

double BarSimulation::energy_two_level() const {
  return 0.5 * mass_.bilinear(state_.x, state_.x) + 0.5 * stiffness_.bilinear(state_.u, state_.u);
}

TEST_CASE("Crank–Nicolson conserves the discrete energy to round-off while the contact status is unchanged") {
  // The benchmark's first free flight lasts until t = 1: no status change before t = 0.9. Both step
  // kernels (their energies are summed in different orders).
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
      for (double courant : {0.5, 1.0, 3.0}) {
        const std::vector<double> e = energy_history(
            mass, parameters_of(Scheme::crank_nicolson, ContactRow::algebraic, kernel), 40, courant, 0.9 - 0.075);
        CAPTURE(to_string(kernel));
        CAPTURE(mass.name);
        CAPTURE(courant);
        // Round-off grows at most linearly with the number of steps k: |E_k − E_0| ≤ 1e-14 + k · 1e-15 (E ≈ 1/8).
        REQUIRE(e.size() > 2);
        for (std::size_t k = 0; k < e.size(); ++k) CHECK(std::abs(e[k] - e.front()) <= 1e-14 + k * 1e-15);
      }
    }
}

TEST_CASE("Paoli–Schatzman with beta = 1/4 conserves its energy while the contact status is unchanged") {
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
    for (ContactRow row : {ContactRow::algebraic, ContactRow::literal}) {
      // From level 2 on: levels 0 and 1 carry the two-level energy of the Crank–Nicolson start.
      const std::vector<double> e =
          energy_history(mod3(), parameters_of(Scheme::paoli_schatzman, row, kernel), 40, 0.5, 0.85);
      CAPTURE(to_string(kernel));
      CAPTURE(to_string(row));
      REQUIRE(e.size() > 10);
      for (std::size_t k = 2; k < e.size(); ++k) CHECK(std::abs(e[k] - e[2]) <= 1e-14 + k * 1e-15);
    }
}

TEST_CASE("backward Euler never increases the discrete energy") {
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
      const std::vector<double> e =
          energy_history(mass, parameters_of(Scheme::backward_euler, ContactRow::algebraic, kernel), 30, 0.5, 9.0);
      CAPTURE(to_string(kernel));
      CAPTURE(mass.name);
      int increases = 0;
      for (std::size_t k = 1; k < e.size(); ++k) increases += e[k] > e[k - 1] * (1 + 1e-14);
      CHECK(increases == 0);
      CHECK(e.back() < 0.9 * e.front());  // and it does dissipate
    }
}

BarSimulation::StepParts BarSimulation::step_parts() {
  const bool has_load = problem_.load != nullptr, starting = start_ != nullptr;
  return {&state_,
          one_step_form_ ? &one_step_form_->solver() : nullptr,
          one_step_form_ ? one_step_form_->fast() : nullptr,
          class_step_,
          explicit_step_,
          has_load,
          steady_load_,
          three_level_,
          algebraic_row_,
          starting};
}

void BarSimulation::switch_step(bool has_load) { one_step_form_->switch_step(state_, has_load); }

// Paoli–Schatzman's explicit first step (GetFEM's demo, doc/peer.md): U¹ = U⁰ + ΔtV⁰ + ½Δt² M⁻¹(F⁰ − SU⁰),
// the three-level scheme's state W' = U¹ − U⁰, X = W'/Δt, and its energy E^{1/2} at t = Δt/2. The demo
// corrects U¹ when the averaged constraint fails in this step; that case is refused (not needed by the
// benchmarks, whose contact node starts away from the obstacle).
void BarSimulation::explicit_first_step() {
  const ContactSolver mass_solver(mass_);
  Eigen::VectorXd a = -(stiffness_ * state_.u);
  if (problem_.load) a += state_.f_now;
  mass_solver.sweep_down(a.data(), a.data());
  mass_solver.sweep_up(a[0] * mass_solver.inverse_pivot()[0], a.data());
  const Eigen::VectorXd u_next = state_.u + dt_ * state_.w + (0.5 * dt_ * dt_) * a;
  const double e = parameters_.restitution;
  if (!((u_next[0] + e * state_.u[0]) / (1 + e) >= -problem_.gap))
    throw std::runtime_error(
        "ps: the explicit first step penetrates the obstacle (not implemented: use the "
        "Crank-Nicolson start)");
  state_.x = (u_next - state_.u) / dt_;
  state_.w = u_next - state_.u;
  const double beta = parameters_.beta;
  state_.energy =
      0.5 * mass_.bilinear(state_.x, state_.x) +
      0.5 * (beta * stiffness_.bilinear(u_next, u_next) + (1 - 2 * beta) * stiffness_.bilinear(u_next, state_.u) +
             beta * stiffness_.bilinear(state_.u, state_.u));
  state_.u = u_next;
  if (problem_.load && !steady_load_) load_at(dt_, state_.f_now);
  state_.lambda = 0.0;
  has_lambda_ = false;
  lambda_time_ = 0.0;
  energy_time_ = 0.5 * dt_;
  state_.active = false;
  explicit_start_ = false;
  ++level_;
}

void BarSimulation::step() {
  if (explicit_start_) return explicit_first_step();
  if (start_) {
    start_->step();
    // W' = U¹ − U⁰: rounded once to ε|U| (the starter's increment is not kept), which perturbs the
    // velocity by ε|U|/Δt once, not at every step.
    state_.w = start_->state_.u - state_.u;
    state_.u = start_->state_.u;
    state_.x = start_->state_.w;  // the starter's velocity V¹
    if (problem_.load) state_.f_now = start_->state_.f_now;
    state_.lambda = start_->state_.lambda;
    lambda_time_ = start_->lambda_time_;
    has_lambda_ = algebraic_row_;  // the literal form's λ¹ comes with its first own step
    state_.energy = start_->state_.energy;
    energy_time_ = start_->energy_time_;
    state_.active = start_->state_.active;
    start_.reset();
    ++level_;
    return;
  }
  const bool has_load = static_cast<bool>(problem_.load);
  if (has_load && !steady_load_) load_at(static_cast<double>(level_ + 1) * dt_, state_.f_next);
  step_->advance(state_, level_, has_load);
  finish_step();
}

// After the state has been advanced (by either kernel, or by a lane of the batched step,
// batched_step.cpp): the massless node's velocity, the instants of λ and of the energy, the level.
void BarSimulation::finish_step() {
  const double t_now = static_cast<double>(level_) * dt_;
  const double t_next = static_cast<double>(level_ + 1) * dt_;
  if (algebraic_row_ && !three_level_) state_.w[0] = massless_node_velocity(t_next);

  has_lambda_ = true;
  if (three_level_) {
    lambda_time_ = algebraic_row_ ? t_next : t_now;
    energy_time_ = 0.5 * (t_now + t_next);
  } else {
    lambda_time_ = t_next;
    energy_time_ = t_next;
  }
  ++level_;
}

TEST_CASE("Paoli–Schatzman (1/4, 0) with the algebraic contact row coincides with Crank–Nicolson") {
  const UniformMesh mesh(1.0, 32);
  const double dt = 0.5 * mesh.h();
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    BarSimulation cn(benchmark_problem(), mesh, mass, parameters_of(Scheme::crank_nicolson), dt);
    BarSimulation ps(benchmark_problem(), mesh, mass, parameters_of(Scheme::paoli_schatzman), dt);
    double difference = 0;
    for (Index k = 0; k < steps_to_reach(6.0, dt); ++k) {
      cn.step();
      ps.step();
      difference = std::max(difference, (*cn.sample().displacement - *ps.sample().displacement).cwiseAbs().maxCoeff());
      if (k > 0) CHECK(cn.sample().multiplier == doctest::Approx(ps.sample().multiplier).epsilon(1e-9));
    }
    CAPTURE(mass.name);
    CHECK(difference < 1e-12);
  }
}

Sample BarSimulation::sample() const {
  const double t = time();
  const double velocity_time = (three_level_ && level_ > 1) ? t - 0.5 * dt_ : t;
  const Eigen::VectorXd* velocity = three_level_ ? &state_.x : &state_.w;  // the two-level velocity is W
  return {level_,
          t,
          &state_.u,
          velocity_time,
          velocity,
          has_lambda_,
          level_ == 0 ? 0.0 : lambda_time_,
          state_.lambda,
          level_ == 0 ? 0.0 : energy_time_,
          state_.energy};
}

void run(BarSimulation& simulation, Index steps, const std::function<void(const Sample&)>& observe) {
  if (observe) observe(simulation.sample());
  for (Index k = 0; k < steps; ++k) {
    simulation.step();
    if (observe) observe(simulation.sample());
  }
}

// The first impact time, by the library's step or by (★) solved for Uⁿ⁺¹ (written here from the same
// matrices, step_matrices and step_right_hand_side, with the velocity from the difference and the
// massless node's velocity from its row, as the steps did before the increment form).
double first_impact_time(Index elements, const MassRedistribution& mass, double dt, StepForm form) {
  const UniformMesh mesh(1.0, elements);
  const double h = mesh.h();
  const Index limit = steps_to_reach(3.0 * mesh.length, dt);
  const auto crossing = [dt](Index k, double before, double after) {
    return (static_cast<double>(k - 1) + before / (before - after)) * dt;
  };
  if (form == StepForm::increment) {
    BarSimulation simulation(benchmark_problem(), mesh, mass, SchemeParameters(), dt);
    if (!contact_node_is_massless(simulation.mass()))
      throw std::invalid_argument("first_impact_time: the mass must leave the contact node massless");
    double previous = (*simulation.sample().displacement)[1];
    for (Index k = 1; k <= limit; ++k) {
      simulation.step();
      const double g = (*simulation.sample().displacement)[1];
      if (g <= 0) return crossing(k, previous, g);
      previous = g;
    }
  } else {
    const Tridiagonal m = checked_mass(mesh, mass).matrix, s = p1_stiffness(mesh);
    if (!contact_node_is_massless(m))
      throw std::invalid_argument("first_impact_time: the mass must leave the contact node massless");
    const StepMatrices step = step_matrices(m, s, SchemeParameters(), dt);
    const ContactSolver solver(step.a);
    const Index n = mesh.unknowns();
    Eigen::VectorXd u(n), v = Eigen::VectorXd::Zero(n), u_next(n);
    for (Index i = 0; i < n; ++i) u[i] = benchmark_problem().initial_displacement(mesh.x(i));
    const CondensedContact initial = condense_contact_node(u[1], h, 0.0);
    u[0] = initial.u0;
    double lambda = initial.multiplier, previous = u[1];
    for (Index k = 1; k <= limit; ++k) {
      const Eigen::VectorXd rhs = step_right_hand_side(step, u, v, lambda);
      lambda = solver.solve(rhs.data(), u_next.data(), step.kappa).multiplier;
      v = step.velocity_rate * (u_next - u) - step.velocity_memory * v;
      v[0] = u_next[0] > 0 ? v[1] : 0.0;
      u.swap(u_next);
      if (u[1] <= 0) return crossing(k, previous, u[1]);
      previous = u[1];
    }
  }
  throw std::runtime_error("first_impact_time: no impact before t = 3L");
}

Index steps_to_reach(double final_time, double dt) {
  if (!(std::isfinite(final_time) && final_time > 0))
    throw std::invalid_argument("the final time must be positive and finite");
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("the time step must be positive and finite");
  const double ratio = final_time / dt;
  if (ratio > 1e12) throw std::invalid_argument("the final time needs more than 1e12 time steps");
  return static_cast<Index>(std::ceil(ratio - 1e-9));
}

TEST_CASE("the number of steps to reach T needs T > 0, dt > 0 finite and at most 1e12 steps") {
  CHECK(steps_to_reach(1.0, 0.1) == 10);
  CHECK(steps_to_reach(1.0, 0.3) == 4);
  CHECK_THROWS_WITH_AS(steps_to_reach(0.0, 0.1), doctest::Contains("final time"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(steps_to_reach(1.0, -0.1), doctest::Contains("time step"), std::invalid_argument);
  CHECK_THROWS_AS(steps_to_reach(std::nan(""), 0.1), std::invalid_argument);
  CHECK_THROWS_AS(steps_to_reach(1.0, HUGE_VAL), std::invalid_argument);
  CHECK_THROWS_WITH_AS(steps_to_reach(1.0, 1e-13), doctest::Contains("more than 1e12"), std::invalid_argument);
}

}  // namespace mrm
