/// @file lanes_alone.cpp
/// @brief The doctests of the batched step (batched_step.cpp, kernels.cpp): every lane bitwise its run
/// stepped alone, for every scheme, every width and every target of the machine.
#include "batched/batched_step.hpp"

#include <cstring>
#include <functional>
#include <string>
#include <stdexcept>
#include <vector>

#include <doctest/doctest.h>

#include "classes/contact_classes.hpp"
#include "steps/explicit_schemes.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"

namespace mrm {

/// @file lanes_alone.cpp
/// ## The batched step against the runs stepped alone
///
/// Prediction: bit for bit the same states (U, W', X, λ, the energy, the status, the instants) at every
/// step, lane by lane, for every scheme with a batched kernel (cn, be, ps with both contact rows, ec,
/// cn-switch, the Newmark-type classes newmark, penalty, nitsche, moreau-jean, dke, taylor-flanagan and
/// explicit: every scheme of the registry) and every vector target this machine has: the batched step
/// performs each lane's operations in the scalar order, and CN-switch's status changes and
/// Paoli–Schatzman's first step are the lane's own scalar step, as are the classes' contact decisions, DKE's
/// projection and the ends of step (NewmarkTypeStep::decide, finish; OneSolveStep::projection, decide,
/// finish; ExplicitStep::contact). The runs of a batch differ in Δt (Courant numbers 0.5 … 1.7; the explicit
/// classes 0.5 … 0.92 of their stability limit), mass (Mod 1, Mod 3, the consistent mass where the scheme
/// allows it; Taylor–Flanagan's lumped or not), for Paoli–Schatzman in β and e, for the Newmark type in β (0
/// at 0.9 of the stability limit, or (γ + ½)²/4), γ, the penalty and Nitsche's θ and γ₀, for Moreau–Jean in
/// θ and e, and for Moreau–Jean, DKE and the explicit classes in the initial gap (0 or h/2); their number
/// 2W + 1 leaves a group with padding lanes or a run alone. A difference of one ulp anywhere fails; so do
/// four mutations of the Newmark-type kernel (tried): the form's partial sums paired otherwise, the law's
/// force on row 0 dropped, the shift's select inverted, a kept lane's velocity not kept; four of the
/// one-solve kernel (tried): DKE's projection dropped, DKE's P₀ = −g₀ dropped, the kinetic form taken of the
/// wrong vector, a kept Moreau–Jean lane's velocity not kept (the partial step below); and four of the
/// explicit kernel (tried): Taylor–Flanagan's correction skipped, the clamped end's element dropped from the
/// energy, a kept lane's second kick not kept, the explicit scheme's u₀ not set.
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
}

// Every scheme with a batched kernel, Paoli–Schatzman with both contact rows.
struct BatchedCase {
  Scheme scheme;
  ContactRow row;
};
std::vector<BatchedCase> batched_cases() {
  return {{Scheme::crank_nicolson, ContactRow::algebraic},
          {Scheme::backward_euler, ContactRow::algebraic},
          {Scheme::paoli_schatzman, ContactRow::algebraic},
          {Scheme::paoli_schatzman, ContactRow::literal},
          {Scheme::energy_conserving, ContactRow::algebraic},
          {Scheme::switching, ContactRow::algebraic},
          {Scheme::newmark, ContactRow::algebraic},
          {Scheme::penalty, ContactRow::algebraic},
          {Scheme::nitsche, ContactRow::algebraic},
          {Scheme::moreau_jean, ContactRow::algebraic},
          {Scheme::dke, ContactRow::algebraic},
          {Scheme::taylor_flanagan, ContactRow::algebraic},
          {Scheme::explicit_central, ContactRow::algebraic}};
}

// Run k's lumping, mass, gap and Δt of an explicit class: Taylor–Flanagan with the consistent mass, lumped
// (row-sum) or not; explicit with Mod 1 or Mod 3, lumped; every third run with a gap of h/2; Δt the fraction
// `fraction` of the run's stability limit (explicit_stability_limit).
MassRedistribution explicit_parameters(SchemeParameters& p, std::size_t k, Problem& problem, const UniformMesh& mesh,
                                       double fraction, double& dt) {
  if (k % 3 == 2) problem.gap = 0.5 * mesh.h();
  const bool tf = p.scheme == Scheme::taylor_flanagan;
  const MassRedistribution mass = tf ? consistent_mass() : k % 2 == 0 ? mod1() : mod3();
  p.lumping = tf && k % 2 == 1 ? MassLumping::none : MassLumping::row_sum;
  const Eigen::VectorXd lumped = row_sum_lumped_mass(mesh, mass);
  dt = fraction * explicit_stability_limit(mesh, p.lumping == MassLumping::row_sum ? &lumped : nullptr);
  return mass;
}

// Run k's parameters, mass and gap of Moreau–Jean (θ = ½, ¾, 1; e = 1, ½, 0; the consistent mass, the one it
// allows) or DKE (Mod 1, Mod 3, the consistent mass); every other run of the two with an initial gap of h/2
// (the obstacle at −g₀ in the decision and in DKE's projection).
MassRedistribution one_solve_parameters(SchemeParameters& p, std::size_t k, Problem& problem, double h) {
  if (k % 2 == 1) problem.gap = 0.5 * h;
  if (p.scheme == Scheme::dke) return k % 3 == 0 ? mod1() : k % 3 == 1 ? mod3() : consistent_mass();
  p.moreau_theta = k % 3 == 0 ? 0.5 : k % 3 == 1 ? 0.75 : 1.0;
  p.restitution = k % 4 == 0 ? 1.0 : k % 4 == 1 ? 0.5 : 0.0;
  return consistent_mass();
}

// Run k's parameters of a Newmark-type class: γ = ½ or 0.6; β = (γ + ½)²/4 (stable at any Δt) or, where
// `explicit_step` allows and the class does (exact enforcement needs a massless node for β = 0), β = 0 at 0.9
// of its stability limit, which then replaces `dt`; penalty γ₀ = 1 or 100; Nitsche θ = 0, 1 or −1, γ₀ = 5
// or 50.
void class_parameters(SchemeParameters& p, std::size_t k, const UniformMesh& mesh, const MassRedistribution& mass,
                      bool explicit_step, double& dt) {
  p.newmark_gamma = k % 4 == 3 ? 0.6 : 0.5;
  if (p.scheme == Scheme::penalty) p.penalty = k % 3 == 1 ? 100.0 : 1.0;
  if (p.scheme == Scheme::nitsche) {
    p.nitsche_theta = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : -1.0;
    p.nitsche_gamma = k % 4 < 2 ? 5.0 : 50.0;
  }
  const bool massless = contact_node_is_massless(modified_mass(mesh, mass));
  const double implicit = 0.25 * (p.newmark_gamma + 0.5) * (p.newmark_gamma + 0.5);  // β ≥ γ/2: any Δt
  p.newmark_beta = explicit_step && k % 2 == 1 && (p.scheme != Scheme::newmark || massless) ? 0.0 : implicit;
  if (p.newmark_beta == 0.0)
    dt = 0.9 * newmark_stability_limit(modified_mass(mesh, mass), p1_stiffness(mesh), p, mesh.contact_compliance());
}

// Steps `batched` and the same runs `alone` `steps` times and compares every run's sample after each step, bit
// for bit (level, instants, U, V, λ, the energy); a difference is reported with the run, the step and what
// differs, and ends the comparison. `status_changes`, if given, counts the changes of the contact status.
bool steps_alike(BatchedSimulation& batched, std::vector<BarSimulation>& alone, Index steps, int* status_changes) {
  const std::size_t count = alone.size();
  std::vector<bool> active(count, false);
  for (Index n = 1; n <= steps; ++n) {
    batched.step();
    for (std::size_t k = 0; k < count; ++k) {
      alone[k].step();
      const Sample a = batched.run(k).sample(), b = alone[k].sample();
      const bool same = a.level == b.level && same_bits(a.time, b.time) &&
                        same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                        a.has_multiplier == b.has_multiplier && same_bits(a.multiplier, b.multiplier) &&
                        same_bits(a.multiplier_time, b.multiplier_time) && same_bits(a.energy, b.energy) &&
                        same_bits(a.energy_time, b.energy_time);
      if (!same) {
        CAPTURE(k);
        CAPTURE(n);
        const std::string parts = std::string(same_bits(*a.displacement, *b.displacement) ? "" : " U") +
                                  (same_bits(*a.velocity, *b.velocity) ? "" : " V") +
                                  (same_bits(a.multiplier, b.multiplier) ? "" : " lambda") +
                                  (same_bits(a.energy, b.energy) ? "" : " E") + (a.level == b.level ? "" : " level");
        CAPTURE(parts);
        const double du = (*a.displacement - *b.displacement).cwiseAbs().maxCoeff();
        CAPTURE(du);
        CAPTURE(a.energy - b.energy);
        CHECK(same);
        return false;
      }
      const bool now = b.multiplier < 0;
      if (status_changes) *status_changes += now != active[k];
      active[k] = now;
    }
  }
  return true;
}

// Whether the case's scheme allows a contact node with inertia (the consistent mass): energy-conserving and
// Paoli–Schatzman with the algebraic row need a massless one.
bool inertia_allowed(const BatchedCase& c) {
  return c.scheme != Scheme::energy_conserving &&
         !(c.scheme == Scheme::paoli_schatzman && c.row == ContactRow::algebraic);
}

// For every scheme of the fused step (batch families 0–3: cn, be, ps with both contact rows, ec, cn-switch)
// on every vector target, the runs run(c, k), k < count(lanes), made twice with the same arguments, are
// stepped 150 steps (past the first impact at the Δt the callers take) in one batch and alone and compared
// step by step (steps_alike), after expect(batched, alone) has checked the batch. Returns the status changes
// of CN-switch's runs, which its callers check are some (its θ-step, alone, was taken).
int fused_cases_alike(const std::function<std::size_t(std::size_t lanes)>& count,
                      const std::function<BarSimulation(const BatchedCase&, std::size_t k)>& run,
                      const std::function<void(const BatchedSimulation&, std::vector<BarSimulation>&)>& expect) {
  std::vector<BatchedCase> fused;
  for (const BatchedCase& c : batched_cases())
    if (batch_family(c.scheme) <= 3) fused.push_back(c);
  REQUIRE(fused.size() == 6);
  int status_changes = 0;
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const BatchedCase& c : fused) {
      CAPTURE(to_string(c.scheme));
      CAPTURE(to_string(c.row));
      std::vector<BarSimulation> batch, alone;
      for (std::size_t k = 0; k < count(target.lanes); ++k) {
        batch.push_back(run(c, k));
        alone.push_back(run(c, k));
      }
      BatchedSimulation batched(std::move(batch));
      expect(batched, alone);
      CHECK(steps_alike(batched, alone, 150, c.scheme == Scheme::switching ? &status_changes : nullptr));
    }
  }
  use_batch_target(0);
  return status_changes;
}

// The scheme parameters of a case.
SchemeParameters case_parameters(const BatchedCase& c) {
  SchemeParameters p;
  p.scheme = c.scheme;
  p.contact_row = c.row;
  return p;
}

// A steady load towards the obstacle, f(x) = −(1 + x) (its F₀ ≠ 0), added to `problem`.
Problem with_steady_load(Problem problem) {
  problem.load = [](double x, double) { return -(1.0 + x); };
  problem.steady_load = true;
  return problem;
}

}  // namespace

TEST_CASE("the batched step is bitwise each run stepped alone, lane by lane, for every scheme and target") {
  const std::vector<BatchedCase> cases = batched_cases();
  const UniformMesh mesh(1.0, 24);
  const Index steps = 150;  // past the first impact (t = 1) at every Δt below
  const std::vector<BatchTarget> targets = batch_targets();
  REQUIRE(!targets.empty());
  int batched_cases = 0, status_changes = 0;
  for (const BatchTarget& target : targets) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const BatchedCase& c : cases) {
      CAPTURE(to_string(c.scheme));
      CAPTURE(to_string(c.row));
      std::vector<BarSimulation> batch, alone;
      const std::size_t count = 2 * target.lanes + 1;
      for (std::size_t k = 0; k < count; ++k) {
        MassRedistribution mass = k % 3 == 0           ? mod1()
                                  : k % 3 == 1         ? mod3()
                                  : inertia_allowed(c) ? consistent_mass()
                                                       : mod2();
        SchemeParameters p;
        p.scheme = c.scheme;
        p.contact_row = c.row;
        Problem problem = benchmark_problem();
        // A restitution e > 0 with the literal row needs a contact node with inertia (schemes.cpp refuses
        // it on a massless node): the consistent mass of k % 3 == 2 only.
        const bool massless = !(k % 3 == 2 && inertia_allowed(c));
        if (c.scheme == Scheme::paoli_schatzman && k % 2 == 1)
          p.beta = 0.3, p.restitution = c.row == ContactRow::literal && massless ? 0.0 : 0.5;
        double dt = (0.5 + 0.1 * static_cast<double>(k % 13)) * mesh.h();
        if (batch_family(c.scheme) == 4) class_parameters(p, k, mesh, mass, true, dt);
        if (c.scheme == Scheme::moreau_jean || c.scheme == Scheme::dke)
          mass = one_solve_parameters(p, k, problem, mesh.h());
        if (find_entry(central_difference_schemes(), c.scheme))
          mass = explicit_parameters(p, k, problem, mesh, 0.5 + 0.035 * static_cast<double>(k % 13), dt);
        batch.emplace_back(problem, mesh, mass, p, dt);
        alone.emplace_back(problem, mesh, mass, p, dt);
      }
      BatchedSimulation batched(std::move(batch));
      CHECK(batched.lanes() == target.lanes);
      batched_cases += batched.batched_runs() > 0;
      CHECK(steps_alike(batched, alone, steps, c.scheme == Scheme::switching ? &status_changes : nullptr));
    }
  }
  use_batch_target(0);
  // Not vacuous: every case went through the vector lanes on every target, CN-switch changed status.
  CHECK(batched_cases == static_cast<int>(targets.size() * cases.size()));
  // Every scheme of the registry has a case here, and every case went through the lanes (above): a scheme
  // added without a batched kernel fails.
  for (const SchemeInfo& info : scheme_registry()) {
    CAPTURE(info.id);
    CHECK(std::any_of(cases.begin(), cases.end(), [&](const BatchedCase& c) { return c.scheme == info.scheme; }));
  }
  CHECK(status_changes > 0);
}

/// @file lanes_alone.cpp
/// ## Runs at their own rates: the partial step
///
/// step(advance) steps the runs with advance[k] ≠ 0 and keeps the others: a kept lane is written back
/// unchanged by the sweep up (the mask CN-switch uses for its status changes), and its run's bookkeeping
/// is not touched. So runs of Δt, 2Δt, … step together, each only at the multiples of its rate. The
/// prediction is the identity again: at every batch step, every run, advanced or kept, is bitwise its run
/// stepped alone as many times. Checked for every scheme and target with the rates 1, 2, 3, 5 (run k's
/// Δt is its rate times a common step), read without copying the lanes out (sample(k, lanes)), so that a
/// kept lane newer than its run's vectors meets another lane's Paoli–Schatzman first step (at n = 5:
/// the rate-2 lane stepped in the lanes at n = 4 and stays); a wrong flag count throws.
TEST_CASE("a partial step keeps the runs that stay, and runs at their own rates are each bitwise the run alone") {
  const std::vector<BatchedCase> cases = batched_cases();
  const UniformMesh mesh(1.0, 24);
  const std::vector<Index> rates = {1, 2, 3, 5};
  const Index batch_steps = 300;  // every run reaches t = 300 · 0.25h ≈ 3.1, past the first impact (t = 1)
  int kept_lanes = 0;
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const BatchedCase& c : cases) {
      CAPTURE(to_string(c.scheme));
      CAPTURE(to_string(c.row));
      std::vector<BarSimulation> batch, alone;
      const std::size_t count = 2 * target.lanes + 1;
      for (std::size_t k = 0; k < count; ++k) {
        SchemeParameters p;
        p.scheme = c.scheme;
        p.contact_row = c.row;
        if (c.scheme == Scheme::paoli_schatzman && k % 2 == 1) p.beta = 0.3;
        double dt = 0.25 * static_cast<double>(rates[k % rates.size()]) * mesh.h();
        MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
        Problem problem = benchmark_problem();
        if (batch_family(c.scheme) == 4) class_parameters(p, k, mesh, mass, false, dt);  // implicit: any rate
        if (c.scheme == Scheme::moreau_jean || c.scheme == Scheme::dke)
          mass = one_solve_parameters(p, k, problem, mesh.h());
        if (find_entry(central_difference_schemes(), c.scheme))  // rates 1, 2, 3, 5 of 0.18 of the stability limit
          mass = explicit_parameters(p, k, problem, mesh, 0.18 * static_cast<double>(rates[k % rates.size()]), dt);
        batch.emplace_back(problem, mesh, mass, p, dt);
        alone.emplace_back(problem, mesh, mass, p, dt);
      }
      BatchedSimulation batched(std::move(batch));
      REQUIRE(batched.batched_runs() > 0);
      bool identical = true;
      for (Index n = 1; n <= batch_steps && identical; ++n) {
        std::vector<char> advance(count);
        for (std::size_t k = 0; k < count; ++k) {
          advance[k] = n % rates[k % rates.size()] == 0;
          if (advance[k]) alone[k].step();
          kept_lanes += !advance[k];
        }
        batched.step(advance);
        for (std::size_t k = 0; k < count; ++k) {
          LaneVectors where{};
          const Sample a = batched.sample(k, where), b = alone[k].sample();
          bool same = a.level == b.level && same_bits(a.time, b.time) && same_bits(a.multiplier, b.multiplier) &&
                      same_bits(a.energy, b.energy);
          for (Index i = 0; i < mesh.elements; ++i) {
            const std::size_t at = static_cast<std::size_t>(i) * where.stride;
            same = same && same_bits(where.displacement[at], (*b.displacement)[i]) &&
                   same_bits(where.velocity[at], (*b.velocity)[i]);
          }
          if (!same) {
            CAPTURE(k);
            CAPTURE(n);
            CHECK(same);
            identical = false;
          }
        }
      }
      CHECK(identical);
    }
  }
  use_batch_target(0);
  CHECK(kept_lanes > 0);
  std::vector<BarSimulation> two;
  two.emplace_back(benchmark_problem(), mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  two.emplace_back(benchmark_problem(), mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  BatchedSimulation batched(std::move(two));
  CHECK_THROWS_AS(batched.step(std::vector<char>(3, 1)), std::invalid_argument);
}

/// @file lanes_alone.cpp
/// ## Steady loads in the lanes
///
/// A run whose load does not change with t (Problem::steady_load: the bouncing benchmark's gravity) takes a
/// lane of its own family: its load term g_now F_i + g_next F_i is formed once per lane (batched_step.cpp)
/// and added to each row's right-hand side in the sweep down, where the fused step adds the same sum at
/// every step; its contact decision reads F₀ as the fused step does. A lane without a load adds −0, which
/// leaves every value, its sign of zero included, as it was. Prediction: the identity again, lane by lane,
/// past the first impact, for every scheme of the fused step (cn, be, ps with both contact rows, ec,
/// cn-switch) and every target, with loaded and unloaded runs in the same groups; and every run but the
/// one left over in the lanes (a load that changes with t is still stepped alone). Dropping the load term
/// from the sweep down, or F₀ from the decision, fails (tried).
TEST_CASE("runs with a steady load share the lanes with runs without one, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 24);
  const int status_changes = fused_cases_alike(
      [](std::size_t lanes) { return 2 * lanes + 1; },
      [&](const BatchedCase& c, std::size_t k) {
        const Problem problem = k % 2 == 0 ? with_steady_load(benchmark_problem()) : benchmark_problem();
        return BarSimulation(problem, mesh, mod1(), case_parameters(c),
                             (0.5 + 0.1 * static_cast<double>(k % 7)) * mesh.h());
      },
      [](const BatchedSimulation& batched, std::vector<BarSimulation>& alone) {
        CHECK(batched.batched_runs() == alone.size() - 1);  // loaded or not, every run but the one left over
      });
  CHECK(status_changes > 0);  // CN-switch's θ-step, alone, with its load, was taken
  // A load that changes with t is formed at every step: such a run is stepped alone.
  std::vector<BarSimulation> two;
  Problem varying = benchmark_problem();
  varying.load = [](double x, double t) { return -(1.0 + x) * (1.0 + t); };
  two.emplace_back(varying, mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  two.emplace_back(varying, mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  CHECK(BatchedSimulation(std::move(two)).batched_runs() == 0);
}

/// @file lanes_alone.cpp
/// ## Heads of different lengths in one group
///
/// The fused step's first rows are explicit (FastStep::head: the rows the mass redistribution and the contact
/// row make differ from the Toeplitz interior), and their number depends on the mass: 1 for the consistent
/// mass, 2 for Mod 1 to Mod 3, more for a mass spread over the first nodes. A group takes the longest head;
/// in the rows where the heads differ, the kernels form both rows, the explicit one and the Toeplitz one, and
/// each lane takes its own: its right-hand side in the sweep down, its energy sums in the sweep up (the
/// explicit rows' terms or the interior's differences, each into its own sums), the first values of its
/// interior sums at its own first interior row, and at row 1 the recurrence's d₋₁ as its run sets it.
/// Prediction: each lane bitwise its run stepped alone, past the first impact, for every scheme of the fused
/// step and every target, and the runs of one mesh and family in full groups whatever their heads (before,
/// each head was a group of its own: a run of the baseline's consistent mass next to three of Mod 1–3 was
/// stepped alone). Taking every mixed row as the interior's, or leaving row 1's d₋₁ to the explicit lanes'
/// value, fails (tried).
TEST_CASE("runs whose heads differ in length share a group, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 24);
  const int status_changes =
      fused_cases_alike([](std::size_t lanes) { return 2 * lanes; },
                        [&](const BatchedCase& c, std::size_t k) {
                          // The schemes that need a massless contact node have heads that differ through the masses that keep
                          // it massless.
                          const std::vector<MassRedistribution> masses = {
                              inertia_allowed(c) ? consistent_mass() : mod2(), mod1(), spread_over_first_nodes(3),
                              mod3(0.25), spread_over_first_nodes(5)};
                          return BarSimulation(benchmark_problem(), mesh, masses[k % masses.size()], case_parameters(c),
                                               (0.5 + 0.1 * static_cast<double>(k % 7)) * mesh.h());
                        },
                        [](const BatchedSimulation& batched, std::vector<BarSimulation>& alone) {
                          std::size_t shortest = alone[0].step_parts().fast->head().size(), longest = shortest;
                          for (BarSimulation& run : alone) {
                            const std::size_t head = run.step_parts().fast->head().size();
                            shortest = std::min(shortest, head), longest = std::max(longest, head);
                          }
                          CHECK(shortest < longest);                      // not vacuous: the heads differ
                          CHECK(batched.batched_runs() == alone.size());  // every run in the lanes
                          CHECK(batched.group_widths().size() == 2);      // two full groups, whatever the heads
                        });
  CHECK(status_changes > 0);  // CN-switch changed status
}

/// @file lanes_alone.cpp
/// ## Far ends of both kinds in one group
///
/// A mesh of N elements has N unknowns when its far end is held (node N eliminated) and N + 1 when it is
/// free: the same family's runs of one mesh, the paper's benchmark and a free bar, differ by one row. A
/// group takes n = N + 1 rows; in a lane of N unknowns the elimination starts at row n − 2, its last row,
/// from zero, row n − 1 is never read, and in the sweep up its interior ends one row earlier: its interior
/// sums are closed there, then its last row's terms are added, and row n − 1 leaves its sums as they are.
/// Prediction: each lane bitwise its run stepped alone past the first impact, for every scheme of the
/// fused step and every target, with heads of different lengths and steady loads in the same groups, and
/// the runs of one mesh and family in full groups. Taking the long lanes' row n − 2 in the short lanes, or
/// closing their interior sums after their last row, fails (tried). The short lanes' row n − 1 is zeros
/// (its factors, U and W) and stays so, so its carry into row n − 2 and its terms vanish in any case: the
/// masks there keep only the sign of a zero, and removing them is not seen by this test.
TEST_CASE("runs with a held and with a free far end share a group, each lane bitwise its run alone") {
  const UniformMesh held(1.0, 24), free_end = with_far_end(held, FarEnd::free);
  const int status_changes = fused_cases_alike(
      [](std::size_t lanes) { return 2 * lanes; },
      [&](const BatchedCase& c, std::size_t k) {
        // A steady load in some runs of either kind; the masses with heads of different lengths.
        const Problem problem = k % 3 == 1 ? with_steady_load(benchmark_problem()) : benchmark_problem();
        const MassRedistribution mass = k % 4 < 2 ? mod1() : inertia_allowed(c) ? consistent_mass() : mod3();
        return BarSimulation(problem, k % 2 == 0 ? held : free_end, mass, case_parameters(c),
                             (0.5 + 0.1 * static_cast<double>(k % 7)) * held.h());
      },
      [](const BatchedSimulation& batched, std::vector<BarSimulation>& alone) {
        std::size_t held_runs = 0;
        for (const BarSimulation& run : alone) held_runs += run.mesh().far_end == FarEnd::clamped;
        CHECK(held_runs > 0);
        CHECK(held_runs < alone.size());                // not vacuous: both kinds of far end
        CHECK(batched.batched_runs() == alone.size());  // every run in the lanes
        CHECK(batched.group_widths().size() == 2);      // two full groups, whatever the far ends
      });
  CHECK(status_changes > 0);  // CN-switch changed status
}

/// @file lanes_alone.cpp
/// ## One family, one group
///
/// Crank–Nicolson and backward Euler differ only in the values of their step's matrices and rates, which
/// each lane holds for itself: a group can mix them (batch_family 0), and the sweep layer batches them
/// together, so that the lanes of a batch share their Δt more often. Checked: such a mixed group is one
/// group (every run in the lanes), each lane bitwise its run alone past the first impact, on every
/// target; and two runs of two schemes share a group exactly when batch_family says so.
TEST_CASE("Crank-Nicolson and backward Euler share the lanes of a group, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 40);
  const std::vector<double> ratios = {0.5, 0.5, 1.0, 0.25};
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    std::vector<BarSimulation> batch, alone;
    Index steps = 0;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      SchemeParameters p;
      p.scheme = k % 2 == 0 ? Scheme::crank_nicolson : Scheme::backward_euler;
      const double dt = ratios[k % ratios.size()] * mesh.h();
      const MassRedistribution mass = k % 3 == 0 ? mod1() : k % 3 == 1 ? mod2() : mod3();
      batch.emplace_back(benchmark_problem(), mesh, mass, p, dt);
      alone.emplace_back(benchmark_problem(), mesh, mass, p, dt);
      steps = std::max(steps, static_cast<Index>(1.5 / dt));  // past t = 1, the first impact, for every lane
    }
    BatchedSimulation batched(std::move(batch));
    REQUIRE(batched.batched_runs() == target.lanes);
    for (Index n = 1; n <= steps; ++n) {
      batched.step();
      for (std::size_t k = 0; k < target.lanes; ++k) alone[k].step();
    }
    bool identical = true;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const Sample a = batched.run(k).sample(), b = alone[k].sample();
      identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                  same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level;
      CHECK(b.time > 1.0);
    }
    CHECK(identical);
  }
  use_batch_target(0);
  // Two runs of two schemes (mod1: allowed for every scheme with a batched kernel) are one group iff
  // their families are the same.
  const std::vector<Scheme> schemes = {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman,
                                       Scheme::energy_conserving, Scheme::switching};
  int shared = 0;
  for (Scheme a : schemes)
    for (Scheme b : schemes) {
      CAPTURE(to_string(a));
      CAPTURE(to_string(b));
      SchemeParameters pa, pb;
      pa.scheme = a, pb.scheme = b;
      std::vector<BarSimulation> two;
      two.emplace_back(benchmark_problem(), mesh, mod1(), pa, 0.5 * mesh.h());
      two.emplace_back(benchmark_problem(), mesh, mod1(), pb, 0.25 * mesh.h());
      const BatchedSimulation batched(std::move(two));
      const bool together = batched.batched_runs() == 2;
      CHECK(together == (batch_family(a) == batch_family(b)));
      shared += together && a != b;
    }
  CHECK(shared == 2);  // (CN, BE) and (BE, CN)
}

/// @file lanes_alone.cpp
/// ## The plateau of the factors
///
/// Prediction. Crank–Nicolson's step matrix is A = M + (Δt²/4) S; on the interior, with c = Δt²/4,
/// d = 4h/6 + 2c/h on the diagonal and l = u = h/6 − c/h beside it. The pivots from the last row up,
/// p_i = d − l²/p_{i+1}, approach p* = (d + √(d² − 4l²))/2 with the rate ρ = l²/p*² per row; at Δt = 2h,
/// the slowest lane below, d = 8h/3, l = −5h/6, p* ≈ 2.374h and ρ ≈ 0.123, so the relative distance falls
/// below ε = 2⁻⁵³ within ln ε / ln ρ ≈ 18 rows. Allowed: 40 rows off the plateau (the head rows, the
/// rounding onto the fixed point, and the factor products, which need two equal rows). And the same bits,
/// lane by lane, as each run stepped alone, past the first impact of the finest step, on every target.
TEST_CASE("the factors repeat on a plateau of the interior rows, which the sweeps hold in registers") {
  const UniformMesh mesh(1.0, 200);
  const std::vector<double> ratios = {0.25, 0.5, 1.0, 2.0};
  const Index steps = static_cast<Index>(1.2 / (ratios.front() * mesh.h()));  // past t = 1, the first impact
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    std::vector<BarSimulation> batch, alone;
    SchemeParameters cn;
    cn.scheme = Scheme::crank_nicolson;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const double dt = ratios[k % ratios.size()] * mesh.h();
      const MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
      batch.emplace_back(benchmark_problem(), mesh, mass, cn, dt);
      alone.emplace_back(benchmark_problem(), mesh, mass, cn, dt);
    }
    BatchedSimulation batched(std::move(batch));
    REQUIRE(batched.batched_runs() == target.lanes);
    const std::size_t interior = static_cast<std::size_t>(mesh.unknowns()) - 1;  // rows 0 … n − 2
    CAPTURE(batched.plateau_rows());
    CHECK(batched.plateau_rows() + 40 >= interior);
    bool identical = true;
    for (Index n = 1; n <= steps; ++n) {
      batched.step();
      for (std::size_t k = 0; k < target.lanes; ++k) alone[k].step();
    }
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const Sample a = batched.run(k).sample(), b = alone[k].sample();
      identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                  same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level;
      CHECK(alone[k].sample().time > 1.0);
    }
    CHECK(identical);
  }
  use_batch_target(0);
}

/// @file lanes_alone.cpp
/// ## A remainder in a narrow group
///
/// A family of W + 2 or W + 3 runs (W the target's lanes) leaves, after one full group, a remainder of 2
/// or 3 runs; the constructor puts it in one group of the narrowest width that holds it (2 lanes for 2
/// runs, 4 for 3; on a target of 4 lanes, 3 runs fill a full group; on one of 2 lanes there is no
/// remainder of two, and one of one is stepped alone). Prediction: those widths, every run of a group
/// counted by batched_runs, a lane's sample read with the stride of its group's width, and every lane
/// bitwise its run stepped alone past the first impact, for each kernel family (two-level, Paoli–Schatzman,
/// EC, CN-switch) on every target: the narrow kernels are the full one's operations on fewer lanes.
TEST_CASE("a batch's remainder is a group of the narrowest width that holds it, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 20);
  const std::vector<Scheme> schemes = {Scheme::crank_nicolson, Scheme::paoli_schatzman, Scheme::energy_conserving,
                                       Scheme::switching};
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    const std::size_t W = target.lanes;
    for (const std::size_t extra : {std::size_t{2}, std::size_t{3}})
      for (const Scheme scheme : schemes) {
        CAPTURE(extra);
        CAPTURE(to_string(scheme));
        const std::size_t count = W + extra;
        std::vector<BarSimulation> batch, alone;
        Index steps = 0;
        for (std::size_t k = 0; k < count; ++k) {
          SchemeParameters p;
          p.scheme = scheme;
          const double dt = (0.5 + 0.1 * static_cast<double>(k % 11)) * mesh.h();
          const MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
          batch.emplace_back(benchmark_problem(), mesh, mass, p, dt);
          alone.emplace_back(benchmark_problem(), mesh, mass, p, dt);
          steps = std::max(steps, static_cast<Index>(1.5 / dt));  // past t = 1, the first impact, for every lane
        }
        BatchedSimulation batched(std::move(batch));
        CHECK(batched.lanes() == W);
        std::vector<std::size_t> expected(count / W, W);
        const std::size_t q = count % W;
        if (q >= 2) expected.push_back(q <= 2 ? 2 : q <= 4 ? 4 : W);
        CHECK(batched.group_widths() == expected);
        CHECK(batched.batched_runs() == count - (q == 1 ? 1 : 0));
        bool identical = true;
        for (Index n = 1; n <= steps; ++n) {
          batched.step();
          for (std::size_t k = 0; k < count; ++k) alone[k].step();
        }
        // The last run lies in the remainder's group: its lane's stride is the group's width (or 1 if a
        // CN-switch status change has just stepped it alone, its vectors its own).
        LaneVectors lanes{nullptr, nullptr, 0};
        batched.sample(count - 1, lanes);
        const std::size_t stride = q >= 2 ? expected.back() : q == 1 ? 1 : W;
        CHECK((lanes.stride == stride || (scheme == Scheme::switching && lanes.stride == 1)));
        for (std::size_t k = 0; k < count; ++k) {
          const Sample a = batched.run(k).sample(), b = alone[k].sample();
          identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                      same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level &&
                      same_bits(a.time, b.time);
          CHECK(b.time > 1.0);
        }
        CHECK(identical);
      }
  }
  use_batch_target(0);
}

}  // namespace mrm
