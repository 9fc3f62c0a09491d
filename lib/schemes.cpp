// The time schemes: problem.md §4, the paper's §3 (Crank–Nicolson, backward Euler, Paoli–Schatzman).
//
// The semi-discrete problem is M U'' + S U = −λ e₀ + F, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (5)), with M the
// consistent mass or a redistributed mass M^mod whose row and column 0 vanish (paper eq. (6)).
//
// One step of every scheme, written on all unknowns 0..N−1, is
//
//     A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀,     0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0,                         (★)
//
// with constant tridiagonal A, B₁, B₂, a scalar κ > 0, W = Vⁿ for the two-level schemes and
// W = Uⁿ⁻¹ for the three-level one, and g the obstacle (0, or −e u₀ⁿ⁻¹). (★) is solved by the
// closed-form contact step of contact.cpp: one sweep down, the contact decision at the contact
// node's pivot, one sweep up. The schemes differ only in their coefficients:
//
// Crank–Nicolson (trapezoidal rule for U' = V, M V' = −SU − λe₀ + F). Eliminating
// Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ from M(Vⁿ⁺¹ − Vⁿ) = Δt/2 (−S(Uⁿ⁺¹ + Uⁿ) − (λⁿ⁺¹ + λⁿ)e₀ + Fⁿ⁺¹ + Fⁿ):
//
//     (M + θS) Uⁿ⁺¹ = (M − θS) Uⁿ + Δt M Vⁿ + θ(Fⁿ + Fⁿ⁺¹) − θλⁿe₀ − θλⁿ⁺¹e₀,    θ = Δt²/4.
//
// Backward Euler: Uⁿ⁺¹ = Uⁿ + Δt Vⁿ⁺¹, M(Vⁿ⁺¹ − Vⁿ) = Δt(−SUⁿ⁺¹ − λⁿ⁺¹e₀ + Fⁿ⁺¹):
//
//     (M + Δt²S) Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt² Fⁿ⁺¹ − Δt² λⁿ⁺¹ e₀,   Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt.
//
// Paoli–Schatzman (three levels, β ≥ 0, restitution e ∈ [0, 1]):
//
//     M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹)/Δt² + S(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Fⁿ − λⁿe₀,
//     0 ≤ (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ⊥ λⁿ ≤ 0,
//
// that is (M + βΔt²S) Uⁿ⁺¹ = (2M − (1−2β)Δt²S) Uⁿ − (M + βΔt²S) Uⁿ⁻¹ + Δt²Fⁿ − Δt²λⁿe₀ with the
// obstacle g = −e u₀ⁿ⁻¹.
//
// The massless contact row. With a redistributed mass, row 0 of the system has no inertia: it is
// the algebraic contact row S₀·U = F₀ − λ, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (6)), to hold at every time level.
// Crank–Nicolson's row 0 is then (S₀·Uⁿ⁺¹ − F₀ⁿ⁺¹ + λⁿ⁺¹) + (S₀·Uⁿ − F₀ⁿ + λⁿ) = 0 and backward Euler's
// is S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹: with the row holding at level n, both are the algebraic row at level n+1.
// This implementation writes it as such for every scheme ("algebraic" form): row 0 of A is S₀·,
// row 0 of B₁ and B₂ vanish, G₀ = F₀ⁿ⁺¹ and κ = 1 for that row, so the row holds at every level
// whatever round-off or initial data did before. Paoli–Schatzman applied literally ("literal" form)
// keeps its own row 0, Δt² S₀·(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Δt²(F₀ⁿ − λⁿ): the contact row then only
// holds in the β-average of three levels, and its defect dⁿ = S₀·Uⁿ − F₀ⁿ + λ obeys
// βdⁿ⁺¹ + (1−2β)dⁿ + βdⁿ⁻¹ = 0 while the contact is inactive: for β = ¼, dⁿ = (p + qn)(−1)ⁿ, a
// sawtooth that may grow (problem.md §4). The experiments show whether it does.
//
// The discrete energies. Two-level schemes: Eⁿ = ½ VⁿᵀMVⁿ + ½ UⁿᵀSUⁿ; Crank–Nicolson conserves it
// exactly while the contact status does not change, backward Euler dissipates it. Paoli–Schatzman:
// the quantity its linear part conserves is, with D = (Uⁿ⁺¹ − Uⁿ)/Δt,
//
//     Eⁿ⁺½ = ½ DᵀMD + ½ (β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ),
//
// (for β = ¼ the familiar ½DᵀMD + ½ ŪᵀSŪ with Ū = (Uⁿ⁺¹ + Uⁿ)/2), attached to the instant t_{n+½}.
#include "schemes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <stdexcept>

#include <doctest/doctest.h>

#include "exact_solution.hpp"

namespace mrm {

std::string to_string(Scheme s) {
  switch (s) {
    case Scheme::crank_nicolson: return "cn";
    case Scheme::backward_euler: return "be";
    case Scheme::paoli_schatzman: return "ps";
  }
  return "?";
}
std::string to_string(ContactRow r) { return r == ContactRow::algebraic ? "algebraic" : "literal"; }
std::string to_string(InitialContactNode i) { return i == InitialContactNode::consistent ? "consistent" : "interpolant"; }

Scheme scheme_by_name(const std::string& name) {
  if (name == "cn") return Scheme::crank_nicolson;
  if (name == "be") return Scheme::backward_euler;
  if (name == "ps") return Scheme::paoli_schatzman;
  throw std::invalid_argument("unknown scheme \"" + name + "\" (allowed: cn, be, ps)");
}
ContactRow contact_row_by_name(const std::string& name) {
  if (name == "algebraic") return ContactRow::algebraic;
  if (name == "literal") return ContactRow::literal;
  throw std::invalid_argument("unknown contact-row form \"" + name + "\" (allowed: algebraic, literal)");
}
InitialContactNode initial_contact_node_by_name(const std::string& name) {
  if (name == "consistent") return InitialContactNode::consistent;
  if (name == "interpolant") return InitialContactNode::interpolant;
  throw std::invalid_argument("unknown initial contact-node value \"" + name + "\" (allowed: consistent, interpolant)");
}

Problem benchmark_problem(double length, double amplitude) {
  Problem p;
  p.length = length;
  p.initial_displacement = [length, amplitude](double x) { return amplitude * (length - x); };
  p.initial_velocity = [](double) { return 0.0; };
  return p;
}

Index steps_to_reach(double final_time, double dt) {
  if (!(std::isfinite(final_time) && final_time > 0)) throw std::invalid_argument("the final time must be positive and finite");
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("the time step must be positive and finite");
  const double ratio = final_time / dt;
  if (ratio > 1e12) throw std::invalid_argument("the final time needs more than 1e12 time steps");
  return static_cast<Index>(std::ceil(ratio - 1e-9));
}

namespace {

void validate(const SchemeParameters& p, double dt) {
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("the time step dt must be positive and finite");
  if (!(std::isfinite(p.beta) && p.beta >= 0)) throw std::invalid_argument("beta must be a finite number >= 0");
  if (!(p.restitution >= 0 && p.restitution <= 1))
    throw std::invalid_argument("the restitution coefficient e must lie in [0, 1]");
}

void zero_row0(Tridiagonal& a) {
  a.diag[0] = 0.0;
  a.upper[0] = 0.0;
}

}  // namespace

// Setting up (★) for the chosen scheme: the coefficients of the comment at the top of this file.
BarSimulation::BarSimulation(const Problem& problem, const UniformMesh& mesh, const MassRedistribution& mass,
                             const SchemeParameters& parameters, double dt, InitialContactNode initial)
    : problem_(problem), mesh_(mesh), parameters_((validate(parameters, dt), parameters)), dt_(dt),
      mass_(modified_mass(mesh, mass)), stiffness_(p1_stiffness(mesh)) {
  if (!problem.initial_displacement)
    throw std::invalid_argument("problem: no initial displacement u0 (allowed: a function of x)");
  if (problem.length != mesh.length)
    throw std::invalid_argument("problem: the bar has L = " + std::to_string(problem.length) + ", the mesh L = " +
                                std::to_string(mesh.length) + " (allowed: the same L)");
  massless_ = contact_node_is_massless(mass_);
  three_level_ = parameters.scheme == Scheme::paoli_schatzman;
  if (three_level_ && parameters.contact_row == ContactRow::algebraic && !massless_)
    throw std::invalid_argument("the algebraic contact row needs a massless contact node (mass mod1, mod2 or mod3); "
                                "use the literal Paoli–Schatzman form with the consistent mass");
  algebraic_row_ = massless_ && (!three_level_ || parameters.contact_row == ContactRow::algebraic);
  if (massless_ && three_level_ && !algebraic_row_ && parameters.beta == 0.0)
    throw std::invalid_argument("the literal Paoli–Schatzman form with beta = 0 and a massless contact node is "
                                "singular (row 0 of the step matrix vanishes): use beta > 0 or the algebraic form");

  const double dt2 = dt * dt;
  const Tridiagonal& m = mass_;
  const Tridiagonal& s = stiffness_;
  Tridiagonal a, b1_, b2_;
  lambda_in_rhs_ = 0.0;
  switch (parameters.scheme) {
    case Scheme::crank_nicolson: {
      const double theta = dt2 / 4;
      a = m.plus(theta, s);
      b1_ = m.plus(-theta, s);
      b2_ = m.scaled(dt);
      kappa_ = theta;
      load_now_ = theta;
      load_next_ = theta;
      lambda_in_rhs_ = theta;
      velocity_rate_ = 2 / dt, velocity_memory_ = 1;
      break;
    }
    case Scheme::backward_euler: {
      a = m.plus(dt2, s);
      b1_ = m;
      b2_ = m.scaled(dt);
      kappa_ = dt2;
      load_now_ = 0;
      load_next_ = dt2;
      velocity_rate_ = 1 / dt, velocity_memory_ = 0;
      break;
    }
    case Scheme::paoli_schatzman: {
      const double beta = parameters.beta;
      a = m.plus(beta * dt2, s);
      b1_ = m.scaled(2.0).plus(-(1 - 2 * beta) * dt2, s);
      b2_ = m.scaled(-1.0).plus(-beta * dt2, s);
      kappa_ = dt2;
      load_now_ = dt2;
      load_next_ = 0;
      velocity_rate_ = 1 / dt, velocity_memory_ = 0;  // X = (Uⁿ⁺¹ − Uⁿ)/Δt; W' = Uⁿ by a swap
      break;
    }
  }
  if (algebraic_row_) {
    a.diag[0] = s.diag[0];
    a.upper[0] = s.upper[0];
    zero_row0(b1_);
    zero_row0(b2_);
    lambda_in_rhs_ = 0.0;
  }
  solver_ = ContactSolver(a);

  // The rows of B₁, B₂, M and S as the fused step reads them. On a uniform mesh every row away from
  // the contact node is the same (the matrices are Toeplitz there) except the last, whose upper
  // neighbour is the clamped node: the rows from `head` to n−2 share one Row. `head` is the first
  // row from which on all rows up to n−2 are equal, compared exactly, so any weights are handled
  // (Mod 1 and Mod 2 give head = 2, Mod 3 and the consistent mass 2 and 1; a weight that varies
  // along the bar gives head = n−1, every row explicit).
  const Index rows = mesh.unknowns();
  const auto row = [&](Index i) {
    const bool last = i + 1 == rows;
    return Row{b1_.lower[i], b1_.diag[i], last ? 0.0 : b1_.upper[i], b2_.lower[i], b2_.diag[i],
               last ? 0.0 : b2_.upper[i], m.diag[i], 2 * m.lower[i], s.diag[i], 2 * s.lower[i]};
  };
  const auto same = [](const Row& x, const Row& y) {
    return x.b1l == y.b1l && x.b1d == y.b1d && x.b1u == y.b1u && x.b2l == y.b2l && x.b2d == y.b2d &&
           x.b2u == y.b2u && x.md == y.md && x.ml2 == y.ml2 && x.sd == y.sd && x.sl2 == y.sl2;
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
  }
  head_.clear();
  for (Index i = 0; i < head; ++i) head_.push_back(row(i));

  // The initial level. Uⁿ and V⁰ are the nodal interpolants of u⁰ and v⁰; a massless contact node
  // takes the value its algebraic row gives (problem.md §4: otherwise u₀ jumps in the first step and
  // the initial energy is off), unless the interpolant is asked for.
  const Index n = mesh.unknowns();
  u_.resize(n);
  u_new_.setZero(n);
  x_.resize(n);
  if (problem.load) {
    f_now_.setZero(n);
    f_next_.setZero(n);
  }
  for (Index i = 0; i < n; ++i) {
    u_[i] = problem.initial_displacement(mesh.x(i));
    x_[i] = problem.initial_velocity ? problem.initial_velocity(mesh.x(i)) : 0.0;
  }
  if (!(u_.allFinite() && x_.allFinite()))
    throw std::invalid_argument("problem: the initial data u0, v0 are not finite at every node (allowed: finite values)");
  load_at(0.0, f_now_);
  if (massless_) {
    const CondensedContact c = condense_contact_node(u_[1], mesh.h(), problem.load ? f_now_[0] : 0.0);
    if (initial == InitialContactNode::consistent) u_[0] = c.u0;
    lambda_ = c.multiplier;
  } else {
    lambda_ = 0.0;  // an inertial contact node starts without contact force
  }
  has_lambda_ = true;
  choose_energy_scale();
  energy_ = energy_two_level();

  // W = V⁰ for the two-level schemes. The three-level scheme is started by one Crank–Nicolson step
  // (with the same mass and contact row): then W = U⁰ and Paoli–Schatzman with β = ¼ and the algebraic
  // row reproduces Crank–Nicolson exactly when f = 0 (the elimination of V from Crank–Nicolson gives
  // the three-level formula with β = ¼ on every free row; checked below).
  // The two-level schemes' velocity is W itself: X is not kept.
  w_ = x_;
  if (three_level_) {
    SchemeParameters start = parameters;
    start.scheme = Scheme::crank_nicolson;
    start_ = std::make_unique<BarSimulation>(problem, mesh, mass, start, dt, initial);
  } else {
    x_ = Eigen::VectorXd();
  }
}

void BarSimulation::load_at(double t, Eigen::VectorXd& f) const {
  if (!problem_.load) return;
  p1_load(mesh_, [&](double x) { return problem_.load(x, t); }, f);
}

// Scale of the energy. The energy's quadratic forms square the nodal values: on the benchmark,
// u ~ aL and v ~ a, so that the squares reach (aL)² ~ 1e400 or fall to (aL/N)² ~ 1e-414 over the
// lengths and amplitudes that bar1d accepts ([1e-100, 1e100] each), although the energy itself,
// a²L/2, is a representable number. The forms are therefore taken on scaled values σ_u U and σ_v V,
// with σ_u = 2^−e_u and σ_v = 2^−e_v powers of two chosen from the data at t = 0: e_u is the binary
// exponent of the size of the displacements, the largest of |u⁰_i|, L |v⁰_i| and L²|f_i|/h (the
// displacement that the initial velocity or the load produce over the time L a wave takes to cross
// the bar; wave speed 1), and e_v = e_u − e_L, e_L that of L. Each half of the energy is then
// brought back by an exact ldexp. Scaling by a power of two is exact wherever nothing over- or
// underflows, so the scaled forms give the same doubles as the unscaled ones whenever both are
// representable: the choice affects only the cost (two or three multiplications per node). It is made
// only when an exponent (e_u, e_v, or that of h) exceeds 200 in magnitude; below that, with at most
// 2^30 nodes, every square and every form stays between 2^−700 and 2^700 (ratios of u between nodes
// of order N, of v of order 1 over a run whose energy does not grow by 2^100).
void BarSimulation::choose_energy_scale() {
  const int length_exponent = std::ilogb(mesh_.length);
  const int step_exponent = std::ilogb(mesh_.h());
  bool any = false;
  int exponent = 0;
  const auto consider = [&](const Eigen::VectorXd& values, int shift) {
    if (values.size() == 0) return;
    const double largest = values.cwiseAbs().maxCoeff();
    if (!(largest > 0) || !std::isfinite(largest)) return;
    const int e = std::ilogb(largest) + shift;
    exponent = any ? std::max(exponent, e) : e;
    any = true;
  };
  consider(u_, 0);
  consider(x_, length_exponent);
  if (problem_.load) consider(f_now_, 2 * length_exponent - step_exponent);
  displacement_exponent_ = exponent;
  velocity_exponent_ = exponent - length_exponent;
  constexpr int band = 200;
  scaled_ = std::abs(displacement_exponent_) > band || std::abs(velocity_exponent_) > band ||
            std::abs(step_exponent) > band;
}

double BarSimulation::energy_two_level() const {
  if (!scaled_) return 0.5 * mass_.bilinear(x_, x_) + 0.5 * stiffness_.bilinear(u_, u_);
  const Eigen::VectorXd v = std::ldexp(1.0, -velocity_exponent_) * x_;
  const Eigen::VectorXd u = std::ldexp(1.0, -displacement_exponent_) * u_;
  return std::ldexp(0.5 * mass_.bilinear(v, v), 2 * velocity_exponent_) +
         std::ldexp(0.5 * stiffness_.bilinear(u, u), 2 * displacement_exponent_);
}

// One step of (★), fused into the two sweeps of the solve, with no allocation and no refactorisation:
//
// - the sweep down (i = n−1 … 1) forms b_i = (B₁Uⁿ + B₂W + G)_i from the neighbours of node i and
//   eliminates at once, y_i = b_i − ε_i y_{i+1} (ε the elimination factors of contact.cpp);
// - the contact is decided at node 0's pivot d₀ = 1/(A⁻¹)₀₀, the Schur complement of A onto the
//   contact node (contact.cpp: this is what problem.md's w = θA⁻¹C does, for the price of a scalar);
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
void BarSimulation::fused_step() {
  const Index n = mesh_.unknowns();
  const Index head = static_cast<Index>(head_.size());
  const double* u = u_.data();
  const double* w = w_.data();
  double* y = u_new_.data();
  const double* elimination = solver_.elimination().data();
  const double* inverse_pivot = solver_.inverse_pivot().data();
  const double* upward = solver_.upward().data();
  const double* f_now = has_load ? f_now_.data() : nullptr;
  const double* f_next = has_load ? f_next_.data() : nullptr;
  const double g_now = load_now_, g_next = load_next_;

  // Sweep down, as two chains (contact.hpp): y_i = (b_i − ε_i b_{i+1}) + ε_iε_{i+1} y_{i+2}, from row
  // n−1 (its upper neighbour is the clamped node; with b_n = y_n = y_{n+1} = 0 the formula gives
  // y_{n−1} = b_{n−1}, and ε_{n−1} = 0 gives y_{n−2} = b_{n−2} − ε_{n−2} y_{n−1}), through the interior
  // rows n−2 … head with their common coefficients and the head rows head−1 … 1 with their own.
  const double* elimination_pair = solver_.elimination_pair().data();
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

  // Row 0 and the contact decision.
  const Row& r0 = head_[0];
  double b0, kappa = kappa_;
  if (algebraic_row_) {
    b0 = has_load ? f_next[0] : 0.0;
    kappa = 1.0;
  } else {
    b0 = r0.b1d * u[0] + r0.b1u * u[1] + r0.b2d * w[0] + r0.b2u * w[1] - lambda_in_rhs_ * lambda_;
    if constexpr (has_load) b0 += g_now * f_now[0] + g_next * f_next[0];
  }
  const double obstacle = three_level ? -parameters_.restitution * w[0] : 0.0;
  const ContactStep contact = solver_.resolve_contact(b0 - elimination[0] * y_next, kappa, obstacle);
  lambda_ = contact.multiplier;

  // Sweep up. Two-level: V' = rate (U' − U) − memory V, written over W, kinetic form V'ᵀMV',
  // potential U'ᵀSU'. Three-level: X = (U' − U)/Δt, forms XᵀMX, PᵀSP, QᵀSQ; W' = Uⁿ by a swap below.
  double* w_out = w_.data();
  double* x_out = x_.data();
  const double rate = velocity_rate_, memory = velocity_memory_;
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
  // The values entering the forms: as they are, or times σ_u, σ_v (see Scale of the energy above).
  // uf_prev is the previous scaled displacement (un_prev itself serves the solve).
  const double sigma_u = std::ldexp(1.0, -displacement_exponent_), sigma_v = std::ldexp(1.0, -velocity_exponent_);
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
  const double* upward_pair = solver_.upward_pair().data();
  const auto solve_up = [&](Index i) {
    const double z = inverse_pivot[i] * y[i];
    const double un = (z - upward[i] * z_prev) + upward_pair[i] * un_prev2;
    z_prev = z;
    return un;
  };
  emit(r0, 0, contact.u0, explicit_row);
  z_prev = contact.u0;
  for (Index i = 1; i < std::min(head, n - 1); ++i)
    emit(head_[static_cast<std::size_t>(i)], i, solve_up(i), explicit_row);
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

  const auto back = [&](double half, int exponent) { return scaled ? std::ldexp(half, 2 * exponent) : half; };
  if constexpr (three_level) {
    energy_ = back(0.5 * kinetic, velocity_exponent_) +
              back(0.125 * (potential - (1 - 4 * parameters_.beta) * potential_q), displacement_exponent_);
    u_.swap(w_);      // W' = Uⁿ
    u_.swap(u_new_);  // U = Uⁿ⁺¹
  } else {
    energy_ = back(0.5 * kinetic, velocity_exponent_) + back(0.5 * potential, displacement_exponent_);
    u_.swap(u_new_);
  }
  if constexpr (has_load) f_now_.swap(f_next_);
}

void BarSimulation::step() {
  if (start_) {
    start_->step();
    w_.swap(u_);  // W = U⁰
    u_ = start_->u_;
    x_ = start_->w_;  // the starter's velocity V¹
    if (problem_.load) f_now_ = start_->f_now_;
    lambda_ = start_->lambda_;
    lambda_time_ = start_->lambda_time_;
    has_lambda_ = algebraic_row_;  // the literal form's λ¹ comes with its first own step
    energy_ = start_->energy_;
    energy_time_ = start_->energy_time_;
    start_.reset();
    ++level_;
    return;
  }
  const double t_now = static_cast<double>(level_) * dt_;
  const double t_next = static_cast<double>(level_ + 1) * dt_;
  const bool has_load = static_cast<bool>(problem_.load);
  if (has_load) load_at(t_next, f_next_);
  if (three_level_) {
    if (has_load) scaled_ ? fused_step<true, true, true>() : fused_step<true, true, false>();
    else scaled_ ? fused_step<true, false, true>() : fused_step<true, false, false>();
  } else {
    if (has_load) scaled_ ? fused_step<false, true, true>() : fused_step<false, true, false>();
    else scaled_ ? fused_step<false, false, true>() : fused_step<false, false, false>();
  }

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

Sample BarSimulation::sample() const {
  const double t = time();
  const double velocity_time = (three_level_ && level_ > 1) ? t - 0.5 * dt_ : t;
  const Eigen::VectorXd* velocity = three_level_ ? &x_ : &w_;  // the two-level velocity is W
  return {level_, t, &u_, velocity_time, velocity, has_lambda_, level_ == 0 ? 0.0 : lambda_time_, lambda_,
          level_ == 0 ? 0.0 : energy_time_, energy_};
}

void run(BarSimulation& simulation, Index steps, const std::function<void(const Sample&)>& observe) {
  if (observe) observe(simulation.sample());
  for (Index k = 0; k < steps; ++k) {
    simulation.step();
    if (observe) observe(simulation.sample());
  }
}

}  // namespace mrm

// ---------------------------------------------------------------------------------------------------
// Checks of the schemes' energy behaviour (problem.md §4) and of the Paoli–Schatzman identity.

namespace mrm {
namespace {

[[maybe_unused]] std::vector<double> energy_history(const MassRedistribution& mass, const SchemeParameters& p, Index elements,
                                   double courant, double final_time, double length = 1.0, double amplitude = 0.5) {
  const UniformMesh mesh(length, elements);
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(length, amplitude), mesh, mass, p, dt);
  std::vector<double> energy;
  run(simulation, steps_to_reach(final_time, dt), [&](const Sample& s) { energy.push_back(s.energy); });
  return energy;
}

[[maybe_unused]] SchemeParameters with(Scheme scheme, ContactRow row = ContactRow::algebraic) {
  SchemeParameters p;
  p.scheme = scheme;
  p.contact_row = row;
  return p;
}

}  // namespace

TEST_CASE("Crank–Nicolson conserves the discrete energy to round-off while the contact status is unchanged") {
  // The benchmark's first free flight lasts until t = 1: no status change before t = 0.9.
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
    for (double courant : {0.5, 1.0, 3.0}) {
      const std::vector<double> e = energy_history(mass, with(Scheme::crank_nicolson), 40, courant, 0.9 - 0.075);
      CAPTURE(mass.name);
      CAPTURE(courant);
      // Round-off grows at most linearly with the number of steps k: |E_k − E_0| ≤ 1e-14 + k · 1e-15 (E ≈ 1/8).
      REQUIRE(e.size() > 2);
      for (std::size_t k = 0; k < e.size(); ++k) CHECK(std::abs(e[k] - e.front()) <= 1e-14 + k * 1e-15);
    }
  }
}

TEST_CASE("Paoli–Schatzman with beta = 1/4 conserves its energy while the contact status is unchanged") {
  for (ContactRow row : {ContactRow::algebraic, ContactRow::literal}) {
    // From level 2 on: levels 0 and 1 carry the two-level energy of the Crank–Nicolson start.
    const std::vector<double> e = energy_history(mod3(), with(Scheme::paoli_schatzman, row), 40, 0.5, 0.85);
    CAPTURE(to_string(row));
    REQUIRE(e.size() > 10);
    for (std::size_t k = 2; k < e.size(); ++k) CHECK(std::abs(e[k] - e[2]) <= 1e-14 + k * 1e-15);
  }
}

TEST_CASE("backward Euler never increases the discrete energy") {
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
    const std::vector<double> e = energy_history(mass, with(Scheme::backward_euler), 30, 0.5, 9.0);
    CAPTURE(mass.name);
    int increases = 0;
    for (std::size_t k = 1; k < e.size(); ++k) increases += e[k] > e[k - 1] * (1 + 1e-14);
    CHECK(increases == 0);
    CHECK(e.back() < 0.9 * e.front());  // and it does dissipate
  }
}

TEST_CASE("the discrete energy is right at the ends of the accepted lengths and amplitudes") {
  // Under x → Lx, t → Lt, u → aLu the benchmark with (L, a) is the one with (1, 1), and its energy is
  // a²L times that one. With L = 2^±332 and a = 2^±332 (≈ 8.7e99 and 1.1e-100, inside bar1d's
  // [1e-100, 1e100]) every rounding of the run is the same as with (1, 1) up to the power of two, so
  // the energies must be those of (1, 1) times a²L exactly; the squares of the unscaled forms would
  // overflow ((aL)² = 2^1328) or underflow ((aL/N)² ≈ 2^−1337). At the decimal ends 1e±100 the data
  // themselves are rounded differently (relative 1e-16 each, over a few hundred steps): the energy
  // divided by a²L must agree with the (1, 1) run to 1e-12 relative.
  struct Case {
    Scheme scheme;
    ContactRow row;
    const MassRedistribution* mass;
  };
  const MassRedistribution m3 = mod3(), m1 = mod1(), consistent = consistent_mass();
  for (const Case c : {Case{Scheme::crank_nicolson, ContactRow::algebraic, &m3},
                       Case{Scheme::backward_euler, ContactRow::algebraic, &m1},
                       Case{Scheme::paoli_schatzman, ContactRow::algebraic, &m3},
                       Case{Scheme::paoli_schatzman, ContactRow::literal, &consistent}}) {
    SchemeParameters p = with(c.scheme, c.row);
    const std::vector<double> base = energy_history(*c.mass, p, 12, 0.5, 6.0, 1.0, 1.0);
    for (const int length_exponent : {-332, 332})
      for (const int amplitude_exponent : {-332, 332}) {
        const double length = std::ldexp(1.0, length_exponent), amplitude = std::ldexp(1.0, amplitude_exponent);
        const std::vector<double> e = energy_history(*c.mass, p, 12, 0.5, 6.0 * length, length, amplitude);
        CAPTURE(to_string(c.scheme));
        CAPTURE(c.mass->name);
        CAPTURE(length_exponent);
        CAPTURE(amplitude_exponent);
        REQUIRE(e.size() == base.size());
        for (std::size_t k = 0; k < e.size(); ++k) {
          CAPTURE(k);
          CHECK(e[k] == std::ldexp(base[k], 2 * amplitude_exponent + length_exponent));
        }
      }
    for (const double length : {1e-100, 1e100})
      for (const double amplitude : {1e-100, 1e100}) {
        const std::vector<double> e = energy_history(*c.mass, p, 12, 0.5, 6.0 * length, length, amplitude);
        CAPTURE(to_string(c.scheme));
        CAPTURE(c.mass->name);
        CAPTURE(length);
        CAPTURE(amplitude);
        REQUIRE(e.size() == base.size());
        for (std::size_t k = 0; k < e.size(); ++k) {
          CAPTURE(k);
          const double scaled = e[k] / (amplitude * amplitude * length);
          CHECK(std::isfinite(scaled));
          CHECK(std::abs(scaled - base[k]) <= 1e-12 * base[k]);
        }
      }
  }
}

TEST_CASE("the massless contact node starts on its algebraic row: E_h(0) = (1 - h)/8") {
  const UniformMesh mesh(1.0, 20);
  const BarSimulation consistent(benchmark_problem(), mesh, mod3(), with(Scheme::crank_nicolson), 0.025);
  const BarSimulation interpolant(benchmark_problem(), mesh, mod3(), with(Scheme::crank_nicolson), 0.025,
                                  InitialContactNode::interpolant);
  CHECK(std::abs(consistent.sample().energy - (1 - mesh.h()) / 8) < 1e-15);
  CHECK(std::abs(interpolant.sample().energy - 0.125) < 1e-15);
  CHECK(std::abs((*consistent.sample().displacement)[0] - (1 - mesh.h()) / 2) < 1e-15);
}

TEST_CASE("Paoli–Schatzman (1/4, 0) with the algebraic contact row coincides with Crank–Nicolson") {
  const UniformMesh mesh(1.0, 32);
  const double dt = 0.5 * mesh.h();
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    BarSimulation cn(benchmark_problem(), mesh, mass, with(Scheme::crank_nicolson), dt);
    BarSimulation ps(benchmark_problem(), mesh, mass, with(Scheme::paoli_schatzman), dt);
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

// The fused step against the textbook one: the same scheme written as in the comment at the top of
// this file, with whole matrices (A, B₁, B₂ assembled as Tridiagonal), the right-hand side formed
// first, ContactSolver::solve, then the velocities and the energy from their definitions
// (Tridiagonal::bilinear). The cases cover every region of the fused loops: a load, the consistent
// mass, Mod 1–3, the mass spread over 3 nodes, and a weight that varies along the bar (no Toeplitz
// interior at all), with restitution for Paoli–Schatzman.
namespace {

struct TextbookScheme {
  Tridiagonal m, s, a, b1, b2;
  ContactSolver solver;
  double dt, kappa, g_now, g_next, lambda_rhs, beta, restitution;
  bool algebraic, three_level;

  TextbookScheme(const BarSimulation& sim, Scheme scheme) {
    const SchemeParameters& p = sim.parameters();
    m = sim.mass(), s = sim.stiffness(), dt = sim.dt(), beta = p.beta, restitution = p.restitution;
    three_level = scheme == Scheme::paoli_schatzman;
    algebraic = sim.massless_contact_node() && (!three_level || p.contact_row == ContactRow::algebraic);
    const double dt2 = dt * dt, theta = dt2 / 4;
    lambda_rhs = 0;
    if (scheme == Scheme::crank_nicolson) {
      a = m.plus(theta, s), b1 = m.plus(-theta, s), b2 = m.scaled(dt);
      kappa = theta, g_now = theta, g_next = theta, lambda_rhs = theta;
    } else if (scheme == Scheme::backward_euler) {
      a = m.plus(dt2, s), b1 = m, b2 = m.scaled(dt);
      kappa = dt2, g_now = 0, g_next = dt2;
    } else {
      a = m.plus(beta * dt2, s), b1 = m.scaled(2).plus(-(1 - 2 * beta) * dt2, s), b2 = m.plus(beta * dt2, s).scaled(-1);
      kappa = dt2, g_now = dt2, g_next = 0;
    }
    if (algebraic) {
      a.diag[0] = s.diag[0], a.upper[0] = s.upper[0];
      b1.diag[0] = b1.upper[0] = b2.diag[0] = b2.upper[0] = 0;
      kappa = 1, lambda_rhs = 0;
    }
    solver = ContactSolver(a);
  }

  // One step from (U, W, λ) with the loads F, F': returns U', overwrites W with W', X with the
  // velocity, λ with λ', and gives the energy.
  Eigen::VectorXd step(const Eigen::VectorXd& u, Eigen::VectorXd& w, Eigen::VectorXd& x, double& lambda,
                       const Eigen::VectorXd& f, const Eigen::VectorXd& f_next, double& energy) const {
    Eigen::VectorXd b = b1 * u + b2 * w + g_now * f + g_next * f_next;
    b[0] -= lambda_rhs * lambda;
    if (algebraic) b[0] = f_next[0];
    Eigen::VectorXd u_next(u.size());
    lambda = solver.solve(b.data(), u_next.data(), kappa, three_level ? -restitution * w[0] : 0.0).multiplier;
    if (three_level) {
      x = (u_next - u) / dt;
      const double potential =
          beta * s.bilinear(u_next, u_next) + (1 - 2 * beta) * s.bilinear(u_next, u) + beta * s.bilinear(u, u);
      energy = 0.5 * m.bilinear(x, x) + 0.5 * potential;
      w = u;
    } else {
      const bool cn = lambda_rhs > 0 || g_now > 0;
      w = cn ? Eigen::VectorXd(2 * (u_next - u) / dt - w) : Eigen::VectorXd((u_next - u) / dt);
      x = w;
      energy = 0.5 * m.bilinear(w, w) + 0.5 * s.bilinear(u_next, u_next);
    }
    return u_next;
  }
};

[[maybe_unused]] MassRedistribution varying_weight() {
  return {"varying", "a weight that varies along the bar", [](Index i, Index j, const UniformMesh& mesh) {
            if (i == 0 || j == 0) return 0.0;
            return 1.0 + 0.3 * static_cast<double>(i + j) / static_cast<double>(mesh.elements);
          }};
}

}  // namespace

TEST_CASE("the fused step computes the textbook step of every scheme, with and without a load") {
  struct Case {
    Scheme scheme;
    ContactRow row;
    MassRedistribution mass;
    double restitution;
  };
  const std::vector<Case> cases = {
      {Scheme::crank_nicolson, ContactRow::algebraic, mod3(), 0},
      {Scheme::crank_nicolson, ContactRow::algebraic, mod2(), 0},
      {Scheme::crank_nicolson, ContactRow::literal, consistent_mass(), 0},
      {Scheme::backward_euler, ContactRow::algebraic, mod1(), 0},
      {Scheme::backward_euler, ContactRow::algebraic, spread_over_first_nodes(3), 0},
      {Scheme::backward_euler, ContactRow::literal, consistent_mass(), 0},
      {Scheme::paoli_schatzman, ContactRow::algebraic, mod3(), 0},
      {Scheme::paoli_schatzman, ContactRow::algebraic, varying_weight(), 0},
      {Scheme::paoli_schatzman, ContactRow::literal, mod2(), 0.5},
      {Scheme::paoli_schatzman, ContactRow::literal, consistent_mass(), 0.3},
      {Scheme::crank_nicolson, ContactRow::algebraic, varying_weight(), 0},
  };
  for (const bool loaded : {false, true}) {
    for (const Case& c : cases) {
      Problem problem = benchmark_problem();
      if (loaded) problem.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
      const UniformMesh mesh(1.0, 12);
      SchemeParameters p = with(c.scheme, c.row);
      p.beta = c.scheme == Scheme::paoli_schatzman ? 0.3 : 0.25;
      p.restitution = c.restitution;
      const double dt = (c.restitution > 0 || c.mass.name == "mod2" ? 4.0 : 0.7) * mesh.h();  // small and large Δt/h
      BarSimulation fused(problem, mesh, c.mass, p, dt);
      const TextbookScheme textbook(fused, c.scheme);
      const TextbookScheme start(fused, Scheme::crank_nicolson);
      const auto load = [&](double t) {
        return problem.load ? p1_load(mesh, [&](double x) { return problem.load(x, t); })
                            : Eigen::VectorXd(Eigen::VectorXd::Zero(mesh.unknowns()));
      };
      Eigen::VectorXd u = *fused.sample().displacement, w = *fused.sample().velocity, x = w;
      double lambda = fused.sample().multiplier, energy = 0;
      CAPTURE(to_string(c.scheme));
      CAPTURE(c.mass.name);
      CAPTURE(loaded);
      int contacts = 0;
      for (Index k = 0; k < 90; ++k) {
        const double t = static_cast<double>(k) * dt;
        const Eigen::VectorXd u_old = u;
        const bool starting = k == 0 && c.scheme == Scheme::paoli_schatzman;
        u = (starting ? start : textbook).step(u, w, x, lambda, load(t), load(t + dt), energy);
        if (starting) w = u_old;  // W = U⁰ after the Crank–Nicolson start
        fused.step();
        const Sample sample = fused.sample();
        CAPTURE(k);
        // The two computations round differently (the fused one runs its sweeps as two chains, sums
        // its energy forms differently); the schemes neither damp nor amplify such perturbations
        // much, so their difference may accumulate with the number of steps: the bounds grow like k.
        // Velocities are differences of U divided by Δt: their round-off is ~1/Δt times that of U.
        const double steps = static_cast<double>(k + 1);
        const double scale = 1 + u.cwiseAbs().maxCoeff();
        REQUIRE((*sample.displacement - u).cwiseAbs().maxCoeff() < 1e-13 * steps * scale);
        REQUIRE((*sample.velocity - x).cwiseAbs().maxCoeff() < 1e-13 * steps * scale / dt);
        if (sample.has_multiplier) CHECK(std::abs(sample.multiplier - lambda) < 1e-13 * steps * scale / dt);
        CHECK(std::abs(sample.energy - energy) < 1e-13 * steps * (1 + std::abs(energy)) / dt);
        contacts += lambda < 0;
      }
      CHECK(contacts > 0);  // the runs do reach the obstacle
    }
  }
}

TEST_CASE("bad scheme parameters are rejected with a message naming them") {
  const UniformMesh mesh(1.0, 10);
  SchemeParameters p = with(Scheme::paoli_schatzman);
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
  CHECK_THROWS_WITH_AS(scheme_by_name("rk4"), doctest::Contains("allowed: cn, be, ps"), std::invalid_argument);
  p = with(Scheme::crank_nicolson);
  for (double restitution : {-0.5, std::nan("")}) {
    p.restitution = restitution;
    CAPTURE(restitution);
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, 0.1), doctest::Contains("restitution"),
                         std::invalid_argument);
  }
  p.restitution = 0;
  for (double dt : {-0.1, std::nan(""), HUGE_VAL}) {
    CAPTURE(dt);
    CHECK_THROWS_WITH_AS(BarSimulation(benchmark_problem(), mesh, mod3(), p, dt), doctest::Contains("dt"),
                         std::invalid_argument);
  }
}

TEST_CASE("a problem without initial data, with non-finite data or on another bar is rejected") {
  const UniformMesh mesh(1.0, 10);
  const SchemeParameters p = with(Scheme::crank_nicolson);
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
  BarSimulation simulation(problem, mesh, mod3(), p, 0.1);
  CHECK_THROWS_WITH_AS(simulation.step(), doctest::Contains("p1_load"), std::invalid_argument);
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
