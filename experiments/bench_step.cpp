// bench_step: the cost of one time step, per node, against the practical limit of a tridiagonal solve.
//
// What it computes. A time step of Crank–Nicolson, backward Euler and Paoli–Schatzman on the P1 bar
// with a redistributed mass is one solve with a constant tridiagonal matrix A plus a scalar contact
// decision (mathematics.md §4, lib/time/schemes.cpp): its cost should be linear in the number of nodes N and
// close to that of a bare solve with the same pre-factored A. For N = 2^6 … 2^20 elements this program
// times, in nanoseconds per node per step:
//   cn, be, ps   BarSimulation::step() of each scheme (Mod 3 mass, Δt = h/2, the benchmark problem;
//                Paoli–Schatzman with β = ¼ and the algebraic contact row), with the fast step that
//                every program uses (the fused two-chain kernel of lib/steps/fast_step.cpp);
//   cn_ref, be_ref, ps_ref
//                the same with the reference step (StepKernel::reference, lib/time/schemes.cpp: the
//                scheme written as its derivation, assembled matrices, ContactSolver::solve, the
//                velocity and the energy as whole vectors; mathematics.md §4);
//   cn+errors    the same Crank–Nicolson step followed by ErrorAccumulator::add, the error measures of
//                mathematics.md §5 against the exact solution (the difference is the cost of the errors);
//   bare         ContactSolver::solve with Crank–Nicolson's step matrix A: one sweep down, the contact
//                decision, one sweep up, plain substitution loops on the factors computed once (the
//                practical limit of a step);
//   bare2        the same solve with each sweep run as two interleaved chains (the form the schemes'
//                fused step uses, contact.hpp): what the dependency chain of the substitution costs;
//   eigen        Eigen's SimplicialLDLT solve (factorised once) of the same matrix, symmetrised by
//                scaling its algebraic contact row 0 by θ (same sparsity, same cost).
// A second table, "batched", gives for the same N the cost per node, step and run of W runs of the cn
// configuration advanced together in the W lanes of each vector target the machine has (lib/batched/batched_step.cpp:
// AVX-512, AVX2, SSE4, ..., chosen at run time), beside the scalar step, the bare solve (plain, two-chain,
// and two right-hand sides at a time, "bare_x2"), and the limit of the widest target: the larger of the time
// of the step's memory traffic alone (64 to 104 bytes per node and run, timed as a skeleton of its sweeps,
// repro/step_limits.hpp, its arrays at the step's page offsets) and of its 32 operations per node and run
// at the peak rate measured for them; beside the traffic, "aliased", the same skeleton with its arrays
// 64 bytes apart within their pages (what the step's layout avoids, lib/batched/lane_array.hpp); its
// last lines give the widest target and batched_speedup, scalar over batched at the largest N.
// Then the ratio of each scheme (fast and reference steps) and of a run with its error measures (cn+errors:
// its budget is 1.5) to the bare solve, the log-log slope of the cost per step against N
// over 2^10 … 2^20 (least squares), and the peak resident memory of a Crank–Nicolson and of a
// Paoli–Schatzman run at the largest N and at N/4, each in a fresh child process, to show that the
// memory is linear in N.
//
// Sample runs:
//   bench_step
//   bench_step --quick
//   bench_step --output output/bench/bench_step.dat --tex output/bench/bench_step.tex
//              --markdown output/bench/bench_step.md
//
// Description. Timings depend on the machine and its load: they are written to output/bench/, never
// compared byte for byte. Method: every measurement first warms up (and calibrates) by doubling the
// number of steps until a batch takes 2 ms, then times R batches of as many steps as make about 10 ms
// each with std::chrono::steady_clock (or, with --clock cpu, the thread's CPU time, which a loaded
// machine disturbs less); the median over the batches is the figure, the minimum is reported beside
// it (--statistic min: the other way round, the least disturbed batch for a shared machine). A figure
// that cannot be trusted is written n/a with its reason: a difference of two timings within their noise,
// a slope over fewer than three sizes or with a standard error above 0.1. Nothing is pinned; run it on an
// idle machine. Steps: (1) read the options;
// (2) open the outputs; (3) measure the peak memory in child processes (before anything else grows the
// heap); (4) time every variant for every N; (5) fit the slopes; (6) print and write the tables.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/SparseCholesky>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"
#include "step_limits.hpp"
#include "report_values.hpp"
#include "table.hpp"
#include "batched/batched_step.hpp"
#include "steps/contact.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;
using mrm::Index;

namespace {

// ---- Timing -------------------------------------------------------------------------------------

using Clock = std::chrono::steady_clock;

// The clock of the timed batches: wall time from std::chrono::steady_clock (the default), or the CPU
// time of this thread (CLOCK_THREAD_CPUTIME_ID), which does not count the time the thread waits while
// other processes hold the core: the choice for a shared, loaded machine.
bool use_thread_cpu_time = false;

double seconds_now() {
  if (use_thread_cpu_time) {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

// The figure of a timing: the median of its batches (the default), or their minimum (--statistic min:
// on a shared machine the batch least disturbed by other processes, the closest to the cost itself).
bool use_minimum = false;

struct Timing {
  double value = NAN;                  // the figure: the median or the minimum, nanoseconds per node per step
  double median = NAN, minimum = NAN;  // both statistics of the batches
  long steps_per_batch = 0;
};

// `batch(k)` performs k steps. Warm-up and calibration: double k until one batch lasts `warmup`
// seconds; then `repetitions` batches of k·target/elapsed steps; median and minimum per node per step.
Timing measure(const std::function<void(long)>& batch, Index nodes, int repetitions, double target) {
  const double warmup = 2e-3;
  long k = 1;
  double elapsed = 0;
  for (;;) {
    const double start = seconds_now();
    batch(k);
    elapsed = seconds_now() - start;
    if (elapsed >= warmup || k > (1L << 40)) break;
    k *= 2;
  }
  const long steps = std::max(1L, static_cast<long>(std::llround(k * target / elapsed)));
  std::vector<double> per_node(static_cast<std::size_t>(repetitions));
  for (double& t : per_node) {
    const double start = seconds_now();
    batch(steps);
    const double seconds = seconds_now() - start;
    t = seconds * 1e9 / (static_cast<double>(steps) * static_cast<double>(nodes));
  }
  std::sort(per_node.begin(), per_node.end());
  const std::size_t r = per_node.size();
  Timing result;
  result.median = r % 2 ? per_node[r / 2] : 0.5 * (per_node[r / 2 - 1] + per_node[r / 2]);
  result.minimum = per_node.front();
  result.value = use_minimum ? result.minimum : result.median;
  result.steps_per_batch = steps;
  return result;
}

// ---- The variants -------------------------------------------------------------------------------

// The configuration every variant shares: the benchmark of mathematics.md §2, Mod 3, Δt = C h.
const double courant = 0.5;

// Crank–Nicolson's step matrix A = M^mod + θS with θ = Δt²/4 and row 0 replaced by the algebraic
// contact row S₀· (lib/time/schemes.cpp); `symmetric` scales that row by θ instead, which gives the
// symmetric M^mod + θS (M^mod has a zero row 0).
mrm::Tridiagonal crank_nicolson_matrix(const mrm::UniformMesh& mesh, bool symmetric) {
  const double dt = courant * mesh.h(), theta = dt * dt / 4;
  const mrm::Tridiagonal s = mrm::p1_stiffness(mesh);
  mrm::Tridiagonal a = mrm::modified_mass(mesh, mrm::mod3()).plus(theta, s);
  if (!symmetric) {
    a.diag[0] = s.diag[0];
    a.upper[0] = s.upper[0];
  }
  return a;
}

Eigen::VectorXd random_vector(Index n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd b(n);
  for (Index i = 0; i < n; ++i) b[i] = uniform(random);
  return b;
}

// The reference-step variants come last, so that the columns of the others keep their places in the
// data file (figures/bench_step.gp reads them by index). A scheme's variants are named by its id in the
// registry (mrm::to_string), its reference step's with "_ref" appended.
const std::string variant_names[] = {mrm::to_string(mrm::Scheme::crank_nicolson),
                                     mrm::to_string(mrm::Scheme::backward_euler),
                                     mrm::to_string(mrm::Scheme::paoli_schatzman),
                                     "cn+errors",
                                     "bare",
                                     "eigen",
                                     "bare2",
                                     mrm::to_string(mrm::Scheme::crank_nicolson) + "_ref",
                                     mrm::to_string(mrm::Scheme::backward_euler) + "_ref",
                                     mrm::to_string(mrm::Scheme::paoli_schatzman) + "_ref"};
constexpr int variants = 10;
constexpr int v_cn = 0, v_be = 1, v_ps = 2, v_errors = 3, v_bare = 4, v_eigen = 5, v_bare2 = 6, v_cn_ref = 7,
              v_be_ref = 8, v_ps_ref = 9;

// The two-chain solve ("bare2"): the same factors, each sweep's recurrence substituted into itself
// so that it runs as two independent chains (ContactSolver::elimination_pair, upward_pair; the form
// the schemes' fused step uses). Compared with "bare", it shows what the dependency chain costs.
mrm::ContactStep two_chain_solve(const mrm::ContactSolver& solver, const double* b, double* u, double kappa) {
  const Index n = solver.size();
  const double *e = solver.elimination().data(), *e2 = solver.elimination_pair().data();
  const double *q = solver.inverse_pivot().data(), *c = solver.upward().data(), *c2 = solver.upward_pair().data();
  double b1 = 0, y1 = 0, y2 = 0;  // b_{i+1}, y_{i+1}, y_{i+2}
  for (Index i = n - 1; i >= 1; --i) {
    const double y = (b[i] - e[i] * b1) + e2[i] * y2;
    u[i] = y;
    b1 = b[i], y2 = y1, y1 = y;
  }
  const mrm::ContactStep step = solver.resolve_contact(b[0] - e[0] * y1, kappa, 0.0);
  double z1 = step.u0, u1 = step.u0, u2 = 0;  // z_{i−1}, u_{i−1}, u_{i−2}
  u[0] = step.u0;
  for (Index i = 1; i < n; ++i) {
    const double z = q[i] * u[i];
    const double ui = (z - c[i] * z1) + c2[i] * u2;
    u[i] = ui;
    z1 = z, u2 = u1, u1 = ui;
  }
  return step;
}

// A check that the timed code computed something sensible (guards against a benchmark of dead code):
// the backward error of the bare and Eigen solves, and the energy of the runs.
struct Sanity {
  double bare_residual = 0, eigen_residual = 0;
};

// The energy of a timed run, checked after its batches on 64 more (untimed) steps, by what each scheme
// is proved to do (mathematics.md §4, the doctests of schemes.cpp): Crank–Nicolson and Paoli–Schatzman
// (β = ¼) conserve their discrete energy at every step that does not change the contact status, backward
// Euler never increases it. One step changes the energy by the round-off of its evaluation and of the
// state: E is evaluated (fast_step.cpp) from sums of N terms, each sum within γ_N ≈ N ε of the sum of the
// magnitudes of its terms (recursive summation); the stiffness forms are sums of squares, and the mass
// form's telescoped −l D + (d + 2l) Q cancels at most a factor 3 (D ≤ 4 Q, l ≤ d/4), so each evaluation is
// within 3 (N + c) ε of E; two evaluations (E_k and E_{k+1}) and the rounding of the state (a few ε) give the
// tolerance per step τ = 8 (N + 16) ε relative to E, from N = 2² (τ ≈ 4e-14) to 2²⁰
// (τ ≈ 2e-9). A wrong step errs by O(h) or more. Status changes (λ < 0 switching on or off at either level
// of a step, or the level before) are skipped for Crank–Nicolson and Paoli–Schatzman, whose energy may jump
// there; at least one step must remain. A bound on E itself after millions of steps would not do: on
// N = 2² … 2⁴ the drift of the contact steps over a long run is not a bound of anything.
// Two further facts on small meshes such as N = 2⁴ (the timed number of steps, hence the state checked,
// depends on the machine's speed): backward Euler dissipates a small mesh's energy down to 1e-306 within
// the timed steps, where the state's squares are subnormal and a relative tolerance does not hold (its
// "relative change" can reach +0.003); and the first step checked may follow a status change at the last
// timed step (the level before it is not known here), where Paoli–Schatzman's energy can jump by −0.0023. So a step
// whose energy is below DBL_MIN/ε (the squares of the state lose relative precision) is not judged, and
// for Crank–Nicolson and Paoli–Schatzman the first step is not judged either (its level before is unknown).
void check_energy(mrm::BarSimulation& simulation, mrm::Scheme scheme, const mrm::UniformMesh& mesh) {
  const double tau = 8 * (static_cast<double>(mesh.unknowns()) + 16) * std::numeric_limits<double>::epsilon();
  const bool dissipative = scheme == mrm::Scheme::backward_euler;
  const double underflow = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  int underflowed = 0;
  bool before = simulation.sample().multiplier < 0, now = before;
  double energy = simulation.sample().energy, worst = 0;
  int checked = 0;
  for (int k = 0; k < 64; ++k) {
    simulation.step();
    const mrm::Sample s = simulation.sample();
    const bool next = s.has_multiplier && s.multiplier < 0;
    if (!std::isfinite(s.energy) || s.energy < 0)
      throw std::runtime_error("a timed run has a wrong energy: " + cli::format_real(s.energy) + " (" +
                               mrm::to_string(scheme) + ", N = " + std::to_string(mesh.elements) + ")");
    const double change = energy > 0 ? (s.energy - energy) / energy : s.energy == 0 ? 0.0 : INFINITY;
    if (energy < underflow) {
      ++underflowed;
    } else if (dissipative || (k > 0 && before == now && now == next)) {
      const double excess = dissipative ? change / tau : std::abs(change) / tau;
      worst = std::max(worst, excess);
      ++checked;
    }
    before = now, now = next, energy = s.energy;
  }
  if ((checked == 0 && underflowed == 0) || worst > 1)
    throw std::runtime_error("a timed run has a wrong energy: " + mrm::to_string(scheme) +
                             ", N = " + std::to_string(mesh.elements) + ": relative change " +
                             cli::format_real(worst * tau) + " per step against the tolerance " +
                             cli::format_real(tau) + " (" + std::to_string(checked) + " steps checked)");
}

// The normwise backward error max|Au − b| / (max|A| max|u| + max|b|), round-off size for a stable solve.
double relative_residual(const mrm::Tridiagonal& a, const Eigen::VectorXd& u, const Eigen::VectorXd& b) {
  const double norm_a =
      std::max({a.lower.cwiseAbs().maxCoeff(), a.diag.cwiseAbs().maxCoeff(), a.upper.cwiseAbs().maxCoeff()});
  return (a * u - b).cwiseAbs().maxCoeff() / (norm_a * u.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
}

std::array<Timing, variants> time_all(Index elements, int repetitions, double target, Sanity& sanity) {
  std::array<Timing, variants> t;
  const mrm::UniformMesh mesh(1.0, elements);
  const Index n = mesh.unknowns();
  const double dt = courant * mesh.h();
  const mrm::Problem problem = mrm::benchmark_problem();

  const mrm::Scheme schemes[3] = {mrm::Scheme::crank_nicolson, mrm::Scheme::backward_euler,
                                  mrm::Scheme::paoli_schatzman};
  const int fast_variants[3] = {v_cn, v_be, v_ps}, reference_variants[3] = {v_cn_ref, v_be_ref, v_ps_ref};
  for (int k = 0; k < 3; ++k) {
    for (const mrm::StepKernel kernel : {mrm::StepKernel::fast, mrm::StepKernel::reference}) {
      const int v = kernel == mrm::StepKernel::fast ? fast_variants[k] : reference_variants[k];
      mrm::BarSimulation simulation(problem, mesh, mrm::mod3(),
                                    mrm::parameters_of(schemes[k], mrm::ContactRow::algebraic, kernel), dt);
      t[v] = measure(
          [&](long s) {
            for (long i = 0; i < s; ++i) simulation.step();
          },
          n, repetitions, target);
      check_energy(simulation, schemes[k], mesh);
    }
  }
  {
    mrm::BarSimulation simulation(problem, mesh, mrm::mod3(), mrm::parameters_of(mrm::Scheme::crank_nicolson), dt);
    mrm::ErrorAccumulator errors(mesh, mrm::ExactSolution());
    t[v_errors] = measure(
        [&](long k) {
          for (long s = 0; s < k; ++s) {
            simulation.step();
            errors.add(simulation.sample());
          }
        },
        n, repetitions, target);
  }
  {
    const mrm::Tridiagonal a = crank_nicolson_matrix(mesh, false);
    const mrm::ContactSolver solver(a);
    const Eigen::VectorXd b = random_vector(n, 1);
    Eigen::VectorXd u(n);
    const double kappa = 1.0;  // the algebraic row's κ
    mrm::ContactStep last{};
    t[v_bare] = measure(
        [&](long k) {
          for (long s = 0; s < k; ++s) last = solver.solve(b.data(), u.data(), kappa);
        },
        n, repetitions, target);
    // The residual of the solve with the contact force it found: A u = b − κ λ e₀.
    Eigen::VectorXd rhs = b;
    rhs[0] -= kappa * last.multiplier;
    sanity.bare_residual = std::max(sanity.bare_residual, relative_residual(a, u, rhs));

    Eigen::VectorXd u2(n);
    t[v_bare2] = measure(
        [&](long k) {
          for (long s = 0; s < k; ++s) last = two_chain_solve(solver, b.data(), u2.data(), kappa);
        },
        n, repetitions, target);
    rhs = b;
    rhs[0] -= kappa * last.multiplier;
    sanity.bare_residual = std::max(sanity.bare_residual, relative_residual(a, u2, rhs));
  }
  {
    const mrm::Tridiagonal a = crank_nicolson_matrix(mesh, true);
    const Eigen::SparseMatrix<double> sparse = a.to_sparse();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sparse);
    if (ldlt.info() != Eigen::Success) throw std::runtime_error("Eigen's SimplicialLDLT failed to factorise A");
    const Eigen::VectorXd b = random_vector(n, 2);
    Eigen::VectorXd u(n);
    t[v_eigen] = measure(
        [&](long k) {
          for (long s = 0; s < k; ++s) u = ldlt.solve(b);
        },
        n, repetitions, target);
    sanity.eigen_residual = std::max(sanity.eigen_residual, relative_residual(a, u, b));
  }
  return t;
}

// ---- Batched runs, the bare solve two at a time, and the memory limit ------------------------------

// The bare solve of two right-hand sides at once ("bare x2"): the plain substitution loops of
// ContactSolver::solve, each loop carrying two independent chains (one per right-hand side), so that the
// latency of one chain is hidden by the other; ns per node per solve.
void two_at_a_time_solve(const mrm::ContactSolver& solver, const double* b, const double* b2, double* u, double* u2,
                         double kappa) {
  const Index n = solver.size();
  const double *e = solver.elimination().data(), *q = solver.inverse_pivot().data(), *c = solver.upward().data();
  double y = b[n - 1], y2 = b2[n - 1];
  u[n - 1] = y, u2[n - 1] = y2;
  for (Index i = n - 2; i >= 0; --i) {
    y = b[i] - e[i] * y, y2 = b2[i] - e[i] * y2;
    u[i] = y, u2[i] = y2;
  }
  const mrm::ContactStep s = solver.resolve_contact(u[0], kappa, 0.0), s2 = solver.resolve_contact(u2[0], kappa, 0.0);
  u[0] = s.u0, u2[0] = s2.u0;
  for (Index i = 1; i < n; ++i) {
    u[i] = q[i] * u[i] - c[i] * u[i - 1];
    u2[i] = q[i] * u2[i] - c[i] * u2[i - 1];
  }
}

struct BatchedTimings {
  std::vector<Timing> per_target;  // ns per node per step per run, one per batch_targets()
  Timing bare_x2;                  // ns per node per solve
  double plateau = 0;              // the fraction of the rows whose factors stay in registers
  double bytes = 0;                // bytes per node, step and run of the batched step's traffic
  double traffic = 0;              // ns per node per step per run of that traffic alone (the skeleton)
  double aliased = 0;              // the same with the skeleton's arrays 64 bytes apart in their pages
  double bandwidth = 0;            // bytes per ns of the skeleton: bytes / traffic
  double operation = 0;            // ns per lane operation at the peak rate (arithmetic_rounds)
  double arithmetic = 0;           // ns per node per step per run of the step's operations at that rate
  double limit = 0;                // the larger of traffic and arithmetic
};

// The batched step's memory traffic per node, step and run (lib/batched/batched_step.cpp): the sweep down reads
// U, W' and writes y; the sweep up reads y, U, W' and writes Uⁿ⁺¹ and W': 8 doubles, 64 bytes. Off the
// plateau of the factors (BatchedSimulation::plateau_rows: the interior rows whose LU factors repeat, held
// in registers) the sweeps also read ε, εε (down) and 1/d, c, cc (up): 40 bytes more. Which level of
// the memory serves those bytes depends on the order of the accesses (the sweep up starts on the rows
// the sweep down has just written), so their time is measured, not modelled: the skeleton of the two
// sweeps (repro/step_limits.hpp) makes the same loads and stores in the same order with no arithmetic
// worth the name.
constexpr double batched_state_bytes = 8 * 8, batched_factor_bytes = 5 * 8;
// Its arithmetic per node, step and run on an interior row of Crank–Nicolson (SweepDown, SweepUpT<false,
// false>): the right-hand side r.c1l(uᵢ₋₁ + uᵢ₊₁) + r.c1d uᵢ + r.c2l(wᵢ₋₁ + wᵢ₊₁) + r.c2d wᵢ, 4
// multiplies and 5 adds, and the elimination (bᵢ − εᵢ bᵢ₊₁) + εεᵢ yᵢ₊₂, 2 and 2 (13 down); the back
// substitution z = yᵢ/pᵢ, (z − cᵢ z₋) + ccᵢ d₋₂, 3 and 2, the new state u + d, 1, the velocity
// rate·d − memory·w, 2 and 1, and the energy's four sums of squares with their two differences, 4 and
// 6 (19 up): 32 operations, each a multiply or an add (none fused), as arithmetic_rounds performs them.
constexpr double batched_operations = 32;

BatchedTimings time_batched(Index elements, int repetitions, double target) {
  BatchedTimings result;
  const mrm::UniformMesh mesh(1.0, elements);
  const Index n = mesh.unknowns();
  const double dt = courant * mesh.h();
  for (const mrm::BatchTarget& t : mrm::batch_targets()) {
    mrm::use_batch_target(t.bit);
    std::vector<mrm::BarSimulation> runs;
    for (std::size_t k = 0; k < t.lanes; ++k)
      runs.emplace_back(mrm::benchmark_problem(), mesh, mrm::mod3(), mrm::parameters_of(mrm::Scheme::crank_nicolson),
                        dt);
    mrm::BatchedSimulation batch(std::move(runs));
    if (batch.batched_runs() != t.lanes) throw std::runtime_error("the batched step did not batch its runs");
    // The plateau of one group (the runs are the same configuration: every group has the same one).
    if (result.per_target.empty())
      result.plateau = static_cast<double>(batch.plateau_rows()) /
                       static_cast<double>(batch.group_widths().size() * static_cast<std::size_t>(n));
    Timing timing = measure(
        [&](long s) {
          for (long i = 0; i < s; ++i) batch.step();
        },
        n * static_cast<Index>(t.lanes), repetitions, target);
    if (!std::isfinite(batch.run(0).sample().energy)) throw std::runtime_error("a batched run has a wrong energy");
    result.per_target.push_back(timing);
  }
  mrm::use_batch_target(0);
  {
    const mrm::ContactSolver solver(crank_nicolson_matrix(mesh, false));
    const Eigen::VectorXd b = random_vector(n, 1), b2 = random_vector(n, 3);
    Eigen::VectorXd u(n), u2(n);
    result.bare_x2 = measure(
        [&](long k) {
          for (long s = 0; s < k; ++s) two_at_a_time_solve(solver, b.data(), b2.data(), u.data(), u2.data(), 1.0);
        },
        2 * n, repetitions, target);
  }
  {
    // The skeleton of the step's traffic at the widest target (the arrays of a group of N + 1 rows and W
    // lanes, its plateau as long as the batch's), then the step's 32 operations at the rate measured for
    // them.
    mrm::repro::TrafficSkeleton skeleton(static_cast<std::size_t>(n),
                                         static_cast<std::size_t>(std::llround(result.plateau * n)));
    const std::size_t W = skeleton.lanes();
    const Timing traffic = measure(
        [&](long s) {
          for (long i = 0; i < s; ++i) skeleton.step();
        },
        n * static_cast<Index>(W), repetitions, target);
    // The same traffic with the arrays 64 bytes apart within their pages (the k-th at 64k), one row of W
    // lanes apart for W = 8: what the step's layout (lib/batched/lane_array.hpp) avoids.
    mrm::repro::TrafficSkeleton aliased(static_cast<std::size_t>(n),
                                        static_cast<std::size_t>(std::llround(result.plateau * n)), 64);
    result.aliased = measure(
                         [&](long s) {
                           for (long i = 0; i < s; ++i) aliased.step();
                         },
                         n * static_cast<Index>(W), repetitions, target)
                         .value;
    result.bytes = batched_state_bytes + (1 - result.plateau) * batched_factor_bytes;
    result.traffic = traffic.value;
    result.bandwidth = result.bytes / result.traffic;
    constexpr long rounds = 1000;
    double sink = 0;
    const Timing operation =
        measure([&](long s) { sink += mrm::repro::arithmetic_rounds(s * rounds, 0.5, 1.0); },
                static_cast<Index>(rounds * mrm::repro::arithmetic_operations_per_round) * static_cast<Index>(W),
                repetitions, target);
    if (!std::isfinite(sink)) throw std::runtime_error("the arithmetic rounds gave a wrong value");
    result.operation = operation.value;
    result.arithmetic = batched_operations * result.operation;
    result.limit = std::max(result.traffic, result.arithmetic);
  }
  return result;
}

// ---- Peak memory --------------------------------------------------------------------------------

// The peak resident set (ru_maxrss, KiB on Linux) that a run of `steps` steps of `scheme` at N
// elements adds to a fresh child process: the child records its peak before building anything and
// after the run, and returns the difference through a pipe. A process's peak never decreases, so
// the child starts small (forked before the timings grow the parent) and does nothing else.
long memory_increment_kib(mrm::Scheme scheme, Index elements, Index steps) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe() failed");
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("fork() failed");
  if (child == 0) {
    close(fd[0]);
    long increment = -1;
    try {
      rusage before{}, after{};
      getrusage(RUSAGE_SELF, &before);
      const mrm::UniformMesh mesh(1.0, elements);
      mrm::BarSimulation simulation(mrm::benchmark_problem(), mesh, mrm::mod3(), mrm::parameters_of(scheme),
                                    courant * mesh.h());
      mrm::ErrorAccumulator errors(mesh, mrm::ExactSolution());
      for (Index k = 0; k < steps; ++k) {
        simulation.step();
        errors.add(simulation.sample());
      }
      getrusage(RUSAGE_SELF, &after);
      increment = after.ru_maxrss - before.ru_maxrss;
    } catch (...) {
      increment = -1;
    }
    const ssize_t written = write(fd[1], &increment, sizeof increment);
    close(fd[1]);
    _exit(written == static_cast<ssize_t>(sizeof increment) ? 0 : 1);
  }
  close(fd[1]);
  long increment = -1;
  const ssize_t got = read(fd[0], &increment, sizeof increment);
  close(fd[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (got != static_cast<ssize_t>(sizeof increment) || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || increment < 0)
    throw std::runtime_error("the memory measurement in a child process failed");
  return increment;
}

// ---- Fit ----------------------------------------------------------------------------------------

// A value that could not be measured or cannot be trusted (a slope over fewer than three sizes or too
// noisy, a marginal memory with one size, a cost below the timing noise) is written "n/a", never nan (the data files' rule, output_file.hpp).
std::string fixed(double value, int digits) {
  if (!std::isfinite(value)) return "n/a";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

// The least-squares slope of log(cost per step) against log N over the sizes in [first, last] (NaN
// with fewer than two).
double loglog_slope(const std::vector<Index>& sizes, const std::vector<double>& ns_per_node, Index first, Index last,
                    double* error = nullptr) {
  std::vector<double> x, y;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    if (sizes[k] < first || sizes[k] > last || !(ns_per_node[k] > 0)) continue;
    x.push_back(std::log(static_cast<double>(sizes[k])));
    y.push_back(std::log(ns_per_node[k] * static_cast<double>(sizes[k])));
  }
  if (x.size() < 2) return NAN;
  double c0, c1, cov00, cov01, cov11, sumsq;
  if (gsl_fit_linear(x.data(), 1, y.data(), 1, x.size(), &c0, &c1, &cov00, &cov01, &cov11, &sumsq) != GSL_SUCCESS)
    return NAN;
  if (error) *error = x.size() > 2 ? std::sqrt(cov11) : NAN;
  return c1;
}

// A slope is given when it can be trusted: over at least three sizes, with a standard error of at most
// this (a cost linear in N has slope 1; noisy timings over a short range of N can give 0.7 or 1.3).
constexpr double largest_slope_error = 0.1;

// Why a slope is not given, for the text outputs ("n/a: ..."); empty when it is.
std::string slope_reason(double slope, double error) {
  if (std::isfinite(slope)) return "";
  if (!std::isfinite(error)) return "fewer than three sizes in the fitted range";
  return "the fit's standard error, " + fixed(error, 3) + ", exceeds " + fixed(largest_slope_error, 1) +
         " (timings too noisy for the range of N)";
}

// The load average of the machine (/proc/loadavg, 1 minute): timings taken under load are suspect.
std::string load_average() {
  std::ifstream file("/proc/loadavg");
  std::string one;
  return file >> one ? one : "unknown";
}

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

// The options, with their defaults (--quick lowers those not given explicitly).
struct Options {
  long min_log2 = 6, max_log2 = 20, repetitions = 11;
  double target_ms = 10;
  bool quick = false;
  std::string output, tex, markdown, clock = "wall", statistic = "median";
};

// Step 1: the options, declared on the parser.
void declare_options(cli::Parser& parser, Options& o) {
  parser.add_integer("--min-log2", "", "K", "smallest mesh N = 2^K elements (K >= 2)", &o.min_log2,
                     cli::in_closed_range(2, 24));
  parser.add_integer("--max-log2", "", "K", "largest mesh N = 2^K elements (K <= 24)", &o.max_log2,
                     cli::in_closed_range(2, 24));
  parser.add_integer("--repetitions", "-r", "R", "timed batches per measurement (the median is reported)",
                     &o.repetitions, cli::in_closed_range(1, 1000));
  parser.add_real("--batch-ms", "", "MS", "target duration of one timed batch in milliseconds", &o.target_ms,
                  cli::in_closed_range(0.1, 10000));
  parser.add_flag("--quick", "-q", "smoke test: N up to 2^12, 3 batches of 2 ms (overridden by explicit options)",
                  &o.quick);
  parser.add_choice("--clock", "", "C",
                    "clock of the timed batches: wall (steady_clock) or cpu (this thread's CPU time, for a loaded "
                    "machine)",
                    {"wall", "cpu"}, &o.clock);
  parser.add_choice("--statistic", "", "S",
                    "the figure of each timing over its batches: the median, or the minimum (the batch least "
                    "disturbed by other processes, for a shared machine)",
                    {"median", "min"}, &o.statistic);
  parser.add_output("--output", "-o", "write the timings as a gnuplot data file", &o.output);
  parser.add_output("--tex", "", "write the table as a LaTeX tabular", &o.tex);
  parser.add_output("--markdown", "", "write the table as Markdown", &o.markdown);
}

// --quick's defaults, and the checks the parser's ranges cannot make.
void settle_options(const cli::Parser& parser, Options& o) {
  if (o.quick) {
    if (!parser.given("--max-log2")) o.max_log2 = 12;
    if (!parser.given("--repetitions")) o.repetitions = 3;
    if (!parser.given("--batch-ms")) o.target_ms = 2;
  }
  if (o.min_log2 > o.max_log2)
    throw cli::UsageError("--min-log2: must not exceed --max-log2 (" + std::to_string(o.max_log2) + ")");
  // The peak memory at the largest mesh, measured at N = 2^20: 420 bytes per element (the schemes,
  // the solvers compared, the error accumulator); 512 with a margin.
  cli::require_mesh_memory("--max-log2", std::ldexp(1.0, static_cast<int>(o.max_log2)), 512);
}

// Peak memory, in fresh children: the largest N and a quarter of it, Crank–Nicolson and Paoli–Schatzman
// (which holds its Crank–Nicolson starter until the first step), 4 steps each, with the error accumulator.
struct Memory {
  Index big = 0, small = 0;
  long cn_big = 0, cn_small = 0, ps_big = 0, ps_small = 0;  ///< KiB

  static double bytes_per_node(long kib, Index n) { return 1024.0 * static_cast<double>(kib) / static_cast<double>(n); }
  // The marginal cost, (memory(N) − memory(N/4)) / (N − N/4): the constant of a memory linear in N.
  double marginal(long kib_big, long kib_small) const {
    return big > small ? 1024.0 * static_cast<double>(kib_big - kib_small) / static_cast<double>(big - small) : NAN;
  }
};

Memory measure_memory(long min_log2, long max_log2) {
  Memory m;
  m.big = Index{1} << max_log2;
  m.small = std::max<Index>(Index{1} << min_log2, m.big / 4);
  m.cn_big = memory_increment_kib(mrm::Scheme::crank_nicolson, m.big, 4);
  m.cn_small = memory_increment_kib(mrm::Scheme::crank_nicolson, m.small, 4);
  m.ps_big = memory_increment_kib(mrm::Scheme::paoli_schatzman, m.big, 4);
  m.ps_small = memory_increment_kib(mrm::Scheme::paoli_schatzman, m.small, 4);
  return m;
}

// The timings of every mesh and their slopes.
struct Results {
  std::vector<Index> sizes;
  std::vector<std::array<Timing, variants>> timings;
  std::vector<BatchedTimings> batched;
  Sanity sanity;
  std::array<double, variants> slope{};        ///< of the cost per step against N over 2^10 .. 2^20 (NaN: not given)
  std::array<double, variants> slope_error{};  ///< its standard error

  // The ratio of variant v to the bare solve.
  static double ratio(const std::array<Timing, variants>& t, int v) { return t[v].value / t[v_bare].value; }
  // The cost of the error measures: the difference of two timings, given (else NaN, "n/a") only when it
  // is above their noise, the spread of each one's batches (median − minimum): a difference within it,
  // or a negative one, measures the machine, not the measures.
  static double errors_cost(const std::array<Timing, variants>& t) {
    const double difference = t[v_errors].value - t[v_cn].value;
    const double noise = (t[v_errors].median - t[v_errors].minimum) + (t[v_cn].median - t[v_cn].minimum);
    return difference > 0 && difference > noise ? difference : NAN;
  }
  // Why errors_cost is not given, for the text outputs.
  static std::string errors_reason(const std::array<Timing, variants>& t) {
    return "below the timing noise: the difference of the two timings, " + fixed(t[v_errors].value - t[v_cn].value, 2) +
           " ns, is not above the spread of their batches, " +
           fixed((t[v_errors].median - t[v_errors].minimum) + (t[v_cn].median - t[v_cn].minimum), 2) + " ns";
  }
};

// Step 4: the timings, N = 2^min .. 2^max, after half a second of steps that brings the core out of
// any idle state (the first measurements would otherwise pay for it); then the slopes.
Results time_meshes(const Options& o) {
  {
    const mrm::UniformMesh mesh(1.0, 4096);
    mrm::BarSimulation warm(mrm::benchmark_problem(), mesh, mrm::mod3(),
                            mrm::parameters_of(mrm::Scheme::crank_nicolson), courant * mesh.h());
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < (o.quick ? 0.1 : 0.5)) warm.step();
  }
  Results r;
  for (long k = o.min_log2; k <= o.max_log2; ++k) {
    const Index elements = Index{1} << k;
    std::cerr << "bench_step: N = 2^" << k << '\n';
    r.sizes.push_back(elements);
    r.timings.push_back(time_all(elements, static_cast<int>(o.repetitions), o.target_ms * 1e-3, r.sanity));
    r.batched.push_back(time_batched(elements, static_cast<int>(o.repetitions), o.target_ms * 1e-3));
  }
  if (!(r.sanity.bare_residual < 1e-13 && r.sanity.eigen_residual < 1e-13))
    throw std::runtime_error("a timed solve is wrong: relative residual " + cli::format_real(r.sanity.bare_residual) +
                             " (bare), " + cli::format_real(r.sanity.eigen_residual) + " (eigen)");
  // The energy of every timed run was checked after its batches (check_energy, above).

  // 5. Slopes of the cost per step against N over 2^10 .. 2^20, for every variant.
  for (int v = 0; v < variants; ++v) {
    std::vector<double> ns;
    for (const auto& t : r.timings) ns.push_back(t[v].value);
    r.slope[v] = loglog_slope(r.sizes, ns, Index{1} << 10, Index{1} << 20, &r.slope_error[v]);
    if (!(r.slope_error[v] <= largest_slope_error)) r.slope[v] = NAN;
  }
  return r;
}

// The summary lines (key = value): the machine, the settings, the slopes, the memory and the residuals.
std::string summary_text(const Options& o, const std::string& load_before, const Results& r, const Memory& m) {
  std::ostringstream summary;
  summary << "cpu = " << cpu_model() << '\n'
          << "mass = mod3\ncourant = " << cli::format_real(courant) << '\n'
          << "cores = " << std::thread::hardware_concurrency() << '\n'
          << "clock = " << o.clock << "\nstatistic = " << o.statistic << "\nrepetitions = " << o.repetitions
          << "\nbatch_ms = " << cli::format_real(o.target_ms) << '\n'
          << "load_average_before = " << load_before << "\nload_average_after = " << load_average() << '\n';
  for (int v = 0; v < variants; ++v) {
    const std::string reason = slope_reason(r.slope[v], r.slope_error[v]);
    summary << "slope_" << variant_names[v] << " = " << (reason.empty() ? fixed(r.slope[v], 3) : "n/a: " + reason)
            << '\n';
  }
  summary << "memory_cn_kib_N" << m.big << " = " << m.cn_big << "\nmemory_cn_kib_N" << m.small << " = " << m.cn_small
          << "\nmemory_ps_kib_N" << m.big << " = " << m.ps_big << "\nmemory_ps_kib_N" << m.small << " = " << m.ps_small
          << "\nmemory_cn_bytes_per_node_N" << m.big << " = " << fixed(Memory::bytes_per_node(m.cn_big, m.big), 1)
          << "\nmemory_cn_bytes_per_node_N" << m.small << " = " << fixed(Memory::bytes_per_node(m.cn_small, m.small), 1)
          << "\nmemory_ps_bytes_per_node_N" << m.big << " = " << fixed(Memory::bytes_per_node(m.ps_big, m.big), 1)
          << "\nmemory_ps_bytes_per_node_N" << m.small << " = " << fixed(Memory::bytes_per_node(m.ps_small, m.small), 1)
          << "\nmemory_cn_marginal_bytes_per_node = " << fixed(m.marginal(m.cn_big, m.cn_small), 1)
          << "\nmemory_ps_marginal_bytes_per_node = " << fixed(m.marginal(m.ps_big, m.ps_small), 1)
          << "\nbare_residual = " << cli::format_real(r.sanity.bare_residual)
          << "\neigen_residual = " << cli::format_real(r.sanity.eigen_residual) << '\n';
  return summary.str();
}

// Standard output: the scalar timings and their ratios, then the summary.
void print_scalar_table(const Options& o, const Results& r, const std::string& summary) {
  std::cout << "# ns per node per step (" << o.statistic << " of " << o.repetitions << " batches; "
            << (use_minimum ? "median" : "min") << " in brackets)\n";
  std::vector<std::string> headers{"N"};
  for (int v = 0; v < variants; ++v) headers.push_back(variant_names[v]);
  for (const char* h :
       {"cn/bare", "be/bare", "ps/bare", "errors", "cn_ref/bare", "be_ref/bare", "ps_ref/bare", "cn+errors/bare"})
    headers.push_back(h);
  mrm::repro::Table screen(headers);
  for (std::size_t k = 0; k < r.sizes.size(); ++k) {
    const auto& t = r.timings[k];
    std::vector<std::string> cells{std::to_string(r.sizes[k])};
    for (int v = 0; v < variants; ++v)
      cells.push_back(fixed(t[v].value, 2) + " [" + fixed(use_minimum ? t[v].median : t[v].minimum, 2) + "]");
    for (const std::string& c : {fixed(Results::ratio(t, v_cn), 2), fixed(Results::ratio(t, v_be), 2),
                                 fixed(Results::ratio(t, v_ps), 2), fixed(Results::errors_cost(t), 2),
                                 fixed(Results::ratio(t, v_cn_ref), 2), fixed(Results::ratio(t, v_be_ref), 2),
                                 fixed(Results::ratio(t, v_ps_ref), 2), fixed(Results::ratio(t, v_errors), 2)})
      cells.push_back(c);
    screen.add_row(cells);
  }
  std::vector<std::size_t> widths(headers.size(), 15);
  widths[0] = 7;
  for (std::size_t c = 1 + variants; c < widths.size(); ++c) widths[c] = 12;
  screen.write_text(std::cout, widths);
  std::cout << summary;
}

// Standard output: the batched step (lib/batched/batched_step.cpp): W runs of Crank–Nicolson (the same
// configuration as the cn column) in the W lanes of each vector target the machine has, ns per node per
// step per run, against the scalar step, the bare solve (one and two at a time) and the limit of the
// widest target: the larger of its memory traffic alone and of its operations at their peak rate.
void print_batched_table(const Options& o, const Results& r, const std::vector<mrm::BatchTarget>& targets) {
  std::cout << "# batched: ns per node per step per run (" << o.statistic << " of " << o.repetitions << " batches)\n";
  std::vector<std::string> headers{"N", "scalar"};
  for (const mrm::BatchTarget& t : targets) headers.push_back(t.name + "x" + std::to_string(t.lanes));
  for (const char* h : {"bare", "bare2", "bare_x2", "plateau", "B/node", "traffic", "aliased", "GB/s", "Gop/s", "arith",
                        "limit", "scalar/widest", "widest/limit"})
    headers.push_back(h);
  mrm::repro::Table screen(headers);
  for (std::size_t k = 0; k < r.sizes.size(); ++k) {
    const auto& t = r.timings[k];
    const BatchedTimings& b = r.batched[k];
    std::vector<std::string> cells{std::to_string(r.sizes[k]), fixed(t[v_cn].value, 2)};
    for (const Timing& x : b.per_target) cells.push_back(fixed(x.value, 3));
    cells.push_back(fixed(t[v_bare].value, 2));
    cells.push_back(fixed(t[v_bare2].value, 2));
    cells.push_back(fixed(b.bare_x2.value, 2));
    cells.push_back(fixed(b.plateau, 4));
    cells.push_back(fixed(b.bytes, 1));
    cells.push_back(fixed(b.traffic, 3));
    cells.push_back(fixed(b.aliased, 3));
    cells.push_back(fixed(b.bandwidth, 1));
    cells.push_back(fixed(1 / b.operation, 1));
    cells.push_back(fixed(b.arithmetic, 3));
    cells.push_back(fixed(b.limit, 3));
    cells.push_back(fixed(t[v_cn].value / b.per_target.front().value, 2));
    cells.push_back(fixed(b.per_target.front().value / b.limit, 2));
    screen.add_row(cells);
  }
  screen.write_text(std::cout, std::vector<std::size_t>(headers.size(), 11));
  // The last lines: the widest target, the bytes of the limit, and the speedup at the largest N.
  std::cout << "batched_target = " << targets.front().name << " (" << targets.front().lanes << " lanes)\n"
            << "batched_bytes_per_node = " << fixed(r.batched.back().bytes, 1) << "\n"
            << "batched_speedup = "
            << fixed(r.timings.back()[v_cn].value / r.batched.back().per_target.front().value, 2) << '\n';
}

// The data file: the options and the summary as comments, then one line per mesh.
void write_data(std::ostream& out, const cli::Parser& parser, const std::string& summary, const Results& r) {
  out << "# bench_step: nanoseconds per node per step (timings: machine- and load-dependent, not reproducible)\n";
  parser.echo(out);
  std::istringstream lines(summary);
  for (std::string line; std::getline(lines, line);) out << "# " << line << '\n';
  out << "# columns: log2N N";
  for (int v = 0; v < variants; ++v) {
    std::string name = variant_names[v];
    std::replace(name.begin(), name.end(), '+', '_');
    out << ' ' << name << "_median " << name << "_min " << name << "_steps";
  }
  out << " cn_over_bare be_over_bare ps_over_bare errors_cost cn_ref_over_bare be_ref_over_bare ps_ref_over_bare"
         " cn_errors_over_bare\n";
  for (std::size_t k = 0; k < r.sizes.size(); ++k) {
    const auto& t = r.timings[k];
    out << std::lround(std::log2(static_cast<double>(r.sizes[k]))) << ' ' << r.sizes[k];
    for (int v = 0; v < variants; ++v)
      out << ' ' << fixed(t[v].median, 4) << ' ' << fixed(t[v].minimum, 4) << ' ' << t[v].steps_per_batch;
    out << ' ' << fixed(Results::ratio(t, v_cn), 4) << ' ' << fixed(Results::ratio(t, v_be), 4) << ' '
        << fixed(Results::ratio(t, v_ps), 4) << ' ' << fixed(Results::errors_cost(t), 4) << ' '
        << fixed(Results::ratio(t, v_cn_ref), 4) << ' ' << fixed(Results::ratio(t, v_be_ref), 4) << ' '
        << fixed(Results::ratio(t, v_ps_ref), 4) << ' ' << fixed(Results::ratio(t, v_errors), 4) << '\n';
  }
}

// The Markdown table for the README: its caption, one row per mesh (the figure of each scheme with the
// fast and the reference step and of the limits, the ratios to the bare solve, the errors), the slopes,
// and the peak memory.
void write_markdown(std::ostream& out, const Options& o, const std::string& load_before, const Results& r,
                    const Memory& m) {
  const std::string caption_md =
      "Nanoseconds per node per step (" + o.statistic + " of " + std::to_string(o.repetitions) + " batches of about " +
      fixed(o.target_ms, 0) + " ms of " + (o.clock == "cpu" ? "thread CPU time" : "wall time") +
      "), Mod 3, Δt = h/2, on " + cpu_model() + " (load average " + load_before +
      " before the run). CN, BE, PS: the fast step (the fused two-chain kernel every program uses); "
      "*ref*: the same schemes with the reference step (the scheme written as its derivation: whole matrices "
      "and vectors, one solve). *bare*: the same pre-factored tridiagonal solve without the scheme (plain "
      "substitution loops); "
      "*bare2*: the same with each sweep run as two interleaved chains (the form the schemes use); *eigen*: Eigen's "
      "SimplicialLDLT solve of the same matrix; *errors*: the cost of the error measures (ErrorAccumulator::add). "
      "The slope is that of log(cost per step) against log N over 2^10..2^20.";
  const std::string memory_line =
      "Peak memory added by a run with the error accumulator (child process, ru_maxrss): CN " +
      std::to_string(m.cn_big) + " KiB at N = " + std::to_string(m.big) + " (" +
      fixed(Memory::bytes_per_node(m.cn_big, m.big), 0) + " B/node), " + std::to_string(m.cn_small) +
      " KiB at N = " + std::to_string(m.small) + " (" + fixed(Memory::bytes_per_node(m.cn_small, m.small), 0) +
      " B/node); PS " + std::to_string(m.ps_big) + " KiB at N = " + std::to_string(m.big) + " (" +
      fixed(Memory::bytes_per_node(m.ps_big, m.big), 0) + " B/node), " + std::to_string(m.ps_small) +
      " KiB at N = " + std::to_string(m.small) + " (" + fixed(Memory::bytes_per_node(m.ps_small, m.small), 0) +
      " B/node). Marginal cost " + "(memory(N) − memory(N/4))/(3N/4): CN " +
      fixed(m.marginal(m.cn_big, m.cn_small), 0) + " B/node, PS " + fixed(m.marginal(m.ps_big, m.ps_small), 0) +
      " B/node.";
  const auto& slope = r.slope;
  mrm::repro::Table table({"N", "CN", "BE", "PS", "CN ref", "BE ref", "PS ref", "bare", "bare2", "Eigen", "CN/bare",
                           "BE/bare", "PS/bare", "CN ref/bare", "BE ref/bare", "PS ref/bare", "errors"});
  for (std::size_t k = 0; k < r.sizes.size(); ++k) {
    const auto& t = r.timings[k];
    table.add_row({std::to_string(r.sizes[k]), fixed(t[v_cn].value, 2), fixed(t[v_be].value, 2),
                   fixed(t[v_ps].value, 2), fixed(t[v_cn_ref].value, 2), fixed(t[v_be_ref].value, 2),
                   fixed(t[v_ps_ref].value, 2), fixed(t[v_bare].value, 2), fixed(t[v_bare2].value, 2),
                   fixed(t[v_eigen].value, 2), fixed(Results::ratio(t, v_cn), 2), fixed(Results::ratio(t, v_be), 2),
                   fixed(Results::ratio(t, v_ps), 2), fixed(Results::ratio(t, v_cn_ref), 2),
                   fixed(Results::ratio(t, v_be_ref), 2), fixed(Results::ratio(t, v_ps_ref), 2),
                   fixed(Results::errors_cost(t), 2)});
  }
  table.add_rule();
  table.add_row({"slope", fixed(slope[v_cn], 3), fixed(slope[v_be], 3), fixed(slope[v_ps], 3),
                 fixed(slope[v_cn_ref], 3), fixed(slope[v_be_ref], 3), fixed(slope[v_ps_ref], 3),
                 fixed(slope[v_bare], 3), fixed(slope[v_bare2], 3), fixed(slope[v_eigen], 3), "", "", "", "", "", "",
                 ""});
  out << caption_md << "\n\n";
  table.write_markdown(out, std::string(17, 'r'));
  out << '\n' << memory_line << '\n';
}

// The report's two tables at the text size: the fast step (what every program runs) against the two
// solves it is compared with, the bare pre-factored tridiagonal solve and Eigen's SimplicialLDLT solve of
// the same matrix; the reference step (the scheme written as its derivation) against the same bare solve.
void write_tex_tables(std::ostream& out, const Results& r) {
  const auto& slope = r.slope;
  mrm::repro::Table fast(
      {"$N$", "CN", "BE", "PS", "bare", "bare2", "Eigen", "CN/bare", "BE/bare", "PS/bare", "CN/Eigen"});
  mrm::repro::Table reference(
      {"$N$", "CN ref", "BE ref", "PS ref", "bare", "CN ref/bare", "BE ref/bare", "PS ref/bare", "errors"});
  for (std::size_t k = 0; k < r.sizes.size(); ++k) {
    const auto& t = r.timings[k];
    fast.add_row({std::to_string(r.sizes[k]), fixed(t[v_cn].value, 2), fixed(t[v_be].value, 2), fixed(t[v_ps].value, 2),
                  fixed(t[v_bare].value, 2), fixed(t[v_bare2].value, 2), fixed(t[v_eigen].value, 2),
                  fixed(Results::ratio(t, v_cn), 2), fixed(Results::ratio(t, v_be), 2),
                  fixed(Results::ratio(t, v_ps), 2), fixed(t[v_cn].value / t[v_eigen].value, 2)});
    reference.add_row({std::to_string(r.sizes[k]), fixed(t[v_cn_ref].value, 2), fixed(t[v_be_ref].value, 2),
                       fixed(t[v_ps_ref].value, 2), fixed(t[v_bare].value, 2), fixed(Results::ratio(t, v_cn_ref), 2),
                       fixed(Results::ratio(t, v_be_ref), 2), fixed(Results::ratio(t, v_ps_ref), 2),
                       fixed(Results::errors_cost(t), 2)});
  }
  fast.add_rule();
  fast.add_row({"slope", fixed(slope[v_cn], 3), fixed(slope[v_be], 3), fixed(slope[v_ps], 3), fixed(slope[v_bare], 3),
                fixed(slope[v_bare2], 3), fixed(slope[v_eigen], 3), "", "", "", ""});
  reference.add_rule();
  reference.add_row({"slope", fixed(slope[v_cn_ref], 3), fixed(slope[v_be_ref], 3), fixed(slope[v_ps_ref], 3),
                     fixed(slope[v_bare], 3), "", "", "", ""});
  const auto tabular = [](const mrm::repro::Table& table) {
    mrm::repro::LatexLayout layout;
    layout.columns = std::string(table.columns(), 'r');
    layout.final_newline = false;
    std::ostringstream text;
    table.write_latex(text, layout);
    return text.str();
  };
  out << "\\mrmdef{bench:table:fast}{" << tabular(fast) << "}\n";
  out << "\\mrmdef{bench:table:ref}{" << tabular(reference) << "}\n";
}

// The figures the text quotes, as the report's values (\mrmdef, like every generated number): at
// N = 2^16, or at the largest N measured if smaller (the short run of make all).
void write_tex_values(std::ostream& out, const Options& o, const Results& r, const Memory& m,
                      const std::vector<mrm::BatchTarget>& targets, const std::string& load_before) {
  const auto& slope = r.slope;
  // How the timings were taken, for the captions.
  mrm::tex_define(out, "bench:repetitions", std::to_string(o.repetitions));
  mrm::tex_define(out, "bench:batch-ms", fixed(o.target_ms, 0));
  mrm::tex_define(out, "bench:clock", o.clock == "cpu" ? "thread CPU time" : "wall time");
  mrm::tex_define(out, "bench:statistic", o.statistic == "min" ? "the minimum" : "the median");
  mrm::tex_define(out, "bench:cpu", cpu_model());
  // The machine and its load when the timings were taken (the 1-minute load average before and after).
  mrm::tex_define(out, "bench:cores", std::to_string(std::thread::hardware_concurrency()));
  mrm::tex_define(out, "bench:load-before", load_before);
  mrm::tex_define(out, "bench:load-after", load_average());
  mrm::tex_define(out, "bench:nmin", std::to_string(r.sizes.front()));
  mrm::tex_define(out, "bench:nmax", std::to_string(r.sizes.back()));
  const Index text_n = std::min<Index>(Index{1} << 16, r.sizes.back());
  mrm::tex_define(out, "bench:text-n", std::to_string(text_n));
  const auto at = [&](Index n) -> const std::array<Timing, variants>* {
    for (std::size_t k = 0; k < r.sizes.size(); ++k)
      if (r.sizes[k] == n) return &r.timings[k];
    return nullptr;
  };
  if (const auto* t = at(text_n)) {
    mrm::tex_define(out, "bench:cn:ns", fixed((*t)[v_cn].value, 2));
    mrm::tex_define(out, "bench:be:ns", fixed((*t)[v_be].value, 2));
    mrm::tex_define(out, "bench:ps:ns", fixed((*t)[v_ps].value, 2));
    mrm::tex_define(out, "bench:bare:ns", fixed((*t)[v_bare].value, 2));
    mrm::tex_define(out, "bench:bare2:ns", fixed((*t)[v_bare2].value, 2));
    mrm::tex_define(out, "bench:eigen:ns", fixed((*t)[v_eigen].value, 2));
    mrm::tex_define(out, "bench:cn:ratio", fixed(Results::ratio(*t, v_cn), 2));
    mrm::tex_define(out, "bench:be:ratio", fixed(Results::ratio(*t, v_be), 2));
    mrm::tex_define(out, "bench:ps:ratio", fixed(Results::ratio(*t, v_ps), 2));
    mrm::tex_define(out, "bench:cn:eigen-ratio", fixed((*t)[v_cn].value / (*t)[v_eigen].value, 2));
    if (std::isfinite(Results::errors_cost(*t)))
      mrm::tex_define(out, "bench:errors:ns", fixed(Results::errors_cost(*t), 2));
    else
      mrm::tex_define(out, "bench:errors:na", Results::errors_reason(*t));
    mrm::tex_define(out, "bench:measures:ratio", fixed(Results::ratio(*t, v_errors), 2));
    mrm::tex_define(out, "bench:cn-ref:ns", fixed((*t)[v_cn_ref].value, 2));
    mrm::tex_define(out, "bench:be-ref:ns", fixed((*t)[v_be_ref].value, 2));
    mrm::tex_define(out, "bench:ps-ref:ns", fixed((*t)[v_ps_ref].value, 2));
    mrm::tex_define(out, "bench:cn-ref:ratio", fixed(Results::ratio(*t, v_cn_ref), 2));
    mrm::tex_define(out, "bench:be-ref:ratio", fixed(Results::ratio(*t, v_be_ref), 2));
    mrm::tex_define(out, "bench:ps-ref:ratio", fixed(Results::ratio(*t, v_ps_ref), 2));
    // The batched step at the same N: the widest target, its cost per run, the speedup over the
    // scalar step, the bare solve two at a time, and the limit of its memory traffic.
    const BatchedTimings& b = r.batched[static_cast<std::size_t>(t - r.timings.data())];
    mrm::tex_define(out, "bench:batched:target", targets.front().name);
    mrm::tex_define(out, "bench:batched:lanes", std::to_string(targets.front().lanes));
    mrm::tex_define(out, "bench:batched:ns", fixed(b.per_target.front().value, 3));
    mrm::tex_define(out, "bench:batched:speedup", fixed((*t)[v_cn].value / b.per_target.front().value, 2));
    mrm::tex_define(out, "bench:batched:limit", fixed(b.limit, 3));
    mrm::tex_define(out, "bench:batched:bytes", fixed(b.bytes, 1));
    mrm::tex_define(out, "bench:batched:plateau-percent", fixed(100 * b.plateau, 2));
    mrm::tex_define(out, "bench:batched:bandwidth", fixed(b.bandwidth, 1));
    mrm::tex_define(out, "bench:batched:traffic", fixed(b.traffic, 3));
    mrm::tex_define(out, "bench:batched:aliased", fixed(b.aliased, 3));
    mrm::tex_define(out, "bench:batched:operations", fixed(batched_operations, 0));
    mrm::tex_define(out, "bench:batched:peak", fixed(1 / b.operation, 1));
    mrm::tex_define(out, "bench:batched:arithmetic", fixed(b.arithmetic, 3));
    mrm::tex_define(out, "bench:batched:to-limit", fixed(b.per_target.front().value / b.limit, 2));
    mrm::tex_define(out, "bench:batched:bound", b.traffic >= b.arithmetic ? "memory traffic" : "arithmetic");
    mrm::tex_define(out, "bench:batched:speedup-bound", fixed((*t)[v_cn].value / b.limit, 2));
    mrm::tex_define(out, "bench:bare-x2:ns", fixed(b.bare_x2.value, 2));
  }
  // The slopes, each given only when it can be trusted (slope_reason), else the reason.
  for (const auto& [key, v] : {std::pair{"cn", v_cn}, std::pair{"be", v_be}, std::pair{"ps", v_ps}}) {
    const std::string reason = slope_reason(slope[v], r.slope_error[v]);
    mrm::tex_define(out, std::string("bench:") + key + (reason.empty() ? ":slope" : ":slope:na"),
                    reason.empty() ? fixed(slope[v], 3) : reason);
  }
  mrm::tex_define(out, "bench:slope-from", std::to_string(std::max<Index>(r.sizes.front(), Index{1} << 10)));
  mrm::tex_define(out, "bench:slope-to", std::to_string(std::min<Index>(r.sizes.back(), Index{1} << 20)));
  mrm::tex_define(out, "bench:memory:cn:bytes-per-node", fixed(Memory::bytes_per_node(m.cn_big, m.big), 0));
  mrm::tex_define(out, "bench:memory:largest-n", std::to_string(m.big));
  mrm::tex_define(out, "bench:memory:cn:marginal", fixed(m.marginal(m.cn_big, m.cn_small), 0));
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("bench_step", [&] {
    // 1. Options.
    Options o;
    cli::Parser parser("bench_step",
                       "Times one step of Crank-Nicolson, backward Euler and Paoli-Schatzman per node (the fast "
                       "step every program uses and the reference step written as the derivation), a bare "
                       "pre-factored tridiagonal solve and Eigen's SimplicialLDLT solve of the same matrix, for "
                       "N = 2^6 .. 2^20 elements; prints the ratios to the bare solve, the log-log slope of the "
                       "cost per step against N and the peak memory; then the batched step (runs in vector lanes) "
                       "per vector target against the scalar step and against its limit, the larger of the time "
                       "of its memory traffic alone and of its operations at the peak rate, both measured. Timings "
                       "go to output/bench/, not to the deterministic data.",
                       {"bench_step", "bench_step --quick",
                        "bench_step --output output/bench/bench_step.dat --tex output/bench/bench_step.tex "
                        "--markdown output/bench/bench_step.md"});
    declare_options(parser, o);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    settle_options(parser, o);
    gsl_set_error_handler_off();
    use_thread_cpu_time = o.clock == "cpu";
    use_minimum = o.statistic == "min";

    // 2. The outputs, opened now so that an unwritable path fails before the measurements.
    std::unique_ptr<cli::AtomicFile> data, table_tex, table_md;
    if (parser.given("--output")) data = std::make_unique<cli::AtomicFile>(o.output, "--output");
    if (parser.given("--tex")) table_tex = std::make_unique<cli::AtomicFile>(o.tex, "--tex");
    if (parser.given("--markdown")) table_md = std::make_unique<cli::AtomicFile>(o.markdown, "--markdown");

    // 3. Peak memory, in fresh children.
    const Memory memory = measure_memory(o.min_log2, o.max_log2);
    const std::string load_before = load_average();

    // 4 and 5. The timings and their slopes.
    const Results results = time_meshes(o);

    // 6. The tables: stdout, data file, LaTeX, Markdown.
    const std::string summary = summary_text(o, load_before, results, memory);
    print_scalar_table(o, results, summary);
    const std::vector<mrm::BatchTarget> targets = mrm::batch_targets();
    print_batched_table(o, results, targets);
    if (data) write_data(data->stream(), parser, summary, results);
    if (table_md) write_markdown(table_md->stream(), o, load_before, results, memory);
    if (table_tex) {
      std::ostream& out = table_tex->stream();
      out << "% bench_step: generated by `make bench` (or the short run of `make all`); timings depend on the\n"
             "% machine and its load. Two tables at the text size: the fast step, and the reference step.\n";
      write_tex_tables(out, results);
      write_tex_values(out, o, results, memory, targets, load_before);
    }
    cli::commit_all({data.get(), table_tex.get(), table_md.get()});  // all three or none
    return 0;
  });
}
