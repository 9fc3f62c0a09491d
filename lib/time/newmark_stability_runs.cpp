/// @file newmark_stability_runs.cpp
/// @brief The doctests of the explicit Newmark classes' step limit and modified energies
/// (classes/newmark_stability.cpp) on runs (BarSimulation): the limit against a power iteration, and the
/// identities (J), (B), (C), (G) and (JN) at every step. They sit above the classes they check because a
/// run is built on the registry of every family.
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
#include "fem/dense_eigenvalues.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/pencil.hpp"

namespace mrm {

namespace {

// The largest eigenvalue of M⁻¹K by a power iteration on the dense matrices (K, M symmetric, M positive
// definite): xₖ₊₁ = M⁻¹K xₖ/‖·‖, the Rayleigh quotient xᵀKx/xᵀMx of the last iterate.
[[maybe_unused]] double power_iteration(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, int iterations) {
  const Eigen::LLT<Eigen::MatrixXd> factor(m);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(k.rows(), 1.0, 2.0);
  for (int i = 0; i < iterations; ++i) {
    x = factor.solve(k * x);
    x /= x.norm();
  }
  return x.dot(k * x) / x.dot(m * x);
}

// The dense Schur complement of K on the nodes 1..N−1 (node 0 eliminated by its row).
[[maybe_unused]] Eigen::MatrixXd schur_on_interior(const Eigen::MatrixXd& k) {
  const Index n = k.rows() - 1;
  return k.bottomRightCorner(n, n) - k.col(0).tail(n) * k.row(0).tail(n) / k(0, 0);
}

}  // namespace

TEST_CASE(
    "the Newmark step limit for beta < gamma/2: the pencil's largest eigenvalue, stable just below, refused above") {
  // For each case: Λ = (Ω_c/Δt_max)² is checked against a power iteration of M⁻¹K on the actual dense
  // matrices of every side of the contact law (free and active; with a massless node the Schur complements
  // on 1..N−1 and the held block): the largest of them equals Λ to 1e-8 (the held block or the active
  // side is the largest), none exceeds it. Nitsche with θ = 0 (K not symmetric): the eigenvalues of M⁻¹K
  // by Eigen's dense eigensolver, whose largest modulus must not exceed Λ (the conjecture of the comment).
  // Then runs below the limit (next comment) and the refusal of 1.01 Δt_max, naming dt.
  const UniformMesh mesh(1.0, 16);
  const double h = mesh.h();
  struct Case {
    Scheme scheme;
    MassRedistribution mass;
    double beta, gamma, parameter, theta;
  };
  for (const Case& c :
       {Case{Scheme::penalty, consistent_mass(), 0.0, 0.5, 1.0, 0.0},
        Case{Scheme::penalty, consistent_mass(), 0.0, 0.5, 100.0, 0.0},
        Case{Scheme::penalty, consistent_mass(), 0.1, 0.6, 5.0, 0.0},
        Case{Scheme::nitsche, consistent_mass(), 0.0, 0.5, 5.0, 1.0},
        Case{Scheme::nitsche, consistent_mass(), 0.0, 0.5, 5.0, 0.0},
        Case{Scheme::newmark, consistent_mass(), 0.1, 0.5, 0.0, 0.0}, Case{Scheme::newmark, mod3(), 0.0, 0.5, 0.0, 0.0},
        Case{Scheme::penalty, mod3(), 0.0, 0.5, 1.0, 0.0}}) {
    SchemeParameters p = class_parameters(c.scheme, c.beta, c.gamma);
    if (c.scheme == Scheme::penalty) p.penalty = c.parameter;
    if (c.scheme == Scheme::nitsche) p.nitsche_gamma = c.parameter, p.nitsche_theta = c.theta;
    const Tridiagonal m = modified_mass(mesh, c.mass), s = p1_stiffness(mesh);
    const double limit = newmark_stability_limit(m, s, p, h);
    const double omega_c = 1 / std::sqrt(0.5 * c.gamma - c.beta), bound = omega_c * omega_c / (limit * limit);
    CAPTURE(to_string(c.scheme));
    CAPTURE(c.mass.name);
    CAPTURE(c.parameter);
    CAPTURE(c.theta);
    CAPTURE(limit / h);
    // The actual matrices: K free and active (dense), M.
    const Eigen::MatrixXd md = m.to_sparse().toDense(), sd = s.to_sparse().toDense();
    Eigen::MatrixXd free = sd, active = sd;
    Eigen::VectorXd d = Eigen::VectorXd::Zero(mesh.unknowns());
    d[0] = -1 / h, d[1] = 1 / h;
    if (c.scheme == Scheme::penalty) active(0, 0) += c.parameter / h;
    if (c.scheme == Scheme::nitsche) {
      const double gamma = c.parameter / h;
      Eigen::VectorXd e0 = Eigen::VectorXd::Zero(mesh.unknowns());
      e0[0] = 1;
      free -= (c.theta / gamma) * d * d.transpose();
      active = free + (1 / gamma) * (gamma * e0 + c.theta * d) * (gamma * e0 + d).transpose();
    }
    double measured = 0;
    const Index n = mesh.unknowns() - 1;
    if (c.mass.name == "mod3") {
      const Eigen::MatrixXd mi = md.bottomRightCorner(n, n);
      measured = std::max({power_iteration(schur_on_interior(free), mi, 20000),
                           power_iteration(sd.bottomRightCorner(n, n), mi, 20000),
                           c.scheme == Scheme::penalty ? power_iteration(schur_on_interior(active), mi, 20000) : 0.0});
      CHECK(measured == doctest::Approx(bound).epsilon(1e-8));  // the held block is the largest
    } else if (c.scheme == Scheme::nitsche && c.theta != 1.0) {
      for (const Eigen::MatrixXd* k : {&free, &active}) {
        const Eigen::VectorXcd eigenvalues = general_eigenvalues(md.inverse() * *k);
        measured = std::max(measured, eigenvalues.cwiseAbs().maxCoeff());
      }
      MESSAGE("Nitsche theta = 0: largest |eigenvalue| of M^-1 K " << measured << " against the symmetric part's "
                                                                   << bound);
      CHECK(measured <= bound * (1 + 1e-8));
    } else {
      const Eigen::MatrixXd held = sd.bottomRightCorner(n, n);
      measured = std::max(power_iteration(free, md, 20000),
                          c.scheme == Scheme::newmark ? power_iteration(held, md.bottomRightCorner(n, n), 20000)
                                                      : power_iteration(active, md, 20000));
      CHECK(measured == doctest::Approx(bound).epsilon(1e-8));
    }
    // Just below: bounded over ten periods; just above: refused, naming dt.
    // Below the limit: the largest E/E₀ over ten periods at 0.99, 0.9 and 0.7 Δt_max. The limit is the linear
    // one of each side of the kink; the run switches between the sides, and the switches are not covered by
    // it: close to the limit the stiff laws gain energy (measured, N = 16: penalty γ₀ = 100 152× and 111× at
    // 0.99 and 0.9, Nitsche 78× and 7.6× (θ = 1), 166× and 7.9× (θ = 0); 1.44× for penalty γ₀ = 1 at 0.99),
    // and at 0.7 Δt_max every case stays within 1.2 E₀. Checked: within 1.5 E₀ at 0.7 Δt_max. Exact enforcement
    // with the standard mass (newmark, consistent) is not checked: it is ill-posed at every step (the chatter
    // of doc/contact_treatments.md §2; measured E/E₀ ~ 1e8 at 0.25 Δt_max), whatever its step limit.
    if (!(c.scheme == Scheme::newmark && c.mass.name == "consistent")) {
      for (const double fraction : {0.99, 0.9, 0.7}) {
        BarSimulation below(benchmark_problem(), mesh, c.mass, p, fraction * limit);
        const double e0 = below.sample().energy;
        double largest = 0;
        try {
          run(below, steps_to_reach(30.0, below.dt()),
              [&](const Sample& x) { largest = std::max(largest, x.energy / e0); });
        } catch (const std::runtime_error&) {
          largest = HUGE_VAL;  // lost finiteness
        }
        MESSAGE(to_string(c.scheme) << " + " << c.mass.name << " (parameter " << c.parameter << ", theta " << c.theta
                                    << ", beta " << c.beta << ") at " << fraction << " dt_max: max E/E0 = " << largest);
        if (fraction == 0.7) CHECK(largest <= 1.5);
      }
    }
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, c.mass, p, 1.01 * limit), doctest::Contains("dt: "),
                         InvalidParameter);
  }
  // β ≥ γ/2: no limit.
  CHECK(newmark_stability_limit(modified_mass(mesh, consistent_mass()), p1_stiffness(mesh),
                                class_parameters(Scheme::penalty, 0.25, 0.5), h) == HUGE_VAL);
}

TEST_CASE(
    "central differences with a penalty: E_h changes only at switches, by (J), within (B), and (C) and (G) hold") {
  // The run of the measured gains (N = 16, γ₀ = 100 and 10, the consistent mass, 0.9 Δt_max, ten periods):
  // (J) to round-off at every step (so the whole growth of E_h is the sum of the switch jumps), jumps of
  // both signs (losses entering, gains leaving), (B) and (C) at every level, (G) at every level with ρ
  // from the dense A, and E_h grown by more than 2 (the gain is real, not a measure's artefact).
  const UniformMesh mesh(1.0, 16);
  const double h = mesh.h();
  const Tridiagonal m = modified_mass(mesh, consistent_mass()), s = p1_stiffness(mesh);
  for (const auto& [gamma0, r] : {std::pair{100.0, 0.9}, std::pair{10.0, 0.9}, std::pair{10.0, 0.5}}) {
    SchemeParameters p = class_parameters(Scheme::penalty, 0.0);
    p.penalty = gamma0;
    const double k = gamma0 / h, dt = r * newmark_stability_limit(m, s, p, h);
    // ρ = ¼kΔt² e₀ᵀA⁻¹e₀, A = M − ¼Δt²(S + ke₀e₀ᵀ).
    Eigen::MatrixXd a = m.to_sparse().toDense() - 0.25 * dt * dt * s.to_sparse().toDense();
    a(0, 0) -= 0.25 * dt * dt * k;
    const double rho = 0.25 * k * dt * dt * a.inverse()(0, 0);
    CAPTURE(gamma0);
    CAPTURE(rho);
    BarSimulation run(benchmark_problem(), mesh, consistent_mass(), p, dt);
    Eigen::VectorXd before = *run.sample().displacement;
    run.step();
    Eigen::VectorXd now = *run.sample().displacement;
    const double first = penalty_modified_energy(m, s, k, 0.0, dt, before, now);
    double previous = first, worst_identity = 0, worst_bound = 0, worst_coercive = 0, worst_gronwall = 0;
    int gains = 0, losses = 0, switches = 0;
    for (Index n = 1; n < steps_to_reach(30.0, dt); ++n) {
      run.step();
      const Eigen::VectorXd& after = *run.sample().displacement;
      const double eh = penalty_modified_energy(m, s, k, 0.0, dt, now, after);
      const double jump = penalty_switch_jump(k, before[0], now[0], after[0]);
      worst_identity = std::max(worst_identity, std::abs(eh - previous - jump) / std::max(eh, first));
      const double v_before = (now[0] - before[0]) / dt, v_after = (after[0] - now[0]) / dt;
      worst_bound = std::max(worst_bound,
                             std::abs(jump) / (0.125 * k * dt * dt * std::max(v_before * v_before, v_after * v_after)));
      const Eigen::VectorXd v = (after - now) / dt, mean = 0.5 * (now + after);
      const double q_mean = 0.5 * (std::min(0.0, now[0]) + std::min(0.0, after[0]));
      const double floor = (1 - r * r) * 0.5 * v.dot(m * v) + 0.5 * mean.dot(s * mean) + 0.5 * k * q_mean * q_mean;
      worst_coercive = std::max(worst_coercive, (floor - eh) / eh);
      switches += jump != 0.0;
      gains += jump > 0, losses += jump < 0;
      if (rho < 1) worst_gronwall = std::max(worst_gronwall, eh / (first * std::pow(1 - rho, -switches)));
      previous = eh;
      before = now;
      now = after;
    }
    MESSAGE("gamma0 " << gamma0 << ", r " << r << ": E_h " << first << " -> " << previous << ", " << switches
                      << " switching steps (" << gains << " gains, " << losses << " losses), rho " << rho
                      << ", (J) residual " << worst_identity << ", |J|/(B) <= " << worst_bound
                      << ", E_h/(G) <= " << worst_gronwall);
    CHECK(worst_identity <= 1e-12);      // (J): round-off on O(1) energies
    CHECK(worst_bound <= 1 + 1e-12);     // (B)
    CHECK(worst_coercive <= 1e-12);      // (C)
    CHECK(worst_gronwall <= 1 + 1e-12);  // (G)
    CHECK(gains > 0);
    CHECK(losses > 0);
    if (r == 0.9) CHECK(previous > 2 * first);  // the gain the linear limit does not prevent
  }
  CHECK(penalty_switch_jump(1.0, 0.5, -0.1, -0.2) == doctest::Approx(-0.5 * 0.1 * 0.5));  // entering: a loss
  CHECK(penalty_switch_jump(1.0, -0.2, -0.1, 0.5) == doctest::Approx(0.5 * 0.1 * 0.5));   // leaving: a gain
  CHECK(penalty_switch_jump(1.0, -0.2, -0.1, -0.3) == 0.0);                               // no switch
}

TEST_CASE(
    "central differences with Nitsche: E_N changes by (JN), and theta = 1 only at switches within (B), theta = 0 "
    "also between") {
  // Runs of block 6's grid (N = 16, γ₀ = 5, the consistent mass, ten periods; θ = 1 at 0.9 and 0.5 Δt_max, θ = 0
  // at 0.9):
  // (JN) to round-off at every step; θ = 1: E_N changes only at switching steps (a status change of P on a
  // neighbouring level), by at most (1/8γ)Δt² max(ℓ·v)² ((B) with q → P, k → 1/γ), with gains and losses,
  // and grows by more than 2 (the gain the linear limit does not prevent); for θ = 1 also the penalty's (C)
  // (E_N ≥ (1 − r²)½‖v‖²_M + ½ŪᵀS_θŪ + (1/2γ)P̄₋², r = 0.9, the limit's active pencil S_θ + (1/γ)ℓℓᵀ) and (G)
  // (ρ = (1/4γ)Δt² ℓᵀA⁻¹ℓ, A = M − ¼Δt²(S_θ + (1/γ)ℓℓᵀ)) at every level; θ = 0: the remainder
  // ((1 − θ)/2γ)P₋ⁿ(σⁿ⁺¹ − σⁿ⁻¹) is nonzero on steps without a switch, and its sum over them is not small
  // (no modified energy is conserved between switches).
  const UniformMesh mesh(1.0, 16);
  const double h = mesh.h();
  const Tridiagonal m = modified_mass(mesh, consistent_mass()), s = p1_stiffness(mesh);
  for (const auto& [theta, r] : {std::pair{1.0, 0.9}, std::pair{1.0, 0.5}, std::pair{0.0, 0.9}}) {
    SchemeParameters p = class_parameters(Scheme::nitsche, 0.0);
    p.nitsche_gamma = 5.0;
    p.nitsche_theta = theta;
    const double gamma = p.nitsche_gamma / h, dt = r * newmark_stability_limit(m, s, p, h);
    Tridiagonal s_theta = s;  // S_θ = S − (θ/γ)ddᵀ
    const double c = theta / (gamma * h * h);
    s_theta.diag[0] -= c, s_theta.diag[1] -= c, s_theta.upper[0] += c, s_theta.lower[1] += c;
    const auto P = [&](const Eigen::VectorXd& u) { return (gamma - 1 / h) * u[0] + u[1] / h; };
    const auto sigma = [&](const Eigen::VectorXd& u) { return (u[1] - u[0]) / h; };
    const auto e_n = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {  // (EN)
      const Eigen::VectorXd v = (b - a) / dt;
      return 0.5 * v.dot(m * v) + 0.5 * a.dot(s_theta * b) + std::min(0.0, P(a)) * std::min(0.0, P(b)) / (2 * gamma);
    };
    Eigen::VectorXd ell = Eigen::VectorXd::Zero(mesh.unknowns());
    ell[0] = gamma - 1 / h, ell[1] = 1 / h;
    const Eigen::MatrixXd a =
        m.to_sparse().toDense() - 0.25 * dt * dt * (s_theta.to_sparse().toDense() + ell * ell.transpose() / gamma);
    const double rho = 0.25 * dt * dt / gamma * ell.dot(a.inverse() * ell);
    BarSimulation run(benchmark_problem(), mesh, consistent_mass(), p, dt);
    Eigen::VectorXd before = *run.sample().displacement;
    run.step();
    Eigen::VectorXd now = *run.sample().displacement;
    const double first = e_n(before, now);
    double previous = first, worst_identity = 0, worst_bound = 0, remainder_between = 0, largest_remainder = 0;
    double worst_coercive = 0, worst_gronwall = 0;
    int gains = 0, losses = 0, between = 0, switches = 0;
    for (Index n = 1; n < steps_to_reach(30.0, dt); ++n) {
      run.step();
      const Eigen::VectorXd& after = *run.sample().displacement;
      const double e = e_n(now, after), pm = std::min(0.0, P(now));
      const double jump = -pm * (std::max(0.0, P(after)) - std::max(0.0, P(before))) / (2 * gamma);
      const double remainder = (1 - theta) * pm * (sigma(after) - sigma(before)) / (2 * gamma);
      worst_identity = std::max(worst_identity, std::abs(e - previous - jump - remainder) / std::max(e, first));
      if (jump != 0.0) {
        const double lv_before = P(now) - P(before), lv_after = P(after) - P(now);  // Δt ℓ·v
        worst_bound = std::max(worst_bound,
                               std::abs(jump) / (std::max(lv_before * lv_before, lv_after * lv_after) / (8 * gamma)));
        gains += jump > 0, losses += jump < 0;
      } else if (remainder != 0.0) {
        ++between;
        remainder_between += remainder;
        largest_remainder = std::max(largest_remainder, std::abs(remainder) / first);
      }
      if (theta == 1.0 && jump == 0.0) CHECK(std::abs(e - previous) <= 1e-12 * std::max(e, first));
      switches += jump != 0.0;
      if (theta == 1.0) {
        const Eigen::VectorXd v = (after - now) / dt, mean = 0.5 * (now + after);
        const double p_mean = 0.5 * (std::min(0.0, P(now)) + std::min(0.0, P(after)));
        const double floor =
            (1 - r * r) * 0.5 * v.dot(m * v) + 0.5 * mean.dot(s_theta * mean) + p_mean * p_mean / (2 * gamma);
        worst_coercive = std::max(worst_coercive, (floor - e) / e);
        if (rho < 1) worst_gronwall = std::max(worst_gronwall, e / (first * std::pow(1 - rho, -switches)));
      }
      previous = e;
      before = now;
      now = after;
    }
    MESSAGE("Nitsche theta " << theta << ", gamma0 5, " << r << " dt_max: E_N " << first << " -> " << previous << ", "
                             << gains << " gains, " << losses << " losses at switches, (JN) residual " << worst_identity
                             << ", |J|/(B) <= " << worst_bound << "; " << between
                             << " contact steps without a switch, their remainder summed " << remainder_between
                             << " (largest " << largest_remainder << " E_N)");
    CHECK(worst_identity <= 1e-12);   // (JN): round-off on O(1) energies
    CHECK(worst_bound <= 1 + 1e-12);  // (B) for the switch part
    CHECK(gains > 0);
    CHECK(losses > 0);
    if (theta == 1.0) {
      CHECK(between == 0);                        // symmetric Nitsche: nothing between switches
      if (r == 0.9) CHECK(previous > 2 * first);  // the gain the linear limit does not prevent
      MESSAGE("theta 1, r " << r << ": rho " << rho << ", (C) defect " << worst_coercive
                            << ", E_N/(G) <= " << worst_gronwall);
      CHECK(worst_coercive <= 1e-12);      // (C)
      if (r == 0.5) CHECK(rho < 1);        // (G) is not void at 0.5 (2.4 at 0.9)
      CHECK(worst_gronwall <= 1 + 1e-12);  // (G)
    } else {
      CHECK(between > 10);                                // the circulatory force works in every contact step
      CHECK(std::abs(remainder_between) > 1e-3 * first);  // and its work does not cancel
    }
  }
}

}  // namespace mrm
