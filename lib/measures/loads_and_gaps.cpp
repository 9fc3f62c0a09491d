/// @file loads_and_gaps.cpp
/// @brief Static solutions under a load, the energy balance with the load's work, the free fall and the
/// gap closing, checked through the schemes: a load f, a free far end,
/// an initial gap, piecewise-constant material and graded meshes, each against a closed form or an
/// identity. The code is where it belongs (p1.cpp: the mesh, the material and the load vector;
/// mass_redistribution.cpp: the family on unequal elements; contact.cpp and schemes.cpp: the gap as an
/// obstacle offset); this file holds the derivations of what a run must then do, and their doctests.
///
/// 1. Static solutions (a constant load f). The P1 Galerkin solution of −(E u')' = f in 1D is exact at
///    the nodes when E is constant on each element and the load vector is exact (the Green's function
///    of a node is piecewise linear on the mesh): so the nodal interpolant U* of the static solution
///    solves S U* = F − λ e₀ exactly, and a run started at rest from it stays there at every step of
///    every scheme (Uⁿ = U*, Vⁿ = 0 is a fixed point of each step (★) of schemes.cpp: B₁U* + B₂·0 + G
///    = A U* + κ λ e₀ when S U* = F − λ e₀). Two cases, with E_e, h_e of any graded mesh:
///      - no contact (f > 0 pulls the end off the obstacle, free at x = 0): E u' = −f x, so
///        u(x) = ∫ₓᴸ f s/E(s) ds ≥ 0, λ = 0;
///      - persistent contact (f < 0 presses the end onto the obstacle, u(0) = −gap): E u' = C − f x and
///        u(x) = −gap + ∫₀ˣ (C − f s)/E(s) ds, with C fixed by u(L) = 0:
///        C ∫₀ᴸ 1/E = gap + f ∫₀ᴸ s/E; the multiplier is λ = E u'(0) = C ≤ 0.
///    For piecewise-constant E the integrals are sums over elements, exact.
///
/// 2. The energy balance with the load's work. With the massless contact row S₀·U = F₀ − λ holding at
///    both levels, Crank–Nicolson's rows of inertia, M̄(Vⁿ⁺¹ − Vⁿ) = (Δt/2)(−S(Uⁿ + Uⁿ⁺¹) + Fⁿ + Fⁿ⁺¹)
///    with V̄ = (Uⁿ⁺¹ − Uⁿ)/Δt, dotted with Uⁿ⁺¹ − Uⁿ and added to row 0 times Δu₀, give
///
///        Eⁿ⁺¹ − Eⁿ = ½(Fⁿ + Fⁿ⁺¹)·(Uⁿ⁺¹ − Uⁿ) − ½(λⁿ + λⁿ⁺¹)(u₀ⁿ⁺¹ − u₀ⁿ),   E = ½VᵀMV + ½UᵀSU,
///
///    and the last term vanishes on every step without a change of the contact status (free: λ = 0;
///    in contact: u₀ = −gap at both levels). On any mesh, material and far end.
///
/// 3. Rigid motion of a free bar (free far end). A rigid translation U = c(t)·1 has SU = 0. Under a
///    constant f the load vector is F = f·m with m_i = ∫ρφ_i... here f is a force per unit length on
///    a bar of ρ = 1, so F_i = f ∫φ_i = f (h_{i−1} + h_i)/2, the row sums of the consistent mass. A mass
///    M̄ then carries the free fall c'' = f exactly iff its row sums, with the contact row folded in,
///    equal F: node 0 is massless and quasi-static, (u₀ − u₁)/h₀ = F₀ (its own element hangs, u₀ =
///    u₁ + h₀F₀), and passes F₀ to node 1, whose row then needs M̄₁₁ + M̄₁₂ = (F₀ + F₁)/f = h₀ + h₁/2.
///    Mod 3 (M̄₁₁ = h₀ + h₁/3: the removed element's mass on node 1, PᵀMP) satisfies it on every mesh,
///    so a free bar under gravity falls rigidly (nodes ≥ 1) to round-off; Mod 1 (M̄₁₁ + M̄₁₂ = h₀/3 +
///    h₁/2) and Mod 2 (every row × w) do not: node 1 of Mod 1 overtakes the bar, the bar of Mod 2 falls
///    at f/w. Crank–Nicolson integrates c'' = f exactly (the trapezoidal rule is exact on the linear V).
///
/// 4. The gap closing. A free bar moving rigidly with velocity −v toward the obstacle across the gap g
///    (f = 0) has u₀ = −vt: the contact indicator u₀ + g + h₀λ is linear in t in free flight, so the
///    interpolated impact time is g/v to round-off, for every scheme (each integrates a uniform motion
///    exactly). Under gravity from rest, node 1 falls as f t²/2 and node 0 hangs h₀²|f|/2 below it: the
///    discrete gap closes at t* = √(2g/|f| − h₀²) (the continuum's √(2g/|f|) up to O(h₀²)), read off by
///    linear interpolation of a quadratic indicator: error ≤ |f|Δt²/(8|u̇₀(t*)|).
///    The impacting bar (Code_Aster SDNV100, dimensionless): after the impact, the end is held while
///    the compression wave runs to the free end and back, 2L/c, under the stress λ = −ρcv (= −v here),
///    and the bar leaves with velocity +v. The finite element run approximates both: duration within
///    O(h) of 2L, mean λ over the contact within O(h) of −v.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "measures/phase.hpp"
#include "time/schemes.hpp"

namespace mrm {

namespace {

[[maybe_unused]] SchemeParameters scheme(Scheme s) {
  SchemeParameters p;
  p.scheme = s;
  return p;
}

// The graded, layered mesh of the checks: r = 1.05, N = 20, the first 8 elements E = 4, ρ = 2 (a stiff,
// heavy layer at the contact), the rest E = ρ = 1.
[[maybe_unused]] UniformMesh layered_mesh(FarEnd far_end = FarEnd::clamped) {
  std::vector<double> young(20, 1.0), density(20, 1.0);
  for (int e = 0; e < 8; ++e) young[e] = 4.0, density[e] = 2.0;
  return with_far_end(with_material(graded_mesh(1.0, 20, 1.05), young, density), far_end);
}

// ∫₀ˣ s^k / E(s) ds at a node x_i (k = 0, 1), exact element by element.
[[maybe_unused]] double compliance_moment(const UniformMesh& mesh, Index i, int k) {
  double sum = 0;
  for (Index e = 0; e < i; ++e) {
    const double a = mesh.x(e), b = mesh.x(e + 1);
    sum += (k == 0 ? b - a : 0.5 * (b * b - a * a)) / mesh.young(e);
  }
  return sum;
}

}  // namespace

TEST_CASE("static solutions under a constant load are fixed points of every scheme, on graded layered meshes") {
  struct Case {
    UniformMesh mesh;
    double f, gap;
  };
  const Case cases[] = {{UniformMesh(1.0, 16), 0.8, 0.0},
                        {UniformMesh(1.0, 16), -0.8, 0.0},
                        {layered_mesh(), 0.8, 0.0},
                        {layered_mesh(), -0.8, 0.0},
                        {layered_mesh(), -0.8, 0.05}};
  double largest_drift = 0, largest_lambda_error = 0;
  for (const Case& c : cases) {
    const UniformMesh& mesh = c.mesh;
    const Index n = mesh.elements;
    const double L = mesh.length, f = c.f;
    const bool contact = f < 0;
    // The closed forms of the derivation (1): C from u(L) = 0 in contact.
    const double c_contact = (c.gap + f * compliance_moment(mesh, n, 1)) / compliance_moment(mesh, n, 0);
    const auto exact = [&](Index i) {
      if (contact) return -c.gap + c_contact * compliance_moment(mesh, i, 0) - f * compliance_moment(mesh, i, 1);
      return f * (compliance_moment(mesh, n, 1) - compliance_moment(mesh, i, 1));
    };
    Problem problem = benchmark_problem();
    problem.gap = c.gap;
    problem.load = [f](double, double) { return f; };
    // u⁰ is the P1 interpolant of the nodal values: the mesh's nodes are looked up.
    problem.initial_displacement = [&mesh, &exact](double x) {
      for (Index i = 0; i <= mesh.elements; ++i)
        if (x == mesh.x(i)) return exact(i);
      return std::nan("");
    };
    for (const Scheme s :
         {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman, Scheme::switching}) {
      for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
        BarSimulation run_(problem, mesh, mass, scheme(s), 0.3 * mesh.h(0));
        double drift = 0, worst_lambda = 0;
        for (int k = 0; k < 200; ++k) {
          run_.step();
          const Sample smp = run_.sample();
          for (Index i = 0; i < n; ++i) drift = std::max(drift, std::abs((*smp.displacement)[i] - exact(i)));
          worst_lambda = std::max(worst_lambda, std::abs(smp.multiplier - (contact ? c_contact : 0.0)));
        }
        CAPTURE(c.f);
        CAPTURE(c.gap);
        CAPTURE(mesh.uniform());
        CAPTURE(to_string(s));
        CAPTURE(mass.name);
        CAPTURE(c_contact);
        // Round-off: the displacements are O(1), the forces of row 0 O(E₀/h₀) times them.
        CHECK(drift <= 1e-12);
        CHECK(worst_lambda <= 1e-10);
        largest_drift = std::max(largest_drift, drift);
        largest_lambda_error = std::max(largest_lambda_error, worst_lambda);
      }
    }
    if (contact) {
      MESSAGE("static contact: lambda = C = " << c_contact << " (uniform: fL/2 = " << f * L / 2 << ")");
      if (mesh.uniform()) CHECK(std::abs(c_contact - f * L / 2) < 1e-14);
    }
  }
  MESSAGE("static solutions, 200 steps, 4 schemes x 3 masses x 5 cases: max |U^n - U*| = "
          << largest_drift << ", max |lambda^n - C| = " << largest_lambda_error);
}

TEST_CASE("Crank–Nicolson's energy changes by the work of the load on every step without a status change") {
  // Derivation (2): ΔE = ½(Fⁿ + Fⁿ⁺¹)·ΔU exactly away from status changes, for a time-dependent load,
  // a gap, graded layered meshes with either far end. Round-off: a few ε times the sizes of the terms.
  double largest = 0;
  for (const FarEnd far_end : {FarEnd::clamped, FarEnd::free}) {
    for (const bool graded : {false, true}) {
      const UniformMesh mesh = graded ? layered_mesh(far_end) : with_far_end(UniformMesh(1.0, 20), far_end);
      Problem problem = benchmark_problem();
      problem.gap = 0.02;
      problem.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
      for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
        for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference}) {
          SchemeParameters p;
          p.kernel = kernel;
          BarSimulation run_(problem, mesh, mass, p, 0.5 * mesh.h(0));
          const auto load = [&](double t) { return p1_load(mesh, [&](double x) { return problem.load(x, t); }); };
          int checked = 0, changes = 0;
          double worst = 0;
          for (int k = 0; k < 400; ++k) {
            const Sample before = run_.sample();
            const Eigen::VectorXd u = *before.displacement;
            const double e = before.energy, lambda = before.multiplier;
            run_.step();
            const Sample after = run_.sample();
            const Eigen::VectorXd& u_next = *after.displacement;
            if ((lambda < 0) != (after.multiplier < 0) || (k == 0)) {
              ++changes;
              continue;
            }
            const double work = 0.5 * (load(before.time) + load(after.time)).dot(u_next - u);
            worst = std::max(worst, std::abs(after.energy - e - work));
            ++checked;
          }
          CAPTURE(far_end == FarEnd::free);
          CAPTURE(graded);
          CAPTURE(mass.name);
          CAPTURE(to_string(kernel));
          CAPTURE(worst);
          CHECK(worst <= 1e-12);
          largest = std::max(largest, worst);
          CHECK(checked > 300);
          CHECK(changes >= 2);  // the run does hit the obstacle (the checks see contact and free steps)
        }
      }
    }
  }
  MESSAGE("CN energy balance with the load's work: max |dE - F.dU| = " << largest);
}

TEST_CASE("a free bar under gravity falls rigidly with Mod 3 (any mesh), not with Mod 1 or Mod 2") {
  const double g = 10.0, dt_factor = 0.5, horizon = 0.5;
  for (const bool graded : {false, true}) {
    const UniformMesh mesh = graded ? with_far_end(graded_mesh(1.0, 20, 1.05), FarEnd::free)
                                    : with_far_end(UniformMesh(1.0, 20), FarEnd::free);
    Problem problem = benchmark_problem();
    problem.initial_displacement = [](double) { return 0.0; };
    problem.gap = 10.0;  // far away: no contact within the horizon
    problem.load = [g](double, double) { return -g; };
    const double h0 = mesh.h(0), dt = dt_factor * h0;
    for (const MassRedistribution& mass : {mod3(), consistent_mass(), mod1(), mod2()}) {
      BarSimulation run_(problem, mesh, mass, SchemeParameters{}, dt);
      double worst = 0, offset = 0;
      run(run_, steps_to_reach(horizon, dt), [&](const Sample& s) {
        const double fall = -0.5 * g * s.time * s.time;
        for (Index i = 1; i < mesh.unknowns(); ++i) worst = std::max(worst, std::abs((*s.displacement)[i] - fall));
        offset = (*s.displacement)[0] - (*s.displacement)[1];
      });
      CAPTURE(graded);
      CAPTURE(mass.name);
      CAPTURE(worst);
      MESSAGE(std::string(graded ? "graded " : "uniform ")
              << mass.name << ": max |u_i - (-g t^2/2)| over t <= 0.5 = " << worst);
      if (mass.name == "mod3" || mass.name == "consistent") {
        CHECK(worst <= 1e-12);
        // node 0 hangs below node 1 by h₀²g/2 (massless: its row is quasi-static); with inertia, 0.
        if (mass.name == "mod3") CHECK(std::abs(offset + 0.5 * g * h0 * h0) <= 1e-14);
      } else {
        CHECK(worst > 1e-4);  // Mod 1's node 1 and Mod 2's whole bar leave the rigid fall
      }
    }
  }
}

TEST_CASE("the gap closes at the free-flight time, and the impacting bar stays in contact for about 2L/c") {
  // Rigid approach at speed v across the gap (derivation 4), the paper's schemes and EC (the contact
  // classes: contact_classes.cpp's doctests): on every free level the contact indicator u₀ + gap is
  // gap − vt to round-off, and the contact starts at the first level at or after g/v. (The detector's interpolation uses the first
  // contact level, whose node 1 already carries the contact force: the free levels are what is exact.)
  const double v = 0.5, gap = 0.13;
  const UniformMesh mesh = with_far_end(UniformMesh(1.0, 40), FarEnd::free);
  Problem problem = benchmark_problem();
  problem.initial_displacement = [](double) { return 0.0; };
  problem.initial_velocity = [v](double) { return -v; };
  problem.gap = gap;
  const double h = mesh.h(), dt = 0.5 * h;
  for (const Scheme s : {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman, Scheme::switching,
                         Scheme::energy_conserving}) {
    for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
      BarSimulation run_(problem, mesh, mass, scheme(s), dt);
      std::vector<double> contact_times, lambdas;
      double worst_free = 0, last_free = 0;
      run(run_, steps_to_reach(3.0, dt), [&](const Sample& smp) {
        const double indicator = (*smp.displacement)[0] + gap;
        if (contact_times.empty() && indicator > 0) {
          worst_free = std::max(worst_free, std::abs(indicator - (gap - v * smp.time)));
          last_free = smp.time;
        }
        if (smp.has_multiplier && smp.multiplier < 0)
          contact_times.push_back(smp.time), lambdas.push_back(smp.multiplier);
      });
      REQUIRE(!contact_times.empty());
      CAPTURE(to_string(s));
      CAPTURE(mass.name);
      CAPTURE(worst_free);
      CHECK(worst_free <= 1e-14);
      CHECK(last_free < gap / v);
      CHECK(contact_times.front() >= gap / v - 1e-12);
      CHECK(contact_times.front() - dt <= last_free + 1e-12);  // no level skipped between them
      if (s == Scheme::crank_nicolson) {
        // SDNV100 in dimensionless form: contact for 2L/c = 2, under λ = −ρcv = −v.
        const double duration = contact_times.back() - contact_times.front() + dt;
        double mean = 0;
        for (double l : lambdas) mean += l / static_cast<double>(lambdas.size());
        MESSAGE("impacting bar, CN, " << mass.name << ", N = 40: contact duration " << duration << " (2L/c = 2), mean "
                                      << "lambda " << mean << " (-v = " << -v << ")");
        CHECK(std::abs(duration - 2.0) <= 4 * h);
        CHECK(std::abs(mean + v) <= 0.1 * v);
      }
    }
  }
  problem.gap = -0.1;
  CHECK_THROWS_WITH_AS(BarSimulation(problem, mesh, mod3(), SchemeParameters{}, dt),
                       doctest::Contains("gap: the initial gap must be finite and >= 0"), InvalidParameter);

  // Free fall across the gap from rest (the bouncing bar's first flight), Mod 3: on every free level
  // u₀ + gap = gap − |f|t²/2 − |f|h₀²/2 to round-off, and the contact starts at the first level at or
  // after t* = √(2 gap/|f| − h₀²), on a uniform and a graded mesh.
  for (const bool graded : {false, true}) {
    const UniformMesh m = graded ? with_far_end(graded_mesh(1.0, 30, 1.04), FarEnd::free)
                                 : with_far_end(UniformMesh(1.0, 30), FarEnd::free);
    const double g = 10.0, drop = 0.05, h0 = m.h(0), step = 0.25 * h0;
    Problem falling = benchmark_problem();
    falling.initial_displacement = [](double) { return 0.0; };
    falling.load = [g](double, double) { return -g; };
    falling.gap = drop;
    BarSimulation run_(falling, m, mod3(), SchemeParameters{}, step);
    double worst_free = 0, last_free = 0, first_contact = -1;
    run(run_, steps_to_reach(0.2, step), [&](const Sample& smp) {
      const double indicator = (*smp.displacement)[0] + drop;
      if (first_contact < 0 && indicator > 0) {
        worst_free = std::max(worst_free, std::abs(indicator - (drop - 0.5 * g * (smp.time * smp.time + h0 * h0))));
        last_free = smp.time;
      } else if (first_contact < 0) {
        first_contact = smp.time;
      }
    });
    const double t_star = std::sqrt(2 * drop / g - h0 * h0);
    CAPTURE(graded);
    CAPTURE(worst_free);
    CAPTURE(t_star);
    CHECK(worst_free <= 1e-14);
    CHECK(last_free < t_star);
    CHECK(first_contact >= t_star - 1e-12);
    CHECK(first_contact - step <= last_free + 1e-12);
    MESSAGE(std::string(graded ? "graded" : "uniform")
            << " free fall: t* = " << t_star << " (continuum sqrt(2 gap/g) = " << std::sqrt(2 * drop / g)
            << "), contact from level t = " << first_contact);
  }
}

}  // namespace mrm
