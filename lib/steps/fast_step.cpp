/// @file fast_step.cpp
/// @brief The fast path of BarSimulation (mathematics.md §4): the step (★) of schemes.cpp fused into
/// the two sweeps of its tridiagonal solve.
///
/// It computes what BarSimulation's reference step computes (schemes.cpp: assembled matrices,
/// ContactSolver::solve, the velocity and the energy from their definitions), in another order, on the
/// StepState it is given; the doctest at the end of this file compares the two for every scheme, mass
/// and contact-row form.
#include "steps/fast_step.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include <doctest/doctest.h>

#include "steps/contact.hpp"
#include "steps/energy_step.hpp"
#include "fem/mass_redistribution.hpp"

namespace mrm {

// The rows of C₁, C₂ (the increment form), M and S as the fused step reads them. On a uniform mesh every row away from
// the contact node is the same (the matrices are Toeplitz there) except the last, whose upper
// neighbour is the clamped node: the rows from `head` to n−2 share one Row. `head` is the first
// row from which on all rows up to n−2 are equal, compared exactly, so any weights are handled
// (Mod 1 and Mod 2 give head = 2, Mod 3 and the consistent mass 2 and 1; a weight that varies
// along the bar gives head = n−1, every row explicit).
FastStep::FastStep(const StepMatrices& step, const Tridiagonal& m, const Tridiagonal& s, const SchemeParameters& p,
                   double h)
    : coefficients_(step),
      three_level_(p.scheme == Scheme::paoli_schatzman),
      energy_conserving_(p.scheme == Scheme::energy_conserving),
      switching_(p.scheme == Scheme::switching),
      restitution_(p.restitution),
      beta_(p.beta),
      h_(h) {
  const Tridiagonal &c1 = step.c1, &c2 = step.c2;  // the increment form's matrices (schemes.cpp)
  coefficients_.a = coefficients_.b1 = coefficients_.b2 = coefficients_.c1 = coefficients_.c2 =
      Tridiagonal();                                      // the scalars only; C₁, C₂ in Rows
  const Index minimum_head = energy_conserving_ ? 2 : 1;  // EC reads row 1 explicitly (see the sweep up)
  const Index rows = m.size();
  const auto row = [&](Index i) {
    const bool last = i + 1 == rows;
    return Row{c1.lower[i],   c1.diag[i],     last ? 0.0 : c1.upper[i],
               c2.lower[i],   c2.diag[i],     last ? 0.0 : c2.upper[i],
               m.diag[i],     2 * m.lower[i], s.diag[i],
               2 * s.lower[i]};
  };
  const auto same = [](const Row& x, const Row& y) {
    return x.c1l == y.c1l && x.c1d == y.c1d && x.c1u == y.c1u && x.c2l == y.c2l && x.c2d == y.c2d && x.c2u == y.c2u &&
           x.md == y.md && x.ml2 == y.ml2 && x.sd == y.sd && x.sl2 == y.sl2;
  };
  last_ = row(rows - 1);
  interior_ = last_;
  Index head = 1;  // n = 2: row 0 and the last row only
  if (rows >= 3) {
    interior_ = row(rows - 2);
    head = rows - 2;
    while (head > 1 && same(row(head - 1), interior_)) --head;
    // The interior loop uses the symmetry of C₁ and C₂ there; without it, every row is explicit.
    if (!(interior_.c1l == interior_.c1u && interior_.c2l == interior_.c2u)) head = rows - 1;
    head = std::max(head, std::min(minimum_head, rows - 1));
  }
  head_.clear();
  for (Index i = 0; i < head; ++i) head_.push_back(row(i));
}

bool FastStep::step(StepState& state, const ContactSolver& solver, bool has_load) const {
  if (three_level_) return has_load ? fused_step<true, true>(state, solver) : fused_step<true, false>(state, solver);
  return has_load ? fused_step<false, true>(state, solver) : fused_step<false, false>(state, solver);
}

// Row 0 and the contact decision (κ = 1 for the algebraic contact row, set at assembly), from the
// values of Uⁿ and W' at nodes 0 and 1, y₁ of the sweep down, λⁿ and the status (the load's values at
// node 0 are read only with a load). The same code for the fused step and each lane of the batched step
// (batched_step.cpp), so that both do the same operations in the same order.
FastStep::ContactDecision FastStep::contact_decision(double u0, double u1, double w0, double w1, double y_next,
                                                     double lambda, bool active, const ContactSolver& solver,
                                                     bool has_load, double f0_now, double f0_next) const {
  const double g_now = coefficients_.load_now, g_next = coefficients_.load_next;
  const Row& r0 = head_[0];
  double b0;
  if (coefficients_.algebraic_row) {
    b0 = r0.c1d * u0 + r0.c1u * u1 + (has_load ? f0_next : 0.0);  // F₀ⁿ⁺¹ − S₀·Uⁿ
  } else {
    b0 = r0.c1d * u0 + r0.c1u * u1 + r0.c2d * w0 + r0.c2u * w1 - coefficients_.lambda_in_rhs * lambda;
    if (has_load) b0 += g_now * f0_now + g_next * f0_next;
  }
  // EC decides the contact on row 1 instead (energy_step.cpp: its sweep up starts from the value u₀
  // that carries the discrete-gradient force, which is not the contact node's new value at a status
  // change); CN-switch returns before writing anything when the status changes.
  // The obstacle g = −e u₀ⁿ⁻¹ = −e (u₀ⁿ − W'₀), moved by the gap, and of the increment g − u₀ⁿ;
  // on contact u₀ⁿ⁺¹ = g exactly. EC's scalar problem is written for u: row 1's ΔU₁ = z + μΔU₀ is passed as
  // u₁ⁿ⁺¹ = (u₁ⁿ + z − μu₀ⁿ) + μu₀ⁿ⁺¹ (schemes.cpp, the reference step).
  double obstacle = three_level_ ? -restitution_ * (u0 - w0) : 0.0;
  if (coefficients_.obstacle_offset != 0.0) obstacle += coefficients_.obstacle_offset;  // (keeps a −0)
  ContactDecision decision;
  if (energy_conserving_) {
    const double h = h_, mu = -solver.upward()[1];
    const double gap = coefficients_.obstacle_offset != 0.0 ? -coefficients_.obstacle_offset : 0.0;  // g₀
    const double load0_now = has_load ? f0_now : 0.0, load0_next = has_load ? f0_next : 0.0;
    const EnergyConservingContact c = energy_conserving_contact(u1 + solver.inverse_pivot()[1] * y_next - mu * u0, mu,
                                                                u0, u1 + h * load0_now, h, load0_next, gap);
    decision.lambda = c.multiplier;
    decision.active = c.active;
    decision.u0_next = c.u0;
    decision.recurrence_d0 = c.recurrence_u0 - u0;
  } else {
    const ContactStep contact =
        solver.resolve_contact(b0 - solver.elimination()[0] * y_next, coefficients_.kappa, obstacle - u0);
    if (switching_ && contact.active != active) {
      decision.status_change = true;
      return decision;
    }
    decision.lambda = contact.multiplier;
    decision.active = contact.active;
    decision.u0_next = contact.active ? obstacle : u0 + contact.u0;
    decision.recurrence_d0 = contact.u0;
  }
  return decision;
}

/// @file fast_step.cpp
/// ## One step fused into the two sweeps of the solve
///
/// One step of (★), fused into the two sweeps of the solve, with no allocation and no refactorisation:
///
/// - the sweep down (i = n−1 … 1) forms b_i = (C₁Uⁿ + C₂W' + G)_i, the right-hand side of the increment
///   form A ΔU = C₁Uⁿ + C₂W' + G − κλe₀ (schemes.cpp), from the neighbours of node i and
///   eliminates at once, y_i = b_i − ε_i y_{i+1} (ε the elimination factors of contact.cpp);
/// - the contact is decided at node 0's pivot d₀ = 1/(A⁻¹)₀₀, the Schur complement of A onto the
///   contact node (contact.cpp: this is what the w = θA⁻¹C of mathematics.md §4 does, for the price of a scalar);
/// - the sweep up (i = 0 … n−1) gives ΔU_i = y_i/d_i − (A_{i,i−1}/d_i) ΔU_{i−1}, Uⁿ⁺¹_i = Uⁿ_i + ΔU_i
///   and, from the values at nodes i−1 and i, the new W' and X (from ΔU, never from a difference of
///   two levels) and the quadratic forms of the energy.
///
/// Each sweep is a first-order recurrence: its chain of dependent operations (a multiplication and a
/// subtraction per node) is what limits a tridiagonal solve on a modern core, not the arithmetic nor
/// the memory traffic. Both recurrences are therefore run in their two-chain form (contact.hpp:
/// y_i from y_{i+2}, Uⁿ⁺¹_i from Uⁿ⁺¹_{i−2}, even and odd nodes independent), which halves the
/// chain; row 0 keeps the one-step form (its elimination factor is of order 1/h², the product with
/// the next one would cost accuracy). Everything else (the right-hand side, the velocities, the
/// energy) is independent work that the processor overlaps with the chains; with the chains halved,
/// that work is what the step costs (bench_step measures both). To keep it small, the coefficients of
/// C₁, C₂, M and S are read from a few Rows (the Toeplitz interior, where B₁ and B₂ are symmetric:
/// four multiplications for b_i), so the memory traffic is that of the state vectors and the factor
/// arrays. The energies need only the quadratic forms of their definition: two-level,
/// E = ½ VᵀMV + ½ UᵀSU at the new level; Paoli–Schatzman, with P = Uⁿ⁺¹ + Uⁿ and Q = Uⁿ⁺¹ − Uⁿ,
///
///     β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ = ¼ (PᵀSP − (1 − 4β) QᵀSQ),
///
/// (expand PᵀSP and QᵀSQ), so E = ½ XᵀMX + ⅛ (PᵀSP − (1−4β) QᵀSQ), and for β = ¼ only PᵀSP counts.
/// The scheme (two or three levels) and the presence of a load are template parameters, so that the
/// loops carry no dead work.
template <bool three_level, bool has_load>
bool FastStep::fused_step(StepState& state, const ContactSolver& solver) const {
  const Index n = state.u.size();
  const Index head = static_cast<Index>(head_.size());
  const double* u = state.u.data();
  const double* w = state.w.data();
  double* y = state.u_new.data();
  const double* elimination = solver.elimination().data();
  const double* inverse_pivot = solver.inverse_pivot().data();
  const double* upward = solver.upward().data();
  const double* f_now = has_load ? state.f_now.data() : nullptr;
  const double* f_next = has_load ? state.f_next.data() : nullptr;
  const double g_now = coefficients_.load_now, g_next = coefficients_.load_next;

  // Sweep down, as two chains (contact.hpp): y_i = (b_i − ε_i b_{i+1}) + ε_iε_{i+1} y_{i+2}, from row
  // n−1 (its upper neighbour is the clamped node; with b_n = y_n = y_{n+1} = 0 the formula gives
  // y_{n−1} = b_{n−1}, and ε_{n−1} = 0 gives y_{n−2} = b_{n−2} − ε_{n−2} y_{n−1}), through the interior
  // rows n−2 … head with their common coefficients and the head rows head−1 … 1 with their own.
  const double* elimination_pair = solver.elimination_pair().data();
  const auto rhs = [&](const Row& r, Index i, double u_up, double w_up) {
    double b = r.c1l * u[i - 1] + r.c1d * u[i] + r.c1u * u_up + r.c2l * w[i - 1] + r.c2d * w[i] + r.c2u * w_up;
    if constexpr (has_load) b += g_now * f_now[i] + g_next * f_next[i];
    return b;
  };
  // In the interior, C₁ and C₂ are symmetric Toeplitz (checked at set-up): b_i = C₁_l (u_{i−1} + u_{i+1})
  // + C₁_d u_i + the same for W', four multiplications instead of six.
  const auto rhs_interior = [&](const Row& r, Index i) {
    double b = r.c1l * (u[i - 1] + u[i + 1]) + r.c1d * u[i] + r.c2l * (w[i - 1] + w[i + 1]) + r.c2d * w[i];
    if constexpr (has_load) b += g_now * f_now[i] + g_next * f_next[i];
    return b;
  };
  double b_up = 0, y_up = 0, y_up2 = 0;  // b_{i+1}, y_{i+1}, y_{i+2}
  const auto eliminate = [&](Index i, double b) {
    const double yi = (b - elimination[i] * b_up) + elimination_pair[i] * y_up2;
    y[i] = yi;
    b_up = b, y_up2 = y_up, y_up = yi;
  };
  eliminate(n - 1, rhs(last_, n - 1, 0.0, 0.0));
  {
    const Row r = interior_;
    for (Index i = n - 2; i >= head; --i) eliminate(i, rhs_interior(r, i));
  }
  for (Index i = std::min(head, n - 1) - 1; i >= 1; --i)
    eliminate(i, rhs(head_[static_cast<std::size_t>(i)], i, u[i + 1], w[i + 1]));
  const double y_next = y_up;

  // Row 0 and the contact decision (contact_decision above; the batched step calls it lane by lane).
  const Row& r0 = head_[0];
  const ContactDecision decision = contact_decision(u[0], u[1], w[0], w[1], y_next, state.lambda, state.active, solver,
                                                    has_load, has_load ? f_now[0] : 0.0, has_load ? f_next[0] : 0.0);
  if (decision.status_change) return false;  // CN-switch: its θ-step instead, nothing written yet
  state.lambda = decision.lambda;
  state.active = decision.active;
  const double u0_next = decision.u0_next, recurrence_d0 = decision.recurrence_d0;

  // Sweep up. Two-level: V' = rate ΔU − memory V, written over W', kinetic form V'ᵀMV', potential
  // U'ᵀSU'. Three-level: X = ΔU/Δt, forms XᵀMX, PᵀSP, QᵀSQ (Q = ΔU); ΔU written over W'.
  double* w_out = state.w.data();
  double* x_out = state.x.data();
  const double rate = coefficients_.velocity_rate, memory = coefficients_.velocity_memory;
  double kinetic = 0, potential = 0, potential_q = 0;
  double un_prev = 0, d_prev = 0, d_prev2 = 0, z_prev = 0, v_prev = 0, p_prev = 0, q_prev = 0;
  // The interior rows a = head … b = n−2 of M and S are Toeplitz, (d, l) = (A_ii, A_{i,i−1}): there a
  // form is accumulated through D = Σ (z_i − z_{i−1})² and Q = Σ z_i², since
  //
  //     Σ_{i=a}^{b} (d z_i² + 2l z_{i−1} z_i) = −l D + (d + 2l) Q − l z_b² + l z_{a−1}²
  //
  // (expand −l (z_i − z_{i−1})² and telescope). For S, d + 2l = 0: the stiffness forms are sums of
  // squared differences, free of the cancellation of Σ z_i² against Σ z_{i−1} z_i (relative error
  // O(ε) instead of O(ε N²): the energy of Crank–Nicolson stays constant to round-off).
  double k_d = 0, k_q = 0, p_d = 0, p_q = 0, q_d = 0, q_q = 0;
  // emit(i, ΔU_i, Uⁿ⁺¹_i): node 0 passes its own Uⁿ⁺¹_0 (g exactly on contact, EC's max(0, s)).
  const auto emit = [&](const Row& r, Index i, double d, double un, auto toeplitz) {
    constexpr bool sums = decltype(toeplitz)::value;
    const double uo = u[i];
    y[i] = un;
    if constexpr (three_level) {
      const double x = rate * d, p = un + uo, q = d;
      x_out[i] = x;
      w_out[i] = d;
      if constexpr (sums) {
        const double dx = x - v_prev, dp = p - p_prev, dq = q - q_prev;
        k_d += dx * dx, k_q += x * x;
        p_d += dp * dp, p_q += p * p;
        q_d += dq * dq, q_q += q * q;
      } else {
        kinetic += r.md * x * x + r.ml2 * v_prev * x;
        potential += r.sd * p * p + r.sl2 * p_prev * p;
        potential_q += r.sd * q * q + r.sl2 * q_prev * q;
      }
      v_prev = x, p_prev = p, q_prev = q;
    } else {
      const double v = rate * d - memory * w[i];
      w_out[i] = v;
      if constexpr (sums) {
        const double dv = v - v_prev, du = un - un_prev;
        k_d += dv * dv, k_q += v * v;
        p_d += du * du, p_q += un * un;
      } else {
        kinetic += r.md * v * v + r.ml2 * v_prev * v;
        potential += r.sd * un * un + r.sl2 * un_prev * un;
      }
      v_prev = v;
    }
    un_prev = un;
    d_prev2 = d_prev, d_prev = d;
  };
  const std::false_type explicit_row;
  const std::true_type toeplitz_row;
  // ΔU_i = (z_i − c_i z_{i−1}) + c_i c_{i−1} ΔU_{i−2}, z_i = y_i/d_i, two chains again; z₀ = ΔU₀ (c₀ = 0).
  const double* upward_pair = solver.upward_pair().data();
  const auto solve_up = [&](Index i) {
    const double z = inverse_pivot[i] * y[i];
    const double d = (z - upward[i] * z_prev) + upward_pair[i] * d_prev2;
    z_prev = z;
    return d;
  };
  const auto emit_up = [&](const Row& r, Index i, auto toeplitz) {
    const double d = solve_up(i);
    emit(r, i, d, u[i] + d, toeplitz);
  };
  // Node 0's value enters the energy and the velocity; the recurrence runs from recurrence_d0 (the same
  // number except for EC at a status change): z₀ for node 1, and ΔU_{i−2} for node 2, set after node 1
  // (EC keeps row 1 among the explicit rows for this: minimum_head = 2).
  emit(r0, 0, u0_next - u[0], u0_next, explicit_row);
  z_prev = recurrence_d0;
  for (Index i = 1; i < std::min(head, n - 1); ++i) {
    emit_up(head_[static_cast<std::size_t>(i)], i, explicit_row);
    if (i == 1) d_prev2 = recurrence_d0;
  }
  if (head < n - 1) {
    const Row r = interior_;
    // The values z_{a−1} at row head − 1 (the first of the kinetic, the potential and the second forms).
    const double ka = v_prev, pa = three_level ? p_prev : un_prev, qa = q_prev;
    for (Index i = head; i < n - 1; ++i) emit_up(r, i, toeplitz_row);
    const double kb = v_prev, pb = three_level ? p_prev : un_prev, qb = q_prev;
    const auto form = [](double d, double l2, double sum_d, double sum_q, double za, double zb) {
      const double l = 0.5 * l2;
      return -l * sum_d + (d + l2) * sum_q - l * zb * zb + l * za * za;
    };
    kinetic += form(r.md, r.ml2, k_d, k_q, ka, kb);
    potential += form(r.sd, r.sl2, p_d, p_q, pa, pb);
    if constexpr (three_level) potential_q += form(r.sd, r.sl2, q_d, q_q, qa, qb);
  }
  emit_up(last_, n - 1, explicit_row);

  if constexpr (three_level) {
    state.energy = 0.5 * kinetic + 0.125 * (potential - (1 - 4 * beta_) * potential_q);
    state.u.swap(state.u_new);  // U = Uⁿ⁺¹ (W' = ΔU was written in the sweep up)
  } else {
    state.energy = 0.5 * kinetic + 0.5 * potential;
    state.u.swap(state.u_new);
  }
  if constexpr (has_load) state.f_now.swap(state.f_next);
  return true;
}

/// @file fast_step.cpp
/// ## The fast step against the reference step
///
}  // namespace mrm
