/// @file dke.cpp
/// @brief Deuflhard–Krause–Ertel's contact-stabilised Newmark (`dke`): its derivation and its step. The
/// doctests that run it are in contact_classes.cpp ("dke: (DKE) at every step ...", "dke with a load").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "classes/step_pieces.hpp"

namespace mrm::class_steps {

namespace {

// ## Deuflhard–Krause–Ertel's contact-stabilised Newmark (`dke`)
//
// Source: P. Deuflhard, R. Krause, S. Ertel, "A contact-stabilized Newmark method for dynamical contact
// problems", Int. J. Numer. Meth. Engng 73 (2008) 1274–1290 (the project's notes cite it as SIAM J. Numer.
// Anal.; the ZIB publication list gives IJNME). What is taken from the description of the method
// (doc/contact_treatments.md §7):
// Newmark(¼, ½) in which the contact force of the old level is dropped and replaced by a predictor, the
// old level's free-flight prediction Uⁿ + ΔtVⁿ projected onto the admissible set K = {U : u₀ + g₀ ≥ 0} in
// the mass norm; the new level is then a Newmark step with the contact force at the new level only. What
// is reconstructed here (the paper is not in the library; every formula below is derived, not copied): the
// velocity update as a Newmark step from the projected (stabilised) velocity Ṽ (below), which makes the
// dissipation identity (DKE) exact; the stress the scheme reports; the massless contact node's case.
//
// The step, in the notation of (N) (M, S, F the load vector, τ = Δt, gⁿ = u₀ⁿ + g₀ ≥ 0):
//
//     W = Uⁿ + τVⁿ,     P = argmin_{Z ∈ K} ‖Z − W‖_M,     Ṽ = (P − Uⁿ)/τ,
//     M(Uⁿ⁺¹ − P) = −(τ²/4) S(Uⁿ + Uⁿ⁺¹) + (τ²/4)(Fⁿ + Fⁿ⁺¹) − (τ²/4) μ e₀,   0 ≤ u₀ⁿ⁺¹ + g₀ ⊥ μ ≤ 0,   (DKE-1)
//     Vⁿ⁺¹ = Ṽ + (2/τ)(Uⁿ⁺¹ − P).
//
// In 1D the projection is one scalar: K is a half-space in the coordinate u₀, so its M-projection is
// P = W + α M⁻¹e₀ with α = max(0, −(w₀ + g₀))/(M⁻¹)₀₀ (the optimality condition M(P − W) = α e₀, α ≥ 0,
// α(p₀ + g₀) = 0): with a consistent mass it moves every node along M⁻¹e₀ (mostly the contact node and its
// neighbour's row), with a lumped one the contact node only. Ṽ = Vⁿ + (α/τ)M⁻¹e₀ is the M-projection of
// Vⁿ onto {V : u₀ⁿ + τv₀ + g₀ ≥ 0}. The second line is Newmark(¼, ½) started from (Uⁿ, Ṽ) with Rⁿ =
// −SUⁿ + Fⁿ (no contact force at level n): the right-hand side MP − (τ²/4)SUⁿ + (τ²/4)(Fⁿ + Fⁿ⁺¹) is (N)'s
// with Vⁿ → Ṽ, λⁿ → 0; one solve with the closed-form contact step, κ = τ²/4. The step is two-level.
//
// Energy, E = ½VᵀMV + ½UᵀSU. The projection: 0 ∈ {V : …} (gⁿ ≥ 0), so ½‖Vⁿ‖²_M − ½‖Ṽ‖²_M =
// ½‖Vⁿ − Ṽ‖²_M + (Vⁿ − Ṽ, Ṽ)_M = (α²/2τ²)(M⁻¹)₀₀ + (α/τ²)gⁿ (using ṽ₀ = −(u₀ⁿ + g₀)/τ where α > 0). The
// Newmark step from (Uⁿ, Ṽ): Uⁿ⁺¹ − Uⁿ = (τ/2)(Ṽ + Vⁿ⁺¹), and pairing (DKE-1)·(2/τ²)·(τ/2)(Ṽ + Vⁿ⁺¹) as in (E)
// leaves the load's work and the contact's, −(μ/2)(u₀ⁿ⁺¹ − u₀ⁿ) = −(μ/2)(gⁿ⁺¹ − gⁿ) = (μ/2)gⁿ (μgⁿ⁺¹ = 0). So
//
//     Eⁿ⁺¹ − Eⁿ = W_F − (α²/2τ²)(M⁻¹)₀₀ − (α/τ²) gⁿ − (|μ|/2) gⁿ,      W_F = ½(Fⁿ + Fⁿ⁺¹)·(Uⁿ⁺¹ − Uⁿ),   (DKE)
//
// every term after W_F ≤ 0: without a load the energy never grows, at an impact or anywhere else. The
// projection loses at least (α²/2τ²)(M⁻¹)₀₀ = ½ m_eff (Δv₀)² with Δv₀ = α(M⁻¹)₀₀/τ the jump of the contact
// node's velocity and m_eff = 1/(M⁻¹)₀₀ its effective mass: the kinetic energy of the normal velocity the
// projection removes, an inelastic impact of the contact node (restitution 0) at every step where the
// predictor penetrates. That is the price of the stabilisation: O(h) per impact with the consistent mass
// (m_eff = O(h)), the contact node's energy. (Derived; the doctest checks (DKE) to round-off.)
//
// The stress. The contact acts through two impulses per step: the projection's M(Ṽ − Vⁿ) = (α/τ)e₀ and the
// step's M(Vⁿ⁺¹ − Ṽ) ∋ −(τ/2)μe₀. The stress reported is the step's mean contact force,
// λⁿ⁺¹ = μ/2 − α/τ² ≤ 0 (a persistent contact has α → 0 and μ ≈ 2λ: the step weights it by τ²/4 where
// Crank–Nicolson weights λⁿ + λⁿ⁺¹ by τ²/4): a choice of this project, as Moreau–Jean's −p/Δt.
//
// Limit cases. No contact (P = W, μ = 0): Newmark(¼, ½) = Crank–Nicolson with no contact force, the
// `newmark` step (doctest). A massless contact node: the M-norm does not see u₀, the projection moves no
// node with mass (Ṽ = Vⁿ on them), and row 0 is the algebraic contact row S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − μ as in (N)
// (where Rⁿ₀ = 0 already drops λⁿ): the step is Crank–Nicolson's with the same mass, λ = μ (doctest, Mod 3:
// the same run to round-off), so DKE is a treatment for the standard mass, and mass redistribution is
// another cure of the same ill-posedness (doc/contact_treatments.md §2).
class DkeStep final : public OneSolveStep {
 public:
  DkeStep(const Tridiagonal& mass, const Tridiagonal& stiffness, double dt, bool has_load, double gap, bool fused,
          const std::string& id)
      : id_(id),
        mass_(mass),
        stiffness_(stiffness),
        dt_(dt),
        massless_(contact_node_is_massless(mass)),
        has_load_(has_load),
        fused_(fused),
        gap_(gap) {
    const double q = 0.25 * dt * dt;
    Tridiagonal a = mass.plus(q, stiffness);
    weight0_ = q;
    if (massless_) {  // the algebraic contact row
      a.diag[0] = stiffness.diag[0];
      a.upper[0] = stiffness.upper[0];
      weight0_ = 1.0;
    } else {  // M⁻¹e₀ for the projection
      inverse_column_.setZero(mass.size());
      inverse_column_[0] = 1.0;
      solve_free(ContactSolver(mass), inverse_column_);
    }
    solver_ = ContactSolver(a);
    rhs_.resize(mass.size());
  }

  // The initial level: no contact force (the scheme has none at level n), E⁰.
  void start(StepState& state) override {
    state.lambda = 0.0;
    state.active = false;
    state.energy = energy(state);
  }

  // The step as its derivation reads (StepKernel::reference): Uⁿ⁺¹ in state.u_new, Vⁿ⁺¹ in state.w;
  // returns the contact step (u₀ⁿ⁺¹, μ) and α.
  std::pair<Decision, double> readable_advance(StepState& state) {
    const double dt = dt_, q = 0.25 * dt * dt;
    // The predictor W = Uⁿ + τVⁿ and its M-projection P = W + αM⁻¹e₀; Ṽ = (P − Uⁿ)/τ.
    predicted_ = state.u + dt * state.w;
    double alpha = 0;
    if (!massless_ && predicted_[0] + gap_ < 0) {
      alpha = -(predicted_[0] + gap_) / inverse_column_[0];
      predicted_ += alpha * inverse_column_;
      predicted_[0] = -gap_;  // exactly on the obstacle (the formula gives it up to round-off)
    }
    // (DKE-1): (M + τ²/4 S)Uⁿ⁺¹ = MP − τ²/4 SUⁿ + τ²/4(Fⁿ + Fⁿ⁺¹) − τ²/4 μe₀; massless: row 0 S₀·U = F₀ⁿ⁺¹ − μ.
    rhs_ = mass_ * predicted_ - q * (stiffness_ * state.u);
    if (has_load_) rhs_ += q * (state.f_now + state.f_next);
    if (massless_) rhs_[0] = has_load_ ? state.f_next[0] : 0.0;
    Eigen::VectorXd& u = state.u_new;
    const ContactStep contact = solver_.solve(rhs_.data(), u.data(), weight0_, gap_ != 0.0 ? -gap_ : 0.0);
    // Vⁿ⁺¹ = Ṽ + (2/τ)(Uⁿ⁺¹ − P), Ṽ = (P − Uⁿ)/τ.
    state.w = (predicted_ - state.u) / dt + (2 / dt) * (u - predicted_);
    return {Decision{contact.u0, contact.multiplier}, alpha};
  }

  // The same step in three passes, each entry computed with the readable step's operations in the same
  // order, no allocation (StepKernel::fast; doctest "the fused class steps are their readable steps, bit
  // for bit"):
  //   1. P_i = Uⁿ_i + τVⁿ_i (+ αM⁻¹e₀ projected; α is decided by node 0 alone);
  //   2. b_i = (MP)_i − (τ²/4)(SUⁿ)_i (+ (τ²/4)(Fⁿ_i + Fⁿ⁺¹_i)), formed inside the sweep down of A;
  //   3. the contact step on row 0, then the sweep up of Uⁿ⁺¹ and, node by node,
  //      Vⁿ⁺¹_i = (P_i − Uⁿ_i)/τ + (2/τ)(Uⁿ⁺¹_i − P_i).
  std::pair<Decision, double> fused_advance(StepState& state) {
    const Index n = mass_.size();
    const double dt = dt_, q = 0.25 * dt * dt;
    const double *u = state.u.data(), *w = state.w.data();
    // 1. The predictor and its projection.
    predicted_.resize(n);
    double* p = predicted_.data();
    for (Index i = 0; i < n; ++i) p[i] = u[i] + dt * w[i];
    double alpha = 0;
    if (const std::optional<double> projected = projection(u[0], w[0])) {
      alpha = *projected;
      const double* column = inverse_column_.data();
      for (Index i = 0; i < n; ++i) p[i] += alpha * column[i];
      p[0] = -gap_;
    }
    // 2. b inside the sweep down.
    const double *f_now = has_load_ ? state.f_now.data() : nullptr, *f_next = has_load_ ? state.f_next.data() : nullptr;
    const auto b = [&](Index i, double mass_p, double stiffness_u) {
      double bi = mass_p - q * stiffness_u;
      if (has_load_) bi += q * (f_now[i] + f_next[i]);
      return bi;
    };
    double* y = state.u_new.data();
    const double b0 =
        massless_ ? (has_load_ ? f_next[0] : 0.0) : b(0, row_product(mass_, p, 0, n), row_product(stiffness_, u, 0, n));
    sweep_down_forming(solver_, n, y, mass_, p, stiffness_, u, b, b0);
    // 3. The contact step, the sweep up and Vⁿ⁺¹.
    const Decision contact = decide(y[0], u[0], w[0]);
    const double *ip = solver_.inverse_pivot().data(), *cu = solver_.upward().data();
    const double two = 2 / dt;
    double* v = state.w.data();
    double ui = contact.x0;
    y[0] = ui;
    v[0] = (p[0] - u[0]) / dt + two * (ui - p[0]);
    for (Index i = 1; i < n; ++i) {
      ui = ip[i] * y[i] - cu[i] * ui;
      y[i] = ui;
      v[i] = (p[i] - u[i]) / dt + two * (ui - p[i]);
    }
    return {contact, alpha};
  }

  void step(StepState& state, Index level) override {
    state.u_new.resize(state.u.size());
    const auto [contact, alpha] = fused_ ? fused_advance(state) : readable_advance(state);
    state.u.swap(state.u_new);
    finish(state, contact, alpha, energy(state), level);
    if (has_load_) state.f_now.swap(state.f_next);
  }

  // The pieces of the batched step (OneSolveStep), each the fused step's own.
  bool batchable() const override { return fused_ && !has_load_; }
  Lanes lanes() const override {
    return {&mass_, &stiffness_, &mass_, &solver_, &inverse_column_, dt_, 0.25 * dt_ * dt_, 1.0, gap_, massless_};
  }
  // α of the projection P = W + αM⁻¹e₀, where the predictor's w₀ = u₀ + Δt v₀ penetrates (a node with mass).
  std::optional<double> projection(double u0, double v0) const override {
    const double w0 = u0 + dt_ * v0;
    if (!massless_ && w0 + gap_ < 0) return -(w0 + gap_) / inverse_column_[0];
    return std::nullopt;
  }
  // The closed-form contact step on row 0 (weight τ²/4, or 1 on the algebraic row), the obstacle at −g₀.
  Decision decide(double y0, double, double) const override {
    const ContactStep contact = solver_.resolve_contact(y0, weight0_, gap_ != 0.0 ? -gap_ : 0.0);
    return {contact.u0, contact.multiplier};
  }
  // λ = μ/2 − α/τ² (the step's mean contact force; μ on the algebraic row), the status, the energy.
  void finish(StepState& state, const Decision& d, double alpha, double kinetic_and_strain, Index level) override {
    state.lambda = massless_ ? d.value : 0.5 * d.value - alpha / (dt_ * dt_);
    state.active = state.lambda < 0;
    state.energy = kinetic_and_strain;
    require_finite(state.energy, id_, level + 1);
  }

 private:
  double energy(const StepState& s) const { return kinetic_and_strain(mass_, stiffness_, s); }
  std::string id_;
  Tridiagonal mass_, stiffness_;
  double dt_;
  bool massless_, has_load_, fused_;
  double gap_, weight0_ = 0;
  ContactSolver solver_;
  Eigen::VectorXd inverse_column_, predicted_, rhs_;
};

}  // namespace

std::unique_ptr<ContactClassStep> make_dke_step(const Tridiagonal& mass, const Tridiagonal& stiffness, double dt,
                                                bool has_load, double gap, bool fused, const std::string& id) {
  return std::make_unique<DkeStep>(mass, stiffness, dt, has_load, gap, fused, id);
}

}  // namespace mrm::class_steps
