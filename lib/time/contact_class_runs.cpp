/// @file contact_class_runs.cpp
/// @brief The doctests that run the contact classes (classes/contact_classes.cpp, newmark_type.cpp,
/// moreau_jean.cpp, dke.cpp) through a run (BarSimulation): their limit cases, their energy identities,
/// the load and the gap, the fused steps against the readable ones, and two bars by symmetry. They sit
/// above the classes they check because a run is built on the registry of every family.
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

#include "classes/contact_classes.hpp"
#include "classes/step_pieces.hpp"
#include "fem/mass_redistribution.hpp"
#include "time/two_bodies.hpp"

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// Doctests: the limit cases and the energy identities of the derivation above, on the library's runs.
namespace {

// The identity (MJ) of Moreau–Jean checked at every step of `run` up to `horizon`: E changes by
// p(θv₀ⁿ⁺¹ + (1 − θ)v₀ⁿ) − (θ − ½)(‖ΔV‖²_M + ‖ΔU‖²_S), plus the load's work F·ΔU for a load constant in time
// (`load` empty: none). Returns the largest defect and the number of steps with an impulse.
[[maybe_unused]] std::pair<double, int> moreau_jean_identity(BarSimulation& run, double theta,
                                                             const Eigen::VectorXd& load, double horizon) {
  const Tridiagonal& m = run.mass();
  const Tridiagonal& s = run.stiffness();
  const double dt = run.dt();
  double worst = 0;
  int impulses = 0;
  for (Index n = 0; n < steps_to_reach(horizon, dt); ++n) {
    const Eigen::VectorXd u = *run.sample().displacement, v = *run.sample().velocity;
    const double energy = run.sample().energy;
    run.step();
    const Eigen::VectorXd du = *run.sample().displacement - u, dv = *run.sample().velocity - v;
    const double impulse = -run.sample().multiplier * dt;
    const double predicted = impulse * (theta * (*run.sample().velocity)[0] + (1 - theta) * v[0]) -
                             (theta - 0.5) * (m.bilinear(dv, dv) + s.bilinear(du, du)) +
                             (load.size() > 0 ? load.dot(du) : 0.0);
    worst = std::max(worst, std::abs(run.sample().energy - energy - predicted));
    impulses += impulse > 0;
  }
  return {worst, impulses};
}

// The largest difference of the displacements of two runs over `steps` steps.
[[maybe_unused]] double largest_difference(BarSimulation& a, BarSimulation& b, Index steps) {
  double difference = 0;
  for (Index k = 0; k < steps; ++k) {
    a.step();
    b.step();
    difference = std::max(difference, (*a.sample().displacement - *b.sample().displacement).cwiseAbs().maxCoeff());
  }
  return difference;
}

}  // namespace

TEST_CASE("Newmark (1/4, 1/2) with exact enforcement is Crank-Nicolson, with and without inertia at the contact node") {
  // The derivation: the first line of (N) with β = ¼ is Crank–Nicolson's (★) row for row; the
  // velocities agree on the rows with inertia (the massless node's is BarSimulation's in both). With a
  // massless node, over three periods (impacts and releases included) the runs agree to round-off: a few
  // ε|U| per step, K = 720 steps. With the consistent mass the contact node chatters after the first impact
  // (u₀ = 0 and u₀ > 0 alternate every few steps) and each contact step turns a perturbation δu₀ into
  // δλ ≈ δu₀/(Δt²/4 (A⁻¹)₀₀), so round-off grows from step to step (measured: 1e-15 at t = 1, 1e-11 at
  // t = 1.5, 0.07 at t = 9): compared over [0, 1.5], at 1e-10.
  const UniformMesh mesh(1.0, 40);
  const double dt = 0.5 * mesh.h();
  for (const MassRedistribution& mass : {consistent_mass(), mod3(), mod1()}) {
    BarSimulation cn(benchmark_problem(), mesh, mass, SchemeParameters(), dt);
    BarSimulation newmark(benchmark_problem(), mesh, mass, class_parameters(Scheme::newmark), dt);
    double difference = 0, lambda_difference = 0, velocity_difference = 0;
    const bool inertial = mass.name == "consistent";
    for (Index k = 0; k < steps_to_reach(inertial ? 1.5 : 9.0, dt); ++k) {
      cn.step();
      newmark.step();
      difference =
          std::max(difference, (*cn.sample().displacement - *newmark.sample().displacement).cwiseAbs().maxCoeff());
      velocity_difference =
          std::max(velocity_difference, (*cn.sample().velocity - *newmark.sample().velocity).cwiseAbs().maxCoeff());
      lambda_difference = std::max(lambda_difference, std::abs(cn.sample().multiplier - newmark.sample().multiplier));
    }
    CAPTURE(mass.name);
    CHECK(difference <= (inertial ? 1e-10 : 1e-12));
    CHECK(velocity_difference <= 1e-8);  // ε|U|/Δt per step, and the chatter's growth
    CHECK(lambda_difference <= 1e-6);    // the multiplier carries 1/(βΔt²) ≈ 6400 with inertia
    CHECK(std::abs(cn.sample().energy - newmark.sample().energy) <= (inertial ? 1e-10 : 1e-12));
  }
}

TEST_CASE(
    "Newmark with beta = 0 is explicit: central differences for gamma = 1/2, the exact row refused with inertia") {
  // γ = ½: Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹ = Δt² M⁻¹ Rⁿ, Rⁿ = −SUⁿ − λⁿe₀ (the file comment), checked as
  // M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹) + Δt²(SUⁿ + λⁿe₀) = 0 on the penalty's run with the consistent mass, through impacts.
  const UniformMesh mesh(1.0, 20);
  const double dt = 0.002;
  const Tridiagonal m = modified_mass(mesh, consistent_mass()), s = p1_stiffness(mesh);
  BarSimulation run(benchmark_problem(), mesh, consistent_mass(), class_parameters(Scheme::penalty, 0.0), dt);
  Eigen::VectorXd before = *run.sample().displacement;
  run.step();
  Eigen::VectorXd now = *run.sample().displacement;
  double lambda = run.sample().multiplier, worst = 0;
  int contact_levels = 0;
  for (Index k = 0; k < 3000; ++k) {
    run.step();
    const Eigen::VectorXd& after = *run.sample().displacement;
    Eigen::VectorXd residual = m * (after - 2 * now + before) + dt * dt * (s * now);
    residual[0] += dt * dt * lambda;
    worst = std::max(worst, residual.cwiseAbs().maxCoeff());
    contact_levels += lambda < 0;
    before = now;
    now = after;
    lambda = run.sample().multiplier;
  }
  CAPTURE(worst);
  CHECK(worst <= 1e-15);  // a few ε of the O(h) entries of MU
  CHECK(contact_levels > 100);
  CHECK_THROWS_WITH_AS(
      BarSimulation(benchmark_problem(), mesh, consistent_mass(), class_parameters(Scheme::newmark, 0.0), dt),
      doctest::Contains("newmark_beta: 0 with exact enforcement"), InvalidParameter);
  // With a massless contact node the explicit step exists: the contact row is algebraic at every level.
  BarSimulation massless(benchmark_problem(), mesh, mod3(), class_parameters(Scheme::newmark, 0.0), dt);
  for (Index k = 0; k < 3000; ++k) {
    massless.step();
    const Sample s0 = massless.sample();
    const double u0 = (*s0.displacement)[0], u1 = (*s0.displacement)[1];
    CHECK(u0 >= 0);
    CHECK(std::abs(u0 - std::max(0.0, u1)) <= 1e-15);  // u₀ = max(0, u₁) (the algebraic row, f = 0)
  }
}

TEST_CASE(
    "penalty with Newmark (1/4, 1/2): the energy identity (E) at every step, E + Phi conserved away from the kink") {
  // (E): Eⁿ⁺¹ + Φⁿ⁺¹ − Eⁿ − Φⁿ = 0 when u₀ⁿ, u₀ⁿ⁺¹ lie on the same side of 0; across it −½(γ₀/h)|ab| at
  // an impact (a = u₀ⁿ > 0 > b = u₀ⁿ⁺¹), +½(γ₀/h)|ab| at a release. The library's energy is E + Φ.
  // Round-off: a few ε E per step.
  for (const MassRedistribution& mass : {consistent_mass(), mod3()}) {
    for (const double gamma0 : {1.0, 100.0}) {
      const UniformMesh mesh(1.0, 30);
      const double dt = 0.5 * mesh.h(), k = gamma0 / mesh.h();
      SchemeParameters p = class_parameters(Scheme::penalty);
      p.penalty = gamma0;
      BarSimulation run(benchmark_problem(), mesh, mass, p, dt);
      double worst = 0;
      int crossings = 0;
      for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
        const double a = (*run.sample().displacement)[0], e = run.sample().energy;
        run.step();
        const double b = (*run.sample().displacement)[0];
        const double defect = (a < 0) != (b < 0) ? 0.5 * k * std::abs(a * b) * (a < 0 ? 1 : -1) : 0.0;
        crossings += (a < 0) != (b < 0);
        worst = std::max(worst, std::abs(run.sample().energy - e - defect));
      }
      CAPTURE(mass.name);
      CAPTURE(gamma0);
      CHECK(worst <= 1e-14);
      CHECK(crossings >= 4);  // penetrations entered and left
    }
  }
}

TEST_CASE("penalty and Nitsche tend to exact enforcement as gamma0 grows, at the rate 1/gamma0") {
  // The penalty's penetration is O(h|λ|/γ₀) and the run's distance to the exact-enforcement run (both
  // Newmark (¼, ½), consistent mass) is its consequence: ×100 in γ₀ should divide it by about 100.
  // Measured ratios 70–130 admitted (the distance also carries the O(Δt) shift of the impact times).
  const UniformMesh mesh(1.0, 20);
  const double dt = 0.5 * mesh.h();
  for (const Scheme scheme : {Scheme::penalty, Scheme::nitsche}) {
    double previous = 0;
    for (const double gamma0 : {1e4, 1e6}) {
      SchemeParameters p = class_parameters(scheme);
      (scheme == Scheme::penalty ? p.penalty : p.nitsche_gamma) = gamma0;
      BarSimulation exact(benchmark_problem(), mesh, consistent_mass(), class_parameters(Scheme::newmark), dt);
      BarSimulation run(benchmark_problem(), mesh, consistent_mass(), p, dt);
      const double distance = largest_difference(exact, run, steps_to_reach(3.0, dt));
      CAPTURE(to_string(scheme));
      CAPTURE(gamma0);
      CAPTURE(distance);
      CHECK(distance < 1e-2);
      if (previous > 0) {
        CHECK(previous / distance > 70);
        CHECK(previous / distance < 130);
      }
      previous = distance;
    }
  }
}

TEST_CASE("Nitsche with theta = 1 is a gradient: Newmark (1/4, 1/2) conserves E + Phi away from the status changes") {
  const UniformMesh mesh(1.0, 30);
  const double dt = 0.5 * mesh.h();
  SchemeParameters p = class_parameters(Scheme::nitsche);
  p.nitsche_theta = 1.0;
  BarSimulation run(benchmark_problem(), mesh, consistent_mass(), p, dt);
  double worst = 0;
  int same = 0;
  for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
    const double e = run.sample().energy;
    const bool active = run.sample().multiplier < 0;
    run.step();
    if (active == (run.sample().multiplier < 0)) {
      worst = std::max(worst, std::abs(run.sample().energy - e));
      ++same;
    }
  }
  CHECK(worst <= 1e-13);
  CHECK(same > 500);
}

TEST_CASE("Moreau-Jean: the identity (MJ) at every step, and theta = 1/2, e = 1 conserves E") {
  const UniformMesh mesh(1.0, 30);
  const double dt = 0.5 * mesh.h();
  for (const double theta : {0.5, 0.75}) {
    for (const double e : {1.0, 0.5, 0.0}) {
      SchemeParameters p = class_parameters(Scheme::moreau_jean);
      p.moreau_theta = theta;
      p.restitution = e;
      BarSimulation run(benchmark_problem(), mesh, consistent_mass(), p, dt);
      const auto [worst, impulses] = moreau_jean_identity(run, theta, Eigen::VectorXd(), 9.0);
      CAPTURE(theta);
      CAPTURE(e);
      CHECK(worst <= 1e-14);
      CHECK(impulses >= 3);
      if (theta == 0.5 && e == 1.0) CHECK(std::abs(run.sample().energy - 0.125) <= 1e-13);
    }
  }
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), class_parameters(Scheme::moreau_jean), dt),
                       doctest::Contains("mass: moreau-jean needs a contact node with inertia"), InvalidParameter);
}

TEST_CASE("the contact classes refuse meaningless parameters, naming them") {
  const UniformMesh mesh(1.0, 10);
  const auto refused = [&](const SchemeParameters& p) {
    try {
      BarSimulation(benchmark_problem(), mesh, consistent_mass(), p, 0.01);
    } catch (const InvalidParameter& e) {
      return e.parameter;
    }
    return std::string("accepted");
  };
  SchemeParameters p = class_parameters(Scheme::penalty);
  for (const double g : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    p.penalty = g;
    CHECK(refused(p) == "penalty");
  }
  p = class_parameters(Scheme::nitsche);
  p.nitsche_gamma = 0;
  CHECK(refused(p) == "nitsche_gamma");
  p = class_parameters(Scheme::nitsche);
  p.nitsche_theta = 1.5;
  CHECK(refused(p) == "nitsche_theta");
  p.nitsche_theta = 1.0;
  p.nitsche_gamma = 0.5;  // θ ≥ γ₀: the first element's stiffness (1 − θ/γ₀)/h < 0
  CHECK(refused(p) == "nitsche_theta");
  p = class_parameters(Scheme::newmark, 0.25, 0.4);
  CHECK(refused(p) == "newmark_gamma");
  p = class_parameters(Scheme::newmark, -0.1);
  CHECK(refused(p) == "newmark_beta");
  p = class_parameters(Scheme::moreau_jean);
  p.moreau_theta = 0.4;
  CHECK(refused(p) == "moreau_theta");
  p.moreau_theta = 0.5;
  p.restitution = 1.1;
  CHECK(refused(p) == "restitution");
  p = class_parameters(Scheme::penalty);
  p.restitution = 0.5;  // the penalty takes no restitution
  CHECK(refused(p) == "restitution");
  p = SchemeParameters();
  p.penalty = 3;  // Crank–Nicolson takes no penalty
  CHECK(refused(p) == "penalty");
  CHECK(refused(class_parameters(Scheme::nitsche)) == "accepted");
}

TEST_CASE(
    "Paoli-Schatzman with restitution: the literal row with a massless node is refused for e > 0, the sound forms "
    "run") {
  // schemes.cpp (the constructor): the literal row's obstacle −e u₀ⁿ⁻¹ on a massless node grows without
  // bound (E = 7e9 at e = ½, N = 100, T = 30). The algebraic row and the consistent mass (literal row)
  // keep E bounded; there is no proved bound (the three-level energy is not E), so the check is that E stays
  // within 10 % of E₀ over 10 periods at N = 40, c = ½, e = 1 (measured: 4.4 % consistent, 3.7 % Mod 3).
  const UniformMesh mesh(1.0, 40);
  const double dt = 0.5 * mesh.h();
  SchemeParameters p;
  p.scheme = Scheme::paoli_schatzman;
  p.restitution = 1.0;
  p.contact_row = ContactRow::literal;
  CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, dt),
                       doctest::Contains("restitution: above 0 with the literal"), InvalidParameter);
  for (const bool consistent : {true, false}) {
    p.contact_row = consistent ? ContactRow::literal : ContactRow::algebraic;
    BarSimulation run(benchmark_problem(), mesh, consistent ? consistent_mass() : mod3(), p, dt);
    double largest = 0;
    int impacts = 0;
    bool active = false;
    for (Index n = 0; n < steps_to_reach(30.0, dt); ++n) {
      run.step();
      largest = std::max(largest, std::abs(run.sample().energy / 0.125 - 1));
      impacts += !active && run.sample().multiplier < 0;
      active = run.sample().multiplier < 0;
    }
    CAPTURE(consistent);
    CHECK(largest < 0.1);
    CHECK(impacts >= 10);
  }
}

}  // namespace mrm

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// Doctests of "The load and the gap".

namespace {

// The doctests' pressed bar: the paper's bar pressed toward the obstacle by f = −1 (gravity-paper's kind)
// across a gap g₀ = 0.05, N = 30, Δt = h/2 (impacts, a persistent contact phase and releases), with the
// P1 load vector F of f (constant in time: Fⁿ = Fⁿ⁺¹ = F).
struct PressedBar {
  UniformMesh mesh{1.0, 30};
  double dt = 0.5 * mesh.h(), gap = 0.05;
  Problem problem = benchmark_problem();
  Eigen::VectorXd f;
  PressedBar() {
    problem.load = [](double, double) { return -1.0; };
    problem.gap = gap;
    p1_load(
        mesh, [](double) { return -1.0; }, f);
  }
};

}  // namespace

TEST_CASE(
    "a constant load without contact: the contact classes' free fall (exact for Newmark, (theta - 1/2) g dt t off for "
    "Moreau-Jean)") {
  // A bar free at both ends, at rest, under f = −g, the obstacle far below (g₀ = 1, the fall is 0.45 by
  // T = 0.3). The exact nodal motion is the rigid fall U = −gt²/2 (M·1 times −g is the consistent load
  // vector; with Mod 3 on the rows with mass, and node 0 hangs h²g/2 below node 1 on its algebraic row).
  const double g = 10.0, final_time = 0.3;
  const UniformMesh mesh = with_far_end(UniformMesh(1.0, 20), FarEnd::free);
  const double h = mesh.h(), dt = 0.25 * h;
  Problem falling = benchmark_problem();
  falling.initial_displacement = [](double) { return 0.0; };
  falling.load = [g](double, double) { return -g; };
  falling.gap = 1.0;
  struct Case {
    Scheme scheme;
    double beta;
    MassRedistribution mass;
  };
  for (const Case& c : {Case{Scheme::newmark, 0.25, consistent_mass()}, Case{Scheme::newmark, 0.25, mod3()},
                        Case{Scheme::newmark, 0.0, mod3()}, Case{Scheme::penalty, 0.25, consistent_mass()},
                        Case{Scheme::penalty, 0.0, consistent_mass()}, Case{Scheme::penalty, 0.25, mod3()},
                        Case{Scheme::nitsche, 0.25, consistent_mass()}, Case{Scheme::nitsche, 0.0, mod3()},
                        Case{Scheme::newmark, 0.3, consistent_mass()}}) {
    BarSimulation simulation(falling, mesh, c.mass, class_parameters(c.scheme, c.beta), dt);
    const bool massless = simulation.massless_contact_node();
    double worst = 0, hang = 0;
    run(simulation, steps_to_reach(final_time, dt), [&](const Sample& s) {
      const double exact = -0.5 * g * s.time * s.time;
      for (Index i = massless ? 1 : 0; i < s.displacement->size(); ++i)
        worst = std::max(worst, std::abs((*s.displacement)[i] - exact));
      if (massless) hang = std::max(hang, std::abs((*s.displacement)[0] - (*s.displacement)[1] + 0.5 * g * h * h));
      CHECK(s.multiplier == 0.0);
    });
    CAPTURE(to_string(c.scheme));
    CAPTURE(c.beta);
    CAPTURE(c.mass.name);
    CHECK(worst <= 1e-13);  // a few ε of |U| ≤ 0.45 per step, 240 steps
    CHECK(hang <= 1e-14);
  }
  // Moreau–Jean: Uⁿ = −gtₙ²/2 − (θ − ½)gΔt tₙ on every node.
  for (const double theta : {0.5, 0.75, 1.0}) {
    SchemeParameters p = class_parameters(Scheme::moreau_jean);
    p.moreau_theta = theta;
    BarSimulation simulation(falling, mesh, consistent_mass(), p, dt);
    double worst = 0;
    run(simulation, steps_to_reach(final_time, dt), [&](const Sample& s) {
      const double predicted = -0.5 * g * s.time * s.time - (theta - 0.5) * g * dt * s.time;
      worst = std::max(worst, (s.displacement->array() - predicted).abs().maxCoeff());
    });
    CAPTURE(theta);
    CHECK(worst <= 1e-13);
  }
}

TEST_CASE(
    "the energy identity with the load's work: (EF) for the penalty and Nitsche, (MJ) + F_theta.dU for Moreau-Jean") {
  // The pressed bar (PressedBar). At every step, E + Φ changes by the load's work W = ½(Fⁿ + Fⁿ⁺¹)·ΔU
  // plus the kink's defect ∓½(γ₀/h)|ab| (penalty, a = u₀ⁿ + g₀, b = u₀ⁿ⁺¹ + g₀ of opposite signs);
  // Nitsche θ = 1 on steps without a status change by W alone; Moreau–Jean by (MJ) plus F_θ·ΔU.
  // Round-off: a few ε E per step.
  const PressedBar bar;
  const UniformMesh& mesh = bar.mesh;
  const Problem& pressed = bar.problem;
  const Eigen::VectorXd& f = bar.f;
  const double dt = bar.dt, gap = bar.gap, k = 1.0 / mesh.h();
  for (const MassRedistribution& mass : {consistent_mass(), mod3()}) {
    BarSimulation run(pressed, mesh, mass, class_parameters(Scheme::penalty), dt);
    double worst = 0;
    int crossings = 0, contact_levels = 0;
    for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
      const Eigen::VectorXd u = *run.sample().displacement;
      const double e = run.sample().energy, a = u[0] + gap;
      run.step();
      const Eigen::VectorXd& u_next = *run.sample().displacement;
      const double b = u_next[0] + gap;
      const double defect = (a < 0) != (b < 0) ? 0.5 * k * std::abs(a * b) * (a < 0 ? 1 : -1) : 0.0;
      const double work = f.dot(u_next - u);
      crossings += (a < 0) != (b < 0);
      contact_levels += b < 0;
      worst = std::max(worst, std::abs(run.sample().energy - e - work - defect));
    }
    CAPTURE(mass.name);
    CHECK(worst <= 1e-14);
    CHECK(crossings >= 2);
    CHECK(contact_levels > 100);  // the load holds the bar on the obstacle for a while
  }
  {
    SchemeParameters p = class_parameters(Scheme::nitsche);
    p.nitsche_theta = 1.0;
    BarSimulation run(pressed, mesh, consistent_mass(), p, dt);
    double worst = 0;
    int same = 0;
    for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
      const Eigen::VectorXd u = *run.sample().displacement;
      const double e = run.sample().energy;
      const bool active = run.sample().multiplier < 0;
      run.step();
      if (active == (run.sample().multiplier < 0)) {
        worst = std::max(worst, std::abs(run.sample().energy - e - f.dot(*run.sample().displacement - u)));
        ++same;
      }
    }
    CHECK(worst <= 1e-13);
    CHECK(same > 500);
  }
  for (const double theta : {0.5, 0.75}) {
    SchemeParameters p = class_parameters(Scheme::moreau_jean);
    p.moreau_theta = theta;
    p.restitution = 0.5;
    BarSimulation run(pressed, mesh, consistent_mass(), p, dt);
    const auto [worst, impulses] = moreau_jean_identity(run, theta, f, 9.0);
    CAPTURE(theta);
    CHECK(worst <= 1e-14);
    CHECK(impulses >= 3);
  }
}

// The fused steps (StepKernel::fast) against the readable ones (StepKernel::reference): every sample bit
// for bit (U, V, λ, E) at every step, for every contact class (newmark, penalty, nitsche, moreau-jean,
// dke), each mass it takes, with and without a load and a gap, β = 0 and ¼ for the Newmark family (θ = 0
// and 1 for Nitsche, θ = ½ and 1 with e = 0 and 1 for Moreau–Jean), over 1500 steps of the paper's
// benchmark (about ten impacts). A changed order of one operation fails it (checked: (MUⁿ)_i + (Δt(MVⁿ)_i
// + Δt²(½ − β)Rⁿ_i) in the Newmark step failed every Newmark-family run; ΔtθV_i + Δt(1 − θ)Vⁿ_i in
// Moreau–Jean's failed its θ = ½ runs, where θ = 1 gives the same bits by either order).
TEST_CASE("the fused class steps are their readable steps, bit for bit") {
  const UniformMesh mesh(1.0, 24);
  const auto same_bits = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
  };
  const auto same_double = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  std::vector<SchemeParameters> cases;
  for (const Scheme scheme : {Scheme::newmark, Scheme::penalty, Scheme::nitsche})
    for (const double beta : {0.0, 0.25}) {
      SchemeParameters p = class_parameters(scheme, beta);
      if (scheme == Scheme::nitsche)
        for (const double theta : {0.0, 1.0}) {
          p.nitsche_theta = theta;
          cases.push_back(p);
        }
      else
        cases.push_back(p);
    }
  cases.push_back(class_parameters(Scheme::dke));
  for (const double theta : {0.5, 1.0})
    for (const double e : {0.0, 1.0}) {
      SchemeParameters p = class_parameters(Scheme::moreau_jean);
      p.moreau_theta = theta;
      p.restitution = e;
      cases.push_back(p);
    }
  int runs = 0, steps_compared = 0;
  for (SchemeParameters p : cases)
    for (const MassRedistribution& mass : {consistent_mass(), mod3()})
      for (const bool loaded : {false, true})
        for (const double gap : {0.0, 0.1}) {
          Problem problem = benchmark_problem();
          problem.gap = gap;
          if (loaded) problem.load = [](double x, double t) { return -0.5 + 0.3 * std::sin(3 * x + 5 * t); };
          const bool explicit_newmark = takes(p.scheme, SchemeParameter::newmark_beta) && p.newmark_beta == 0.0;
          const double dt = (explicit_newmark ? 0.2 : 0.5) * mesh.h();
          std::unique_ptr<BarSimulation> fused, readable;
          p.kernel = StepKernel::fast;
          try {
            fused = std::make_unique<BarSimulation>(problem, mesh, mass, p, dt);
          } catch (const InvalidParameter&) {
            continue;  // a class that refuses this mass, or β = 0 with exact enforcement and inertia
          }
          p.kernel = StepKernel::reference;
          readable = std::make_unique<BarSimulation>(problem, mesh, mass, p, dt);
          CAPTURE(to_string(p.scheme));
          CAPTURE(p.newmark_beta);
          CAPTURE(mass.name);
          CAPTURE(loaded);
          CAPTURE(gap);
          bool same = true;
          int contact_levels = 0;
          Index k = 0;
          for (; k <= 1500 && same; ++k) {
            if (k > 0) {
              fused->step();
              readable->step();
            }
            const Sample a = fused->sample(), b = readable->sample();
            same = same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                   same_double(a.multiplier, b.multiplier) && same_double(a.energy, b.energy);
            contact_levels += a.multiplier < 0;
          }
          CAPTURE(k);
          CHECK(same);
          CHECK(contact_levels > 10);  // the comparison passes through contact
          ++runs;
          steps_compared += static_cast<int>(k);
        }
  CHECK(runs >= 40);
  MESSAGE("fused against readable class steps: " << runs << " runs, " << steps_compared << " levels");
}

TEST_CASE("a gap shifts the first impact by gap/velocity, for every scheme of the registry") {
  // The paper's benchmark: the contact end flies at v = ½ (u(0, t) = ½ − t/2) until the first impact at
  // t = 1; with a gap g₀ it reaches −g₀ at 1 + 2g₀ (before t = 2, when the reflection from the clamp
  // arrives). The first level with contact (λ < 0, or an impulse) lies within a step or two of it: the
  // discrete end is not exactly at ½ − t/2 (the initial data's kink at x = 0), so 2Δt is allowed.
  const UniformMesh mesh(1.0, 40);
  const double dt = 0.5 * mesh.h();
  for (const SchemeInfo& info : scheme_registry()) {
    for (const MassRedistribution& mass : {consistent_mass(), mod3()}) {
      std::array<double, 2> first{};
      bool refused = false;
      for (const double gap : {0.0, 0.2}) {
        Problem problem = benchmark_problem();
        problem.gap = gap;
        SchemeParameters p;
        p.scheme = info.scheme;
        if (info.scheme == Scheme::paoli_schatzman && mass.name == "consistent") p.contact_row = ContactRow::literal;
        if (info.scheme == Scheme::newmark || info.scheme == Scheme::penalty || info.scheme == Scheme::nitsche)
          p.newmark_beta = 0.25;
        double t = -1;
        try {
          BarSimulation simulation(problem, mesh, mass, p, dt);
          for (Index n = 0; n < steps_to_reach(1.8, dt) && t < 0; ++n) {
            simulation.step();
            if (simulation.sample().multiplier < 0) t = simulation.sample().time;
          }
        } catch (const InvalidParameter& e) {
          CHECK(e.parameter == "mass");  // a class that needs the other kind of contact node: never the gap
          refused = true;
          break;
        }
        first[gap == 0.0 ? 0 : 1] = t;
      }
      if (refused) continue;
      CAPTURE(info.id);
      CAPTURE(mass.name);
      CAPTURE(first[0]);
      CAPTURE(first[1]);
      CHECK(std::abs(first[1] - 1.4) <= 2 * dt);
      CHECK(std::abs(first[1] - first[0] - 0.4) <= 2 * dt);
    }
  }
}

}  // namespace mrm

namespace mrm {

TEST_CASE("dke: (DKE) at every step, the energy never grows, no penetration at the levels, and its limit cases") {
  // The paper's benchmark with the consistent mass (the standard mass: the class's case), N = 40, Δt = h/2,
  // over three periods (impacts, contact phases, releases), without and with a gap g₀ = 0.2. At every step,
  // from the sample: α = max(0, −(w₀ + g₀))/(M⁻¹)₀₀ with W = Uⁿ + ΔtVⁿ (recomputed here from the definition,
  // M⁻¹e₀ by a dense solve), μ = 2(λⁿ⁺¹ + α/Δt²) (the reported stress, inverted), and then: μ ≤ 0,
  // μ(u₀ⁿ⁺¹ + g₀) = 0, u₀ⁿ⁺¹ + g₀ ≥ 0 (penetration zero at the levels, to round-off of O(1) values), and
  // Eⁿ⁺¹ − Eⁿ equal to (DKE)'s −(α²/2Δt²)(M⁻¹)₀₀ − (α/Δt²)gⁿ + (μ/2)gⁿ to round-off, each term ≤ 0, so
  // Eⁿ⁺¹ ≤ Eⁿ; at least one step with a projection (α > 0: an impact) and one with μ < 0.
  const UniformMesh mesh(1.0, 40);
  const double dt = 0.5 * mesh.h();
  const Tridiagonal m = modified_mass(mesh, consistent_mass());
  const Eigen::MatrixXd md = m.to_sparse().toDense();
  const Eigen::VectorXd column = md.llt().solve(Eigen::VectorXd::Unit(mesh.unknowns(), 0));  // M⁻¹e₀
  for (const double gap : {0.0, 0.2}) {
    Problem problem = benchmark_problem();
    problem.gap = gap;
    BarSimulation run(problem, mesh, consistent_mass(), class_parameters(Scheme::dke), dt);
    double worst_identity = 0, worst_penetration = 0, worst_complementarity = 0, largest_gain = -HUGE_VAL;
    double projection_loss = 0;
    int projections = 0, multipliers = 0;
    for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
      const Eigen::VectorXd u = *run.sample().displacement, v = *run.sample().velocity;
      const double e = run.sample().energy, g_now = u[0] + gap, w0 = u[0] + dt * v[0];
      run.step();
      const double g_next = (*run.sample().displacement)[0] + gap;
      const double alpha = std::max(0.0, -(w0 + gap)) / column[0];
      const double mu = 2 * (run.sample().multiplier + alpha / (dt * dt));
      const double lost = alpha * alpha / (2 * dt * dt) * column[0] + alpha / (dt * dt) * g_now - 0.5 * mu * g_now;
      worst_identity = std::max(worst_identity, std::abs(run.sample().energy - e + lost));
      worst_penetration = std::max(worst_penetration, -g_next);
      worst_complementarity = std::max({worst_complementarity, mu, std::abs(mu * g_next)});
      largest_gain = std::max(largest_gain, run.sample().energy - e);
      projections += alpha > 0, multipliers += mu < 0;
      projection_loss += alpha * alpha / (2 * dt * dt) * column[0] + alpha / (dt * dt) * g_now;
    }
    MESSAGE("dke, consistent mass, N = 40, dt = h/2, gap "
            << gap << ": (DKE) residual " << worst_identity << ", largest step change of E " << largest_gain << ", "
            << projections << " projections (losing " << projection_loss << " in all), " << multipliers
            << " steps with mu < 0, E " << run.sample().energy << " of 0.125");
    CAPTURE(gap);
    CHECK(worst_identity <= 1e-14);         // (DKE): round-off on E = 1/8
    CHECK(largest_gain <= 1e-14);           // the energy never grows (round-off: a few ε E per step)
    CHECK(worst_penetration <= 1e-15);      // u₀ + g₀ ≥ 0 at every level
    CHECK(worst_complementarity <= 1e-12);  // μ ≤ 0 and μg = 0 (μ ~ 1/Δt² scale)
    CHECK(projections > 0);
    CHECK(multipliers > 0);
  }
  // No contact: a gap that the run never closes (g₀ = 10 over two periods): the `newmark` (¼, ½) run, to
  // round-off, at every level (a few ε|U| per step, |U| ≤ 3, K = 480 steps: 1e-12).
  {
    Problem far = benchmark_problem();
    far.gap = 10.0;
    BarSimulation dke(far, mesh, consistent_mass(), class_parameters(Scheme::dke), dt);
    BarSimulation newmark(far, mesh, consistent_mass(), class_parameters(Scheme::newmark), dt);
    const double difference = largest_difference(dke, newmark, steps_to_reach(6.0, dt));
    CAPTURE(difference);
    CHECK(difference <= 1e-12);
    CHECK(std::abs(dke.sample().energy - newmark.sample().energy) <= 1e-13);
  }
  // A massless contact node (Mod 3): Crank–Nicolson's run with the same mass (the projection moves no node
  // with mass, row 0 is the algebraic row), λ included, over three periods.
  {
    BarSimulation dke(benchmark_problem(), mesh, mod3(), class_parameters(Scheme::dke), dt);
    BarSimulation cn(benchmark_problem(), mesh, mod3(), SchemeParameters(), dt);
    double difference = 0, lambda_difference = 0;
    for (Index k = 0; k < steps_to_reach(9.0, dt); ++k) {
      dke.step();
      cn.step();
      difference = std::max(difference, (*dke.sample().displacement - *cn.sample().displacement).cwiseAbs().maxCoeff());
      lambda_difference = std::max(lambda_difference, std::abs(dke.sample().multiplier - cn.sample().multiplier));
    }
    CAPTURE(difference);
    CAPTURE(lambda_difference);
    CHECK(difference <= 1e-12);
    CHECK(lambda_difference <= 1e-10);
    CHECK(std::abs(dke.sample().energy - cn.sample().energy) <= 1e-12);
  }
}

TEST_CASE("dke with a load: (DKE) with the load's work") {
  // The pressed bar (PressedBar: impacts, a persistent contact phase, releases), the consistent mass:
  // Eⁿ⁺¹ − Eⁿ = W_F − (the losses of (DKE)), W_F = F·ΔU for the constant load.
  const PressedBar bar;
  const UniformMesh& mesh = bar.mesh;
  const Eigen::VectorXd& f = bar.f;
  const double dt = bar.dt, gap = bar.gap;
  const Eigen::MatrixXd md = modified_mass(mesh, consistent_mass()).to_sparse().toDense();
  const Eigen::VectorXd column = md.llt().solve(Eigen::VectorXd::Unit(mesh.unknowns(), 0));
  BarSimulation run(bar.problem, mesh, consistent_mass(), class_parameters(Scheme::dke), dt);
  double worst = 0, worst_penetration = 0;
  int contact_levels = 0;
  for (Index n = 0; n < steps_to_reach(9.0, dt); ++n) {
    const Eigen::VectorXd u = *run.sample().displacement, v = *run.sample().velocity;
    const double e = run.sample().energy, g_now = u[0] + gap, w0 = u[0] + dt * v[0];
    run.step();
    const Eigen::VectorXd& u_next = *run.sample().displacement;
    const double alpha = std::max(0.0, -(w0 + gap)) / column[0];
    const double mu = 2 * (run.sample().multiplier + alpha / (dt * dt));
    const double lost = alpha * alpha / (2 * dt * dt) * column[0] + alpha / (dt * dt) * g_now - 0.5 * mu * g_now;
    worst = std::max(worst, std::abs(run.sample().energy - e - f.dot(u_next - u) + lost));
    worst_penetration = std::max(worst_penetration, -(u_next[0] + gap));
    contact_levels += run.sample().multiplier < 0;
  }
  CAPTURE(worst);
  CHECK(worst <= 1e-14);
  CHECK(worst_penetration <= 1e-15);
  CHECK(contact_levels > 100);
}

TEST_CASE("two-bars by symmetry: each body of the two-body Crank-Nicolson run is the one-bar run against a wall") {
  // The two-bars benchmark (doc/benchmarks.md §6: identical free bars, L = 10, E = ρ = 1, touching, ±0.1
  // toward each other): the
  // two-body run (two_bodies.hpp, CN, massless contact nodes) keeps wᴬ = wᴮ, and each equals the one-bar
  // CN run of a free bar at −0.1 against a wall at g₀/2 = 0 with the same mass (fig_classes.cpp,
  // configuration_of's comment), at every level to round-off, with the same λ; through the contact
  // [0, 20] and the release.
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    const UniformMesh mesh = with_far_end(UniformMesh(10.0, 40), FarEnd::free);
    const double dt = 0.5 * mesh.h();
    const Index n = mesh.unknowns();
    TwoBodyPart part{mesh, mass, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Constant(n, -0.1), nullptr};
    TwoBodySimulation pair({part, part}, 0.0, dt);
    Problem one;
    one.length = 10.0;
    one.initial_displacement = [](double) { return 0.0; };
    one.initial_velocity = [](double) { return -0.1; };
    BarSimulation bar(one, mesh, mass, class_parameters(Scheme::crank_nicolson), dt);
    double worst = 0, worst_pair = 0, worst_lambda = 0;
    int contact_levels = 0;
    for (Index k = 0; k < steps_to_reach(30.0, dt); ++k) {
      pair.step();
      bar.step();
      const Eigen::VectorXd& w = *bar.sample().displacement;
      worst = std::max(
          {worst, (pair.displacement(0) - w).cwiseAbs().maxCoeff(), (pair.displacement(1) - w).cwiseAbs().maxCoeff()});
      worst_pair = std::max(worst_pair, (pair.displacement(0) - pair.displacement(1)).cwiseAbs().maxCoeff());
      worst_lambda = std::max(worst_lambda, std::abs(pair.multiplier() - bar.sample().multiplier));
      contact_levels += pair.multiplier() < 0;
    }
    CAPTURE(mass.name);
    CAPTURE(worst);
    CAPTURE(worst_lambda);
    CHECK(worst_pair <= 1e-15);                       // the exchange symmetry (|w| ≤ 1)
    CHECK(worst <= 1e-13);                            // the reduction, to round-off of O(1) displacements
    CHECK(worst_lambda <= 1e-13);                     // |λ| = 0.1 during contact
    CHECK(contact_levels > 100);                      // the contact phase [0, 20] is in the run
    CHECK(std::abs(bar.sample().multiplier) == 0.0);  // released by t = 30
  }
}

}  // namespace mrm
