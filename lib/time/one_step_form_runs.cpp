/// @file one_step_form_runs.cpp
/// @brief The doctests that run the schemes of the paper's form (★) (steps/one_step_form.cpp) through a
/// run (BarSimulation): the fast kernel against the reference step (steps/fast_step.cpp), and EC and
/// CN-switch in the library's step (steps/energy_step.cpp, mathematics.md §12). They sit above the
/// steps they check because a run is built on the registry of every family.
#include "time/schemes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include "fem/mass_redistribution.hpp"
#include "steps/energy_step.hpp"
#include "steps/fast_step.hpp"
#include "steps/one_step_form.hpp"

namespace mrm {

/// The fast step against the reference step (mathematics.md §4). Both compute (★) with the same
/// factorised A; they differ only in the order of the floating-point operations: the fast kernel
/// forms b on the fly and runs each sweep as two chains (products of two elimination factors), sums
/// its energy forms by telescoping, multiplies by 1/Δt where the reference divides by Δt. Each step
/// of either commits errors of a few ε = 2⁻⁵² relative to the size of the quantities it combines,
/// and the scheme carries them on like any perturbation of its state: the contact step is Lipschitz
/// in b (u₀ = max(g, …), λ = min(0, …); a status decided differently by two round-off-close values
/// costs no jump), so the difference grows like the scheme's own response to a perturbation.
///
/// Prediction: the difference over a run of K steps is at most about K c ε A times the solution's
/// scale, c a modest factor (the condition of a step, O(N)), A ≥ 1 the scheme's amplification of a
/// perturbation of its state. A is measured by a third run, the initial displacement perturbed by
/// p = 1e-10 sin(5x): A = max(1, max over the run of ‖ΔUⁿ‖∞ / p). It is ≈ 1 where the scheme is
/// stable (backward Euler, Crank–Nicolson and Paoli–Schatzman with the algebraic row at Δt < h) and
/// large where it is not: Crank–Nicolson with the consistent mass gains energy at every impact
/// (10³–10⁷ here), the literal Paoli–Schatzman row lets its sawtooth grow (10–10²), large steps with
/// restitution move the impact times. With K = 200 and N = 12, Kcε ~ 1e-13: the bound is τ = 1e-12
/// of the solution's scale times A, the scale of each quantity being what its formula combines:
///
/// | quantity | bound of the difference          | its scale                                         |
/// |----------|----------------------------------|---------------------------------------------------|
/// | Uⁿ       | τ A U*                           | U* = max over the run of ‖Uⁿ‖∞                    |
/// | velocity | τ A U*/Δt                        | a difference of displacements divided by Δt       |
/// | λ        | τ A (‖M‖∞ U*/Δt² + ‖S‖∞ U* + F*) | the forces that row 0 of (★) balances (F* ≥ ‖F‖∞) |
/// | energy   | τ A (‖M‖∞ (U*/Δt)² + ‖S‖∞ U*²)   | the sizes of the terms of ½VᵀMV + ½UᵀSU           |
///
/// The instants of every sample, computed by the same code, are exactly equal. A wrong term in either
/// step would differ by O(h) or more at the first step, far above these bounds. The cases: every
/// scheme (EC and CN-switch included; EC without the consistent mass, which it refuses), every mass of
/// the paper (consistent, Mod 1–3) and two more that exercise every region of
/// the fast kernel (the lost mass spread over 3 nodes; a weight varying along the bar, no Toeplitz
/// interior at all), both Paoli–Schatzman forms (β = ¼, e = 0 at Δt = 0.7h; β = 0.3, e = 0.5 at
/// Δt = 4h), with and without a load; every run has impacts.
namespace {

[[maybe_unused]] MassRedistribution varying_weight() {
  return {"varying", "a weight that varies along the bar", [](Index i, Index j, const UniformMesh& mesh) {
            if (i == 0 || j == 0) return 0.0;
            return 1.0 + 0.3 * static_cast<double>(i + j) / static_cast<double>(mesh.elements);
          }};
}

// max_i Σ_j |A_ij|
[[maybe_unused]] double row_sum_norm(const Tridiagonal& a) {
  return (a.lower.cwiseAbs() + a.diag.cwiseAbs() + a.upper.cwiseAbs()).maxCoeff();
}

}  // namespace

TEST_CASE("the fast step and the reference step agree to round-off for every scheme, mass and form") {
  struct Form {
    Scheme scheme;
    ContactRow row;
  };
  const std::vector<Form> forms = {
      {Scheme::crank_nicolson, ContactRow::algebraic},    {Scheme::backward_euler, ContactRow::algebraic},
      {Scheme::paoli_schatzman, ContactRow::algebraic},   {Scheme::paoli_schatzman, ContactRow::literal},
      {Scheme::energy_conserving, ContactRow::algebraic}, {Scheme::switching, ContactRow::algebraic}};
  const std::vector<MassRedistribution> masses = {consistent_mass(),          mod1(),          mod2(), mod3(),
                                                  spread_over_first_nodes(3), varying_weight()};
  const double tolerance = 1e-12, perturbation = 1e-10;
  const double load_bound = 1.7;  // |f| ≤ 1.7 below, so ‖F‖∞ ≤ 1.7 h
  const Index steps = 200;
  const UniformMesh mesh(1.0, 12);
  int runs = 0;
  double worst = 0;  // the largest difference over its bound, over all runs
  for (const bool loaded : {false, true}) {
    for (const Form& form : forms) {
      for (const MassRedistribution& mass : masses) {
        // The algebraic Paoli–Schatzman row needs a massless contact node (refused otherwise, checked below).
        if (form.row == ContactRow::algebraic && form.scheme == Scheme::paoli_schatzman && mass.name == "consistent")
          continue;
        if (form.scheme == Scheme::energy_conserving && mass.name == "consistent") continue;  // refused likewise
        for (const double courant : {0.7, 4.0}) {
          Problem problem = benchmark_problem();
          if (loaded) problem.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
          SchemeParameters p;
          p.scheme = form.scheme;
          p.contact_row = form.row;
          const bool large = courant > 1;
          p.beta = form.scheme == Scheme::paoli_schatzman && large ? 0.3 : 0.25;
          // (e > 0 with the literal row and a massless contact node is refused: schemes.cpp.)
          const bool literal_massless = form.row == ContactRow::literal && mass.name != "consistent";
          p.restitution = form.scheme == Scheme::paoli_schatzman && large && !literal_massless ? 0.5 : 0.0;
          const double dt = courant * mesh.h();
          p.kernel = StepKernel::fast;
          BarSimulation fast(problem, mesh, mass, p, dt);
          Problem perturbed_problem = problem;
          perturbed_problem.initial_displacement = [&](double x) {
            return problem.initial_displacement(x) + perturbation * std::sin(5 * x);
          };
          BarSimulation perturbed(perturbed_problem, mesh, mass, p, dt);
          p.kernel = StepKernel::reference;
          BarSimulation reference(problem, mesh, mass, p, dt);
          CAPTURE(to_string(form.scheme));
          CAPTURE(to_string(form.row));
          CAPTURE(mass.name);
          CAPTURE(loaded);
          CAPTURE(courant);

          double response = 0, u_scale = 0, du = 0, dv = 0, dlambda = 0, denergy = 0;
          int impacts = 0;
          bool in_contact = false, same_instants = true;
          for (Index k = 0; k <= steps; ++k) {
            if (k > 0) {
              fast.step();
              reference.step();
              perturbed.step();
            }
            const Sample f = fast.sample(), r = reference.sample();
            response = std::max(response, (*perturbed.sample().displacement - *f.displacement).cwiseAbs().maxCoeff());
            same_instants = same_instants && f.level == r.level && f.time == r.time &&
                            f.velocity_time == r.velocity_time && f.has_multiplier == r.has_multiplier &&
                            f.multiplier_time == r.multiplier_time && f.energy_time == r.energy_time;
            u_scale = std::max({u_scale, f.displacement->cwiseAbs().maxCoeff(), r.displacement->cwiseAbs().maxCoeff()});
            du = std::max(du, (*f.displacement - *r.displacement).cwiseAbs().maxCoeff());
            dv = std::max(dv, (*f.velocity - *r.velocity).cwiseAbs().maxCoeff());
            if (f.has_multiplier) dlambda = std::max(dlambda, std::abs(f.multiplier - r.multiplier));
            denergy = std::max(denergy, std::abs(f.energy - r.energy));
            impacts += r.multiplier < 0 && !in_contact;
            in_contact = r.multiplier < 0;
          }
          const double amplification = std::max(1.0, response / perturbation);
          const double m_norm = row_sum_norm(fast.mass()), s_norm = row_sum_norm(fast.stiffness());
          const double relative = tolerance * amplification;
          const double u_bound = relative * u_scale;
          const double v_bound = relative * u_scale / dt;
          const double lambda_bound =
              relative * (m_norm * u_scale / (dt * dt) + s_norm * u_scale + (loaded ? load_bound * mesh.h() : 0.0));
          const double energy_bound = relative * (m_norm * std::pow(u_scale / dt, 2) + s_norm * u_scale * u_scale);
          CAPTURE(amplification);
          CAPTURE(du);
          CAPTURE(dv);
          CAPTURE(dlambda);
          CAPTURE(denergy);
          CHECK(same_instants);
          CHECK(du <= u_bound);
          CHECK(dv <= v_bound);
          CHECK(dlambda <= lambda_bound);
          CHECK(denergy <= energy_bound);
          CHECK(impacts >= 1);  // the runs do reach the obstacle
          worst = std::max({worst, du / u_bound, dv / v_bound, dlambda / lambda_bound, denergy / energy_bound});
          ++runs;
        }
      }
    }
  }
  CAPTURE(worst);
  CHECK(runs == 2 * 2 * (6 * 6 - 2));
  CHECK(worst <= 1.0);
}

TEST_CASE(
    "EC with a gap: the energy is conserved to round-off at every step, and Signorini's conditions hold at -gap") {
  // "With a gap" (§3): the paper's bar, g₀ = 0.05 and 0.3, Mod 3 and Mod 1, Δt = h and 5h, both step
  // kernels. Every step's change |Eⁿ⁺¹ − Eⁿ|/E₀ stays within §5's round-off model 16Nε(1 + h/Δt), on the
  // steps across a status change as on the others (an error in the gap's terms would show there first);
  // u₀ + g₀ ≥ 0 and λ(u₀ + g₀) = 0 at every level; impacts and releases on every run. Crank–Nicolson with
  // the same gap, for contrast, drifts by more than 1e-3 at Δt = 5h (its releases gain energy).
  for (const double gap : {0.05, 0.3})
    for (const MassRedistribution& mass : {mod3(), mod1()})
      for (const double courant : {1.0, 5.0})
        for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
          const UniformMesh mesh(1.0, 20);
          const double dt = courant * mesh.h(), bound = energy_round_off_per_step(20, courant);
          Problem problem = benchmark_problem();
          problem.gap = gap;
          SchemeParameters p;
          p.scheme = Scheme::energy_conserving;
          p.kernel = kernel;
          BarSimulation ec(problem, mesh, mass, p, dt);
          p.scheme = Scheme::crank_nicolson;
          BarSimulation cn(problem, mesh, mass, p, dt);
          const double e0 = ec.sample().energy;
          double at_change = 0, elsewhere = 0, cn_drift = 0, worst_gap = 0, worst_complementarity = 0, e = e0;
          int changes = 0;
          bool active = false;
          for (Index k = 0; k < steps_to_reach(60.0, dt); ++k) {
            ec.step();
            cn.step();
            const Sample s = ec.sample();
            const double g = (*s.displacement)[0] + gap;
            const bool changed = (s.multiplier < 0) != active;
            double& worst = changed ? at_change : elsewhere;
            worst = std::max(worst, std::abs(s.energy - e) / e0);
            e = s.energy;
            cn_drift = std::max(cn_drift, std::abs(cn.sample().energy - e0) / e0);
            worst_gap = std::max(worst_gap, -g);
            worst_complementarity = std::max(worst_complementarity, std::abs(s.multiplier * g));
            changes += changed;
            active = s.multiplier < 0;
          }
          CAPTURE(gap);
          CAPTURE(mass.name);
          CAPTURE(courant);
          CAPTURE(cn_drift);
          CAPTURE(bound);
          CHECK(at_change <= bound);
          CHECK(elsewhere <= bound);
          CHECK(worst_gap <= 0.0);
          CHECK(worst_complementarity <= 1e-15);
          CHECK(changes >= 10);
          if (courant == 5.0) CHECK(cn_drift > 1e-3);
        }
}

// ---------------------------------------------------------------------------------------------------
// Checks of EC and CN-switch in the library's step (mathematics.md §12; the derivation and the checks
// of its scalar pieces and of the reduced problem are in energy_step.cpp). Both kernels are run.

namespace {

// A problem whose initial data are the nodal values (U, V) of another run's level: the massless
// contact node takes its algebraic value again, so a two-level scheme restarts exactly from (Ū, V).
[[maybe_unused]] Problem restart_problem(const Sample& sample, const UniformMesh& mesh) {
  Problem p = benchmark_problem(mesh.length);
  const Eigen::VectorXd u = *sample.displacement, v = *sample.velocity;
  const double h = mesh.h();
  const auto node = [h, n = u.size()](double x) { return std::min<Index>(static_cast<Index>(std::lround(x / h)), n); };
  p.initial_displacement = [u, node](double x) {
    const Index i = node(x);
    return i < u.size() ? u[i] : 0.0;
  };
  p.initial_velocity = [v, node](double x) {
    const Index i = node(x);
    return i < v.size() ? v[i] : 0.0;
  };
  return p;
}

struct EnergyRun {
  double largest_drift = 0;     // max |Eⁿ − E⁰| / E⁰
  double largest_increase = 0;  // max (Eⁿ⁺¹ − Eⁿ) / E⁰, or −∞ … as the largest one-step change
  double final_ratio = 0;       // E(T)/E⁰
  int status_changes = 0;
  Index steps = 0;
};

[[maybe_unused]] EnergyRun energy_run(const SchemeParameters& p, const MassRedistribution& mass, Index elements,
                                      double courant, double final_time) {
  const UniformMesh mesh(1.0, elements);
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, p, dt);
  EnergyRun r;
  r.largest_increase = -HUGE_VAL;
  r.steps = steps_to_reach(final_time, dt);
  const double e0 = simulation.sample().energy;
  double previous = e0;
  bool active = simulation.sample().multiplier < 0;
  for (Index k = 0; k < r.steps; ++k) {
    simulation.step();
    const Sample s = simulation.sample();
    r.largest_drift = std::max(r.largest_drift, std::abs(s.energy - e0) / e0);
    r.largest_increase = std::max(r.largest_increase, (s.energy - previous) / e0);
    previous = s.energy;
    r.status_changes += (s.multiplier < 0) != active;
    active = s.multiplier < 0;
  }
  r.final_ratio = previous / e0;
  return r;
}

}  // namespace

TEST_CASE("EC conserves the discrete energy to round-off at every step, status changes included") {
  // Crank–Nicolson gains orders of magnitude on the first run (N = 16, Δt = 10h, 100 periods) and a few
  // E₀ on the second (N = 20, Δt = h, 1000 periods). EC's energy changes only by round-off: one step
  // conserves E up to the residual of its solve, a few ε times the condition of A = M + θS relative to
  // M, which grows like 1 + (Δt/h)², and these errors accumulate at most linearly in the number of
  // steps k: |E_k − E₀| ≤ k · 1e-15 (1 + (Δt/h)²) E₀.
  struct Case {
    Index elements;
    double courant, final_time;
  };
  for (const Case& c : {Case{16, 10.0, 300.0}, Case{20, 1.0, 3000.0}}) {
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
      for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
        const EnergyRun r = energy_run(parameters_of(Scheme::energy_conserving, ContactRow::algebraic, kernel), mass,
                                       c.elements, c.courant, c.final_time);
        CAPTURE(c.elements);
        CAPTURE(c.courant);
        CAPTURE(mass.name);
        CAPTURE(to_string(kernel));
        CAPTURE(r.largest_drift);
        CHECK(r.largest_drift <= static_cast<double>(r.steps) * 1e-15 * (1 + c.courant * c.courant));
        CHECK(r.status_changes >= static_cast<int>(2 * c.final_time / 3) - 2);  // an impact and a release per period
      }
    }
  }
}

TEST_CASE("EC on a bar that flies off: its energy drifts like u(0,t)^2, mostly in the evaluation") {
  // A uniform bar with a free far end, undeformed and moving into the obstacle at v = −1: the contact
  // holds for 2L/c = 2, then the bar leaves at v = +1 and translates, u(0, t) ≈ t − 2. The energy the
  // step reports (fast_step.cpp) sums the end rows of ½UᵀSU as products S_ii u_i² + 2S_{i,i−1}u_{i−1}u_i
  // of size u²/h that cancel, so by energy_step.cpp §5 its error is of order s = ε N u(0, t)²/(L E₀).
  // The state's own energy, ½VᵀM̄V + Σ (u_{i+1} − u_i)²/(2h) summed in differences, is free of that
  // cancellation but not of the step's: V = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ loses ε|u|/Δt per step. Measured (one
  // run, N = 50, Δt = h/2, t up to 1000): the evaluated drift is 1.2 s at t = 1000 and grows like
  // u(0, t)^2.07 between t = 250 and 1000; the state's is 40–60 times smaller and grows like u^1.8. The
  // checks, chosen after that run with a margin of about 4: the evaluated drift within [s/4, 4s], the
  // state's below s/10 and below a tenth of the evaluated one.
  const UniformMesh mesh = with_far_end(UniformMesh(1.0, 50), FarEnd::free);
  const double h = mesh.h(), dt = 0.5 * h, final_time = 1000;
  Problem flying;
  flying.initial_displacement = [](double) { return 0.0; };
  flying.initial_velocity = [](double) { return -1.0; };
  BarSimulation ec(flying, mesh, mod3(), parameters_of(Scheme::energy_conserving), dt);
  const auto state_energy = [&](const Sample& s) {
    const Eigen::VectorXd& u = *s.displacement;
    const Eigen::VectorXd& v = *s.velocity;
    double potential = 0;
    for (Index i = 0; i + 1 < u.size(); ++i) potential += (u[i + 1] - u[i]) * (u[i + 1] - u[i]);
    return 0.5 * v.dot(ec.mass() * v) + potential / (2 * h);
  };
  const double e0 = ec.sample().energy;
  CHECK(state_energy(ec.sample()) == doctest::Approx(e0).epsilon(1e-15));
  double evaluated_drift = 0, state_drift = 0;
  const Index steps = steps_to_reach(final_time, dt);
  for (Index k = 0; k < steps; ++k) {
    ec.step();
    const Sample s = ec.sample();
    evaluated_drift = std::max(evaluated_drift, std::abs(s.energy - e0) / e0);
    state_drift = std::max(state_drift, std::abs(state_energy(s) - e0) / e0);
  }
  const double u0 = (*ec.sample().displacement)[0];
  const double scale = std::numeric_limits<double>::epsilon() * 50 * u0 * u0 / e0;  // ε N u(0, T)²/(L E₀)
  CAPTURE(u0);
  CAPTURE(evaluated_drift);
  CAPTURE(state_drift);
  CAPTURE(scale);
  CHECK(u0 == doctest::Approx(final_time - 2).epsilon(0.01));  // it flew off
  CHECK(evaluated_drift >= scale / 4);
  CHECK(evaluated_drift <= 4 * scale);
  CHECK(state_drift <= scale / 10);
  CHECK(state_drift <= evaluated_drift / 10);
}

TEST_CASE("one EC step is Crank–Nicolson's without a status change, and conserves E across one") {
  // From the states of a Crank–Nicolson run (every level over 3 periods, Δt = h/2 and 3h), one step of
  // each scheme: without a change of the contact status the two steps agree to round-off (the same
  // linear system; the contact is decided on another row); across one, Crank–Nicolson's energy changes by
  // ab/2h at an impact and −ab/2h at a release (a, b = u₁ before and after) and EC's does not.
  for (const double courant : {0.5, 3.0}) {
    for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
      const UniformMesh mesh(1.0, 24);
      const double dt = courant * mesh.h(), h = mesh.h();
      BarSimulation run(benchmark_problem(), mesh, mod3(), parameters_of(Scheme::crank_nicolson), dt);
      int same = 0, changed = 0;
      CAPTURE(courant);
      CAPTURE(to_string(kernel));
      for (Index k = 0; k < steps_to_reach(9.0, dt); ++k, run.step()) {
        const Problem restart = restart_problem(run.sample(), mesh);
        BarSimulation cn(restart, mesh, mod3(), parameters_of(Scheme::crank_nicolson, ContactRow::algebraic, kernel),
                         dt);
        BarSimulation ec(restart, mesh, mod3(), parameters_of(Scheme::energy_conserving, ContactRow::algebraic, kernel),
                         dt);
        const double e0 = cn.sample().energy, a = (*cn.sample().displacement)[1];
        cn.step();
        ec.step();
        const double b = (*cn.sample().displacement)[1];
        const double scale = 1 + cn.sample().displacement->cwiseAbs().maxCoeff();
        CAPTURE(k);
        CHECK(std::abs(ec.sample().energy - e0) <= 1e-14);
        if (contact_is_active(a) == contact_is_active(b)) {
          CHECK((*ec.sample().displacement - *cn.sample().displacement).cwiseAbs().maxCoeff() <= 1e-14 * scale);
          CHECK((*ec.sample().velocity - *cn.sample().velocity).cwiseAbs().maxCoeff() <= 1e-14 * scale / dt);
          ++same;
        } else {
          CHECK(std::abs(cn.sample().energy - e0 - contact_energy_defect(a, b, h, 0.5)) <= 1e-14);
          CHECK(std::abs(contact_energy_defect(a, b, h, 0.5)) > 1e-9);  // a real status change, not a graze
          ++changed;
        }
      }
      CHECK(same > 5 * changed);
      CHECK(changed >= 6);  // an impact and a release per period
    }
  }
}

TEST_CASE("EC with a load: the energy changes by the work of the loads only") {
  // energy_step.cpp: with E = ½VᵀM̄V + ½ŪᵀS̄Ū − ψ(s), s = u₁ + hF₀, one EC step changes E by
  // ½(F̄ⁿ + F̄ⁿ⁺¹)·(Ūⁿ⁺¹ − Ūⁿ) − ½χ(sⁿ, sⁿ⁺¹)(F₀ⁿ⁺¹ − F₀ⁿ); the library's energy is that E plus F₀u₀.
  const UniformMesh mesh(1.0, 20);
  const double h = mesh.h(), dt = 2 * h;
  Problem problem = benchmark_problem();
  problem.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
    BarSimulation ec(problem, mesh, mod2(), parameters_of(Scheme::energy_conserving, ContactRow::algebraic, kernel),
                     dt);
    const auto load = [&](double t) { return p1_load(mesh, [&](double x) { return problem.load(x, t); }); };
    int changes = 0;
    CAPTURE(to_string(kernel));
    for (Index k = 0; k < 200; ++k) {
      const Sample before = ec.sample();
      const Eigen::VectorXd u = *before.displacement, f = load(before.time);
      const double e = before.energy;
      ec.step();
      const Sample after = ec.sample();
      const Eigen::VectorXd& u_next = *after.displacement;
      const Eigen::VectorXd f_next = load(after.time);
      const double a = u[1] + h * f[0], b = u_next[1] + h * f_next[0];
      const Index m = u.size() - 1;
      const double work = 0.5 * (f + f_next).tail(m).dot((u_next - u).tail(m)) -
                          0.5 * contact_secant(a, b) * (f_next[0] - f[0]) + f_next[0] * u_next[0] - f[0] * u[0];
      CAPTURE(k);
      CHECK(std::abs(after.energy - e - work) <= 1e-13 * (1 + std::abs(e)));
      changes += contact_is_active(a) != contact_is_active(b);
    }
    CHECK(changes >= 4);
  }
}

TEST_CASE("CN-switch never increases the energy, dissipating O(h) per status change") {
  // mathematics.md §12, energy_step.cpp §4: a Crank–Nicolson step without a status change conserves E, a
  // backward-Euler step dissipates at least ½‖ΔV‖²_M̄. So no step gains more than round-off, bounded in
  // energy_step.cpp §5 by 16 N ε (1 + h/Δt) E₀, on the runs where Crank–Nicolson gains most.
  struct Case {
    Index elements;
    double courant, final_time;
  };
  for (const Case& c : {Case{16, 10.0, 300.0}, Case{20, 1.0, 3000.0}}) {
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
      for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
        const EnergyRun r = energy_run(parameters_of(Scheme::switching, ContactRow::algebraic, kernel), mass,
                                       c.elements, c.courant, c.final_time);
        CAPTURE(c.elements);
        CAPTURE(mass.name);
        CAPTURE(to_string(kernel));
        CAPTURE(r.largest_increase);
        CAPTURE(energy_round_off_per_step(c.elements, c.courant));
        CHECK(r.largest_increase <= energy_round_off_per_step(c.elements, c.courant));
        CHECK(r.final_ratio < 1);
      }
    }
  }
  // The dissipation. An impact or a release changes the velocity by O(1) on the elements the front
  // crosses in one step, of mass O(Δt) = O(h) at fixed Δt/h: the backward-Euler step there dissipates
  // O(h), every other step nothing. Over 10 periods (20 status changes), Δt = h/2, the loss
  // E₀ − E(T) should halve when h halves: the ratio of the losses at N and 2N is 2 up to the O(h)
  // corrections, measured within 2 ± 0.3 on N = 100, 200, 400.
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    double previous_loss = 0;
    for (const Index elements : {100, 200, 400}) {
      const EnergyRun r = energy_run(parameters_of(Scheme::switching), mass, elements, 0.5, 30.0);
      const double loss = 1 - r.final_ratio;
      CAPTURE(mass.name);
      CAPTURE(elements);
      CAPTURE(loss);
      CAPTURE(r.status_changes);
      MESSAGE("loss " << mass.name << " " << elements << " " << loss);
      CHECK(loss > 0);
      if (previous_loss > 0) CHECK(std::abs(previous_loss / loss - 2) <= 0.3);
      CHECK(r.status_changes == 20);
      previous_loss = loss;
    }
  }
}

TEST_CASE("CN-switch with theta = 1/2 is Crank–Nicolson, and theta outside 1/2 ... 1 is refused") {
  const UniformMesh mesh(1.0, 20);
  SchemeParameters p = parameters_of(Scheme::switching);
  p.switch_theta = 0.5;
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
    p.kernel = kernel;
    BarSimulation cn(benchmark_problem(), mesh, mod1(),
                     parameters_of(Scheme::crank_nicolson, ContactRow::algebraic, kernel), 0.05);
    BarSimulation sw(benchmark_problem(), mesh, mod1(), p, 0.05);
    double difference = 0;
    for (Index k = 0; k < 240; ++k) {
      cn.step();
      sw.step();
      difference = std::max(difference, (*cn.sample().displacement - *sw.sample().displacement).cwiseAbs().maxCoeff());
    }
    CAPTURE(to_string(kernel));
    CHECK(difference <= 1e-13);
  }
  for (const double theta : {0.49, 1.01, std::nan("")}) {
    p.switch_theta = theta;
    CAPTURE(theta);
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("[0.5, 1]"),
                         std::invalid_argument);
  }
  CHECK_THROWS_WITH_AS(
      BarSimulation(benchmark_problem(), mesh, consistent_mass(), parameters_of(Scheme::energy_conserving), 0.1),
      doctest::Contains("massless contact node"), std::invalid_argument);
}

}  // namespace mrm
