/// @file batched_step.cpp
/// @brief Many runs advanced together, one run per vector lane: the runs grouped by lanes (the number of
/// unknowns and the scheme family), each group's state and factors interleaved, and each group stepped by
/// the vector kernels of kernels.cpp (the fused step of fast_step.cpp; the Newmark type, Moreau–Jean and
/// DKE of contact_classes.cpp; the explicit classes of explicit_schemes.cpp), their contact decisions and
/// ends of step each lane's own (FastStep::contact_decision, NewmarkTypeStep, OneSolveStep,
/// ExplicitStep::contact). Each lane ends bitwise as its run stepped alone (lanes_alone.cpp).
///
/// Width: a group has the target's full width W, except the remainder of a family (q < W runs left after
/// its full groups), which gets the narrowest width that holds it: 2 lanes for 2 runs, 4 for 3 or 4, W
/// for more (a run left alone is stepped alone). A padding lane costs as much as a run (bench_step times
/// the step at each width): on an AVX-512 machine, 2 runs padded to 8 lanes were slower than the same runs
/// stepped alone.
#include "batched/batched_step.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <string>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <doctest/doctest.h>
#include <hwy/targets.h>

#include "batched/kernels.hpp"
#include "batched/lane_array.hpp"
#include "steps/contact.hpp"
#include "classes/contact_classes.hpp"
#include "steps/explicit_schemes.hpp"
#include "steps/fast_step.hpp"
#include "fem/mass_redistribution.hpp"

namespace mrm {

void use_batch_target(std::int64_t bit) {
  hwy::SetSupportedTargetsForTest(bit);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

std::vector<BatchTarget> batch_targets() {
  use_batch_target(0);  // every supported target, not the one a previous use_batch_target chose
  std::vector<BatchTarget> targets;
  for (const std::int64_t bit : hwy::SupportedAndGeneratedTargets()) {
    use_batch_target(bit);
    const std::size_t lanes = batched::lane_count(batched::Width::full);
    if (lanes >= 2) targets.push_back({hwy::TargetName(bit), lanes, bit});  // one lane is the scalar step
  }
  use_batch_target(0);
  // Widest first; among equal widths the later (more capable) target first, as Highway orders them.
  std::stable_sort(targets.begin(), targets.end(),
                   [](const BatchTarget& a, const BatchTarget& b) { return a.lanes > b.lanes; });
  return targets;
}

BatchTarget current_batch_target() {
  const std::int64_t bit = hwy::SupportedAndGeneratedTargets().front();  // the best the dispatch chooses
  return {hwy::TargetName(bit), batched::lane_count(batched::Width::full), bit};
}

int batch_family(Scheme scheme) { return scheme_info(scheme).batch_family; }

/// @cond MRM_INTERNAL (a group's lanes: not part of the library's interface)
// One group: W lanes (a run each, or a copy of lane 0's run for the lanes left over), interleaved. W is
// the target's full width, or 4 or 2 for the remainder of a family (the constructor).
struct BatchedSimulation::Group {
  std::vector<std::size_t> runs;  // the run of each lane (W of them); padding lanes repeat lane 0's, ignored
  std::size_t used = 0;           // lanes 0 … used−1 are runs of their own
  batched::Width width = batched::Width::full;  // the kernel of W lanes: the full width, or capped at 4 or 2
  // head: the explicit head rows of the lane with the most, head_min of the lane with the fewest, heads each
  // lane's (as doubles, for the kernels' masks: batched::Kernel).
  std::size_t n = 0, head = 0, head_min = 0;
  // Each lane's unknowns: n, or n − 1 for a held far end beside free ones (short_lanes, batched::Kernel,
  // allocated only then).
  std::vector<std::size_t> rows;
  std::size_t flat_begin = 0, flat_end = 0;  // the plateau of the factors (find_plateau)
  std::size_t arrays = 0;  // its arrays by node allocated so far (lane_array: each its own page offset)
  bool three_level = false, switching = false;
  batched::LaneArray u, y, w, x, elimination, elimination_pair, inverse_pivot, upward, upward_pair, head_rows, heads,
      short_lanes, interior, last, rate, memory, ps_q_weight, u0_next, recurrence_d0, keep, energy;
  // The steady loads' terms of the right-hand side, L_i = g_now F_i + g_next F_i per lane (null when no
  // lane has a load; −0 in a lane without one, fill below).
  batched::LaneArray load;
  std::vector<FastStep::ContactDecision> decisions;  // the lanes' contact decisions of the current step
  // A group of Newmark-type steps (batch_family 4, batched::NewmarkKernel): u, y, w, the factors of A
  // (elimination, inverse_pivot, upward), u0_next (the decision's u₀) and keep above, and these.
  bool newmark = false;
  batched::LaneArray r, r_next, t, m_diag, m_lower, m_upper, s_diag, s_lower, s_upper, l_diag, l_lower, l_upper,
      mass_elimination, mass_inverse_pivot, mass_upward, z, dt, force_weight, one_minus_gamma, gamma, g0, g1, massless,
      lambda, shift, kinetic_strain;
  std::vector<NewmarkTypeStep*> steps;  // each lane's step (its decision and end of step)
  // A group of Moreau–Jean or DKE steps (batch_family 5 or 6, batched::OneSolveKernel): u, y, w, the rows of M
  // and S, the factors of A, dt, keep and kinetic_strain above, u0_next as the decision's x₀, and these.
  bool one_solve = false, dke = false;
  batched::LaneArray p, right_diag, right_lower, right_upper, column, weight, theta, one_minus_theta, two_over_dt,
      row0_zero, alpha, projected, minus_gap;
  std::vector<OneSolveStep*> solve_steps;               // each lane's step (its pieces)
  std::vector<OneSolveStep::Decision> solve_decisions;  // the lanes' decisions of the current step
  // A group of the explicit classes (batch_family 7, batched::ExplicitKernel): u, y, w, the rows of M and S, dt,
  // keep and energy above, and these (a: the consistent mass's solve).
  bool explicit_scheme = false, lumped = true;
  batched::LaneArray a, inverse_mass, pivot, factor, impulse_response, half_dt, h, clamped, correct, dt_mu, dt2_mu;
  std::vector<const ExplicitStep*> explicit_steps;       // each lane's step (its contact)
  std::vector<ExplicitStep::Contact> explicit_contacts;  // the lanes' contacts of the current step
};
/// @endcond

namespace {

// A group's next array by node (`count` = its rows × lanes), when it has `arrays` of them: at its own offset
// within a page (lane_array.hpp; a group allocates the arrays its sweeps stream first), so that no two of
// them alias a few rows apart. Its values per lane (lane_values: one value or a few rows of coefficients
// per lane, read a few times a step) are aligned to 64 bytes only. When the memory is not there the failure
// is std::bad_alloc, which the programs report as an error (status 1).
batched::LaneArray lane_array(std::size_t count, std::size_t& arrays) {
  return batched::LaneArray(count, batched::lane_array_offset(arrays++));
}
batched::LaneArray lane_values(std::size_t count) { return batched::LaneArray(count); }

// The rows of a FastStep as 10 doubles (the order of batched::RowV).
template <typename Row>
std::array<double, 10> coefficients(const Row& r) {
  return {r.c1l, r.c1d, r.c1u, r.c2l, r.c2d, r.c2u, r.md, r.ml2, r.sd, r.sl2};
}

// The plateau of a group's factors. The interior rows are one Toeplitz row (d on the diagonal, l and u
// beside it), and the elimination from the last row up (contact.cpp) computes the pivots by
// p_i = d − (u/p_{i+1}) l, a contraction near its fixed point p* = d − ul/p* (|ul/p*²| < 1 for these
// diagonally dominant matrices): a few tens of rows above the last one the pivots, and with them the
// five factor vectors the sweeps read (ε_i, ε_i ε_{i+1}, 1/p_i, ℓ_i/p_i and its pair product), repeat
// the same doubles row after row. A rounding map with an attracting fixed point lands on it exactly, or
// on a cycle of neighbouring doubles; only rows checked equal are used: the plateau is the first run
// [a, b) of interior rows, from the top, whose five factors equal row a's in every lane, bit for bit.
// The sweeps hold those five vectors in registers there instead of loading them: the same numbers, so
// the same bits; only the memory traffic changes (40 of the ~104 bytes per node and lane: bench_step).
}  // namespace

void BatchedSimulation::find_plateau(Group& g) {
  // The rows every lane takes as interior rows: head … n − 2 (n − 3 when some lanes have n − 1 unknowns).
  const std::size_t W = g.runs.size(), end = g.n - (g.short_lanes.get() ? 2 : 1);
  const double* factors[] = {g.elimination.get(), g.elimination_pair.get(), g.inverse_pivot.get(), g.upward.get(),
                             g.upward_pair.get()};
  const auto same_rows = [&](std::size_t i, std::size_t m) {
    for (const double* f : factors)
      if (std::memcmp(f + i * W, f + m * W, W * sizeof(double)) != 0) return false;
    return true;
  };
  std::size_t a = g.head;
  while (a + 1 < end && !same_rows(a, a + 1)) ++a;
  std::size_t b = a + 1;
  while (b < end && same_rows(b, a)) ++b;
  if (a + 1 >= end || g.head >= end) a = b = g.head;  // no two equal rows: no plateau
  g.flat_begin = a, g.flat_end = b;
}

BatchedSimulation::BatchedSimulation(std::vector<BarSimulation> runs) : runs_(std::move(runs)) {
  lanes_ = batched::lane_count(batched::Width::full);
  // The widths a group can have, narrowest first: 2, 4 (each at most the full width; equal to it on a
  // target of 2 or 4 lanes) and the full width, with their kernels (Group::width).
  const std::array<std::pair<std::size_t, batched::Width>, 3> widths = {
      {{batched::lane_count(batched::Width::two), batched::Width::two},
       {batched::lane_count(batched::Width::four), batched::Width::four},
       {lanes_, batched::Width::full}}};
  const std::size_t count = runs_.size();
  stale_.assign(count, 0);
  group_of_.assign(count, 0);
  lane_of_.assign(count, 0);
  // The key of runs that can share a group: the number of unknowns, the scheme family and the layout of
  // the fast step. A run with the reference kernel, or with a load that changes with t, is stepped alone; a
  // steady load (Problem::steady_load) is a vector of the lane's own (Group::load).
  using Key = std::tuple<std::size_t, int, std::size_t>;
  std::map<Key, std::vector<std::size_t>> families;
  for (std::size_t k = 0; k < count; ++k) {
    BarSimulation& r = runs_[k];
    const BarSimulation::StepParts parts = r.step_parts();
    const FastStep* fast = parts.fast;
    const std::size_t n = static_cast<std::size_t>(parts.state->u.size());
    if (!fast && !parts.has_load && lanes_ >= 2 && r.level() == 0 && n >= 4) {
      // A Newmark-type step (newmark, penalty, nitsche) on the fused kernel without a load: family 4.
      const auto* step = dynamic_cast<const NewmarkTypeStep*>(parts.class_step);
      if (step && step->batchable()) {
        families[Key{n, 4, 0}].push_back(k);
        continue;
      }
      // The explicit classes (family 7) on a uniform homogeneous mesh (the energy's stiffness_form on one h),
      // lumped or not in groups of their own.
      if (parts.explicit_step && r.mesh().uniform() && r.mesh().homogeneous()) {
        families[Key{n, 7, parts.explicit_step->lanes().lumped ? 0 : 1}].push_back(k);
        continue;
      }
      // Moreau–Jean (family 5) or DKE (6) on the fused kernel without a load.
      const auto* solve = dynamic_cast<const OneSolveStep*>(parts.class_step);
      if (solve && solve->batchable()) {
        families[Key{n, batch_family(r.parameters().scheme), 0}].push_back(k);
        continue;
      }
    }
    if (!fast || (parts.has_load && !parts.steady_load) || n < 2 || lanes_ < 2 || r.level() != 0) {
      alone_.push_back(k);
      continue;
    }
    // batch_family's numbers (its doctest checks that they agree). The runs of one mesh (N elements) share a
    // group whatever their explicit head rows and their far end, held (N unknowns) or free (N + 1): in the
    // rows where lanes differ the kernels take each lane's own row (batched::Kernel). The key is then the
    // number of elements; a run whose head leaves fewer than four interior rows keeps a key of its own
    // (its unknowns and its head).
    const int family = fast->three_level() ? 1 : fast->energy_conserving() ? 2 : fast->switching() ? 3 : 0;
    const std::size_t head = fast->head().size(), elements = static_cast<std::size_t>(r.mesh().elements);
    const bool shares = head + 4 < n && (n == elements || n == elements + 1);
    families[shares ? Key{elements, family, 0} : Key{n, family, head}].push_back(k);
  }
  // Each family: groups of the full width W, then the remainder q < W in one group of the narrowest width
  // that holds it (2 runs in 2 lanes, 3 or 4 in 4, more in the full width), or alone if q = 1. The width
  // changes no bit of a lane (every operation is lane-wise), only the cost of the padding lanes.
  for (const auto& [key, members] : families) {
    for (std::size_t first = 0; first < members.size(); first += lanes_) {
      const std::size_t used = std::min(lanes_, members.size() - first);
      if (used == 1) {  // a group of one: stepped alone
        alone_.push_back(members[first]);
        continue;
      }
      auto g = std::make_unique<Group>();
      g->used = used;
      std::size_t width = lanes_;
      for (const auto& [w, kernel] : widths)
        if (w >= used) {
          width = w, g->width = kernel;
          break;
        }
      for (std::size_t j = 0; j < width; ++j) g->runs.push_back(members[first + (j < used ? j : 0)]);
      for (std::size_t j = 0; j < used; ++j) {
        group_of_[g->runs[j]] = groups_.size();
        lane_of_[g->runs[j]] = j;
      }
      if (std::get<1>(key) == 4) {
        g->n = std::get<0>(key);
        fill_newmark(*g, runs_);
        groups_.push_back(std::move(g));
        continue;
      }
      if (std::get<1>(key) == 7) {
        g->n = std::get<0>(key);
        fill_explicit(*g, runs_);
        groups_.push_back(std::move(g));
        continue;
      }
      if (std::get<1>(key) == 5 || std::get<1>(key) == 6) {
        g->n = std::get<0>(key);
        fill_one_solve(*g, runs_, std::get<1>(key) == 6);
        groups_.push_back(std::move(g));
        continue;
      }
      const FastStep& f0 = *runs_[g->runs[0]].step_parts().fast;
      g->n = 0, g->head = 0, g->head_min = std::numeric_limits<std::size_t>::max();
      for (std::size_t j = 0; j < width; ++j) {
        const BarSimulation::StepParts parts = runs_[g->runs[j]].step_parts();
        const std::size_t h = parts.fast->head().size();
        g->rows.push_back(static_cast<std::size_t>(parts.state->u.size()));  // N or N + 1 (the key)
        g->n = std::max(g->n, g->rows.back());
        g->head = std::max(g->head, h), g->head_min = std::min(g->head_min, h);
      }
      const bool ragged = *std::min_element(g->rows.begin(), g->rows.end()) < g->n;
      g->three_level = f0.three_level();
      g->switching = f0.switching();
      const std::size_t nw = g->n * width;
      for (auto* a : {&g->u, &g->y, &g->w, &g->x, &g->elimination, &g->elimination_pair, &g->inverse_pivot, &g->upward,
                      &g->upward_pair})
        *a = lane_array(nw, g->arrays);
      bool loaded = false;  // the steady loads' terms (below): streamed too
      for (std::size_t j = 0; j < width; ++j) loaded = loaded || runs_[g->runs[j]].step_parts().has_load;
      if (loaded) g->load = lane_array(nw, g->arrays);
      g->head_rows = lane_values(g->head * 10 * width);
      g->heads = lane_values(width);
      if (ragged) g->short_lanes = lane_values(width);
      g->interior = lane_values(10 * width);
      g->last = lane_values(10 * width);
      for (auto* a : {&g->rate, &g->memory, &g->ps_q_weight, &g->u0_next, &g->recurrence_d0, &g->keep, &g->energy})
        *a = lane_values(width);
      g->decisions.resize(width);
      for (std::size_t j = 0; j < width; ++j) {
        const BarSimulation::StepParts parts = runs_[g->runs[j]].step_parts();
        const FastStep& f = *parts.fast;
        const ContactSolver& s = *parts.solver;
        for (std::size_t i = 0; i < g->n; ++i) {  // past the lane's last row (n − 1 unknowns): zeros, not read
          const auto e = static_cast<Index>(i);
          const bool in = i < g->rows[j];
          g->elimination[i * width + j] = in ? s.elimination()[e] : 0.0;
          g->elimination_pair[i * width + j] = in ? s.elimination_pair()[e] : 0.0;
          g->inverse_pivot[i * width + j] = in ? s.inverse_pivot()[e] : 0.0;
          g->upward[i * width + j] = in ? s.upward()[e] : 0.0;
          g->upward_pair[i * width + j] = in ? s.upward_pair()[e] : 0.0;
        }
        if (ragged) g->short_lanes[j] = g->rows[j] < g->n ? 1.0 : 0.0;
        // The lane's head rows; below its own head (a longer head in another lane) its interior row, which
        // the kernels do not take there (finite numbers all the same).
        const auto ci = coefficients(f.interior()), cl = coefficients(f.last());
        g->heads[j] = static_cast<double>(f.head().size());
        for (std::size_t h = 0; h < g->head; ++h) {
          const auto c = h < f.head().size() ? coefficients(f.head()[h]) : ci;
          for (std::size_t m = 0; m < 10; ++m) g->head_rows[(h * 10 + m) * width + j] = c[m];
        }
        for (std::size_t m = 0; m < 10; ++m) {
          g->interior[m * width + j] = ci[m];
          g->last[m * width + j] = cl[m];
        }
        g->rate[j] = f.coefficients().velocity_rate;
        g->memory[j] = f.coefficients().velocity_memory;
        g->ps_q_weight[j] = 1 - 4 * f.beta();  // as fused_step writes it: (1 − 4β)
        g->keep[j] = 0;
      }
      // A steady load enters the fused step's right-hand side of row i as b_i + (g_now F_i + g_next F_i)
      // (FastStep::fused_step: b += g_now f_now[i] + g_next f_next[i], with f_now = f_next = F bit for bit,
      // which BarSimulation checks), so the term in parentheses is formed here once, by the same two products
      // and sum, and the sweep down adds it to b_i: the scalar step's bits. A lane without a load adds −0,
      // which leaves every b_i as it is, its sign of zero included (x + (−0) = x in IEEE 754 for every x).
      if (loaded) {
        for (std::size_t j = 0; j < width; ++j) {
          const BarSimulation::StepParts parts = runs_[g->runs[j]].step_parts();
          const double g_now = parts.fast->coefficients().load_now, g_next = parts.fast->coefficients().load_next;
          for (std::size_t i = 0; i < g->n; ++i) {
            const auto e = static_cast<Index>(i);
            g->load[i * width + j] = parts.has_load && i < g->rows[j]
                                         ? g_now * parts.state->f_now[e] + g_next * parts.state->f_next[e]
                                         : -0.0;
          }
        }
      }
      for (std::size_t j = 0; j < width; ++j) load_lane(*g, j, runs_[g->runs[j]]);
      find_plateau(*g);
      groups_.push_back(std::move(g));
    }
  }
}

BatchedSimulation::~BatchedSimulation() = default;
BatchedSimulation::BatchedSimulation(BatchedSimulation&&) noexcept = default;
BatchedSimulation& BatchedSimulation::operator=(BatchedSimulation&&) noexcept = default;

namespace {

// Lane j of a group's interleaved array (element i at i·W + j) from a run's vector of the group's n entries,
// or zeros from an empty one (a vector the run's step does not have: Newmark's z, DKE's M⁻¹e₀ on a massless
// node, the other mass's arrays of an explicit step).
void interleave(double* to, const Eigen::VectorXd& from, std::size_t n, std::size_t W, std::size_t j) {
  for (std::size_t i = 0; i < n; ++i) to[i * W + j] = from.size() == 0 ? 0.0 : from[static_cast<Index>(i)];
}
// The three diagonals of a tridiagonal matrix.
void interleave(const std::array<double*, 3>& to, const Tridiagonal& a, std::size_t n, std::size_t W, std::size_t j) {
  interleave(to[0], a.diag, n, W, j), interleave(to[1], a.lower, n, W, j), interleave(to[2], a.upper, n, W, j);
}
// The three factors of a solver that its two sweeps read (ε, 1/p, ℓ/p).
void interleave(const std::array<double*, 3>& to, const ContactSolver& a, std::size_t n, std::size_t W, std::size_t j) {
  interleave(to[0], a.elimination(), n, W, j), interleave(to[1], a.inverse_pivot(), n, W, j);
  interleave(to[2], a.upward(), n, W, j);
}

}  // namespace

// A Newmark-type run's step (its lanes' rows, factors and Rⁿ).
NewmarkTypeStep& BatchedSimulation::newmark_step(BarSimulation& run) {
  return dynamic_cast<NewmarkTypeStep&>(*run.step_parts().class_step);
}

void BatchedSimulation::fill_newmark(Group& g, std::vector<BarSimulation>& runs) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.newmark = true;
  for (auto* a : {&g.u,
                  &g.y,
                  &g.w,
                  &g.elimination,
                  &g.inverse_pivot,
                  &g.upward,
                  &g.r,
                  &g.r_next,
                  &g.t,
                  &g.m_diag,
                  &g.m_lower,
                  &g.m_upper,
                  &g.s_diag,
                  &g.s_lower,
                  &g.s_upper,
                  &g.l_diag,
                  &g.l_lower,
                  &g.l_upper,
                  &g.mass_elimination,
                  &g.mass_inverse_pivot,
                  &g.mass_upward,
                  &g.z})
    *a = lane_array(nw, g.arrays);
  for (auto* a : {&g.dt, &g.force_weight, &g.one_minus_gamma, &g.gamma, &g.g0, &g.g1, &g.massless, &g.lambda, &g.shift,
                  &g.kinetic_strain, &g.u0_next, &g.keep})
    *a = lane_values(W);
  for (std::size_t j = 0; j < W; ++j) {
    NewmarkTypeStep& step = newmark_step(runs[g.runs[j]]);
    g.steps.push_back(&step);
    const NewmarkTypeStep::Lanes l = step.lanes();
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, *l.mass, g.n, W, j);
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.l_diag.get(), g.l_lower.get(), g.l_upper.get()}, *l.linear, g.n, W, j);
    interleave({g.elimination.get(), g.inverse_pivot.get(), g.upward.get()}, *l.solver, g.n, W, j);
    interleave({g.mass_elimination.get(), g.mass_inverse_pivot.get(), g.mass_upward.get()}, *l.mass_solver, g.n, W, j);
    interleave(g.z.get(), *l.z, g.n, W, j);  // newmark: no z, zeros (never shifted)
    // As the fused step computes them: Δt²(½ − β) and 1 − γ.
    g.dt[j] = l.dt;
    g.force_weight[j] = l.dt * l.dt * (0.5 - l.beta);
    g.one_minus_gamma[j] = 1 - l.gamma;
    g.gamma[j] = l.gamma;
    g.g0[j] = l.g[0];
    g.g1[j] = l.g[1];
    g.massless[j] = l.massless ? 1.0 : 0.0;
    g.keep[j] = 0.0;
    load_lane(g, j, runs[g.runs[j]]);
  }
}

// A Moreau–Jean or DKE run's step.
OneSolveStep& BatchedSimulation::one_solve_step(BarSimulation& run) {
  return dynamic_cast<OneSolveStep&>(*run.step_parts().class_step);
}

void BatchedSimulation::fill_one_solve(Group& g, std::vector<BarSimulation>& runs, bool dke) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.one_solve = true, g.dke = dke;
  for (auto* a : {&g.u, &g.y, &g.w, &g.p, &g.elimination, &g.inverse_pivot, &g.upward, &g.right_diag, &g.right_lower,
                  &g.right_upper, &g.m_diag, &g.m_lower, &g.m_upper, &g.s_diag, &g.s_lower, &g.s_upper, &g.column})
    *a = lane_array(nw, g.arrays);
  for (auto* a : {&g.dt, &g.weight, &g.theta, &g.one_minus_theta, &g.two_over_dt, &g.row0_zero, &g.alpha, &g.projected,
                  &g.minus_gap, &g.u0_next, &g.keep, &g.kinetic_strain})
    *a = lane_values(W);
  g.solve_decisions.resize(W);
  for (std::size_t j = 0; j < W; ++j) {
    OneSolveStep& step = one_solve_step(runs[g.runs[j]]);
    g.solve_steps.push_back(&step);
    const OneSolveStep::Lanes l = step.lanes();
    interleave({g.right_diag.get(), g.right_lower.get(), g.right_upper.get()}, *l.right, g.n, W, j);
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, *l.mass, g.n, W, j);
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.elimination.get(), g.inverse_pivot.get(), g.upward.get()}, *l.solver, g.n, W, j);
    interleave(g.column.get(), *l.column, g.n, W, j);  // Moreau–Jean, a massless node: zeros (never projected)
    // As the fused steps compute them: 1 − θ, 2/Δt, −g₀.
    g.dt[j] = l.dt;
    g.weight[j] = l.weight;
    g.theta[j] = l.theta;
    g.one_minus_theta[j] = 1 - l.theta;
    g.two_over_dt[j] = 2 / l.dt;
    g.row0_zero[j] = l.row0_zero ? 1.0 : 0.0;
    g.minus_gap[j] = -l.gap;
    g.alpha[j] = 0.0, g.projected[j] = 0.0, g.keep[j] = 0.0;
    load_lane(g, j, runs[g.runs[j]]);
  }
}

void BatchedSimulation::fill_explicit(Group& g, std::vector<BarSimulation>& runs) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.explicit_scheme = true;
  g.lumped = runs[g.runs[0]].step_parts().explicit_step->lanes().lumped;
  for (auto* a : {&g.u, &g.y, &g.w, &g.a, &g.s_diag, &g.s_lower, &g.s_upper, &g.m_diag, &g.m_lower, &g.m_upper,
                  &g.inverse_mass, &g.pivot, &g.factor, &g.impulse_response})
    *a = lane_array(nw, g.arrays);
  for (auto* a : {&g.dt, &g.half_dt, &g.h, &g.clamped, &g.correct, &g.dt_mu, &g.dt2_mu, &g.keep, &g.energy})
    *a = lane_values(W);
  g.explicit_contacts.resize(W);
  for (std::size_t j = 0; j < W; ++j) {
    BarSimulation& run = runs[g.runs[j]];
    const ExplicitStep& step = *run.step_parts().explicit_step;
    g.explicit_steps.push_back(&step);
    const ExplicitStep::Lanes l = step.lanes();
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, run.mass(), g.n, W, j);  // the energy's M
    // The other mass's arrays (lumped: pivot and factor; consistent: 1/m) and explicit's r are empty: zeros.
    interleave(g.inverse_mass.get(), *l.inverse_mass, g.n, W, j);
    interleave(g.pivot.get(), *l.pivot, g.n, W, j);
    interleave(g.factor.get(), *l.factor, g.n, W, j);
    interleave(g.impulse_response.get(), *l.impulse_response, g.n, W, j);
    // As the step and BarSimulation compute them: Δt/2 (0.5Δt) and the energy's h.
    g.dt[j] = l.dt;
    g.half_dt[j] = 0.5 * l.dt;
    g.h[j] = run.mesh().h();
    g.clamped[j] = run.mesh().elements == static_cast<Index>(g.n) ? 1.0 : 0.0;
    g.correct[j] = 0.0, g.dt_mu[j] = 0.0, g.dt2_mu[j] = 0.0, g.keep[j] = 0.0;
    load_lane(g, j, run);
  }
}

void BatchedSimulation::load_lane(Group& g, std::size_t j, BarSimulation& run) {
  const StepState& state = *run.step_parts().state;
  const std::size_t W = g.runs.size();
  if (g.one_solve || g.explicit_scheme) {
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      g.u[i * W + j] = state.u[e];
      g.w[i * W + j] = state.w[e];
    }
    return;
  }
  if (g.newmark) {
    const Eigen::VectorXd& r = *newmark_step(run).lanes().force;
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      g.u[i * W + j] = state.u[e];
      g.w[i * W + j] = state.w[e];
      g.r[i * W + j] = r[e];
    }
    return;
  }
  const std::size_t rows = g.rows[j];  // past them (n − 1 unknowns in a lane of n): zeros, not read
  const bool has_x = static_cast<std::size_t>(state.x.size()) == rows;
  for (std::size_t i = 0; i < g.n; ++i) {
    const auto e = static_cast<Index>(i);
    const bool in = i < rows;
    g.u[i * W + j] = in ? state.u[e] : 0.0;
    g.w[i * W + j] = in ? state.w[e] : 0.0;
    g.x[i * W + j] = in && has_x ? state.x[e] : 0.0;
  }
}

void BatchedSimulation::store_lane(const Group& g, std::size_t j, BarSimulation& run) {
  StepState& state = *run.step_parts().state;
  const std::size_t W = g.runs.size();
  if (g.one_solve || g.explicit_scheme) {
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      state.u[e] = g.u[i * W + j];
      state.w[e] = g.w[i * W + j];
    }
    return;
  }
  if (g.newmark) {
    Eigen::VectorXd& r = *newmark_step(run).lanes().force;
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      state.u[e] = g.u[i * W + j];
      state.w[e] = g.w[i * W + j];
      r[e] = g.r[i * W + j];
    }
    return;
  }
  const std::size_t rows = g.rows[j];
  const bool has_x = static_cast<std::size_t>(state.x.size()) == rows;
  for (std::size_t i = 0; i < rows; ++i) {
    const auto e = static_cast<Index>(i);
    state.u[e] = g.u[i * W + j];
    state.w[e] = g.w[i * W + j];
    if (has_x) state.x[e] = g.x[i * W + j];
  }
}

const BarSimulation& BatchedSimulation::run(std::size_t k) {
  if (k >= runs_.size()) throw std::out_of_range("BatchedSimulation::run: no run " + std::to_string(k));
  if (!stale_[k]) return runs_[k];
  // Every stale lane of k's group in one pass over the interleaved vectors: a driver that observes
  // every run at every step asks for all of them, and one lane alone would read every cache line of the
  // group's vectors (W passes for W lanes). Copies only: the same bits as store_lane.
  const Group& g = *groups_[group_of_[k]];
  const std::size_t W = g.runs.size();
  std::vector<std::size_t> lanes;
  for (std::size_t j = 0; j < g.used; ++j)
    if (stale_[g.runs[j]]) lanes.push_back(j);
  if (lanes.size() == 1 || g.newmark || g.one_solve ||
      g.explicit_scheme) {  // one lane, or a class group's lanes one by one
    for (std::size_t j : lanes) {
      store_lane(g, j, runs_[g.runs[j]]);
      stale_[g.runs[j]] = 0;
    }
    return runs_[k];
  }
  std::vector<double*> u, w, x;
  for (std::size_t j : lanes) {
    StepState& state = *runs_[g.runs[j]].step_parts().state;
    u.push_back(state.u.data());
    w.push_back(state.w.data());
    x.push_back(static_cast<std::size_t>(state.x.size()) == g.rows[j] ? state.x.data() : nullptr);
  }
  const std::size_t count = lanes.size();
  for (std::size_t i = 0; i < g.n; ++i) {
    const double* gu = &g.u[i * W];
    const double* gw = &g.w[i * W];
    const double* gx = &g.x[i * W];
    for (std::size_t m = 0; m < count; ++m) {
      const std::size_t j = lanes[m];
      if (i >= g.rows[j]) continue;  // a lane of n − 1 unknowns
      u[m][i] = gu[j];
      w[m][i] = gw[j];
      if (x[m]) x[m][i] = gx[j];
    }
  }
  for (std::size_t j : lanes) stale_[g.runs[j]] = 0;
  return runs_[k];
}

Sample BatchedSimulation::sample(std::size_t k, LaneVectors& lanes) const {
  if (k >= runs_.size()) throw std::out_of_range("BatchedSimulation::sample: no run " + std::to_string(k));
  const BarSimulation& r = runs_[k];
  const Sample s = r.sample();
  if (!stale_[k]) {
    lanes = own_lanes(s);
  } else {
    // The lanes hold what store_lane would copy: U in u, and the sample's velocity (X for the three-level
    // schemes, W for the two-level ones) in x or w.
    const Group& g = *groups_[group_of_[k]];
    const std::size_t W = g.runs.size(), j = lane_of_[k];
    lanes = {&g.u[j], g.three_level ? &g.x[j] : &g.w[j], W, j};
  }
  return s;
}

std::size_t BatchedSimulation::plateau_rows() const {
  std::size_t rows = 0;
  for (const auto& g : groups_) rows += g->flat_end - g->flat_begin;
  return rows;
}

std::vector<std::size_t> BatchedSimulation::group_widths() const {
  std::vector<std::size_t> widths;
  for (const auto& g : groups_) widths.push_back(g->runs.size());
  return widths;
}

std::size_t BatchedSimulation::batched_runs() const {
  std::size_t count = 0;
  for (const auto& g : groups_) count += g->used;
  return count;
}

void BatchedSimulation::step() { advance(nullptr); }

// A partial step: the runs with advance[k] = 0 are left as they are. In a group they are kept lanes (the
// sweep up writes their U, W' and X back unchanged, as for CN-switch's status changes; the state they
// were computed from is not used), and their bookkeeping is not touched; a group none of whose runs
// advances is not stepped. A padding lane follows lane 0, whose run it repeats.
void BatchedSimulation::step(const std::vector<char>& flags) {
  if (flags.size() != runs_.size())
    throw std::invalid_argument("BatchedSimulation::step: " + std::to_string(flags.size()) + " flags for " +
                                std::to_string(runs_.size()) + " runs (allowed: one per run)");
  advance(flags.data());
}

void BatchedSimulation::advance(const char* flags) {  // null: every run
  if (batched::lane_count(batched::Width::full) != lanes_)
    throw std::logic_error("BatchedSimulation::step: the vector target changed since the batch was made");
  for (const std::size_t k : alone_)
    if (!flags || flags[k]) runs_[k].step();
  for (const auto& group : groups_) {
    Group& g = *group;
    const std::size_t W = g.runs.size();
    const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
    bool any = false, all = true;
    for (std::size_t j = 0; j < g.used; ++j) any = any || moves(j), all = all && moves(j);
    if (!any) continue;
    if (g.newmark) {
      advance_newmark(g, flags);
      continue;
    }
    if (g.one_solve) {
      advance_one_solve(g, flags);
      continue;
    }
    if (g.explicit_scheme) {
      advance_explicit(g, flags);
      continue;
    }
    // Paoli–Schatzman's first step is Crank–Nicolson's (BarSimulation::step's starter): each run alone.
    bool starting = false;
    for (std::size_t j = 0; j < g.used; ++j)
      starting = starting || (moves(j) && runs_[g.runs[j]].step_parts().starting);
    if (starting) {
      for (std::size_t j = 0; j < W; ++j) {
        if (!moves(j)) continue;  // a run that stays: its lane stays too (it may be newer than its vectors)
        BarSimulation& run = runs_[g.runs[j]];
        if (j < g.used) {
          if (stale_[g.runs[j]]) store_lane(g, j, run);
          run.step();
          stale_[g.runs[j]] = 0;
        }
        load_lane(g, j, run);  // a padding lane repeats lane 0's run
      }
      continue;
    }
    batched::Kernel k;
    k.n = g.n, k.lanes = W, k.head = g.head, k.head_min = g.head_min, k.heads = g.heads.get();
    k.short_lanes = g.short_lanes.get();  // null when every lane has n unknowns
    k.flat_begin = g.flat_begin, k.flat_end = g.flat_end;
    k.three_level = g.three_level, k.keeps = g.switching || !all;
    k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.x = g.x.get();
    k.elimination = g.elimination.get(), k.elimination_pair = g.elimination_pair.get();
    k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get(), k.upward_pair = g.upward_pair.get();
    k.head_rows = g.head_rows.get(), k.interior = g.interior.get(), k.last = g.last.get();
    k.rate = g.rate.get(), k.memory = g.memory.get(), k.ps_q_weight = g.ps_q_weight.get();
    k.u0_next = g.u0_next.get(), k.recurrence_d0 = g.recurrence_d0.get(), k.keep = g.keep.get();
    k.energy = g.energy.get();
    k.load = g.load.get();
    batched::sweep_down(g.width, k);
    // Between the sweeps, each lane's contact decision: FastStep::contact_decision, the scalar code.
    std::vector<FastStep::ContactDecision>& decisions = g.decisions;
    for (std::size_t j = 0; j < W; ++j) {
      if (!moves(j)) {  // kept: its values are not written (the sweep up reads but discards them)
        decisions[j] = {};
        g.keep[j] = 1.0;
        g.u0_next[j] = g.u[j];
        g.recurrence_d0[j] = 0.0;
        continue;
      }
      const BarSimulation::StepParts parts = runs_[g.runs[j]].step_parts();
      const StepState& state = *parts.state;
      const bool load = parts.has_load;  // steady (the constructor): F₀ⁿ = F₀ⁿ⁺¹ = F₀
      const FastStep::ContactDecision c =
          parts.fast->contact_decision(g.u[j], g.u[W + j], g.w[j], g.w[W + j], g.y[W + j], state.lambda, state.active,
                                       *parts.solver, load, load ? state.f_now[0] : 0.0, load ? state.f_next[0] : 0.0);
      decisions[j] = c;
      g.keep[j] = c.status_change ? 1.0 : 0.0;
      g.u0_next[j] = c.status_change ? g.u[j] : c.u0_next;  // (a kept lane's values are not written)
      g.recurrence_d0[j] = c.status_change ? 0.0 : c.recurrence_d0;
    }
    batched::sweep_up(g.width, k);
    std::swap(g.u, g.y);  // U = Uⁿ⁺¹, as fused_step swaps u and u_new
    for (std::size_t j = 0; j < g.used; ++j) {
      if (!moves(j)) continue;
      const std::size_t r = g.runs[j];
      BarSimulation& run = runs_[r];
      const BarSimulation::StepParts parts = run.step_parts();
      StepState& state = *parts.state;
      if (decisions[j].status_change) {  // CN-switch's θ-step, alone, from the untouched state
        store_lane(g, j, run);
        run.switch_step(parts.has_load);
        load_lane(g, j, run);
        stale_[r] = 0;
      } else {
        state.lambda = decisions[j].lambda;
        state.active = decisions[j].active;
        state.energy = g.energy[j];
        // finish_step reads the new u₀ and V₁ (the massless node's velocity): those two are copied
        // out now, the rest of the vectors when run(k) is asked for.
        state.u[0] = g.u[j];
        state.w[1] = g.w[W + j];
        stale_[r] = 1;
      }
      run.finish_step();
      if (parts.algebraic_row && !parts.three_level) g.w[j] = state.w[0];  // its massless node's velocity
    }
  }
}

// The skeleton of a class group's step (Newmark type, Moreau–Jean and DKE, explicit): which lanes advance
// (flags: a kept lane is written back unchanged and its run is not touched; a padding lane follows lane 0),
// the family's passes and its lanes' decisions, passes(moves, all) (all: every run advances), then for each
// advancing run its end of step, finish(j, run, state) (the entries its end of step reads are copied out of
// the lanes now, the rest of the vectors when run(k) is asked for), BarSimulation's bookkeeping and the
// massless node's velocity back into the lane.
template <class Passes, class Finish>
void BatchedSimulation::advance_class(Group& g, const char* flags, const Passes& passes, const Finish& finish) {
  const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
  bool all = true;
  for (std::size_t j = 0; j < g.used; ++j) all = all && moves(j);
  passes(moves, all);
  for (std::size_t j = 0; j < g.used; ++j) {
    if (!moves(j)) continue;
    const std::size_t r = g.runs[j];
    BarSimulation& run = runs_[r];
    const BarSimulation::StepParts parts = run.step_parts();
    StepState& state = *parts.state;
    stale_[r] = 1;
    finish(j, run, state);
    run.finish_step();
    if (parts.algebraic_row && !parts.three_level) g.w[j] = state.w[0];  // its massless node's velocity
  }
}

// The Newmark-type group's step: the sweep down of A, each lane's decision (the run's own decide()), the
// sweep up with Rⁿ⁺¹, V and the energy's forms in vectors, then each run's end of step (its finish(): λ,
// status, energy, the finiteness check) and BarSimulation's bookkeeping. A kept lane (flags) is written back
// unchanged and its run is not touched.
void BatchedSimulation::advance_newmark(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto passes = [&](const auto& moves, bool all) {
    batched::NewmarkKernel k;
    k.n = g.n, k.lanes = W, k.keeps = !all;
    k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.r = g.r.get(), k.r_next = g.r_next.get(), k.t = g.t.get();
    k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
    k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
    k.l_diag = g.l_diag.get(), k.l_lower = g.l_lower.get(), k.l_upper = g.l_upper.get();
    k.elimination = g.elimination.get(), k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get();
    k.mass_elimination = g.mass_elimination.get(), k.mass_inverse_pivot = g.mass_inverse_pivot.get();
    k.mass_upward = g.mass_upward.get(), k.z = g.z.get();
    k.dt = g.dt.get(), k.force_weight = g.force_weight.get(), k.one_minus_gamma = g.one_minus_gamma.get();
    k.gamma = g.gamma.get(), k.g0 = g.g0.get(), k.g1 = g.g1.get(), k.massless = g.massless.get();
    k.u0 = g.u0_next.get(), k.lambda = g.lambda.get(), k.shift = g.shift.get(), k.keep = g.keep.get();
    k.kinetic_strain = g.kinetic_strain.get();
    batched::newmark_down(g.width, k);
    for (std::size_t j = 0; j < W; ++j) {
      if (!moves(j)) {  // kept: its values are not written
        g.keep[j] = 1.0, g.lambda[j] = 0.0, g.shift[j] = 0.0, g.u0_next[j] = g.u[j];
        continue;
      }
      const NewmarkTypeStep::Decision c = g.steps[j]->decide(g.y[j], g.y[W + j]);
      g.keep[j] = 0.0, g.lambda[j] = c.lambda, g.shift[j] = c.shift ? 1.0 : 0.0, g.u0_next[j] = c.u0;
    }
    batched::newmark_up(g.width, k);
    std::swap(g.u, g.y);  // U = Uⁿ⁺¹ and Rⁿ = Rⁿ⁺¹, as the step swaps them
    std::swap(g.r, g.r_next);
  };
  advance_class(g, flags, passes, [&](std::size_t j, BarSimulation& run, StepState& state) {
    // finish() reads u₀, u₁ (Nitsche's energy) and finish_step V₁ (the massless node's velocity): those are
    // copied out now, the rest of the vectors when run(k) is asked for.
    state.u[0] = g.u[j];
    state.u[1] = g.u[W + j];
    state.w[1] = g.w[W + j];
    g.steps[j]->finish(state, g.lambda[j], g.kinetic_strain[j], run.level());
  });
}

// A Moreau–Jean or DKE group's step: each lane's projection (DKE), the sweep down of A, each lane's contact
// step (the run's own decide()), the sweep up with the other vector and the energy's forms in vectors, then
// each run's end of step (its finish(): λ, status, energy, the finiteness check) and BarSimulation's
// bookkeeping. A kept lane (flags) is written back unchanged and its run is not touched.
void BatchedSimulation::advance_one_solve(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto passes = [&](const auto& moves, bool all) {
    batched::OneSolveKernel k;
    k.n = g.n, k.lanes = W, k.keeps = !all, k.dke = g.dke;
    k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.p = g.p.get();
    k.right_diag = g.right_diag.get(), k.right_lower = g.right_lower.get(), k.right_upper = g.right_upper.get();
    k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
    k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
    k.elimination = g.elimination.get(), k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get();
    k.column = g.column.get(), k.dt = g.dt.get(), k.weight = g.weight.get(), k.theta = g.theta.get();
    k.one_minus_theta = g.one_minus_theta.get(), k.two_over_dt = g.two_over_dt.get(), k.row0_zero = g.row0_zero.get();
    k.alpha = g.alpha.get(), k.projected = g.projected.get(), k.minus_gap = g.minus_gap.get();
    k.x0 = g.u0_next.get(), k.keep = g.keep.get(), k.kinetic_strain = g.kinetic_strain.get();
    for (std::size_t j = 0; j < W; ++j) {  // DKE's projection, from u₀ⁿ and v₀ⁿ (a kept lane projects nothing)
      const std::optional<double> alpha = moves(j) ? g.solve_steps[j]->projection(g.u[j], g.w[j]) : std::nullopt;
      g.projected[j] = alpha ? 1.0 : 0.0;
      g.alpha[j] = alpha.value_or(0.0);
    }
    batched::one_solve_down(g.width, k);
    for (std::size_t j = 0; j < W; ++j) {
      if (!moves(j)) {  // kept: its values are not written
        g.keep[j] = 1.0, g.u0_next[j] = 0.0, g.solve_decisions[j] = {};
        continue;
      }
      g.solve_decisions[j] = g.solve_steps[j]->decide(g.y[j], g.u[j], g.w[j]);
      g.keep[j] = 0.0, g.u0_next[j] = g.solve_decisions[j].x0;
    }
    batched::one_solve_up(g.width, k);
    // The new level: Moreau–Jean's Vⁿ⁺¹ and DKE's Uⁿ⁺¹ are in y, as each step swaps them in.
    std::swap(g.dke ? g.u : g.w, g.y);
  };
  advance_class(g, flags, passes, [&](std::size_t j, BarSimulation& run, StepState& state) {
    // finish_step reads u₀ and V₁ (the massless node's velocity): the entries 0 and 1 are copied out now, the
    // rest of the vectors when run(k) is asked for.
    state.u[0] = g.u[j], state.u[1] = g.u[W + j];
    state.w[0] = g.w[j], state.w[1] = g.w[W + j];
    g.solve_steps[j]->finish(state, g.solve_decisions[j], g.alpha[j], g.kinetic_strain[j], run.level());
  });
}

// An explicit group's step: the half kick and the drift in vectors, each lane's contact (the run's own
// ExplicitStep::contact: Taylor–Flanagan's correction, whose update of V and Ũ is then made in vectors, or the
// explicit scheme's u₀), the second half kick and the energy in vectors, then each run's end of step (λ, the
// status, the energy) and BarSimulation's bookkeeping. A kept lane (flags) is written back unchanged and its
// run is not touched.
void BatchedSimulation::advance_explicit(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto passes = [&](const auto& moves, bool all) {
    for (std::size_t j = 0; j < W; ++j) g.keep[j] = moves(j) ? 0.0 : 1.0, g.correct[j] = 0.0;
    batched::ExplicitKernel k;
    k.n = g.n, k.lanes = W, k.keeps = !all, k.lumped = g.lumped;
    k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.a = g.a.get();
    k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
    k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
    k.inverse_mass = g.inverse_mass.get(), k.pivot = g.pivot.get(), k.factor = g.factor.get();
    k.impulse_response = g.impulse_response.get(), k.dt = g.dt.get(), k.half_dt = g.half_dt.get(), k.h = g.h.get();
    k.clamped = g.clamped.get(), k.correct = g.correct.get(), k.dt_mu = g.dt_mu.get(), k.dt2_mu = g.dt2_mu.get();
    k.keep = g.keep.get(), k.energy = g.energy.get();
    batched::explicit_drift(g.width, k);
    for (std::size_t j = 0; j < W; ++j) {
      if (!moves(j)) continue;  // kept: no correction, its Ũ (its Uⁿ) untouched
      const ExplicitStep::Contact c = g.explicit_steps[j]->contact(g.y[j], g.y[W + j], g.w[j], 0.0);
      g.explicit_contacts[j] = c;
      if (c.correct) {  // as the step computes them: (Δtμ) and (Δt Δt μ)
        g.correct[j] = 1.0, g.dt_mu[j] = g.dt[j] * c.lambda, g.dt2_mu[j] = g.dt[j] * g.dt[j] * c.lambda;
        k.corrects = true;
      }
      if (c.set_u0) g.y[j] = c.u0;
    }
    batched::explicit_kick(g.width, k);
    std::swap(g.u, g.y);  // U = Uⁿ⁺¹
  };
  advance_class(g, flags, passes, [&](std::size_t j, BarSimulation&, StepState& state) {
    // finish_step reads u₀ and V₁ (the massless node's velocity): the entries 0 and 1 are copied out now, the
    // rest of the vectors when run(k) is asked for.
    state.u[0] = g.u[j], state.u[1] = g.u[W + j];
    state.w[0] = g.w[j], state.w[1] = g.w[W + j];
    state.lambda = g.explicit_contacts[j].lambda;
    state.active = g.explicit_contacts[j].active;
    state.energy = g.energy[j];
  });
}

}  // namespace mrm
