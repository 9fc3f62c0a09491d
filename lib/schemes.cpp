/// @file schemes.cpp
/// @brief The time schemes: mathematics.md §4, the paper's §3 (Crank–Nicolson, backward Euler, Paoli–Schatzman).
///
/// The semi-discrete problem is M U'' + S U = −λ e₀ + F, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (5)), with M the
/// consistent mass or a redistributed mass M^mod whose row and column 0 vanish (paper eq. (6)).
///
/// One step of every scheme, written on all unknowns 0..N−1, is
///
///     A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀,     0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0,                         (★)
///
/// that is, \f$ A U^{n+1} = B_1 U^n + B_2 W + G - \kappa \lambda e_0 \f$ with \f$ 0 \le u_0^{n+1} - g \perp \lambda \le 0 \f$,
/// with constant tridiagonal A, B₁, B₂, a scalar κ > 0, W = Vⁿ for the two-level schemes and
/// W = Uⁿ⁻¹ for the three-level one, and g the obstacle (0, or −e u₀ⁿ⁻¹). (★) is solved by the
/// closed-form contact step of contact.cpp: one sweep down, the contact decision at the contact
/// node's pivot, one sweep up. The schemes differ only in their coefficients:
///
/// Crank–Nicolson (trapezoidal rule for U' = V, M V' = −SU − λe₀ + F). Eliminating
/// Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ from M(Vⁿ⁺¹ − Vⁿ) = Δt/2 (−S(Uⁿ⁺¹ + Uⁿ) − (λⁿ⁺¹ + λⁿ)e₀ + Fⁿ⁺¹ + Fⁿ):
///
///     (M + θS) Uⁿ⁺¹ = (M − θS) Uⁿ + Δt M Vⁿ + θ(Fⁿ + Fⁿ⁺¹) − θλⁿe₀ − θλⁿ⁺¹e₀,    θ = Δt²/4.
///
/// Backward Euler: Uⁿ⁺¹ = Uⁿ + Δt Vⁿ⁺¹, M(Vⁿ⁺¹ − Vⁿ) = Δt(−SUⁿ⁺¹ − λⁿ⁺¹e₀ + Fⁿ⁺¹):
///
///     (M + Δt²S) Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt² Fⁿ⁺¹ − Δt² λⁿ⁺¹ e₀,   Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt.
///
/// Paoli–Schatzman (three levels, β ≥ 0, restitution e ∈ [0, 1]):
///
///     M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹)/Δt² + S(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Fⁿ − λⁿe₀,
///     0 ≤ (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ⊥ λⁿ ≤ 0,
///
/// that is (M + βΔt²S) Uⁿ⁺¹ = (2M − (1−2β)Δt²S) Uⁿ − (M + βΔt²S) Uⁿ⁻¹ + Δt²Fⁿ − Δt²λⁿe₀ with the
/// obstacle g = −e u₀ⁿ⁻¹.
///
/// The massless contact row. With a redistributed mass, row 0 of the system has no inertia: it is
/// the algebraic contact row S₀·U = F₀ − λ, 0 ≤ u₀ ⊥ λ ≤ 0 (paper eq. (6)), to hold at every time level.
/// Crank–Nicolson's row 0 is then (S₀·Uⁿ⁺¹ − F₀ⁿ⁺¹ + λⁿ⁺¹) + (S₀·Uⁿ − F₀ⁿ + λⁿ) = 0 and backward Euler's
/// is S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹: with the row holding at level n, both are the algebraic row at level n+1.
/// This implementation writes it as such for every scheme ("algebraic" form): row 0 of A is S₀·,
/// row 0 of B₁ and B₂ vanish, G₀ = F₀ⁿ⁺¹ and κ = 1 for that row, so the row holds at every level
/// whatever round-off or initial data did before. Paoli–Schatzman applied literally ("literal" form)
/// keeps its own row 0, Δt² S₀·(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = Δt²(F₀ⁿ − λⁿ): the contact row then only
/// holds in the β-average of three levels, and its defect dⁿ = S₀·Uⁿ − F₀ⁿ + λ obeys
/// βdⁿ⁺¹ + (1−2β)dⁿ + βdⁿ⁻¹ = 0 while the contact is inactive: for β = ¼, dⁿ = (p + qn)(−1)ⁿ, a
/// sawtooth that may grow (mathematics.md §4). The experiments show whether it does.
///
/// The discrete energies. Two-level schemes: Eⁿ = ½ VⁿᵀMVⁿ + ½ UⁿᵀSUⁿ; Crank–Nicolson conserves it
/// exactly while the contact status does not change, backward Euler dissipates it. Paoli–Schatzman:
/// the quantity its linear part conserves is, with D = (Uⁿ⁺¹ − Uⁿ)/Δt,
///
///     Eⁿ⁺½ = ½ DᵀMD + ½ (β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ),
///
/// (for β = ¼ the familiar ½DᵀMD + ½ ŪᵀSŪ with Ū = (Uⁿ⁺¹ + Uⁿ)/2), attached to the instant t_{n+½}.
#include "schemes.hpp"

#include <cmath>
#include <memory>
#include <type_traits>
#include <stdexcept>

#include <doctest/doctest.h>

#include "exact_solution.hpp"
#include "fast_step.hpp"

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
std::string to_string(StepKernel k) { return k == StepKernel::reference ? "reference" : "fast"; }

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

  // The matrices and scalars of (★), scheme by scheme, as derived at the top of this file
  // (mathematics.md §4): M the mass (consistent or redistributed), S the stiffness, A the step matrix.
  const double dt2 = dt * dt;
  const Tridiagonal& M = mass_;
  const Tridiagonal& S = stiffness_;
  Tridiagonal A;
  lambda_in_rhs_ = 0.0;
  switch (parameters.scheme) {
    case Scheme::crank_nicolson: {
      // (M + θS) Uⁿ⁺¹ = (M − θS) Uⁿ + Δt M Vⁿ + θ(Fⁿ + Fⁿ⁺¹) − θλⁿe₀ − θλⁿ⁺¹e₀,  θ = Δt²/4;
      // Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ.
      const double theta = dt2 / 4;
      A = M.plus(theta, S);
      b1_ = M.plus(-theta, S);
      b2_ = M.scaled(dt);
      kappa_ = theta;
      load_now_ = theta;
      load_next_ = theta;
      lambda_in_rhs_ = theta;
      velocity_rate_ = 2 / dt, velocity_memory_ = 1;
      break;
    }
    case Scheme::backward_euler: {
      // (M + Δt²S) Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt² Fⁿ⁺¹ − Δt² λⁿ⁺¹ e₀;  Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt.
      A = M.plus(dt2, S);
      b1_ = M;
      b2_ = M.scaled(dt);
      kappa_ = dt2;
      load_now_ = 0;
      load_next_ = dt2;
      velocity_rate_ = 1 / dt, velocity_memory_ = 0;
      break;
    }
    case Scheme::paoli_schatzman: {
      // (M + βΔt²S) Uⁿ⁺¹ = (2M − (1−2β)Δt²S) Uⁿ − (M + βΔt²S) Uⁿ⁻¹ + Δt²Fⁿ − Δt²λⁿe₀.
      const double beta = parameters.beta;
      A = M.plus(beta * dt2, S);
      b1_ = M.scaled(2.0).plus(-(1 - 2 * beta) * dt2, S);
      b2_ = M.scaled(-1.0).plus(-beta * dt2, S);
      kappa_ = dt2;
      load_now_ = dt2;
      load_next_ = 0;
      velocity_rate_ = 1 / dt, velocity_memory_ = 0;  // X = (Uⁿ⁺¹ − Uⁿ)/Δt; W' = Uⁿ by a swap
      break;
    }
  }
  // The algebraic contact row S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹: row 0 of A is S₀·, rows 0 of B₁ and B₂ vanish,
  // κ = 1 (G₀ = F₀ⁿ⁺¹ is set by the step).
  if (algebraic_row_) {
    A.diag[0] = S.diag[0];
    A.upper[0] = S.upper[0];
    zero_row0(b1_);
    zero_row0(b2_);
    kappa_ = 1.0;
    lambda_in_rhs_ = 0.0;
  }
  solver_ = ContactSolver(A);
  // The fast path reads B₁, B₂, M and S from its own rows (fast_step.cpp): B₁ and B₂ are kept only
  // for the reference step, so that the fast path's memory is that of the state and the factors.
  if (parameters.kernel == StepKernel::fast) {
    fast_ = std::make_unique<const FastStep>(b1_, b2_, M, S);
    b1_ = Tridiagonal();
    b2_ = Tridiagonal();
  }

  // The initial level. Uⁿ and V⁰ are the nodal interpolants of u⁰ and v⁰; a massless contact node
  // takes the value its algebraic row gives (mathematics.md §4: otherwise u₀ jumps in the first step and
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

BarSimulation::~BarSimulation() = default;
BarSimulation::BarSimulation(BarSimulation&&) = default;
BarSimulation& BarSimulation::operator=(BarSimulation&&) = default;

void BarSimulation::load_at(double t, Eigen::VectorXd& f) const {
  if (!problem_.load) return;
  p1_load(mesh_, [&](double x) { return problem_.load(x, t); }, f);
}

double BarSimulation::energy_two_level() const {
  return 0.5 * mass_.bilinear(x_, x_) + 0.5 * stiffness_.bilinear(u_, u_);
}

// ---------------------------------------------------------------------------------------------------
// The reference step: (★) written as derived at the top of this file (mathematics.md §4).
//
// With A, B₁, B₂, κ and the load weights assembled once by the constructor, one step is
//
//   1. the right-hand side  b = B₁ Uⁿ + B₂ W + g_now Fⁿ + g_next Fⁿ⁺¹, row 0 corrected: with the
//      algebraic contact row b₀ = F₀ⁿ⁺¹ (and κ = 1); Crank–Nicolson with inertia at node 0 carries
//      its −θλⁿ there;
//   2. one tridiagonal solve of A Uⁿ⁺¹ = b − κ λ e₀ with 0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0, by the closed-form
//      contact step ContactSolver::solve (contact.cpp), g = 0 or, for Paoli–Schatzman, −e u₀ⁿ⁻¹;
//   3. the velocity from its definition: Crank–Nicolson Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ, backward Euler
//      Vⁿ⁺¹ = (Uⁿ⁺¹ − Uⁿ)/Δt, Paoli–Schatzman X = (Uⁿ⁺¹ − Uⁿ)/Δt (and W becomes Uⁿ);
//   4. the energy from its definition: Eⁿ⁺¹ = ½ Vⁿ⁺¹ᵀMVⁿ⁺¹ + ½ Uⁿ⁺¹ᵀSUⁿ⁺¹ (two levels),
//      Eⁿ⁺½ = ½ XᵀMX + ½ (β Uⁿ⁺¹ᵀSUⁿ⁺¹ + (1−2β) Uⁿ⁺¹ᵀSUⁿ + β UⁿᵀSUⁿ) (Paoli–Schatzman).
//
// The stiffness forms are summed element by element, UᵀSV = ∫ u_h' v_h' dx = Σ_e (u_{e+1} − u_e)
// (v_{e+1} − v_e)/h with the clamped value u_N = 0: the same number as S's bilinear form, without
// cancelling the terms 2u_i²/h against −2u_{i−1}u_i/h (whose sizes grow like N² times the energy).
// This step allocates its temporaries and walks the vectors several times; the fast path
// (fast_step.cpp) does the same arithmetic inside the two sweeps of the solve. The doctest below
// ("the fast step and the reference step agree to round-off") compares them.
namespace {

// UᵀSV for the P1 stiffness on the unknowns 0..N−1, element by element (the node N is clamped).
double stiffness_form(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double h) {
  const Index n = u.size();
  double sum = 0;
  for (Index e = 0; e < n; ++e) {
    const double du = (e + 1 < n ? u[e + 1] : 0.0) - u[e];
    const double dv = (e + 1 < n ? v[e + 1] : 0.0) - v[e];
    sum += du * dv;
  }
  return sum / h;
}

}  // namespace

void BarSimulation::reference_step(bool has_load) {
  const double dt = dt_, h = mesh_.h();
  const Tridiagonal& M = mass_;
  const Eigen::VectorXd& u = u_;  // Uⁿ
  const Eigen::VectorXd& w = w_;  // W: Vⁿ (two levels) or Uⁿ⁻¹ (Paoli–Schatzman)

  // 1. The right-hand side.
  Eigen::VectorXd rhs = b1_ * u + b2_ * w;
  if (has_load) rhs += load_now_ * f_now_ + load_next_ * f_next_;
  if (algebraic_row_) rhs[0] = has_load ? f_next_[0] : 0.0;
  else rhs[0] -= lambda_in_rhs_ * lambda_;

  // 2. One solve with the closed-form contact step.
  const double obstacle = three_level_ ? -parameters_.restitution * w[0] : 0.0;
  Eigen::VectorXd& u_next = u_new_;  // Uⁿ⁺¹
  const ContactStep contact = solver_.solve(rhs.data(), u_next.data(), kappa_, obstacle);
  const double contact_multiplier = contact.multiplier;

  // 3 and 4. The velocity and the energy.
  if (three_level_) {
    const double beta = parameters_.beta;
    x_ = (u_next - u) / dt;
    energy_ = 0.5 * M.bilinear(x_, x_) +
              0.5 * (beta * stiffness_form(u_next, u_next, h) + (1 - 2 * beta) * stiffness_form(u_next, u, h) +
                     beta * stiffness_form(u, u, h));
    w_ = u_;  // W' = Uⁿ
  } else {
    Eigen::VectorXd& v_next = w_;  // Vⁿ⁺¹ overwrites Vⁿ, entry by entry
    if (parameters_.scheme == Scheme::crank_nicolson) v_next = 2 * (u_next - u) / dt - w;
    else v_next = (u_next - u) / dt;
    energy_ = 0.5 * M.bilinear(v_next, v_next) + 0.5 * stiffness_form(u_next, u_next, h);
  }
  u_.swap(u_new_);  // U = Uⁿ⁺¹
  lambda_ = contact_multiplier;
  if (has_load) f_now_.swap(f_next_);
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
  if (fast_) fast_->step(*this, has_load);
  else reference_step(has_load);

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
// Checks of the schemes' energy behaviour (mathematics.md §4) and of the Paoli–Schatzman identity.

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

[[maybe_unused]] SchemeParameters with(Scheme scheme, ContactRow row = ContactRow::algebraic,
                                      StepKernel kernel = StepKernel::fast) {
  SchemeParameters p;
  p.scheme = scheme;
  p.contact_row = row;
  p.kernel = kernel;
  return p;
}

}  // namespace

TEST_CASE("Crank–Nicolson conserves the discrete energy to round-off while the contact status is unchanged") {
  // The benchmark's first free flight lasts until t = 1: no status change before t = 0.9. Both step
  // kernels (their energies are summed in different orders).
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
    for (double courant : {0.5, 1.0, 3.0}) {
      const std::vector<double> e =
          energy_history(mass, with(Scheme::crank_nicolson, ContactRow::algebraic, kernel), 40, courant, 0.9 - 0.075);
      CAPTURE(to_string(kernel));
      CAPTURE(mass.name);
      CAPTURE(courant);
      // Round-off grows at most linearly with the number of steps k: |E_k − E_0| ≤ 1e-14 + k · 1e-15 (E ≈ 1/8).
      REQUIRE(e.size() > 2);
      for (std::size_t k = 0; k < e.size(); ++k) CHECK(std::abs(e[k] - e.front()) <= 1e-14 + k * 1e-15);
    }
  }
}

TEST_CASE("Paoli–Schatzman with beta = 1/4 conserves its energy while the contact status is unchanged") {
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
  for (ContactRow row : {ContactRow::algebraic, ContactRow::literal}) {
    // From level 2 on: levels 0 and 1 carry the two-level energy of the Crank–Nicolson start.
    const std::vector<double> e = energy_history(mod3(), with(Scheme::paoli_schatzman, row, kernel), 40, 0.5, 0.85);
    CAPTURE(to_string(kernel));
    CAPTURE(to_string(row));
    REQUIRE(e.size() > 10);
    for (std::size_t k = 2; k < e.size(); ++k) CHECK(std::abs(e[k] - e[2]) <= 1e-14 + k * 1e-15);
  }
}

TEST_CASE("backward Euler never increases the discrete energy") {
  for (const StepKernel kernel : {StepKernel::fast, StepKernel::reference})
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3(), consistent_mass()}) {
    const std::vector<double> e =
        energy_history(mass, with(Scheme::backward_euler, ContactRow::algebraic, kernel), 30, 0.5, 9.0);
    CAPTURE(to_string(kernel));
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

// The fast step against the reference step (mathematics.md §4). Both compute (★) with the same
// factorised A; they differ only in the order of the floating-point operations: the fast kernel
// forms b on the fly and runs each sweep as two chains (products of two elimination factors), sums
// its energy forms by telescoping, multiplies by 1/Δt where the reference divides by Δt. Each step
// of either commits errors of a few ε = 2⁻⁵² relative to the size of the quantities it combines,
// and the scheme carries them on like any perturbation of its state: the contact step is Lipschitz
// in b (u₀ = max(g, …), λ = min(0, …); a status decided differently by two round-off-close values
// costs no jump), so the difference grows like the scheme's own response to a perturbation.
//
// Prediction: the difference over a run of K steps is at most about K c ε A times the solution's
// scale, c a modest factor (the condition of a step, O(N)), A ≥ 1 the scheme's amplification of a
// perturbation of its state. A is measured by a third run, the initial displacement perturbed by
// p = 1e-10 sin(5x): A = max(1, max over the run of ‖ΔUⁿ‖∞ / p). It is ≈ 1 where the scheme is
// stable (backward Euler, Crank–Nicolson and Paoli–Schatzman with the algebraic row at Δt < h) and
// large where it is not: Crank–Nicolson with the consistent mass gains energy at every impact
// (10³–10⁷ here), the literal Paoli–Schatzman row lets its sawtooth grow (10–10²), large steps with
// restitution move the impact times. With K = 200 and N = 12, Kcε ~ 1e-13: the bound is τ = 1e-12
// of the solution's scale times A, the scale of each quantity being what its formula combines:
//   Uⁿ           τ A U*, U* = max over the run of ‖Uⁿ‖∞;
//   velocity     τ A U*/Δt (a difference of displacements divided by Δt);
//   λ            τ A (‖M‖∞ U*/Δt² + ‖S‖∞ U* + F*), the forces that row 0 of (★) balances (F* ≥ ‖F‖∞);
//   energy       τ A (‖M‖∞ (U*/Δt)² + ‖S‖∞ U*²), the sizes of the terms of ½VᵀMV + ½UᵀSU;
// and the instants of every sample, computed by the same code, exactly equal. A wrong term in either
// step would differ by O(h) or more at the first step, far above these bounds. The cases: every
// scheme, every mass of the paper (consistent, Mod 1–3) and two more that exercise every region of
// the fast kernel (the lost mass spread over 3 nodes; a weight varying along the bar, no Toeplitz
// interior at all), both Paoli–Schatzman forms (β = ¼, e = 0 at Δt = 0.7h; β = 0.3, e = 0.5 at
// Δt = 4h), with and without a load; every run has impacts.
namespace {

[[maybe_unused]] MassRedistribution varying_weight() {
  return {"varying", "a weight that varies along the bar", [](Index i, Index j, const UniformMesh& mesh) {
            if (i == 0 || j == 0) return 0.0;
            return 1.0 + 0.3 * static_cast<double>(i + j) / static_cast<double>(mesh.elements);
          }};
}

// max_i Σ_j |A_ij|
[[maybe_unused]] double row_sum_norm(const Tridiagonal& a) {
  return (a.lower.cwiseAbs() + a.diag.cwiseAbs() + a.upper.cwiseAbs()).maxCoeff();
}

}  // namespace

TEST_CASE("the fast step and the reference step agree to round-off for every scheme, mass and form") {
  struct Form {
    Scheme scheme;
    ContactRow row;
  };
  const std::vector<Form> forms = {{Scheme::crank_nicolson, ContactRow::algebraic},
                                   {Scheme::backward_euler, ContactRow::algebraic},
                                   {Scheme::paoli_schatzman, ContactRow::algebraic},
                                   {Scheme::paoli_schatzman, ContactRow::literal}};
  const std::vector<MassRedistribution> masses = {consistent_mass(), mod1(), mod2(), mod3(),
                                                  spread_over_first_nodes(3), varying_weight()};
  const double tolerance = 1e-12, perturbation = 1e-10;
  const double load_bound = 1.7;  // |f| ≤ 1.7 below, so ‖F‖∞ ≤ 1.7 h
  const Index steps = 200;
  const UniformMesh mesh(1.0, 12);
  int runs = 0;
  double worst = 0;  // the largest difference over its bound, over all runs
  for (const bool loaded : {false, true}) {
    for (const Form& form : forms) {
      for (const MassRedistribution& mass : masses) {
        // The algebraic Paoli–Schatzman row needs a massless contact node (refused otherwise, checked below).
        if (form.row == ContactRow::algebraic && form.scheme == Scheme::paoli_schatzman && mass.name == "consistent")
          continue;
        for (const double courant : {0.7, 4.0}) {
          Problem problem = benchmark_problem();
          if (loaded) problem.load = [](double x, double t) { return -1.0 + 0.7 * std::sin(3 * x + 5 * t); };
          SchemeParameters p = with(form.scheme, form.row);
          const bool large = courant > 1;
          p.beta = form.scheme == Scheme::paoli_schatzman && large ? 0.3 : 0.25;
          p.restitution = form.scheme == Scheme::paoli_schatzman && large ? 0.5 : 0.0;
          const double dt = courant * mesh.h();
          p.kernel = StepKernel::fast;
          BarSimulation fast(problem, mesh, mass, p, dt);
          Problem perturbed_problem = problem;
          perturbed_problem.initial_displacement = [&](double x) { return problem.initial_displacement(x) + perturbation * std::sin(5 * x); };
          BarSimulation perturbed(perturbed_problem, mesh, mass, p, dt);
          p.kernel = StepKernel::reference;
          BarSimulation reference(problem, mesh, mass, p, dt);
          CAPTURE(to_string(form.scheme));
          CAPTURE(to_string(form.row));
          CAPTURE(mass.name);
          CAPTURE(loaded);
          CAPTURE(courant);

          double response = 0, u_scale = 0, du = 0, dv = 0, dlambda = 0, denergy = 0;
          int impacts = 0;
          bool in_contact = false, same_instants = true;
          for (Index k = 0; k <= steps; ++k) {
            if (k > 0) {
              fast.step();
              reference.step();
              perturbed.step();
            }
            const Sample f = fast.sample(), r = reference.sample();
            response = std::max(response, (*perturbed.sample().displacement - *f.displacement).cwiseAbs().maxCoeff());
            same_instants = same_instants && f.level == r.level && f.time == r.time &&
                            f.velocity_time == r.velocity_time && f.has_multiplier == r.has_multiplier &&
                            f.multiplier_time == r.multiplier_time && f.energy_time == r.energy_time;
            u_scale = std::max({u_scale, f.displacement->cwiseAbs().maxCoeff(), r.displacement->cwiseAbs().maxCoeff()});
            du = std::max(du, (*f.displacement - *r.displacement).cwiseAbs().maxCoeff());
            dv = std::max(dv, (*f.velocity - *r.velocity).cwiseAbs().maxCoeff());
            if (f.has_multiplier) dlambda = std::max(dlambda, std::abs(f.multiplier - r.multiplier));
            denergy = std::max(denergy, std::abs(f.energy - r.energy));
            impacts += r.multiplier < 0 && !in_contact;
            in_contact = r.multiplier < 0;
          }
          const double amplification = std::max(1.0, response / perturbation);
          const double m_norm = row_sum_norm(fast.mass()), s_norm = row_sum_norm(fast.stiffness());
          const double relative = tolerance * amplification;
          const double u_bound = relative * u_scale;
          const double v_bound = relative * u_scale / dt;
          const double lambda_bound =
              relative * (m_norm * u_scale / (dt * dt) + s_norm * u_scale + (loaded ? load_bound * mesh.h() : 0.0));
          const double energy_bound = relative * (m_norm * std::pow(u_scale / dt, 2) + s_norm * u_scale * u_scale);
          CAPTURE(amplification);
          CAPTURE(du);
          CAPTURE(dv);
          CAPTURE(dlambda);
          CAPTURE(denergy);
          CHECK(same_instants);
          CHECK(du <= u_bound);
          CHECK(dv <= v_bound);
          CHECK(dlambda <= lambda_bound);
          CHECK(denergy <= energy_bound);
          CHECK(impacts >= 1);  // the runs do reach the obstacle
          worst = std::max({worst, du / u_bound, dv / v_bound, dlambda / lambda_bound, denergy / energy_bound});
          ++runs;
        }
      }
    }
  }
  CAPTURE(worst);
  CHECK(runs == 2 * 2 * (3 * 6 + 5));
  CHECK(worst <= 1.0);
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
