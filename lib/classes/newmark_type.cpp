/// @file newmark_type.cpp
/// @brief Newmark(β, γ) with a contact force: exact enforcement (`newmark`), a penalty (`penalty`) or
/// Nitsche's terms (`nitsche`), in the notation of contact_classes.cpp. The doctests that run them are in
/// contact_classes.cpp.
///
/// ## Newmark(β, γ) with a contact force (newmark, penalty, nitsche)
///
/// Written on R = M A, the force (internal and contact) that the acceleration A carries, so that a
/// singular M (a massless contact node) needs no A:
///
///     M Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt²((½ − β) Rⁿ + β Rⁿ⁺¹),      Rⁿ = −S Uⁿ + F_c(Uⁿ),
///     M Vⁿ⁺¹ = M Vⁿ + Δt((1 − γ) Rⁿ + γ Rⁿ⁺¹),                                             (N)
///
/// that is, with S_ℓ the linear part of S − ∂F_c (S itself, or S − (θ/γ)ddᵀ for Nitsche, below) and
/// F_c = −λ(U) g its nonlinear part,
///
///     (M + βΔt² S_ℓ) Uⁿ⁺¹ = M Uⁿ + Δt M Vⁿ + Δt²(½ − β) Rⁿ − βΔt² λ(Uⁿ⁺¹) g.
///
/// β = ¼, γ = ½ is the trapezoidal rule, Crank–Nicolson: with Rⁿ = −SUⁿ − λⁿe₀ the first line is
/// (M + Δt²/4 S) Uⁿ⁺¹ = (M − Δt²/4 S) Uⁿ + Δt M Vⁿ − Δt²/4 (λⁿ + λⁿ⁺¹) e₀, schemes.cpp's Crank–Nicolson
/// row for row (doctest in contact_classes.cpp). β = 0 is explicit: the step solves with M only, and the contact force is
/// evaluated at the new level after the displacement (GetFEM's demo's "explicit Newmark"); with γ = ½ it is
/// central differences, Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹ = Δt² M⁻¹ Rⁿ (eliminate V between two steps; doctest). A massless
/// contact node has no row of (N): its row is the algebraic contact row at every level, Rⁿ₀ = 0, that is
/// S_ℓ₀·Uⁿ⁺¹ = −λ(Uⁿ⁺¹) g₀ (row 0 of the step matrix replaced by S_ℓ's row 0, right-hand side 0), and its
/// velocity is BarSimulation's (the derivative of that row, mathematics.md §7).
///
/// The contact laws (one scalar each, so one solve per step: A U = b − λ c with c = w ⊙ g, w the row
/// weights βΔt² (1 on a massless node's algebraic row), by superposition U = U_f − λ z, U_f = A⁻¹b,
/// z = A⁻¹c once per run):
///
/// - `newmark`, exact enforcement (GetFEM's version 0): 0 ≤ u₀ⁿ⁺¹ ⊥ λⁿ⁺¹ ≤ 0, g = e₀: the closed-form
///   contact step of contact.cpp with κ = w₀. With β = 0 and a contact node with inertia the force has
///   no weight in the step (κ = 0): no explicit step exists (refused, as the demo refuses it).
/// - `penalty` (version 2): λ(U) = (γ₀/h) min(0, u₀), g = e₀, penalty energy Φ = λ²/(2γ₀/h).
/// - `nitsche` (version 3): with γ = γ₀/h and u_x(0) = d·U, d = (−1/h, 1/h, 0, …) the P1 gradient at x = 0,
///   P(U) = γu₀ + d·U, λ(U) = min(0, P(U)), and the force GetFEM's demo assembles from its boundary terms
///   (θ/γ) u_x v_x + (1/γ) [P]₋ (γv + θv_x):  F_c(U) = (θ/γ)(d·U) d − (1/γ) λ(U) (γe₀ + θd). Its linear
///   part goes into S_ℓ = S − (θ/γ)ddᵀ (the first element's stiffness becomes (1 − θ/γ₀)/h: θ < γ₀ is
///   required), g = e₀ + (θ/γ)d = (1 − θ/γ₀, θ/γ₀, 0, …). For θ = 1 it is a gradient, F_c = −∇Φ with
///   Φ = (1/2γ)(λ² − (d·U)²); the demo's energy adds θΦ for every θ. With θ = 0 and contact, row 0 of
///   S − F_c' is γu₀ alone: the boundary flux −u_x(0) is cancelled and replaced by the penalty γu₀.
///
/// The nonlinear laws are decided as GetFEM decides them: on the predictor U_f (active iff P(U_f) < 0),
/// then, if active, λ = kP with P = P_f/(1 + k ℓ·z) (k = γ₀/h or 1, ℓ the vector of P). For the
/// penalty and for Nitsche with θ = 1 (a gradient of a convex Φ) this is the unique solution of the
/// step; for θ ≠ 1 it is the demo's rule, not a proved solution.
///
/// Energy identity of Newmark(¼, ½) (the trapezoidal rule): Uⁿ⁺¹ − Uⁿ = Δt/2 (Vⁿ + Vⁿ⁺¹) and
/// M(Vⁿ⁺¹ − Vⁿ) = Δt/2 (Rⁿ + Rⁿ⁺¹) give, for E = ½VᵀMV + ½UᵀSU,
///
///     Eⁿ⁺¹ − Eⁿ = ½ (F_cⁿ + F_cⁿ⁺¹)·(Uⁿ⁺¹ − Uⁿ),                                             (E)
///
/// and with F_c = −∇Φ, Φ quadratic on each side of the kink, the total energy E + Φ is conserved by every
/// step whose two levels lie on the same side (the trapezoidal rule integrates a linear force exactly).
/// Across the kink of the penalty (a = u₀ⁿ, b = u₀ⁿ⁺¹ of opposite signs, λ = (γ₀/h) min(0, ·)) (E) gives
/// −½(λⁿ + λⁿ⁺¹)(b − a) + (λⁿ⁺¹² − λⁿ²)/(2γ₀/h): an impact (a > 0 > b) loses ½(γ₀/h)|ab|, a release
/// (a < 0 < b) gains ½(γ₀/h)|ab|, as Crank–Nicolson's release with a massless node does (schemes.cpp, EC).
/// Doctests in contact_classes.cpp check (E) and this defect step by step.
///
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "classes/step_pieces.hpp"

namespace mrm::class_steps {

namespace {

// A number in a message, as %g writes it (six significant digits).
std::string shown(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Newmark(β, γ) with exact enforcement, a penalty or Nitsche's terms (file comment, (N)).
class NewmarkContactStep final : public NewmarkTypeStep {
 public:
  NewmarkContactStep(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& p, double dt,
                     double h, bool has_load, double gap, const std::string& id)
      : id_(id),
        scheme_(p.scheme),
        mass_(mass),
        stiffness_(stiffness),
        linear_(stiffness),
        dt_(dt),
        beta_(p.newmark_beta),
        gamma_(p.newmark_gamma),
        massless_(contact_node_is_massless(mass)),
        has_load_(has_load),
        fused_(p.kernel == StepKernel::fast),
        gap_(gap) {
    const Index n = mass.size();
    // The contact law: λ(U) = k min(0, ℓ·U), F_c = −λ g (+ Nitsche's linear part, put into S_ℓ).
    if (scheme_ == Scheme::penalty) {
      k_ = p.penalty / h;
      ell_ = {1.0, 0.0};
      g_ = {1.0, 0.0};
      offset_ = gap;  // P = u₀ + g₀
    } else if (scheme_ == Scheme::nitsche) {
      const double gamma = p.nitsche_gamma / h, theta = p.nitsche_theta;
      // Nitsche's terms divide by γ = γ₀/h (θ/γ, 1/γ) and by γh² (θ/(γh²) below): γ must be a normal double (a
      // subnormal γ leaves those quotients without precision, a zero one 0/0), θ/(γh²) a finite one, and the
      // first element's own stiffness 1/h must survive beside θ/(γ₀h): |θ|/γ₀ at most 1/ε.
      const char* lost = !(gamma >= std::numeric_limits<double>::min()) ? "gamma = gamma0/h is not a normal double"
                         : theta != 0 && !(std::abs(theta) * std::numeric_limits<double>::epsilon() <= p.nitsche_gamma)
                             ? "|theta|/gamma0 is beyond 1/eps: the first element's own stiffness is lost in rounding"
                         : theta != 0 && !std::isfinite(theta / (gamma * h * h)) ? "theta/(gamma h^2) is not a double"
                                                                                 : nullptr;
      if (lost)
        throw InvalidParameter("nitsche_gamma", "gamma0 = " + shown(p.nitsche_gamma) +
                                                    " on elements of h = " + shown(h) + ": " + lost +
                                                    " (allowed: gamma0 >= h 2.2e-308 and gamma0 >= 2.2e-16 |theta|)");
      k_ = 1.0;
      ell_ = {gamma - 1 / h, 1 / h};                                // P = γu₀ + (u₁ − u₀)/h
      g_ = {1 - theta / p.nitsche_gamma, theta / p.nitsche_gamma};  // e₀ + (θ/γ) d
      const double c = theta == 0 ? 0.0 : theta / (gamma * h * h);  // (θ/γ) ddᵀ's entries ±θ/(γh²)
      linear_.diag[0] -= c;
      linear_.upper[0] += c;
      linear_.lower[1] += c;
      linear_.diag[1] -= c;
      nitsche_energy_ = theta / (2 * gamma);
      d_ = {-1 / h, 1 / h};
      offset_ = gamma * gap;  // P = γ(u₀ + g₀) + d·U
    } else {
      ell_ = {1.0, 0.0};
      g_ = {1.0, 0.0};
    }
    // The step matrix A = M + βΔt² S_ℓ (row 0 S_ℓ's row 0 for a massless node) and the row weights w.
    const double w = beta_ * dt * dt;
    // Exact enforcement on a node with inertia: the constraint's force enters row 0 with the weight βΔt²
    // (β = 0 is refused for it: validate_contact_class). Below ε M₀₀ the weight βΔt²S₀₀ is lost in the
    // rounding of M₀₀ + βΔt²S₀₀, which is β = 0 in floating point, and the force recovered by dividing by
    // βΔt² grows without bound: the derived smallest β is ε M₀₀/(Δt² S₀₀).
    if (scheme_ == Scheme::newmark && !massless_ && beta_ > 0 &&
        !(w * stiffness.diag[0] >= std::numeric_limits<double>::epsilon() * mass.diag[0]))
      throw InvalidParameter(
          "newmark_beta",
          shown(beta_) +
              " with exact enforcement and a contact node with inertia: beta dt^2 S00 is below the "
              "rounding of M00, as beta = 0 (allowed: beta >= eps M00 / (dt^2 S00) = " +
              shown(std::numeric_limits<double>::epsilon() * mass.diag[0] / (dt * dt * stiffness.diag[0])) + ")");
    Tridiagonal a = mass.plus(w, linear_);
    weight0_ = w;
    if (massless_) {
      a.diag[0] = linear_.diag[0];
      a.upper[0] = linear_.upper[0];
      weight0_ = 1.0;
    }
    solver_ = ContactSolver(a);
    Tridiagonal m = mass;  // M̃: M with row 0 e₀ᵀ for a massless node (V₀ is BarSimulation's)
    if (massless_) {
      m.diag[0] = 1.0;
      m.upper[0] = 0.0;
    }
    mass_solver_ = ContactSolver(m);
    if (scheme_ != Scheme::newmark) {
      z_.setZero(n);
      z_[0] = weight0_ * g_[0];
      z_[1] = w * g_[1];
      solve_free(solver_, z_);
      ell_z_ = ell_[0] * z_[0] + ell_[1] * z_[1];
    }
    rhs_.resize(n);
    r_next_.resize(n);
  }

  // The initial level: λ⁰ from the law (exact enforcement: the run's, 0 with inertia), R⁰, E⁰.
  void start(StepState& state) override {
    if (scheme_ != Scheme::newmark) state.lambda = law(state.u);
    force(state.u, state.lambda, has_load_ ? &state.f_now : nullptr, r_);
    state.active = state.lambda < 0;
    state.energy = energy(state);
  }

  // The step as its derivation reads (StepKernel::reference): Uⁿ⁺¹ in state.u_new, Rⁿ⁺¹ in r_next_,
  // Vⁿ⁺¹ in state.w; returns λⁿ⁺¹.
  double readable_advance(StepState& state) {
    const double dt = dt_;
    // b = M Uⁿ + Δt M Vⁿ + Δt²(½ − β) Rⁿ + βΔt² Fⁿ⁺¹, row 0 F₀ⁿ⁺¹ for a massless node (its algebraic row).
    rhs_ = mass_ * state.u + dt * (mass_ * state.w) + (dt * dt * (0.5 - beta_)) * r_;
    if (has_load_) rhs_ += (beta_ * dt * dt) * state.f_next;
    if (massless_) rhs_[0] = has_load_ ? state.f_next[0] : 0.0;
    Eigen::VectorXd& u = state.u_new;
    u = rhs_;
    double lambda = 0;
    if (scheme_ == Scheme::newmark) {
      const ContactStep contact = solver_.solve(rhs_.data(), u.data(), weight0_, gap_ != 0.0 ? -gap_ : 0.0);
      lambda = contact.multiplier;
    } else {
      solve_free(solver_, u);  // U_f
      const double p_free = ell_[0] * u[0] + ell_[1] * u[1] + offset_;
      if (p_free < 0) {  // active on the predictor (GetFEM's rule): P = P_f/(1 + kℓ·z), U = U_f − λz
        lambda = k_ * p_free / (1 + k_ * ell_z_);
        u -= lambda * z_;
      }
    }
    force(u, lambda, has_load_ ? &state.f_next : nullptr, r_next_);
    // M Vⁿ⁺¹ = M Vⁿ + Δt((1 − γ)Rⁿ + γRⁿ⁺¹).
    rhs_ = dt * ((1 - gamma_) * r_ + gamma_ * r_next_);
    solve_free(mass_solver_, rhs_);
    state.w += rhs_;
    return lambda;
  }

  // The same step in four passes over the nodes, each entry computed with the operations of the
  // readable step, in the same order (the project compiles with -ffp-contract=off), and no allocation
  // (StepKernel::fast, the default; the doctest "the fused class steps are their readable steps, bit for
  // bit" compares the two at every step):
  //   1. b_i = ((MUⁿ)_i + Δt(MVⁿ)_i) + Δt²(½ − β)Rⁿ_i (+ βΔt²Fⁿ⁺¹_i), formed inside the sweep down of A,
  //      y_i = b_i − ε_i y_{i+1}, from node n − 1 to 0 (row 0: F₀ⁿ⁺¹ or 0 for a massless node);
  //   2. the contact decision on row 0, then the sweep up u_i = y_i/d_i − c_i u_{i−1} (penalty, Nitsche: of
  //      U_f, then U = U_f − λz node by node), and behind it Rⁿ⁺¹_{i−1} = −(S_ℓUⁿ⁺¹)_{i−1} (+ Fⁿ⁺¹_{i−1}), whose
  //      row needs u_i; rows 0 and 1 then take −λg, and row 0 of a massless node is 0;
  //   3. Δt((1 − γ)Rⁿ_i + γRⁿ⁺¹_i), formed inside the sweep down of M̃;
  //   4. the sweep up of M̃, adding each entry to Vⁿ as it comes.
  double fused_advance(StepState& state) {
    const Index n = mass_.size();
    const double dt = dt_, c_r = dt * dt * (0.5 - beta_), c_f = beta_ * dt * dt;
    const double *u = state.u.data(), *w = state.w.data(), *r = r_.data();
    const double* f = has_load_ ? state.f_next.data() : nullptr;
    double* y = state.u_new.data();
    // 1. b inside the sweep down of A.
    const auto b = [&](Index i, double mass_u, double mass_w) {
      double bi = mass_u + dt * mass_w;
      bi = bi + c_r * r[i];
      if (has_load_) bi = bi + c_f * f[i];
      return bi;
    };
    const double b0 =
        massless_ ? (has_load_ ? f[0] : 0.0) : b(0, row_product(mass_, u, 0, n), row_product(mass_, w, 0, n));
    sweep_down_forming(solver_, n, y, mass_, u, mass_, w, b, b0);
    // 2. The contact decision, the sweep up of A and Rⁿ⁺¹ one row behind.
    const double *ip = solver_.inverse_pivot().data(), *cu = solver_.upward().data();
    const auto [lambda, u0, shift] = decide(y[0], n > 1 ? y[1] : 0.0);  // shift: U = U_f − λz
    const double *ld = linear_.diag.data(), *ll = linear_.lower.data(), *lu = linear_.upper.data();
    const double* z = z_.data();
    double* rn = r_next_.data();
    const auto force_row = [&](Index i, double product) {
      double ri = -product;
      if (has_load_) ri = ri + f[i];
      return ri;
    };
    double free = u0;
    y[0] = shift ? free - lambda * z[0] : free;
    if (n > 1) {
      free = ip[1] * y[1] - cu[1] * free;
      y[1] = shift ? free - lambda * z[1] : free;
      rn[0] = force_row(0, row_product(linear_, y, 0, n));
    }
    for (Index i = 2; i < n; ++i) {
      free = ip[i] * y[i] - cu[i] * free;
      y[i] = shift ? free - lambda * z[i] : free;
      rn[i - 1] = force_row(i - 1, interior_row(ld, ll, lu, y, i - 1));
    }
    rn[n - 1] = force_row(n - 1, row_product(linear_, y, n - 1, n));
    rn[0] -= lambda * g_[0];
    rn[1] -= lambda * g_[1];
    if (massless_) rn[0] = 0.0;
    // 3. Δt((1 − γ)Rⁿ + γRⁿ⁺¹) inside the sweep down of M̃.
    const double a = 1 - gamma_, g = gamma_;
    const double* em = mass_solver_.elimination().data();
    double* t = rhs_.data();
    double ti = dt * (a * r[n - 1] + g * rn[n - 1]);
    t[n - 1] = ti;
    for (Index i = n - 2; i >= 0; --i) {
      ti = dt * (a * r[i] + g * rn[i]) - em[i] * ti;
      t[i] = ti;
    }
    // 4. The sweep up of M̃ and Vⁿ⁺¹ = Vⁿ + (its result).
    const double *ipm = mass_solver_.inverse_pivot().data(), *cm = mass_solver_.upward().data();
    double* wn = state.w.data();
    double vi = t[0] * ipm[0];
    wn[0] += vi;
    for (Index i = 1; i < n; ++i) {
      vi = ipm[i] * t[i] - cm[i] * vi;
      wn[i] += vi;
    }
    return lambda;
  }

  void step(StepState& state, Index level) override {
    state.u_new.resize(state.u.size());
    const double lambda = fused_ ? fused_advance(state) : readable_advance(state);
    state.u.swap(state.u_new);
    r_.swap(r_next_);
    finish(state, lambda, kinetic_and_strain(mass_, stiffness_, state), level);
  }

  // The pieces of the step the batched step calls (NewmarkTypeStep; batched_step.cpp).
  bool batchable() const override { return fused_ && !has_load_; }
  Lanes lanes() override {
    return {&mass_, &stiffness_, &linear_, &solver_, &mass_solver_, &z_, &r_, dt_, beta_, gamma_, massless_, g_};
  }
  // The contact decision on row 0 (the fused step's 2.): exact enforcement resolves it on A's last pivot;
  // penalty and Nitsche take λ = k P_f/(1 + kℓ·z) when the free step's P_f = ℓ·U_f + offset is negative.
  Decision decide(double y0, double y1) const override {
    if (scheme_ == Scheme::newmark) {
      const ContactStep contact = solver_.resolve_contact(y0, weight0_, gap_ != 0.0 ? -gap_ : 0.0);
      return {contact.multiplier, contact.u0, false};
    }
    const double *ip = solver_.inverse_pivot().data(), *cu = solver_.upward().data();
    const double u0 = y0 * ip[0];
    const double u1 = ip[1] * y1 - cu[1] * u0;
    const double p_free = ell_[0] * u0 + ell_[1] * u1 + offset_;
    if (p_free < 0) return {k_ * p_free / (1 + k_ * ell_z_), u0, true};
    return {0.0, u0, false};
  }
  void finish(StepState& state, double lambda, double kinetic_strain, Index level) override {
    state.lambda = lambda;
    state.active = lambda < 0;
    state.energy = energy_from(kinetic_strain, state);
    if (has_load_) state.f_now.swap(state.f_next);
    require_finite(state.energy, id_, level + 1);
  }

 private:
  // λ(U) = k min(0, ℓ·U + offset) (penalty, Nitsche; the offset carries the gap).
  double law(const Eigen::VectorXd& u) const { return k_ * std::min(0.0, ell_[0] * u[0] + ell_[1] * u[1] + offset_); }
  // R = −S_ℓ U − λ g + F, with R₀ = 0 on a massless node (its row holds).
  void force(const Eigen::VectorXd& u, double lambda, const Eigen::VectorXd* load, Eigen::VectorXd& r) const {
    r = -(linear_ * u);
    if (load) r += *load;
    r[0] -= lambda * g_[0];
    r[1] -= lambda * g_[1];
    if (massless_) r[0] = 0.0;
  }
  // E = ½VᵀMV + ½UᵀSU + Φ: penalty λ²/(2k); Nitsche θ/(2γ)(λ² − (d·U)²) (the demo's energy).
  double energy(const StepState& s) const { return energy_from(kinetic_and_strain(mass_, stiffness_, s), s); }
  // The same from ½VᵀMV + ½UᵀSU, reading λ, u₀ and u₁ of `s`.
  double energy_from(double kinetic_strain, const StepState& s) const {
    double e = kinetic_strain;
    if (scheme_ == Scheme::penalty) e += s.lambda * s.lambda / (2 * k_);
    if (scheme_ == Scheme::nitsche) {
      const double ux = d_[0] * s.u[0] + d_[1] * s.u[1];
      e += nitsche_energy_ * (s.lambda * s.lambda - ux * ux);
    }
    return e;
  }

  std::string id_;
  Scheme scheme_;
  Tridiagonal mass_, stiffness_, linear_;
  double dt_, beta_, gamma_;
  bool massless_, has_load_, fused_;
  double gap_;
  double k_ = 0, weight0_ = 0, ell_z_ = 0, nitsche_energy_ = 0, offset_ = 0;
  std::array<double, 2> ell_{}, g_{}, d_{};
  ContactSolver solver_, mass_solver_;
  Eigen::VectorXd z_, r_, r_next_, rhs_;
};

}  // namespace

std::unique_ptr<ContactClassStep> make_newmark_type_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                         const SchemeParameters& p, double dt, double h, bool has_load,
                                                         double gap, const std::string& id) {
  return std::make_unique<NewmarkContactStep>(mass, stiffness, p, dt, h, has_load, gap, id);
}

}  // namespace mrm::class_steps
