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

#include <cmath>
#include <memory>
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
  Tridiagonal a;
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
      w_new_[0] = 2 / dt, w_new_[1] = -2 / dt, w_new_[2] = -1;
      break;
    }
    case Scheme::backward_euler: {
      a = m.plus(dt2, s);
      b1_ = m;
      b2_ = m.scaled(dt);
      kappa_ = dt2;
      load_now_ = 0;
      load_next_ = dt2;
      w_new_[0] = 1 / dt, w_new_[1] = -1 / dt, w_new_[2] = 0;
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
      w_new_[0] = 0, w_new_[1] = 1, w_new_[2] = 0;
      break;
    }
  }
  if (three_level_) {
    x_new_[0] = 1 / dt, x_new_[1] = -1 / dt, x_new_[2] = 0;
    sigma_[0] = parameters.beta, sigma_[1] = 1 - 2 * parameters.beta, sigma_[2] = parameters.beta;
  } else {
    for (int k = 0; k < 3; ++k) x_new_[k] = w_new_[k];
    sigma_[0] = 1, sigma_[1] = 0, sigma_[2] = 0;
  }
  if (algebraic_row_) {
    a.diag[0] = s.diag[0];
    a.upper[0] = s.upper[0];
    zero_row0(b1_);
    zero_row0(b2_);
    lambda_in_rhs_ = 0.0;
  }
  solver_ = ContactSolver(a);

  // The initial level. Uⁿ and V⁰ are the nodal interpolants of u⁰ and v⁰; a massless contact node
  // takes the value its algebraic row gives (problem.md §4: otherwise u₀ jumps in the first step and
  // the initial energy is off), unless the interpolant is asked for.
  const Index n = mesh.unknowns();
  u_.resize(n);
  u_new_.setZero(n);
  x_.resize(n);
  f_now_.setZero(n);
  f_next_.setZero(n);
  for (Index i = 0; i < n; ++i) {
    u_[i] = problem.initial_displacement(mesh.x(i));
    x_[i] = problem.initial_velocity ? problem.initial_velocity(mesh.x(i)) : 0.0;
  }
  if (!(u_.allFinite() && x_.allFinite()))
    throw std::invalid_argument("problem: the initial data u0, v0 are not finite at every node (allowed: finite values)");
  load_at(0.0, f_now_);
  if (massless_) {
    const CondensedContact c = condense_contact_node(u_[1], mesh.h(), f_now_[0]);
    if (initial == InitialContactNode::consistent) u_[0] = c.u0;
    lambda_ = c.multiplier;
  } else {
    lambda_ = 0.0;  // an inertial contact node starts without contact force
  }
  has_lambda_ = true;
  energy_ = energy_two_level();

  // W = V⁰ for the two-level schemes. The three-level scheme is started by one Crank–Nicolson step
  // (with the same mass and contact row): then W = U⁰ and Paoli–Schatzman with β = ¼ and the algebraic
  // row reproduces Crank–Nicolson exactly when f = 0 (the elimination of V from Crank–Nicolson gives
  // the three-level formula with β = ¼ on every free row; checked below).
  w_ = x_;
  if (three_level_) {
    SchemeParameters start = parameters;
    start.scheme = Scheme::crank_nicolson;
    start_ = std::make_unique<BarSimulation>(problem, mesh, mass, start, dt, initial);
  }
}

void BarSimulation::load_at(double t, Eigen::VectorXd& f) const {
  if (!problem_.load) return;
  f = p1_load(mesh_, [&](double x) { return problem_.load(x, t); });
}

double BarSimulation::energy_two_level() const {
  return 0.5 * mass_.bilinear(x_, x_) + 0.5 * stiffness_.bilinear(u_, u_);
}

// One step of (★), fused: the sweep down forms the right-hand side b = B₁Uⁿ + B₂W + G on the fly and
// eliminates; the contact is decided at node 0; the sweep up gives Uⁿ⁺¹, the new W, the velocity X
// and the energy, all in the same pass. No allocation, no refactorisation.
void BarSimulation::step() {
  if (start_) {
    start_->step();
    w_.swap(u_);  // W = U⁰
    u_ = start_->u_;
    x_ = start_->x_;
    f_now_ = start_->f_now_;
    lambda_ = start_->lambda_;
    lambda_time_ = start_->lambda_time_;
    has_lambda_ = algebraic_row_;  // the literal form's λ¹ comes with its first own step
    energy_ = start_->energy_;
    energy_time_ = start_->energy_time_;
    start_.reset();
    ++level_;
    return;
  }
  const Index n = mesh_.unknowns();
  const double t_next = static_cast<double>(level_ + 1) * dt_;
  if (problem_.load) load_at(t_next, f_next_);

  const double* u = u_.data();
  const double* w = w_.data();
  double* y = u_new_.data();
  const double *b1l = b1_.lower.data(), *b1d = b1_.diag.data(), *b1u = b1_.upper.data();
  const double *b2l = b2_.lower.data(), *b2d = b2_.diag.data(), *b2u = b2_.upper.data();
  const double* elim = solver_.elimination().data();
  const double *fn = f_now_.data(), *fnext = f_next_.data();
  const bool has_load = static_cast<bool>(problem_.load);

  // Sweep down, i = n−1 … 1 (row 0 is peeled off below).
  double y_next = 0.0;
  for (Index i = n - 1; i >= 1; --i) {
    double b = b1l[i] * u[i - 1] + b1d[i] * u[i] + b2l[i] * w[i - 1] + b2d[i] * w[i];
    if (i + 1 < n) b += b1u[i] * u[i + 1] + b2u[i] * w[i + 1];
    if (has_load) b += load_now_ * fn[i] + load_next_ * fnext[i];
    y_next = b - elim[i] * y_next;
    y[i] = y_next;
  }
  // Row 0 and the contact decision.
  double b0;
  double kappa = kappa_;
  if (algebraic_row_) {
    b0 = fnext[0];
    kappa = 1.0;
  } else {
    b0 = b1d[0] * u[0] + b1u[0] * u[1] + b2d[0] * w[0] + b2u[0] * w[1] + load_now_ * fn[0] + load_next_ * fnext[0] -
         lambda_in_rhs_ * lambda_;
  }
  const double obstacle = three_level_ ? -parameters_.restitution * w[0] : 0.0;
  const ContactStep contact = solver_.resolve_contact(b0 - elim[0] * y_next, kappa, obstacle);

  // Sweep up: Uⁿ⁺¹, W' = c·(Uⁿ⁺¹, Uⁿ, W), X = c·(Uⁿ⁺¹, Uⁿ, W) and the energy's quadratic forms.
  const double* inv_pivot = solver_.inverse_pivot().data();
  const double* lower = solver_.lower().data();
  const double *ml = mass_.lower.data(), *md = mass_.diag.data();
  const double *sl = stiffness_.lower.data(), *sd = stiffness_.diag.data();
  double* wout = w_.data();
  double* xout = x_.data();
  double kinetic = 0, s_new_new = 0, s_new_old = 0, s_old_old = 0;
  double un_prev = 0, u_prev = 0, x_prev = 0;
  for (Index i = 0; i < n; ++i) {
    const double un = (i == 0) ? contact.u0 : (y[i] - lower[i] * un_prev) * inv_pivot[i];
    const double uo = u[i];
    const double wo = w[i];
    const double x = x_new_[0] * un + x_new_[1] * uo + x_new_[2] * wo;
    wout[i] = w_new_[0] * un + w_new_[1] * uo + w_new_[2] * wo;
    xout[i] = x;
    y[i] = un;
    kinetic += md[i] * x * x + 2 * ml[i] * x_prev * x;
    s_new_new += sd[i] * un * un + 2 * sl[i] * un_prev * un;
    s_new_old += sd[i] * un * uo + sl[i] * (un * u_prev + un_prev * uo);
    s_old_old += sd[i] * uo * uo + 2 * sl[i] * u_prev * uo;
    un_prev = un;
    u_prev = uo;
    x_prev = x;
  }
  energy_ = 0.5 * kinetic + 0.5 * (sigma_[0] * s_new_new + sigma_[1] * s_new_old + sigma_[2] * s_old_old);
  u_.swap(u_new_);
  if (has_load) f_now_.swap(f_next_);

  const double t_now = static_cast<double>(level_) * dt_;
  lambda_ = contact.multiplier;
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
  return {level_, t, &u_, velocity_time, &x_, has_lambda_, level_ == 0 ? 0.0 : lambda_time_, lambda_,
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
                                   double courant, double final_time) {
  const UniformMesh mesh(1.0, elements);
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, p, dt);
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
