// The fast path of BarSimulation (mathematics.md §4): the step (★) of schemes.cpp, fused into the
// two sweeps of its tridiagonal solve. It computes what BarSimulation's reference step computes
// (schemes.cpp: assembled matrices, ContactSolver::solve, the velocity and the energy from their
// definitions), in another order: the doctest "the fast step and the reference step agree to
// round-off" in schemes.cpp compares the two for every scheme, mass and contact-row form.
#include "fast_step.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "contact.hpp"
#include "energy_step.hpp"
#include "schemes.hpp"

namespace mrm {

// The rows of B₁, B₂, M and S as the fused step reads them. On a uniform mesh every row away from
// the contact node is the same (the matrices are Toeplitz there) except the last, whose upper
// neighbour is the clamped node: the rows from `head` to n−2 share one Row. `head` is the first
// row from which on all rows up to n−2 are equal, compared exactly, so any weights are handled
// (Mod 1 and Mod 2 give head = 2, Mod 3 and the consistent mass 2 and 1; a weight that varies
// along the bar gives head = n−1, every row explicit).
FastStep::FastStep(const Tridiagonal& b1, const Tridiagonal& b2, const Tridiagonal& m, const Tridiagonal& s,
                   Index minimum_head) {
  const Index rows = m.size();
  const auto row = [&](Index i) {
    const bool last = i + 1 == rows;
    return Row{b1.lower[i],   b1.diag[i],     last ? 0.0 : b1.upper[i],
               b2.lower[i],   b2.diag[i],     last ? 0.0 : b2.upper[i],
               m.diag[i],     2 * m.lower[i], s.diag[i],
               2 * s.lower[i]};
  };
  const auto same = [](const Row& x, const Row& y) {
    return x.b1l == y.b1l && x.b1d == y.b1d && x.b1u == y.b1u && x.b2l == y.b2l && x.b2d == y.b2d && x.b2u == y.b2u &&
           x.md == y.md && x.ml2 == y.ml2 && x.sd == y.sd && x.sl2 == y.sl2;
  };
  last_ = row(rows - 1);
  interior_ = last_;
  Index head = 1;  // n = 2: row 0 and the last row only
  if (rows >= 3) {
    interior_ = row(rows - 2);
    head = rows - 2;
    while (head > 1 && same(row(head - 1), interior_)) --head;
    // The interior loop uses the symmetry of B₁ and B₂ there; without it, every row is explicit.
    if (!(interior_.b1l == interior_.b1u && interior_.b2l == interior_.b2u)) head = rows - 1;
    head = std::max(head, std::min(minimum_head, rows - 1));
  }
  head_.clear();
  for (Index i = 0; i < head; ++i) head_.push_back(row(i));
}

bool FastStep::step(BarSimulation& simulation, bool has_load) const {
  const bool scaled = simulation.scaled_;
  if (simulation.three_level_) {
    if (has_load) return scaled ? fused_step<true, true, true>(simulation) : fused_step<true, true, false>(simulation);
    return scaled ? fused_step<true, false, true>(simulation) : fused_step<true, false, false>(simulation);
  }
  if (has_load) return scaled ? fused_step<false, true, true>(simulation) : fused_step<false, true, false>(simulation);
  return scaled ? fused_step<false, false, true>(simulation) : fused_step<false, false, false>(simulation);
}

// One step of (★), fused into the two sweeps of the solve, with no allocation and no refactorisation:
//
// - the sweep down (i = n−1 … 1) forms b_i = (B₁Uⁿ + B₂W + G)_i from the neighbours of node i and
//   eliminates at once, y_i = b_i − ε_i y_{i+1} (ε the elimination factors of contact.cpp);
// - the contact is decided at node 0's pivot d₀ = 1/(A⁻¹)₀₀, the Schur complement of A onto the
//   contact node (contact.cpp: this is what the w = θA⁻¹C of mathematics.md §4 does, for the price of a scalar);
// - the sweep up (i = 0 … n−1) gives Uⁿ⁺¹_i = y_i/d_i − (A_{i,i−1}/d_i) Uⁿ⁺¹_{i−1} and, from the values
//   at nodes i−1 and i, the new W and X and the quadratic forms of the energy.
//
// Each sweep is a first-order recurrence: its chain of dependent operations (a multiplication and a
// subtraction per node) is what limits a tridiagonal solve on a modern core, not the arithmetic nor
// the memory traffic. Both recurrences are therefore run in their two-chain form (contact.hpp:
// y_i from y_{i+2}, Uⁿ⁺¹_i from Uⁿ⁺¹_{i−2}, even and odd nodes independent), which halves the
// chain; row 0 keeps the one-step form (its elimination factor is of order 1/h², the product with
// the next one would cost accuracy). Everything else (the right-hand side, the velocities, the
// energy) is independent work that the processor overlaps with the chains; with the chains halved,
// that work is what the step costs (bench_step measures both). To keep it small, the coefficients of
// B₁, B₂, M and S are read from a few Rows (the Toeplitz interior, where B₁ and B₂ are symmetric:
// four multiplications for b_i), so the memory traffic is that of the state vectors and the factor
// arrays. The energies need only the quadratic forms of their definition: two-level,
// E = ½ VᵀMV + ½ UᵀSU at the new level; Paoli–Schatzman, with P = Uⁿ⁺¹ + Uⁿ and Q = Uⁿ⁺¹ − Uⁿ,
//
//     β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ = ¼ (PᵀSP − (1 − 4β) QᵀSQ),
//
// (expand PᵀSP and QᵀSQ), so E = ½ XᵀMX + ⅛ (PᵀSP − (1−4β) QᵀSQ), and for β = ¼ only PᵀSP counts.
// The scheme (two or three levels) and the presence of a load are template parameters, so that the
// loops carry no dead work.
template <bool three_level, bool has_load, bool scaled>
bool FastStep::fused_step(BarSimulation& sim) const {
  const Index n = sim.mesh_.unknowns();
  const Index head = static_cast<Index>(head_.size());
  const double* u = sim.u_.data();
  const double* w = sim.w_.data();
  double* y = sim.u_new_.data();
  const double* elimination = sim.solver_.elimination().data();
  const double* inverse_pivot = sim.solver_.inverse_pivot().data();
  const double* upward = sim.solver_.upward().data();
  const double* f_now = has_load ? sim.f_now_.data() : nullptr;
  const double* f_next = has_load ? sim.f_next_.data() : nullptr;
  const double g_now = sim.step_.load_now, g_next = sim.step_.load_next;

  // Sweep down, as two chains (contact.hpp): y_i = (b_i − ε_i b_{i+1}) + ε_iε_{i+1} y_{i+2}, from row
  // n−1 (its upper neighbour is the clamped node; with b_n = y_n = y_{n+1} = 0 the formula gives
  // y_{n−1} = b_{n−1}, and ε_{n−1} = 0 gives y_{n−2} = b_{n−2} − ε_{n−2} y_{n−1}), through the interior
  // rows n−2 … head with their common coefficients and the head rows head−1 … 1 with their own.
  const double* elimination_pair = sim.solver_.elimination_pair().data();
  const auto rhs = [&](const Row& r, Index i, double u_up, double w_up) {
    double b = r.b1l * u[i - 1] + r.b1d * u[i] + r.b1u * u_up + r.b2l * w[i - 1] + r.b2d * w[i] + r.b2u * w_up;
    if constexpr (has_load) b += g_now * f_now[i] + g_next * f_next[i];
    return b;
  };
  // In the interior, B₁ and B₂ are symmetric Toeplitz (checked at set-up): b_i = B₁_l (u_{i−1} + u_{i+1})
  // + B₁_d u_i + the same for W, four multiplications instead of six.
  const auto rhs_interior = [&](const Row& r, Index i) {
    double b = r.b1l * (u[i - 1] + u[i + 1]) + r.b1d * u[i] + r.b2l * (w[i - 1] + w[i + 1]) + r.b2d * w[i];
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

  // Row 0 and the contact decision (κ = 1 for the algebraic contact row, set at assembly).
  const Row& r0 = head_[0];
  double b0;
  if (sim.algebraic_row_) {
    b0 = has_load ? f_next[0] : 0.0;
  } else {
    b0 = r0.b1d * u[0] + r0.b1u * u[1] + r0.b2d * w[0] + r0.b2u * w[1] - sim.step_.lambda_in_rhs * sim.lambda_;
    if constexpr (has_load) b0 += g_now * f_now[0] + g_next * f_next[0];
  }
  // EC decides the contact on row 1 instead (energy_step.cpp: its sweep up starts from the value u₀
  // that carries the discrete-gradient force, which is not the contact node's new value at a status
  // change); CN-switch returns before writing anything when the status changes.
  const double obstacle = three_level ? -sim.parameters_.restitution * w[0] : 0.0;
  ContactStep contact;
  double recurrence_u0;
  if (sim.energy_conserving_) {
    const double h = sim.mesh_.h();
    const double load0_now = has_load ? f_now[0] : 0.0, load0_next = has_load ? f_next[0] : 0.0;
    const EnergyConservingContact c =
        energy_conserving_contact(inverse_pivot[1] * y_next, -upward[1], u[0], u[1] + h * load0_now, h, load0_next);
    contact = {c.u0, c.multiplier, c.active};
    recurrence_u0 = c.recurrence_u0;
  } else {
    contact = sim.solver_.resolve_contact(b0 - elimination[0] * y_next, sim.step_.kappa, obstacle);
    if (sim.switch_ && contact.active != sim.active_) return false;
    recurrence_u0 = contact.u0;
  }
  sim.lambda_ = contact.multiplier;
  sim.active_ = contact.active;

  // Sweep up. Two-level: V' = rate (U' − U) − memory V, written over W, kinetic form V'ᵀMV',
  // potential U'ᵀSU'. Three-level: X = (U' − U)/Δt, forms XᵀMX, PᵀSP, QᵀSQ; W' = Uⁿ by a swap below.
  double* w_out = sim.w_.data();
  double* x_out = sim.x_.data();
  const double rate = sim.step_.velocity_rate, memory = sim.step_.velocity_memory;
  double kinetic = 0, potential = 0, potential_q = 0;
  double un_prev = 0, un_prev2 = 0, z_prev = 0, v_prev = 0, p_prev = 0, q_prev = 0;
  // The interior rows a = head … b = n−2 of M and S are Toeplitz, (d, l) = (A_ii, A_{i,i−1}): there a
  // form is accumulated through D = Σ (z_i − z_{i−1})² and Q = Σ z_i², since
  //
  //     Σ_{i=a}^{b} (d z_i² + 2l z_{i−1} z_i) = −l D + (d + 2l) Q − l z_b² + l z_{a−1}²
  //
  // (expand −l (z_i − z_{i−1})² and telescope). For S, d + 2l = 0: the stiffness forms are sums of
  // squared differences, free of the cancellation of Σ z_i² against Σ z_{i−1} z_i (relative error
  // O(ε) instead of O(ε N²): the energy of Crank–Nicolson stays constant to round-off).
  double k_d = 0, k_q = 0, p_d = 0, p_q = 0, q_d = 0, q_q = 0;
  // The values entering the forms: as they are, or times σ_u and σ_v when the simulation scales its
  // energy (schemes.cpp: Scale of the energy); uf_prev is the previous scaled displacement (un_prev
  // itself serves the solve). With `scaled` false the code is the unscaled one.
  const double sigma_u = std::ldexp(1.0, -sim.displacement_exponent_);
  const double sigma_v = std::ldexp(1.0, -sim.velocity_exponent_);
  double uf_prev = 0;
  const auto emit = [&](const Row& r, Index i, double un, auto toeplitz) {
    constexpr bool sums = decltype(toeplitz)::value;
    const double uo = u[i];
    y[i] = un;
    if constexpr (three_level) {
      const double x_raw = rate * (un - uo), p_raw = un + uo, q_raw = un - uo;
      x_out[i] = x_raw;
      const double x = scaled ? sigma_v * x_raw : x_raw, p = scaled ? sigma_u * p_raw : p_raw,
                   q = scaled ? sigma_u * q_raw : q_raw;
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
      const double v_raw = rate * (un - uo) - memory * w[i];
      w_out[i] = v_raw;
      const double v = scaled ? sigma_v * v_raw : v_raw, uf = scaled ? sigma_u * un : un;
      const double uf_before = scaled ? uf_prev : un_prev;
      if constexpr (sums) {
        const double dv = v - v_prev, du = uf - uf_before;
        k_d += dv * dv, k_q += v * v;
        p_d += du * du, p_q += uf * uf;
      } else {
        kinetic += r.md * v * v + r.ml2 * v_prev * v;
        potential += r.sd * uf * uf + r.sl2 * uf_before * uf;
      }
      v_prev = v;
      if constexpr (scaled) uf_prev = uf;
    }
    un_prev2 = un_prev, un_prev = un;
  };
  const std::false_type explicit_row;
  const std::true_type toeplitz_row;
  // Uⁿ⁺¹_i = (z_i − c_i z_{i−1}) + c_i c_{i−1} Uⁿ⁺¹_{i−2}, z_i = y_i/d_i, two chains again; z₀ = u₀ (c₀ = 0).
  const double* upward_pair = sim.solver_.upward_pair().data();
  const auto solve_up = [&](Index i) {
    const double z = inverse_pivot[i] * y[i];
    const double un = (z - upward[i] * z_prev) + upward_pair[i] * un_prev2;
    z_prev = z;
    return un;
  };
  // Node 0's value enters the energy and the velocity; the recurrence runs from recurrence_u0 (the same
  // number except for EC at a status change): z₀ for node 1, and Uⁿ⁺¹_{i−2} for node 2, set after node 1
  // (EC keeps row 1 among the explicit rows for this: minimum_head = 2).
  emit(r0, 0, contact.u0, explicit_row);
  z_prev = recurrence_u0;
  for (Index i = 1; i < std::min(head, n - 1); ++i) {
    emit(head_[static_cast<std::size_t>(i)], i, solve_up(i), explicit_row);
    if (i == 1) un_prev2 = recurrence_u0;
  }
  if (head < n - 1) {
    const Row r = interior_;
    // The values z_{a−1} at row head − 1 (the first of the kinetic, the potential and the second forms).
    const double ka = v_prev, pa = three_level ? p_prev : (scaled ? uf_prev : un_prev), qa = q_prev;
    for (Index i = head; i < n - 1; ++i) emit(r, i, solve_up(i), toeplitz_row);
    const double kb = v_prev, pb = three_level ? p_prev : (scaled ? uf_prev : un_prev), qb = q_prev;
    const auto form = [](double d, double l2, double sum_d, double sum_q, double za, double zb) {
      const double l = 0.5 * l2;
      return -l * sum_d + (d + l2) * sum_q - l * zb * zb + l * za * za;
    };
    kinetic += form(r.md, r.ml2, k_d, k_q, ka, kb);
    potential += form(r.sd, r.sl2, p_d, p_q, pa, pb);
    if constexpr (three_level) potential_q += form(r.sd, r.sl2, q_d, q_q, qa, qb);
  }
  emit(last_, n - 1, solve_up(n - 1), explicit_row);

  const auto back = [](double half, int exponent) { return scaled ? std::ldexp(half, 2 * exponent) : half; };
  if constexpr (three_level) {
    sim.energy_ = back(0.5 * kinetic, sim.velocity_exponent_) +
                  back(0.125 * (potential - (1 - 4 * sim.parameters_.beta) * potential_q), sim.displacement_exponent_);
    sim.u_.swap(sim.w_);      // W' = Uⁿ
    sim.u_.swap(sim.u_new_);  // U = Uⁿ⁺¹
  } else {
    sim.energy_ = back(0.5 * kinetic, sim.velocity_exponent_) + back(0.5 * potential, sim.displacement_exponent_);
    sim.u_.swap(sim.u_new_);
  }
  if constexpr (has_load) sim.f_now_.swap(sim.f_next_);
  return true;
}

}  // namespace mrm
